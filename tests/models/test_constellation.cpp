#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <set>
#include <vector>

#include "models/constellation.hpp"
#include "models/geodesy.hpp"
#include "models/orbit.hpp"
#include "models/solver.hpp"
#include "core/time.hpp"

namespace navemu {
namespace {

constexpr double kPiD = 3.14159265358979323846;
constexpr double kDeg = kPiD / 180.0;

// Baseline 24-slot constellation, GPS SPS Performance Standard Table 3.2-1 (3rd ed. 2001
// Table 3-1): RAAN and argument of latitude at 0000Z 1 July 1993, degrees, slots A1..F4.
struct SlotRef {
  double raan_deg, arg_lat_deg;
};
const SlotRef kTable[24] = {
    {272.847, 268.126}, {272.847, 161.786}, {272.847, 11.676},  {272.847, 41.806},
    {332.847, 80.956},  {332.847, 173.336}, {332.847, 309.976}, {332.847, 204.376},
    {32.847, 111.876},  {32.847, 11.796},   {32.847, 339.666},  {32.847, 241.556},
    {92.847, 135.226},  {92.847, 265.446},  {92.847, 35.156},   {92.847, 167.356},
    {152.847, 197.046}, {152.847, 302.596}, {152.847, 66.066},  {152.847, 333.686},
    {212.847, 238.886}, {212.847, 345.226}, {212.847, 105.206}, {212.847, 135.346},
};
constexpr double kTableA_m = 26'559'710.0;
constexpr double kTableInclination = 55.0 * kDeg;
// Greenwich hour angle at the defined epoch, 18 h 36 m 14.4 s.
constexpr double kTableGha = (18.0 + 36.0 / 60.0 + 14.4 / 3600.0) * 15.0 * kDeg;

double wrap(double a) { return std::remainder(a, 2.0 * kPiD); }

// The record with toe nearest to t for a PRN (IS-GPS-200 20.3.4.5: fit interval centred on
// toe), independent of select_ephemeris.
const GpsEphemeris& nearest(const NavData& nav, SatId sat, GpsTime t) {
  const GpsEphemeris* best = nullptr;
  for (const auto& e : nav.gps) {
    if (e.sat != sat) continue;
    if (best == nullptr ||
        std::abs(seconds_between(t, e.toe)) < std::abs(seconds_between(t, best->toe)))
      best = &e;
  }
  EXPECT_NE(best, nullptr) << "PRN " << sat.number();
  return *best;
}

// Position and velocity in a frame whose x axis points where the Greenwich meridian was
// when the Earth-rotation angle was `gha`, turning about z at `frame_rate` (0: inertial; the
// node rate Omega_dot: the frame in which the regressing orbit plane stays fixed, so that the
// angular momentum gives the plane's own inclination and node). With `gha` the table's
// Greenwich hour angle at its epoch this is the frame of the SPS PS table's RAAN.
struct Inertial {
  Vec3 r, v;
};
Inertial to_frame(const SatState& s, double gha, double frame_rate) {
  const Vec3 w(0.0, 0.0, kOmegaEarth_radps - frame_rate);
  const Vec3 v_rot = s.v_ecef_mps + w.cross(s.p_ecef_m);
  const double c = std::cos(gha), sn = std::sin(gha);
  auto rot = [&](const Vec3& x) {
    return Vec3(c * x.x() - sn * x.y(), sn * x.x() + c * x.y(), x.z());
  };
  return {rot(s.p_ecef_m), rot(v_rot)};
}

struct Elements {
  double inclination, raan, arg_lat;
};
Elements elements(const Inertial& x) {
  const Vec3 h = x.r.cross(x.v);
  const Vec3 node = Vec3::UnitZ().cross(h).normalized();
  const Vec3 in_plane = h.normalized().cross(node);
  return {std::acos(h.z() / h.norm()), std::atan2(node.y(), node.x()),
          std::atan2(x.r.dot(in_plane), x.r.dot(node))};
}

// 2023-01-08 10:00 GPST (GPS week 2244, 36000 s).
const GpsTime kScenario = GpsTime{(2244LL * kSecondsPerWeek + 36000LL) * kNsPerS};

TEST(NominalConstellation, TwentyFourPrnsWithFreshRecordsOverTheWindow) {
  const NavData nav = nominal_constellation(kScenario);
  EXPECT_NE(nav.source.find("SPS"), std::string::npos);
  std::map<int, std::vector<const GpsEphemeris*>> by_prn;
  for (const auto& e : nav.gps) by_prn[e.sat.number()].push_back(&e);
  ASSERT_EQ(by_prn.size(), 24u);
  EXPECT_EQ(by_prn.begin()->first, 1);
  EXPECT_EQ(by_prn.rbegin()->first, 24);
  for (const auto& [prn, recs] : by_prn) {
    std::set<std::int64_t> toes;
    std::set<int> iodes;
    for (const auto* e : recs) {
      EXPECT_EQ(e->toe.ns % (7200 * kNsPerS), 0) << "toe on a 2-hour boundary";
      EXPECT_EQ(e->toc, e->toe);
      EXPECT_EQ(e->health, 0);
      EXPECT_EQ(e->e, 0.0);
      EXPECT_EQ(e->af0_s, 0.0);
      EXPECT_EQ(e->tgd_s, 0.0);
      EXPECT_EQ(e->iodc, e->iode);
      toes.insert(e->toe.ns);
      iodes.insert(e->iode);
    }
    EXPECT_EQ(toes.size(), recs.size()) << "PRN " << prn;
    EXPECT_EQ(iodes.size(), recs.size()) << "PRN " << prn;
    EXPECT_LE(*toes.begin(), kScenario.plus_s(-7200.0).ns);
    EXPECT_GE(*toes.rbegin(), kScenario.plus_s(24 * 3600.0).ns);
  }
  // At any time from t - 2 h to t + 24 h, select_ephemeris finds for every PRN a record
  // with |t - toe| <= 1 h (half the 2-hour spacing, well inside the 4-hour fit interval).
  for (double dt = -7200.0; dt <= 24 * 3600.0; dt += 600.0) {
    const GpsTime t = kScenario.plus_s(dt);
    for (int prn = 1; prn <= 24; ++prn) {
      const GpsEphemeris* e = select_ephemeris(nav, gps_sat(prn), t);
      ASSERT_NE(e, nullptr) << "PRN " << prn;
      EXPECT_LE(std::abs(seconds_between(t, e->toe)), 3600.0);
    }
  }
  // An instant that is not on a boundary, including before the GPS epoch's first week.
  EXPECT_EQ(nominal_constellation(GpsTime{12345 * kNsPerS}).gps.size(), nav.gps.size());
}

TEST(NominalConstellation, CircularFiftyFiveDegreeOrbitsOfTheTableRadius) {
  const NavData nav = nominal_constellation(kScenario);
  double max_dr = 0.0, max_di = 0.0;
  for (const auto& e : nav.gps) {
    for (double tk = -7200.0; tk <= 7200.0; tk += 1800.0) {
      const SatState s = gps_sat_state(e, e.toe.plus_s(tk));
      max_dr = std::max(max_dr, std::abs(s.p_ecef_m.norm() - kTableA_m));
      const Elements el = elements(to_frame(s, 0.0, e.omega_dot_radps));
      max_di = std::max(max_di, std::abs(el.inclination - kTableInclination));
      // The osculating inertial inclination differs by the node's motion, Omega_dot / n
      // ~ 5e-5 rad at most.
      const Elements osc = elements(to_frame(s, 0.0, 0.0));
      EXPECT_LT(std::abs(osc.inclination - kTableInclination), 1e-4);
      EXPECT_EQ(s.clock_bias_s, 0.0);
    }
  }
  EXPECT_LT(max_dr, 1.0);
  EXPECT_LT(max_di, 1e-6);
  std::printf("[ nominal ] max |r - A| = %.3e m, max |i - 55 deg| = %.3e rad\n", max_dr, max_di);
}

// Two revolutions per turn of the Earth relative to the regressing node: the Earth-fixed
// geometry repeats after 2 pi / (omega_e - Omega_dot), a sidereal day less ~9 s, and the
// nodal period is half of it, about 11 h 58 min.
TEST(NominalConstellation, PeriodHalfASiderealDayAndGroundTrackRepeats) {
  const NavData nav = nominal_constellation(kScenario);
  const GpsEphemeris& e0 = nearest(nav, gps_sat(1), kScenario);
  const double a = e0.sqrt_a_sqrtm * e0.sqrt_a_sqrtm;
  const double n = std::sqrt(kGpsMu_m3ps2 / (a * a * a)) + e0.delta_n_radps;
  const double period_s = 2.0 * kPiD / n;
  const double sidereal_day_s = 2.0 * kPiD / kOmegaEarth_radps;
  EXPECT_NEAR(period_s, 11 * 3600 + 58 * 60, 60.0);
  EXPECT_NEAR(period_s, sidereal_day_s / 2.0, 10.0);
  const double repeat_s = 2.0 * kPiD / (kOmegaEarth_radps - e0.omega_dot_radps);
  EXPECT_NEAR(2.0 * period_s, repeat_s, 1e-6);

  double max_repeat = 0.0, max_sidereal = 0.0;
  for (int prn = 1; prn <= 24; ++prn) {
    for (double dt = 0.0; dt < 3 * 3600.0; dt += 1800.0) {
      const GpsTime t = kScenario.plus_s(dt);
      const Vec3 p0 = gps_sat_state(nearest(nav, gps_sat(prn), t), t).p_ecef_m;
      const GpsTime t1 = t.plus_s(repeat_s);
      const Vec3 p1 = gps_sat_state(nearest(nav, gps_sat(prn), t1), t1).p_ecef_m;
      const GpsTime t2 = t.plus_s(sidereal_day_s);
      const Vec3 p2 = gps_sat_state(nearest(nav, gps_sat(prn), t2), t2).p_ecef_m;
      // Ground track: sub-satellite points on a sphere of the Earth's equatorial radius.
      const double re = 6378137.0;
      max_repeat = std::max(max_repeat, (p1.normalized() - p0.normalized()).norm() * re);
      max_sidereal = std::max(max_sidereal, (p2.normalized() - p0.normalized()).norm() * re);
    }
  }
  EXPECT_LT(max_repeat, 1000.0);
  EXPECT_LT(max_sidereal, 20000.0);
  std::printf("[ nominal ] nodal period %.2f s; ground-track offset after %.2f s: %.3e m, "
              "after one sidereal day (%.2f s): %.0f m\n",
              period_s, repeat_s, max_repeat, sidereal_day_s, max_sidereal);
}

// At the table's defined epoch, RAAN (inertial, with the table's Greenwich hour angle) and
// argument of latitude of every slot are those of the table.
TEST(NominalConstellation, ReproducesTableAtDefinedEpoch) {
  const GpsTime t_ref = gps_from_utc(CalendarTime{1993, 7, 1, 0, 0, 0.0});
  EXPECT_EQ(t_ref.ns, 425'520'009LL * kNsPerS);  // GPS - UTC = 9 s from 1993-07-01
  const NavData nav = nominal_constellation(t_ref);
  double max_raan = 0.0, max_u = 0.0;
  for (int prn = 1; prn <= 24; ++prn) {
    const GpsEphemeris& e = nearest(nav, gps_sat(prn), t_ref);
    const SatState s = gps_sat_state(e, t_ref);
    const Elements el = elements(to_frame(s, kTableGha, e.omega_dot_radps));
    const SlotRef& ref = kTable[prn - 1];
    const double d_raan = std::abs(wrap(el.raan - ref.raan_deg * kDeg));
    const double d_u = std::abs(wrap(el.arg_lat - ref.arg_lat_deg * kDeg));
    max_raan = std::max(max_raan, d_raan);
    max_u = std::max(max_u, d_u);
    EXPECT_LT(d_raan, 1e-8) << "PRN " << prn;
    EXPECT_LT(d_u, 1e-8) << "PRN " << prn;
  }
  std::printf("[ nominal ] at 1993-07-01 0000Z: max |RAAN - table| = %.2e rad, "
              "max |u - table| = %.2e rad\n",
              max_raan, max_u);

  // The table's GHA is the Greenwich sidereal angle at its epoch: GMST at 0h UT1 by the
  // IAU 1982 expression, T in Julian centuries from J2000.0 (JD 2449169.5 - 2451545.0).
  const double tc = (2449169.5 - 2451545.0) / 36525.0;
  double gmst_s = 24110.54841 + 8640184.812866 * tc + 0.093104 * tc * tc - 6.2e-6 * tc * tc * tc;
  gmst_s = std::fmod(gmst_s, 86400.0);
  if (gmst_s < 0) gmst_s += 86400.0;
  const double table_gha_s = kTableGha / (2.0 * kPiD) * 86400.0;
  EXPECT_NEAR(gmst_s, table_gha_s, 2.0);
  std::printf("[ nominal ] GMST(1993-07-01 0h UT1) = %.2f s, table GHA = %.2f s of sidereal "
              "time\n",
              gmst_s, table_gha_s);
}

// Coverage: 100 ground points (a Fibonacci lattice, uniform over the sphere) over 24 h every
// 10 min. Every point sees at least 4 satellites above 5 deg, and PDOP <= 6 holds at >= 98 %
// of the point-epochs (the SPS PS PDOP availability standard for the baseline constellation).
TEST(NominalConstellation, GlobalCoverageAndPdop) {
  const NavData nav = nominal_constellation(kScenario);
  const int n_points = 100;
  std::vector<Geodetic> grid;
  const double golden = kPiD * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < n_points; ++i) {
    const double z = 1.0 - (2.0 * i + 1.0) / n_points;
    const double lon = std::remainder(golden * i, 2.0 * kPiD);
    grid.push_back({std::asin(z) / kDeg, lon / kDeg, 0.0});
  }
  std::vector<Vec3> grid_ecef;
  for (const auto& g : grid) grid_ecef.push_back(ecef_from_geodetic(g));

