// The navigation data of a scenario (emulator/nav_source.cpp): the built-in constellation
// covers any scenario; a run without a duration is told until when its file lasts; a file with
// gaps lists the intervals it covers.

#include <gtest/gtest.h>

#include <sstream>

#include "emulator/commands.hpp"
#include "core/errors.hpp"
#include "tests/test_support.hpp"

namespace navemu {
namespace {

TEST(ScenarioNav, BuiltInConstellationCoversAnyScenario) {
  std::ostringstream log;
  const GpsTime start = from_week_tow(2244, 36000.0);
  const NavData nav = load_scenario_nav("", start, 365 * 86400.0, log);
  EXPECT_FALSE(nav.gps.empty());
  EXPECT_NO_THROW(load_scenario_nav("", start, std::nullopt, log));
  EXPECT_TRUE(log.str().empty()) << log.str();
}

// The GEONET file has data for a fix until 2005-04-03 02:00 GPST (its last data sets' toe,
// 00:00, + 2 h): 14 h after 2005-04-02 12:00 GPST.
TEST(ScenarioNav, RunWithoutDurationIsToldUntilWhenTheFileLasts) {
  NAVEMU_REQUIRE_SHARED();
  const std::string file = test::shared_data("gnss/rtklib_geonet_20050402/07590920.05n").string();
  std::ostringstream log;
  const GpsTime start = gps_from_calendar(CalendarTime{2005, 4, 2, 12, 0, 0.0});
  load_scenario_nav(file, start, std::nullopt, log);
  EXPECT_EQ(log.str(), "navemu: navigation data " + file +
                           " has 4 satellites inside their fit intervals until 2005-04-03T01:59:47Z "
                           "(1317:7200.000), 14.0 h after the start; past that the receiver is left "
                           "with stale ephemerides, then none, and loses its fix\n");
  // With a duration inside, nothing to say.
  std::ostringstream quiet;
  load_scenario_nav(file, start, 3600.0, quiet);
  EXPECT_TRUE(quiet.str().empty()) << quiet.str();
}

// Data sets every 6 h (toe 10:00, 16:00, 22:00 GPST on 2023-01-08, 4 satellites each) leave
// 2 h gaps between their fit intervals; UTC is 18 s behind GPS time.
TEST(ScenarioNav, GapsAreListed) {
  const GpsTime t0 = from_week_tow(2244, 36000.0);
  NavData nav;
  nav.source = "gaps.rnx";
  for (int k : {0, 6, 12})
    for (int prn = 1; prn <= 4; ++prn) {
      GpsEphemeris e;
      e.sat = gps_sat(prn);
      e.toe = e.toc = t0.plus_s(k * 3600.0);
      nav.gps.push_back(e);
    }
  EXPECT_NO_THROW(require_nav_coverage(nav, t0, t0.plus_s(7200.0), {}));
  EXPECT_NO_THROW(require_nav_coverage(nav, t0.plus_s(5 * 3600.0), t0.plus_s(8 * 3600.0), {}));
  try {
    require_nav_coverage(nav, t0, t0.plus_s(4 * 3600.0), {});
    ADD_FAILURE() << "a scenario across a gap passed";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              "gaps.rnx: --nav: the file has data for 4 satellites inside their fit intervals only "
              "from 2023-01-08T07:59:42Z (2244:28800.000) to 2023-01-08T11:59:42Z (2244:43200.000), "
              "from 2023-01-08T13:59:42Z (2244:50400.000) to 2023-01-08T17:59:42Z (2244:64800.000), "
              "from 2023-01-08T19:59:42Z (2244:72000.000) to 2023-01-08T23:59:42Z (2244:86400.000), "
              "but the scenario runs from 2023-01-08T09:59:42Z (2244:36000.000) to "
              "2023-01-08T13:59:42Z (2244:50400.000): shorten --duration to at most 7200 s, or use "
              "a navigation file for the scenario's dates (e.g. BRDC00IGS_R_20230080000_01D_MN.rnx, "
              "the IGS daily broadcast ephemerides from CDDIS)");
  }
  // A start in a gap: the first interval long enough for the scenario is suggested.
  try {
    require_nav_coverage(nav, t0.plus_s(2.5 * 3600.0), t0.plus_s(5 * 3600.0), {});
    ADD_FAILURE() << "a scenario in a gap passed";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("set --start inside one (e.g. --start 2023-01-08T07:59:42Z)"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace navemu
