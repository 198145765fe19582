// Signal tracking: loop thermal noise against hand-computed values, C/N0 by elevation, and the
// bookkeeping of carrier-phase arcs.

#include "models/tracking.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "models/geodesy.hpp"
#include "tests/test_support.hpp"

namespace navemu {
namespace {

// C/N0 = 45 dB-Hz is 10^4.5 = 31622.7766 Hz.
//
// DLL, d = 1 chip, B_L = 1 Hz, T = 20 ms:
//   B_L d / (2 C/N0)             = 1 / 63245.5532         = 1.5811388e-5 chip^2
//   1 + 2 / (T C/N0 (2 - d))     = 1 + 2 / 632.455532     = 1.0031623
//   sqrt(product)                = sqrt(1.5861388e-5)     = 3.9826358e-3 chip
//   x 293.052 m                                           = 1.1671194 m
TEST(Tracking, DllNoiseAt45DbHzByHand) {
  TrackingParams p;  // d = 1, B_L = 1 Hz, T = 20 ms, C/A chip
  EXPECT_NEAR(dll_noise_m(45.0, p), 1.1671194, 1e-6);
}

// Narrow correlator d = 0.1:
//   1 / 632455.532 = 1.5811388e-6;  1 + 2 / (632.455532 x 1.9) = 1.0016644;
//   sqrt(1.5837704e-6) = 1.2584794e-3 chip = 0.3687999 m,
// sqrt(10) x sqrt(1.0031623 / 1.0016644) = 3.1646 times less than d = 1.
TEST(Tracking, NarrowCorrelatorReducesDllNoiseBySqrtTen) {
  TrackingParams wide;
  TrackingParams narrow;
  narrow.chip_spacing = 0.1;
  EXPECT_NEAR(dll_noise_m(45.0, narrow), 0.3687999, 1e-6);
  const double ratio = dll_noise_m(45.0, wide) / dll_noise_m(45.0, narrow);
  EXPECT_NEAR(ratio, std::sqrt(10.0), 0.01 * std::sqrt(10.0));
  // At high C/N0 the squaring loss vanishes and the ratio tends to sqrt(10) exactly.
  EXPECT_NEAR(dll_noise_m(80.0, wide) / dll_noise_m(80.0, narrow), std::sqrt(10.0), 1e-5);
}

// PLL, B_n = 15 Hz, T = 20 ms, 45 dB-Hz:
//   15 / 31622.7766 = 4.7434165e-4;  1 + 1 / (2 x 0.02 x 31622.7766) = 1.00079057;
//   sqrt(4.7471665e-4) = 2.1787993e-2 rad;  / 2 pi = 3.4676668e-3 cycles (0.66 mm at L1).
TEST(Tracking, PllNoiseAt45DbHzByHand) {
  TrackingParams p;
  EXPECT_NEAR(pll_noise_cycles(45.0, p), 3.4676668e-3, 1e-9);
}

// FLL, B_n = 2 Hz, T = 20 ms, F = 1, 45 dB-Hz:
//   4 x 2 / 31622.7766 = 2.5298221e-4;  1 + 1 / (0.02 x 31622.7766) = 1.00158114;
//   sqrt(2.5338222e-4) = 1.5917985e-2;  / (2 pi 0.02) = 0.12667129 Hz.
TEST(Tracking, FllNoiseAt45DbHzByHand) {
  TrackingParams p;
  EXPECT_NEAR(fll_noise_hz(45.0, p), 0.12667129, 1e-7);
}

TEST(Tracking, NoiseFallsWithCn0AndGrowsWithBandwidth) {
  TrackingParams p;
  EXPECT_GT(dll_noise_m(30.0, p), dll_noise_m(40.0, p));
  EXPECT_GT(pll_noise_cycles(30.0, p), pll_noise_cycles(40.0, p));
  EXPECT_GT(fll_noise_hz(30.0, p), fll_noise_hz(40.0, p));
  TrackingParams wide = p;
  wide.dll_bandwidth_hz = 4.0;
  EXPECT_NEAR(dll_noise_m(45.0, wide), 2.0 * dll_noise_m(45.0, p), 1e-12);
}

TEST(Cn0, ZenithTablePointsAndLinearInBetween) {
  const Cn0Model m;
  EXPECT_NEAR(cn0_dbhz(m, 90.0 * kDegToRad), m.zenith_dbhz, 1e-12);
  for (const auto& [el_deg, gain_db] : m.gain_db_by_el_deg)
    EXPECT_NEAR(cn0_dbhz(m, el_deg * kDegToRad), m.zenith_dbhz + gain_db, 1e-9) << el_deg;
  // 50 deg: a third of the way from 45 (-2 dB) to 60 (-1 dB).
  EXPECT_NEAR(cn0_dbhz(m, 50.0 * kDegToRad), 49.0 - 2.0 + 1.0 / 3.0, 1e-9);
  // 7.5 deg: halfway from 5 (-10 dB) to 10 (-8 dB).
  EXPECT_NEAR(cn0_dbhz(m, 7.5 * kDegToRad), 49.0 - 9.0, 1e-9);
}

TEST(Cn0, HeldAtTheTableEnds) {
  const Cn0Model m;
  EXPECT_NEAR(cn0_dbhz(m, -5.0 * kDegToRad), 49.0 - 13.0, 1e-12);
  EXPECT_NEAR(cn0_dbhz(m, 95.0 * kDegToRad), 49.0, 1e-12);
  Cn0Model shifted = m;
  shifted.zenith_dbhz = 45.0;
  EXPECT_NEAR(cn0_dbhz(shifted, 20.0 * kDegToRad), 40.0, 1e-9);
}

TEST(CarrierArcs, AmbiguityConstantAndIntegerWithinAnArcAndLockTimeGrows) {
  CarrierArcs arcs(123);
  const CarrierArcs::Arc first = arcs.update(gps_sat(12), 100.0, true);
  EXPECT_TRUE(first.new_arc);
  EXPECT_EQ(first.lock_time_s, 0.0);
  EXPECT_EQ(first.ambiguity_cycles, std::floor(first.ambiguity_cycles));
  EXPECT_LE(std::abs(first.ambiguity_cycles), 1e6);
  for (int k = 1; k < 60; ++k) {
    const CarrierArcs::Arc a = arcs.update(gps_sat(12), 100.0 + k, true);
    EXPECT_FALSE(a.new_arc);
    EXPECT_EQ(a.ambiguity_cycles, first.ambiguity_cycles);
    EXPECT_DOUBLE_EQ(a.lock_time_s, k);
  }
}

TEST(CarrierArcs, UntrackedEpochStartsANewArc) {
  CarrierArcs arcs(123);
  const double amb0 = arcs.update(gps_sat(3), 0.0, true).ambiguity_cycles;
  arcs.update(gps_sat(3), 1.0, true);
  const CarrierArcs::Arc lost = arcs.update(gps_sat(3), 2.0, false);
  EXPECT_FALSE(lost.new_arc);
  EXPECT_EQ(lost.ambiguity_cycles, 0.0);
  EXPECT_EQ(lost.lock_time_s, 0.0);
  arcs.update(gps_sat(3), 3.0, false);
  const CarrierArcs::Arc back = arcs.update(gps_sat(3), 4.0, true);
  EXPECT_TRUE(back.new_arc);
  EXPECT_EQ(back.lock_time_s, 0.0);
  EXPECT_NE(back.ambiguity_cycles, amb0);
  EXPECT_EQ(back.ambiguity_cycles, std::floor(back.ambiguity_cycles));
  const CarrierArcs::Arc next = arcs.update(gps_sat(3), 5.0, true);
  EXPECT_FALSE(next.new_arc);
  EXPECT_EQ(next.ambiguity_cycles, back.ambiguity_cycles);
  EXPECT_DOUBLE_EQ(next.lock_time_s, 1.0);
}

TEST(CarrierArcs, GapLongerThanTheLimitStartsANewArc) {
  CarrierArcs arcs(9);  // max gap 10 s
  const double amb0 = arcs.update(gps_sat(7), 0.0, true).ambiguity_cycles;
  // Exactly 10 s without an update is still the same arc.
  const CarrierArcs::Arc same = arcs.update(gps_sat(7), 10.0, true);
  EXPECT_FALSE(same.new_arc);
  EXPECT_EQ(same.ambiguity_cycles, amb0);
  EXPECT_DOUBLE_EQ(same.lock_time_s, 10.0);
  // More than 10 s is a loss of lock.
  const CarrierArcs::Arc after = arcs.update(gps_sat(7), 20.5, true);
  EXPECT_TRUE(after.new_arc);
  EXPECT_NE(after.ambiguity_cycles, amb0);
  EXPECT_EQ(after.lock_time_s, 0.0);
  // A configured limit applies instead.
  CarrierArcs strict(9, 1.5);
  strict.update(gps_sat(7), 0.0, true);
  EXPECT_FALSE(strict.update(gps_sat(7), 1.0, true).new_arc);
  EXPECT_TRUE(strict.update(gps_sat(7), 3.0, true).new_arc);
}

TEST(CarrierArcs, SameSeedSameArcsIndependentOfOtherPrns) {
  CarrierArcs a(77), b(77), c(78);
  int same_ac = 0;
  for (int k = 0; k < 40; ++k) {
    const bool tracked = (k % 7) != 3;  // a loss of lock every 7 epochs
    const double t = k;
    const CarrierArcs::Arc x = a.update(gps_sat(21), t, tracked);
    b.update(gps_sat(5), t, !tracked);  // another PRN in between must not matter
    const CarrierArcs::Arc y = b.update(gps_sat(21), t, tracked);
    ASSERT_EQ(x.ambiguity_cycles, y.ambiguity_cycles);
    ASSERT_EQ(x.new_arc, y.new_arc);
    ASSERT_EQ(x.lock_time_s, y.lock_time_s);
    const CarrierArcs::Arc z = c.update(gps_sat(21), t, tracked);
    if (tracked) same_ac += x.ambiguity_cycles == z.ambiguity_cycles;
  }
  EXPECT_EQ(same_ac, 0);
}

// Ambiguities of many first arcs are uniform on [-1e6, 1e6]: mean 0 and variance
// ((2e6 + 1)^2 - 1) / 12 = 3.3333e11, within five standard errors.
TEST(CarrierArcs, AmbiguityIsUniformOverPlusMinusOneMillion) {
  CarrierArcs arcs(2024);
  const std::vector<SatId> sats = test::first_satellites(99);
  const int n_sats = static_cast<int>(sats.size());
  const int arcs_per_sat = 202;
  const int n = arcs_per_sat * n_sats;  // 19998 arcs, each drawing from its own stream
  double sum = 0, sum2 = 0, lo = 0, hi = 0;
  for (int i = 0; i < n; ++i) {
    const SatId sat = sats[static_cast<std::size_t>(i % n_sats)];
    const double t = static_cast<double>(i / n_sats);
    const double x = arcs.update(sat, t, true).ambiguity_cycles;
    arcs.update(sat, t + 0.5, false);  // lost: the next epoch of this satellite starts a new arc
    ASSERT_EQ(x, std::floor(x));
    sum += x;
    sum2 += x * x;
    lo = std::min(lo, x);
    hi = std::max(hi, x);
  }
  const double var = (2e6 + 1.0) * (2e6 + 1.0) / 12.0;
  // Uniform: sd of the mean sqrt(var / n); of the second moment sqrt((9/5 - 1) var^2 / n).
  EXPECT_LT(std::abs(sum / n), 5.0 * std::sqrt(var / n));
  EXPECT_LT(std::abs(sum2 / n / var - 1.0), 5.0 * std::sqrt(0.8 / n));
  EXPECT_GE(lo, -1e6);
  EXPECT_LE(hi, 1e6);
  EXPECT_LT(lo, -0.99e6);
  EXPECT_GT(hi, 0.99e6);
}

// The Hatch filter on a satellite whose range grows 800 m/s, with a carrier offset by its
// ambiguity: 4000 seeded arcs of 300 epochs at 1 s, T = 100 s, code noise 1 m (white) or code
// multipath 1 m (Gauss-Markov, 60 s). The smoothed code's error variance against what the
// filter reports, and both against closed forms: a plain mean while k <= T/dt (1/k), the
// steady state of the fixed weight w = dt/T, w / (2 - w) = 1/199 for white noise. The variance
// estimate of n = 4000 independent errors has a relative sd of sqrt(2/n) = 2.2 %: 5 sigma.
struct SmoothedErrors {
  std::vector<double> at_50, at_300;
  double noise_fraction_50 = 0, noise_fraction_300 = 0, multipath_fraction_300 = 0;
};
SmoothedErrors smooth_arcs(bool multipath, double multipath_tau_s) {
  SmoothedErrors out;
  for (std::uint64_t arc = 0; arc < 4000; ++arc) {
    RandomStream rng(7, arc);
    GaussMarkov mp(1.0, multipath_tau_s, rng);
    CarrierSmoother f;
    for (int k = 1; k <= 300; ++k) {
      const double t = 1000.0 + k;
      const double range_m = 2.2e7 + 800.0 * t;
      if (k > 1) mp.step(1.0, rng);
      const double error_m = multipath ? mp.value() : rng.normal();
      const double s = f.update(t, range_m + error_m, range_m + 123456.0 * 0.19, k == 1, 100.0, multipath_tau_s);
      if (k == 50) {
        out.at_50.push_back(s - range_m);
        out.noise_fraction_50 = f.noise_fraction();
      }
      if (k == 300) {
        out.at_300.push_back(s - range_m);
        out.noise_fraction_300 = f.noise_fraction();
        out.multipath_fraction_300 = f.multipath_fraction();
      }
    }
  }
  return out;
}
double mean_square(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x * x;
  return s / static_cast<double>(v.size());
}

TEST(CarrierSmoother, AveragesWhiteCodeNoiseAsTheClosedFormsSay) {
  const SmoothedErrors e = smooth_arcs(false, 60.0);
  const double tol = 5.0 * std::sqrt(2.0 / 4000.0);
  EXPECT_NEAR(e.noise_fraction_50, 1.0 / 50.0, 1e-12);
  EXPECT_NEAR(mean_square(e.at_50) / (1.0 / 50.0), 1.0, tol);
  // 200 epochs after the window filled, within 2 % of the steady state (the departure
  // shrinks by (1 - w)^2 = 0.98 per epoch).
  EXPECT_NEAR(e.noise_fraction_300 / (1.0 / 199.0), 1.0, 0.02);
  EXPECT_NEAR(mean_square(e.at_300) / e.noise_fraction_300, 1.0, tol);
}

TEST(CarrierSmoother, LeavesWhatItReportsOfGaussMarkovMultipath) {
  const SmoothedErrors e = smooth_arcs(true, 60.0);
  // A minute's multipath is averaged down, but far less than white noise.
  EXPECT_GT(e.multipath_fraction_300, 0.2);
  EXPECT_LT(e.multipath_fraction_300, 0.6);
  EXPECT_NEAR(mean_square(e.at_300) / e.multipath_fraction_300, 1.0, 5.0 * std::sqrt(2.0 / 4000.0));
  // An error that never changes is not smoothed at all.
  EXPECT_NEAR(smooth_arcs(true, 1e12).multipath_fraction_300, 1.0, 1e-6);
}

TEST(CarrierSmoother, RestartsAtANewArcAGapOrASlipTheArcsMissed) {
  CarrierSmoother f;
  const auto step = [&](double t, double code, double carrier, bool new_arc) {
    return f.update(t, code, carrier, new_arc, 100.0, 60.0);
  };
  step(0.0, 100.0, 0.0, true);
  EXPECT_NEAR(step(1.0, 103.0, 1.0, false), 102.0, 1e-12);  // (103 + (100 + 1)) / 2
  EXPECT_LT(f.noise_fraction(), 1.0);
  EXPECT_EQ(step(2.0, 500.0, 2.0, true), 500.0);  // new arc
  EXPECT_EQ(f.noise_fraction(), 1.0);
  step(3.0, 501.0, 3.0, false);
  EXPECT_EQ(step(200.0, 700.0, 200.0, false), 700.0);  // 197 s without an epoch: longer than T
  step(201.0, 701.0, 201.0, false);
  // The carrier jumps 40 m that the code does not: a slip nobody flagged.
  EXPECT_EQ(step(202.0, 702.0, 242.0, false), 702.0);
}

}  // namespace
}  // namespace navemu
