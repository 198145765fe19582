// Multipath: Fresnel coefficients against hand values and an independent route (complex Snell
// law, Abeles' relation), the antenna pattern against the C/N0 model's table, the EML
// discriminator's tracking error against the closed-form multipath error envelope, the
// composite power and carrier phase, and the paper's first-return rule.

#include "models/multipath.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdint>
#include <optional>
#include <vector>

#include "models/tracking.hpp"

namespace navemu {
namespace {

using cd = std::complex<double>;
constexpr double kPiExact = 3.14159265358979323846;
constexpr double kDeg = kPiExact / 180.0;
constexpr double kChipM = 293.052;

void expect_complex_near(cd actual, cd expected, double tol, const char* what) {
  EXPECT_NEAR(actual.real(), expected.real(), tol) << what;
  EXPECT_NEAR(actual.imag(), expected.imag(), tol) << what;
}

// ---- Fresnel ----------------------------------------------------------------------------------

TEST(Fresnel, PerfectConductorReflectsAllIntoCrossPolar) {
  const Fresnel f = fresnel_perfect_conductor();
  expect_complex_near(f.perp, {-1.0, 0.0}, 0.0, "perp");
  expect_complex_near(f.par, {1.0, 0.0}, 0.0, "par");
  expect_complex_near(f.co, {0.0, 0.0}, 0.0, "co");
  EXPECT_EQ(std::abs(f.cross), 1.0);
  // ITU-R P.2040 metal (eps_r 1, sigma 1e7 S/m) through the dielectric formula tends to it
  // (Gamma_par departs from +1 by about 2 / (|sqrt eps| sin psi), |sqrt eps| = 1.07e4: near
  // grazing a good conductor still has a pseudo-Brewster dip, hence no angles below 30 deg).
  for (double psi_deg : {30.0, 60.0, 90.0}) {
    const Fresnel m = fresnel(1.0, 1e7, psi_deg * kDeg);
    expect_complex_near(m.perp, {-1.0, 0.0}, 1e-3, "metal perp");
    expect_complex_near(m.par, {1.0, 0.0}, 1e-3, "metal par");
    EXPECT_LT(std::abs(m.co), 1e-3);
    EXPECT_NEAR(std::abs(m.cross), 1.0, 1e-3);
  }
}

TEST(Fresnel, LosslessNormalIncidenceIsOneThirdForEpsFour) {
  // n = sqrt(4) = 2: |Gamma| = (n - 1) / (n + 1) = 1/3 for both; perp = -1/3, par = +1/3 in
  // this convention, so a circular wave turns entirely into the other hand.
  const Fresnel f = fresnel(4.0, 0.0, 90.0 * kDeg);
  expect_complex_near(f.perp, {-1.0 / 3.0, 0.0}, 1e-15, "perp");
  expect_complex_near(f.par, {1.0 / 3.0, 0.0}, 1e-15, "par");
  EXPECT_NEAR(std::abs(f.co), 0.0, 1e-15);
  EXPECT_NEAR(std::abs(f.cross), 1.0 / 3.0, 1e-15);
}

TEST(Fresnel, GrazingIncidenceIsMinusOneForBoth) {
  const Fresnel f = fresnel(5.24, 0.0659, 0.0);
  expect_complex_near(f.perp, {-1.0, 0.0}, 1e-15, "perp");
  expect_complex_near(f.par, {-1.0, 0.0}, 1e-15, "par");
  expect_complex_near(f.co, {-1.0, 0.0}, 1e-15, "co");
  EXPECT_NEAR(std::abs(f.cross), 0.0, 1e-15);
}

TEST(Fresnel, BrewsterAngleOfEpsFour) {
  // tan(90 deg - psi_B) = sqrt(eps_r) = 2: psi_B = 26.565 deg. There Gamma_par = 0 and
  // Gamma_perp = (1 - eps_r) / (1 + eps_r) = -0.6 (sin psi_B = 1/sqrt 5, cos^2 = 4/5:
  // (0.4472 - sqrt 3.2) / (0.4472 + sqrt 3.2) = -1.3416 / 2.2361).
  const double psi_b = 90.0 * kDeg - std::atan(2.0);
  const Fresnel f = fresnel(4.0, 0.0, psi_b);
  EXPECT_NEAR(std::abs(f.par), 0.0, 1e-15);
  expect_complex_near(f.perp, {-0.6, 0.0}, 1e-15, "perp");
  // Gamma_par changes sign there: RHCP stays mostly co-polar below, turns cross-polar above.
  const Fresnel below = fresnel(4.0, 0.0, psi_b - 5.0 * kDeg);
  const Fresnel above = fresnel(4.0, 0.0, psi_b + 5.0 * kDeg);
  EXPECT_LT(below.par.real(), 0.0);
  EXPECT_GT(above.par.real(), 0.0);
  EXPECT_GT(std::abs(below.co), std::abs(below.cross));
  EXPECT_LT(std::abs(above.co), std::abs(above.cross));
}

// The textbook route with the incidence angle theta = 90 deg - psi and the complex Snell law
// (the Fresnel equations of Hecht, Optics, and of Born & Wolf sect. 1.5.2): n = sqrt(eps),
// cos theta_t = sqrt(1 - sin^2 theta / eps),
//   r_s = (cos theta - n cos theta_t) / (cos theta + n cos theta_t),
//   r_p = (n cos theta - cos theta_t) / (n cos theta + cos theta_t).
struct SnellRoute {
  cd rs, rp;
};
SnellRoute snell_route(cd eps, double grazing_rad) {
  const double theta = kPiExact / 2.0 - grazing_rad;
  const cd n = std::sqrt(eps);
  const cd sin_t = std::sin(theta) / n;
  const cd cos_t = std::sqrt(1.0 - sin_t * sin_t);
  const double ci = std::cos(theta);
  return {(ci - n * cos_t) / (ci + n * cos_t), (n * ci - cos_t) / (n * ci + cos_t)};
}

TEST(Fresnel, ItuConcreteAtL1MatchesTheSnellRoute) {
  // ITU-R P.2040 concrete at 1.57542 GHz: eps_r = 5.24, sigma = 0.0462 f^0.7822 = 0.06592 S/m,
  // eps = 5.24 - j 60 lambda sigma = 5.24 - j 0.7527.
  const double sigma = 0.0462 * std::pow(1.57542, 0.7822);
  const cd eps{5.24, -60.0 * kL1WavelengthM * sigma};
  EXPECT_NEAR(eps.imag(), -0.7527, 1e-4);
  for (double psi_deg : {10.0, 45.0}) {
    const Fresnel f = fresnel(5.24, sigma, psi_deg * kDeg);
    const SnellRoute r = snell_route(eps, psi_deg * kDeg);
    expect_complex_near(f.perp, r.rs, 1e-12, "perp vs r_s");
    expect_complex_near(f.par, r.rp, 1e-12, "par vs r_p");
    expect_complex_near(f.co, 0.5 * (r.rp + r.rs), 1e-12, "co");
    expect_complex_near(f.cross, 0.5 * (r.rp - r.rs), 1e-12, "cross");
  }
  // The same values written out (Snell route evaluated separately in double precision):
  //   10 deg: r_s = -0.8465107 + 0.0123873 j (|.| 0.8466), r_p = -0.3877340 - 0.0235572 j
  //   45 deg: r_s = -0.5125656 + 0.0290538 j (|.| 0.5134), r_p =  0.2618794 - 0.0297840 j
  // 10 deg is below concrete's Brewster angle (~23.6 deg): mostly co-polar (|co| 0.617,
  // |cross| 0.230); 45 deg above it: mostly cross-polar (|co| 0.125, |cross| 0.388).
  const Fresnel f10 = fresnel(5.24, sigma, 10.0 * kDeg);
  const Fresnel f45 = fresnel(5.24, sigma, 45.0 * kDeg);
  expect_complex_near(f10.perp, {-0.8465107, 0.0123873}, 1e-7, "10 deg perp");
  expect_complex_near(f10.par, {-0.3877340, -0.0235572}, 1e-7, "10 deg par");
  expect_complex_near(f45.perp, {-0.5125656, 0.0290538}, 1e-7, "45 deg perp");
  expect_complex_near(f45.par, {0.2618794, -0.0297840}, 1e-7, "45 deg par");
  EXPECT_NEAR(std::abs(f10.co), 0.6171, 1e-4);
  EXPECT_NEAR(std::abs(f10.cross), 0.2301, 1e-4);
  EXPECT_NEAR(std::abs(f45.co), 0.1253, 1e-4);
  EXPECT_NEAR(std::abs(f45.cross), 0.3883, 1e-4);
  // Loss: the lossy coefficients are complex, with the phase of e^{+j omega t}.
  EXPECT_GT(f10.perp.imag(), 0.0);
  EXPECT_LT(f45.par.imag(), 0.0);
}

TEST(Fresnel, AbelesRelationHoldsForLossyGrounds) {
  // For any interface, r_p = r_s (r_s - cos 2 theta) / (1 - r_s cos 2 theta), theta the
  // incidence angle (Abeles 1950; Azzam & Bashara, Ellipsometry and Polarized Light): par from
  // perp without the formula for par.
  const double lambda = kL1WavelengthM;
  struct Material {
    double eps_r, sigma;
  };
  // ITU-R P.2040 wet ground, medium dry ground, glass at L1.
  for (const Material m : {Material{25.01, 0.2708}, Material{14.33, 0.07342}, Material{6.31, 0.006618}}) {
    for (double psi_deg : {2.0, 10.0, 30.0, 60.0, 85.0}) {
      const Fresnel f = fresnel(m.eps_r, m.sigma, psi_deg * kDeg, lambda);
      const double c2 = std::cos(2.0 * (90.0 - psi_deg) * kDeg);
      const cd par = f.perp * (f.perp - c2) / (1.0 - f.perp * c2);
      expect_complex_near(f.par, par, 1e-12, "Abeles");
    }
  }
}

// ---- Antenna ------------------------------------------------------------------------------------

TEST(MultipathAntenna, PatchPatternIsTheCn0TableAboveTheHorizon) {
  const AntennaPattern a = patch_antenna_pattern();
  Cn0Model m;
  m.zenith_dbhz = 0.0;  // cn0_dbhz then returns the table's gain
  for (double el = 0.0; el <= 90.0; el += 2.5)
    EXPECT_NEAR(antenna_gain_db(a, el * kDeg, false), cn0_dbhz(m, el * kDeg), 1e-12) << el;
  // Below: straight from the horizon value (-13 dB) to -20 dB at the nadir.
  const double horizon = cn0_dbhz(m, 0.0);
  EXPECT_NEAR(antenna_gain_db(a, -90.0 * kDeg, false), -20.0, 1e-12);
  EXPECT_NEAR(antenna_gain_db(a, -45.0 * kDeg, false), 0.5 * (horizon - 20.0), 1e-12);
  EXPECT_NEAR(antenna_gain_db(a, -120.0 * kDeg, false), -20.0, 1e-12);  // held
  EXPECT_NEAR(antenna_gain_db(a, 90.0 * kDeg, false), 0.0, 1e-12);
  // LHCP: the rejection below RHCP from the same direction.
  EXPECT_NEAR(antenna_gain_db(a, 30.0 * kDeg, true),
              antenna_gain_db(a, 30.0 * kDeg, false) - a.lhcp_rejection_db, 1e-12);
}

// ---- EML tracking error ----------------------------------------------------------------------------

// Closed-form coherent-DLL error (chips) for the direct path (1, delay 0) plus one reflection
// of relative amplitude a < 1 in phase (s = +1) or in anti-phase (s = -1) at delay tau chips,
// triangular correlation, spacing d <= 1. Near the direct path the direct path contributes
// 2 eps to D and the reflection s a f(eps - tau), with f(x) = 2x for |x| <= d/2, d sign(x)
// for d/2 <= |x| <= 1 - d/2, sign(x) (1 + d/2 - |x|) up to 1 + d/2, 0 beyond. Solving
// 2 eps = s a f(tau - eps) piece by piece:
//   in phase:   a tau / (1 + a)                 tau <= (1 + a) d/2
//               a d / 2                         tau <= 1 - d/2 + a d/2
//               a (1 + d/2 - tau) / (2 - a)     tau <= 1 + d/2
//   anti-phase: -a tau / (1 - a)                tau <= (1 - a) d/2
//               -a d / 2                        tau <= 1 - d/2 - a d/2
//               -a (1 + d/2 - tau) / (2 + a)    tau <= 1 + d/2
//   and 0 beyond 1 + d/2: the classic multipath error envelope (van Nee 1993; Braasch,
//   Springer Handbook of GNSS ch. 15: maximum a d/2 chips, zero beyond 1 + d/2 chips).
double envelope_chips(double a, int s, double tau, double d) {
  if (tau > 1.0 + 0.5 * d) return 0.0;
  if (s > 0) {
    if (tau <= (1.0 + a) * 0.5 * d) return a * tau / (1.0 + a);
    if (tau <= 1.0 - 0.5 * d + 0.5 * a * d) return 0.5 * a * d;
    return a * (1.0 + 0.5 * d - tau) / (2.0 - a);
  }
  if (tau <= (1.0 - a) * 0.5 * d) return -a * tau / (1.0 - a);
  if (tau <= 1.0 - 0.5 * d - 0.5 * a * d) return -0.5 * a * d;
  return -a * (1.0 + 0.5 * d - tau) / (2.0 + a);
}

std::vector<PathSignal> direct_and_reflection(double a, int s, double tau_chips) {
  return {{0.0, {1.0, 0.0}}, {tau_chips * kChipM, {s * a, 0.0}}};
}

TEST(EmlTracking, EnvelopeMatchesClosedFormForWideAndNarrowCorrelators) {
  for (double d : {1.0, 0.1}) {
    for (double a : {0.5, 0.9}) {
      for (int s : {+1, -1}) {
        for (int i = 0; i <= 180; ++i) {
          const double tau = 0.01 * i;
          const auto eps = eml_tracking_error_m(direct_and_reflection(a, s, tau), d);
          ASSERT_TRUE(eps.has_value()) << "d " << d << " a " << a << " s " << s << " tau " << tau;
          EXPECT_NEAR(*eps, envelope_chips(a, s, tau, d) * kChipM, 1e-6)
              << "d " << d << " a " << a << " s " << s << " tau " << tau;
        }
      }
    }
  }
}

TEST(EmlTracking, EnvelopeSpotValuesByHand) {
  // d = 1, a = 0.5: in phase, the maximum a d / 2 = 0.25 chip = 73.263 m at tau = 0.75;
  // anti-phase at tau = 0.1 (< (1 - a) d/2 = 0.25): -a tau / (1 - a) = -0.1 chip = -29.3052 m.
  EXPECT_NEAR(*eml_tracking_error_m(direct_and_reflection(0.5, +1, 0.75), 1.0), 73.263, 1e-6);
  EXPECT_NEAR(*eml_tracking_error_m(direct_and_reflection(0.5, -1, 0.1), 1.0), -29.3052, 1e-6);
  // Small delay, in phase: a tau / (1 + a) = 0.5 * 0.05 / 1.5 chip = 4.8842 m.
  EXPECT_NEAR(*eml_tracking_error_m(direct_and_reflection(0.5, +1, 0.05), 1.0), 4.8842, 1e-4);
  // d = 0.1: plateau a d / 2 = 0.025 chip = 7.3263 m for 0.075 <= tau <= 0.975 in phase,
  // -7.3263 m for 0.025 <= tau <= 0.925 in anti-phase.
  EXPECT_NEAR(*eml_tracking_error_m(direct_and_reflection(0.5, +1, 0.5), 0.1), 7.3263, 1e-6);
  EXPECT_NEAR(*eml_tracking_error_m(direct_and_reflection(0.5, -1, 0.5), 0.1), -7.3263, 1e-6);
  // Tail, d = 0.1, tau = 1.0 chip, in phase: a (1.05 - 1) / 1.5 = 0.016667 chip = 4.8842 m.
  EXPECT_NEAR(*eml_tracking_error_m(direct_and_reflection(0.5, +1, 1.0), 0.1), 4.8842, 1e-4);
}

TEST(EmlTracking, ReflectionBeyondOneChipPlusHalfSpacingGivesNoError) {
  for (double d : {1.0, 0.1}) {
    for (double phase : {0.0, 1.0, kPiExact}) {
      const double tau = 1.0 + 0.5 * d + 0.001;
      const std::vector<PathSignal> p{{0.0, {1.0, 0.0}}, {tau * kChipM, std::polar(0.9, phase)}};
      const auto eps = eml_tracking_error_m(p, d);
      ASSERT_TRUE(eps.has_value());
      EXPECT_NEAR(*eps, 0.0, 1e-9) << d << " " << phase;
    }
  }
}

TEST(EmlTracking, NlosReflectionAloneIsTrackedAtItsDelay) {
  for (double d : {1.0, 0.1}) {
    for (double delay_m : {12.856, 123.4, 700.0}) {
      const std::vector<PathSignal> p{{delay_m, std::polar(0.3, 2.1)}};
      const auto eps = eml_tracking_error_m(p, d);
      ASSERT_TRUE(eps.has_value());
      EXPECT_NEAR(*eps, delay_m, 1e-9) << d << " " << delay_m;
    }
  }
}

TEST(EmlTracking, QuadratureReflectionFollowsTheCompositeCarrierPhase) {
  // a = 0.5 at +90 deg, tau = 0.2 chip, d = 1. With the carrier on the composite phase,
  // Re(conj(P) Q) = R(e) f(e) + a^2 R(e - tau) f(e - tau) (cross terms are imaginary); near the
  // direct path f(e) = 2e, f(e - tau) = -2(tau - e):
  //   (1 - e) e = a^2 (1 - tau + e)(tau - e)
  //   (a^2 - 1) e^2 + (1 - a^2 (2 tau - 1)) e - a^2 tau (1 - tau) = 0
  //   -0.75 e^2 + 1.15 e - 0.04 = 0  ->  e = (1.15 - sqrt(1.15^2 - 0.12)) / 1.5 = 0.0356096 chip
  // (a carrier locked to the direct path alone would give 0; in phase it is 0.0666667).
  const std::vector<PathSignal> p{{0.0, {1.0, 0.0}}, {0.2 * kChipM, {0.0, 0.5}}};
  const double e = (1.15 - std::sqrt(1.15 * 1.15 - 0.12)) / 1.5;
  EXPECT_NEAR(*eml_tracking_error_m(p, 1.0), e * kChipM, 1e-6);
  // Phase -90 deg gives the same (conj symmetry).
  const std::vector<PathSignal> q{{0.0, {1.0, 0.0}}, {0.2 * kChipM, {0.0, -0.5}}};
  EXPECT_NEAR(*eml_tracking_error_m(q, 1.0), e * kChipM, 1e-6);
}

TEST(EmlTracking, ResolvedPathsFollowTheEarliestSignificantOne) {
  // A reflection 3 chips late does not disturb a direct path it cannot reach...
  const std::vector<PathSignal> strong_direct{{0.0, {1.0, 0.0}}, {3.0 * kChipM, {0.0, -0.9}}};
  EXPECT_NEAR(*eml_tracking_error_m(strong_direct, 1.0), 0.0, 1e-9);
  // ... nor one that is weaker but within 6 dB of it ...
  const std::vector<PathSignal> fair_direct{{0.0, {0.6, 0.0}}, {3.0 * kChipM, {1.0, 0.0}}};
  EXPECT_NEAR(*eml_tracking_error_m(fair_direct, 1.0), 0.0, 1e-9);
  // ... but a direct path more than 6 dB below the reflection is not where the receiver locks.
  const std::vector<PathSignal> weak_direct{{0.0, {0.3, 0.0}}, {3.0 * kChipM, {1.0, 0.0}}};
  EXPECT_NEAR(*eml_tracking_error_m(weak_direct, 1.0), 3.0 * kChipM, 1e-9);
}

TEST(EmlTracking, NeutralPlateauYieldsItsMiddle) {
  // Equal in-phase paths one chip apart, d = 0.1: for 0.05 < eps < 0.95 their early-minus-late
  // contributions cancel exactly (+d and -d) and the prompt is flat (1); the loop has no
  // preference there and the model reports the middle, 0.5 chip.
  const std::vector<PathSignal> p{{0.0, {1.0, 0.0}}, {kChipM, {1.0, 0.0}}};
  EXPECT_NEAR(*eml_tracking_error_m(p, 0.1), 0.5 * kChipM, 1e-9);
}

TEST(EmlTracking, NoSignalOrNoSpacingGivesNothing) {
  EXPECT_FALSE(eml_tracking_error_m({}, 1.0).has_value());
  EXPECT_FALSE(eml_tracking_error_m({{0.0, {0.0, 0.0}}, {30.0, {0.0, 0.0}}}, 1.0).has_value());
  EXPECT_FALSE(eml_tracking_error_m({{0.0, {1.0, 0.0}}}, 0.0).has_value());
  // Two equal paths in anti-phase at the same delay cancel everywhere: nothing to track.
  EXPECT_FALSE(eml_tracking_error_m({{0.0, {1.0, 0.0}}, {0.0, {-1.0, 0.0}}}, 1.0).has_value());
}

// The header's D(eps), written out directly: carrier on phi_c = arg P(eps).
double discriminator(const std::vector<PathSignal>& paths, double eps_chips, double d) {
  auto r = [](double x) { return std::max(0.0, 1.0 - std::abs(x)); };
  cd p{0.0, 0.0};
  for (const PathSignal& s : paths) p += s.amplitude * r(eps_chips - s.delay_m / kChipM);
  const double phi_c = std::arg(p);
  double sum = 0.0;
  for (const PathSignal& s : paths) {
    const double x = eps_chips - s.delay_m / kChipM;
    sum += (s.amplitude * std::polar(1.0, -phi_c)).real() * (r(x - 0.5 * d) - r(x + 0.5 * d));
  }
  return sum;
}

TEST(EmlTracking, RandomPathSetsSettleOnAStableZero) {
  // Up to 64 paths (the scene's maximum) with random delays over 3 chips and random complex
  // amplitudes: the returned point is where D crosses zero from negative to positive, with
  // signal in the prompt, within the pull-in range of some significant path.
  std::uint64_t state = 0x9E3779B97F4A7C15ull;
  auto uniform = [&state]() {  // splitmix64, 53-bit mantissa
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return static_cast<double>(z >> 11) * 0x1.0p-53;
  };
  int checked = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const double d = trial % 2 == 0 ? 1.0 : 0.1;
    const auto n = static_cast<std::size_t>(1 + trial % 64);
    std::vector<PathSignal> paths;
    double a_max = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      const double delay_m = (i == 0 && trial % 3 != 0) ? 0.0 : 3.0 * kChipM * uniform();
      const cd a = std::polar(uniform(), 2.0 * kPiExact * uniform());
      a_max = std::max(a_max, std::abs(a));
      paths.push_back({delay_m, a});
    }
    const auto eps_m = eml_tracking_error_m(paths, d);
    ASSERT_TRUE(eps_m.has_value()) << trial;
    const double e = *eps_m / kChipM;
    const double h = 1e-7;
    EXPECT_LE(discriminator(paths, e - h, d), 1e-9) << trial;
    EXPECT_GE(discriminator(paths, e + h, d), -1e-9) << trial;
    const double p = std::pow(10.0, composite_power_db(paths, *eps_m) / 20.0);
    EXPECT_GT(p, 1e-9) << trial;
    bool near_significant = false;
    for (const PathSignal& s : paths)
      near_significant |= std::abs(s.amplitude) >= kEmlSignificantPathRatio * a_max &&
                          std::abs(e - s.delay_m / kChipM) <= 1.0 + 0.5 * d;
    EXPECT_TRUE(near_significant) << trial;
    ++checked;
  }
  EXPECT_EQ(checked, 300);
}

