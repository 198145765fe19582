// Broadcast orbit and clock errors: the paper's formula by hand, the radial / along / cross
// frame, the documented sign of the range error, and seeded, sigma-bounded statistics.

#include "models/sat_errors.hpp"
#include "tests/test_support.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <cmath>
#include <cstdio>
#include <map>
#include <vector>

namespace navemu {
namespace {

TEST(SatErrors, PaperFormulaByHand) {
  // theta = 0, R_0 = R_ref: (1 + 0) 10^2 + c^2 1e-18 + 0.918
  //   = 100 + 0.0898755178737 + 0.918 = 101.0078755178737, sqrt = 10.0502674351.
  EXPECT_NEAR(paper_sv_ephemeris_error_m(0.0, 26'550'000.0), 10.0502674351, 1e-9);
  // theta = 90 deg: 1.5 * 100 + 1.0078755 = 151.0078755, sqrt = 12.2885261735.
  EXPECT_NEAR(paper_sv_ephemeris_error_m(kPi / 2.0, 26'550'000.0), 12.2885261735, 1e-9);
  // R_0 = 2 R_ref: 10^1 + 1.0078755 = 11.0078755, sqrt = 3.3178118.
  EXPECT_NEAR(paper_sv_ephemeris_error_m(0.0, 53'100'000.0), std::sqrt(11.0078755178737), 1e-9);
}

TEST(SatErrors, RadialAlongCrossFrameIsOrthonormalAndRightHanded) {
  const Vec3 p(15'000e3, -10'000e3, 18'000e3);
  const Vec3 v(1'500.0, 2'500.0, 300.0);
  const Mat3 r = R_rac_from_ecef(p, v);
  EXPECT_LT((r * r.transpose() - Mat3::Identity()).norm(), 1e-14);
  EXPECT_NEAR(r.determinant(), 1.0, 1e-14);
  EXPECT_LT((r.row(0).transpose() - p.normalized()).norm(), 1e-15);
  // Along-track has a positive component along the velocity, cross-track is normal to it.
  EXPECT_GT(r.row(1).dot(v), 0.0);
  EXPECT_NEAR(r.row(2).dot(v), 0.0, 1e-9);
}

// Satellite over the north pole moving along +x; receiver directly below it.
struct Zenith {
  Vec3 sat_p{0.0, 0.0, 26'560e3};
  Vec3 sat_v{3'874.0, 0.0, 0.0};
  Vec3 rx{0.0, 0.0, 6'357e3};
  Vec3 los() const { return (sat_p - rx).normalized(); }
};

TEST(SatErrors, PureRadialErrorFromBelowShortensTheRangeByTheRadialValue) {
  SatErrorParams p;
  p.along_sigma_m = 0.0;
  p.cross_sigma_m = 0.0;
  p.clock_sigma_m = 0.0;
  p.radial_sigma_m = 2.0;
  SatErrors e(p, 99);
  const Zenith z;
  for (int prn = 1; prn <= 32; ++prn) {
    const double err = e.range_error_m(gps_sat(prn), 0.0, z.sat_p, z.sat_v, z.los());
    const double radial = e.terms(gps_sat(prn)).radial_m;
    ASSERT_NE(radial, 0.0);
    // Broadcast too high by `radial`: the satellite is really closer, the pseudorange shorter.
    EXPECT_DOUBLE_EQ(err, -radial);
    // Seen at right angles to the radial the same error does not reach the range.
    const Vec3 los_side = Vec3(1.0, 0.0, 0.0);
    EXPECT_NEAR(e.range_error_m(gps_sat(prn), 0.0, z.sat_p, z.sat_v, los_side), 0.0, 1e-12);
  }
}

// For any geometry, adding the error to the range computed from the ephemeris position gives
// the range to the true position (broadcast - dr), to first order in |dr| / range (~1e-7 m).
TEST(SatErrors, RangeErrorIsTheRangeToTheTruePositionMinusTheBroadcastRange) {
  SatErrorParams p;
  p.radial_sigma_m = 3.0;
  p.along_sigma_m = 5.0;
  p.cross_sigma_m = 4.0;
  SatErrors e(p, 5);
  const Vec3 rx = ecef_from_geodetic({47.0, 8.0, 500.0});
  const Vec3 sat_p(12'000e3, 9'000e3, 21'000e3);
  const Vec3 sat_v(-2'100.0, 2'800.0, 0.0);
  const Vec3 los = (sat_p - rx).normalized();
  for (int prn = 1; prn <= 32; ++prn) {
    const double err = e.range_error_m(gps_sat(prn), 100.0, sat_p, sat_v, los);
    const SatErrors::Terms t = e.terms(gps_sat(prn));
    const Vec3 dr = R_rac_from_ecef(sat_p, sat_v).transpose() * Vec3(t.radial_m, t.along_m, t.cross_m);
    const double true_range = (sat_p - dr - rx).norm();
    const double broadcast_range = (sat_p - rx).norm();
    EXPECT_NEAR(broadcast_range + err, true_range + t.clock_m, 1e-5);
  }
}

TEST(SatErrors, UnknownPrnHasZeroTerms) {
  SatErrors e(SatErrorParams{}, 1);
  const SatErrors::Terms t = e.terms(gps_sat(17));
  EXPECT_EQ(t.radial_m, 0.0);
  EXPECT_EQ(t.clock_m, 0.0);
}

// Stationary sigma of every term and of the projected range error, and the correlation at a
// lag of tau (e^-1), over many independent PRN processes (10 seeds x 1000 PRNs).
// Every system's satellites (normalised by their system's scale: sisre_relative_to_gps).
TEST(SatErrors, StationarySigmasAndCorrelationTimeWithinSigmaBounds) {
  const SatErrorParams p;  // 0.2 / 1.0 / 0.6 / 0.5 m, tau 3600 s
  const Vec3 rx = ecef_from_geodetic({-33.0, 151.0, 50.0});
  const Vec3 sat_p(-20'000e3, 10'000e3, -14'000e3);
  const Vec3 sat_v(1'200.0, 3'000.0, 400.0);
  const Vec3 los = (sat_p - rx).normalized();
  const Mat3 rac = R_rac_from_ecef(sat_p, sat_v);
  const double sr = p.radial_sigma_m * rac.row(0).dot(los);
  const double sa = p.along_sigma_m * rac.row(1).dot(los);
  const double sc = p.cross_sigma_m * rac.row(2).dot(los);
  const double range_var = sr * sr + sa * sa + sc * sc + p.clock_sigma_m * p.clock_sigma_m;

  double s_r = 0, s_a = 0, s_c = 0, s_k = 0, s_range = 0, s_r1 = 0, s_r01 = 0, s_range1 = 0;
  int n = 0;
  const std::vector<SatId> sats = test::first_satellites(99);
  for (std::uint64_t seed = 1; seed <= 100; ++seed) {  // 100 seeds x 99 satellites
    SatErrors e(p, seed);
    for (const SatId sat : sats) {
      ++n;
      const double k = sisre_relative_to_gps(sat.system());
      const double r0 = e.range_error_m(sat, 1000.0, sat_p, sat_v, los) / k;
      SatErrors::Terms t0 = e.terms(sat);
      const double r1 = e.range_error_m(sat, 1000.0 + p.tau_s, sat_p, sat_v, los) / k;
      SatErrors::Terms t1 = e.terms(sat);
      for (SatErrors::Terms* t : {&t0, &t1}) *t = {t->radial_m / k, t->along_m / k, t->cross_m / k, t->clock_m / k};
      s_r += t0.radial_m * t0.radial_m;
      s_a += t0.along_m * t0.along_m;
      s_c += t0.cross_m * t0.cross_m;
      s_k += t0.clock_m * t0.clock_m;
      s_range += r0 * r0;
      s_range1 += r1 * r1;
      s_r1 += t1.along_m * t1.along_m;
      s_r01 += t0.along_m * t1.along_m;
    }
  }
  // Sample variance with known zero mean: relative sd sqrt(2/n). Five sigma.
  const double tol = 5.0 * std::sqrt(2.0 / n);
  auto rel = [n](double sum, double sigma) { return std::abs(sum / n / (sigma * sigma) - 1.0); };
  EXPECT_LT(rel(s_r, p.radial_sigma_m), tol);
  EXPECT_LT(rel(s_a, p.along_sigma_m), tol);
  EXPECT_LT(rel(s_c, p.cross_sigma_m), tol);
  EXPECT_LT(rel(s_k, p.clock_sigma_m), tol);
  EXPECT_LT(rel(s_range, std::sqrt(range_var)), tol);
  EXPECT_LT(rel(s_range1, std::sqrt(range_var)), tol);  // still stationary after the step
  EXPECT_LT(rel(s_r1, p.along_sigma_m), tol);
  // Lag-tau correlation e^-1; sd of the estimate ~ (1 - rho^2) / sqrt(n).
  const double rho = s_r01 / std::sqrt(s_a * s_r1);
  const double expected = std::exp(-1.0);
  EXPECT_LT(std::abs(rho - expected), 5.0 * (1.0 - expected * expected) / std::sqrt(n)) << rho;
}

// Each system's global-average SISRE (Montenbruck et al. 2018, in sat_errors.hpp): 0.2 m
// Galileo, 0.6 m GPS (the default parameters, 0.56 m), 1 m BeiDou, 2 m GLONASS, as the
// stationary errors of 2,000 satellite draws each give it (the GPS weights of
// SatErrorParams::sisre_m). The weighted sum of squares, dominated by the clock term, has a
// relative sd of 1.14 per draw, its mean 1.14/sqrt(n), the RMS half that: 5 sigma is 3/sqrt(n).
TEST(SatErrors, EachSystemsSisreIsItsPublishedShare) {
  const SatErrorParams p;
  std::map<GnssSystem, std::pair<double, int>> sum;  // of SISRE^2 terms, count
  for (std::uint64_t seed = 1; seed <= 100; ++seed) {
    SatErrors e(p, seed);
    for (const GnssSystem system : {GnssSystem::kGps, GnssSystem::kGalileo, GnssSystem::kBeidou, GnssSystem::kGlonass})
      for (int number = 1; number <= 20; ++number) {
        const SatId sat(system, number);
        e.range_error_m(sat, 0.0, Vec3(26'000e3, 0.0, 0.0), Vec3(0.0, 3'000.0, 1'000.0), Vec3::UnitX());
        const SatErrors::Terms t = e.terms(sat);
        auto& [s2, n] = sum[system];
        s2 += 0.98 * 0.98 * t.radial_m * t.radial_m + t.clock_m * t.clock_m +
              (t.along_m * t.along_m + t.cross_m * t.cross_m) / 49.0;
        ++n;
      }
  }
  const std::map<GnssSystem, double> published_m = {
      {GnssSystem::kGps, p.sisre_m()}, {GnssSystem::kGalileo, 0.2 / 0.6 * p.sisre_m()},
      {GnssSystem::kBeidou, 1.0 / 0.6 * p.sisre_m()}, {GnssSystem::kGlonass, 2.0 / 0.6 * p.sisre_m()}};
  for (const auto& [system, s] : sum) {
    const double rms = std::sqrt(s.first / s.second);
    std::printf("%s SISRE %.3f m (expected %.3f m)\n", system_info(system).name, rms, published_m.at(system));
    EXPECT_NEAR(rms / published_m.at(system), 1.0, 3.0 / std::sqrt(s.second)) << system_info(system).name;
  }
  EXPECT_NEAR(p.sisre_m(), 0.6, 0.05);  // the defaults: GPS of recent years
}

TEST(SatErrors, ProcessesAdvanceByTheTimeSinceThePrnsLastCall) {
  const SatErrorParams p;
  const Zenith z;
  // PRN 5's values do not depend on other PRNs being queried in between.
  SatErrors a(p, 11), b(p, 11);
  const double a0 = a.range_error_m(gps_sat(5), 0.0, z.sat_p, z.sat_v, z.los());
  const double b0 = b.range_error_m(gps_sat(5), 0.0, z.sat_p, z.sat_v, z.los());
  b.range_error_m(gps_sat(7), 0.0, z.sat_p, z.sat_v, z.los());
  b.range_error_m(gps_sat(7), 400.0, z.sat_p, z.sat_v, z.los());
  EXPECT_EQ(a0, b0);
  EXPECT_EQ(a.range_error_m(gps_sat(5), 600.0, z.sat_p, z.sat_v, z.los()),
            b.range_error_m(gps_sat(5), 600.0, z.sat_p, z.sat_v, z.los()));
  // The same time again, or an earlier one, leaves the processes where they are.
  const SatErrors::Terms t = a.terms(gps_sat(5));
  a.range_error_m(gps_sat(5), 600.0, z.sat_p, z.sat_v, z.los());
  a.range_error_m(gps_sat(5), 300.0, z.sat_p, z.sat_v, z.los());
  EXPECT_EQ(a.terms(gps_sat(5)).along_m, t.along_m);
  EXPECT_EQ(a.terms(gps_sat(5)).clock_m, t.clock_m);
  // Time moving on moves them.
  a.range_error_m(gps_sat(5), 700.0, z.sat_p, z.sat_v, z.los());
  EXPECT_NE(a.terms(gps_sat(5)).along_m, t.along_m);
}

TEST(SatErrors, SameSeedSameErrorsDifferentSeedDifferent) {
  const SatErrorParams p;
  const Zenith z;
  SatErrors a(p, 2024), b(p, 2024), c(p, 2025);
  int same_ac = 0;
  for (int k = 0; k < 50; ++k) {
    const double t = 30.0 * k;
    for (int prn = 1; prn <= 8; ++prn) {
      const double ea = a.range_error_m(gps_sat(prn), t, z.sat_p, z.sat_v, z.los());
      ASSERT_EQ(ea, b.range_error_m(gps_sat(prn), t, z.sat_p, z.sat_v, z.los()));
      same_ac += ea == c.range_error_m(gps_sat(prn), t, z.sat_p, z.sat_v, z.los());
    }
  }
  EXPECT_EQ(same_ac, 0);
}

}  // namespace
}  // namespace navemu
