// The receiver solver: analytic DOPs, exact recovery of a known position/clock/velocity from
// error-free measurements, fix types by satellite count, and velocity from real Doppler.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "models/atmosphere.hpp"
#include "models/constellation.hpp"
#include "models/orbit.hpp"
#include "protocols/rinex.hpp"
#include "tests/rinex_data.hpp"
#include "models/solver.hpp"
#include "tests/test_support.hpp"

namespace navemu {
namespace {

TEST(SolverDops, AnalyticZenithPlusThreeOnTheHorizon) {
  // One satellite at the zenith and three on the horizon 120 deg apart:
  // H^T H = [[1.5,0,0,0],[0,1.5,0,0],[0,0,1,-1],[0,0,-1,4]], so HDOP = sqrt(4/3),
  // VDOP = sqrt(4/3), TDOP = sqrt(1/3), PDOP = sqrt(8/3), GDOP = sqrt(3).
  const std::vector<AzEl> dirs = {
      {0.0, kPi / 2}, {0.0, 0.0}, {2 * kPi / 3, 0.0}, {4 * kPi / 3, 0.0}};
  const Dops d = dops_from_directions(dirs);
  EXPECT_NEAR(d.hdop, std::sqrt(4.0 / 3.0), 1e-12);
  EXPECT_NEAR(d.vdop, std::sqrt(4.0 / 3.0), 1e-12);
  EXPECT_NEAR(d.tdop, std::sqrt(1.0 / 3.0), 1e-12);
  EXPECT_NEAR(d.pdop, std::sqrt(8.0 / 3.0), 1e-12);
  EXPECT_NEAR(d.gdop, std::sqrt(3.0), 1e-12);
}

TEST(SolverDops, DegenerateAndTooFew) {
  const std::vector<AzEl> three = {{0, 1}, {1, 1}, {2, 1}};
  EXPECT_EQ(dops_from_directions(three).pdop, 0.0);
  // Four satellites on one cone around the zenith: clock and height inseparable.
  const std::vector<AzEl> cone = {{0, 0.5}, {kPi / 2, 0.5}, {kPi, 0.5}, {3 * kPi / 2, 0.5}};
  EXPECT_EQ(dops_from_directions(cone).pdop, 0.0);
}

struct Scenario {
  GpsTime t_tag = from_week_tow(2244, 36000.0);  // receiver time tag
  Geodetic rx{30.0, 95.0, 120.0};
  double clock_m = 12'345.678;   // receiver clock bias * c
  Vec3 v_ecef_mps{12.0, -7.0, 3.0};
  double drift_mps = 0.25;       // receiver clock drift * c
};

// Error-free measurements of the built-in constellation for a receiver whose clock runs
// clock_m / c ahead: the signals arrive at true time t_tag - clock/c.
std::vector<RangeMeasurement> exact_measurements(const Scenario& s, double mask_deg) {
  const NavData nav = nominal_constellation(s.t_tag);
  const Vec3 p = ecef_from_geodetic(s.rx);
  const GpsTime t_true = s.t_tag.plus_s(-s.clock_m / kSpeedOfLight_mps);
  std::vector<RangeMeasurement> out;
  for (int prn = 1; prn <= 24; ++prn) {
    const GpsEphemeris* eph = select_ephemeris(nav, gps_sat(prn), s.t_tag);
    const SatGeometry g = gps_sat_geometry(*eph, t_true, p, s.v_ecef_mps);
    if (g.dir.el_rad < mask_deg * kDegToRad) continue;
    const double rr = g.range_rate_mps + s.drift_mps;
    const double doppler_hz = -rr * kGpsL1_Hz / kSpeedOfLight_mps;
    out.push_back(make_range_measurement(*eph, s.t_tag, g.range_m + s.clock_m, doppler_hz));
  }
  return out;
}

// A state near the transmit time (the generator's, at the true one) carried there to first
// order gives the measurement solving Kepler's equation at the receiver's estimate gives: for
// pseudorange errors of metres to kilometres (microseconds) to well under a millimetre and a
// picosecond; a state a millisecond or more away is not used.
TEST(SolverInput, AStateNearTheTransmitTimeIsCarriedThere) {
  const Scenario s;
  const NavData nav = nominal_constellation(s.t_tag);
  const Vec3 p = ecef_from_geodetic(s.rx);
  const GpsTime t_true = s.t_tag.plus_s(-s.clock_m / kSpeedOfLight_mps);
  for (int prn = 1; prn <= 24; ++prn) {
    const GpsEphemeris* eph = select_ephemeris(nav, gps_sat(prn), s.t_tag);
    const SatGeometry g = gps_sat_geometry(*eph, t_true, p);
    const SatStateAt near{g.t_transmit, g.sat_transmit};
    for (const double error_m : {0.0, 3.0, -250.0, 3000.0, 400e3}) {
      SCOPED_TRACE(::testing::Message() << "G" << prn << " error " << error_m << " m");
      const double pr_m = g.range_m + s.clock_m + error_m;
      const RangeMeasurement direct = make_range_measurement(BroadcastRecord{eph}, s.t_tag, pr_m);
      const RangeMeasurement carried = make_range_measurement(BroadcastRecord{eph}, s.t_tag, pr_m, {}, nullptr, &near);
      const double tol_m = error_m > 100e3 ? 0.0 : 1e-4;  // 400 km: 1.3 ms away, solved again
      EXPECT_LE((carried.sat_p_ecef_m - direct.sat_p_ecef_m).norm(), tol_m);
      EXPECT_LE(std::abs(carried.sat_clock_m - direct.sat_clock_m), tol_m);
      EXPECT_LE((carried.sat_v_ecef_mps - direct.sat_v_ecef_mps).norm(), tol_m * 10.0);  // a dt: 0.6 um/s per us
      EXPECT_EQ(carried.sat_variance_m2, direct.sat_variance_m2);
      // The given state is the one used (one moved by a metre moves the measurement's), unless
      // too far.
      SatStateAt moved = near;
      moved.state.p_ecef_m.x() += 1.0;
      const RangeMeasurement from_moved = make_range_measurement(BroadcastRecord{eph}, s.t_tag, pr_m, {}, nullptr, &moved);
      EXPECT_NEAR((from_moved.sat_p_ecef_m - direct.sat_p_ecef_m).norm(), error_m > 100e3 ? 0.0 : 1.0, 1e-4);
    }
  }
}

TEST(SolverExact, RecoversPositionClockAndVelocity) {
  const Scenario s;
  const auto meas = exact_measurements(s, 5.0);
  ASSERT_GE(meas.size(), 6u);
  SolverOptions opt;
  opt.elevation_mask_deg = 5.0;
  const Solution sol = solve(meas, s.t_tag, opt);
  ASSERT_EQ(sol.fix, FixType::k3D);
  EXPECT_EQ(sol.num_used, static_cast<int>(meas.size()));
  EXPECT_LT((sol.p_ecef_m - ecef_from_geodetic(s.rx)).norm(), 1e-3);
  EXPECT_NEAR(sol.clock_m, s.clock_m, 1e-3);
  for (const SatResidual& r : sol.sats) EXPECT_LT(std::abs(r.residual_m), 1e-3);
  ASSERT_TRUE(sol.v_ecef_mps.has_value());
  EXPECT_LT((*sol.v_ecef_mps - s.v_ecef_mps).norm(), 1e-3);
  EXPECT_NEAR(sol.clock_drift_mps, s.drift_mps, 1e-3);

  // The DOPs are those of the used directions.
  std::vector<AzEl> dirs;
  for (const SatResidual& r : sol.sats) dirs.push_back({r.az_deg * kDegToRad, r.el_deg * kDegToRad});
  EXPECT_NEAR(sol.dops.pdop, dops_from_directions(dirs).pdop, 1e-9);
}

// Several systems: each clock group gets its own clock (GPS's plus an inter-system bias), and
// the position is the one of the single-system solution.
TEST(SolverExact, OneClockPerSystemTimeScale) {
  const Scenario s;
  auto meas = exact_measurements(s, 5.0);
  ASSERT_GE(meas.size(), 8u);
  // Relabel: the first three as Galileo satellites seen 15 m (50 ns) later, the next as the one
  // GLONASS satellite 7 m earlier, one as QZSS, which shares GPS time.
  constexpr double kGalileoBias_m = 15.0, kGlonassBias_m = -7.0;
  for (int i = 0; i < 3; ++i) {
    meas[static_cast<std::size_t>(i)].sat = SatId(GnssSystem::kGalileo, 11 + i);
    meas[static_cast<std::size_t>(i)].pseudorange_m += kGalileoBias_m;
  }
  meas[3].sat = SatId(GnssSystem::kGlonass, 5);
  meas[3].pseudorange_m += kGlonassBias_m;
  meas[4].sat = SatId(GnssSystem::kQzss, 2);
  SolverOptions opt;
  opt.elevation_mask_deg = 5.0;
  const Solution sol = solve(meas, s.t_tag, opt);
  ASSERT_EQ(sol.fix, FixType::k3D);
  EXPECT_LT((sol.p_ecef_m - ecef_from_geodetic(s.rx)).norm(), 1e-3);
  EXPECT_NEAR(sol.clock_m, s.clock_m, 1e-3);
  ASSERT_TRUE(sol.group_clock_m[clock_group(GnssSystem::kGps)]);
  ASSERT_TRUE(sol.group_clock_m[clock_group(GnssSystem::kGalileo)]);
  ASSERT_TRUE(sol.group_clock_m[clock_group(GnssSystem::kGlonass)]);
  EXPECT_FALSE(sol.group_clock_m[clock_group(GnssSystem::kBeidou)]);
  EXPECT_NEAR(*sol.group_clock_m[clock_group(GnssSystem::kGalileo)], s.clock_m + kGalileoBias_m, 1e-3);
  EXPECT_NEAR(*sol.group_clock_m[clock_group(GnssSystem::kGlonass)], s.clock_m + kGlonassBias_m, 1e-3);
  for (const SatResidual& r : sol.sats) EXPECT_LT(std::abs(r.residual_m), 1e-3) << r.sat.rinex();

  // Without GPS and QZSS the reported clock is the first remaining system's (GLONASS before
  // Galileo in the group order); Galileo's three and GLONASS's one satellite with two clocks
  // leave two equations for three coordinates: no fix.
  const std::vector<RangeMeasurement> others(meas.begin(), meas.begin() + 4);
  EXPECT_EQ(solve(others, s.t_tag, opt).fix, FixType::kNone);
  std::vector<RangeMeasurement> galileo_only(meas.begin(), meas.begin() + 3);
  for (std::size_t i = 5; i < meas.size(); ++i) {
    RangeMeasurement m = meas[i];
    m.sat = SatId(GnssSystem::kGalileo, 20 + static_cast<int>(i));
    m.pseudorange_m += kGalileoBias_m;
    galileo_only.push_back(m);
  }
  const Solution gal = solve(galileo_only, s.t_tag, opt);
  ASSERT_EQ(gal.fix, FixType::k3D);
  EXPECT_NEAR(gal.clock_m, s.clock_m + kGalileoBias_m, 1e-3);
  EXPECT_LT((gal.p_ecef_m - ecef_from_geodetic(s.rx)).norm(), 1e-3);
}

TEST(SolverExact, ElevationMaskExcludesLowSatellites) {
  const Scenario s;
  const auto meas = exact_measurements(s, 0.0);
  SolverOptions opt;
  opt.elevation_mask_deg = 30.0;
  const Solution sol = solve(meas, s.t_tag, opt);
  ASSERT_EQ(sol.fix, FixType::k3D);
  int used = 0, below = 0;
  for (const SatResidual& r : sol.sats) {
    if (r.used) ++used;
    if (r.el_deg < 30.0) {
      ++below;
      EXPECT_FALSE(r.used) << "PRN " << r.sat.number();
    }
  }
  EXPECT_GT(below, 0);
  EXPECT_EQ(used, sol.num_used);
  EXPECT_LT((sol.p_ecef_m - ecef_from_geodetic(s.rx)).norm(), 1e-3);
}

// RTKLIB's Saastamoinen stops at -100 m; the solver takes it at -100 m below that, so that a
// receiver at the edge (the sea south of Sri Lanka: geoid -106 m) converges. Measurements carry
// the model's delay at -100 m; without the hold the estimate flipped between two solutions.
TEST(SolverExact, ConvergesAtTheTroposphereModelsLowestHeight) {
  for (const double h_m : {-99.7, -100.3, -130.0}) {
    Scenario s;
    s.rx = {6.0, 80.5, h_m};
    std::vector<RangeMeasurement> meas = exact_measurements(s, 10.0);
    ASSERT_GE(meas.size(), 5u);
    const Vec3 p = ecef_from_geodetic(s.rx);
    const Geodetic lowest{s.rx.lat_deg, s.rx.lon_deg, std::max(h_m, kSaastamoinenLowest_m)};
    for (RangeMeasurement& m : meas)
      m.pseudorange_m += saastamoinen_delay(lowest, azimuth_elevation(s.rx, p, m.sat_p_ecef_m).el_rad,
                                            standard_atmosphere(lowest.h_m, 0.7))
                             .total_m();
    SolverOptions opt;
    opt.elevation_mask_deg = 10.0;
    opt.saastamoinen = true;
    opt.initial_p_ecef_m = ecef_from_geodetic({s.rx.lat_deg, s.rx.lon_deg, -80.0});
    const Solution sol = solve(meas, s.t_tag, opt);
    ASSERT_EQ(sol.fix, FixType::k3D) << h_m << " m";
    EXPECT_LT((sol.p_ecef_m - p).norm(), 0.01) << h_m << " m";
  }
}

TEST(SolverFixType, ThreeSatellitesGiveTwoDWithHeightHeldFewerGiveNone) {
  const Scenario s;
  auto meas = exact_measurements(s, 10.0);
  ASSERT_GE(meas.size(), 4u);
  meas.resize(3);
  SolverOptions opt;
  opt.elevation_mask_deg = 10.0;
  // Without a prior position there is nothing to hold: no fix.
  EXPECT_EQ(solve(meas, s.t_tag, opt).fix, FixType::kNone);
  // With a prior at the right height (but 200 m off horizontally): a 2D fix at that height.
  Geodetic prior = s.rx;
  prior.lat_deg += 0.001;
  prior.lon_deg -= 0.001;
  opt.initial_p_ecef_m = ecef_from_geodetic(prior);
  const Solution sol = solve(meas, s.t_tag, opt);
  ASSERT_EQ(sol.fix, FixType::k2D);
  EXPECT_LT((sol.p_ecef_m - ecef_from_geodetic(s.rx)).norm(), 0.01);
  meas.resize(2);
  EXPECT_EQ(solve(meas, s.t_tag, opt).fix, FixType::kNone);
}

// CFG-NAVSPG-FIXMODE (F9P integration manual, "Navigation input filters"): 3D only never gives
// a 2D fix; 2D only holds the height at the fixed one whatever the satellites are.
TEST(SolverFixType, FixModesThreeDOnlyAndTwoDOnly) {
  const Scenario s;
  auto meas = exact_measurements(s, 10.0);
  ASSERT_GE(meas.size(), 5u);
  SolverOptions opt;
  opt.elevation_mask_deg = 10.0;
  Geodetic prior = s.rx;
  prior.lat_deg += 0.001;
  opt.initial_p_ecef_m = ecef_from_geodetic(prior);

  opt.fix_mode = SolverFixMode::k3DOnly;
  EXPECT_EQ(solve(meas, s.t_tag, opt).fix, FixType::k3D);
  auto three = meas;
  three.resize(3);
  EXPECT_EQ(solve(three, s.t_tag, opt).fix, FixType::kNone);

  opt.fix_mode = SolverFixMode::k2DOnly;
  opt.fixed_height_m = s.rx.h_m;  // the true height: the exact position
  Solution sol = solve(meas, s.t_tag, opt);
  ASSERT_EQ(sol.fix, FixType::k2D);
  EXPECT_LT((sol.p_ecef_m - ecef_from_geodetic(s.rx)).norm(), 0.01);
  EXPECT_EQ(solve(three, s.t_tag, opt).fix, FixType::k2D);

  opt.fixed_height_m = s.rx.h_m + 50.0;  // a wrong height is held all the same
  sol = solve(meas, s.t_tag, opt);
  ASSERT_EQ(sol.fix, FixType::k2D);
  EXPECT_NEAR(geodetic_from_ecef(sol.p_ecef_m).h_m, s.rx.h_m + 50.0, 0.5);

  // Without a prior the estimate first comes down from the Earth's centre in 3D (four
  // satellites at least), then holds the height.
  opt.initial_p_ecef_m = Vec3::Zero();
  opt.fixed_height_m = s.rx.h_m;
  sol = solve(meas, s.t_tag, opt);
  ASSERT_EQ(sol.fix, FixType::k2D);
  EXPECT_LT((sol.p_ecef_m - ecef_from_geodetic(s.rx)).norm(), 0.01);
}

TEST(SolverRealDoppler, StaticStationVelocityIsNearZero) {
  NAVEMU_REQUIRE_SHARED();
  // ESBC is a static IGS station: velocities from its L1 C/A Doppler (D1C) must be ~0.
  const auto dir = test::shared_data("gnss/esbc_20200625");
  const ObsData obs = test::rinex_obs_file(dir / "ESBC00DNK_R_20201770000_01H_30S_MO.rnx");
  const NavData nav = test::rinex_nav_file(dir / "ESBC00DNK_R_20201770000_01D_MN.rnx");
  const int c1c = obs.header.index_of('G', "C1C");
  const int d1c = obs.header.index_of('G', "D1C");
  ASSERT_GE(c1c, 0);
  ASSERT_GE(d1c, 0);
  SolverOptions opt;
  opt.klobuchar = nav.klobuchar;
  opt.saastamoinen = true;
  double max_speed = 0.0;
  int solved = 0;
  for (const ObsEpoch& e : obs.epochs) {
    std::vector<RangeMeasurement> meas;
    for (const SatObs& so : e.sats) {
      if (so.system != 'G') continue;
      const double pr = so.values[static_cast<std::size_t>(c1c)];
      const double d = so.values[static_cast<std::size_t>(d1c)];
      const GpsEphemeris* eph = select_ephemeris(nav, gps_sat(so.number), e.time);
      if (eph == nullptr || !std::isfinite(pr) || !std::isfinite(d)) continue;
      meas.push_back(make_range_measurement(*eph, e.time, pr, d));
    }
    const Solution sol = solve(meas, e.time, opt);
    if (sol.fix != FixType::k3D || !sol.v_ecef_mps) continue;
    ++solved;
    max_speed = std::max(max_speed, sol.v_ecef_mps->norm());
  }
  std::printf("ESBC Doppler velocity: %d epochs, max speed %.4f m/s\n", solved, max_speed);
  EXPECT_EQ(solved, static_cast<int>(obs.epochs.size()));
  EXPECT_LT(max_speed, 0.1);
}

// The chi-square quantiles against the published table (Abramowitz & Stegun, Table 26.8;
// the same values as RTKLIB's chisqr[] for alpha = 0.001), 5 significant digits.
TEST(SolverRaim, ChiSquareQuantilesMatchThePublishedTable) {
  const struct { double p; int dof; double x; } table[] = {
      {0.999, 1, 10.828}, {0.999, 2, 13.816}, {0.999, 5, 20.515}, {0.999, 10, 29.588},
      {0.999, 30, 59.703}, {0.95, 1, 3.8415}, {0.95, 10, 18.307}, {0.99, 20, 37.566},
      {0.5, 2, 1.3863}};
  for (const auto& r : table) EXPECT_NEAR(chi_square_quantile(r.p, r.dof), r.x, 5e-5 * r.x) << r.p << " " << r.dof;
}

// The real ESBC epochs (GPS L1 C/A, broadcast corrections) with one satellite's pseudorange
// 1 km long (a different one each epoch): without the residual test every fix is pulled off by
// hundreds of metres; with it that satellite, and only it, is excluded, and the fix is the
// clean data's fix without it (to a millimetre): a median 0.25 m from the fix of all clean
// satellites (leaving one out moves a fix by its share of the errors: up to 2.4 m here). The
// clean epochs pass the test untouched.
TEST(SolverRaim, ASatelliteOneKilometreOffIsExcludedOnRealData) {
  NAVEMU_REQUIRE_SHARED();
  const auto dir = test::shared_data("gnss/esbc_20200625");
  const ObsData obs = test::rinex_obs_file(dir / "ESBC00DNK_R_20201770000_01H_30S_MO.rnx");
  const NavData nav = test::rinex_nav_file(dir / "ESBC00DNK_R_20201770000_01D_MN.rnx");
  const int c1c = obs.header.index_of('G', "C1C");
  ASSERT_GE(c1c, 0);
  SolverOptions opt;
  opt.klobuchar = nav.klobuchar;
  opt.saastamoinen = true;
  opt.elevation_mask_deg = 10.0;
  SolverOptions raim = opt;
  raim.raim = true;
  std::size_t index = 0;
  double nearest_plain_m = 1e9, worst_vs_reduced_m = 0.0;
  std::vector<double> off_m;
  for (const ObsEpoch& e : obs.epochs) {
    std::vector<RangeMeasurement> meas;
    for (const SatObs& so : e.sats) {
      const double pr = so.system == 'G' ? so.values[static_cast<std::size_t>(c1c)] : NAN;
      const GpsEphemeris* eph = so.system == 'G' ? select_ephemeris(nav, gps_sat(so.number), e.time) : nullptr;
      if (eph != nullptr && std::isfinite(pr)) meas.push_back(make_range_measurement(*eph, e.time, pr));
    }
    const Solution clean = solve(meas, e.time, opt), clean_raim = solve(meas, e.time, raim);
    ASSERT_EQ(clean.fix, FixType::k3D);
    ASSERT_EQ(clean_raim.fix, FixType::k3D);
    EXPECT_EQ(clean_raim.p_ecef_m, clean.p_ecef_m);
    EXPECT_GT(clean.degrees_of_freedom, 0);
    EXPECT_LE(clean.chi_square, chi_square_quantile(0.999, clean.degrees_of_freedom));
    for (const SatResidual& r : clean_raim.sats) EXPECT_FALSE(r.excluded);

    const std::size_t bad = index++ % meas.size();
    if (!clean.sats[bad].used) continue;  // below the mask: nothing to detect
    std::vector<RangeMeasurement> reduced = meas;
    reduced.erase(reduced.begin() + static_cast<std::ptrdiff_t>(bad));
    const Solution clean_without = solve(reduced, e.time, opt);
    meas[bad].pseudorange_m += 1000.0;
    const Solution plain = solve(meas, e.time, opt), fde = solve(meas, e.time, raim);
    ASSERT_EQ(fde.fix, FixType::k3D) << e.time.ns;
    ASSERT_EQ(fde.sats.size(), meas.size());
    for (std::size_t i = 0; i < meas.size(); ++i) {
      EXPECT_EQ(fde.sats[i].sat, meas[i].sat);
      EXPECT_EQ(fde.sats[i].excluded, i == bad) << meas[i].sat.rinex();
    }
    EXPECT_NEAR(fde.sats[bad].residual_m, 1000.0, 5.0);
    EXPECT_FALSE(fde.sats[bad].used);
    nearest_plain_m = std::min(nearest_plain_m, (plain.p_ecef_m - clean.p_ecef_m).norm());
    worst_vs_reduced_m = std::max(worst_vs_reduced_m, (fde.p_ecef_m - clean_without.p_ecef_m).norm());
    off_m.push_back((fde.p_ecef_m - clean.p_ecef_m).norm());
  }
  ASSERT_GE(off_m.size(), 90u);
  std::sort(off_m.begin(), off_m.end());
  const double median_m = off_m[off_m.size() / 2];
  std::printf("[ raim ] %zu ESBC epochs with a satellite 1 km off: without the test >= %.1f m off; with "
              "it the reduced clean fix to %.1e m, from the full clean fix median %.3f m, max %.3f m\n",
              off_m.size(), nearest_plain_m, worst_vs_reduced_m, median_m, off_m.back());
  EXPECT_GT(nearest_plain_m, 10.0);
  EXPECT_LT(worst_vs_reduced_m, 1e-3);
  EXPECT_LT(median_m, 0.5);
}

// Two satellites off (+300 m and -200 m) among exact measurements: the first exclusion still
// fails, the second passes; both are reported, the fix is the exact position again. With one
// exclusion allowed (RTKLIB's raim_fde) there is no fix.
TEST(SolverRaim, TwoFaultySatellitesAreExcludedOneAfterTheOther) {
  const Scenario s;
  auto meas = exact_measurements(s, 5.0);
  ASSERT_GE(meas.size(), 8u);
  meas[1].pseudorange_m += 300.0;
  meas[4].pseudorange_m -= 200.0;
  SolverOptions opt;
  opt.elevation_mask_deg = 5.0;
  opt.raim = true;
  const Solution sol = solve(meas, s.t_tag, opt);
  ASSERT_EQ(sol.fix, FixType::k3D);
  ASSERT_EQ(sol.sats.size(), meas.size());
  for (std::size_t i = 0; i < meas.size(); ++i) EXPECT_EQ(sol.sats[i].excluded, i == 1 || i == 4) << i;
  EXPECT_NEAR(sol.sats[1].residual_m, 300.0, 1e-3);
  EXPECT_NEAR(sol.sats[4].residual_m, -200.0, 1e-3);
  EXPECT_LT((sol.p_ecef_m - ecef_from_geodetic(s.rx)).norm(), 1e-3);
  opt.raim_max_exclusions = 1;
  const Solution one = solve(meas, s.t_tag, opt);
  EXPECT_EQ(one.fix, FixType::kNone);
  EXPECT_TRUE(one.integrity_failed);
}

// Fewer satellites than an exclusion needs: a failing fix is no fix, reported as failed.
TEST(SolverRaim, AFailingFixWithoutRoomForExclusionIsNoFix) {
  const Scenario s;
  auto meas = exact_measurements(s, 5.0);
  meas.resize(5);  // 4 unknowns + 1: testable, but no exclusion is (4 rows, 0 degrees of freedom)
  meas[2].pseudorange_m += 500.0;
  SolverOptions opt;
  opt.elevation_mask_deg = 5.0;
  opt.raim = true;
  const Solution sol = solve(meas, s.t_tag, opt);
  EXPECT_EQ(sol.fix, FixType::kNone);
  EXPECT_TRUE(sol.integrity_failed);
  opt.raim = false;
  EXPECT_EQ(solve(meas, s.t_tag, opt).fix, FixType::k3D);
}


// The receiver's way (raim_keeps_failed_fix): the fix no exclusion rescues is kept over every
// satellite, flagged, and its covariance scaled by chi^2 / dof, the a-posteriori variance
// factor: the same position as without the test, an accuracy grown to its residuals.
TEST(SolverRaim, AReceiverKeepsTheFailedFixWithItsCovarianceScaledToItsResiduals) {
  const Scenario s;
  auto meas = exact_measurements(s, 5.0);
  meas.resize(5);
  meas[2].pseudorange_m += 500.0;
  SolverOptions opt;
  opt.elevation_mask_deg = 5.0;
  const Solution plain = solve(meas, s.t_tag, opt);
  opt.raim = true;
  opt.raim_keeps_failed_fix = true;
  const Solution kept = solve(meas, s.t_tag, opt);
  ASSERT_EQ(kept.fix, FixType::k3D);
  EXPECT_TRUE(kept.integrity_failed);
  EXPECT_EQ(kept.p_ecef_m, plain.p_ecef_m);
  ASSERT_EQ(kept.degrees_of_freedom, 1);
  EXPECT_GT(kept.chi_square, 100.0);
  for (int i = 0; i < 3; ++i)
    EXPECT_NEAR(kept.cov_ecef_m2(i, i), plain.cov_ecef_m2(i, i) * kept.chi_square, 1e-9 * kept.cov_ecef_m2(i, i));
}

}  // namespace
}  // namespace navemu