// A brute-force reference for the tracking point: D on a fine grid, its negative-to-positive
// sign changes (interpolated) with signal in the prompt, chosen by the header's rule.
std::optional<double> brute_force_tracking_chips(const std::vector<PathSignal>& paths, double d) {
  auto r = [](double x) { return std::max(0.0, 1.0 - std::abs(x)); };
  double lo = 1e300, hi = -1e300, a_max = 0.0;
  for (const PathSignal& s : paths) {
    lo = std::min(lo, s.delay_m / kChipM);
    hi = std::max(hi, s.delay_m / kChipM);
    a_max = std::max(a_max, std::abs(s.amplitude));
  }
  const double pull_in = 1.0 + 0.5 * d;
  const double step = 1e-4;
  std::vector<std::pair<double, double>> zeros;  // (eps, |P|)
  double x0 = lo - pull_in, d0 = discriminator(paths, x0, d);
  for (double x1 = x0 + step; x1 <= hi + pull_in; x1 += step) {
    const double d1 = discriminator(paths, x1, d);
    if (d0 < 0.0 && d1 > 0.0) {
      const double z = x0 + step * d0 / (d0 - d1);
      cd p{0.0, 0.0};
      for (const PathSignal& s : paths) p += s.amplitude * r(z - s.delay_m / kChipM);
      if (std::abs(p) > 1e-3) zeros.emplace_back(z, std::abs(p));
    }
    x0 = x1;
    d0 = d1;
  }
  if (zeros.empty()) return std::nullopt;
  std::vector<double> significant;
  for (const PathSignal& s : paths)
    if (std::abs(s.amplitude) >= kEmlSignificantPathRatio * a_max) significant.push_back(s.delay_m / kChipM);
  std::sort(significant.begin(), significant.end());
  for (double tau : significant) {
    std::optional<double> best;
    for (const auto& z : zeros)
      if (std::abs(z.first - tau) <= pull_in && (!best || std::abs(z.first - tau) < std::abs(*best - tau)))
        best = z.first;
    if (best) return best;
  }
  return std::max_element(zeros.begin(), zeros.end(),
                          [](const auto& a, const auto& b) { return a.second < b.second; })->first;
}

