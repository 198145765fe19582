// Satellite positions and clocks of every system against RTKLIB's (rnx2rtkp, Debian package
// rtklib) from the same broadcast file: rnx2rtkp's trace at level 4 writes, for each satellite
// of each epoch it processes, the transmission time (GPS time, to the microsecond), the
// satellite's ECEF position at that time and its clock with the relativistic term
// ("sat=NN rs= x y z dts= ns"). navemu's broadcast_sat_state / glonass_sat_state give the same
// from the records RTKLIB may have chosen (the nearest in time of each satellite's records).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <string>

#include <fmt/format.h>

#include "models/orbit.hpp"
#include "tests/rinex_data.hpp"
#include "tests/test_support.hpp"

namespace navemu {
namespace {

// RTKLIB's satellite numbers (rtklib.h satno() with GLONASS, Galileo, QZSS and BeiDou enabled,
// as the Debian build is): GPS 1-32, GLONASS 33-59, Galileo 60-95, QZSS 96-105 (PRN 193-202),
// BeiDou from 106.
std::optional<SatId> rtklib_sat(int n) {
  if (n >= 1 && n <= 32) return SatId(GnssSystem::kGps, n);
  if (n <= 59) return SatId(GnssSystem::kGlonass, n - 32);
  if (n <= 95) return SatId(GnssSystem::kGalileo, n - 59);
  if (n <= 105) return SatId(GnssSystem::kQzss, n - 95);
  if (n <= 105 + 63) return SatId(GnssSystem::kBeidou, n - 105);
  return std::nullopt;
}

struct Difference {
  int n = 0;
  double position_m = 0.0, clock_ns = 0.0;  // the largest
};

TEST(OrbitRtklib, EverySystemsSatellitesWhereRtklibPutsThem) {
  NAVEMU_REQUIRE_SHARED();
  const auto day = test::shared_data("gnss/esbc_20200625");
  const auto obs = day / "ESBC00DNK_R_20201770000_01H_30S_MO.rnx", nav_file = day / "ESBC00DNK_R_20201770000_01D_MN.rnx";
  const auto dir = std::filesystem::path(::testing::TempDir()) / "navemu_orbit_rtklib";
  std::filesystem::create_directories(dir);
  const auto pos = dir / "out.pos", trace = dir / "out.pos.trace";
  std::filesystem::remove(trace);
  const auto rtk = test::run_command("rnx2rtkp -x 4 -p 0 -sys G,R,E,C,J -ts 2020/06/25 00:00:00 -te 2020/06/25 00:05:00 -o " +
                                     test::shell_quote(pos.string()) + " " + test::shell_quote(obs.string()) + " " +
                                     test::shell_quote(nav_file.string()) + " >/dev/null 2>&1");
  ASSERT_EQ(rtk.exit_code, 0) << "rnx2rtkp (Debian package rtklib) missing or failed";
  const NavData nav = test::rinex_nav_file(nav_file);

  std::ifstream in(trace);
  ASSERT_TRUE(in) << trace;
  std::map<GnssSystem, Difference> by_system;
  std::string line;
  while (std::getline(in, line)) {
    // "4 2020/06/24 23:59:59.914260 sat= 2 rs= 21815349.091 -13786112.641 -5530031.645 dts= -477281.492 ..."
    const std::size_t s = line.find(" sat="), r = line.find(" rs="), d = line.find(" dts=");
    if (line.rfind("4 ", 0) != 0 || s == std::string::npos || r == std::string::npos || d == std::string::npos) continue;
    CalendarTime c;
    char sep = 0;
    std::istringstream t(line.substr(2, s - 2));
    t >> c.year >> sep >> c.month >> sep >> c.day >> c.hour >> sep >> c.minute >> sep >> c.second;
    const std::optional<SatId> sat = rtklib_sat(std::stoi(line.substr(s + 5)));
    if (!t || !sat) continue;
    std::istringstream v(line.substr(r + 4));
    Vec3 p_rtklib;
    v >> p_rtklib.x() >> p_rtklib.y() >> p_rtklib.z();
    const double dts_ns = std::stod(line.substr(d + 5));
    if (p_rtklib.norm() == 0.0) continue;  // RTKLIB found no usable record for it
    const GpsTime when = gps_from_calendar(c);

    // The closest of navemu's states from this satellite's records near that time, position
    // and clock together (1 ns of clock as 0.3 m: Galileo's I/NAV and F/NAV sets of one issue
    // share the orbit and differ in the clock).
    double best_score = std::numeric_limits<double>::infinity(), best_m = best_score, best_clock_ns = 0.0;
    const auto consider = [&](const SatState& st) {
      const double dp = (st.p_ecef_m - p_rtklib).norm(), dclk_ns = std::abs(st.clock_bias_s * 1e9 - dts_ns);
      if (dp + 0.3 * dclk_ns < best_score) {
        best_score = dp + 0.3 * dclk_ns;
        best_m = dp;
        best_clock_ns = dclk_ns;
      }
    };
    const auto kepler = [&](const auto& records) {
      for (const auto& e : records)
        if (e.sat == *sat && std::abs(seconds_between(when, e.toe)) < 4.0 * 3600.0) consider(broadcast_sat_state(e, when));
    };
    switch (sat->system()) {
      case GnssSystem::kGps: kepler(nav.gps); break;
      case GnssSystem::kGalileo: kepler(nav.galileo); break;
      case GnssSystem::kBeidou: kepler(nav.beidou); break;
      case GnssSystem::kQzss: kepler(nav.qzss); break;
      case GnssSystem::kGlonass:
        for (const GlonassEphemeris& e : nav.glonass)
          if (e.sat == *sat && std::abs(seconds_between(when, e.tb)) < 1800.0) consider(glonass_sat_state(e, when));
        break;
      default: break;
    }
    Difference& diff = by_system[sat->system()];
    ++diff.n;
    diff.position_m = std::max(diff.position_m, best_m);
    diff.clock_ns = std::max(diff.clock_ns, best_clock_ns);
  }
  for (const auto& [system, diff] : by_system)
    fmt::print("{}: {} satellite states, position within {:.4f} m, clock within {:.4f} ns of RTKLIB's\n",
               system_info(system).name, diff.n, diff.position_m, diff.clock_ns);
  for (const GnssSystem system : {GnssSystem::kGps, GnssSystem::kGalileo, GnssSystem::kBeidou, GnssSystem::kGlonass}) {
    const Difference& diff = by_system[system];
    EXPECT_GT(diff.n, 50) << system_info(system).name << ": 11 epochs of the satellites in view";
    EXPECT_LE(diff.position_m, 0.01) << system_info(system).name;  // the 1 cm
    EXPECT_LE(diff.clock_ns, 0.03) << system_info(system).name;    // 1 cm of range
  }
}

}  // namespace
}  // namespace navemu
