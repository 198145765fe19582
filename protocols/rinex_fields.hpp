#pragma once
// Private helpers shared by the RINEX readers (rinex_nav.cpp, rinex_obs.cpp): the file as a
// list of lines, fixed-column field extraction, Fortran-style numbers (D exponents, blank
// fields) and errors that name file, line and field.
//
// RINEX is a fixed-column format (RINEX 2.11 section 2, RINEX 3.05 section 2): every field
// has a start column and a width; trailing blanks may be missing (RINEX 2.11 section 6.3
// "variable-length records"), so a field past the end of a line reads as blank.

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <istream>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "core/errors.hpp"
#include "core/time.hpp"

namespace navemu::rinex {

// The text of a file, split into lines ('\n', with a trailing '\r' removed).
// Line numbers are 1-based: line(n) for n in [1, size()].
class Lines {
 public:
  Lines(std::string text, std::string source) : text_(std::move(text)), source_(std::move(source)) {
    std::string_view all(text_);
    std::size_t start = 0;
    while (start < all.size()) {
      std::size_t end = all.find('\n', start);
      if (end == std::string_view::npos) end = all.size();
      std::string_view l = all.substr(start, end - start);
      if (!l.empty() && l.back() == '\r') l.remove_suffix(1);
      lines_.push_back(l);
      start = end + 1;
    }
  }
  Lines(const Lines&) = delete;
  Lines& operator=(const Lines&) = delete;

  int size() const { return static_cast<int>(lines_.size()); }
  std::string_view line(int n) const { return lines_[static_cast<std::size_t>(n - 1)]; }
  const std::string& source() const { return source_; }
  std::string_view head(std::size_t n) const { return std::string_view(text_).substr(0, n); }

 private:
  std::string text_;  // owns the characters the views point into
  std::string source_;
  std::vector<std::string_view> lines_;
};

[[noreturn]] inline void fail(const std::string& source, int line, std::string field,
                              const std::string& problem) {
  throw InputError(source, line, std::move(field), problem);
}

inline std::string read_stream(std::istream& in, const std::string& source) {
  std::ostringstream ss;
  if (in.good()) ss << in.rdbuf();
  if (in.bad()) fail(source, 0, "", "read error");
  return std::move(ss).str();
}

// Characters [col, col + width) of a line, clipped to its end (blank when past the end).
inline std::string_view column(std::string_view line, std::size_t col, std::size_t width) {
  if (col >= line.size()) return {};
  return line.substr(col, std::min(width, line.size() - col));
}

inline std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

inline bool is_blank(std::string_view s) { return trim(s).empty(); }

// Header record label, columns 61-80 (RINEX 2.11 section 2, RINEX 3.05 section 2).
inline std::string_view header_label(std::string_view line) { return trim(column(line, 60, 20)); }

inline bool starts_with(std::string_view s, std::string_view prefix) {
  return s.substr(0, prefix.size()) == prefix;
}

enum class NumStatus { ok, blank, bad, not_finite };

// Reads a Fortran F/E/D-format number: blanks around it, an optional sign, and an exponent
// letter E, e, D or d (RINEX 2.11 Table A4: D19.12 fields in navigation files).
inline NumStatus to_double(std::string_view text, double& out) {
  text = trim(text);
  if (text.empty()) return NumStatus::blank;
  char buf[48];
  if (text.size() >= sizeof buf) return NumStatus::bad;
  std::size_t n = 0;
  std::size_t k = 0;
  if (text[0] == '+') k = 1;
  for (; k < text.size(); ++k) {
    const char c = text[k];
    buf[n++] = (c == 'D' || c == 'd') ? 'E' : c;
  }
  if (n == 0) return NumStatus::bad;
  const auto [ptr, ec] = std::from_chars(buf, buf + n, out, std::chars_format::general);
  if (ptr != buf + n) return NumStatus::bad;
  if (ec == std::errc::result_out_of_range) return NumStatus::not_finite;
  if (ec != std::errc{}) return NumStatus::bad;
  if (!std::isfinite(out)) return NumStatus::not_finite;
  return NumStatus::ok;
}

inline NumStatus to_int(std::string_view text, int& out) {
  text = trim(text);
  if (text.empty()) return NumStatus::blank;
  if (text[0] == '+') text.remove_prefix(1);
  if (text.empty()) return NumStatus::bad;
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), out);
  if (ec != std::errc{} || ptr != text.data() + text.size()) return NumStatus::bad;
  return NumStatus::ok;
}

// A place in a file for error messages.
struct Where {
  const std::string& source;
  int line;
};

[[noreturn]] inline void fail_number(const Where& w, const std::string& field,
                                     std::string_view text, NumStatus st) {
  switch (st) {
    case NumStatus::blank:
      fail(w.source, w.line, field, "missing (blank field or line too short)");
    case NumStatus::not_finite:
      fail(w.source, w.line, field, fmt::format("not a finite number: '{}'", trim(text)));
    default:
      fail(w.source, w.line, field, fmt::format("not a number: '{}'", trim(text)));
  }
}

// A required real number in columns [col, col + width).
inline double req_double(const Where& w, std::string_view line, std::size_t col, std::size_t width,
                         const std::string& field) {
  const std::string_view text = column(line, col, width);
  double v = 0.0;
  const NumStatus st = to_double(text, v);
  if (st != NumStatus::ok) fail_number(w, field, text, st);
  return v;
}

