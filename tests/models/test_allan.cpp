// Overlapping Allan deviation and the fitted noise terms: a hand-computed series, seeded white
// noise, random walk and Gauss-Markov processes against their analytic curves (sigma-bounded),
// the datasheet unit conversions, and a real imu_utils curve.

#include "models/allan.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <iostream>
#include <numbers>
#include <string>
#include <vector>

#include "models/random.hpp"
#include "tests/test_support.hpp"

namespace navemu {
namespace {

// Relative one-sigma-ish uncertainty of an overlapping ADEV point: 1/sqrt(number of
// independent clusters N/m) (NIST SP 1065 section 5.3; the true value for white noise is
// about 0.6 of this, so a bound of k times it is a conservative k-sigma bound).
double relative_uncertainty(std::size_t n, double m) { return 1.0 / std::sqrt(double(n) / m); }

TEST(AllanOverlapping, HandComputedEightSamples) {
  // y = 1 3 2 5 4 4 6 3, dt = 0.5 s.
  // m = 1: differences of adjacent samples 2 -1 3 -1 0 2 -3, squares sum 28 over 7:
  //        sigma^2 = 28 / (2 * 7) = 2.
  // m = 2: 2-sample means 2 2.5 3.5 4.5 4 5 4.5; differences 2 apart 1.5 2 .5 .5 .5, squares
  //        sum 7 over 5: sigma^2 = 7 / 10 = 0.7.
  // m = 3: 3-sample means 2 10/3 11/3 13/3 14/3 13/3; differences 3 apart 7/3 4/3 2/3,
  //        squares sum 69/9 over 3: sigma^2 = 69 / 9 / 6 = 23/18.
  // m stops at floor((8 - 1) / 2) = 3.
  const std::vector<double> y = {1, 3, 2, 5, 4, 4, 6, 3};
  const auto c = overlapping_allan_deviation(y, 0.5, 10);
  ASSERT_EQ(c.size(), 3u);
  EXPECT_DOUBLE_EQ(c[0].tau_s, 0.5);
  EXPECT_DOUBLE_EQ(c[1].tau_s, 1.0);
  EXPECT_DOUBLE_EQ(c[2].tau_s, 1.5);
  EXPECT_NEAR(c[0].adev, std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(c[1].adev, std::sqrt(0.7), 1e-12);
  EXPECT_NEAR(c[2].adev, std::sqrt(23.0 / 18.0), 1e-12);
  EXPECT_EQ(c[0].clusters, 7);
  EXPECT_EQ(c[1].clusters, 5);
  EXPECT_EQ(c[2].clusters, 3);
  // A constant offset does not change the deviation.
  std::vector<double> shifted = y;
  for (double& v : shifted) v += 1000.0;
  const auto cs = overlapping_allan_deviation(shifted, 0.5, 10);
  for (std::size_t i = 0; i < c.size(); ++i) EXPECT_NEAR(cs[i].adev, c[i].adev, 1e-9);
}

TEST(AllanOverlapping, LogSpacedUniqueClusterSizes) {
  const std::vector<double> y(1000, 0.0);
  const auto c = overlapping_allan_deviation(y, 1.0, 4);
  // round(10^(i/4)): 1 2 3 6 10 18 32 56 100 178 316 (562 > 499 stops).
  const std::vector<double> expected = {1, 2, 3, 6, 10, 18, 32, 56, 100, 178, 316};
  ASSERT_EQ(c.size(), expected.size());
  for (std::size_t i = 0; i < c.size(); ++i) EXPECT_EQ(c[i].tau_s, expected[i]);
  EXPECT_TRUE(overlapping_allan_deviation({1.0, 2.0}, 1.0).empty());
  EXPECT_THROW(overlapping_allan_deviation(y, 0.0), std::invalid_argument);
  EXPECT_THROW(overlapping_allan_deviation(y, 1.0, 0), std::invalid_argument);
}

TEST(AllanWhiteNoise, MatchesDensityOverSqrtTau) {
  // White rate noise of density N: per-sample sigma N / sqrt(dt); ADEV(tau) = N / sqrt(tau).
  const double density = 0.02, dt = 0.01;
  const std::size_t n = 1'000'000;
  RandomStream rng(11, stream_id("allan-white"));
  std::vector<double> y(n);
  for (double& v : y) v = 3.0 + density / std::sqrt(dt) * rng.normal();
  const auto curve = overlapping_allan_deviation(y, dt, 10);
  int checked = 0;
  for (const AllanPoint& p : curve) {
    const double m = p.tau_s / dt;
    if (double(n) / m < 10.0) continue;
    const double expected = allan_white(density, p.tau_s);
    EXPECT_NEAR(p.adev / expected, 1.0, 3.0 * relative_uncertainty(n, m)) << "tau " << p.tau_s;
    ++checked;
  }
  EXPECT_GE(checked, 40);
  const AllanFit fit = fit_allan(curve);
  EXPECT_NEAR(fit.white_density / density, 1.0, 0.02);
  EXPECT_EQ(fit.random_walk, 0.0);
}

TEST(AllanRandomWalk, MatchesKSqrtTauOverThree) {
  // A sampled rate random walk with increments of variance K^2 dt has the Allan variance
  // K^2 tau / 3 * (1 + 1 / (2 m^2)) (sum over the cluster of the discrete walk; the second
  // term is the sampling correction, 3 % at m = 3). Independent reference: the closed form.
  const double k = 0.005, dt = 0.01;
  const std::size_t n = 1'000'000;
  RandomStream rng(12, stream_id("allan-rw"));
  std::vector<double> y(n);
  double x = 0.0;
  for (double& v : y) {
    x += k * std::sqrt(dt) * rng.normal();
    v = x;
  }
  const auto curve = overlapping_allan_deviation(y, dt, 10);
  int checked = 0;
  for (const AllanPoint& p : curve) {
    const double m = std::round(p.tau_s / dt);
    if (double(n) / m < 10.0) continue;
    const double expected = allan_random_walk(k, p.tau_s) * std::sqrt(1.0 + 1.0 / (2.0 * m * m));
    EXPECT_NEAR(p.adev / expected, 1.0, 4.0 * relative_uncertainty(n, m)) << "tau " << p.tau_s;
    ++checked;
  }
  EXPECT_GE(checked, 40);
}

TEST(AllanFit, RecoversWhiteNoiseAndRandomWalk) {
  // White noise N plus rate random walk K: crossing at tau = sqrt(3) N / K = 3.5 s.
  const double density = 0.01, k = 0.005, dt = 0.01;
  const std::size_t n = 4'000'000;  // 11 h: the random walk's own scatter is ~2 % here
  RandomStream rng(13, stream_id("allan-fit"));
  std::vector<double> y(n);
  double walk = 0.0;
  for (double& v : y) {
    walk += k * std::sqrt(dt) * rng.normal();
    v = walk + density / std::sqrt(dt) * rng.normal();
  }
  const AllanFit fit = fit_allan(overlapping_allan_deviation(y, dt, 10));
  EXPECT_NEAR(fit.white_density / density, 1.0, 0.10);
  EXPECT_NEAR(fit.random_walk / k, 1.0, 0.10);
  // The minimum of N/sqrt(tau) (+) K sqrt(tau/3) is sqrt(2 N K / sqrt(3)) at the crossing.
  const double floor = std::sqrt(2.0 * density * k / std::sqrt(3.0));
  EXPECT_NEAR(fit.bias_instability * kAllanBiasInstabilityFactor / floor, 1.0, 0.10);
  EXPECT_NEAR(std::log10(fit.bias_instability_tau_s), std::log10(std::sqrt(3.0) * density / k),
              0.3);
}

// Allan variance of a first-order Gauss-Markov process of standard deviation sigma and
// correlation time tc (driving noise PSD q = 2 sigma^2 / tc), IEEE Std 952-1997 C.1.5 /
// El-Sheimy, Hou & Niu 2008 eq. (14):
//   q tc^2 / tau * [1 - tc / (2 tau) (3 - 4 exp(-tau/tc) + exp(-2 tau/tc))].
double gauss_markov_avar(double sigma, double tc, double tau) {
  const double q = 2.0 * sigma * sigma / tc;
  return q * tc * tc / tau *
         (1.0 - tc / (2.0 * tau) * (3.0 - 4.0 * std::exp(-tau / tc) + std::exp(-2.0 * tau / tc)));
}

TEST(AllanFit, GaussMarkovFloor) {
  // White noise plus a Gauss-Markov bias whose hump (0.617 sigma at 1.9 tc) levels the curve
  // into a floor. Reference: the first local minimum of the analytic curve on a fine grid.
  const double density = 0.002, sigma = 0.002, tc = 10.0, dt = 0.01;
  const std::size_t n = 1'000'000;
  double floor = 0.0, prev = 1e300;
  for (int i = 0; i < 2000; ++i) {
    const double tau = std::pow(10.0, -2.0 + 0.002 * i);
    const double a = std::sqrt(density * density / tau + gauss_markov_avar(sigma, tc, tau));
    if (a > prev) {
      floor = prev;
      break;
    }
    prev = a;
  }
  ASSERT_GT(floor, 0.0);
  RandomStream rng(14, stream_id("allan-gm"));
  GaussMarkov bias(sigma, tc, rng);
  std::vector<double> y(n);
  for (double& v : y) v = bias.step(dt, rng) + density / std::sqrt(dt) * rng.normal();
  const auto curve = overlapping_allan_deviation(y, dt, 10);
  const AllanFit fit = fit_allan(curve);
  EXPECT_NEAR(fit.bias_instability * kAllanBiasInstabilityFactor / floor, 1.0, 0.10)
      << "tau " << fit.bias_instability_tau_s;
  EXPECT_GT(fit.bias_instability_tau_s, 2.0);
  EXPECT_LT(fit.bias_instability_tau_s, 30.0);
  EXPECT_NEAR(fit.white_density / density, 1.0, 0.10);
  // With these numbers the floor / 0.664 is close to sigma itself.
  EXPECT_NEAR(fit.bias_instability / sigma, 1.0, 0.15);
}

TEST(AllanFit, AnalyticCurveAndShortCurves) {
  // Noise-free curve N / sqrt(tau) (+) 0.664 B (+) K sqrt(tau/3), tau from 0.01 s to 1e6 s:
  // white noise dominates below 0.1 s, the floor from 10 s to 1000 s, the random walk above
  // 3e4 s. Its minimum, at sqrt(3) N / K = 102 s, is sqrt((0.664 B)^2 + 2 N K / sqrt(3)).
  const double nd = 1e-4, b = 1.5e-4, k = 1.7e-6;
  const double fl = kAllanBiasInstabilityFactor * b;
  std::vector<AllanPoint> curve;
  for (int i = 0; i <= 80; ++i) {
    const double tau = std::pow(10.0, -2.0 + 0.1 * i);
    curve.push_back({tau, std::sqrt(nd * nd / tau + fl * fl + k * k * tau / 3.0), 0});
  }
  const AllanFit fit = fit_allan(curve);
  const double minimum = std::sqrt(fl * fl + 2.0 * nd * k / std::sqrt(3.0));
  EXPECT_NEAR(fit.white_density / nd, 1.0, 0.05);  // read below 0.1 s, extrapolated to 1 s
  EXPECT_NEAR(fit.bias_instability * kAllanBiasInstabilityFactor / minimum, 1.0, 0.01);
  EXPECT_NEAR(fit.bias_instability_tau_s / 102.0, 1.0, 0.3);
  EXPECT_NEAR(fit.random_walk / k, 1.0, 0.10);
  // A curve that stops at 0.08 s: the white-noise line is extrapolated to 1 s; no floor and
  // no rise, so B is an upper bound and K is 0.
  const std::vector<AllanPoint> early(curve.begin(), curve.begin() + 10);
  const AllanFit fe = fit_allan(early);
  EXPECT_NEAR(fe.white_density / nd, 1.0, 0.05);
  EXPECT_GE(fe.bias_instability * kAllanBiasInstabilityFactor, curve[9].adev * 0.999);
  EXPECT_EQ(fe.random_walk, 0.0);
  // Nothing to read.
  const AllanFit none = fit_allan({});
  EXPECT_EQ(none.white_density, 0.0);
  EXPECT_EQ(none.bias_instability, 0.0);
}

TEST(AllanUnits, DatasheetConversions) {
  // Each datasheet unit expressed independently in SI and converted back to 1.
  const double deg = std::numbers::pi / 180.0, hour = 3600.0;
  EXPECT_NEAR(arw_deg_per_sqrt_h(deg / std::sqrt(hour)), 1.0, 1e-12);    // 1 deg/sqrt(h)
  EXPECT_NEAR(gyro_bias_instability_deg_per_h(deg / hour), 1.0, 1e-12);  // 1 deg/h
  EXPECT_NEAR(rrw_deg_per_h_per_sqrt_h(deg / hour / std::sqrt(hour)), 1.0, 1e-12);
  EXPECT_NEAR(vrw_mps_per_sqrt_h(1.0 / std::sqrt(hour)), 1.0, 1e-12);    // 1 m/s/sqrt(h)
  EXPECT_NEAR(accel_bias_instability_mg(9.80665e-3), 1.0, 1e-12);       // 1 mg
  EXPECT_NEAR(accrw_mps_per_h_1p5(1.0 / std::pow(hour, 1.5)), 1.0, 1e-12);
  // Datasheet example: ADIS16448 ARW 0.66 deg/sqrt(h) = 1.92e-4 rad/s/sqrt(Hz).
  EXPECT_NEAR(arw_deg_per_sqrt_h(1.92e-4), 0.66, 0.001);
}

std::vector<double> read_column(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::vector<double> v;
  for (double x; in >> x;) v.push_back(x);
  return v;
}

TEST(AllanFit, ImuUtilsBmi160GyroX) {
  NAVEMU_REQUIRE_SHARED();
  // imu_utils (gaowenliang/imu_utils, src/gyr_lib/fitallan_gyr.cpp) writes the measured curve
  // in deg/h (rad/s * 57.3 * 3600) and derives its yaml terms from a least-squares model fit
  // sigma^2 = Q^2/tau^2 + N^2/tau + B^2 + K^2 tau + R^2 tau^2, not from the curve itself:
  //   gyr_n = sqrt(freq) * model_adev(1 s) / (57.3 * 3600): ADEV at 1 s times sqrt(sample
  //           rate), i.e. the discrete per-sample sigma, not the density in rad/s/sqrt(Hz);
  //   gyr_w = min(model_adev) / (57.3 * 3600): the floor itself, without the 1/0.664 factor.
  // The rate is the inverse of the first tau (m = 1): 1 / 0.005091714 s = 196.4 Hz.
  const auto tau = read_column(test::shared_data("imu/imu_utils_allan/data_BMI160_gyr_t.txt"));
  const auto dev = read_column(test::shared_data("imu/imu_utils_allan/data_BMI160_gyr_x.txt"));
  ASSERT_EQ(tau.size(), dev.size());
  ASSERT_GT(tau.size(), 50u);
  const double deg_per_h = 1.0 / (57.3 * 3600.0);  // imu_utils' own factor
  std::vector<AllanPoint> curve;
  for (std::size_t i = 0; i < tau.size(); ++i) curve.push_back({tau[i], dev[i] * deg_per_h, 0});
  const AllanFit fit = fit_allan(curve);
  const double rate_hz = 1.0 / tau[0];
  const double gyr_n = 1.4274184891384049e-03, gyr_w = 3.7205161559693717e-05;
  EXPECT_NEAR(fit.white_density * std::sqrt(rate_hz) / gyr_n, 1.0, 0.20)
      << "N " << fit.white_density << " rad/s/sqrt(Hz)";
  EXPECT_NEAR(fit.bias_instability * kAllanBiasInstabilityFactor / gyr_w, 1.0, 0.20)
      << "B " << fit.bias_instability << " rad/s at " << fit.bias_instability_tau_s << " s";
  EXPECT_GT(fit.bias_instability_tau_s, 20.0);
  EXPECT_LT(fit.bias_instability_tau_s, 100.0);
  RecordProperty("white_rad_s_sqrtHz", std::to_string(fit.white_density));
  RecordProperty("bias_instability_rad_s", std::to_string(fit.bias_instability));
  RecordProperty("random_walk", std::to_string(fit.random_walk));
}

// The x-axis value of `key` (gyr_n, gyr_w, acc_n, acc_w) in an imu_utils *_imu_param.yaml.
double imu_utils_x_axis(const std::filesystem::path& yaml, const std::string& key) {
  std::ifstream in(yaml);
  bool in_x = false;
  for (std::string line; std::getline(in, line);) {
    if (line.find("x-axis:") != std::string::npos) in_x = true;
    else if (line.find("-axis:") != std::string::npos) in_x = false;
    const std::size_t k = line.find(key + ":");
    if (in_x && k != std::string::npos) return std::stod(line.substr(k + key.size() + 1));
  }
  return std::nan("");
}

TEST(AllanFit, ImuUtilsCurvesOfSixSensors) {
  NAVEMU_REQUIRE_SHARED();
  // Every measured x-axis curve, gyroscope and accelerometer. The yaml files of 16448, A3, N3,
  // gx4 and xsens were written by imu_utils' earlier fit, whose white noise is the model ADEV
  // at 1 s (a density); BMI160's by the later one, which multiplies it by sqrt(rate) (see
  // ImuUtilsBmi160GyroX). Both *_w are the model minimum without 1/0.664. Some curves rise
  // over the first clusters (output filtering: A3 and N3 accelerometers); the floor must still
  // be found past it.
  const std::string dir = "imu/imu_utils_allan/";
  for (const std::string sensor : {"16448", "A3", "N3", "gx4", "xsens", "BMI160"}) {
    for (const std::string kind : {"gyr", "acc"}) {
      const auto tau = read_column(test::shared_data(dir + "data_" + sensor + "_" + kind + "_t.txt"));
      const auto dev = read_column(test::shared_data(dir + "data_" + sensor + "_" + kind + "_x.txt"));
      ASSERT_EQ(tau.size(), dev.size()) << sensor << kind;
      ASSERT_GT(tau.size(), 50u) << sensor << kind;
      const double scale = kind == "gyr" ? 1.0 / (57.3 * 3600.0) : 1.0;
      std::vector<AllanPoint> curve;
      for (std::size_t i = 0; i < tau.size(); ++i) curve.push_back({tau[i], dev[i] * scale, 0});
      const AllanFit fit = fit_allan(curve);
      const auto yaml = test::shared_data(dir + sensor + "_imu_param.yaml");
      double n_ref = imu_utils_x_axis(yaml, kind + "_n");
      if (sensor == "BMI160") n_ref /= std::sqrt(1.0 / tau[0]);
      const double w_ref = imu_utils_x_axis(yaml, kind + "_w");
      EXPECT_NEAR(fit.white_density / n_ref, 1.0, 0.25) << sensor << " " << kind;
      EXPECT_NEAR(fit.bias_instability * kAllanBiasInstabilityFactor / w_ref, 1.0, 0.25)
          << sensor << " " << kind << " at " << fit.bias_instability_tau_s << " s";
      EXPECT_GT(fit.bias_instability_tau_s, 1.0) << sensor << " " << kind;
    }
  }
}

TEST(AllanOverlapping, ThreeHoursAt200HzPerAxis) {
  // 3 h at 200 Hz = 2.16 M samples; O(N) per tau. The bound only catches an O(N^2) slip.
  const std::size_t n = 2'160'000;
  RandomStream rng(15, stream_id("allan-speed"));
  std::vector<double> y(n);
  for (double& v : y) v = rng.normal();
  const auto t0 = std::chrono::steady_clock::now();
  const auto curve = overlapping_allan_deviation(y, 0.005, 10);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_GT(curve.size(), 55u);
  EXPECT_LT(s, 5.0);
  RecordProperty("seconds", std::to_string(s));
  std::cout << "overlapping ADEV of " << n << " samples, " << curve.size() << " taus: " << s
            << " s\n";
}

}  // namespace
}  // namespace navemu