TEST(EmlTracking, MatchesABruteForceScanOfTheDiscriminator) {
  // Cases that catch a zero between two corners hidden by a second one (both ends of the
  // segment negative) and a sign change of D where the prompt vanishes (the carrier phase
  // flips by pi there: D jumps, but there is no signal to track).
  const std::vector<std::vector<PathSignal>> cases{
      {{0.0, {-0.0789, -0.4770}}, {263.48, {0.5534, -0.0546}}},
      {{0.0, {0.688, 0.0}}, {156.29, {0.634, 0.0}}, {19.14, {-0.828, 0.0}}},
      {{0.0, {0.432, 0.0}}, {352.60, {0.385, 0.0}}, {57.94, {-0.409, 0.0}}},
  };
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const auto expected = brute_force_tracking_chips(cases[i], 1.0);
    const auto eps = eml_tracking_error_m(cases[i], 1.0);
    ASSERT_TRUE(expected.has_value()) << i;
    ASSERT_TRUE(eps.has_value()) << i;
    EXPECT_NEAR(*eps / kChipM, *expected, 1e-3) << i;
  }
  // Random sets of 2-6 paths over 1.5 chips, both spacings.
  std::uint64_t state = 12345;
  auto uniform = [&state]() {  // splitmix64
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return static_cast<double>(z >> 11) * 0x1.0p-53;
  };
  int compared = 0;
  for (int trial = 0; trial < 150; ++trial) {
    const double d = trial % 2 == 0 ? 1.0 : 0.1;
    std::vector<PathSignal> paths{{0.0, std::polar(0.3 + 0.7 * uniform(), 2.0 * kPiExact * uniform())}};
    const int n = 1 + trial % 5;
    for (int i = 0; i < n; ++i)
      paths.push_back({1.5 * kChipM * uniform(), std::polar(0.3 + 0.7 * uniform(), 2.0 * kPiExact * uniform())});
    const auto expected = brute_force_tracking_chips(paths, d);
    const auto eps = eml_tracking_error_m(paths, d);
    ASSERT_EQ(eps.has_value(), expected.has_value()) << trial;
    if (!eps) continue;
    EXPECT_NEAR(*eps / kChipM, *expected, 1e-3) << trial;
    ++compared;
  }
  EXPECT_GT(compared, 140);
}