// Fortran writes numbers right-justified in their columns, so a number that stops short of
// the last column of its field was cut (a truncated line or file).
inline void check_right_justified(const Where& w, std::string_view text, std::size_t width,
                                  const std::string& field) {
  if (is_blank(text)) return;
  if (text.size() < width || text.back() == ' ')
    fail(w.source, w.line, field,
         fmt::format("incomplete number '{}': not right-justified in its {} columns (line cut "
                     "short?)",
                     trim(text), width));
}

// A required real number that fills its columns up to the last one.
inline double req_full_double(const Where& w, std::string_view line, std::size_t col,
                              std::size_t width, const std::string& field) {
  const double v = req_double(w, line, col, width, field);
  check_right_justified(w, column(line, col, width), width, field);
  return v;
}

// An optional real number: std::nullopt when blank, an error when present but not a number.
inline std::optional<double> opt_double(const Where& w, std::string_view line, std::size_t col,
                                        std::size_t width, const std::string& field) {
  const std::string_view text = column(line, col, width);
  double v = 0.0;
  const NumStatus st = to_double(text, v);
  if (st == NumStatus::blank) return std::nullopt;
  if (st != NumStatus::ok) fail_number(w, field, text, st);
  return v;
}

// An optional real number that, when present, fills its columns up to the last one.
inline std::optional<double> opt_full_double(const Where& w, std::string_view line, std::size_t col,
                                             std::size_t width, const std::string& field) {
  const std::optional<double> v = opt_double(w, line, col, width, field);
  check_right_justified(w, column(line, col, width), width, field);
  return v;
}

inline int req_int(const Where& w, std::string_view line, std::size_t col, std::size_t width,
                   const std::string& field) {
  const std::string_view text = column(line, col, width);
  int v = 0;
  const NumStatus st = to_int(text, v);
  if (st != NumStatus::ok) fail_number(w, field, text, st);
  return v;
}

// A real number that must hold an integer value (RINEX stores IODE, week, flags as D19.12).
inline int integral(const Where& w, double v, const std::string& field) {
  if (!(std::fabs(v) < 2.0e9) || std::fabs(v - std::round(v)) > 1e-6 * std::max(1.0, std::fabs(v)))
    fail(w.source, w.line, field, fmt::format("expected an integer value, got {}", v));
  return static_cast<int>(std::lround(v));
}

// Two-digit years (RINEX 2.11 section 6.5): 80-99 are 1980-1999, 00-79 are 2000-2079.
inline int full_year(int yy) {
  if (yy >= 80 && yy <= 99) return 1900 + yy;
  if (yy >= 0 && yy < 80) return 2000 + yy;
  return yy;  // not a two-digit year; the date check reports it
}

// Checks a broken-down epoch and converts it, read in the GPS time scale.
inline GpsTime epoch_to_gps(const Where& w, const CalendarTime& c, const std::string& field) {
  static constexpr int kDaysInMonth[12] = {31, 29, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  const bool ok = c.year >= 1980 && c.year <= 2200 && c.month >= 1 && c.month <= 12 && c.day >= 1 &&
                  c.day <= kDaysInMonth[c.month - 1] && c.hour >= 0 && c.hour <= 23 &&
                  c.minute >= 0 && c.minute <= 59 && c.second >= 0.0 && c.second < 61.0;
  if (!ok)
    fail(w.source, w.line, field,
         fmt::format("not a valid date/time: {:04d}-{:02d}-{:02d} {:02d}:{:02d}:{}", c.year, c.month,
                     c.day, c.hour, c.minute, c.second));
  return gps_from_calendar(c);
}

// Common checks on the first header line "RINEX VERSION / TYPE" (RINEX 2.11 Tables A1/A3,
// RINEX 3.05 observation and navigation header descriptions): version F9.2 in columns 1-9, file type in column 21, satellite
// system in column 41.
struct VersionLine {
  double version = 0.0;
  char type = ' ';
  char system = ' ';
};

inline VersionLine read_version_line(const Lines& lines) {
  const std::string& src = lines.source();
  if (lines.size() == 0) fail(src, 1, "RINEX VERSION / TYPE", "empty file");
  const std::string_view first = lines.line(1);
  if (starts_with(lines.head(2), "\x1f\x8b"))
    fail(src, 1, "RINEX VERSION / TYPE", "gzip-compressed file: decompress it first");
  if (header_label(first) == "CRINEX VERS   / TYPE")
    fail(src, 1, "RINEX VERSION / TYPE",
         "Hatanaka-compressed (CRINEX) file: decompress it with CRX2RNX first");
  if (header_label(first) != "RINEX VERSION / TYPE")
    fail(src, 1, "RINEX VERSION / TYPE",
         "not a RINEX file: first line must be the RINEX VERSION / TYPE header record");
  VersionLine v;
  const Where w{src, 1};
  v.version = req_double(w, first, 0, 9, "version");
  const std::string_view type = column(first, 20, 1);
  v.type = type.empty() ? ' ' : type[0];
  const std::string_view sys = column(first, 40, 1);
  v.system = sys.empty() ? ' ' : sys[0];
  return v;
}

}  // namespace navemu::rinex
