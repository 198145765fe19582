// The IMU models against what they promise: 3 h static runs of every shipped profile read back
// through the Allan deviation (white noise at 1 s, bias-instability floor, random walk), the
// real parts' generated curves against their measured ones (../shared/data/imu/imu_utils_allan),
// and the paper's two dead-reckoning cases (Fig. 2/3 gyroscope, Fig. 7 Phidget).

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "emulator/imu_profile.hpp"
#include "models/allan.hpp"
#include "models/imu_kinematics.hpp"
#include "models/imu_model.hpp"
#include "tests/test_support.hpp"

namespace navemu {
namespace {

const Geodetic kSite{32.3, -90.9, 60.0};  // the paper's test site

// Six output channels of a static, level, north-facing run (accel x,y,z then gyro x,y,z).
struct StaticRun {
  double output_rate_hz = 0.0;
  std::array<std::vector<double>, 6> ch;
};

StaticRun static_run(const ImuParams& p, double duration_s, std::uint64_t seed) {
  ImuModel imu(p, seed);
  const IdealImu ideal = ideal_imu_static(kSite, Quat::Identity());
  StaticRun r;
  r.output_rate_hz = p.output_rate_hz;
  const auto n_out = static_cast<std::size_t>(duration_s * p.output_rate_hz);
  for (auto& c : r.ch) c.reserve(n_out + 1);
  const GpsTime t0 = from_week_tow(2244, 0.0);
  const auto n_internal = static_cast<long long>(duration_s * p.internal_rate_hz);
  ImuSample s;
  for (long long k = 0; k < n_internal; ++k) {
    if (!imu.step(t0.plus_s(static_cast<double>(k) / p.internal_rate_hz), ideal, 25.0, s)) continue;
    for (int a = 0; a < 3; ++a) {
      r.ch[static_cast<std::size_t>(a)].push_back(s.f_body_mps2[a]);
      r.ch[static_cast<std::size_t>(a + 3)].push_back(s.w_body_radps[a]);
    }
  }
  return r;
}

// Log-log interpolation of a curve at tau (nullopt outside it).
std::optional<double> adev_at(const std::vector<AllanPoint>& c, double tau) {
  for (std::size_t i = 1; i < c.size(); ++i) {
    if (c[i - 1].tau_s <= tau && tau <= c[i].tau_s) {
      const double u = std::log(tau / c[i - 1].tau_s) / std::log(c[i].tau_s / c[i - 1].tau_s);
      return std::exp(std::log(c[i - 1].adev) + u * std::log(c[i].adev / c[i - 1].adev));
    }
  }
  return std::nullopt;
}

// The noise terms output channel c (accel x, y, z, gyro x, y, z) is configured with: the
// triad's values times the channel's per-axis multipliers (multipliers left at 1).
ImuSensorParams axis_params(const ImuParams& p, std::size_t c) {
  ImuSensorParams sp = c < 3 ? p.accel : p.gyro;
  const auto a = static_cast<Eigen::Index>(c % 3);
  sp.white_density *= sp.white_axis_scale[a];
  sp.bias_instability *= sp.bias_axis_scale[a];
  sp.random_walk *= sp.random_walk_axis_scale[a];
  sp.white_axis_scale = sp.bias_axis_scale = sp.random_walk_axis_scale = Vec3::Ones();
  return sp;
}

class ImuProfileAllan : public ::testing::TestWithParam<std::string> {};

TEST_P(ImuProfileAllan, ThreeHourStaticRunShowsTheConfiguredNoiseTerms) {
  const ImuProfile profile = load_imu_profile(GetParam());
  const double duration_s = 3.0 * 3600.0;
  const ImuParams p = imu_params_for_run(profile, duration_s);
  const StaticRun r = static_run(p, duration_s, 7);
  const bool paper = profile.model == "paper";
  for (std::size_t c = 0; c < 6; ++c) {
    const ImuSensorParams& sp = axis_params(p, c);
    const auto curve = overlapping_allan_deviation(r.ch[c], 1.0 / r.output_rate_hz, 10);
    const AllanFit fit = fit_allan(curve);
    const double at1 = *adev_at(curve, 1.0);
    std::printf("%s ch%zu: ADEV(1 s)/N %.3f, B fit/configured %.3f (floor at %.0f s), K fit %.3g "
                "configured %.3g\n",
                GetParam().c_str(), c, at1 / sp.white_density,
                sp.bias_instability > 0 ? fit.bias_instability / sp.bias_instability : 0.0,
                fit.bias_instability_tau_s, fit.random_walk, sp.random_walk);
    // White noise: the Allan deviation at 1 s is the density (IEEE 952 Annex C), +/-10 %.
    EXPECT_NEAR(at1 / sp.white_density, 1.0, 0.10) << GetParam() << " channel " << c;
    // Bias instability: the floor / 0.664, +/-30 % (not for the paper's profiles, whose
    // white-noise coefficients bury the Gauss-Markov bump).
    if (!paper && sp.bias_instability > 0) {
      EXPECT_NEAR(fit.bias_instability / sp.bias_instability, 1.0, 0.30)
          << GetParam() << " channel " << c;
    }
  }
}

// Allan variance of the configured terms: white noise N^2/tau, random walk K^2 tau/3
// (IEEE Std 952-1997 Annex C), and a first-order Gauss-Markov bias of sigma and T:
// (2 sigma^2 T / tau) [1 - (T / 2 tau)(3 - 4 exp(-tau/T) + exp(-2 tau/T))].
double analytic_adev(const ImuSensorParams& sp, double tau) {
  const double sigma = kGmSigmaPerBiasInstability * sp.bias_instability;
  const double t = sp.bias_instability_tau_s, x = tau / t;
  const double gm = 2.0 * sigma * sigma * t / tau *
                    (1.0 - t / (2.0 * tau) * (3.0 - 4.0 * std::exp(-x) + std::exp(-2.0 * x)));
  return std::sqrt(sp.white_density * sp.white_density / tau +
                   sp.random_walk * sp.random_walk * tau / 3.0 + gm);
}

TEST_P(ImuProfileAllan, RandomWalkSlopeWhereConfigured) {
  // 24 h at 10 Hz (no filter, so the white density is unchanged): ~86 independent clusters at
  // tau = 1000 s, a relative uncertainty of ~11 %; the bound is 3 sigma (35 %).
  const ImuProfile profile = load_imu_profile(GetParam());
  if (profile.model == "paper") GTEST_SKIP() << "the paper's model has no random walk";
  ImuParams p = imu_params_for_run(profile, 24.0 * 3600.0);
  p.internal_rate_hz = p.output_rate_hz = 10.0;
  p.bandwidth_hz = 0.0;
  const StaticRun r = static_run(p, 24.0 * 3600.0, 5);
  for (std::size_t c = 0; c < 6; ++c) {
    const ImuSensorParams sp = axis_params(p, c);
    if (sp.random_walk <= 0) continue;
    const double tau = 1000.0;
    const double expected = analytic_adev(sp, tau);
    const double rw_share = sp.random_walk * std::sqrt(tau / 3.0) / expected;
    const auto curve = overlapping_allan_deviation(r.ch[c], 0.1, 10);
    const double ratio = *adev_at(curve, tau) / expected;
    std::printf("%s ch%zu: ADEV(1000 s) / analytic %.3f (random walk %.0f %% of it)\n",
                GetParam().c_str(), c, ratio, 100.0 * rw_share);
    EXPECT_NEAR(ratio, 1.0, 0.35) << GetParam() << " channel " << c;
  }
}

INSTANTIATE_TEST_SUITE_P(Profiles, ImuProfileAllan,
                         ::testing::ValuesIn(available_imu_profiles()),
                         [](const auto& param_info) { return param_info.param; });

// Real parts: the generated curve (average of the three axes) against the measured one
// (average of the three axes of imu_utils' curves) for tau from 0.1 s to 1000 s, and each axis
// against its own measured curve (the profiles' per-axis multipliers, fitted by
// tools/fit_imu_axis_scales.py).
struct RealPart {
  const char* profile;
  const char* data_name;  // imu_utils file prefix
};

class ImuRealCurves : public ::testing::TestWithParam<RealPart> {};

std::vector<double> read_column(const std::filesystem::path& f) {
  std::ifstream in(f);
  std::vector<double> v;
  for (double x; in >> x;) v.push_back(x);
  return v;
}

TEST_P(ImuRealCurves, GeneratedCurveWithinFactorOneAndAHalfOfTheMeasuredOne) {
  NAVEMU_REQUIRE_SHARED();
  const RealPart part = GetParam();
  const ImuProfile profile = load_imu_profile(part.profile);
  const double duration_s = 3.0 * 3600.0;
  const ImuParams p = imu_params_for_run(profile, duration_s);
  const StaticRun r = static_run(p, duration_s, 11);
  const auto dir = test::shared_data("imu/imu_utils_allan");
  for (const std::string kind : {"gyr", "acc"}) {
    // Measured: gyroscope in deg/h, accelerometer in m/s^2 (../shared/data/README.md 3b).
    const double to_si = kind == "gyr" ? (3.14159265358979323846 / 180.0) / 3600.0 : 1.0;
    const auto tau = read_column(dir / fmt::format("data_{}_{}_t.txt", part.data_name, kind));
    std::array<std::vector<double>, 3> meas;
    for (int a = 0; a < 3; ++a)
      meas[static_cast<std::size_t>(a)] =
          read_column(dir / fmt::format("data_{}_{}_{}.txt", part.data_name, kind, "xyz"[a]));
    std::array<std::vector<AllanPoint>, 3> gen;
    for (std::size_t a = 0; a < 3; ++a)
      gen[a] = overlapping_allan_deviation(r.ch[(kind == "gyr" ? 3 : 0) + a], 1.0 / r.output_rate_hz, 20);
    double worst = 1.0;
    double worst_tau = 0.0;
    int compared = 0;
    for (std::size_t i = 0; i < tau.size(); ++i) {
      if (tau[i] < 0.1 || tau[i] > 1000.0) continue;
      double m = 0.0, g = 0.0;
      bool ok = true;
      for (std::size_t a = 0; a < 3; ++a) {
        m += meas[a].at(i) * to_si / 3.0;
        const auto v = adev_at(gen[a], tau[i]);
        if (v) {
          g += *v / 3.0;
        } else {
          ok = false;
        }
      }
      if (!ok) continue;
      ++compared;
      const double ratio = g / m;
      if (std::abs(std::log(ratio)) > std::abs(std::log(worst))) worst = ratio, worst_tau = tau[i];
    }
    std::printf("%s %s: %d points from 0.1 to 1000 s, worst generated/measured %.3f at %.1f s\n",
                part.profile, kind.c_str(), compared, worst, worst_tau);
    // Each axis against its own measured curve (real axes differ by up to ~4x; the profiles'
    // per-axis multipliers carry that). Reported, not asserted: 19 of the 24 axis curves are
    // within the factor 1.5; BMI160 accel x rises with a slope of ~0.8 beyond 50 s, which white
    // noise, a Gauss-Markov bias and a random walk (slope <= 1/2) cannot follow, and the others
    // outside sit at 300-1000 s, where a 3 h run has ~10 clusters.
    for (std::size_t a = 0; a < 3; ++a) {
      double axis_worst = 1.0;
      double axis_worst_tau = 0.0;
      int axis_compared = 0;
      for (std::size_t i = 0; i < tau.size(); ++i) {
        if (tau[i] < 0.1 || tau[i] > 1000.0) continue;
        const auto v = adev_at(gen[a], tau[i]);
        if (!v) continue;
        ++axis_compared;
        const double ratio = *v / (meas[a].at(i) * to_si);
        if (std::abs(std::log(ratio)) > std::abs(std::log(axis_worst))) {
          axis_worst = ratio;
          axis_worst_tau = tau[i];
        }
      }
      std::printf("  axis %c alone: worst generated/measured %.3f at %.1f s\n", "xyz"[a],
                  axis_worst, axis_worst_tau);
      EXPECT_GT(axis_compared, 20) << part.profile << " " << kind << " axis " << "xyz"[a];
    }
    EXPECT_GT(compared, 20);
    EXPECT_LT(std::abs(std::log(worst)), std::log(1.5)) << part.profile << " " << kind;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Parts, ImuRealCurves,
    ::testing::Values(RealPart{"bmi160", "BMI160"}, RealPart{"adis16448", "16448"},
                      RealPart{"xsens_mti100", "xsens"}, RealPart{"microstrain_gx4", "gx4"}),
    [](const auto& param_info) { return std::string(param_info.param.profile); });

// Integrates a static run with the strapdown mechanization from the true initial state; the
// gyroscope-only headings (each axis alone, Earth rate removed) as the paper plots them.
struct DeadReckoned {
  Vec3 gyro_heading_deg = Vec3::Zero();
  Vec3 rpy_deg = Vec3::Zero();
  double horizontal_m = 0.0;
};

DeadReckoned dead_reckon(const StaticRun& r) {
  const double dt = 1.0 / r.output_rate_hz;
  const IdealImu ideal = ideal_imu_static(kSite, Quat::Identity());
  Strapdown sd(StrapdownState{from_week_tow(2244, 0.0), kSite, Vec3::Zero(), Quat::Identity()});
  DeadReckoned d;
  for (std::size_t k = 0; k < r.ch[0].size(); ++k) {
    const Vec3 f(r.ch[0][k], r.ch[1][k], r.ch[2][k]);
    const Vec3 w(r.ch[3][k], r.ch[4][k], r.ch[5][k]);
    sd.step(f, w, dt);
    d.gyro_heading_deg += (w - ideal.w_ib_body_radps) * dt * kRadToDeg;
  }
  d.rpy_deg = euler_rpy_from_quat(sd.state().q_ned_from_body) * kRadToDeg;
  const Vec3 ned = R_ned_from_ecef(kSite) * (ecef_from_geodetic(sd.state().position) - ecef_from_geodetic(kSite));
  d.horizontal_m = std::hypot(ned.x(), ned.y());
  return d;
}

TEST(ImuPaper, FigureTwoGyroscopeDriftsAboutThreeDegreesPerHour) {
  // Paper section 2.2, Fig. 2/3: 20 min static; each gyroscope's heading drifts ~3 deg/h.
  const ImuProfile profile = load_imu_profile("paper_fig2_gyro");
  const double duration_s = 20.0 * 60.0;
  const StaticRun r = static_run(imu_params_for_run(profile, duration_s), duration_s, 1);
  const DeadReckoned d = dead_reckon(r);
  const Vec3 rate_deg_per_h = d.gyro_heading_deg / (duration_s / 3600.0);
  std::printf("paper Fig. 2 gyroscope, 20 min: heading drift x %.2f, y %.2f, z %.2f deg/h\n",
              rate_deg_per_h.x(), rate_deg_per_h.y(), rate_deg_per_h.z());
  for (int a = 0; a < 3; ++a) {
    EXPECT_GE(std::abs(rate_deg_per_h[a]), 1.5) << "axis " << a;
    EXPECT_LE(std::abs(rate_deg_per_h[a]), 6.0) << "axis " << a;
  }
}

TEST(ImuPaper, PhidgetTenMinutesAt125HzDriftsLikeALowCostUnit) {
  // Paper section 3, Fig. 7: a Phidget-like unit (drift "roughly 3 deg/minute"), 10 min at
  // 125 Hz, static. Reported; the bounds only say it drifts as a low-cost unit does.
  const ImuProfile profile = load_imu_profile("paper_phidget");
  const double duration_s = 600.0;
  const StaticRun r = static_run(imu_params_for_run(profile, duration_s, 125.0), duration_s, 1);
  ASSERT_EQ(r.output_rate_hz, 125.0);
  const DeadReckoned d = dead_reckon(r);
  std::printf("paper Phidget, 10 min at 125 Hz: gyro-only heading drift x %.1f, y %.1f, z %.1f "
              "deg; strapdown attitude rpy %.1f, %.1f, %.1f deg; horizontal position %.0f m\n",
              d.gyro_heading_deg.x(), d.gyro_heading_deg.y(), d.gyro_heading_deg.z(),
              d.rpy_deg.x(), d.rpy_deg.y(), d.rpy_deg.z(), d.horizontal_m);
  // ~3 deg/min of heading drift: tens of degrees in 10 min.
  EXPECT_GT(d.gyro_heading_deg.cwiseAbs().maxCoeff(), 10.0);
  EXPECT_LT(d.gyro_heading_deg.cwiseAbs().maxCoeff(), 100.0);
  EXPECT_GT(d.horizontal_m, 100.0);  // kilometres after two hours in the paper
}

}  // namespace
}  // namespace navemu
