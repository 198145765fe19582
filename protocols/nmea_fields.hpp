#pragma once
// Building blocks of the NMEA 0183 encoders (protocols/nmea.cpp), shared with the encoders of
// the proprietary sentences of the same receivers (protocols/pubx.cpp) so that every sentence
// rounds and formats its fields one way: a sentence assembled in a fixed buffer, and the field
// writers with their rounding rules (documented in nmea.hpp). For protocols/ only.

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

#include "protocols/nmea.hpp"

namespace navemu::nmea::detail {

// "$" + address + fields + "*hh" + CR LF (NMEA 0183 section 5.3).
inline constexpr std::size_t kMaxSentence = 82;
inline constexpr std::size_t kTail = 5;  // "*hh\r\n"

inline constexpr double kMpsToKmh = 3.6;  // 1 km/h = 1/3.6 m/s

inline constexpr std::array<std::int64_t, 8> kPow10{1, 10, 100, 1000, 10000, 100000, 1000000, 10000000};

// One sentence assembled in a fixed buffer (no allocation). Every field is preceded by ','.
class Line {
 public:
  Line(std::string_view talker, std::string_view type) {
    put('$');
    text(talker.substr(0, 2));
    text(type);
  }

  void put(char c) {
    if (n_ < buf_.size()) buf_[n_++] = c;
  }
  void text(std::string_view s) {
    for (char c : s) put(c);
  }
  void sep() { put(','); }
  // A non-negative integer with at least `min_digits` digits, zero-padded: what "{:0{}d}"
  // gives, without the formatting library's parsing (GSV sends hundreds of these a second).
  void digits(std::uint64_t v, int min_digits = 1) {
    std::array<char, 20> tmp{};
    std::size_t n = 0;
    do {
      tmp[n++] = static_cast<char>('0' + v % 10);
      v /= 10;
    } while (v != 0);
    while (n < tmp.size() && n < static_cast<std::size_t>(std::max(min_digits, 0))) tmp[n++] = '0';
    while (n > 0) put(tmp[--n]);
  }

  template <typename... T>
  void format(fmt::format_string<T...> f, T&&... args) {
    const auto r =
        fmt::format_to_n(buf_.data() + n_, buf_.size() - n_, f, std::forward<T>(args)...);
    n_ = std::min(buf_.size(), n_ + r.size);
  }

  // Fixed point with `decimals` digits and at least `int_digits` zero-padded integer digits; no
  // sign on a value that rounds to zero ("-0.0" is not sent).
  void fixed(double v, int decimals, int int_digits = 1) {
    const int width = int_digits + (decimals > 0 ? decimals + 1 : 0);
    std::array<char, 48> tmp{};
    const auto r =
        fmt::format_to_n(tmp.data(), tmp.size(), "{:0{}.{}f}", std::fabs(v), width, decimals);
    const std::string_view s(tmp.data(), std::min(tmp.size(), r.size));
    if (v < 0 && s.find_first_of("123456789") != std::string_view::npos) put('-');
    text(s);
  }

  // `units` (a non-negative count of 10^-decimals) as "i.fff" with zero-padded integer part.
  void scaled(std::int64_t units, int decimals, int int_digits) {
    const std::int64_t scale = kPow10[static_cast<std::size_t>(decimals)];
    digits(static_cast<std::uint64_t>(units / scale), int_digits);
    if (decimals > 0) {
      put('.');
      digits(static_cast<std::uint64_t>(units % scale), decimals);
    }
  }

  bool fits() const { return n_ + kTail <= kMaxSentence; }

  void finish(std::string& out) const {
    const std::string_view body(buf_.data() + 1, n_ - 1);
    out.append(buf_.data(), n_);
    fmt::format_to(std::back_inserter(out), "*{:02X}\r\n", checksum(body));
  }

 private:
  std::array<char, 160> buf_{};  // longer than any sentence before fitting (see nmea.hpp)
  std::size_t n_ = 0;
};

// A set value, finite, clamped to [lo, hi]; nothing otherwise.
std::optional<double> valid(std::optional<double> v, double lo, double hi);

// A UTC time rounded as a whole to the sent number of decimals; the rounding carries through
// seconds, minutes, hours and the date, so 60 seconds never appear.
struct Stamp {
  int year, month, day, hour, minute, second;
  std::int64_t fraction;  // units of 10^-decimals s
  int decimals;
};
Stamp stamp(const UtcTime& t, int decimals);

// hhmmss(.ss)
void put_time(Line& l, const Stamp& s);

// ,lat,N,lon,E with `decimals` decimals of the minutes, or four empty fields.
void put_position(Line& l, const std::optional<LatLon>& p, int decimals);

// A direction in [0, 360) degrees; one that rounds to 360 is sent as 0. Nothing when unset.
void put_course(Line& l, std::optional<double> v, int decimals, int int_digits);

// Fixed point (Line::fixed); nothing when unset.
void put_fixed(Line& l, std::optional<double> v, int decimals, int int_digits = 1);

// `sig` significant digits, never fewer than the integer digits, at most 3 decimals ("0.98",
// "2.5", "126"); nothing when unset.
void put_significant(Line& l, std::optional<double> v, int sig);

}  // namespace navemu::nmea::detail
