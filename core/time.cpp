#include "core/time.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <limits>

#include "core/errors.hpp"

namespace navemu {

namespace {

constexpr std::int64_t kNsPerDay = kSecondsPerDay * kNsPerS;
constexpr std::int64_t kNsPerWeek = kSecondsPerWeek * kNsPerS;

// Floor division and the matching non-negative remainder (C++ '/' truncates toward zero).
constexpr std::int64_t floor_div(std::int64_t a, std::int64_t b) {
  const std::int64_t q = a / b;
  return (a % b != 0 && ((a < 0) != (b < 0))) ? q - 1 : q;
}

// Days since 1970-01-01 of a proleptic Gregorian date, and back. H. Hinnant,
// "chrono-Compatible Low-Level Date Algorithms" (days_from_civil / civil_from_days).
constexpr std::int64_t days_from_civil(std::int64_t y, std::int64_t m, std::int64_t d) {
  y -= m <= 2 ? 1 : 0;
  const std::int64_t era = floor_div(y, 400);
  const std::int64_t yoe = y - era * 400;                                // [0, 399]
  const std::int64_t doy = (153 * (m + (m > 2 ? -3 : 9)) + 2) / 5 + d - 1;  // [0, 365]
  const std::int64_t doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;        // [0, 146096]
  return era * 146097 + doe - 719468;
}

struct Ymd {
  std::int64_t y;
  int m;
  int d;
};

constexpr Ymd civil_from_days(std::int64_t z) {
  z += 719468;
  const std::int64_t era = floor_div(z, 146097);
  const std::int64_t doe = z - era * 146097;                                   // [0, 146096]
  const std::int64_t yoe = (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365;  // [0, 399]
  const std::int64_t y = yoe + era * 400;
  const std::int64_t doy = doe - (365 * yoe + yoe / 4 - yoe / 100);            // [0, 365]
  const std::int64_t mp = (5 * doy + 2) / 153;                                 // [0, 11]
  const std::int64_t d = doy - (153 * mp + 2) / 5 + 1;                         // [1, 31]
  const std::int64_t m = mp < 10 ? mp + 3 : mp - 9;                            // [1, 12]
  return Ymd{m <= 2 ? y + 1 : y, static_cast<int>(m), static_cast<int>(d)};
}

// The GPS epoch 1980-01-06 in days since 1970-01-01.
constexpr std::int64_t kGpsEpochDays = days_from_civil(1980, 1, 6);
static_assert(kGpsEpochDays == 3657);

constexpr bool is_leap_year(std::int64_t y) { return (y % 4 == 0 && y % 100 != 0) || y % 400 == 0; }

constexpr int days_in_month(std::int64_t y, int m) {
  constexpr std::array<int, 12> kDays{31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  return m == 2 && is_leap_year(y) ? 29 : kDays[static_cast<std::size_t>(m - 1)];
}

// Nanoseconds since the GPS epoch of a calendar reading taken as a uniform 86400-s-per-day
// scale (no leap seconds): the time scale in which the calendar is read.
constexpr std::int64_t ns_from_fields(std::int64_t y, int mo, int d, int h, int mi, std::int64_t sec_ns) {
  const std::int64_t days = days_from_civil(y, mo, d) - kGpsEpochDays;
  return days * kNsPerDay + (static_cast<std::int64_t>(h) * 3600 + mi * 60) * kNsPerS + sec_ns;
}

std::int64_t ns_from_seconds(double s) { return std::llround(s * 1e9); }

// Broken-down calendar time with integer seconds and nanoseconds.
struct CalNs {
  std::int64_t year = 1980;
  int month = 1;
  int day = 6;
  int hour = 0;
  int minute = 0;
  int second = 0;  // 60 during a UTC leap second
  std::int64_t nano = 0;
};

CalNs cal_ns_from_ns(std::int64_t ns) {
  const std::int64_t days = floor_div(ns, kNsPerDay);
  const std::int64_t in_day = ns - days * kNsPerDay;
  const Ymd ymd = civil_from_days(days + kGpsEpochDays);
  const std::int64_t s = in_day / kNsPerS;
  CalNs c;
  c.year = ymd.y;
  c.month = ymd.m;
  c.day = ymd.d;
  c.hour = static_cast<int>(s / 3600);
  c.minute = static_cast<int>((s / 60) % 60);
  c.second = static_cast<int>(s % 60);
  c.nano = in_day % kNsPerS;
  return c;
}

CalendarTime to_calendar(const CalNs& c) {
  CalendarTime out;
  out.year = static_cast<int>(c.year);
  out.month = c.month;
  out.day = c.day;
  out.hour = c.hour;
  out.minute = c.minute;
  out.second = static_cast<double>(c.second) + static_cast<double>(c.nano) * 1e-9;
  return out;
}

// GPS - UTC (IERS Bulletin C; IS-GPS-200 section 20.3.3.5.2.4 defines delta t_LS as this
// whole-second offset). Each entry: the UTC date at whose 00:00:00 the new value takes effect
// (the leap second 23:59:60 is inserted at the end of the previous day).
struct LeapEntry {
  int year;
  int month;
  int day;
  int gps_minus_utc_s;
  std::int64_t utc_ns;  // the date's 00:00:00 on the uniform UTC-reading scale (no leap seconds)
  std::int64_t gps_ns;  // the GPS instant at which UTC reads that 00:00:00
};
// The instants are computed at compile time: every conversion of a time stamp looks them up.
constexpr LeapEntry leap(int year, int month, int day, int gps_minus_utc_s) {
  const std::int64_t utc_ns = ns_from_fields(year, month, day, 0, 0, 0);
  return LeapEntry{year, month, day, gps_minus_utc_s, utc_ns, utc_ns + gps_minus_utc_s * kNsPerS};
}
constexpr std::array<LeapEntry, 18> kLeapTable{{
    leap(1981, 7, 1, 1),  leap(1982, 7, 1, 2),  leap(1983, 7, 1, 3),  leap(1985, 7, 1, 4),
    leap(1988, 1, 1, 5),  leap(1990, 1, 1, 6),  leap(1991, 1, 1, 7),  leap(1992, 7, 1, 8),
    leap(1993, 7, 1, 9),  leap(1994, 7, 1, 10), leap(1996, 1, 1, 11), leap(1997, 7, 1, 12),
    leap(1999, 1, 1, 13), leap(2006, 1, 1, 14), leap(2009, 1, 1, 15), leap(2012, 7, 1, 16),
    leap(2015, 7, 1, 17), leap(2017, 1, 1, 18),
}};

// GPS - UTC at a UTC reading on the uniform scale; `in_leap_second` for 23:59:60.x, whose
// uniform reading equals the next day's 00:00:00.x but which still carries the old offset.
int leap_at_utc_ns(std::int64_t utc_uniform_ns, bool in_leap_second, std::optional<int> after_table_s) {
  const std::int64_t t = in_leap_second ? utc_uniform_ns - kNsPerS : utc_uniform_ns;
  if (after_table_s && t >= kLeapTable.back().utc_ns) return *after_table_s;
  int value = 0;
  for (const LeapEntry& e : kLeapTable) {
    if (t >= e.utc_ns) value = e.gps_minus_utc_s;
  }
  return value;
}

// UTC broken down from a GPS instant, showing 23:59:60.x during an inserted second.
// Whether t lies in an inserted leap second (UTC 23:59:60.x).
bool in_inserted_second(GpsTime t) {
  for (const LeapEntry& e : kLeapTable) {
    const std::int64_t start = e.gps_ns;
    if (t.ns >= start - kNsPerS && t.ns < start) return true;
  }
  return false;
}

CalNs utc_cal_ns_from_gps(GpsTime t, std::optional<int> after_table_s) {
  const std::int64_t utc_ns = t.ns - static_cast<std::int64_t>(leap_seconds_at_gps(t, after_table_s)) * kNsPerS;
  if (in_inserted_second(t)) {
    // Read the previous second and label it 60.
    CalNs c = cal_ns_from_ns(utc_ns - kNsPerS);
    c.second += 1;
    return c;
  }
  return cal_ns_from_ns(utc_ns);
}

bool is_leap_second_day(std::int64_t y, int m, int d) {
  // True when a leap second was inserted at the end of this UTC day.
  const std::int64_t next = days_from_civil(y, m, d) + 1;
  for (const LeapEntry& e : kLeapTable) {
    if (days_from_civil(e.year, e.month, e.day) == next) return true;
  }
  return false;
}

// ---- parse_time helpers --------------------------------------------------------------------

constexpr std::string_view kAcceptedForms =
    "expected ISO-8601 UTC (e.g. 2023-01-08T09:59:42Z or 2023-01-08 09:59:42.5) or GPS "
    "WEEK:TOW (e.g. 2244:36000 or 2244:36000.5)";

[[noreturn]] void reject(std::string_view text, std::string_view field, std::string_view why) {
  throw InputError(std::string(field),
                   fmt::format("'{}' is not a valid time ({}); {}", text, why, kAcceptedForms));
}

bool is_digit(char ch) { return ch >= '0' && ch <= '9'; }

// Reads exactly `n` digits at `pos`.
bool read_fixed(std::string_view s, std::size_t& pos, std::size_t n, std::int64_t& out) {
  if (pos + n > s.size()) return false;
  std::int64_t v = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const char ch = s[pos + i];
    if (!is_digit(ch)) return false;
    v = v * 10 + (ch - '0');
  }
  pos += n;
  out = v;
  return true;
}

// Reads 1..max_digits digits at `pos`.
bool read_uint(std::string_view s, std::size_t& pos, std::size_t max_digits, std::int64_t& out) {
  std::size_t n = 0;
  std::int64_t v = 0;
  while (pos + n < s.size() && is_digit(s[pos + n])) {
    if (n == max_digits) return false;
    v = v * 10 + (s[pos + n] - '0');
    ++n;
  }
  if (n == 0) return false;
  pos += n;
  out = v;
  return true;
}

// Reads an optional fraction ".ddd…" at `pos` as nanoseconds, rounded half up on the tenth
// digit (further digits are ignored). A lone '.' is an error.
bool read_fraction_ns(std::string_view s, std::size_t& pos, std::int64_t& ns) {
  ns = 0;
  if (pos >= s.size() || s[pos] != '.') return true;
  ++pos;
  std::size_t n = 0;
  std::int64_t scale = 100'000'000;
  bool round_up = false;
  while (pos < s.size() && is_digit(s[pos])) {
    const int digit = s[pos] - '0';
    if (n < 9) {
      ns += digit * scale;
      scale /= 10;
    } else if (n == 9) {
      round_up = digit >= 5;
    }
    ++n;
    ++pos;
  }
  if (n == 0) return false;
  if (round_up) ns += 1;  // may reach 1e9: the caller adds it to whole seconds
  return true;
}

GpsTime parse_iso(std::string_view s, std::string_view field) {
  std::size_t pos = 0;
  std::int64_t y = 0, mo = 0, d = 0, h = 0, mi = 0, sec = 0, frac = 0;
  const auto sep = [&](char c) {
    if (pos < s.size() && s[pos] == c) {
      ++pos;
      return true;
    }
    return false;
  };
  if (!read_fixed(s, pos, 4, y) || !sep('-') || !read_fixed(s, pos, 2, mo) || !sep('-') ||
      !read_fixed(s, pos, 2, d))
    reject(s, field, "date is not YYYY-MM-DD");
  if (!(sep('T') || sep(' '))) reject(s, field, "expected 'T' or ' ' between date and time");
  if (!read_fixed(s, pos, 2, h) || !sep(':') || !read_fixed(s, pos, 2, mi) || !sep(':') ||
      !read_fixed(s, pos, 2, sec))
    reject(s, field, "time of day is not hh:mm:ss");
  if (!read_fraction_ns(s, pos, frac)) reject(s, field, "no digits after the decimal point");
  sep('Z');
  if (pos != s.size()) reject(s, field, fmt::format("unexpected '{}' at the end", s.substr(pos)));

  if (mo < 1 || mo > 12) reject(s, field, fmt::format("month {} out of range 1..12", mo));
  const int m = static_cast<int>(mo);
  if (d < 1 || d > days_in_month(y, m))
    reject(s, field, fmt::format("day {} out of range for {:04}-{:02}", d, y, mo));
  if (h > 23) reject(s, field, fmt::format("hour {} out of range 0..23", h));
  if (mi > 59) reject(s, field, fmt::format("minute {} out of range 0..59", mi));
  const bool leap_second = sec == 60;
  if (sec > 60 || (leap_second && !(h == 23 && mi == 59 && is_leap_second_day(y, m, static_cast<int>(d)))))
    reject(s, field, fmt::format("second {} out of range (60 only at a UTC leap second)", sec));
  if (y < 1980 || (y == 1980 && mo == 1 && d < 6)) reject(s, field, "before the GPS epoch 1980-01-06");
  if (y > 2200) reject(s, field, "after the year 2200");

  const std::int64_t uniform = ns_from_fields(y, m, static_cast<int>(d), static_cast<int>(h),
                                              static_cast<int>(mi), sec * kNsPerS + frac);
  const int leap = leap_at_utc_ns(uniform, leap_second, std::nullopt);
  return GpsTime{uniform + static_cast<std::int64_t>(leap) * kNsPerS};
}

GpsTime parse_week_tow(std::string_view s, std::string_view field) {
  std::size_t pos = 0;
  std::int64_t week = 0, tow = 0, frac = 0;
  if (!read_uint(s, pos, 5, week)) reject(s, field, "week is not a non-negative whole number");
  if (pos >= s.size() || s[pos] != ':') reject(s, field, "expected ':' after the week");
  ++pos;
  if (!read_uint(s, pos, 6, tow)) reject(s, field, "time of week is not a non-negative number");
  if (!read_fraction_ns(s, pos, frac)) reject(s, field, "no digits after the decimal point");
  if (pos != s.size()) reject(s, field, fmt::format("unexpected '{}' at the end", s.substr(pos)));
  if (week > 10'000) reject(s, field, fmt::format("week {} out of range 0..10000", week));
  const std::int64_t tow_ns = tow * kNsPerS + frac;
  if (tow_ns >= kNsPerWeek) reject(s, field, "time of week must be below 604800 s");
  return GpsTime{week * kNsPerWeek + tow_ns};
}

}  // namespace

// ---- week / time of week (IS-GPS-200 section 20.3.3.3.1.1: full week count since the epoch) ---

GpsTime from_week_tow(int week, double tow_s) {
  return GpsTime{static_cast<std::int64_t>(week) * kNsPerWeek + ns_from_seconds(tow_s)};
}

WeekTow to_week_tow(GpsTime t) {
  const std::int64_t week = floor_div(t.ns, kNsPerWeek);
  const std::int64_t rem = t.ns - week * kNsPerWeek;
  // Whole seconds and nanoseconds are converted separately so that tow_s is the double
  // nearest to the exact value.
  const double tow = static_cast<double>(rem / kNsPerS) + static_cast<double>(rem % kNsPerS) * 1e-9;
  return WeekTow{static_cast<int>(week), tow};
}

// ---- calendar ------------------------------------------------------------------------------

GpsTime gps_from_calendar(const CalendarTime& c) {
  return GpsTime{ns_from_fields(c.year, c.month, c.day, c.hour, c.minute, ns_from_seconds(c.second))};
}

CalendarTime calendar_from_gps(GpsTime t) { return to_calendar(cal_ns_from_ns(t.ns)); }

int day_of_year(int year, int month, int day) {
  return static_cast<int>(days_from_civil(year, month, day) - days_from_civil(year, 1, 1)) + 1;
}

// ---- UTC -----------------------------------------------------------------------------------

int leap_seconds_at_utc(const CalendarTime& utc, std::optional<int> after_table_s) {
  const std::int64_t uniform =
      ns_from_fields(utc.year, utc.month, utc.day, utc.hour, utc.minute, ns_from_seconds(utc.second));
  return leap_at_utc_ns(uniform, utc.second >= 60.0, after_table_s);
}

int leap_seconds_at_gps(GpsTime t, std::optional<int> after_table_s) {
  if (after_table_s && t.ns >= kLeapTable.back().gps_ns) return *after_table_s;
  int value = 0;
  for (const LeapEntry& e : kLeapTable) {
    if (t.ns >= e.gps_ns) value = e.gps_minus_utc_s;
  }
  return value;
}

GpsTime gps_from_utc(const CalendarTime& utc, std::optional<int> after_table_s) {
  const std::int64_t uniform =
      ns_from_fields(utc.year, utc.month, utc.day, utc.hour, utc.minute, ns_from_seconds(utc.second));
  const int leap = leap_at_utc_ns(uniform, utc.second >= 60.0, after_table_s);
  return GpsTime{uniform + static_cast<std::int64_t>(leap) * kNsPerS};
}

constexpr std::int64_t kGpsEpochUnix_s = 315'964'800;  // Unix time of 1980-01-06T00:00:00Z

GpsTime gps_from_unix_ns(std::int64_t unix_ns) {
  const std::int64_t unix_s = unix_ns / kNsPerS - (unix_ns % kNsPerS < 0 ? 1 : 0);
  const CalendarTime utc = calendar_from_gps(GpsTime{(unix_s - kGpsEpochUnix_s) * kNsPerS});
  return GpsTime{gps_from_utc(utc).ns + (unix_ns - unix_s * kNsPerS)};
}

std::int64_t unix_ns_from_gps(GpsTime t) {
  // UTC since the GPS epoch, without a calendar; 23:59:60.x reads as 23:59:59.x (POSIX).
  std::int64_t utc_ns = t.ns - static_cast<std::int64_t>(leap_seconds_at_gps(t, std::nullopt)) * kNsPerS;
  if (in_inserted_second(t)) utc_ns -= kNsPerS;
  return kGpsEpochUnix_s * kNsPerS + utc_ns;
}

CalendarTime utc_from_gps(GpsTime t, std::optional<int> after_table_s) {
  return to_calendar(utc_cal_ns_from_gps(t, after_table_s));
}

// ---- text ----------------------------------------------------------------------------------

GpsTime parse_time(std::string_view text, std::string_view field) {
  if (text.empty()) reject(text, field, "empty");
  // WEEK:TOW has its ':' right after the digits of the week; ISO-8601 starts with "YYYY-".
  std::size_t digits = 0;
  while (digits < text.size() && is_digit(text[digits])) ++digits;
  if (digits < text.size() && text[digits] == ':') return parse_week_tow(text, field);
  if (digits == 4 && digits < text.size() && text[digits] == '-') return parse_iso(text, field);
  reject(text, field, "unrecognized form");
}

std::string format_iso_utc(GpsTime t, std::optional<int> after_table_s) {
  const CalNs c = utc_cal_ns_from_gps(t, after_table_s);
  const std::int64_t ms = c.nano / 1'000'000;  // truncated, so the seconds never carry
  std::string out = fmt::format("{:04}-{:02}-{:02}T{:02}:{:02}:{:02}", c.year, c.month, c.day,
                                c.hour, c.minute, c.second);
  if (ms != 0) out += fmt::format(".{:03}", ms);
  out += 'Z';
  return out;
}

std::string format_week_tow(GpsTime t) {
  const std::int64_t week = floor_div(t.ns, kNsPerWeek);
  const std::int64_t rem = t.ns - week * kNsPerWeek;
  const std::int64_t ms = rem / 1'000'000;  // truncated to the millisecond
  return fmt::format("{}:{}.{:03}", week, ms / 1000, ms % 1000);
}

}  // namespace navemu