// ---- Composite power and phase ------------------------------------------------------------------

TEST(MultipathComposite, PowerOfEqualPathsAtZeroDelay) {
  const std::vector<PathSignal> anti{{0.0, {1.0, 0.0}}, {0.0, {-1.0, 0.0}}};
  EXPECT_LT(composite_power_db(anti, 0.0), -100.0);
  EXPECT_EQ(composite_power_db(anti, 0.0), kCompositePowerFloorDb);
  const std::vector<PathSignal> in{{0.0, {1.0, 0.0}}, {0.0, {1.0, 0.0}}};
  ASSERT_NEAR(*eml_tracking_error_m(in, 1.0), 0.0, 1e-9);
  EXPECT_NEAR(composite_power_db(in, 0.0), 20.0 * std::log10(2.0), 1e-12);  // +6.0206 dB
  EXPECT_NEAR(composite_power_db(in, 0.0), 6.0206, 1e-4);
  // Off the peak by a quarter chip: R(0.25) = 0.75 of one path.
  const std::vector<PathSignal> one{{0.0, {1.0, 0.0}}};
  EXPECT_NEAR(composite_power_db(one, 0.25 * kChipM), 20.0 * std::log10(0.75), 1e-12);
  EXPECT_EQ(composite_power_db({}, 0.0), kCompositePowerFloorDb);
}

