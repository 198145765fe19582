// GPS time: week/TOW, calendar, leap seconds, parsing and formatting, against published
// reference instants.

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <string>

#include "core/errors.hpp"
#include "core/time.hpp"
#include "tests/test_support.hpp"

namespace navemu {
namespace {

constexpr std::int64_t kS = kNsPerS;

void expect_calendar(const CalendarTime& c, int y, int mo, int d, int h, int mi, double s) {
  EXPECT_EQ(c.year, y);
  EXPECT_EQ(c.month, mo);
  EXPECT_EQ(c.day, d);
  EXPECT_EQ(c.hour, h);
  EXPECT_EQ(c.minute, mi);
  EXPECT_NEAR(c.second, s, 1e-9);
}

// ---- week / TOW and calendar ----------------------------------------------------------------

TEST(TimeWeekTow, GpsEpochIsWeekZero) {
  const GpsTime t0 = gps_from_calendar({1980, 1, 6, 0, 0, 0.0});
  EXPECT_EQ(t0.ns, 0);
  const WeekTow wt = to_week_tow(t0);
  EXPECT_EQ(wt.week, 0);
  EXPECT_EQ(wt.tow_s, 0.0);
  expect_calendar(calendar_from_gps(GpsTime{0}), 1980, 1, 6, 0, 0, 0.0);
}

// The Spirent SimGEN header (../shared/data/gnss/spirent_simgen_static_20230108) gives
// 1357207140 s = 2023-01-08 09:59:00 GPST; week 2244 starts on Sunday 2023-01-08.
TEST(TimeWeekTow, SpirentScenarioStart) {
  const GpsTime t = gps_from_calendar({2023, 1, 8, 10, 0, 0.0});
  EXPECT_EQ(t.ns, 1'357'207'200 * kS);
  const WeekTow wt = to_week_tow(t);
  EXPECT_EQ(wt.week, 2244);
  EXPECT_EQ(wt.tow_s, 36000.0);
  EXPECT_EQ(from_week_tow(2244, 36000.0), t);
  EXPECT_EQ(gps_from_calendar({2023, 1, 8, 9, 59, 0.0}).ns, 1'357'207'140 * kS);
  expect_calendar(utc_from_gps(t), 2023, 1, 8, 9, 59, 42.0);
}

// First rollover of the 10-bit week (IS-GPS-200 20.3.3.3.1.1): 1999-08-22 00:00:00 GPST,
// i.e. 1999-08-21 23:59:47 UTC (13 leap seconds); second rollover 2019-04-07 (18 s).
TEST(TimeWeekTow, WeekRollovers) {
  const GpsTime r1 = from_week_tow(1024, 0.0);
  expect_calendar(calendar_from_gps(r1), 1999, 8, 22, 0, 0, 0.0);
  expect_calendar(utc_from_gps(r1), 1999, 8, 21, 23, 59, 47.0);
  EXPECT_EQ(r1.ns, 619'315'200 * kS);

  const GpsTime r2 = from_week_tow(2048, 0.0);
  expect_calendar(calendar_from_gps(r2), 2019, 4, 7, 0, 0, 0.0);
  expect_calendar(utc_from_gps(r2), 2019, 4, 6, 23, 59, 42.0);
  EXPECT_EQ(gps_from_calendar({2019, 4, 7, 0, 0, 0.0}), r2);
}

TEST(TimeWeekTow, FractionalAndNanosecondExact) {
  const GpsTime t = from_week_tow(2244, 36000.5);
  EXPECT_EQ(t.ns, (2244 * kSecondsPerWeek + 36000) * kS + 500'000'000);
  EXPECT_EQ(to_week_tow(t).tow_s, 36000.5);
  const GpsTime end = GpsTime{(2245 * kSecondsPerWeek) * kS - 1};
  const WeekTow wt = to_week_tow(end);
  EXPECT_EQ(wt.week, 2244);
  EXPECT_LT(wt.tow_s, 604800.0);
  EXPECT_NEAR(wt.tow_s, 604799.999999999, 1e-9);
  EXPECT_EQ(gps_from_calendar({2020, 6, 25, 0, 0, 12.345678901}).ns % kS, 345'678'901);
}

TEST(TimeWeekTow, NegativeTimesFloorCorrectly) {
  const WeekTow wt = to_week_tow(GpsTime{-1});
  EXPECT_EQ(wt.week, -1);
  EXPECT_NEAR(wt.tow_s, 604799.999999999, 1e-9);
  expect_calendar(calendar_from_gps(GpsTime{-1}), 1980, 1, 5, 23, 59, 59.999999999);
  expect_calendar(calendar_from_gps(GpsTime{-kSecondsPerDay * kS}), 1980, 1, 5, 0, 0, 0.0);
  EXPECT_EQ(gps_from_calendar({1980, 1, 1, 0, 0, 0.0}).ns, -5 * kSecondsPerDay * kS);
}

TEST(TimeCalendar, RoundTripAcrossLeapDays) {
  for (const CalendarTime c : {CalendarTime{2000, 2, 29, 12, 34, 56.789},
                               CalendarTime{2100, 3, 1, 0, 0, 0.0},
                               CalendarTime{2024, 12, 31, 23, 59, 59.999999999},
                               CalendarTime{1996, 2, 29, 1, 2, 3.0}}) {
    const CalendarTime back = calendar_from_gps(gps_from_calendar(c));
    expect_calendar(back, c.year, c.month, c.day, c.hour, c.minute, c.second);
  }
  // 2100 is not a leap year: 2100-02-28 + 1 day = 2100-03-01.
  EXPECT_EQ(gps_from_calendar({2100, 3, 1, 0, 0, 0.0}).ns -
                gps_from_calendar({2100, 2, 28, 0, 0, 0.0}).ns,
            kSecondsPerDay * kS);
}

TEST(TimeCalendar, DayOfYear) {
  EXPECT_EQ(day_of_year(2005, 4, 2), 92);    // RINEX file 07590920.05o
  EXPECT_EQ(day_of_year(2020, 6, 25), 177);  // ESBC00DNK_R_20201770000
  EXPECT_EQ(day_of_year(2023, 1, 8), 8);
  EXPECT_EQ(day_of_year(2024, 12, 31), 366);
  EXPECT_EQ(day_of_year(2023, 12, 31), 365);
  EXPECT_EQ(day_of_year(2000, 3, 1), 61);
}

// ---- leap seconds ----------------------------------------------------------------------------

// GPS time (s) at which each inserted second 23:59:60 UTC begins, and GPS-UTC after it;
// from the LIGO Algorithm Library table XLALLeapSeconds.h (TAI-UTC - 19 s), which is built
// from USNO tai-utc.dat / IERS Bulletin C.
struct LeapRef {
  std::int64_t gps_s;
  int after;
  const char* utc_day;  // the day ending in 23:59:60
};
constexpr std::array<LeapRef, 18> kLeapRefs{{
    {46828800, 1, "1981-06-30"},    {78364801, 2, "1982-06-30"},    {109900802, 3, "1983-06-30"},
    {173059203, 4, "1985-06-30"},   {252028804, 5, "1987-12-31"},   {315187205, 6, "1989-12-31"},
    {346723206, 7, "1990-12-31"},   {393984007, 8, "1992-06-30"},   {425520008, 9, "1993-06-30"},
    {457056009, 10, "1994-06-30"},  {504489610, 11, "1995-12-31"},  {551750411, 12, "1997-06-30"},
    {599184012, 13, "1998-12-31"},  {820108813, 14, "2005-12-31"},  {914803214, 15, "2008-12-31"},
    {1025136015, 16, "2012-06-30"}, {1119744016, 17, "2015-06-30"}, {1167264017, 18, "2016-12-31"},
}};

TEST(TimeLeap, TableMatchesReferenceInstants) {
  for (const LeapRef& r : kLeapRefs) {
    SCOPED_TRACE(r.utc_day);
    const GpsTime start{r.gps_s * kS};
    EXPECT_EQ(leap_seconds_at_gps(GpsTime{start.ns - 1}), r.after - 1);
    EXPECT_EQ(leap_seconds_at_gps(GpsTime{start.ns + kS}), r.after);
    EXPECT_EQ(format_iso_utc(start), std::string(r.utc_day) + "T23:59:60Z");
    EXPECT_EQ(format_iso_utc(GpsTime{start.ns - kS}), std::string(r.utc_day) + "T23:59:59Z");
    EXPECT_EQ(parse_time(std::string(r.utc_day) + "T23:59:60Z"), start);
  }
  EXPECT_EQ(leap_seconds_at_gps(GpsTime{0}), 0);
}

TEST(TimeLeap, SpanAcrossLeapSecondIsTwoSeconds) {
  const GpsTime before = gps_from_utc({2016, 12, 31, 23, 59, 59.0});
  const GpsTime after = gps_from_utc({2017, 1, 1, 0, 0, 0.0});
  EXPECT_EQ(after.ns - before.ns, 2 * kS);
  // 2017-01-01T00:00:00Z is Unix time 1483228800; GPS = Unix - 315964800 + 18.
  EXPECT_EQ(after.ns, (1'483'228'800 - 315'964'800 + 18) * kS);
  // The same instant from Unix time, and one before the 2016-12-31 leap second (17 s then).
  EXPECT_EQ(gps_from_unix_ns(1'483'228'800 * kS + 250'000'000).ns, after.ns + 250'000'000);
  EXPECT_EQ(gps_from_unix_ns(1'483'228'799 * kS).ns, (1'483'228'799 - 315'964'800 + 17) * kS);
  EXPECT_EQ(unix_ns_from_gps(after), 1'483'228'800 * kS);
  EXPECT_EQ(unix_ns_from_gps(GpsTime{after.ns + 250'000'000}), 1'483'228'800 * kS + 250'000'000);
  EXPECT_EQ(unix_ns_from_gps(before), 1'483'228'799 * kS);
  // During the inserted second Unix time repeats 23:59:59, as CLOCK_REALTIME does.
  EXPECT_EQ(unix_ns_from_gps(GpsTime{before.ns + kS + 250'000'000}), 1'483'228'799 * kS + 250'000'000);

  const GpsTime inside = GpsTime{before.ns + kS + 250'000'000};
  const CalendarTime c = utc_from_gps(inside);
  expect_calendar(c, 2016, 12, 31, 23, 59, 60.25);
  EXPECT_EQ(gps_from_utc(c), inside);
  EXPECT_EQ(leap_seconds_at_utc(c), 17);
  EXPECT_EQ(leap_seconds_at_utc({2016, 12, 31, 23, 59, 59.999}), 17);
  EXPECT_EQ(leap_seconds_at_utc({2017, 1, 1, 0, 0, 0.0}), 18);
}

TEST(TimeLeap, ValuesOnDatasetDays) {
  EXPECT_EQ(leap_seconds_at_utc({2005, 4, 2, 0, 0, 0.0}), 13);  // 07590920.05n LEAP SECONDS
  EXPECT_EQ(leap_seconds_at_utc({2020, 6, 25, 0, 0, 0.0}), 18);  // ESBC MN header
  EXPECT_EQ(leap_seconds_at_gps(gps_from_calendar({2005, 4, 2, 0, 0, 0.0})), 13);
  EXPECT_EQ(leap_seconds_at_gps(gps_from_calendar({2020, 6, 25, 0, 0, 0.0})), 18);
  EXPECT_EQ(leap_seconds_at_utc({1980, 1, 6, 0, 0, 0.0}), 0);
}

TEST(TimeLeap, AfterTableOverride) {
  const GpsTime late = gps_from_calendar({2030, 1, 1, 0, 0, 0.0});
  EXPECT_EQ(leap_seconds_at_gps(late), 18);
  EXPECT_EQ(leap_seconds_at_gps(late, 19), 19);
  EXPECT_EQ(leap_seconds_at_utc({2030, 1, 1, 0, 0, 0.0}, 19), 19);
  expect_calendar(utc_from_gps(late, 19), 2029, 12, 31, 23, 59, 41.0);
  EXPECT_EQ(gps_from_utc({2029, 12, 31, 23, 59, 41.0}, 19), late);
  // Inside the table the override is ignored.
  EXPECT_EQ(leap_seconds_at_gps(gps_from_calendar({2005, 4, 2, 0, 0, 0.0}), 19), 13);
  EXPECT_EQ(leap_seconds_at_utc({2005, 4, 2, 0, 0, 0.0}, 19), 13);
}

// ---- parsing ---------------------------------------------------------------------------------

TEST(TimeParse, AcceptedForms) {
  const GpsTime ref = from_week_tow(2244, 36000.0);
  EXPECT_EQ(parse_time("2023-01-08T09:59:42Z"), ref);
  EXPECT_EQ(parse_time("2023-01-08T09:59:42"), ref);
  EXPECT_EQ(parse_time("2023-01-08 09:59:42"), ref);
  EXPECT_EQ(parse_time("2023-01-08 09:59:42Z"), ref);
  EXPECT_EQ(parse_time("2244:36000"), ref);
  EXPECT_EQ(parse_time("2244:36000.0"), ref);
  const GpsTime half{ref.ns + 500'000'000};
  EXPECT_EQ(parse_time("2244:36000.5"), half);
  EXPECT_EQ(parse_time("2023-01-08T09:59:42.5Z"), half);
  EXPECT_EQ(parse_time("2023-01-08T09:59:42.123456789Z").ns, ref.ns + 123'456'789);
  EXPECT_EQ(parse_time("2023-01-08T09:59:42.1234567896Z").ns, ref.ns + 123'456'790);
  EXPECT_EQ(parse_time("0:0"), GpsTime{0});
  EXPECT_EQ(parse_time("2244:604799.999999999").ns, (2245 * kSecondsPerWeek) * kS - 1);
  EXPECT_EQ(parse_time("2016-12-31T23:59:60.5Z").ns, (1'167'264'017 * kS) + 500'000'000);
}

TEST(TimeParse, RejectedForms) {
  for (const char* bad : {"", "2023-13-08T00:00:00Z", "2023-00-08T00:00:00Z", "2023-02-29T00:00:00Z",
                          "2023-01-32T00:00:00Z", "2023-01-08T24:00:00Z", "2023-01-08T10:60:00Z",
                          "2023-01-08T23:59:60Z", "2016-12-31T23:58:60Z", "2023-01-08T10:00:61Z",
                          "2023-01-08", "2023-01-08T10:00", "2023-1-08T10:00:00Z",
                          "2023-01-08T10:00:00ZZ", "2023-01-08T10:00:00Z junk", "2023-01-08X10:00:00",
                          "2023-01-08T10:00:00.", "1979-12-31T00:00:00Z", "2244:604800",
                          "2244:700000", "-1:0", "2244:-1", "2244", "2244:", ":36000", "2244:36000x",
                          "2244:36000.", " 2244:36000", "2244:36000 ", "2244 :36000", "2244:1e3",
                          "now", "T"}) {
    SCOPED_TRACE(bad);
    EXPECT_THROW(parse_time(bad), InputError);
  }
}

TEST(TimeParse, ErrorNamesFieldAndBothForms) {
  try {
    parse_time("2023-13-08T00:00:00Z", "start_time");
    FAIL() << "no exception";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(e.field(), "start_time");
    EXPECT_NE(msg.find("start_time"), std::string::npos) << msg;
    EXPECT_NE(msg.find("month"), std::string::npos) << msg;
    EXPECT_NE(msg.find("ISO-8601"), std::string::npos) << msg;
    EXPECT_NE(msg.find("WEEK:TOW"), std::string::npos) << msg;
  }
}

// ---- formatting ------------------------------------------------------------------------------

TEST(TimeFormat, IsoAndWeekTow) {
  const GpsTime t = from_week_tow(2244, 36000.0);
  EXPECT_EQ(format_iso_utc(t), "2023-01-08T09:59:42Z");
  EXPECT_EQ(format_week_tow(t), "2244:36000.000");
  const GpsTime t5{t.ns + 500'000'000};
  EXPECT_EQ(format_iso_utc(t5), "2023-01-08T09:59:42.500Z");
  EXPECT_EQ(format_week_tow(t5), "2244:36000.500");
  EXPECT_EQ(format_week_tow(GpsTime{0}), "0:0.000");
  EXPECT_EQ(format_iso_utc(GpsTime{0}), "1980-01-06T00:00:00Z");
  EXPECT_EQ(format_iso_utc(from_week_tow(2244, 36000.0), 20), "2023-01-08T09:59:40Z");
}

TEST(TimeFormat, RoundTrips) {
  for (const char* s : {"2023-01-08T09:59:42Z", "2005-04-02T00:00:00Z", "2020-06-25T23:59:59.999Z",
                        "2016-12-31T23:59:60Z", "2016-12-31T23:59:60.999Z", "2017-01-01T00:00:00Z",
                        "1980-01-06T00:00:00Z", "2100-02-28T12:00:00.001Z"}) {
    EXPECT_EQ(format_iso_utc(parse_time(s)), s);
  }
  for (const char* s : {"2244:36000.000", "0:0.000", "1024:604799.999", "2048:0.001"}) {
    EXPECT_EQ(format_week_tow(parse_time(s)), s);
  }
}

}  // namespace
}  // namespace navemu