  int samples = 0, pdop_ok = 0, min_visible = 99;
  double worst_pdop = 0.0;
  for (double dt = 0.0; dt < 86400.0; dt += 600.0) {
    const GpsTime t = kScenario.plus_s(dt);
    std::vector<Vec3> sats;
    for (int prn = 1; prn <= 24; ++prn)
      sats.push_back(gps_sat_state(nearest(nav, gps_sat(prn), t), t).p_ecef_m);
    for (std::size_t i = 0; i < grid.size(); ++i) {
      std::vector<AzEl> dirs;
      for (const auto& p : sats) {
        const AzEl d = azimuth_elevation(grid[i], grid_ecef[i], p);
        if (d.el_rad >= 5.0 * kDeg) dirs.push_back(d);
      }
      const int visible = static_cast<int>(dirs.size());
      min_visible = std::min(min_visible, visible);
      EXPECT_GE(visible, 4) << "lat " << grid[i].lat_deg << " lon " << grid[i].lon_deg
                            << " t+" << dt;
      const Dops d = dops_from_directions(dirs);
      ++samples;
      if (visible >= 4 && d.pdop > 0.0 && d.pdop <= 6.0) ++pdop_ok;
      if (visible >= 4) worst_pdop = std::max(worst_pdop, d.pdop);
    }
  }
  const double availability = static_cast<double>(pdop_ok) / samples;
  EXPECT_GE(availability, 0.98);
  std::printf("[ nominal ] %d point-epochs: min satellites above 5 deg = %d, "
              "PDOP <= 6 at %.2f %%, worst PDOP %.1f\n",
              samples, min_visible, 100.0 * availability, worst_pdop);
}

// Each slot gets a new data set every 2 h, as from the GPS control segment: a new toe = toc and a
// new IODE = IODC (IS-GPS-200 20.3.4.4). The new set is the same orbit parametrised at the new
// toe: over the 2 h between two toes (the cutover, where select_ephemeris changes sets, lies
// midway) both give the same position and velocity, far closer than real consecutive uploads
// agree (two curve fits of the real orbit: up to 1.6 m on the GEONET day, test_orbit.cpp).
// Across a GPS week rollover too; the sets made a day later are those already given for the
// same toe, and so are the ones a receiver renews with past the window (reuploaded()).
TEST(NominalConstellation, UploadsEveryTwoHoursContinueTheSameOrbit) {
  const GpsTime t = from_week_tow(2244, 604800.0 - 4 * 3600.0);  // Saturday 20:00 GPST
  const NavData nav = nominal_constellation(t);
  EXPECT_TRUE(nav.renews);
  std::map<int, std::map<std::int64_t, const GpsEphemeris*>> by_prn;  // PRN -> toe -> record
  for (const GpsEphemeris& e : nav.gps) by_prn[e.sat.number()][e.toe.ns] = &e;
  double max_dp = 0.0, max_dv = 0.0;
  int cutovers = 0, week_rollovers = 0;
  for (const auto& [prn, sets] : by_prn) {
    for (auto it = sets.begin(); std::next(it) != sets.end(); ++it) {
      const GpsEphemeris& a = *it->second;
      const GpsEphemeris& b = *std::next(it)->second;
      EXPECT_EQ(seconds_between(b.toe, a.toe), 7200.0);
      EXPECT_EQ(b.iode, (a.iode + 1) % 256);
      EXPECT_EQ(b.iodc, b.iode);
      if (to_week_tow(b.toe).week != to_week_tow(a.toe).week) ++week_rollovers;
      for (double tk = 0.0; tk <= 7200.0; tk += 300.0) {
        const GpsTime ti = a.toe.plus_s(tk);
        const SatState sa = gps_sat_state(a, ti), sb = gps_sat_state(b, ti);
        max_dp = std::max(max_dp, (sa.p_ecef_m - sb.p_ecef_m).norm());
        max_dv = std::max(max_dv, (sa.v_ecef_mps - sb.v_ecef_mps).norm());
      }
      const GpsTime cutover = a.toe.plus_s(3600.0);
      EXPECT_EQ(select_ephemeris(nav, gps_sat(prn), cutover.plus_s(-1.0)), &a);
      EXPECT_EQ(select_ephemeris(nav, gps_sat(prn), cutover.plus_s(1.0)), &b);
      ++cutovers;
    }
  }
  EXPECT_EQ(week_rollovers, 24);
  EXPECT_LT(max_dp, 1e-3);
  EXPECT_LT(max_dv, 1e-6);
  std::printf("[ nominal ] %d cutovers (%d across the week rollover): max position difference "
              "%.2e m, velocity %.2e m/s\n",
              cutovers, week_rollovers, max_dp, max_dv);

  // A renewal a day later: the sets of the same toe are the same, field for field.
  const NavData later = nominal_constellation(t.plus_s(86400.0));
  int same_toe = 0;
  for (const GpsEphemeris& e : later.gps) {
    const auto it = by_prn[e.sat.number()].find(e.toe.ns);
    if (it == by_prn[e.sat.number()].end()) continue;
    ++same_toe;
    EXPECT_EQ(e.iode, it->second->iode);
    EXPECT_EQ(e.m0_rad, it->second->m0_rad);
    EXPECT_EQ(e.omega0_rad, it->second->omega0_rad);
  }
  EXPECT_EQ(same_toe, 24 * 3);  // toe t + 22 h, t + 24 h, t + 26 h

  // Past the window, each slot's latest set uploaded anew (what a receiver renews with) is the
  // set the constellation makes for that toe: same IODE and the same orbit.
  double max_reupload = 0.0;
  for (const GpsEphemeris& e : later.gps) {
    const GpsEphemeris& last = *by_prn[e.sat.number()].rbegin()->second;
    if (e.toe <= last.toe) continue;
    const GpsEphemeris r = reuploaded(last, e.toe);
    EXPECT_EQ(r.iode, e.iode);
    EXPECT_EQ(r.iodc, e.iodc);
    EXPECT_EQ(r.toc, e.toc);
    EXPECT_EQ(r.transmission_tow_s, e.transmission_tow_s);
    for (double tk = -3600.0; tk <= 3600.0; tk += 1800.0)
      max_reupload = std::max(max_reupload, (gps_sat_state(r, e.toe.plus_s(tk)).p_ecef_m -
                                             gps_sat_state(e, e.toe.plus_s(tk)).p_ecef_m).norm());
  }
  EXPECT_LT(max_reupload, 1e-3);
}

}  // namespace
}  // namespace navemu