TEST(MultipathComposite, CarrierPhaseErrorOfOneShortReflection) {
  // Excess Delta = lambda / 8 with a real coefficient 0.5: amplitude 0.5 e^{-j pi/4}. The
  // classic carrier multipath error (Georgiadou & Kleusberg 1988) is
  //   atan(a sin theta / (1 + a cos theta)) lambda / 2 pi,  theta = 2 pi Delta / lambda,
  // positive (a longer path lengthens the measured range), with a the reflection's amplitude
  // in the prompt correlator: 0.5 R(Delta / chip) = 0.5 (1 - 8.1e-5).
  const double lambda = kL1WavelengthM;
  const double delta = lambda / 8.0;
  const double theta = 2.0 * kPiExact * delta / lambda;
  const std::vector<PathSignal> p{{0.0, {1.0, 0.0}}, {delta, std::polar(0.5, -theta)}};
  const double a = 0.5 * (1.0 - delta / kChipM);
  const double expected = std::atan(a * std::sin(theta) / (1.0 + a * std::cos(theta))) * lambda / (2.0 * kPiExact);
  EXPECT_GT(expected, 0.0);
  EXPECT_NEAR(composite_phase_error_m(p, 0.0), expected, 1e-12);
}

TEST(MultipathComposite, NlosCarrierCarriesTheWholeExcessPath) {
  // A lone reflection off metal (cross-polar, real positive) 12.856 m long: the carrier phase
  // is late by the whole excess path, as the code is.
  const double lambda = kL1WavelengthM;
  const double delta = 12.856;
  const double g = std::pow(10.0, -15.0 / 20.0);
  const std::vector<PathSignal> pec{{delta, g * std::polar(1.0, -2.0 * kPiExact * delta / lambda)}};
  const double eps = *eml_tracking_error_m(pec, 1.0);
  EXPECT_NEAR(composite_phase_error_m(pec, eps), delta, 1e-9);
  // A real negative coefficient adds half a wavelength (either way modulo lambda).
  const std::vector<PathSignal> neg{{delta, -0.6 * std::polar(1.0, -2.0 * kPiExact * delta / lambda)}};
  EXPECT_NEAR(std::abs(composite_phase_error_m(neg, eps) - delta), lambda / 2.0, 1e-9);
  EXPECT_EQ(composite_phase_error_m({}, 0.0), 0.0);
}

