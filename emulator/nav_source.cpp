#include <fmt/format.h>

#include <charconv>
#include <cstdlib>
#include <functional>
#include <chrono>
#include <cmath>
#include <vector>

#include "emulator/commands.hpp"
#include "models/constellation.hpp"
#include "models/errors.hpp"
#include "models/rinex.hpp"

namespace navemu {

namespace {

double parse_number(std::string_view text, const std::string& field, const char* what) {
  while (!text.empty() && text.front() == ' ') text.remove_prefix(1);
  while (!text.empty() && text.back() == ' ') text.remove_suffix(1);
  double v = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size() || !std::isfinite(v))
    throw InputError(field, fmt::format("{} '{}' is not a finite number", what, text));
  return v;
}

// A numeric option's check: `ok` on its finite value, or `what` in the message.
CLI::Validator number_check(std::function<bool(double)> ok, std::string what, std::string description) {
  return CLI::Validator(
      [ok = std::move(ok), what = std::move(what)](std::string& text) -> std::string {
        const char* begin = text.c_str();
        char* end = nullptr;
        const double v = std::strtod(begin, &end);
        if (text.empty() || end != begin + text.size()) return fmt::format("'{}' is not a number", text);
        if (!std::isfinite(v)) return fmt::format("'{}' is not a finite number", text);
        if (!ok(v)) return fmt::format("{} is not {}", text, what);
        return "";
      },
      std::move(description));
}

}  // namespace

CLI::Validator number_between(double min, double max) {
  return number_check([=](double v) { return v >= min && v <= max; },
                      fmt::format("between {} and {}", min, max), fmt::format("NUMBER in [{}, {}]", min, max));
}

CLI::Validator positive_number() {
  return number_check([](double v) { return v > 0.0; }, "above 0", "POSITIVE");
}

CLI::Validator non_negative_number() {
  return number_check([](double v) { return v >= 0.0; }, "0 or more", "NONNEGATIVE");
}

std::vector<double> parse_numbers(const std::string& text, const std::string& field,
                                  const std::vector<std::string>& names, const char* form) {
  std::vector<std::string_view> parts;
  std::string_view rest = text;
  for (std::size_t pos; (pos = rest.find(',')) != std::string_view::npos;) {
    parts.push_back(rest.substr(0, pos));
    rest.remove_prefix(pos + 1);
  }
  parts.push_back(rest);
  if (parts.size() != names.size())
    throw InputError(field, fmt::format("expected {}, got '{}'", form, text));
  std::vector<double> v;
  for (std::size_t i = 0; i < parts.size(); ++i)
    v.push_back(parse_number(parts[i], field, names[i].c_str()));
  return v;
}

Geodetic parse_geodetic(const std::string& text, const std::string& field) {
  const std::vector<double> v =
      parse_numbers(text, field, {"latitude", "longitude", "height"},
                    "LAT,LON,H (degrees, degrees, metres above the WGS-84 ellipsoid)");
  const Geodetic g{v[0], v[1], v[2]};
  if (std::abs(g.lat_deg) > 90.0)
    throw InputError(field, fmt::format("latitude {} outside [-90, 90] degrees", g.lat_deg));
  if (g.lon_deg < -180.0 || g.lon_deg > 360.0)
    throw InputError(field, fmt::format("longitude {} outside [-180, 360] degrees", g.lon_deg));
  if (g.h_m < -11000.0 || g.h_m > 1e8)
    throw InputError(field, fmt::format("height {} m outside [-11000, 1e8] m", g.h_m));
  return g;
}

GpsTime gps_now() {
  // The only wall-clock read of the commands: the system clock (UTC) turned into GPS time.
  return gps_from_unix_ns(std::chrono::duration_cast<std::chrono::nanoseconds>(
                              std::chrono::system_clock::now().time_since_epoch())
                              .count());
}

GpsTime time_option(const std::string& text, const std::string& field) {
  if (text != "now") return parse_time(text, field);
  const GpsTime now = gps_now();
  return GpsTime{now.ns - now.ns % kNsPerS};  // whole seconds
}

NavData load_nav_or_nominal(const std::string& nav_file, GpsTime t) {
  if (nav_file.empty()) return nominal_constellation(t);
  return read_rinex_nav(nav_file);
}

}  // namespace navemu
