// RINEX 3 observation files written by protocols/rinex_writer.hpp are read by RTKLIB's
// rnx2rtkp (Debian package rtklib), which solves them to the position they were made for.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <vector>

#include "core/time.hpp"
#include "models/atmosphere.hpp"
#include "models/ephemeris.hpp"
#include "models/geodesy.hpp"
#include "models/orbit.hpp"
#include "protocols/rinex.hpp"
#include "protocols/rinex_writer.hpp"
#include "tests/rinex_data.hpp"
#include "tests/test_support.hpp"

namespace navemu {
namespace {

GpsTime gps(int y, int mo, int d, int h, int mi, double s) {
  return gps_from_calendar(CalendarTime{y, mo, d, h, mi, s});
}

// A satellite's observations, LLI and SSI blank.
SatObs obs_of(SatId sat, std::vector<double> values) {
  SatObs s;
  s.system = sat.info().rinex_letter;
  s.number = sat.number();
  s.lli.assign(values.size(), 0);
  s.ssi.assign(values.size(), 0);
  s.values = std::move(values);
  return s;
}

// Error-free C1C pseudoranges for a static receiver at GEONET station 0759's precise position,
// built so that RTKLIB's single-point corrections cancel exactly: satellite clock with TGD
// (IS-GPS-200 20.3.3.3.3.2), broadcast Klobuchar ionosphere, Saastamoinen troposphere in a
// standard atmosphere with 70 % humidity. RTKLIB must then land on the true position.
TEST(RinexWriter, RtklibPositionsFromWrittenFile) {
  NAVEMU_REQUIRE_SHARED();
  const NavData nav = test::rinex_nav_file(test::shared_data("gnss/rtklib_geonet_20050402/07590920.05n"));
  ASSERT_TRUE(nav.klobuchar.has_value());
  const Vec3 truth(-3976219.1454, 3382371.6073, 3652511.1964);
  const Geodetic geo = geodetic_from_ecef(truth);
  const Meteo meteo = standard_atmosphere(geo.h_m, 0.7);
  const double c = kSpeedOfLight_mps;

  ObsHeader h;
  h.types['G'] = {"C1C", "S1C"};
  h.marker_name = "0759";
  h.approx_position_ecef_m = truth;
  h.interval_s = 30.0;
  h.leap_seconds = nav.leap_seconds;
  std::vector<ObsEpoch> epochs;
  const GpsTime t0 = gps(2005, 4, 2, 0, 0, 0.0);
  for (int k = 0; k <= 20; ++k) {
    ObsEpoch e;
    e.time = t0.plus_s(30.0 * k);
    for (int prn = 1; prn <= 32; ++prn) {
      const SatId sat = gps_sat(prn);
      const GpsEphemeris* eph = select_ephemeris(nav, sat, e.time);
      if (eph == nullptr || std::fabs(seconds_between(e.time, eph->toe)) > 7200.0) continue;
      const SatGeometry g = gps_sat_geometry(*eph, e.time, truth);
      if (g.dir.el_rad < 15.0 * kDegToRad) continue;
      const double iono_m = c * klobuchar_delay_l1_s(*nav.klobuchar, geo, g.dir, e.time);
      const double tropo_m = saastamoinen_delay(geo, g.dir.el_rad, meteo).total_m();
      const double p = g.range_m - c * (g.sat.clock_bias_s - eph->tgd_s) + iono_m + tropo_m;
      e.sats.push_back(obs_of(sat, {p, 45.0}));
    }
    ASSERT_GE(e.sats.size(), 5u) << "epoch " << k;
    epochs.push_back(std::move(e));
  }

  const auto dir = std::filesystem::path(::testing::TempDir()) / "navemu_rinex_writer_rtklib";
  std::filesystem::create_directories(dir);
  const auto obs = dir / "0759sim.obs";
  {
    std::ofstream f(obs, std::ios::binary);
    ObsWriterInfo info;
    info.marker_type = "GEODETIC";
    write_rinex3_obs(f, h, epochs, info);
    ASSERT_TRUE(f.good());
  }
  {
    std::ofstream conf(dir / "spp.conf");
    conf << "pos1-posmode=single\npos1-elmask=15\npos1-ionoopt=brdc\npos1-tropopt=saas\n"
            "pos1-navsys=1\n";
  }
  const auto pos = dir / "out.pos";
  std::filesystem::remove(pos);
  const auto nav_file = test::shared_data("gnss/rtklib_geonet_20050402/07590920.05n");
  const auto rtk = test::run_command(
      "rnx2rtkp -k " + test::shell_quote((dir / "spp.conf").string()) +
      " -p 0 -e -sys G -m 15 -o " + test::shell_quote(pos.string()) + " " +
      test::shell_quote(obs.string()) + " " + test::shell_quote(nav_file.string()) + " 2>/dev/null");
  ASSERT_EQ(rtk.exit_code, 0) << "rnx2rtkp (Debian package rtklib) missing or failed";

  const std::vector<test::RtklibFix> sol = test::read_rtklib_ecef_pos(pos);
  ASSERT_EQ(sol.size(), epochs.size()) << "RTKLIB solved " << sol.size() << " of "
                                       << epochs.size() << " epochs";
  double max_err = 0.0;
  for (const test::RtklibFix& fix : sol) max_err = std::max(max_err, (fix.p_ecef_m - truth).norm());
  std::printf("RTKLIB single-point solutions from the written file: %zu epochs, max 3D error "
              "%.4f m\n",
              sol.size(), max_err);
  EXPECT_LE(max_err, 0.05);
}

}  // namespace
}  // namespace navemu
