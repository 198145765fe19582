#pragma once
// GPS time as integer nanoseconds since the GPS epoch (1980-01-06 00:00:00 UTC), and its
// conversions to week/time-of-week, calendar dates and UTC (with leap seconds).
//
// Every model takes a GpsTime; only the scheduler reads a clock (../shared/DESIGN.md).

#include <compare>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace navemu {

inline constexpr std::int64_t kNsPerS = 1'000'000'000;
inline constexpr std::int64_t kSecondsPerWeek = 604'800;
inline constexpr std::int64_t kSecondsPerDay = 86'400;

struct GpsTime {
  std::int64_t ns = 0;  // nanoseconds since 1980-01-06 00:00:00 GPS time

  static constexpr GpsTime from_seconds(double s_since_epoch) {
    return GpsTime{static_cast<std::int64_t>(s_since_epoch * 1e9 + (s_since_epoch >= 0 ? 0.5 : -0.5))};
  }
  constexpr double seconds() const { return static_cast<double>(ns) * 1e-9; }

  // Shift by a (possibly fractional) number of seconds, rounded to the nanosecond.
  constexpr GpsTime plus_s(double dt_s) const {
    return GpsTime{ns + static_cast<std::int64_t>(dt_s * 1e9 + (dt_s >= 0 ? 0.5 : -0.5))};
  }
  friend constexpr auto operator<=>(GpsTime, GpsTime) = default;
};

// a - b in seconds (exact to the nanosecond for spans up to ~100 days, ~1e-7 s beyond).
constexpr double seconds_between(GpsTime a, GpsTime b) {
  return static_cast<double>(a.ns - b.ns) * 1e-9;
}

// Full (not modulo-1024) GPS week and time of week.
struct WeekTow {
  int week = 0;
  double tow_s = 0.0;  // [0, 604800)
};

GpsTime from_week_tow(int week, double tow_s);
WeekTow to_week_tow(GpsTime t);

// A broken-down calendar time, in whatever time scale the caller says (GPS or UTC).
struct CalendarTime {
  int year = 1980;
  int month = 1;
  int day = 6;
  int hour = 0;
  int minute = 0;
  double second = 0.0;  // may be 60.x for a UTC leap second
};

// Calendar date/time read in the GPS time scale (how RINEX writes GPS epochs).
GpsTime gps_from_calendar(const CalendarTime& c);
CalendarTime calendar_from_gps(GpsTime t);

// GPS - UTC in whole seconds at a UTC instant, from the table of leap seconds
// (IERS Bulletin C; 18 s since 2017-01-01). For instants after the table's end the last
// value applies, unless `after_table_s` (e.g. the LEAP SECONDS of a RINEX header) is given.
int leap_seconds_at_utc(const CalendarTime& utc, std::optional<int> after_table_s = {});
// The same, looked up from a GPS instant.
int leap_seconds_at_gps(GpsTime t, std::optional<int> after_table_s = {});

GpsTime gps_from_utc(const CalendarTime& utc, std::optional<int> after_table_s = {});

// The other systems' time scales, in whole seconds from GPS time or UTC:
// BDT = GPST - 14 s (BDS-SIS-ICD-B1I 3.0, 3.3); GLONASS time = UTC(SU) + 3 h (GLONASS ICD
// 5.1, 3.3.3); GST runs with GPST (Galileo OS SIS ICD 2.1, 5.1.2; the GGTO aside). Week 0 of
// BDT began at GPS week 1356 (2006-01-01), week 0 of GST at GPS week 1024 (1999-08-22).
inline constexpr int kGpsMinusBdt_s = 14;
inline constexpr int kBdtWeek0InGpsWeeks = 1356;
inline constexpr int kGstWeek0InGpsWeeks = 1024;
inline constexpr int kGlonassMinusUtc_s = 3 * 3600;
CalendarTime utc_from_gps(GpsTime t, std::optional<int> after_table_s = {});
// Unix time (nanoseconds since 1970-01-01 UTC, leap seconds excluded, as CLOCK_REALTIME) to GPS
// time: the GPS epoch is Unix second 315964800, plus GPS - UTC at that instant.
GpsTime gps_from_unix_ns(std::int64_t unix_ns);
// The inverse: GPS time to Unix nanoseconds. During an inserted leap second (23:59:60.x) Unix
// time repeats the second before it, as CLOCK_REALTIME does.
std::int64_t unix_ns_from_gps(GpsTime t);

// Day of year (1..366) of a calendar date.
int day_of_year(int year, int month, int day);

// Parses a user-given time: ISO-8601 UTC ("2023-01-08T09:59:42Z", fractional seconds
// allowed, "Z" optional) or GPS week and time of week ("2244:36000", "2244:36000.5").
// Throws InputError naming `field` on anything else.
GpsTime parse_time(std::string_view text, std::string_view field = "time");

// "2023-01-08T09:59:42Z" (UTC, milliseconds shown only when non-zero).
std::string format_iso_utc(GpsTime t, std::optional<int> after_table_s = {});
// "2244:36000.000"
std::string format_week_tow(GpsTime t);

}  // namespace navemu
