// The MEMS IMU error model (models/imu_model.hpp): each term's statistics against its
// parameter, with seeded runs and bounds of a few standard errors; exact behaviour of the
// deterministic terms (resolution, saturation, filter, decimation, latency).

#include "models/imu_model.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

namespace navemu {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A sensor with no error at all at `rate_hz`, output = internal rate, no filter.
ImuParams clean(double rate_hz) {
  ImuParams p;
  p.name = "test";
  p.internal_rate_hz = rate_hz;
  p.output_rate_hz = rate_hz;
  return p;
}

IdealImu ideal_of(const Vec3& f, const Vec3& w) {
  IdealImu i;
  i.f_body_mps2 = f;
  i.w_ib_body_radps = w;
  return i;
}

GpsTime at(std::int64_t n, double rate_hz) {
  return GpsTime{static_cast<std::int64_t>(std::llround(static_cast<double>(n) * 1e9 / rate_hz))};
}

// Runs `steps` internal samples of a model at rest and returns the emitted samples.
std::vector<ImuSample> run(const ImuParams& p, std::uint64_t seed, std::int64_t steps,
                           const IdealImu& ideal = {}, double temperature_c = 25.0) {
  ImuModel m(p, seed);
  std::vector<ImuSample> out;
  ImuSample s;
  for (std::int64_t n = 0; n < steps; ++n)
    if (m.step(at(n, p.internal_rate_hz), ideal, temperature_c, s)) out.push_back(s);
  return out;
}

struct Moments {
  double mean = 0.0, std = 0.0;
};

Moments moments(const std::vector<double>& x) {
  Moments m;
  for (double v : x) m.mean += v;
  m.mean /= static_cast<double>(x.size());
  for (double v : x) m.std += (v - m.mean) * (v - m.mean);
  m.std = std::sqrt(m.std / static_cast<double>(x.size() - 1));
  return m;
}

std::vector<double> column(const std::vector<ImuSample>& s, bool gyro, int axis) {
  std::vector<double> x;
  x.reserve(s.size());
  for (const ImuSample& v : s) x.push_back(gyro ? v.w_body_radps[axis] : v.f_body_mps2[axis]);
  return x;
}

TEST(ImuModel, WhiteNoiseStdIsDensityTimesRootRate) {
  ImuParams p = clean(200.0);
  p.accel.white_density = 1e-3;
  p.gyro.white_density = 2e-4;
  const std::int64_t n = 100000;
  const auto s = run(p, 11, n);
  ASSERT_EQ(static_cast<std::int64_t>(s.size()), n);
  // Standard error of a sample std: sigma / sqrt(2 n) (0.22 % here); bound 5 of them.
  const double rel = 5.0 / std::sqrt(2.0 * static_cast<double>(n));
  for (int axis = 0; axis < 3; ++axis) {
    for (bool gyro : {false, true}) {
      const double sigma = (gyro ? 2e-4 : 1e-3) * std::sqrt(200.0);
      const Moments m = moments(column(s, gyro, axis));
      EXPECT_NEAR(m.std, sigma, rel * sigma) << "gyro " << gyro << " axis " << axis;
      EXPECT_NEAR(m.mean, 0.0, 5.0 * sigma / std::sqrt(static_cast<double>(n)));
    }
  }
}

// The white noise is Gaussian (the model draws it by a ziggurat sampler): third and fourth
// moments and the two-sided tail fractions beyond 1, 2, 3 and 3.5 sigma (3.44 is where the
// ziggurat's tail algorithm takes over), each within 5 standard errors.
TEST(ImuModel, WhiteNoiseIsGaussian) {
  ImuParams p = clean(1.0);
  p.accel.white_density = 1.0;
  p.gyro.white_density = 1.0;
  const auto s = run(p, 99, 200000);
  std::vector<double> x;
  for (int axis = 0; axis < 3; ++axis)
    for (bool gyro : {false, true})
      for (double v : column(s, gyro, axis)) x.push_back(v);
  const double n = static_cast<double>(x.size());
  double m3 = 0.0, m4 = 0.0;
  for (double v : x) {
    m3 += v * v * v / n;
    m4 += v * v * v * v / n;
  }
  EXPECT_NEAR(m3, 0.0, 5.0 * std::sqrt(15.0 / n));
  EXPECT_NEAR(m4, 3.0, 5.0 * std::sqrt(96.0 / n));
  for (double k : {1.0, 2.0, 3.0, 3.5}) {
    const double expected = std::erfc(k / std::sqrt(2.0));
    double count = 0.0;
    for (double v : x) count += std::abs(v) > k ? 1.0 : 0.0;
    EXPECT_NEAR(count / n, expected, 5.0 * std::sqrt(expected * (1.0 - expected) / n)) << k;
  }
}

// Through the low-pass filter and the decimation, the mean over 1 s (the Allan deviation at
// tau = 1 s of white noise) still has the configured density.
TEST(ImuModel, WhiteDensityHoldsAtTheOutputAfterFilterAndDecimation) {
  ImuParams p = clean(1000.0);
  p.output_rate_hz = 125.0;
  p.bandwidth_hz = 60.0;
  p.gyro.white_density = 3e-4;
  const auto s = run(p, 5, 2000 * 1000);
  ASSERT_EQ(s.size(), 2000u * 125u);
  for (int axis = 0; axis < 3; ++axis) {
    const auto x = column(s, true, axis);
    std::vector<double> means;
    for (std::size_t i = 0; i + 125 <= x.size(); i += 125) {
      double sum = 0.0;
      for (std::size_t j = 0; j < 125; ++j) sum += x[i + j];
      means.push_back(sum / 125.0);
    }
    // Allan variance 0.5 <(y_(k+1) - y_k)^2> of the 1-s means.
    double avar = 0.0;
    for (std::size_t k = 0; k + 1 < means.size(); ++k)
      avar += 0.5 * (means[k + 1] - means[k]) * (means[k + 1] - means[k]);
    avar /= static_cast<double>(means.size() - 1);
    EXPECT_NEAR(std::sqrt(avar), 3e-4, 0.08 * 3e-4) << "axis " << axis;
  }
  // Without the compensation the per-sample std at the output would be ~ 3e-4 sqrt(1000 Hz)
  // filtered; with it, internal_white_sigma gives the documented value.
  EXPECT_LT(internal_white_sigma(p, 3e-4), 3e-4 * std::sqrt(1000.0));
  ImuParams plain = clean(400.0);
  EXPECT_DOUBLE_EQ(internal_white_sigma(plain, 3e-4), 3e-4 * std::sqrt(400.0));
}

TEST(ImuModel, GaussMarkovBiasSigmaAndCorrelation) {
  ImuParams p = clean(50.0);
  p.gyro.bias_instability = 1e-4;
  p.gyro.bias_instability_tau_s = 2.0;
  const double sigma = kGmSigmaPerBiasInstability * 1e-4;
  const std::int64_t n = 50 * 4000;  // 4000 s = 2000 correlation times
  const auto s = run(p, 21, n);
  const std::size_t lag = 100;  // one correlation time
  for (int axis = 0; axis < 3; ++axis) {
    const auto x = column(s, true, axis);
    const Moments m = moments(x);
    // ~ T / (2 tau) = 1000 independent samples: std known to ~2.2 %; bound 12 %.
    EXPECT_NEAR(m.std, sigma, 0.12 * sigma) << "axis " << axis;
    double c0 = 0.0, c1 = 0.0;
    for (std::size_t i = 0; i + lag < x.size(); ++i) {
      c0 += (x[i] - m.mean) * (x[i] - m.mean);
      c1 += (x[i] - m.mean) * (x[i + lag] - m.mean);
    }
    EXPECT_NEAR(c1 / c0, std::exp(-1.0), 0.08) << "axis " << axis;
  }
  // Accelerometer has no bias term configured: exactly zero output.
  for (int axis = 0; axis < 3; ++axis) EXPECT_EQ(moments(column(s, false, axis)).std, 0.0);
}

// The Allan-deviation peak of a Gauss-Markov process (header constants): 0.61736 sigma at
// tau = 1.8926 T, and B maps onto the flicker floor 0.664 B.
TEST(ImuModel, GaussMarkovAllanPeakConstants) {
  auto adev = [](double x) {  // tau / T = x, per unit sigma
    return std::sqrt(2.0 / x * (1.0 - (3.0 - 4.0 * std::exp(-x) + std::exp(-2.0 * x)) / (2.0 * x)));
  };
  EXPECT_NEAR(adev(kGmAllanPeakTauPerCorrelationTime), kGmAllanPeakPerSigma, 1e-6);
  EXPECT_LT(adev(1.7), kGmAllanPeakPerSigma);
  EXPECT_LT(adev(2.1), kGmAllanPeakPerSigma);
  EXPECT_NEAR(kAllanFlickerFloorPerBiasInstability, std::sqrt(2.0 * std::log(2.0) / kPi), 1e-8);
  EXPECT_NEAR(kGmSigmaPerBiasInstability * kGmAllanPeakPerSigma, 0.66428, 1e-5);
}

// Random walk: across independent realisations (seeds x axes), Var(b(t)) = K^2 t.
TEST(ImuModel, RandomWalkVarianceGrowsLinearly) {
  ImuParams p = clean(100.0);
  p.accel.random_walk = 2e-3;
  p.gyro.random_walk = 2e-3;
  std::vector<double> at_2s, at_8s;
  for (std::uint64_t seed = 1; seed <= 150; ++seed) {
    const auto s = run(p, seed, 801);
    for (int axis = 0; axis < 3; ++axis)
      for (bool gyro : {false, true}) {
        at_2s.push_back(gyro ? s[200].w_body_radps[axis] : s[200].f_body_mps2[axis]);
        at_8s.push_back(gyro ? s[800].w_body_radps[axis] : s[800].f_body_mps2[axis]);
      }
  }
  // 900 realisations: variance known to sqrt(2/900) = 4.7 %; bound 20 %.
  const double v2 = std::pow(moments(at_2s).std, 2), v8 = std::pow(moments(at_8s).std, 2);
  EXPECT_NEAR(v2, 4e-6 * 2.0, 0.2 * 4e-6 * 2.0);
  EXPECT_NEAR(v8, 4e-6 * 8.0, 0.2 * 4e-6 * 8.0);
  EXPECT_NEAR(v8 / v2, 4.0, 1.0);
}

TEST(ImuModel, TurnOnBiasFixedWithinRunDifferentBetweenSeeds) {
  ImuParams p = clean(100.0);
  p.accel.turn_on_bias_sigma = 0.05;
  p.gyro.turn_on_bias_sigma = 0.01;
  const auto a = run(p, 1, 500);
  for (const ImuSample& s : a) {
    EXPECT_EQ(s.f_body_mps2, a.front().f_body_mps2);
    EXPECT_EQ(s.w_body_radps, a.front().w_body_radps);
  }
  const auto b = run(p, 2, 1);
  EXPECT_NE(a.front().f_body_mps2, b.front().f_body_mps2);
  EXPECT_NE(a.front().w_body_radps, b.front().w_body_radps);
  // Across seeds: zero mean, sigma as configured (600 draws: std to 2.9 %, bound 15 %).
  std::vector<double> draws;
  for (std::uint64_t seed = 1; seed <= 200; ++seed) {
    const auto s = run(p, seed, 1);
    for (int axis = 0; axis < 3; ++axis) draws.push_back(s[0].f_body_mps2[axis]);
  }
  const Moments m = moments(draws);
  EXPECT_NEAR(m.std, 0.05, 0.15 * 0.05);
  EXPECT_NEAR(m.mean, 0.0, 5.0 * 0.05 / std::sqrt(600.0));
}

TEST(ImuModel, ScaleFactorAndMisalignmentDrawnOncePerRun) {
  ImuParams p = clean(100.0);
  p.accel.scale_factor_sigma_ppm = 1000.0;
  p.gyro.misalignment_sigma_rad = 1e-3;
  const IdealImu in = ideal_of(Vec3(10.0, 0.0, 0.0), Vec3(0.0, 0.0, 1.0));
  std::vector<double> scale_errors;
  for (std::uint64_t seed = 1; seed <= 300; ++seed) {
    const auto s = run(p, seed, 3, in);
    EXPECT_EQ(s[0].f_body_mps2, s[2].f_body_mps2);
    scale_errors.push_back(s[0].f_body_mps2.x() / 10.0 - 1.0);
    EXPECT_EQ(s[0].f_body_mps2.y(), 0.0);  // no accelerometer misalignment configured
    // Gyro: z input leaks into x and y through M = I + cross-axis terms, z keeps its value.
    EXPECT_EQ(s[0].w_body_radps.z(), 1.0);
    EXPECT_LT(std::abs(s[0].w_body_radps.x()), 6e-3);
  }
  EXPECT_NEAR(moments(scale_errors).std, 1e-3, 0.15e-3);
}

TEST(ImuModel, ResolutionAndSaturationExact) {
  ImuParams p = clean(100.0);
  p.accel.resolution = 0.01;
  p.accel.full_scale = 1.0;
  p.gyro.resolution = 0.5;
  p.gyro.full_scale = 100.0;
  ImuModel m(p, 1);
  ImuSample s;
  ASSERT_TRUE(m.step(GpsTime{0}, ideal_of(Vec3(0.1234, -0.0049, 0.6789), Vec3(1.2, -3.3, 99.6)),
                     25.0, s));
  EXPECT_DOUBLE_EQ(s.f_body_mps2.x(), 0.12);
  EXPECT_EQ(s.f_body_mps2.y(), 0.0);
  EXPECT_DOUBLE_EQ(s.f_body_mps2.z(), 0.68);
  EXPECT_EQ(s.w_body_radps, Vec3(1.0, -3.5, 99.5));
  EXPECT_FALSE(s.saturated);
  ASSERT_TRUE(m.step(GpsTime{10'000'000}, ideal_of(Vec3(2.0, -1.7, 0.5), Vec3(0, 0, 250.0)), 25.0,
                     s));
  EXPECT_EQ(s.f_body_mps2, Vec3(1.0, -1.0, 0.5));
  EXPECT_EQ(s.w_body_radps.z(), 100.0);
  EXPECT_TRUE(s.saturated);
  EXPECT_TRUE(s.accel_saturated);
  EXPECT_TRUE(s.gyro_saturated);
  // Only the gyroscope over its range.
  ASSERT_TRUE(m.step(GpsTime{20'000'000}, ideal_of(Vec3(0.5, 0, 0), Vec3(0, 0, 250.0)), 25.0, s));
  EXPECT_FALSE(s.accel_saturated);
  EXPECT_TRUE(s.gyro_saturated);
}

TEST(ImuModel, LowPassHasUnitDcGainAndFirstOrderStep) {
  ImuParams p = clean(1000.0);
  p.bandwidth_hz = 5.0;
  ImuModel m(p, 1);
  ImuSample s;
  const IdealImu zero = ideal_of(Vec3(0, 0, 0), Vec3(0, 0, 0));
  const IdealImu one = ideal_of(Vec3(1, 2, -3), Vec3(0.5, 0, 0));
  for (int n = 0; n < 100; ++n) m.step(at(n, 1000.0), zero, 25.0, s);
  EXPECT_EQ(s.f_body_mps2, Vec3::Zero());
  // Time constant 1 / (2 pi 5 Hz) = 31.8 ms: 63.2 % after it, settled after 1 s.
  std::vector<double> y;
  for (int n = 100; n < 1100; ++n) {
    m.step(at(n, 1000.0), one, 25.0, s);
    y.push_back(s.f_body_mps2.x());
  }
  EXPECT_NEAR(y[31], 1.0 - std::exp(-1.0), 0.02);
  EXPECT_NEAR(s.f_body_mps2.x(), 1.0, 1e-9);
  EXPECT_NEAR(s.f_body_mps2.z(), -3.0, 1e-9);
  EXPECT_NEAR(s.w_body_radps.x(), 0.5, 1e-9);
}

TEST(ImuModel, DecimationAndLatency) {
  ImuParams p = clean(1000.0);
  p.output_rate_hz = 125.0;
  p.latency_s = 0.0035;
  EXPECT_EQ(imu_decimation(p), 8);
  ImuModel m(p, 1);
  ImuSample s;
  std::vector<GpsTime> times;
  for (int n = 0; n < 10000; ++n)
    if (m.step(at(n, 1000.0), {}, 25.0, s)) times.push_back(s.t);
  ASSERT_EQ(times.size(), 1250u);
  EXPECT_EQ(times[0].ns, 3'500'000);
  EXPECT_EQ(times[1].ns, 8'000'000 + 3'500'000);
  EXPECT_EQ(times.back().ns, 9'992'000'000 + 3'500'000);
}

TEST(ImuModel, TemperatureAndGSensitivity) {
  ImuParams p = clean(100.0);
  p.accel.bias_temp_coeff_per_c = 1e-3;
  p.gyro.scale_temp_coeff_ppm_per_c = 100.0;
  p.gyro.g_sensitivity = 2e-4;
  const IdealImu in = ideal_of(Vec3(0, 0, -9.8), Vec3(1.0, 0, 0));
  const auto s = run(p, 1, 1, in, 35.0);  // 10 degC above the reference
  EXPECT_NEAR(s[0].f_body_mps2.z(), -9.8 + 10.0 * 1e-3, 1e-12);
  EXPECT_NEAR(s[0].w_body_radps.x(), 1.0 * (1.0 + 10.0 * 100e-6), 1e-12);
  EXPECT_NEAR(s[0].w_body_radps.z(), 2e-4 * -9.8, 1e-12);
}

ImuParams everything_on() {
  ImuParams p = clean(1000.0);
  p.output_rate_hz = 200.0;
  p.bandwidth_hz = 80.0;
  for (ImuSensorParams* s : {&p.accel, &p.gyro}) {
    s->white_density = 1e-3;
    s->bias_instability = 1e-4;
    s->random_walk = 1e-5;
    s->turn_on_bias_sigma = 1e-3;
    s->scale_factor_sigma_ppm = 500.0;
    s->misalignment_sigma_rad = 1e-3;
    s->resolution = 1e-5;
    s->full_scale = 100.0;
  }
  return p;
}

TEST(ImuModel, SameSeedSameOutputDifferentSeedsUncorrelated) {
  const ImuParams p = everything_on();
  const IdealImu in = ideal_of(Vec3(0, 0, -9.8), Vec3(6e-5, 0, -4e-5));
  const auto a = run(p, 7, 200000, in);
  const auto b = run(p, 7, 200000, in);
  const auto c = run(p, 8, 200000, in);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a[i].f_body_mps2, b[i].f_body_mps2);
    ASSERT_EQ(a[i].w_body_radps, b[i].w_body_radps);
    ASSERT_EQ(a[i].t, b[i].t);
  }
  // Correlation of the sample-to-sample differences (white part) of seeds 7 and 8.
  const double bound = 5.0 / std::sqrt(static_cast<double>(a.size()));
  for (int axis = 0; axis < 3; ++axis)
    for (bool gyro : {false, true}) {
      const auto x = column(a, gyro, axis), y = column(c, gyro, axis);
      std::vector<double> dx, dy;
      for (std::size_t i = 1; i < x.size(); ++i) {
        dx.push_back(x[i] - x[i - 1]);
        dy.push_back(y[i] - y[i - 1]);
      }
      const Moments mx = moments(dx), my = moments(dy);
      double cxy = 0.0;
      for (std::size_t i = 0; i < dx.size(); ++i) cxy += (dx[i] - mx.mean) * (dy[i] - my.mean);
      cxy /= static_cast<double>(dx.size() - 1) * mx.std * my.std;
      EXPECT_LT(std::abs(cxy), bound) << "gyro " << gyro << " axis " << axis;
      EXPECT_NE(x, y);
    }
}

