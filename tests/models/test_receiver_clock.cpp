// Receiver clock: the two-state model against its Allan variance and process-noise covariance,
// with seeded, sigma-bounded statistics over independent realisations.

#include "models/receiver_clock.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

namespace navemu {
namespace {

constexpr double kPi = 3.14159265358979323846;

double allan_variance(const ReceiverClockParams& p, double tau_s) {
  return p.h0 / (2.0 * tau_s) + 2.0 * kPi * kPi * p.h_minus2 * tau_s / 3.0;
}

TEST(ReceiverClock, WithoutNoiseTheBiasGrowsWithTheInitialDrift) {
  ReceiverClockParams p;
  p.h0 = 0.0;
  p.h_minus2 = 0.0;
  p.initial_bias_s = 1e-3;
  p.initial_drift_sps = 2e-7;
  ReceiverClock clk(p, RandomStream(1, stream_id("clock", 0)));
  for (int k = 0; k < 100; ++k) clk.step(0.5);
  EXPECT_NEAR(clk.bias_s(), 1e-3 + 2e-7 * 50.0, 1e-15);
  EXPECT_DOUBLE_EQ(clk.drift_sps(), 2e-7);
  clk.step(0.0);   // no time: no change
  clk.step(-1.0);  // backwards: no change
  EXPECT_NEAR(clk.bias_s(), 1e-3 + 2e-7 * 50.0, 1e-15);
}

TEST(ReceiverClock, SameSeedGivesTheSameSequence) {
  ReceiverClockParams p;
  ReceiverClock a(p, RandomStream(42, stream_id("rx_clock", 0)));
  ReceiverClock b(p, RandomStream(42, stream_id("rx_clock", 0)));
  ReceiverClock c(p, RandomStream(43, stream_id("rx_clock", 0)));
  int same_ac = 0;
  for (int k = 0; k < 1000; ++k) {
    a.step(1.0);
    b.step(1.0);
    c.step(1.0);
    ASSERT_EQ(a.bias_s(), b.bias_s());
    ASSERT_EQ(a.drift_sps(), b.drift_sps());
    same_ac += a.bias_s() == c.bias_s();
  }
  EXPECT_EQ(same_ac, 0);
}

// The Allan variance of the fractional frequency y = dx/dt, from the phase (bias) x sampled at
// tau: AVAR(tau) = E[(x(2 tau) - 2 x(tau) + x(0))^2] / (2 tau^2). Each realisation gives one
// second difference per tau, independent across realisations, so the estimator is a scaled
// chi-square with N degrees of freedom: relative standard deviation sqrt(2 / N).
TEST(ReceiverClock, AllanVarianceMatchesThePowerLawCoefficients) {
  const ReceiverClockParams p;  // TCXO defaults: h0 = 2e-19, h_-2 = 2e-20
  const std::array<int, 3> taus = {1, 10, 100};
  const int n = 10'000;
  std::array<double, 3> sum2{};
  for (int i = 0; i < n; ++i) {
    ReceiverClock clk(p, RandomStream(2024, stream_id("allan", i)));
    std::vector<double> x(201);
    x[0] = clk.bias_s();
    for (int k = 1; k <= 200; ++k) {
      clk.step(1.0);
      x[static_cast<std::size_t>(k)] = clk.bias_s();
    }
    for (std::size_t j = 0; j < taus.size(); ++j) {
      const auto t = static_cast<std::size_t>(taus[j]);
      const double d2 = x[2 * t] - 2.0 * x[t] + x[0];
      sum2[j] += d2 * d2;
    }
  }
  for (std::size_t j = 0; j < taus.size(); ++j) {
    const double tau = taus[j];
    const double avar = sum2[j] / n / (2.0 * tau * tau);
    const double expected = allan_variance(p, tau);
    // Expected: 2.316e-19 (tau = 1 s), 1.326e-18 (10 s), 1.316e-17 (100 s).
    EXPECT_LT(std::abs(avar / expected - 1.0), 5.0 * std::sqrt(2.0 / n))
        << "tau " << tau << " s: " << avar << " vs " << expected;
  }
}

// Starting from a known state, the bias and drift after T have the covariance of the exact
// discretisation over T, whatever the step: Var(bias) = Sf T + Sg T^3 / 3 (Q(0,0)),
// Var(drift) = Sg T, Cov = Sg T^2 / 2.
TEST(ReceiverClock, CovarianceAfterTMatchesTheProcessNoise) {
  const ReceiverClockParams p;
  const double dt = 0.5, t_end = 50.0;
  const double sf = p.h0 / 2.0, sg = 2.0 * kPi * kPi * p.h_minus2;
  const double q11 = sf * t_end + sg * t_end * t_end * t_end / 3.0;
  const double q12 = sg * t_end * t_end / 2.0;
  const double q22 = sg * t_end;
  const int n = 10'000;
  double sbb = 0, sdd = 0, sbd = 0;
  for (int i = 0; i < n; ++i) {
    ReceiverClock clk(p, RandomStream(7, stream_id("clock_cov", i)));
    for (int k = 0; k < static_cast<int>(t_end / dt); ++k) clk.step(dt);
    sbb += clk.bias_s() * clk.bias_s();
    sdd += clk.drift_sps() * clk.drift_sps();
    sbd += clk.bias_s() * clk.drift_sps();
  }
  const double vbb = sbb / n, vdd = sdd / n, cbd = sbd / n;
  // Known zero mean: sample variances have relative sd sqrt(2/n); the sample covariance has
  // sd sqrt((q11 q22 + q12^2) / n). Five sigma.
  EXPECT_LT(std::abs(vbb / q11 - 1.0), 5.0 * std::sqrt(2.0 / n)) << vbb << " vs " << q11;
  EXPECT_LT(std::abs(vdd / q22 - 1.0), 5.0 * std::sqrt(2.0 / n)) << vdd << " vs " << q22;
  EXPECT_LT(std::abs(cbd - q12), 5.0 * std::sqrt((q11 * q22 + q12 * q12) / n)) << cbd << " vs " << q12;
}

}  // namespace
}  // namespace navemu
