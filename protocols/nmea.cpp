// NMEA 0183 sentence encoders. Sentence layouts: the approved sentences of NMEA 0183 4.10 as
// the imitated receivers document them (u-blox M9 Interface Description, chapter "NMEA
// protocol"; Garmin GPS 15xH/15xL Technical Specifications, "NMEA sentences") and as their
// captures show them (tests/protocols/test_nmea.cpp). Sentence framing and the 82-character
// limit: NMEA 0183 section 5.3.
#include "protocols/nmea.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <iterator>
#include <utility>

#include "protocols/nmea_fields.hpp"

namespace navemu::nmea {

Format Format::garmin() {
  Format f;
  f.time_decimals = 0;           // hhmmss
  f.latlon_minute_decimals = 4;  // ddmm.mmmm
  f.dop_decimals = 1;
  f.altitude_decimals = 1;
  f.speed_decimals = 1;  // "005.3"
  f.speed_integer_digits = 3;
  f.course_decimals = 1;  // "247.1", magnetic variation "009.3"
  f.course_integer_digits = 3;
  f.snr_digits = 2;
  f.gga_sats_two_digits = true;
  f.mode_indicator = false;  // NMEA 2.0 field set: no mode indicator
  f.nav_status = false;
  f.system_signal_ids = false;
  return f;
}

namespace detail {

constexpr double kMpsToKnots = 3600.0 / 1852.0;  // 1 international knot = 1852 m/h
constexpr double kMaxKnots = 9999.999;
constexpr double kMaxSpeed_mps = kMaxKnots / kMpsToKnots;

// The knobs of a Format, clamped to the documented ranges, so that the length bounds in
// nmea.hpp hold for every Format.
struct Style {
  int time_dec, latlon_dec, dop_dec, alt_dec, speed_dec, speed_int, course_dec, course_int;
  int snr_digits, gst_sig;
  bool sats2, mode, nav_status, ids, limit82;
};

Style style(const Format& f) {
  return {std::clamp(f.time_decimals, 0, 3),
          f.high_precision ? 7 : std::clamp(f.latlon_minute_decimals, 0, 5),
          std::clamp(f.dop_decimals, 0, 2),
          f.high_precision ? 3 : std::clamp(f.altitude_decimals, 0, 3),
          std::clamp(f.speed_decimals, 0, 3),
          std::clamp(f.speed_integer_digits, 1, 3),
          std::clamp(f.course_decimals, 0, 3),
          std::clamp(f.course_integer_digits, 1, 3),
          std::clamp(f.snr_digits, 1, 2),
          std::clamp(f.gst_significant_digits, 1, 6),
          f.gga_sats_two_digits,
          f.mode_indicator,
          f.mode_indicator && f.nav_status,
          f.system_signal_ids,
          !f.high_precision};
}

// A set value, finite, clamped to [lo, hi]; nothing otherwise.
std::optional<double> valid(std::optional<double> v, double lo, double hi) {
  if (!v || !std::isfinite(*v)) return std::nullopt;
  return std::clamp(*v, lo, hi);
}

char letter_or(char c, char fallback) { return c >= 'A' && c <= 'Z' ? c : fallback; }

// Renders a sentence; while it is longer than 82 characters (`limit82`), takes one decimal off
// the first number in `shrink` that still has one and renders it again. The value clamps make
// the sentence fit once all of them are at zero (the bounds are worked out in nmea.hpp).
template <std::size_t N, typename Render>
void emit_fitted(std::string& out, std::array<int*, N> shrink, Render render, bool limit82 = true) {
  for (;;) {
    Line line = render();
    const auto next =
        std::find_if(shrink.begin(), shrink.end(), [](const int* d) { return *d > 0; });
    if (!limit82 || line.fits() || next == shrink.end()) {
      line.finish(out);
      return;
    }
    --**next;
  }
}

// ---- time -------------------------------------------------------------------------------

// Days since 1970-01-01 of a proleptic Gregorian date, and back (H. Hinnant, "chrono-Compatible
// Low-Level Date Algorithms").
std::int64_t days_from_civil(std::int64_t y, int m, int d) {
  y -= m <= 2 ? 1 : 0;
  const std::int64_t era = (y >= 0 ? y : y - 399) / 400;
  const std::int64_t yoe = y - era * 400;
  const std::int64_t doy = (153 * (m + (m > 2 ? -3 : 9)) + 2) / 5 + d - 1;
  const std::int64_t doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
  return era * 146097 + doe - 719468;
}

struct Civil {
  std::int64_t year;
  int month, day;
};

Civil civil_from_days(std::int64_t z) {
  z += 719468;
  const std::int64_t era = (z >= 0 ? z : z - 146096) / 146097;
  const std::int64_t doe = z - era * 146097;
  const std::int64_t yoe = (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365;
  const std::int64_t doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
  const std::int64_t mp = (5 * doy + 2) / 153;
  const int d = static_cast<int>(doy - (153 * mp + 2) / 5 + 1);
  const int m = static_cast<int>(mp < 10 ? mp + 3 : mp - 9);
  return {era * 400 + yoe + (m <= 2 ? 1 : 0), m, d};
}

Stamp stamp(const UtcTime& t, int decimals) {
  const std::int64_t scale = kPow10[static_cast<std::size_t>(decimals)];
  const double sec = std::isfinite(t.second) ? std::clamp(t.second, 0.0, 61.0) : 0.0;
  std::int64_t units =
      (std::int64_t{std::clamp(t.hour, 0, 23)} * 3600 + std::clamp(t.minute, 0, 59) * 60) * scale +
      std::llround(sec * static_cast<double>(scale));
  std::int64_t days = days_from_civil(std::clamp(t.year, 0, 9999), std::clamp(t.month, 1, 12),
                                      std::clamp(t.day, 1, 31));
  const std::int64_t day_units = 86400 * scale;
  days += units / day_units;
  units %= day_units;
  const Civil c = civil_from_days(days);
  const std::int64_t s = units / scale;
  return {static_cast<int>(std::clamp<std::int64_t>(c.year, 0, 9999)),
          c.month,
          c.day,
          static_cast<int>(s / 3600),
          static_cast<int>(s / 60 % 60),
          static_cast<int>(s % 60),
          units % scale,
          decimals};
}

// hhmmss(.ss)
void put_time(Line& l, const Stamp& s) {
  l.format("{:02d}{:02d}{:02d}", s.hour, s.minute, s.second);
  if (s.decimals > 0) l.format(".{:0{}d}", s.fraction, s.decimals);
}

// ---- position ----------------------------------------------------------------------------

// One coordinate as (d)ddmm.mmmm,H, rounded as a whole in units of 10^-decimals minutes so that
// 59.99999...' carries into the degrees.
void put_coordinate(Line& l, double deg, int deg_digits, int decimals, char pos, char neg) {
  const std::int64_t scale = kPow10[static_cast<std::size_t>(decimals)];
  const std::int64_t units = std::llround(std::fabs(deg) * 60.0 * static_cast<double>(scale));
  const std::int64_t per_degree = 60 * scale;
  l.format("{:0{}d}{:02d}", units / per_degree, deg_digits, units % per_degree / scale);
  if (decimals > 0) l.format(".{:0{}d}", units % scale, decimals);
  l.sep();
  l.put(deg < 0 && units != 0 ? neg : pos);
}

// lat,N,lon,E or four empty fields.
void put_position(Line& l, const std::optional<LatLon>& p, int decimals) {
  if (!p || !std::isfinite(p->lat_deg) || !std::isfinite(p->lon_deg)) {
    l.text(",,,,");
    return;
  }
  l.sep();
  put_coordinate(l, std::clamp(p->lat_deg, -90.0, 90.0), 2, decimals, 'N', 'S');
  l.sep();
  put_coordinate(l, std::clamp(p->lon_deg, -180.0, 180.0), 3, decimals, 'E', 'W');
}

// ---- numbers -----------------------------------------------------------------------------

// A direction in [0, 360) degrees; one that rounds to 360 is sent as 0.
void put_course(Line& l, std::optional<double> v, int decimals, int int_digits) {
  if (!v || !std::isfinite(*v)) return;
  double d = std::fmod(*v, 360.0);
  if (d < 0) d += 360.0;
  const std::int64_t scale = kPow10[static_cast<std::size_t>(decimals)];
  std::int64_t units = std::llround(d * static_cast<double>(scale));
  if (units >= 360 * scale) units -= 360 * scale;
  l.scaled(units, decimals, int_digits);
}

void put_fixed(Line& l, std::optional<double> v, int decimals, int int_digits) {
  if (v) l.fixed(*v, decimals, int_digits);
}

// Value then unit letter; both empty when the value is.
void put_with_unit(Line& l, std::optional<double> v, int decimals, char unit) {
  put_fixed(l, v, decimals);
  l.sep();
  if (v) l.put(unit);
}

// GST style: `sig` significant digits, never fewer than the integer digits, at most 3
// decimals ("0.98", "2.5", "126", "228650" in the NEO-M9N capture).
void put_significant(Line& l, std::optional<double> v, int sig) {
  if (!v) return;
  int decimals = 3;
  if (*v > 0) {
    const int e = static_cast<int>(std::floor(std::log10(*v)));
    decimals = std::clamp(sig - 1 - e, 0, 3);
    // 0.996 at two decimals rounds to 1.00: one significant digit too many.
    const double p = static_cast<double>(kPow10[static_cast<std::size_t>(decimals)]);
    if (decimals > 0 && std::round(*v * p) / p >= std::pow(10.0, e + 1)) --decimals;
  } else {
    decimals = std::clamp(sig - 1, 0, 3);
  }
  l.fixed(*v, decimals);
}

void put_int(Line& l, std::optional<int> v, int digits, int lo, int hi) {
  if (!v) return;
  const int x = std::clamp(*v, lo, hi);
  if (x < 0) {  // as "{:0{}d}": the sign counts in the width
    l.put('-');
    l.digits(static_cast<std::uint64_t>(-static_cast<std::int64_t>(x)), digits - 1);
  } else {
    l.digits(static_cast<std::uint64_t>(x), digits);
  }
}

}  // namespace detail

using namespace detail;

// ---- sentences ---------------------------------------------------------------------------

std::uint8_t checksum(std::string_view body) {
  std::uint8_t x = 0;
  for (char c : body) x = static_cast<std::uint8_t>(x ^ static_cast<std::uint8_t>(c));
  return x;
}

// GGA: time, lat, N/S, lon, E/W, quality, numSV, HDOP, alt, M, sep, M, diffAge, diffStation.
// Longest case, all decimals shrunk: 6 ("$GPGGA") + 11 (",hhmmss.sss") + 27 (position) + 2 + 3
// + 4 (",100" HDOP) + 8 (",-9999,M") + 7 (",-999,M") + 4 (",100" age) + 5 + 5 = 82.
void encode(const GgaFields& f, const Format& fmt, std::string& out) {
  const Style st = style(fmt);
  const Stamp t = stamp(f.utc, st.time_dec);
  const auto hdop = valid(f.hdop, 0.0, 99.99);
  const auto alt = valid(f.alt_msl_m, -9999.0, 99999.0);
  const auto sep = valid(f.geoid_separation_m, -999.0, 999.0);
  const auto age = valid(f.dgps_age_s, 0.0, 99.9);
  int alt_dec = st.alt_dec, sep_dec = st.alt_dec, age_dec = 1, dop_dec = st.dop_dec;
  emit_fitted(out, std::array{&alt_dec, &age_dec, &sep_dec, &dop_dec}, [&] {
    Line l(f.talker, "GGA");
    l.sep();
    put_time(l, t);
    put_position(l, f.position, st.latlon_dec);
    l.format(",{}", std::clamp(f.quality, 0, 9));
    if (st.sats2) {
      l.format(",{:02d}", std::clamp(f.num_sats, 0, 99));
    } else {
      l.format(",{}", std::clamp(f.num_sats, 0, 99));
    }
    l.sep();
    put_fixed(l, hdop, dop_dec);
    l.sep();
    put_with_unit(l, alt, alt_dec, 'M');
    l.sep();
    put_with_unit(l, sep, sep_dec, 'M');
    l.sep();
    put_fixed(l, age, age_dec);
    l.sep();
    put_int(l, f.dgps_station, 4, 0, 1023);
    return l;
  }, st.limit82);
}

// RMC: time, status, lat, N/S, lon, E/W, SOG knots, COG, date, magvar, E/W [, mode [, navStatus]].
// Longest case, all decimals shrunk: 6 + 11 + 2 + 27 + 6 (",10000" knots) + 4 (",359") + 7
// (",ddmmyy") + 4 (",180") + 2 + 2 + 2 + 5 = 78.
void encode(const RmcFields& f, const Format& fmt, std::string& out) {
  const Style st = style(fmt);
  const Stamp t = stamp(f.utc, st.time_dec);
  std::optional<double> knots = valid(f.speed_mps, 0.0, kMaxSpeed_mps);
  if (knots) *knots *= kMpsToKnots;
  const auto magvar = valid(f.magvar_deg, -180.0, 180.0);
  int magvar_dec = st.course_dec, speed_dec = st.speed_dec, course_dec = st.course_dec;
  emit_fitted(out, std::array{&magvar_dec, &speed_dec, &course_dec}, [&] {
    Line l(f.talker, "RMC");
    l.sep();
    put_time(l, t);
    l.sep();
    l.put(f.valid ? 'A' : 'V');
    put_position(l, f.position, st.latlon_dec);
    l.sep();
    put_fixed(l, knots, speed_dec, st.speed_int);
    l.sep();
    put_course(l, f.course_deg, course_dec, st.course_int);
    l.format(",{:02d}{:02d}{:02d},", t.day, t.month, t.year % 100);
    if (magvar) {
      l.fixed(std::fabs(*magvar), magvar_dec, st.course_int);
      l.sep();
      l.put(*magvar < 0 ? 'W' : 'E');
    } else {
      l.sep();
    }
    if (st.mode) {
      l.sep();
      l.put(letter_or(f.mode, 'N'));
    }
    if (st.nav_status) {
      l.sep();
      l.put(letter_or(f.nav_status, 'V'));
    }
    return l;
  }, st.limit82);
}

// GSA: selection, fix, 12 PRN slots, PDOP, HDOP, VDOP [, systemId].
// Longest case, all decimals shrunk: 11 ("$GPGSA,A,3,") + 12 x 4 ("999,") + 11 ("100,100,100")
// + 3 (",15") + 5 = 78.
std::string_view system_talker(GnssSystem s) {
  switch (s) {
    case GnssSystem::kGlonass: return "GL";
    case GnssSystem::kGalileo: return "GA";
    case GnssSystem::kBeidou: return "GB";
    case GnssSystem::kQzss: return "GQ";
    case GnssSystem::kNavic: return "GI";
    default: return "GP";
  }
}

std::string_view main_talker(std::uint32_t systems) {
  for (const GnssSystemInfo& i : kGnssSystems)
    if (systems == system_bit(i.system)) return system_talker(i.system);
  return "GN";
}

void encode(const GsaFields& f, const Format& fmt, std::string& out) {
  const Style st = style(fmt);
  const auto pdop = valid(f.pdop, 0.0, 99.99);
  const auto hdop = valid(f.hdop, 0.0, 99.99);
  const auto vdop = valid(f.vdop, 0.0, 99.99);
  int vdop_dec = st.dop_dec, hdop_dec = st.dop_dec, pdop_dec = st.dop_dec;
  emit_fitted(out, std::array{&vdop_dec, &hdop_dec, &pdop_dec}, [&] {
    Line l(f.talker, "GSA");
    l.sep();
    l.put(f.selection == 'M' ? 'M' : 'A');
    l.format(",{}", std::clamp(f.fix, 1, 3));
    for (std::size_t i = 0; i < 12; ++i) {
      l.sep();
      if (i < f.sat_ids.size()) l.format("{:02d}", std::clamp(f.sat_ids[i], 0, 999));
    }
    l.sep();
    put_fixed(l, pdop, pdop_dec);
    l.sep();
    put_fixed(l, hdop, hdop_dec);
    l.sep();
    put_fixed(l, vdop, vdop_dec);
    if (st.ids) l.format(",{}", std::clamp(f.system_id, 0, 15));
    return l;
  });
}

// GSV: numMsg, msgNum, numSV, then per satellite ID, elevation, azimuth, C/N0 [, signalId].
// Longest: 6 + 9 (",25,25,99") + 4 x 14 (",999,90,359,99") + 3 (",15") + 5 = 79.
void encode(const GsvFields& f, const Format& fmt, std::string& out) {
  const Style st = style(fmt);
  const std::size_t n = std::min<std::size_t>(f.satellites.size(), 99);
  const std::size_t sentences = std::max<std::size_t>(1, (n + 3) / 4);
  for (std::size_t k = 0; k < sentences; ++k) {
    emit_fitted(out, std::array<int*, 0>{}, [&] {
      Line l(f.talker, "GSV");
      l.sep();
      l.digits(sentences);
      l.sep();
      l.digits(k + 1);
      l.sep();
      l.digits(n, 2);
      for (std::size_t i = 4 * k; i < std::min(n, 4 * k + 4); ++i) {
        const GsvSatellite& s = f.satellites[i];
        l.sep();
        l.digits(static_cast<std::uint64_t>(std::clamp(s.sat_id, 0, 999)), 2);
        l.sep();
        put_int(l, s.elevation_deg, 2, 0, 90);
        l.sep();
        if (s.azimuth_deg) l.digits(static_cast<std::uint64_t>((*s.azimuth_deg % 360 + 360) % 360), 3);
        l.sep();
        put_int(l, s.snr_dbhz, st.snr_digits, 0, 99);
      }
      // Signal ID 0 stands for all signals (NMEA 0183 4.11); u-blox sends it with no satellites.
      if (st.ids) {
        l.sep();
        l.digits(static_cast<std::uint64_t>(n == 0 ? 0 : std::clamp(f.signal_id, 0, 15)));
      }
      return l;
    });
  }
}

// VTG: COG true, T, COG magnetic, M, SOG knots, N, SOG km/h, K [, mode]. Longest: 6 + 10
// (",359.999,T") + 10 + 11 (",9999.999,N") + 12 (",18519.998,K") + 2 + 5 = 56.
void encode(const VtgFields& f, const Format& fmt, std::string& out) {
  const Style st = style(fmt);
  const std::optional<double> mps = valid(f.speed_mps, 0.0, kMaxSpeed_mps);
  std::optional<double> knots, kmh;
  if (mps) {
    knots = *mps * kMpsToKnots;
    kmh = *mps * kMpsToKmh;
  }
  const auto course_t = valid(f.course_true_deg, -1e9, 1e9);
  const auto course_m = valid(f.course_magnetic_deg, -1e9, 1e9);
  const bool any = course_t || course_m || knots;
  emit_fitted(out, std::array<int*, 0>{}, [&] {
    Line l(f.talker, "VTG");
    const auto unit = [&](char u) {
      l.sep();
      if (any) l.put(u);
      l.sep();
    };
    l.sep();
    put_course(l, course_t, st.course_dec, st.course_int);
    unit('T');
    put_course(l, course_m, st.course_dec, st.course_int);
    unit('M');
    put_fixed(l, knots, st.speed_dec, st.speed_int);
    unit('N');
    put_fixed(l, kmh, st.speed_dec, st.speed_int);
    l.sep();
    if (any) l.put('K');
    if (st.mode) {
      l.sep();
      l.put(letter_or(f.mode, 'N'));
    }
    return l;
  });
}

// GLL: lat, N/S, lon, E/W, time, status [, mode]. Longest: 6 + 27 + 11 + 2 + 2 + 5 = 53.
void encode(const GllFields& f, const Format& fmt, std::string& out) {
  const Style st = style(fmt);
  const Stamp t = stamp(f.utc, st.time_dec);
  emit_fitted(out, std::array<int*, 0>{}, [&] {
    Line l(f.talker, "GLL");
    put_position(l, f.position, st.latlon_dec);
    l.sep();
    put_time(l, t);
    l.sep();
    l.put(f.valid ? 'A' : 'V');
    if (st.mode) {
      l.sep();
      l.put(letter_or(f.mode, 'N'));
    }
    return l;
  });
}

// GST: time, rangeRms, stdMajor, stdMinor, orient, stdLat, stdLong, stdAlt. Every number is
// at most 7 characters ("99999.9", "179.900"): 6 + 11 + 7 x 8 + 5 = 78.
void encode(const GstFields& f, const Format& fmt, std::string& out) {
  const Style st = style(fmt);
  const Stamp t = stamp(f.utc, st.time_dec);
  const std::array<std::optional<double>, 7> v{
      valid(f.range_rms_m, 0.0, 999999.0), valid(f.major_m, 0.0, 999999.0),
      valid(f.minor_m, 0.0, 999999.0),     valid(f.orientation_deg, 0.0, 180.0),
      valid(f.lat_sigma_m, 0.0, 999999.0), valid(f.lon_sigma_m, 0.0, 999999.0),
      valid(f.alt_sigma_m, 0.0, 999999.0)};
  emit_fitted(out, std::array<int*, 0>{}, [&] {
    Line l(f.talker, "GST");
    l.sep();
    put_time(l, t);
    for (const auto& x : v) {
      l.sep();
      put_significant(l, x, st.gst_sig);
    }
    return l;
  });
}

// ZDA: time, day, month, year, local zone hours, local zone minutes. Longest: 6 + 11 + 11
// (",dd,mm,yyyy") + 4 (",-13") + 3 + 5 = 40.
void encode(const ZdaFields& f, const Format& fmt, std::string& out) {
  const Style st = style(fmt);
  const Stamp t = stamp(f.utc, st.time_dec);
  emit_fitted(out, std::array<int*, 0>{}, [&] {
    Line l(f.talker, "ZDA");
    l.sep();
    put_time(l, t);
    l.format(",{:02d},{:02d},{:04d},", t.day, t.month, t.year);
    const int zh = std::clamp(f.local_zone_hours, -13, 13);
    l.format("{:0{}d}", zh, zh < 0 ? 3 : 2);  // "-05", "05"
    l.format(",{:02d}", std::clamp(f.local_zone_minutes, 0, 59));
    return l;
  });
}

// TXT: "$--TXT,xx,xx,xx," is 16 characters, so 61 of text leave room for "*hh" CR LF.
void encode(const TxtFields& f, const Format&, std::string& out) {
  Line l(f.talker, "TXT");
  l.format(",{:02d},{:02d},{:02d},", std::clamp(f.total, 1, 99), std::clamp(f.number, 1, 99),
           std::clamp(f.text_id, 0, 99));
  constexpr std::string_view kReserved = "$*,!\\^~";
  for (const char c : f.text.substr(0, 61))
    l.put(c < 0x20 || c > 0x7E || kReserved.find(c) != std::string_view::npos ? ' ' : c);
  l.finish(out);
}

// PGRME: HPE, M, VPE, M, EPE, M (Garmin GPS 15x Technical Specifications). Longest: 6 + 3 x 10
// (",99999.9,M") + 5 = 41.
void encode(const PgrmeFields& f, const Format&, std::string& out) {
  const std::array<std::optional<double>, 3> v{
      valid(f.hpe_m, 0.0, 99999.9), valid(f.vpe_m, 0.0, 99999.9), valid(f.epe_m, 0.0, 99999.9)};
  emit_fitted(out, std::array<int*, 0>{}, [&] {
    Line l("P", "GRME");
    for (std::size_t i = 0; i < v.size(); ++i) {
      l.sep();
      put_fixed(l, v[i], 1);
      l.sep();
      if (v[i]) l.put('M');
    }
    return l;
  });
}

// ---- parsing -----------------------------------------------------------------------------

namespace {
int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;
}
}  // namespace

Checked check(std::string_view s) {
  if (s.ends_with("\r\n")) {
    s.remove_suffix(2);
  } else if (s.ends_with('\n')) {
    s.remove_suffix(1);
  }
  if (s.size() < 4 || s.front() != '$' || s[s.size() - 3] != '*') return {Checked::kMalformed, {}};
  const int hi = hex_digit(s[s.size() - 2]);
  const int lo = hex_digit(s[s.size() - 1]);
  if (hi < 0 || lo < 0) return {Checked::kMalformed, {}};
  const std::string_view body = s.substr(1, s.size() - 4);
  if (body.empty() || body.front() == ',') return {Checked::kMalformed, {}};  // no address field
  for (char c : body) {
    const auto u = static_cast<unsigned char>(c);
    // The reserved characters of NMEA 0183 other than the field delimiter (and '^', the
    // hexadecimal escape, which may appear in a body).
    if (u < 0x20 || u > 0x7E || c == '$' || c == '*' || c == '!' || c == '\\' || c == '~')
      return {Checked::kMalformed, {}};
  }
  if (checksum(body) != hi * 16 + lo) return {Checked::kBadChecksum, body};
  return {Checked::kOk, body};
}

std::optional<std::vector<std::string>> parse(std::string_view s) {
  const Checked c = check(s);
  if (c.status != Checked::kOk) return std::nullopt;
  std::vector<std::string> fields;
  for (std::size_t start = 0;;) {
    const std::size_t comma = c.body.find(',', start);
    fields.emplace_back(c.body.substr(start, comma - start));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return fields;
}

}  // namespace navemu::nmea
