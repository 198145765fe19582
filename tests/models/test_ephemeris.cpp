// The choice among broadcast ephemeris records (models/ephemeris.hpp): the record for a
// satellite at a time, and the spans of time a set of records supports a fix. Moved from
// tests/protocols/test_rinex.cpp with the RINEX readers; reference values are copied from the
// text of the files in ../shared/data/gnss.

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "core/nav_data.hpp"
#include "core/time.hpp"
#include "models/ephemeris.hpp"
#include "tests/rinex_data.hpp"
#include "tests/test_support.hpp"

namespace navemu {
namespace {

using test::shared_data;

GpsTime gps(int y, int mo, int d, int h, int mi, double s) {
  return gps_from_calendar(CalendarTime{y, mo, d, h, mi, s});
}

// ---------------------------------------------------------------------------------------------
// select_ephemeris

GpsEphemeris eph(SatId sat, GpsTime toe, int health = 0, double tx_tow = -1.0) {
  GpsEphemeris e;
  e.sat = sat;
  e.toe = toe;
  e.toc = toe;
  e.health = health;
  e.transmission_tow_s = tx_tow >= 0.0 ? tx_tow : to_week_tow(toe).tow_s - 7200.0;
  return e;
}

TEST(SelectEphemeris, NearestToe) {
  const GpsTime t0 = from_week_tow(2244, 36000.0);
  NavData nav;
  const SatId g1 = gps_sat(1), g2 = gps_sat(2);
  nav.gps = {eph(g1, t0), eph(g1, t0.plus_s(7200.0)), eph(g2, t0.plus_s(3600.0)),
             eph(g1, t0.plus_s(14400.0))};
  EXPECT_EQ(select_ephemeris(nav, gps_sat(1), t0.plus_s(3000.0)), &nav.gps[0]);
  EXPECT_EQ(select_ephemeris(nav, gps_sat(1), t0.plus_s(4000.0)), &nav.gps[1]);
  EXPECT_EQ(select_ephemeris(nav, gps_sat(1), t0.plus_s(7200.0)), &nav.gps[1]);
  EXPECT_EQ(select_ephemeris(nav, gps_sat(1), t0.plus_s(1e6)), &nav.gps[3]);
  EXPECT_EQ(select_ephemeris(nav, gps_sat(2), t0), &nav.gps[2]);
  EXPECT_EQ(select_ephemeris(nav, gps_sat(3), t0), nullptr);
  EXPECT_EQ(select_ephemeris(NavData{}, gps_sat(1), t0), nullptr);
}

TEST(SelectEphemeris, BeforeFirstToeTakesTheFirst) {
  const GpsTime t0 = from_week_tow(2244, 36000.0);
  NavData nav;
  const SatId g5 = gps_sat(5);
  nav.gps = {eph(g5, t0.plus_s(7200.0)), eph(g5, t0), eph(g5, t0.plus_s(14400.0))};
  EXPECT_EQ(select_ephemeris(nav, gps_sat(5), t0.plus_s(-86400.0)), &nav.gps[1]);
}

TEST(SelectEphemeris, UnhealthySkipped) {
  const GpsTime t0 = from_week_tow(2244, 36000.0);
  NavData nav;
  nav.gps = {eph(gps_sat(7), t0), eph(gps_sat(7), t0.plus_s(7200.0), 63), eph(gps_sat(9), t0, 1)};
  EXPECT_EQ(select_ephemeris(nav, gps_sat(7), t0.plus_s(7200.0)), &nav.gps[0]);
  EXPECT_EQ(select_ephemeris(nav, gps_sat(9), t0), nullptr);
}

TEST(SelectEphemeris, TiesGoToTheLaterTransmission) {
  const GpsTime t0 = from_week_tow(2244, 36000.0);
  NavData nav;
  const SatId g3 = gps_sat(3);
  nav.gps = {eph(g3, t0, 0, 30000.0), eph(g3, t0, 0, 31000.0), eph(g3, t0, 0, 29000.0)};
  EXPECT_EQ(select_ephemeris(nav, gps_sat(3), t0), &nav.gps[1]);
  // Equally far on both sides: the later transmitted record.
  nav.gps = {eph(g3, t0, 0, 30000.0), eph(g3, t0.plus_s(7200.0), 0, 37000.0)};
  EXPECT_EQ(select_ephemeris(nav, gps_sat(3), t0.plus_s(3600.0)), &nav.gps[1]);
}

TEST(SelectEphemeris, OnGeonetNavigationFile) {
  NAVEMU_REQUIRE_SHARED();
  const NavData nav = test::rinex_nav_file(shared_data("gnss/rtklib_geonet_20050402/07590920.05n"));
  // PRN 3 has records with toe 00:00 (IODE 83) and 02:00 (IODE 84) on 2005-04-02.
  const GpsEphemeris* a = select_ephemeris(nav, gps_sat(3), gps(2005, 4, 2, 0, 30, 0.0));
  ASSERT_NE(a, nullptr);
  EXPECT_EQ(a->iode, 83);
  const GpsEphemeris* b = select_ephemeris(nav, gps_sat(3), gps(2005, 4, 2, 1, 30, 0.0));
  ASSERT_NE(b, nullptr);
  EXPECT_EQ(b->iode, 84);
  const GpsEphemeris* c = select_ephemeris(nav, gps_sat(3), gps(2005, 4, 1, 12, 0, 0.0));
  ASSERT_NE(c, nullptr);
  EXPECT_EQ(c->iode, 83);
}

// ---------------------------------------------------------------------------------------------
// covered_spans: where navigation data has at least 4 satellites inside their fit intervals

TEST(CoveredSpans, FitIntervalsOfFourSatellitesMerged) {
  const GpsTime t0 = from_week_tow(2244, 36000.0);
  NavData nav;
  for (int prn = 1; prn <= 4; ++prn)
    nav.gps.insert(nav.gps.end(), {eph(gps_sat(prn), t0), eph(gps_sat(prn), t0.plus_s(7200.0))});
  // toe +- 2 h (IS-GPS-200 4 h fit), the two uploads of each PRN joined.
  std::vector<TimeSpan> spans = covered_spans(nav);
  ASSERT_EQ(spans.size(), 1u);
  EXPECT_EQ(spans[0].from, t0.plus_s(-7200.0));
  EXPECT_EQ(spans[0].to, t0.plus_s(14400.0));
  // Three satellites are not enough; one is, when asked for one.
  nav.gps.resize(6);  // PRN 4 gone
  EXPECT_TRUE(covered_spans(nav).empty());
  EXPECT_EQ(covered_spans(nav, 1).size(), 1u);
  EXPECT_EQ(covered_spans(nav, 3).size(), 1u);
}

TEST(CoveredSpans, GapsUnhealthyRecordsAndFitIntervalFlags) {
  const GpsTime t0 = from_week_tow(2244, 36000.0);
  NavData nav;
  for (int prn = 1; prn <= 4; ++prn)
    nav.gps.insert(nav.gps.end(),
                   {eph(gps_sat(prn), t0), eph(gps_sat(prn), t0.plus_s(6 * 3600.0))});
  std::vector<TimeSpan> spans = covered_spans(nav);
  ASSERT_EQ(spans.size(), 2u);  // [t0 - 2 h, t0 + 2 h] and [t0 + 4 h, t0 + 8 h]
  EXPECT_EQ(spans[0].to, t0.plus_s(7200.0));
  EXPECT_EQ(spans[1].from, t0.plus_s(4 * 3600.0));
  EXPECT_TRUE(spans[0].contains(t0.plus_s(7200.0)));
  EXPECT_FALSE(spans[0].contains(t0.plus_s(7201.0)));
  // An unhealthy record does not count: PRN 4 at 6 h marked unhealthy.
  nav.gps[7].health = 1;
  spans = covered_spans(nav);
  ASSERT_EQ(spans.size(), 1u);
  EXPECT_EQ(spans[0].to, t0.plus_s(7200.0));
  // A 6 h fit interval (fit flag 1) reaches 3 h from toe; the flag written as hours (1) counts
  // as the 4 h minimum.
  for (GpsEphemeris& e : nav.gps) e.fit_interval_h = e.toe == t0 ? 6.0 : 1.0;
  spans = covered_spans(nav);
  ASSERT_EQ(spans.size(), 1u);
  EXPECT_EQ(spans[0].from, t0.plus_s(-3 * 3600.0));
  EXPECT_EQ(spans[0].to, t0.plus_s(3 * 3600.0));
  EXPECT_TRUE(covered_spans(NavData{}).empty());
}

// Broadcast files as they come: the GEONET station's day holds data sets (toe, GPS time) from
// 2005-04-02 00:00 every 2 h to 2005-04-03 00:00, the ESBC station's from 2020-06-24 22:00 to
// 2020-06-26 00:00, the Spirent simulator's at 10:00, 12:00 and 14:00 of 2023-01-08 (the
// records' epochs in the files), each with 9 or more satellites per set: covered from the first
// toe - 2 h to the last toe + 2 h. Also prints how long reading and the check take.
TEST(CoveredSpans, BroadcastFiles) {
  NAVEMU_REQUIRE_SHARED();
  struct Case {
    const char* file;
    GpsTime from, to;
  };
  const Case cases[] = {
      {"rtklib_geonet_20050402/07590920.05n", gps(2005, 4, 1, 22, 0, 0.0), gps(2005, 4, 3, 2, 0, 0.0)},
      {"esbc_20200625/ESBC00DNK_R_20201770000_01D_MN.rnx", gps(2020, 6, 24, 20, 0, 0.0),
       gps(2020, 6, 26, 2, 0, 0.0)},
      {"spirent_simgen_static_20230108/Spirent_RINEX_GN.23N", gps(2023, 1, 8, 8, 0, 0.0),
       gps(2023, 1, 8, 16, 0, 0.0)},
  };
  for (const Case& c : cases) {
    const auto t0 = std::chrono::steady_clock::now();
    const NavData nav = test::rinex_nav_file(shared_data(std::string("gnss/") + c.file));
    const auto t1 = std::chrono::steady_clock::now();
    const std::vector<TimeSpan> spans = covered_spans(nav);
    const auto t2 = std::chrono::steady_clock::now();
    ASSERT_EQ(spans.size(), 1u) << c.file;
    EXPECT_EQ(spans[0].from, c.from) << c.file;
    EXPECT_EQ(spans[0].to, c.to) << c.file;
    using ms = std::chrono::duration<double, std::milli>;
    std::printf("[ coverage ] %s: %zu GPS records (%d of other systems): read %.1f ms, coverage %.3f ms\n",
                c.file, nav.gps.size(), nav.skipped_records, ms(t1 - t0).count(), ms(t2 - t1).count());
  }
}

}  // namespace
}  // namespace navemu