// Faults (issue "impairments"): a 100 Hz sensor, faults from 1 s to 3 s after an origin at 10 s.
std::vector<ImuSample> run_with_faults(const ImuParams& p, std::vector<ImuFault> faults, const IdealImu& in,
                                       std::uint64_t seed = 5) {
  ImuModel m(p, seed);
  m.set_faults(std::move(faults), GpsTime{10'000'000'000});
  std::vector<ImuSample> out;
  ImuSample s;
  for (std::int64_t n = 1000; n < 1500; ++n)
    if (m.step(at(n, p.internal_rate_hz), in, 25.0, s)) out.push_back(s);
  return out;  // out[k] at 10 s + k / 100 s
}

TEST(ImuModel, BiasStepAndScaleFaultAddExactlyOverTheirWindow) {
  const ImuParams p = clean(100.0);
  const IdealImu in = ideal_of(Vec3(1.0, 2.0, -9.8), Vec3(0.1, 0.2, 0.3));
  const EventWindow w{1.0, 2.0, 0.5};  // ramps 1.0-1.5 s and 2.5-3.0 s
  const auto s = run_with_faults(p, {{w, ImuFaultKind::kBias, ImuSensor::kGyro, 2, 0.05},
                                     {w, ImuFaultKind::kScale, ImuSensor::kAccel, -1, 1000.0}},
                                 in);
  ASSERT_EQ(s.size(), 500u);
  for (std::size_t k = 0; k < s.size(); ++k) {
    const double level = event_level(w, static_cast<double>(k) / 100.0);
    EXPECT_DOUBLE_EQ(s[k].w_body_radps.z(), 0.3 + 0.05 * level) << k;
    EXPECT_EQ(s[k].w_body_radps.x(), 0.1) << "other axes untouched";
    for (int i = 0; i < 3; ++i)
      EXPECT_NEAR(s[k].f_body_mps2[i], in.f_body_mps2[i] * (1.0 + 1e-3 * level), 1e-12) << k;
  }
  EXPECT_EQ(s[99].w_body_radps.z(), 0.3) << "before the window";
  EXPECT_DOUBLE_EQ(s[150].w_body_radps.z(), 0.35) << "full level after the ramp";
  EXPECT_EQ(s[300].w_body_radps.z(), 0.3) << "after the window";
}

TEST(ImuModel, StuckAxisHoldsTheLastOutputBeforeTheFault) {
  ImuParams p = clean(100.0);
  p.gyro.white_density = 1e-3;  // noise, so that a held value is the one sample's
  const IdealImu in = ideal_of(Vec3(0, 0, -9.8), Vec3(0, 0, 0.3));
  const auto free = run_with_faults(p, {}, in);
  const auto s = run_with_faults(p, {{EventWindow{1.0, 2.0, 0.0}, ImuFaultKind::kStuck, ImuSensor::kGyro, 0, 0.0}}, in);
  ASSERT_EQ(s.size(), free.size());
  for (std::size_t k = 0; k < s.size(); ++k) {
    if (k >= 100 && k < 300)
      EXPECT_EQ(s[k].w_body_radps.x(), free[99].w_body_radps.x()) << k;
    else
      EXPECT_EQ(s[k].w_body_radps.x(), free[k].w_body_radps.x()) << k;
    EXPECT_EQ(s[k].w_body_radps.y(), free[k].w_body_radps.y()) << "the other axes go on";
  }
  EXPECT_NE(free[150].w_body_radps.x(), free[99].w_body_radps.x());
}

// Added noise: its standard deviation is density x sqrt(rate) (as the model's own white noise,
// test WhiteNoiseStdIsDensityTimesRootRate), within 5 standard errors; outside the window the
// output is the fault-free run's, draw for draw.
TEST(ImuModel, AddedNoiseHasItsDensityAndLeavesTheOtherStreamsAlone) {
  ImuParams p = clean(100.0);
  p.accel.white_density = 1e-3;
  const IdealImu in = ideal_of(Vec3(0, 0, -9.8), Vec3(0, 0, 0));
  const auto free = run_with_faults(p, {}, in);
  const auto s = run_with_faults(p, {{EventWindow{1.0, 2.0, 0.0}, ImuFaultKind::kNoise, ImuSensor::kAccel, 1, 0.02}}, in);
  std::vector<double> added;
  for (std::size_t k = 0; k < s.size(); ++k) {
    if (k >= 100 && k < 300)
      added.push_back(s[k].f_body_mps2.y() - free[k].f_body_mps2.y());
    else
      EXPECT_EQ(s[k].f_body_mps2, free[k].f_body_mps2) << k;
    EXPECT_EQ(s[k].f_body_mps2.x(), free[k].f_body_mps2.x());
  }
  const double sigma = 0.02 * std::sqrt(100.0);
  const Moments m = moments(added);
  EXPECT_NEAR(m.std, sigma, 5.0 * sigma / std::sqrt(2.0 * static_cast<double>(added.size())));
  EXPECT_NEAR(m.mean, 0.0, 5.0 * sigma / std::sqrt(static_cast<double>(added.size())));
}

// A saturation fault clips at its range while it lasts (the narrower of it and the part's
// full scale) and sets the sample's flag; outside its window the output is the free run's.
TEST(ImuModel, SaturationFaultClipsAtItsRangeOnlyWhileItLasts) {
  ImuParams p = clean(100.0);
  p.accel.full_scale = 6.0;  // narrower than the fault's 8 m/s^2 range: the part's range stays
  const IdealImu in = ideal_of(Vec3(0, 0, -9.8), Vec3(0, 0, 0.3));
  const EventWindow w{1.0, 2.0, 0.0};
  const auto s = run_with_faults(p, {{w, ImuFaultKind::kSaturation, ImuSensor::kGyro, 2, 0.2},
                                     {w, ImuFaultKind::kSaturation, ImuSensor::kAccel, -1, 8.0}},
                                 in);
  ASSERT_EQ(s.size(), 500u);
  for (std::size_t k = 0; k < s.size(); ++k) {
    const bool on = k >= 100 && k < 300;
    EXPECT_EQ(s[k].w_body_radps.z(), on ? 0.2 : 0.3) << k;
    EXPECT_EQ(s[k].gyro_saturated, on) << k;
    EXPECT_EQ(s[k].f_body_mps2.z(), -6.0) << k;
    EXPECT_TRUE(s[k].accel_saturated) << k;
  }
}

// A sinusoidal vibration adds exactly A sin(2 pi f (t - start)) x level.
TEST(ImuModel, SinusoidalVibrationAddsItsWave) {
  const ImuParams p = clean(100.0);
  const IdealImu in = ideal_of(Vec3(0, 0, -9.8), Vec3(0.1, 0, 0));
  const EventWindow w{1.0, 2.0, 0.5};
  ImuFault f{w, ImuFaultKind::kVibration, ImuSensor::kGyro, 0, 0.05};
  f.vibration.frequency_hz = 7.0;
  const auto s = run_with_faults(p, {f}, in);
  ASSERT_EQ(s.size(), 500u);
  for (std::size_t k = 0; k < s.size(); ++k) {
    const double t_s = static_cast<double>(k) / 100.0;
    const double wave = 0.05 * std::sin(2.0 * 3.14159265358979323846 * 7.0 * (t_s - 1.0));
    EXPECT_NEAR(s[k].w_body_radps.x(), 0.1 + event_level(w, t_s) * wave, 1e-12) << k;
    EXPECT_EQ(s[k].w_body_radps.y(), 0.0);
  }
}

// Random vibration of a PSD over a band: its rms is sqrt(psd x width) within 5 standard errors
// (about 2 width x duration independent values); its averaged periodogram (1 s Hann segments)
// over the band's middle is psd within 8 % (the Butterworth skirts take ~2.5 %, the estimate's
// 1-sigma is ~1 %), and an octave outside the band it is below psd / 100. The other axes draw
// nothing.
TEST(ImuModel, RandomVibrationHasItsPsdInItsBand) {
  const ImuParams p = clean(200.0);
  const IdealImu in = ideal_of(Vec3(0, 0, -9.8), Vec3(0, 0, 0));
  constexpr double kPsd = 0.01, kLo = 5.0, kHi = 60.0;  // (m/s^2)^2/Hz, Hz
  constexpr int kSeconds = 2000, kRate = 200;
  ImuFault f{EventWindow{0.0, 1e6, 0.0}, ImuFaultKind::kVibration, ImuSensor::kAccel, 1, 0.0};
  f.vibration = {0.0, kPsd, kLo, kHi};
  ImuModel m(p, 3);
  m.set_faults({f}, GpsTime{0});
  std::vector<double> y;
  ImuSample s;
  for (std::int64_t n = 0; n < std::int64_t{kSeconds} * kRate; ++n)
    if (m.step(at(n, kRate), in, 25.0, s)) {
      ASSERT_EQ(s.f_body_mps2.x(), 0.0);
      y.push_back(s.f_body_mps2.y());
    }
  const Moments mo = moments(y);
  const double rms = std::sqrt(kPsd * (kHi - kLo));
  const double n_eff = 2.0 * (kHi - kLo) * kSeconds;
  EXPECT_NEAR(mo.std, rms, 5.0 * rms / std::sqrt(2.0 * n_eff));
  EXPECT_NEAR(mo.mean, 0.0, 5.0 * rms / std::sqrt(n_eff));
  // Welch: PSD_k = 2 |X_k|^2 / (fs sum w^2), X the DFT of the Hann-windowed segment.
  constexpr double kTwoPi = 2.0 * 3.14159265358979323846;
  std::vector<double> w(kRate), c(kRate), sn(kRate), psd(kRate / 2, 0.0);
  double w2 = 0.0;
  for (int j = 0; j < kRate; ++j) {
    w[static_cast<std::size_t>(j)] = 0.5 - 0.5 * std::cos(kTwoPi * j / kRate);
    w2 += w[static_cast<std::size_t>(j)] * w[static_cast<std::size_t>(j)];
    c[static_cast<std::size_t>(j)] = std::cos(kTwoPi * j / kRate);
    sn[static_cast<std::size_t>(j)] = std::sin(kTwoPi * j / kRate);
  }
  for (int seg = 1; seg < kSeconds; ++seg)  // the first second: the filter settling
    for (int k = 1; k < kRate / 2; ++k) {
      double re = 0.0, im = 0.0;
      for (int j = 0; j < kRate; ++j) {
        const auto u = static_cast<std::size_t>(j), r = static_cast<std::size_t>((k * j) % kRate);
        const double x = w[u] * y[static_cast<std::size_t>(seg * kRate + j)];
        re += x * c[r];
        im -= x * sn[r];
      }
      psd[static_cast<std::size_t>(k)] += 2.0 * (re * re + im * im) / (kRate * w2) / (kSeconds - 1);
    }
  double middle = 0.0;
  for (int k = 15; k <= 30; ++k) middle += psd[static_cast<std::size_t>(k)] / 16.0;
  EXPECT_NEAR(middle, kPsd, 0.08 * kPsd);
  EXPECT_LT(psd[2], kPsd / 100.0);
  EXPECT_LT(psd[95], kPsd / 100.0);
  std::printf("random vibration: rms %.4f (expected %.4f), PSD %.5f in the band's middle (psd %.5f), %.2e at 2 Hz, "
              "%.2e at 95 Hz\n",
              mo.std, rms, middle, kPsd, psd[2], psd[95]);
}

// A temperature change acts through the datasheet's temperature coefficients, and the sample
// carries the temperature the part had.
TEST(ImuModel, TemperatureFaultDrivesTheTemperatureCoefficients) {
  ImuParams p = clean(100.0);
  p.gyro.bias_temp_coeff_per_c = 1e-3;         // rad/s per degC
  p.accel.scale_temp_coeff_ppm_per_c = 100.0;  // ppm per degC
  const IdealImu in = ideal_of(Vec3(0, 0, -9.8), Vec3(0, 0, 0));
  const EventWindow w{1.0, 2.0, 0.5};
  const auto s = run_with_faults(p, {{w, ImuFaultKind::kTemperature, ImuSensor::kGyro, -1, 40.0}}, in);
  ASSERT_EQ(s.size(), 500u);
  for (std::size_t k = 0; k < s.size(); ++k) {
    const double dT = 40.0 * event_level(w, static_cast<double>(k) / 100.0);
    EXPECT_NEAR(s[k].temperature_c, 25.0 + dT, 1e-12) << k;
    EXPECT_NEAR(s[k].w_body_radps.x(), 1e-3 * dT, 1e-12) << k;
    EXPECT_NEAR(s[k].f_body_mps2.z(), -9.8 * (1.0 + 100e-6 * dT), 1e-12) << k;
  }
  EXPECT_NEAR(s[200].temperature_c, 65.0, 1e-12);
}

// Different axes and terms are independent streams too.
TEST(ImuModel, AxesUncorrelated) {
  ImuParams p = clean(100.0);
  p.accel.white_density = 1.0;
  p.gyro.white_density = 1.0;
  const auto s = run(p, 3, 100000);
  const auto x = column(s, false, 0), y = column(s, false, 1), w = column(s, true, 0);
  auto corr = [](const std::vector<double>& u, const std::vector<double>& v) {
    const Moments mu = moments(u), mv = moments(v);
    double c = 0.0;
    for (std::size_t i = 0; i < u.size(); ++i) c += (u[i] - mu.mean) * (v[i] - mv.mean);
    return c / (static_cast<double>(u.size() - 1) * mu.std * mv.std);
  };
  EXPECT_LT(std::abs(corr(x, y)), 5.0 / std::sqrt(1e5));
  EXPECT_LT(std::abs(corr(x, w)), 5.0 / std::sqrt(1e5));
}

// The paper's parameters (section 2.2, 3) mapped onto the datasheet model.
TEST(ImuModel, PaperParameterMapping) {
  PaperImuParams q;  // defaults: the paper's section 3 values
  q.run_time_h = 1.0 / 6.0;
  q.gyro_gm_sigma = 2e-4;
  q.accel_null_offset = Vec3(0.01, 0.02, 0.03);
  const ImuParams p = imu_params_from_paper(q, 125.0);
  const double kb = 1.380649e-23;
  const double thermal_a = std::sqrt(4 * kb * q.temperature_k * q.accel_omega0_radps /
                                     (q.accel_proof_mass_kg * q.quality_factor));
  const double quant = 0.01745 * std::sqrt(3 * 0.2 * 0.2 * 6.0) / std::sqrt(125.0);
  const double white_a = 0.12 / std::sqrt(125.0);
  const double white_g = 0.15 * kPi / 180.0 / std::sqrt(125.0);
  EXPECT_NEAR(p.accel.white_density,
              std::sqrt(white_a * white_a + thermal_a * thermal_a + quant * quant), 1e-12);
  EXPECT_GT(p.gyro.white_density, std::sqrt(white_g * white_g + quant * quant) - 1e-12);
  EXPECT_LT(p.gyro.white_density, std::sqrt(white_g * white_g + quant * quant) * 1.001);
  EXPECT_NEAR(kGmSigmaPerBiasInstability * p.gyro.bias_instability, 2e-4, 1e-15);
  EXPECT_EQ(p.gyro.bias_instability_tau_s, 10.0);
  EXPECT_EQ(p.accel.null_offset, Vec3(0.01, 0.02, 0.03));
  EXPECT_EQ(p.output_rate_hz, 125.0);
  // Per output sample, the white noise has the paper's coefficients (plus thermal and
  // quantization): accelerometer 1-sigma just above 0.12 m/s^2.
  const auto s = run(p, 4, 50000);
  const double expect_a = p.accel.white_density * std::sqrt(125.0);
  EXPECT_NEAR(moments(column(s, false, 0)).std, expect_a, 0.02 * expect_a);
  EXPECT_NEAR(moments(column(s, false, 0)).mean, 0.01, 5 * expect_a / std::sqrt(5e4) + 2e-3);
}

TEST(ImuModel, RejectsInvalidParameters) {
  ImuParams p = clean(100.0);
  p.gyro.bias_instability_tau_s = -1.0;
  EXPECT_THROW(ImuModel(p, 1), std::invalid_argument);
  p = clean(100.0);
  p.accel.white_density = std::nan("");
  EXPECT_THROW(ImuModel(p, 1), std::invalid_argument);
  p = clean(100.0);
  p.output_rate_hz = 200.0;
  EXPECT_THROW(ImuModel(p, 1), std::invalid_argument);
}

}  // namespace
}  // namespace navemu