// ---- The paper's rule -----------------------------------------------------------------------------

TEST(MultipathPaperRule, FirstReturnWithinTheCutoffElseTheStrongest) {
  // One return: followed.
  EXPECT_EQ(*paper_rule_delay_m({{12.856, {0.2, 0.1}}}), 12.856);
  // Second return 30 m behind (< 45 m): the first, even when the second is stronger.
  EXPECT_EQ(*paper_rule_delay_m({{30.0, {0.9, 0.0}}, {0.0, {0.5, 0.0}}}), 0.0);
  // 60 m behind: resolved; the strongest return.
  EXPECT_EQ(*paper_rule_delay_m({{0.0, {0.5, 0.0}}, {60.0, {0.0, 0.9}}}), 60.0);
  EXPECT_EQ(*paper_rule_delay_m({{0.0, {1.0, 0.0}}, {60.0, {0.9, 0.0}}}), 0.0);
  // Equally strong: the earlier.
  EXPECT_EQ(*paper_rule_delay_m({{80.0, {0.7, 0.0}}, {10.0, {0.0, 0.7}}, {200.0, {0.1, 0.0}}}), 10.0);
  // Paths without signal are not returns: a blocked direct path leaves the reflections.
  EXPECT_EQ(*paper_rule_delay_m({{0.0, {0.0, 0.0}}, {20.0, {0.3, 0.0}}, {90.0, {0.8, 0.0}}}), 90.0);
  EXPECT_EQ(*paper_rule_delay_m({{0.0, {0.0, 0.0}}, {20.0, {0.3, 0.0}}, {50.0, {0.8, 0.0}}}), 20.0);
  // The cut-off is configurable; exactly at it the returns count as resolved.
  EXPECT_EQ(*paper_rule_delay_m({{0.0, {0.5, 0.0}}, {45.0, {0.9, 0.0}}}), 45.0);
  EXPECT_EQ(*paper_rule_delay_m({{0.0, {0.5, 0.0}}, {60.0, {0.9, 0.0}}}, 100.0), 0.0);
  // Nothing.
  EXPECT_FALSE(paper_rule_delay_m({}).has_value());
  EXPECT_FALSE(paper_rule_delay_m({{0.0, {0.0, 0.0}}}).has_value());
}

}  // namespace
}  // namespace navemu
