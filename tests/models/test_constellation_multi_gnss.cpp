// The built-in Galileo, BeiDou, QZSS and GLONASS constellations (models/constellation.hpp):
// their orbits against the real broadcast orbits of one day (../shared/data/gnss/esbc_20200625,
// 2020-06-25), the published places and coverage of each system, consecutive uploads that
// continue one orbit, and a receiver that tracks them all for days.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <vector>

#include "models/constellation.hpp"
#include "models/geodesy.hpp"
#include "models/measurement.hpp"
#include "models/orbit.hpp"
#include "models/solver.hpp"
#include "tests/rinex_data.hpp"
#include "tests/test_support.hpp"

namespace navemu {
namespace {

constexpr double kDeg = kPi / 180.0;
const GpsTime kT0 = from_week_tow(2111, 4 * 86400.0);  // 2020-06-25 00:00 GPST, the ESBC day
constexpr std::uint32_t kAll = (1u << 7) - 1u;

// A record's osculating semi-major axis, eccentricity and inclination from its state at t (in
// the inertial frame aligned with the ECEF one at t: v + omega_e x p).
struct Shape {
  double a_m, e, i_deg;
};
Shape shape(const SatState& s) {
  const Vec3 p = s.p_ecef_m, v = s.v_ecef_mps + Vec3(0.0, 0.0, kOmegaEarth_radps).cross(s.p_ecef_m);
  const double r = p.norm(), v2 = v.squaredNorm();
  const double a = 1.0 / (2.0 / r - v2 / kGpsMu_m3ps2);
  const Vec3 h = p.cross(v);
  const Vec3 ecc = v.cross(h) / kGpsMu_m3ps2 - p / r;
  return {a, ecc.norm(), std::acos(h.z() / h.norm()) / kDeg};
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? NAN : v[v.size() / 2];
}

// Mean a, e and i over a day (every 15 min) of the satellites `which` accepts, from the
// records select_record picks.
struct MeanShape {
  double a_m = NAN, e = NAN, i_deg = NAN;
};
template <class Which>
MeanShape day_shape(const NavData& nav, GnssSystem system, Which which) {
  std::vector<double> a, e, i;
  for (int n = system_info(system).first_number; n <= system_info(system).last_number; ++n) {
    const SatId sat(system, n);
    if (!which(sat)) continue;
    for (double dt = 0.0; dt < 86400.0; dt += 900.0) {
      const BroadcastRecord r = select_record(nav, sat, kT0.plus_s(dt));
      if (std::holds_alternative<std::monostate>(r)) continue;
      const Shape s = shape(record_sat_state(r, kT0.plus_s(dt)));
      a.push_back(s.a_m);
      e.push_back(s.e);
      i.push_back(s.i_deg);
    }
  }
  return {median(a), median(e), median(i)};
}

// Longitudes (deg E) where `sat` crosses the equator northwards over the day.
std::vector<double> ascending_crossings(const NavData& nav, SatId sat) {
  std::vector<double> out;
  double last_lat = NAN, last_lon = NAN;
  for (double dt = 0.0; dt <= 86400.0; dt += 60.0) {
    const BroadcastRecord r = select_record(nav, sat, kT0.plus_s(dt));
    if (std::holds_alternative<std::monostate>(r)) continue;
    const Geodetic g = geodetic_from_ecef(record_sat_state(r, kT0.plus_s(dt)).p_ecef_m);
    if (last_lat < 0.0 && g.lat_deg >= 0.0) out.push_back(last_lon);
    last_lat = g.lat_deg;
    last_lon = g.lon_deg;
  }
  return out;
}

bool beidou_meo(SatId s) { return s.number() >= 19 && s.number() <= 37; }
bool beidou_igso(SatId s) {
  const int n = s.number();
  return (n >= 6 && n <= 10) || n == 13 || n == 16 || (n >= 38 && n <= 40);
}

// The nominal orbits have the shapes of the real ones that broadcast that day: Galileo (not the
// two satellites launched into eccentric orbits, E14 and E18), BeiDou MEO (BDS-3) and IGSO,
// QZSS's quasi-zenith orbits (e, i) and GLONASS; the IGSO ground tracks cross the equator where
// the real first ones do; and every real GLONASS slot is on the nominal slot's frequency channel.
TEST(NominalMultiGnss, OrbitsHaveTheShapesOfTheRealBroadcastOnes) {
  const auto file = test::shared_data("gnss/esbc_20200625/ESBC00DNK_R_20201770000_01D_MN.rnx");
  if (test::shared_dir().empty()) GTEST_SKIP() << "../shared/data absent";
  const NavData real = test::rinex_nav_file(file);
  const NavData nominal = nominal_constellation(kT0, kAll);
  struct Case {
    const char* name;
    GnssSystem system;
    bool (*which)(SatId);
    double max_da_km, max_de, max_di_deg;
  };
  const Case cases[] = {
      {"Galileo", GnssSystem::kGalileo, [](SatId s) { return s.number() != 14 && s.number() != 18; }, 5.0, 0.01, 1.0},
      {"BeiDou MEO", GnssSystem::kBeidou, beidou_meo, 5.0, 0.01, 1.0},
      {"BeiDou IGSO", GnssSystem::kBeidou, beidou_igso, 10.0, 0.01, 1.5},
      {"QZSS QZO", GnssSystem::kQzss, [](SatId s) { return s.number() <= 3; }, 10.0, 0.01, 1.5},
      {"GLONASS", GnssSystem::kGlonass, [](SatId) { return true; }, 5.0, 0.01, 1.0},
  };
  for (const Case& c : cases) {
    const MeanShape r = day_shape(real, c.system, c.which), n = day_shape(nominal, c.system, c.which);
    std::printf("[ shapes  ] %-11s real a %.1f km e %.4f i %.2f deg, nominal a %.1f km e %.4f i %.2f deg\n", c.name,
                r.a_m / 1e3, r.e, r.i_deg, n.a_m / 1e3, n.e, n.i_deg);
    EXPECT_NEAR(n.a_m / 1e3, r.a_m / 1e3, c.max_da_km) << c.name;
    EXPECT_NEAR(n.e, r.e, c.max_de) << c.name;
    EXPECT_NEAR(n.i_deg, r.i_deg, c.max_di_deg) << c.name;
  }
  // The first three BDS-2 IGSO (C06-C08) cross the equator at 118 deg E (BDS-SIS-ICD 3.1), and
  // so do the built-in C38-C40.
  for (int prn : {6, 7, 8, 38, 39, 40}) {
    const std::vector<double> x = ascending_crossings(prn >= 38 ? nominal : real, SatId(GnssSystem::kBeidou, prn));
    EXPECT_EQ(x.size(), 1u) << "C" << prn;
    for (double lon : x) EXPECT_NEAR(lon, 118.0, 1.0) << "C" << prn;
  }
  std::set<int> slots;
  for (const GlonassEphemeris& e : real.glonass) {
    for (const GlonassEphemeris& f : nominal.glonass)
      if (f.sat == e.sat) {
        EXPECT_EQ(f.frequency_channel, e.frequency_channel) << e.sat.rinex();
        break;
      }
    slots.insert(e.sat.number());
  }
  EXPECT_GE(slots.size(), 22u);
}

// Each system's published places: the BeiDou GEOs stay over their longitudes (the real C05 is
// within 1 deg of its 58.75 deg E), QZSS's J07 over 127 deg E, and from Tokyo one of the three
// quasi-zenith satellites is always high (above 60 deg) while the BeiDou GEOs hold their
// elevations; at a European site each of Galileo, BeiDou and GLONASS alone shows at least 4
// satellites above 10 deg at every time of the day, 6-11 on average (the 24 GPS slots: 5, 6.8).
TEST(NominalMultiGnss, EachSystemIsWhereItsOperatorPutsIt) {
  const NavData nav = nominal_constellation(kT0, kAll);
  const auto place = [&](SatId sat, double dt) {
    return record_sat_state(select_record(nav, sat, kT0.plus_s(dt)), kT0.plus_s(dt)).p_ecef_m;
  };
  const std::pair<int, double> geos[] = {{1, 140.0}, {2, 80.0}, {3, 110.5}, {4, 160.0}, {5, 58.75}};
  for (const auto& [prn, lon] : geos)
    for (double dt = 0.0; dt < 86400.0; dt += 3600.0) {
      const Geodetic g = geodetic_from_ecef(place(SatId(GnssSystem::kBeidou, prn), dt));
      ASSERT_NEAR(g.lon_deg, lon, 0.01) << "C0" << prn << " at " << dt;
      ASSERT_NEAR(g.lat_deg, 0.0, 0.01) << "C0" << prn << " at " << dt;
    }
  for (double dt = 0.0; dt < 86400.0; dt += 3600.0) {
    const Geodetic g = geodetic_from_ecef(place(SatId(GnssSystem::kQzss, 7), dt));
    ASSERT_NEAR(g.lon_deg, 127.0, 0.01);
    ASSERT_NEAR(g.lat_deg, 0.0, 0.01);
  }
  if (!test::shared_dir().empty()) {
    const NavData real = test::rinex_nav_file(test::shared_data("gnss/esbc_20200625/ESBC00DNK_R_20201770000_01D_MN.rnx"));
    const SatId c05(GnssSystem::kBeidou, 5);
    const Geodetic g = geodetic_from_ecef(record_sat_state(select_record(real, c05, kT0), kT0).p_ecef_m);
    EXPECT_NEAR(g.lon_deg, 58.75, 1.0);
  }

  const Geodetic tokyo{35.68, 139.69, 40.0};
  const Vec3 p_tokyo = ecef_from_geodetic(tokyo);
  double lowest_best_qzo = 90.0;
  for (double dt = 0.0; dt < 86400.0; dt += 300.0) {
    double best = -90.0;
    for (int prn = 1; prn <= 3; ++prn)
      best = std::max(best, azimuth_elevation(tokyo, p_tokyo, place(SatId(GnssSystem::kQzss, prn), dt)).el_rad / kDeg);
    lowest_best_qzo = std::min(lowest_best_qzo, best);
  }
  EXPECT_GT(lowest_best_qzo, 60.0);

  const Geodetic europe{50.0, 10.0, 200.0};
  const Vec3 p_europe = ecef_from_geodetic(europe);
  for (GnssSystem system : {GnssSystem::kGps, GnssSystem::kGalileo, GnssSystem::kBeidou, GnssSystem::kGlonass}) {
    int fewest = 99, sum = 0, epochs = 0;
    for (double dt = 0.0; dt < 86400.0; dt += 600.0, ++epochs) {
      int above = 0;
      for (int n = system_info(system).first_number; n <= system_info(system).last_number; ++n) {
        const BroadcastRecord r = select_record(nav, SatId(system, n), kT0.plus_s(dt));
        if (std::holds_alternative<std::monostate>(r)) continue;
        const Vec3 p = record_sat_state(r, kT0.plus_s(dt)).p_ecef_m;
        if (azimuth_elevation(europe, p_europe, p).el_rad > 10.0 * kDeg) ++above;
      }
      fewest = std::min(fewest, above);
      sum += above;
    }
    const double mean = static_cast<double>(sum) / epochs;
    std::printf("[ sky     ] %-8s at 50 N 10 E above 10 deg: fewest %d, mean %.1f\n", system_info(system).name, fewest,
                mean);
    EXPECT_GE(fewest, 4) << system_info(system).name;
    EXPECT_GE(mean, 6.0) << system_info(system).name;
    EXPECT_LE(mean, 11.0) << system_info(system).name;
  }
}

// The largest position difference of consecutive records of each satellite along the span
// between their reference times (every 5 min).
template <class Eph>
double worst_step_m(const std::vector<Eph>& records) {
  std::map<SatId, std::vector<const Eph*>> by_sat;
  for (const Eph& e : records) by_sat[e.sat].push_back(&e);
  double worst = 0.0;
  for (const auto& [sat, list] : by_sat)
    for (std::size_t k = 1; k < list.size(); ++k) {
      const GpsTime from = reference_time(*list[k - 1]), to = reference_time(*list[k]);
      EXPECT_GT(to, from);
      for (GpsTime t = from; t <= to; t = t.plus_s(300.0))
        worst = std::max(worst, (record_sat_state(list[k - 1], t).p_ecef_m - record_sat_state(list[k], t).p_ecef_m).norm());
    }
  return worst;
}

// Consecutive uploads continue one orbit: every satellite's sets agree along the span between
// their reference times (Keplerian sets to the micrometre; GLONASS's integrated states to the
// millimetre), the sets of a later day's constellation for the same toe are the same, and
// GLONASS's tb fall at 15 and 45 min past the hour of UTC (ICD 4.4).
TEST(NominalMultiGnss, ConsecutiveUploadsContinueOneOrbit) {
  const NavData nav = nominal_constellation(kT0, kAll);
  EXPECT_EQ(nav.galileo.size(), 24u * 15);
  EXPECT_EQ(nav.beidou.size(), 32u * 15);
  EXPECT_EQ(nav.qzss.size(), 4u * 15);
  EXPECT_EQ(nav.glonass.size(), 24u * 55);  // tb from t - 30 min to t + 26 h 30 min
  const double galileo = worst_step_m(nav.galileo), beidou = worst_step_m(nav.beidou), qzss = worst_step_m(nav.qzss),
               glonass = worst_step_m(nav.glonass);
  std::printf("[ uploads ] consecutive sets differ by at most: Galileo %.1e m, BeiDou %.1e m, QZSS %.1e m, "
              "GLONASS %.1e m\n",
              galileo, beidou, qzss, glonass);
  EXPECT_LT(galileo, 1e-5);
  EXPECT_LT(beidou, 1e-5);
  EXPECT_LT(qzss, 1e-5);
  EXPECT_LT(glonass, 1e-3);
  for (const GlonassEphemeris& e : nav.glonass) {
    const CalendarTime utc = utc_from_gps(e.tb);
    ASSERT_TRUE(utc.minute == 15 || utc.minute == 45) << format_iso_utc(e.tb);
    ASSERT_EQ(utc.second, 0.0);
  }
  // A day later, the sets of the same toe are the same (Galileo, BeiDou: made anew from the
  // orbits), and BeiDou's toe are on BDT's hours.
  const NavData later = nominal_constellation(kT0.plus_s(86400.0), kAll);
  int same = 0;
  for (const GalileoEphemeris& e : later.galileo)
    for (const GalileoEphemeris& f : nav.galileo)
      if (f.sat == e.sat && f.toe == e.toe) {
        EXPECT_EQ(e.m0_rad, f.m0_rad);
        EXPECT_EQ(e.omega0_rad, f.omega0_rad);
        EXPECT_EQ(e.iod_nav, f.iod_nav);
        ++same;
      }
  EXPECT_EQ(same, 24 * 3);
  for (const BeidouEphemeris& e : nav.beidou)
    ASSERT_EQ(std::fmod(to_week_tow(e.toe.plus_s(-kGpsMinusBdt_s)).tow_s, 7200.0), 0.0);
}

// A receiver tracking every system on the built-in constellations for three days (the data
// made for the start hold 26 h; they are renewed twice): every epoch at Tokyo has GPS,
// Galileo, BeiDou and GLONASS satellites and QZSS ones, each with a record no older than its
// system's upload interval allows, and with every error source off the position comes back
// to the millimetre.
TEST(NominalMultiGnss, AReceiverTracksEverySystemForDays) {
  const NavData nav = nominal_constellation(kT0, kAll);
  MeasurementConfig cfg;
  cfg.errors = ErrorSwitches{false, false, false, false, false, false};
  cfg.systems = kAll;
  MeasurementGenerator gen(nav, cfg);
  const Vec3 p = ecef_from_geodetic(Geodetic{35.68, 139.69, 40.0});
  SolverOptions o;
  o.elevation_mask_deg = 0.0;
  std::map<GnssSystem, std::size_t> fewest;
  double worst_m = 0.0, oldest_glonass_s = 0.0;
  for (double dt = 0.0; dt <= 3 * 86400.0; dt += 600.0) {
    const GpsTime t = kT0.plus_s(dt);
    const EpochMeasurements e = gen.generate(t, p);
    std::map<GnssSystem, std::size_t> count;
    for (const SatMeasurement& m : e.sats) {
      ++count[m.sat.system()];
      if (const auto* g = std::get_if<const GlonassEphemeris*>(&m.record))
        oldest_glonass_s = std::max(oldest_glonass_s, std::abs(seconds_between(t, (*g)->tb)));
    }
    for (GnssSystem s : {GnssSystem::kGps, GnssSystem::kGalileo, GnssSystem::kBeidou, GnssSystem::kQzss,
                         GnssSystem::kGlonass}) {
      const auto [it, fresh] = fewest.try_emplace(s, count[s]);
      if (!fresh) it->second = std::min(it->second, count[s]);
    }
    const Solution sol = solve(gen.solver_input(e), e.t_receiver, o);
    ASSERT_EQ(sol.fix, FixType::k3D) << "t + " << dt << " s";
    worst_m = std::max(worst_m, (sol.p_ecef_m - p).norm());
  }
  for (const auto& [s, n] : fewest) {
    std::printf("[ renewal ] %-8s fewest satellites at Tokyo over 3 days: %zu\n", system_info(s).name, n);
    EXPECT_GE(n, s == GnssSystem::kQzss ? 2u : 4u) << system_info(s).name;
  }
  EXPECT_LE(oldest_glonass_s, kMaxGlonassAge_s);
  EXPECT_LT(worst_m, 1e-3);
}

}  // namespace
}  // namespace navemu
