#include <fmt/format.h>
#include <fmt/ostream.h>

#include <charconv>
#include <cstdlib>
#include <functional>
#include <chrono>
#include <cmath>
#include <ostream>
#include <set>
#include <vector>

#include "emulator/commands.hpp"
#include "models/constellation.hpp"
#include "core/errors.hpp"
#include "models/ephemeris.hpp"
#include "emulator/rinex_files.hpp"

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

NavData load_nav_or_nominal(const std::string& nav_file, GpsTime t, std::uint32_t systems) {
  if (nav_file.empty()) return nominal_constellation(t, systems);
  return read_rinex_nav(nav_file);
}

namespace {

std::string when(GpsTime t) { return fmt::format("{} ({})", format_iso_utc(t), format_week_tow(t)); }

std::string satellites(int n) {
  return n == 1 ? "1 satellite inside its fit interval"
                : fmt::format("{} satellites inside their fit intervals", n);
}

GpsTime whole_second_at_or_after(GpsTime t) {
  const std::int64_t r = ((t.ns % kNsPerS) + kNsPerS) % kNsPerS;
  return r == 0 ? t : GpsTime{t.ns - r + kNsPerS};
}

// The IGS daily merged broadcast file of a date, as CDDIS serves it
// (archive/gnss/data/daily/YYYY/brdc/).
std::string brdc_name(GpsTime t) {
  const CalendarTime c = utc_from_gps(t);
  return fmt::format("BRDC00IGS_R_{:04}{:03}0000_01D_MN.rnx", c.year,
                     day_of_year(c.year, c.month, c.day));
}

}  // namespace

void require_nav_coverage(const NavData& nav, GpsTime from, GpsTime to,
                          const ScenarioOptions& options, int min_satellites) {
  const std::vector<TimeSpan> spans = covered_spans(nav, min_satellites);
  const TimeSpan* started = nullptr;  // the interval the scenario starts in
  const TimeSpan* fits = nullptr;     // the first one as long as the scenario, else the longest
  for (const TimeSpan& s : spans) {
    if (s.contains(from)) {
      if (s.contains(to)) return;
      started = &s;
    }
    const auto length = [](const TimeSpan& x) { return x.to.ns - x.from.ns; };
    if (fits == nullptr || (length(*fits) < to.ns - from.ns && length(s) > length(*fits))) fits = &s;
  }

  std::string has;
  if (spans.empty()) {
    std::set<SatId> sats;
    for (const GpsEphemeris& e : nav.gps) sats.insert(e.sat);
    has = fmt::format("has no time with {} ({} GPS records, {} satellites)",
                      satellites(min_satellites), nav.gps.size(), sats.size());
  } else {
    has = fmt::format("has data for {} only", satellites(min_satellites));
    constexpr std::size_t kShown = 3;
    for (std::size_t i = 0; i < spans.size() && i < kShown; ++i)
      has += fmt::format("{} from {} to {}", i == 0 ? "" : ",", when(spans[i].from), when(spans[i].to));
    if (spans.size() > kShown) has += fmt::format(" and {} more intervals", spans.size() - kShown);
  }
  const std::string scenario = from == to ? fmt::format("the scenario starts at {}", when(from))
                                          : fmt::format("the scenario runs from {} to {}",
                                                        when(from), when(to));
  // The fix: a shorter scenario when it starts inside an interval, otherwise a start inside one;
  // or a file for the scenario's dates either way.
  std::string fix;
  if (started != nullptr && options.duration != nullptr)
    fix = fmt::format("shorten {} to at most {:.0f} s, or ", options.duration,
                      std::floor(seconds_between(started->to, from)));
  else if (fits != nullptr)
    fix = fmt::format("set {} inside {} (e.g. {} {}), or ", options.start,
                      spans.size() == 1 ? "it" : "one", options.start_flag,
                      format_iso_utc(whole_second_at_or_after(fits->from)));
  fix += fmt::format("use a navigation file for the scenario's date{} (e.g. {}, the IGS daily "
                     "broadcast ephemerides from CDDIS)",
                     started != nullptr ? "s" : "", brdc_name(from));
  throw InputError(nav.source, 0, options.nav,
                   fmt::format("the file {}, but {}: {}", has, scenario, fix));
}

void check_scenario_nav(const NavData& nav, GpsTime start, std::optional<double> duration_s,
                        std::ostream& log) {
  const ScenarioOptions options{"scenario.nav", "scenario.start or --start", "--start",
                                duration_s ? "--duration" : nullptr};
  require_nav_coverage(nav, start, duration_s ? start.plus_s(*duration_s) : start, options);
  if (!duration_s && !nav.renews)
    for (const TimeSpan& s : covered_spans(nav))
      if (s.contains(start))
        fmt::print(log,
                   "navemu: navigation data {} has {} until {}, {:.1f} h after the start; "
                   "past that the receiver is left with stale ephemerides, then none, and "
                   "loses its fix\n",
                   nav.source, satellites(kSatellitesForFix), when(s.to),
                   seconds_between(s.to, start) / 3600.0);
}

NavData load_scenario_nav(const std::string& nav_file, GpsTime start, std::optional<double> duration_s,
                          std::ostream& log) {
  NavData nav = load_nav_or_nominal(nav_file, start);
  check_scenario_nav(nav, start, duration_s, log);
  return nav;
}

}  // namespace navemu
