#pragma once
// Fields of received NMEA sentences converted back to the encoders' SI fields, for the tests
// that re-encode real receiver output (test_nmea.cpp, test_pubx.cpp).

#include <gtest/gtest.h>

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "protocols/nmea.hpp"

namespace navemu::nmea::test_fields {

using Fields = std::vector<std::string>;

inline Fields must_parse(std::string_view s) {
  auto f = parse(s);
  EXPECT_TRUE(f.has_value()) << s;
  return f.value_or(Fields{});
}

inline std::optional<double> num(const std::string& s) {
  if (s.empty()) return std::nullopt;
  return std::stod(s);
}

inline std::optional<int> inum(const std::string& s) {
  if (s.empty()) return std::nullopt;
  return std::stoi(s);
}

inline UtcTime time_of(const std::string& hhmmss, const std::string& ddmmyy = "010100") {
  UtcTime t;
  t.hour = std::stoi(hhmmss.substr(0, 2));
  t.minute = std::stoi(hhmmss.substr(2, 2));
  t.second = std::stod(hhmmss.substr(4));
  t.day = std::stoi(ddmmyy.substr(0, 2));
  t.month = std::stoi(ddmmyy.substr(2, 2));
  t.year = 2000 + std::stoi(ddmmyy.substr(4, 2));
  return t;
}

// ddmm.mmmm,N,dddmm.mmmm,W starting at fields[i].
inline std::optional<LatLon> position_of(const Fields& f, std::size_t i) {
  if (f[i].empty()) return std::nullopt;
  const auto coordinate = [](const std::string& v, std::size_t deg_digits, const std::string& h) {
    const double d = std::stod(v.substr(0, deg_digits)) + std::stod(v.substr(deg_digits)) / 60.0;
    return h == "S" || h == "W" ? -d : d;
  };
  return LatLon{coordinate(f[i], 2, f[i + 1]), coordinate(f[i + 2], 3, f[i + 3])};
}

}  // namespace navemu::nmea::test_fields
