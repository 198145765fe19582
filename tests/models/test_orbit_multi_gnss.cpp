// Galileo, BeiDou, QZSS and GLONASS broadcast orbits and clocks (models/orbit.hpp
// broadcast_sat_state, glonass_sat_state) against independent references of one day,
// 2020-06-25, in ../shared/data/gnss/esbc_20200625 (RTKLIB's own positions from the same file:
// tests/integration/test_orbit_rtklib.cpp):
//  - Galileo and GLONASS against the precise orbits of the CNES/CLS analysis centre
//    (GRG0MGXFIN SP3, the satellites' centres of mass);
//  - BeiDou's geostationary C05 at its published orbital slot, 58.75 deg E;
//  - Galileo, BeiDou and GLONASS against the pseudoranges the station ESBC00DNK measured at its
//    surveyed place, which hold the orbits, the clocks, the group delays and the time systems
//    together;
//  - consecutive data sets of one satellite, which the operators fit independently, where
//    their fit intervals meet.

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "models/orbit.hpp"
#include "models/solver.hpp"
#include "protocols/rinex.hpp"
#include "tests/rinex_data.hpp"
#include "tests/test_support.hpp"

namespace navemu {
namespace {

const char* const kDay = "gnss/esbc_20200625/";

const NavData& esbc_nav() {
  static const NavData nav = test::rinex_nav_file(test::shared_data(std::string(kDay) + "ESBC00DNK_R_20201770000_01D_MN.rnx"));
  return nav;
}

// The data set a receiver has for `sat` at t: the one with the latest toe at most 10 minutes
// ahead of t (Galileo and BeiDou upload a set shortly before its toe), no older than 3 h; for
// Galileo the I/NAV one (data sources bit 0), as an E1 receiver decodes it. Galileo's sets are
// fitted forwards from their toe: used hours before it they are metres off.
template <class Eph>
const Eph* latest(const std::vector<Eph>& records, SatId sat, GpsTime t) {
  const Eph* best = nullptr;
  for (const Eph& e : records) {
    if (!(e.sat == sat)) continue;
    if constexpr (requires { e.data_sources; })
      if (!(e.data_sources & 1)) continue;
    const double age_s = seconds_between(t, e.toe);
    if (age_s < -600.0 || age_s > 3.0 * 3600.0) continue;
    if (best == nullptr || best->toe < e.toe) best = &e;
  }
  return best;
}

struct Sp3Position {
  GpsTime t;
  SatId sat;
  Vec3 p_ecef_m;
};

// SP3-c/d position records ("PE01 x y z clk", km) under their epoch lines ("*  2020  6 25 ..."),
// time system GPS (the file's %c line).
std::vector<Sp3Position> read_sp3(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::vector<Sp3Position> out;
  std::string line;
  GpsTime t;
  while (std::getline(in, line)) {
    if (line.rfind("* ", 0) == 0) {
      std::istringstream s(line.substr(1));
      CalendarTime c;
      s >> c.year >> c.month >> c.day >> c.hour >> c.minute >> c.second;
      t = gps_from_calendar(c);
    } else if (line.size() > 46 && line[0] == 'P') {
      const std::optional<SatId> sat = SatId::from_rinex(line[1], std::stoi(line.substr(2, 2)));
      if (!sat) continue;
      std::istringstream s(line.substr(4));
      Vec3 p;
      s >> p.x() >> p.y() >> p.z();
      out.push_back({t, *sat, p * 1000.0});
    }
  }
  return out;
}

// Galileo's broadcast orbits against the precise ones. The broadcast orbit is the antenna
// phase centre's; the SP3 the centre of mass, which lies some 0.6-1.1 m farther from the Earth
// (the IGS/MGEX Galileo antenna offsets, z towards the Earth). Published signal-in-space
// orbit errors of Galileo in 2020 are at the decimetre level (Montenbruck et al., "Galileo
// broadcast ephemeris and clock errors", GPS Solutions 2018: orbit-only SISRE ~0.2 m), so
// along and across track the two agree to well under a metre and radially to the offset.
TEST(OrbitGalileo, BroadcastAgreesWithThePreciseOrbitsOfTheDay) {
  NAVEMU_REQUIRE_SHARED();
  const NavData& nav = esbc_nav();
  const std::vector<Sp3Position> sp3 = read_sp3(test::shared_data(std::string(kDay) + "GRG0MGXFIN_20201770000_01D_15M_ORB.SP3"));
  int n = 0;
  double sum_r = 0.0, sum2_a = 0.0, sum2_c = 0.0, max_3d = 0.0;
  std::vector<double> radial;
  for (const Sp3Position& ref : sp3) {
    if (ref.sat.system() != GnssSystem::kGalileo) continue;
    const GalileoEphemeris* e = latest(nav.galileo, ref.sat, ref.t);
    if (e == nullptr || e->health != 0) continue;
    const SatState s = broadcast_sat_state(*e, ref.t);
    const Vec3 d = s.p_ecef_m - ref.p_ecef_m;
    const Vec3 r_hat = ref.p_ecef_m.normalized();
    const Vec3 c_hat = ref.p_ecef_m.cross(s.v_ecef_mps).normalized();
    const Vec3 a_hat = c_hat.cross(r_hat);
    radial.push_back(d.dot(r_hat));
    sum_r += d.dot(r_hat);
    sum2_a += d.dot(a_hat) * d.dot(a_hat);
    sum2_c += d.dot(c_hat) * d.dot(c_hat);
    max_3d = std::max(max_3d, d.norm());
    ++n;
  }
  ASSERT_GT(n, 1000) << "24 satellites x 96 epochs, less those far from a healthy I/NAV data set";
  const double mean_r = sum_r / n, rms_a = std::sqrt(sum2_a / n), rms_c = std::sqrt(sum2_c / n);
  std::sort(radial.begin(), radial.end());
  fmt::print("Galileo broadcast - precise over {} positions: radial mean {:+.2f} m (median {:+.2f}), along RMS "
             "{:.2f} m, across RMS {:.2f} m, 3D max {:.2f} m\n",
             n, mean_r, radial[radial.size() / 2], rms_a, rms_c, max_3d);
  EXPECT_LT(mean_r, -0.4) << "the antenna lies towards the Earth";
  EXPECT_GT(mean_r, -1.3);
  EXPECT_LT(rms_a, 0.5);
  EXPECT_LT(rms_c, 0.5);
  EXPECT_LT(max_3d, 2.5);
}

// The GLONASS record nearest to t (every 30 min, tb at 15 and 45 min past the hour), within
// 15 min: the interval over which its state vector is integrated.
const GlonassEphemeris* nearest_glonass(const NavData& nav, SatId sat, GpsTime t) {
  const GlonassEphemeris* best = nullptr;
  for (const GlonassEphemeris& e : nav.glonass)
    if (e.sat == sat && e.health == 0 && std::abs(seconds_between(t, e.tb)) <= 900.0 &&
        (best == nullptr || std::abs(seconds_between(t, e.tb)) < std::abs(seconds_between(t, best->tb))))
      best = &e;
  return best;
}

// GLONASS's broadcast state vectors, integrated (GLONASS ICD A.3.1.2), against the precise
// orbits. The broadcast position is the antenna phase centre's, some 2.3 m nearer the Earth
// than the centre of mass on GLONASS-M (IGS ANTEX z offsets), and good to a few metres
// (Montenbruck et al., "Broadcast versus precise ephemerides: a multi-GNSS perspective", GPS
// Solutions 2015: GLONASS orbit errors of 2-4 m 3D RMS).
TEST(OrbitGlonass, IntegratedStateVectorsAgreeWithThePreciseOrbitsOfTheDay) {
  NAVEMU_REQUIRE_SHARED();
  const NavData& nav = esbc_nav();
  const std::vector<Sp3Position> sp3 = read_sp3(test::shared_data(std::string(kDay) + "GRG0MGXFIN_20201770000_01D_15M_ORB.SP3"));
  std::vector<double> errors;
  double sum_r = 0.0;
  for (const Sp3Position& ref : sp3) {
    if (ref.sat.system() != GnssSystem::kGlonass) continue;
    const GlonassEphemeris* e = nearest_glonass(nav, ref.sat, ref.t);
    if (e == nullptr) continue;
    const Vec3 d = glonass_sat_state(*e, ref.t).p_ecef_m - ref.p_ecef_m;
    sum_r += d.dot(ref.p_ecef_m.normalized());
    errors.push_back(d.norm());
  }
  ASSERT_GT(errors.size(), 700u) << "the satellites in view of the station, whose records it logged";
  double sum2 = 0.0;
  for (double x : errors) sum2 += x * x;
  std::sort(errors.begin(), errors.end());
  const double rms = std::sqrt(sum2 / static_cast<double>(errors.size()));
  fmt::print("GLONASS broadcast - precise over {} positions: 3D RMS {:.2f} m, median {:.2f} m, 95 % {:.2f} m, radial "
             "mean {:+.2f} m\n",
             errors.size(), rms, errors[errors.size() / 2], errors[errors.size() * 95 / 100],
             sum_r / static_cast<double>(errors.size()));
  EXPECT_LT(rms, 5.0);
  EXPECT_LT(errors[errors.size() * 95 / 100], 8.0);
  EXPECT_LT(sum_r / static_cast<double>(errors.size()), -1.0) << "the antenna lies towards the Earth";
  EXPECT_GT(sum_r / static_cast<double>(errors.size()), -3.0);
}

// C05 is BeiDou's geostationary satellite at 58.75 deg E (China Satellite Navigation Office,
// BDS constellation status, GEO slots 58.75, 80, 110.5, 140, 160 deg E). Its broadcast orbit
// is fitted in a frame tilted by 5 degrees (BDS-SIS-ICD-B1I 3.0 5.2.4.12): computed as a
// medium orbit it would lie degrees off the equator.
// GlonassArc (the receiver's once-integrated arc of a record) gives the states of
// glonass_sat_state to a tenth of a millimetre (the two integrations' own step errors) over the
// record's whole span and beyond, for every record of the day: far below the broadcast orbit's
// metres.
TEST(OrbitGlonass, TheOnceIntegratedArcGivesTheSameStates) {
  NAVEMU_REQUIRE_SHARED();
  const NavData& nav = esbc_nav();
  ASSERT_FALSE(nav.glonass.empty());
  double worst_p_m = 0.0, worst_v_mps = 0.0, worst_clock_s = 0.0;
  for (const GlonassEphemeris& e : nav.glonass) {
    const GlonassArc arc(e);
    EXPECT_TRUE(arc.of(e));
    for (double dt = -1200.0; dt <= 1200.0; dt += 7.3) {
      const GpsTime t = e.tb.plus_s(dt);
      const SatState a = arc.state(t), b = glonass_sat_state(e, t);
      worst_p_m = std::max(worst_p_m, (a.p_ecef_m - b.p_ecef_m).norm());
      worst_v_mps = std::max(worst_v_mps, (a.v_ecef_mps - b.v_ecef_mps).norm());
      worst_clock_s = std::max(worst_clock_s, std::abs(a.clock_bias_s - b.clock_bias_s));
    }
  }
  std::printf("[ glonass ] arc against glonass_sat_state over +-20 min of %zu records: %.2e m, %.2e m/s\n",
              nav.glonass.size(), worst_p_m, worst_v_mps);
  EXPECT_LT(worst_p_m, 1e-3);
  EXPECT_LT(worst_v_mps, 1e-7);
  EXPECT_EQ(worst_clock_s, 0.0);
}

// The receiver's solver takes a GLONASS satellite's state from the arc it keeps: the same
// measurement as integrating from tb to a millimetre (0.15 mm here); an arc made for another
// record is not used (the solver integrates instead: identical to no arc).
TEST(OrbitGlonass, TheSolversMeasurementFromTheArcEqualsTheIntegratedOne) {
  NAVEMU_REQUIRE_SHARED();
  const NavData& nav = esbc_nav();
  ASSERT_GE(nav.glonass.size(), 2u);
  const GlonassEphemeris& e = nav.glonass.front();
  const GlonassEphemeris& other = nav.glonass.back();
  const GlonassArc arc(e), other_arc(other);
  for (double dt = -900.0; dt <= 900.0; dt += 113.0) {
    const GpsTime t = e.tb.plus_s(dt);
    const RangeMeasurement plain = make_range_measurement(e, t, 2.1e7, 1234.5);
    const RangeMeasurement from_arc = make_range_measurement(e, t, 2.1e7, 1234.5, &arc);
    const RangeMeasurement wrong_arc = make_range_measurement(e, t, 2.1e7, 1234.5, &other_arc);
    EXPECT_LT((from_arc.sat_p_ecef_m - plain.sat_p_ecef_m).norm(), 1e-3) << dt;
    EXPECT_LT((from_arc.sat_v_ecef_mps - plain.sat_v_ecef_mps).norm(), 1e-7) << dt;
    EXPECT_EQ(from_arc.sat_clock_m, plain.sat_clock_m);
    EXPECT_EQ(wrong_arc.sat_p_ecef_m, plain.sat_p_ecef_m);
  }
}

TEST(OrbitBeidou, TheGeostationaryC05StaysOverItsSlot) {
  NAVEMU_REQUIRE_SHARED();
  const NavData& nav = esbc_nav();
  int n = 0;
  for (const BeidouEphemeris& e : nav.beidou) {
    if (!(e.sat == SatId(GnssSystem::kBeidou, 5))) continue;
    for (const double dt_s : {-1800.0, 0.0, 1800.0}) {
      const SatState s = broadcast_sat_state(e, e.toe.plus_s(dt_s));
      const Geodetic g = geodetic_from_ecef(s.p_ecef_m);
      EXPECT_NEAR(g.lon_deg, 58.75, 0.3) << e.source;
      EXPECT_NEAR(g.lat_deg, 0.0, 2.0) << e.source;
      EXPECT_NEAR(s.p_ecef_m.norm(), 42'164'000.0, 50'000.0) << e.source;
      // Its velocity is the derivative of its position (the rotated frame's, Table 5-11).
      const Vec3 diff = (broadcast_sat_state(e, e.toe.plus_s(dt_s + 0.5)).p_ecef_m -
                         broadcast_sat_state(e, e.toe.plus_s(dt_s - 0.5)).p_ecef_m);
      EXPECT_LT((s.v_ecef_mps - diff).norm(), 1e-3) << e.source;
      ++n;
    }
  }
  EXPECT_GE(n, 3 * 20);
}

// Consecutive data sets of one satellite are fitted to the operator's orbit one after the
// other; where the later takes over (halfway between their toes) they give the same position
// to the size of the fit error. A wrong time system or frame shifts them by kilometres.
TEST(OrbitMultiGnss, ConsecutiveDataSetsMeet) {
  NAVEMU_REQUIRE_SHARED();
  const NavData& nav = esbc_nav();
  const auto check = [](const auto& records, const char* system, double bound_m) {
    std::map<SatId, std::vector<const KeplerEphemeris*>> by_sat;
    for (const auto& e : records) by_sat[e.sat].push_back(&e);
    std::vector<double> gaps;
    for (auto& [sat, list] : by_sat) {
      std::sort(list.begin(), list.end(), [](auto* a, auto* b) { return a->toe < b->toe; });
      for (std::size_t i = 1; i < list.size(); ++i) {
        const double dt = seconds_between(list[i]->toe, list[i - 1]->toe);
        if (dt <= 0.0 || dt > 3.0 * 3600.0) continue;
        const GpsTime mid = list[i - 1]->toe.plus_s(dt / 2.0);
        gaps.push_back((broadcast_sat_state(*list[i], mid).p_ecef_m - broadcast_sat_state(*list[i - 1], mid).p_ecef_m).norm());
      }
    }
    ASSERT_FALSE(gaps.empty()) << system;
    std::sort(gaps.begin(), gaps.end());
    fmt::print("{}: {} consecutive data sets meet within {:.2f} m (median), {:.2f} m (95 %), {:.2f} m (max)\n", system,
               gaps.size(), gaps[gaps.size() / 2], gaps[gaps.size() * 95 / 100], gaps.back());
    EXPECT_LT(gaps[gaps.size() * 95 / 100], bound_m) << system;
  };
  check(nav.galileo, "Galileo", 2.0);
  check(nav.beidou, "BeiDou", 2.0);
  check(nav.qzss, "QZSS", 3.0);
  check(nav.gps, "GPS", 3.0);
  // GLONASS: each state vector integrated to the midpoint with the next (30 min apart).
  std::vector<double> gaps;
  for (std::size_t i = 0; i < nav.glonass.size(); ++i)
    for (std::size_t j = i + 1; j < nav.glonass.size(); ++j) {
      const GlonassEphemeris &a = nav.glonass[i], &b = nav.glonass[j];
      const double dt = seconds_between(b.tb, a.tb);
      if (!(a.sat == b.sat) || dt != 1800.0) continue;
      const GpsTime mid = a.tb.plus_s(dt / 2.0);
      gaps.push_back((glonass_sat_state(a, mid).p_ecef_m - glonass_sat_state(b, mid).p_ecef_m).norm());
      break;
    }
  ASSERT_GT(gaps.size(), 100u);
  std::sort(gaps.begin(), gaps.end());
  fmt::print("GLONASS: {} consecutive state vectors meet within {:.2f} m (median), {:.2f} m (95 %), {:.2f} m (max)\n",
             gaps.size(), gaps[gaps.size() / 2], gaps[gaps.size() * 95 / 100], gaps.back());
  EXPECT_LT(gaps[gaps.size() * 95 / 100], 5.0);
}

// The station's own pseudoranges (ESBC00DNK, first hour of the day, 30 s) against the
// geometric range from its surveyed place to each satellite at transmission, the satellite
// clock with its single-frequency group delay (Galileo E1: BGD E1/E5b, OS SIS ICD 5.1.5; BeiDou
// B1I: TGD1, BDS-SIS-ICD-B1I 5.2.4.10; GLONASS L1OF: none, its clock is L1's) and a standard
// troposphere. GLONASS's receiver biases differ by frequency channel by up to metres.
// What is left per epoch and system is the receiver clock (with its inter-system bias), taken
// out as the median, and the ionosphere, a few metres at night: a wrong clock, group delay or
// time system leaves tens of metres to kilometres.
TEST(OrbitMultiGnss, StationPseudorangesCloseAtItsSurveyedPlace) {
  NAVEMU_REQUIRE_SHARED();
  const NavData& nav = esbc_nav();
  const ObsData obs = test::rinex_obs_file(test::shared_data(std::string(kDay) + "ESBC00DNK_R_20201770000_01H_30S_MO.rnx"));
  const Vec3 station(3582105.2910, 532589.7313, 5232754.8054);  // APPROX POSITION XYZ
  const ReceiverPlace rx = receiver_place(station);
  struct System {
    char letter;
    const char* code;
    const char* name;
  };
  // (QZSS, over the western Pacific, is not in view from Denmark.)
  for (const System sys : {System{'E', "C1C", "Galileo"}, System{'C', "C2I", "BeiDou"}, System{'R', "C1C", "GLONASS"}}) {
    const int k = obs.header.index_of(sys.letter, sys.code);
    ASSERT_GE(k, 0) << sys.name;
    std::vector<double> residuals;
    std::size_t epochs = 0;
    for (std::size_t i = 0; i < obs.epochs.size(); i += 10) {
      const ObsEpoch& ep = obs.epochs[i];
      std::vector<double> r;
      for (const SatObs& so : ep.sats) {
        const std::optional<SatId> sat = so.sat();
        if (!sat || so.system != sys.letter) continue;
        const double p = so.values[static_cast<std::size_t>(k)];
        if (std::isnan(p)) continue;
        std::function<SatState(GpsTime)> state;
        double group_delay_s = 0.0;
        if (sys.letter == 'E') {
          if (const GalileoEphemeris* g = latest(nav.galileo, *sat, ep.time)) {
            group_delay_s = g->bgd_e1e5b_s;
            state = [g](GpsTime t) { return broadcast_sat_state(*g, t); };
          }
        } else if (sys.letter == 'C') {
          if (const BeidouEphemeris* b = latest(nav.beidou, *sat, ep.time)) {
            group_delay_s = b->tgd1_s;
            state = [b](GpsTime t) { return broadcast_sat_state(*b, t); };
          }
        } else if (const GlonassEphemeris* g = nearest_glonass(nav, *sat, ep.time)) {
          state = [g](GpsTime t) { return glonass_sat_state(*g, t); };
        }
        if (!state) continue;
        // Transmission in system time: t_rx - P/c - dt_sat (IS-GPS-200 20.3.3.3.3.1).
        const double dt_sat = state(ep.time.plus_s(-p / kSpeedOfLight_mps)).clock_bias_s;
        const double tau = p / kSpeedOfLight_mps + dt_sat;
        const SatState s = state(ep.time.plus_s(-tau));
        const Vec3 p_sat = rotate_earth(s.p_ecef_m, tau);
        const AzEl dir = azimuth_elevation(rx.R_enu_from_ecef, rx.p_ecef_m, p_sat);
        if (dir.el_rad < 15.0 * kPi / 180.0) continue;
        const double tropo_m = 2.4 / std::sin(dir.el_rad);
        r.push_back(p - (p_sat - station).norm() + kSpeedOfLight_mps * (s.clock_bias_s - group_delay_s) - tropo_m);
      }
      if (r.size() < 3) continue;
      std::vector<double> sorted = r;
      std::sort(sorted.begin(), sorted.end());
      const double clock = sorted[sorted.size() / 2];
      for (double x : r) residuals.push_back(x - clock);
      ++epochs;
    }
    ASSERT_GE(epochs, 10u) << sys.name;
    double sum2 = 0.0, worst = 0.0;
    for (double x : residuals) {
      sum2 += x * x;
      worst = std::max(worst, std::abs(x));
    }
    const double rms = std::sqrt(sum2 / static_cast<double>(residuals.size()));
    fmt::print("{} {}: {} pseudoranges in {} epochs close to {:.2f} m RMS, {:.2f} m at worst\n", sys.name, sys.code,
               residuals.size(), epochs, rms, worst);
    EXPECT_LT(rms, 5.0) << sys.name;
    EXPECT_LT(worst, 20.0) << sys.name;
  }
}

}  // namespace
}  // namespace navemu
