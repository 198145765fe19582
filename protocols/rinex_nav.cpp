// RINEX navigation message files: GPS, QZSS, Galileo, BeiDou and GLONASS broadcast ephemerides.
//
//   RINEX 2.10/2.11 GPS navigation files (type 'N'): RINEX 2.11 Tables A3 (header) and A4
//     (data record); GLONASS navigation files (type 'G'): Tables A10 and A11; two-digit years
//     per section 6.5.
//   RINEX 3.0x navigation files (GPS or mixed): RINEX 3.05 appendix, navigation message file
//     header and the GPS, QZSS, Galileo, BDS and GLONASS data record descriptions; SBAS and
//     NavIC/IRNSS records are parsed past.
//   RINEX 4.0x navigation files: RINEX 4.00 navigation data records; every record starts with a
//     "> TYPE SV MESSAGE" line; the "> EPH" records of GPS and QZSS LNAV, Galileo INAV/FNAV,
//     BDS D1/D2 and GLONASS FDMA are read, whose lines have the RINEX 3 layout.

#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

#include <fmt/format.h>

#include "protocols/rinex.hpp"
#include "protocols/rinex_fields.hpp"

namespace navemu {
namespace {

using rinex::column;
using rinex::fail;
using rinex::is_blank;
using rinex::Lines;
using rinex::req_double;
using rinex::req_int;
using rinex::Where;

enum class NavFormat { v2, v3, v4 };

// Week 10000 is in the year 2171; beyond about 15000 the time no longer fits in int64 ns.
void require_week(const std::string& source, int line, const char* field, std::int64_t week) {
  if (week < 0 || week > 10'000) fail(source, line, field, fmt::format("must be in 0..10000, got {}", week));
}

// Field names of the seven BROADCAST ORBIT lines of a Kepler record by system, used in error
// messages: GPS (RINEX 2.11 Table A4, RINEX 3.05 GPS navigation data record) and QZSS (its
// QZSS record: the same layout, a fit interval flag), Galileo and BDS (RINEX 3.05 Galileo and
// BDS navigation data records; RINEX 4.00 INAV/FNAV and D1/D2 keep those lines). "spare"
// fields and the fit interval may be blank.
using OrbitFieldNames = std::array<std::array<const char*, 4>, 7>;
constexpr OrbitFieldNames kGpsOrbitFields{{
    {"IODE", "Crs", "Delta n", "M0"},
    {"Cuc", "e", "Cus", "sqrtA"},
    {"Toe", "Cic", "OMEGA0", "Cis"},
    {"i0", "Crc", "omega", "OMEGA DOT"},
    {"IDOT", "codes on L2", "GPS week", "L2 P data flag"},
    {"SV accuracy", "SV health", "TGD", "IODC"},
    {"transmission time", "fit interval", "spare", "spare"},
}};
constexpr OrbitFieldNames kGalileoOrbitFields{{
    {"IODnav", "Crs", "Delta n", "M0"},
    {"Cuc", "e", "Cus", "sqrtA"},
    {"Toe", "Cic", "OMEGA0", "Cis"},
    {"i0", "Crc", "omega", "OMEGA DOT"},
    {"IDOT", "data sources", "GAL week", "spare"},
    {"SISA", "SV health", "BGD E5a/E1", "BGD E5b/E1"},
    {"transmission time", "spare", "spare", "spare"},
}};
constexpr OrbitFieldNames kBeidouOrbitFields{{
    {"AODE", "Crs", "Delta n", "M0"},
    {"Cuc", "e", "Cus", "sqrtA"},
    {"Toe", "Cic", "OMEGA0", "Cis"},
    {"i0", "Crc", "omega", "OMEGA DOT"},
    {"IDOT", "spare", "BDT week", "spare"},
    {"SV accuracy", "SatH1", "TGD1", "TGD2"},
    {"transmission time", "AODC", "spare", "spare"},
}};

const OrbitFieldNames& orbit_fields(GnssSystem system) {
  switch (system) {
    case GnssSystem::kGalileo: return kGalileoOrbitFields;
    case GnssSystem::kBeidou: return kBeidouOrbitFields;
    default: return kGpsOrbitFields;
  }
}

bool may_be_blank(std::string_view field) { return field == "spare" || field == "fit interval"; }

constexpr int kOrbitLines = 7;
constexpr double kHalfWeek_s = 302400.0;

// A continuation (BROADCAST ORBIT) line: the first `indent` columns are blank and something
// follows (3X in RINEX 2, 4X in RINEX 3 and 4).
bool is_continuation(std::string_view line, std::size_t indent) {
  return line.size() > indent && is_blank(column(line, 0, indent)) && !is_blank(line);
}

// The epoch of a RINEX 2 record's first line: I2,1X,I2.2,1X,I2,1X,I2,1X,I2,1X,I2,F5.1 after
// the PRN (RINEX 2.11 Tables A4 and A11; two-digit years per section 6.5).
CalendarTime read_v2_epoch(const Where& w, std::string_view first) {
  CalendarTime c;
  c.year = rinex::full_year(req_int(w, first, 3, 2, "epoch"));
  c.month = req_int(w, first, 6, 2, "epoch");
  c.day = req_int(w, first, 9, 2, "epoch");
  c.hour = req_int(w, first, 12, 2, "epoch");
  c.minute = req_int(w, first, 15, 2, "epoch");
  c.second = req_double(w, first, 17, 5, "epoch");
  return c;
}

// The epoch of a RINEX 3/4 record's first line: A1,I2.2,1X,I4,5(1X,I2.2) (RINEX 3.05
// navigation data records), in the system's own time scale.
CalendarTime read_v3_epoch(const Where& w, std::string_view first) {
  CalendarTime c;
  c.year = req_int(w, first, 4, 4, "epoch");
  c.month = req_int(w, first, 9, 2, "epoch");
  c.day = req_int(w, first, 12, 2, "epoch");
  c.hour = req_int(w, first, 15, 2, "epoch");
  c.minute = req_int(w, first, 18, 2, "epoch");
  c.second = req_double(w, first, 21, 2, "epoch");
  return c;
}

// A Kepler record as read: the common orbit and clock (times in GPS time, full weeks
// resolved), and the seven lines' values for the system's own fields (NaN where blank).
struct KeplerRecord {
  KeplerEphemeris k;
  std::array<std::array<double, 4>, kOrbitLines> v{};
};

// One Kepler record of `system` (GPS, QZSS, Galileo, BDS): the "PRN / EPOCH / SV CLK" line at
// `n` and seven BROADCAST ORBIT lines. `first_line` is where the record starts (the "> EPH"
// line in RINEX 4), for `source`. Epochs and weeks are the system's own: GPS time (QZSST and
// GST are aligned with it to whole seconds and share its week numbering in RINEX: RINEX 3.05
// "GAL week ... continuous, same as GPS week"), BDT 14 s behind it with weeks from 2006.
KeplerRecord parse_kepler_record(const Lines& lines, int n, NavFormat format, int first_line, GnssSystem system) {
  const std::string& src = lines.source();
  const std::string_view first = lines.line(n);
  const Where w{src, n};
  const GnssSystemInfo& info = system_info(system);
  const OrbitFieldNames& names_of = orbit_fields(system);
  KeplerRecord rec;
  KeplerEphemeris& eph = rec.k;
  int prn = 0;
  CalendarTime c;
  std::size_t clock_col = 0;
  std::size_t orbit_col = 0;
  if (format == NavFormat::v2) {
    prn = req_int(w, first, 0, 2, "PRN");
    c = read_v2_epoch(w, first);
    clock_col = 22;
    orbit_col = 3;
  } else {
    if (column(first, 0, 1) != std::string_view(&info.rinex_letter, 1))
      fail(src, n, "PRN", fmt::format("expected a {} satellite number {}nn", info.name, info.rinex_letter));
    prn = req_int(w, first, 1, 2, "PRN");
    c = read_v3_epoch(w, first);
    clock_col = 23;
    orbit_col = 4;
  }
  eph.sat = SatId(system, prn);
  if (prn < 1 || !eph.sat.defined())
    fail(src, n, "PRN",
         fmt::format("{} PRN {} out of range {}-{}", info.name, prn, info.first_number, info.last_number));
  const std::string sat = fmt::format("{}{:02d}", info.rinex_letter, prn);
  // toc: the epoch in the system's time (RINEX 3.05 navigation data records); BDT + 14 s.
  const int bdt_s = system == GnssSystem::kBeidou ? kGpsMinusBdt_s : 0;
  eph.toc = rinex::epoch_to_gps(w, c, "epoch").plus_s(bdt_s);
  eph.af0_s = rinex::req_full_double(w, first, clock_col, 19, "af0");
  eph.af1_sps = rinex::req_full_double(w, first, clock_col + 19, 19, "af1");
  eph.af2_sps2 = rinex::req_full_double(w, first, clock_col + 38, 19, "af2");

  // BROADCAST ORBIT 1..7, four D19.12 fields each.
  auto& v = rec.v;
  for (int j = 0; j < kOrbitLines; ++j) {
    const int ln = n + 1 + j;
    const auto& names = names_of[static_cast<std::size_t>(j)];
    if (ln > lines.size())
      fail(src, ln, names[0],
           fmt::format("record truncated: end of file where BROADCAST ORBIT - {} of {} "
                       "(record at line {}) was expected",
                       j + 1, sat, n));
    const std::string_view line = lines.line(ln);
    if (!is_blank(column(line, 0, orbit_col)))
      fail(src, ln, names[0],
           fmt::format("record truncated: BROADCAST ORBIT - {} of {} (record at line {}) "
                       "expected, found the start of another record",
                       j + 1, sat, n));
    const Where wl{src, ln};
    for (std::size_t k = 0; k < 4; ++k) {
      const std::size_t col = orbit_col + 19 * k;
      v[static_cast<std::size_t>(j)][k] =
          may_be_blank(names[k]) ? rinex::opt_full_double(wl, line, col, 19, names[k]).value_or(std::nan(""))
                                 : rinex::req_full_double(wl, line, col, 19, names[k]);
    }
  }

  eph.crs_m = v[0][1];
  eph.delta_n_radps = v[0][2];
  eph.m0_rad = v[0][3];
  eph.cuc_rad = v[1][0];
  eph.e = v[1][1];
  eph.cus_rad = v[1][2];
  eph.sqrt_a_sqrtm = v[1][3];
  const double toe_s = v[2][0];
  eph.cic_rad = v[2][1];
  eph.omega0_rad = v[2][2];
  eph.cis_rad = v[2][3];
  eph.i0_rad = v[3][0];
  eph.crc_m = v[3][1];
  eph.omega_rad = v[3][2];
  eph.omega_dot_radps = v[3][3];
  eph.idot_radps = v[4][0];
  const char* week_name = names_of[4][2];
  const int week = rinex::integral(Where{src, n + 5}, v[4][2], week_name);

  if (!(eph.sqrt_a_sqrtm > 0.0))
    fail(src, n + 2, "sqrtA", fmt::format("must be positive, got {}", eph.sqrt_a_sqrtm));
  if (!(eph.e >= 0.0 && eph.e < 1.0))
    fail(src, n + 2, "e", fmt::format("eccentricity must be in [0, 1), got {}", eph.e));
  if (!(toe_s >= 0.0 && toe_s < static_cast<double>(kSecondsPerWeek)))
    fail(src, n + 3, "Toe", fmt::format("must be in [0, 604800) s of week, got {}", toe_s));
  require_week(src, n + 5, week_name, week);

  // toe = continuous week (RINEX 2.10+: "no roll-over") + Toe seconds. A week that puts toe
  // more than half a week from toc (a modulo-1024 week, or the week of transmission rather
  // than of toe) is corrected by whole weeks towards toc.
  eph.toe = system == GnssSystem::kBeidou ? from_week_tow(week + kBdtWeek0InGpsWeeks, toe_s).plus_s(bdt_s)
                                          : from_week_tow(week, toe_s);
  const double d_s = seconds_between(eph.toe, eph.toc);
  if (std::fabs(d_s) > kHalfWeek_s) {
    const std::int64_t k = std::llround(d_s / static_cast<double>(kSecondsPerWeek));
    eph.toe = GpsTime{eph.toe.ns - k * kSecondsPerWeek * kNsPerS};
  }
  eph.source = fmt::format("{}:{}", src, first_line);
  return rec;
}

// A GPS or QZSS LNAV record (IS-GPS-200 Table 20-III fields; IS-QZSS-PNT).
GpsEphemeris parse_gps_record(const Lines& lines, int n, NavFormat format, int first_line,
                              GnssSystem system = GnssSystem::kGps) {
  const KeplerRecord r = parse_kepler_record(lines, n, format, first_line, system);
  const auto& v = r.v;
  const std::string& src = lines.source();
  const Where w1{src, n + 1}, w5{src, n + 5}, w6{src, n + 6};
  GpsEphemeris eph;
  static_cast<KeplerEphemeris&>(eph) = r.k;
  eph.iode = rinex::integral(w1, v[0][0], "IODE");
  eph.codes_on_l2 = rinex::integral(w5, v[4][1], "codes on L2");
  eph.l2p_data_flag = rinex::integral(w5, v[4][3], "L2 P data flag");
  eph.ura_m = v[5][0];
  eph.health = rinex::integral(w6, v[5][1], "SV health");
  eph.tgd_s = v[5][2];
  eph.iodc = rinex::integral(w6, v[5][3], "IODC");
  eph.transmission_tow_s = v[6][0];
  const double fit = v[6][1];
  if (system == GnssSystem::kQzss) {
    // QZSS: a flag (IS-QZSS-PNT: 0 a 2 h curve fit, 1 longer), taken as 2 h and 4 h.
    eph.fit_interval_h = fit == 1.0 ? 4.0 : 2.0;
  } else {
    // Fit interval in hours (RINEX 2.11 section 6.6); blank or 0 means "not known", i.e. the
    // 4-hour curve fit of IS-GPS-200 20.3.3.4.3.1 (fit interval flag 0).
    eph.fit_interval_h = fit > 0.0 ? fit : 4.0;
  }
  return eph;
}

// A Galileo I/NAV or F/NAV record (Galileo OS SIS ICD 2.0 5.1; RINEX 3.05 Galileo record).
GalileoEphemeris parse_galileo_record(const Lines& lines, int n, NavFormat format, int first_line) {
  const KeplerRecord r = parse_kepler_record(lines, n, format, first_line, GnssSystem::kGalileo);
  const auto& v = r.v;
  const std::string& src = lines.source();
  GalileoEphemeris eph;
  static_cast<KeplerEphemeris&>(eph) = r.k;
  eph.iod_nav = rinex::integral(Where{src, n + 1}, v[0][0], "IODnav");
  eph.data_sources = rinex::integral(Where{src, n + 5}, v[4][1], "data sources");
  eph.sisa_m = v[5][0];
  eph.health = rinex::integral(Where{src, n + 6}, v[5][1], "SV health");
  eph.bgd_e1e5a_s = v[5][2];
  eph.bgd_e1e5b_s = v[5][3];
  eph.transmission_tow_s = v[6][0];
  return eph;
}

// A BDS D1 or D2 record (BDS-SIS-ICD-B1I 3.0 5.2.4; RINEX 3.05 BDS record).
BeidouEphemeris parse_beidou_record(const Lines& lines, int n, NavFormat format, int first_line) {
  const KeplerRecord r = parse_kepler_record(lines, n, format, first_line, GnssSystem::kBeidou);
  const auto& v = r.v;
  const std::string& src = lines.source();
  BeidouEphemeris eph;
  static_cast<KeplerEphemeris&>(eph) = r.k;
  eph.aode = rinex::integral(Where{src, n + 1}, v[0][0], "AODE");
  eph.ura_m = v[5][0];
  eph.health = rinex::integral(Where{src, n + 6}, v[5][1], "SatH1");
  eph.tgd1_s = v[5][2];
  eph.tgd2_s = v[5][3];
  eph.transmission_tow_s = v[6][0];
  eph.aodc = rinex::integral(Where{src, n + 7}, v[6][1], "AODC");
  return eph;
}

// Reads the Kepler record of a system letter at line `n` into `nav`; false for the other
// systems' records (GLONASS has its own, SBAS and NavIC are parsed past).
bool read_kepler_record(const Lines& lines, int n, NavFormat format, int first_line, char letter, NavData& nav) {
  switch (letter) {
    case 'G': nav.gps.push_back(parse_gps_record(lines, n, format, first_line)); return true;
    case 'J': nav.qzss.push_back(parse_gps_record(lines, n, format, first_line, GnssSystem::kQzss)); return true;
    case 'E': nav.galileo.push_back(parse_galileo_record(lines, n, format, first_line)); return true;
    case 'C': nav.beidou.push_back(parse_beidou_record(lines, n, format, first_line)); return true;
    default: return false;
  }
}

// Continuation lines per record of the systems that are parsed past in RINEX 3 files
// (RINEX 3.05 data record descriptions of each system): GLONASS 3 (4 from version 3.05, which
// added the status/health line), SBAS 3, Galileo, BDS, QZSS and NavIC/IRNSS 7.
int continuation_lines(char system, double version) {
  switch (system) {
    case 'R':
      return version >= 3.045 ? 4 : 3;
    case 'S':
      return 3;
    case 'E':
    case 'C':
    case 'J':
    case 'I':
      return 7;
    default:
      return -1;
  }
}

// Parses past one record of another system starting at line `n`; returns the next line.
int skip_other_record(const Lines& lines, int n, double version) {
  const std::string& src = lines.source();
  const std::string_view first = lines.line(n);
  const char sys = first[0];
  const int count = continuation_lines(sys, version);
  if (count < 0)
    fail(src, n, "satellite system",
         fmt::format("unknown satellite system '{}' at the start of a record", sys));
  const Where w{src, n};
  const int number = req_int(w, first, 1, 2, "PRN");
  if (number < 1)
    fail(src, n, "PRN", fmt::format("satellite number {}{:02d} out of range", sys, number));
  (void)req_int(w, first, 4, 4, "epoch");
  for (int j = 1; j <= count; ++j) {
    const int ln = n + j;
    if (ln > lines.size() || !is_continuation(lines.line(ln), 4))
      fail(src, ln, "BROADCAST ORBIT",
           fmt::format("record truncated: {} continuation lines expected for {}{:02d} (record at "
                       "line {}), found {}",
                       count, sys, number, n, j - 1));
  }
  int next = n + count + 1;
  // Writers of earlier versions may already add the later GLONASS line; take any further
  // continuation lines as part of this record.
  while (next <= lines.size() && is_continuation(lines.line(next), 4)) ++next;
  return next;
}

// One GLONASS record (RINEX 2.11 Table A11; RINEX 3.05 GLONASS navigation data record; RINEX
// 4.00 "> EPH Rnn FDMA"):
// the "SV / EPOCH / SV CLK" line at `n` (epoch tb in UTC, -TauN, +GammaN, message frame time)
// and three BROADCAST ORBIT lines of X, Y, Z (km), their rates (km/s) and lunisolar
// accelerations (km/s^2) with health, frequency number and age; the fourth line of 3.05 and
// 4.00 (status flags, group delay, URAI, health flags) is parsed past. Returns the next line.
// RINEX 2 has no system letter (3X indents) and three lines.
int parse_glonass_record(const Lines& lines, int n, int first_line, NavFormat format, double version, NavData& nav) {
  const std::string& src = lines.source();
  const std::string_view first = lines.line(n);
  const Where w{src, n};
  GlonassEphemeris eph;
  int slot = 0;
  CalendarTime c;
  std::size_t clock_col = 23, orbit_col = 4;
  if (format == NavFormat::v2) {
    slot = req_int(w, first, 0, 2, "PRN");  // then 3X,4D19.12 lines (RINEX 2.11 Table A11)
    c = read_v2_epoch(w, first);
    clock_col = 22;
    orbit_col = 3;
  } else {
    slot = req_int(w, first, 1, 2, "PRN");
    c = read_v3_epoch(w, first);
  }
  eph.sat = SatId(GnssSystem::kGlonass, slot);
  if (slot < 1 || !eph.sat.defined())
    fail(src, n, "PRN", fmt::format("GLONASS slot {} out of range {}-{}", slot, eph.sat.info().first_number, eph.sat.info().last_number));
  (void)rinex::epoch_to_gps(w, c, "epoch");  // checks the date
  eph.tb = gps_from_utc(c, nav.leap_seconds);
  eph.tau_n_s = -rinex::req_full_double(w, first, clock_col, 19, "-TauN");
  eph.gamma_n = rinex::req_full_double(w, first, clock_col + 19, 19, "GammaN");
  eph.frame_time_s = rinex::req_full_double(w, first, clock_col + 38, 19, "message frame time");
  static constexpr const char* kNames[3][4] = {{"X", "X velocity", "X acceleration", "health"},
                                               {"Y", "Y velocity", "Y acceleration", "frequency number"},
                                               {"Z", "Z velocity", "Z acceleration", "age of information"}};
  std::array<double, 3> last{};
  for (int j = 0; j < 3; ++j) {
    const int ln = n + 1 + j;
    if (ln > lines.size() || !is_continuation(lines.line(ln), orbit_col))
      fail(src, std::min(ln, lines.size()), kNames[j][0],
           fmt::format("record truncated: BROADCAST ORBIT - {} of R{:02d} (record at line {}) expected", j + 1, slot, n));
    const Where wl{src, ln};
    const std::string_view line = lines.line(ln);
    const auto field = [&](int k) {
      return rinex::req_full_double(wl, line, orbit_col + 19 * static_cast<std::size_t>(k), 19, kNames[j][k]);
    };
    eph.p_pz90_m[j] = field(0) * 1e3;
    eph.v_pz90_mps[j] = field(1) * 1e3;
    eph.a_pz90_mps2[j] = field(2) * 1e3;
    last[static_cast<std::size_t>(j)] = field(3);
  }
  eph.health = rinex::integral(Where{src, n + 1}, last[0], "health");
  eph.frequency_channel = rinex::integral(Where{src, n + 2}, last[1], "frequency number");
  eph.age_days = last[2];
  // RINEX 3.05: -7..+13 (+7..+13 only before 2005); the part's range today is -7..+6.
  if (eph.frequency_channel < -7 || eph.frequency_channel > 13)
    fail(src, n + 2, "frequency number", fmt::format("must be in -7..13, got {}", eph.frequency_channel));
  if (!(eph.p_pz90_m.norm() > 1.0e6))
    fail(src, n + 1, "X", "the satellite's position must lie outside the Earth");
  eph.source = fmt::format("{}:{}", src, first_line);
  nav.glonass.push_back(eph);
  int next = n + 4;
  const int expected = format == NavFormat::v2 ? 3 : continuation_lines('R', version);
  for (; next <= n + expected; ++next)
    if (next > lines.size() || !is_continuation(lines.line(next), 4))
      fail(src, std::min(next, lines.size()), "BROADCAST ORBIT",
           fmt::format("record truncated: {} continuation lines expected for R{:02d} (record at line {})", expected, slot, n));
  while (format != NavFormat::v2 && next <= lines.size() && is_continuation(lines.line(next), 4)) ++next;
  return next;
}

std::array<double, 4> read_four(const Lines& lines, int n, std::size_t col, const char* field) {
  const Where w{lines.source(), n};
  const std::string_view line = lines.line(n);
  std::array<double, 4> out{};
  for (std::size_t k = 0; k < 4; ++k) out[k] = req_double(w, line, col + 12 * k, 12, field);
  return out;
}

// The reference time of a system time offset given as seconds and week of its first scale
// (RINEX 3.05 TIME SYSTEM CORR: T "seconds into GPS/GAL/BDS/IRN week", W "GPS/GAL/IRN/BDS
// week, continuous number"): BDS weeks count from 2006 and BDT is 14 s behind GPS time (BDS
// ICD 3.0 section 4.2); Galileo and QZSS share GPS's numbering in RINEX. GLONASS corrections
// carry W = 0 and T = 0: the GPS epoch then, harmless as their a1 is 0.
GpsTime offset_reference(std::string_view type, int week, double sow_s) {
  if (week == 0 && sow_s == 0.0) return GpsTime{};
  if (type.substr(0, 2) == "BD") return from_week_tow(week + kBdtWeek0InGpsWeeks, sow_s + kGpsMinusBdt_s);
  return from_week_tow(week, sow_s);
}

// RINEX 3.05 navigation header "TIME SYSTEM CORR": A4,1X,D17.10,D16.9,1X,I6,1X,I4,1X,A5,1X,I2
// (type, a0, a1, T, W, SBAS/UTC provider, UTC id); T and W may be blank for GLONASS.
TimeSystemOffset read_time_system_corr(const Lines& lines, int n) {
  const Where w{lines.source(), n};
  const std::string_view line = lines.line(n);
  TimeSystemOffset o;
  o.type = std::string(rinex::trim(column(line, 0, 4)));
  if (o.type.size() != 4)
    fail(lines.source(), n, "TIME SYSTEM CORR type", fmt::format("expected a four-letter correction type such as GAGP or GPUT, got '{}'", o.type));
  o.a0_s = req_double(w, line, 5, 17, "TIME SYSTEM CORR a0");
  o.a1_sps = req_double(w, line, 22, 16, "TIME SYSTEM CORR a1");
  const double sow_s = rinex::opt_double(w, line, 38, 7, "TIME SYSTEM CORR T").value_or(0.0);
  const double week = rinex::opt_double(w, line, 45, 5, "TIME SYSTEM CORR W").value_or(0.0);
  if (!(sow_s >= 0.0 && sow_s < 604800.0))
    fail(lines.source(), n, "TIME SYSTEM CORR T", fmt::format("reference time {} s is not a second of the week (0-604799)", sow_s));
  const int wk = rinex::integral(w, week, "TIME SYSTEM CORR W");
  require_week(lines.source(), n, "TIME SYSTEM CORR W", wk);
  o.t_ref = offset_reference(o.type, wk, sow_s);
  o.source = fmt::format("{}:{}", lines.source(), n);
  return o;
}

// RINEX 4.00 "> STO SNN MSG" record: line 1 the reference epoch (4X,I4,5(1X,I2.2)) in the
// satellite system's time and the correction type (1X,A18: GAGP, GPUT, ...), line 2 the
// transmission time, a0, a1, a2 (4X,4D19.12).
TimeSystemOffset read_sto(const Lines& lines, int sto_line, char system_letter, const NavData& nav) {
  const int n1 = sto_line + 1, n2 = sto_line + 2;
  if (n2 > lines.size() || !is_continuation(lines.line(n1), 4) || !is_continuation(lines.line(n2), 4))
    fail(lines.source(), std::min(n2, lines.size()), "STO", "STO record truncated: expected 2 lines after '> STO'");
  const Where w1{lines.source(), n1}, w2{lines.source(), n2};
  const std::string_view l1 = lines.line(n1), l2 = lines.line(n2);
  TimeSystemOffset o;
  const std::string_view rest = rinex::trim(l1.substr(std::min<std::size_t>(l1.size(), 23)));
  o.type = std::string(rest.substr(0, rest.find(' ')));
  if (o.type.size() != 4)
    fail(lines.source(), n1, "STO type", fmt::format("expected a four-letter correction type such as GAGP or GPUT, got '{}'", o.type));
  const CalendarTime c = read_v3_epoch(w1, l1);
  const GpsTime epoch = rinex::epoch_to_gps(w1, c, "STO epoch");
  // Epochs are in the system's time: BDT 14 s behind GPS time, GLONASS records in UTC.
  o.t_ref = system_letter == 'C'   ? epoch.plus_s(kGpsMinusBdt_s)
            : system_letter == 'R' ? gps_from_utc(c, nav.leap_seconds)
                                   : epoch;
  o.a0_s = rinex::req_full_double(w2, l2, 23, 19, "STO a0");
  o.a1_sps = rinex::req_full_double(w2, l2, 42, 19, "STO a1");
  o.a2_sps2 = rinex::opt_full_double(w2, l2, 61, 19, "STO a2").value_or(0.0);
  o.source = fmt::format("{}:{}", lines.source(), sto_line);
  return o;
}

// RINEX 4.00 "> ION Gnn LNAV" record (GPS Klobuchar): line 1 epoch (4X,I4,5(1X,I2.2)) and
// alpha0..alpha2 (3D19.12), line 2 alpha3 beta0..beta2 (4X,4D19.12), line 3 beta3 (4X,D19.12).
KlobucharCoefficients read_ion_klobuchar(const Lines& lines, int ion_line) {
  const char* names[8] = {"alpha0", "alpha1", "alpha2", "alpha3", "beta0", "beta1", "beta2", "beta3"};
  double v[8] = {};
  const std::size_t first_col[3] = {23, 4, 4};
  const int per_line[3] = {3, 4, 1};
  int k = 0;
  for (int l = 0; l < 3; ++l) {
    const int n = ion_line + 1 + l;
    if (n > lines.size() || !is_continuation(lines.line(n), 4))
      fail(lines.source(), std::min(n, lines.size()), names[k],
           "ION record truncated: expected 3 lines after '> ION'");
    const Where w{lines.source(), n};
    for (int j = 0; j < per_line[l]; ++j, ++k)
      v[k] = req_double(w, lines.line(n), first_col[l] + 19 * static_cast<std::size_t>(j), 19,
                        names[k]);
  }
  return KlobucharCoefficients{{v[0], v[1], v[2], v[3]}, {v[4], v[5], v[6], v[7]}};
}

NavData parse_nav_text(std::string text, const std::string& source) {
  const Lines lines(std::move(text), source);
  const rinex::VersionLine vl = rinex::read_version_line(lines);

  NavData nav;
  nav.source = source;
  nav.rinex_version = vl.version;

  NavFormat format = NavFormat::v2;
  if (vl.version >= 2.0 && vl.version < 3.0) {
    format = NavFormat::v2;
    if (vl.type == 'H')
      fail(source, 1, "file type",
           "RINEX 2 'H' navigation files (GEO/SBAS) are not supported: GPS ('N') and GLONASS ('G') are");
  } else if (vl.version >= 3.0 && vl.version < 4.0) {
    format = NavFormat::v3;
  } else if (vl.version >= 4.0 && vl.version < 5.0) {
    format = NavFormat::v4;
  } else {
    fail(source, 1, "version",
         fmt::format("unsupported RINEX version {} (navigation files 2.x, 3.x and 4.x are read)",
                     vl.version));
  }
  // RINEX 2 GLONASS navigation files are type 'G' (RINEX 2.11 Table A10).
  const bool glonass_v2 = format == NavFormat::v2 && vl.type == 'G';
  if (vl.type != 'N' && !glonass_v2)
    fail(source, 1, "file type",
         fmt::format("'{}' is not a navigation file type (expected 'N', or 'G' in RINEX 2)", vl.type));

  // Header (RINEX 2.11 Table A3; RINEX 3.05 and 4.00 navigation header descriptions).
  std::optional<std::array<double, 4>> alpha;
  std::optional<std::array<double, 4>> beta;
  std::optional<std::size_t> delta_utc;  // index of the RINEX 2 DELTA-UTC offset
  int n = 2;
  bool end_of_header = false;
  for (; n <= lines.size(); ++n) {
    const std::string_view line = lines.line(n);
    const std::string_view label = rinex::header_label(line);
    if (label == "END OF HEADER") {
      end_of_header = true;
      break;
    }
    if (format == NavFormat::v2 && label == "ION ALPHA") {
      alpha = read_four(lines, n, 2, "ION ALPHA");  // 2X,4D12.4
    } else if (format == NavFormat::v2 && label == "ION BETA") {
      beta = read_four(lines, n, 2, "ION BETA");
    } else if (label == "IONOSPHERIC CORR") {
      // A4,1X,4D12.4 (RINEX 3.05 navigation header, IONOSPHERIC CORR). Several GPSA/GPSB lines with time marks may be
      // given (3.04+); the first applies.
      const std::string_view kind = rinex::trim(column(line, 0, 4));
      if (kind == "GPSA" && !alpha) alpha = read_four(lines, n, 5, "IONOSPHERIC CORR GPSA");
      if (kind == "GPSB" && !beta) beta = read_four(lines, n, 5, "IONOSPHERIC CORR GPSB");
      if (kind == "GAL" && !nav.nequick_g) {  // ai0, ai1, ai2 and a blank fourth field
        const Where w{source, n};
        nav.nequick_g = std::array<double, 3>{req_double(w, line, 5, 12, "IONOSPHERIC CORR GAL ai0"),
                                              req_double(w, line, 17, 12, "IONOSPHERIC CORR GAL ai1"),
                                              req_double(w, line, 29, 12, "IONOSPHERIC CORR GAL ai2")};
      }
    } else if (format != NavFormat::v2 && label == "TIME SYSTEM CORR") {
      nav.time_offsets.push_back(read_time_system_corr(lines, n));
    } else if (format == NavFormat::v2 && !glonass_v2 && label == "DELTA-UTC: A0,A1,T,W") {
      // 3X,2D19.12,2I9 (RINEX 2.11 Table A3): GPS - UTC.
      const Where w{source, n};
      TimeSystemOffset o{"GPUT", req_double(w, line, 3, 19, "DELTA-UTC A0"), req_double(w, line, 22, 19, "DELTA-UTC A1"),
                         0.0, {}, fmt::format("{}:{}", source, n)};
      const int t = req_int(w, line, 41, 9, "DELTA-UTC T"), week = req_int(w, line, 50, 9, "DELTA-UTC W");
      if (t < 0 || t >= 604800) fail(source, n, "DELTA-UTC T", fmt::format("reference time {} s is not a second of the week (0-604799)", t));
      require_week(source, n, "DELTA-UTC W", week);
      o.t_ref = from_week_tow(week, t);
      delta_utc = nav.time_offsets.size();
      nav.time_offsets.push_back(o);
    } else if (glonass_v2 && label == "CORR TO SYSTEM TIME") {
      // 3I6,3X,D19.12 (RINEX 2.11 Table A10): reference date and -TauC (GLONASST - UTC(SU)).
      const Where w{source, n};
      CalendarTime c;
      c.year = req_int(w, line, 0, 6, "CORR TO SYSTEM TIME year");
      c.month = req_int(w, line, 6, 6, "CORR TO SYSTEM TIME month");
      c.day = req_int(w, line, 12, 6, "CORR TO SYSTEM TIME day");
      const GpsTime t = rinex::epoch_to_gps(w, c, "CORR TO SYSTEM TIME date");
      nav.time_offsets.push_back(
          TimeSystemOffset{"GLUT", req_double(w, line, 21, 19, "CORR TO SYSTEM TIME -TauC"), 0.0, 0.0, t, fmt::format("{}:{}", source, n)});
    } else if (label == "LEAP SECONDS") {
      nav.leap_seconds = req_int(Where{source, n}, line, 0, 6, "LEAP SECONDS");  // I6
    }
  }
  if (!end_of_header)
    fail(source, lines.size(), "END OF HEADER", "end of file before END OF HEADER");
  if (alpha && beta) nav.klobuchar = KlobucharCoefficients{*alpha, *beta};

  // Data records.
  ++n;
  while (n <= lines.size()) {
    const std::string_view line = lines.line(n);
    if (is_blank(line)) {
      ++n;
      continue;
    }
    switch (format) {
      case NavFormat::v2:
        if (is_blank(column(line, 0, 3)))
          fail(source, n, "PRN",
               "expected the first line of a record (PRN / EPOCH / SV CLK), found a "
               "continuation line: the previous record has too many lines");
        if (glonass_v2) {
          n = parse_glonass_record(lines, n, n, NavFormat::v2, vl.version, nav);
        } else {
          nav.gps.push_back(parse_gps_record(lines, n, NavFormat::v2, n));
          n += 1 + kOrbitLines;
        }
        break;
      case NavFormat::v3:
        if (line[0] == ' ')
          fail(source, n, "PRN",
               "expected the first line of a record (SV / EPOCH / SV CLK), found a "
               "continuation line: the previous record has too many lines");
        if (read_kepler_record(lines, n, NavFormat::v3, n, line[0], nav)) {
          n += 1 + kOrbitLines;
        } else if (line[0] == 'R') {
          n = parse_glonass_record(lines, n, n, NavFormat::v3, vl.version, nav);
        } else {
          n = skip_other_record(lines, n, vl.version);
          ++nav.skipped_records;
        }
        break;
      case NavFormat::v4: {
        // "> EPH G01 LNAV", "> STO G   LNAV", "> ION G   LNAV", "> EOP ..." (RINEX 4.00).
        if (line[0] != '>')
          fail(source, n, "record type",
               "expected a '>' record line (e.g. '> EPH G01 LNAV'): the previous record has "
               "too many lines");
        std::array<std::string_view, 3> tok{};
        std::size_t count = 0;
        std::string_view rest = line.substr(1);
        while (count < tok.size()) {
          rest = rinex::trim(rest);
          if (rest.empty()) break;
          const std::size_t sp = rest.find(' ');
          tok[count++] = rest.substr(0, sp);
          rest = sp == std::string_view::npos ? std::string_view{} : rest.substr(sp);
        }
        if (count < 2) fail(source, n, "record type", "incomplete '>' record line");
        // The messages whose records have the RINEX 3 Kepler layout (RINEX 4.00 navigation
        // data records): GPS and QZSS LNAV, Galileo INAV and FNAV, BDS D1 and D2.
        const auto kepler_message = [](char letter, std::string_view message) {
          switch (letter) {
            case 'G':
            case 'J': return message == "LNAV";
            case 'E': return message == "INAV" || message == "FNAV";
            case 'C': return message == "D1" || message == "D2";
            default: return false;
          }
        };
        if (tok[0] == "EPH" && count == 3 && tok[1].size() == 3 && tok[1][0] == 'R' && tok[2] == "FDMA") {
          const int rec = n + 1;
          if (rec > lines.size() || column(lines.line(rec), 0, 3) != tok[1])
            fail(source, std::min(rec, lines.size()), "PRN", fmt::format("record of '{}' expected after line {}", tok[1], n));
          n = parse_glonass_record(lines, rec, n, NavFormat::v4, vl.version, nav);
        } else if (tok[0] == "EPH" && count == 3 && tok[1].size() == 3 && kepler_message(tok[1][0], tok[2])) {
          const int rec = n + 1;
          if (rec > lines.size())
            fail(source, rec, "PRN", "record truncated: end of file after '> EPH' line");
          if (column(lines.line(rec), 0, 3) != tok[1])
            fail(source, rec, "PRN",
                 fmt::format("record of '{}' expected after line {}, found '{}'", tok[1], n,
                             column(lines.line(rec), 0, 3)));
          read_kepler_record(lines, rec, NavFormat::v4, n, tok[1][0], nav);
          n = rec + 1 + kOrbitLines;
        } else {
          // The first GPS LNAV ionosphere record supplies the Klobuchar coefficients (RINEX 4
          // headers carry none).
          if (tok[0] == "ION" && count == 3 && tok[1].size() == 3 && tok[1][0] == 'G' &&
              tok[2] == "LNAV" && !nav.klobuchar)
            nav.klobuchar = read_ion_klobuchar(lines, n);
          if (tok[0] == "STO" && count == 3 && !tok[1].empty()) {
            nav.time_offsets.push_back(read_sto(lines, n, tok[1][0], nav));
            n += 3;
            break;
          }
          // SBAS, NavIC, the CNAV messages (GPS and QZSS CNAV/CNV2, BDS CNV1-3), EOP and
          // other ION records.
          ++nav.skipped_records;
          ++n;
          while (n <= lines.size() && column(lines.line(n), 0, 1) != ">") ++n;
        }
        break;
      }
    }
  }
  // RINEX 2 files carry W as written by the converter: continuous, modulo 1024, or the
  // broadcast 8-bit WNt expanded against the wrong week (07590920.05n: 1061 in GPS week 1316).
  // Only its low 8 bits are broadcast (IS-GPS-200 20.3.3.5.2.4): the week is taken as the one
  // with those bits nearest to the first record's.
  if (delta_utc && !nav.gps.empty()) {
    TimeSystemOffset& o = nav.time_offsets[*delta_utc];
    const WeekTow ref = to_week_tow(o.t_ref);
    const int near = to_week_tow(nav.gps.front().toe).week;
    const int week = near + ((ref.week - near) % 256 + 384) % 256 - 128;
    o.t_ref = from_week_tow(week, ref.tow_s);
  }
  return nav;
}

}  // namespace

NavData parse_rinex_nav(std::string text, const std::string& source) {
  return parse_nav_text(std::move(text), source);
}

NavData parse_rinex_nav(std::istream& in, const std::string& source) {
  return parse_nav_text(rinex::read_stream(in, source), source);
}

}  // namespace navemu
