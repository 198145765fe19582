// RINEX 3.04 observation file writer.
//
//   Header records: RINEX 3.04 appendix, "GNSS observation data file - header section
//     description" (labels in columns 61-80, content in columns 1-60); section 5.3 (marker
//     type), section 5.7 (signal strength unit), section 5.8 (PGM / RUN BY / DATE).
//   Data records: RINEX 3.04 appendix, "GNSS observation data file - data record
//     description": an epoch record "> yyyy mm dd hh mm ss.sssssss  f nnn" then one line per
//     satellite, "Gnn" followed by m(F14.3,I1,I1).
//   Trailing blanks of data records are not written (variable-length records, RINEX 2.11
//     section 6.3; the readers of rinex_obs.cpp and RTKLIB treat missing columns as blank).
//
// Every field is checked against its Fortran format before anything is written, so a value
// that does not fit raises std::invalid_argument instead of shifting the columns after it.

#include "protocols/rinex_writer.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "core/time.hpp"

namespace navemu {
namespace {

constexpr std::size_t kTypesPerLine = 13;        // SYS / # / OBS TYPES: 13(1X,A3)
constexpr std::size_t kGloSlotsPerLine = 8;      // GLONASS SLOT / FRQ #: 8(A1,I2.2,1X,I2,1X)
constexpr std::size_t kContentWidth = 60;        // header content, columns 1-60
constexpr std::string_view kSystemLetters = "GRECJSI";  // RINEX 3.04 section 3.5

[[noreturn]] void invalid(const std::string& what) {
  throw std::invalid_argument("RINEX observation writer: " + what);
}

// Header text fields are A-format: printable ASCII that fits its columns.
std::string text_field(const std::string& s, std::size_t width, std::string_view what) {
  for (const char c : s)
    if (c < ' ' || c > '~')
      invalid(fmt::format("{}: '{}' contains a character that is not printable ASCII", what, s));
  if (s.size() > width)
    invalid(fmt::format("{}: '{}' is longer than its {} columns", what, s, width));
  return fmt::format("{:<{}}", s, width);
}

// Fortran Fw.d: right-justified, d decimals; a number that needs more than w columns is an
// error (Fortran would print asterisks).
std::string fixed(double v, std::size_t width, int decimals, std::string_view what) {
  if (!std::isfinite(v)) invalid(fmt::format("{}: {} is not a finite number", what, v));
  std::string s = fmt::format("{:{}.{}f}", v, width, decimals);
  if (s.size() > width)
    invalid(fmt::format("{}: {} does not fit F{}.{}", what, v, width, decimals));
  return s;
}

// One header record: content padded to 60 columns, label from column 61.
void header_line(std::string& out, const std::string& content, std::string_view label) {
  if (content.size() > kContentWidth)
    throw std::logic_error(fmt::format("RINEX header record {} longer than 60 columns", label));
  out += content;
  out.append(kContentWidth - content.size(), ' ');
  out += label;
  out += '\n';
}

void rtrim(std::string& s) {
  while (!s.empty() && s.back() == ' ') s.pop_back();
}

// An epoch as calendar fields in GPS time with seconds in units of 100 ns (the resolution of
// F11.7 / F13.7), rounded to nearest.
struct EpochFields {
  CalendarTime cal;       // seconds are whole
  int whole_seconds = 0;  // 0..59
  std::int64_t ticks = 0; // fraction of the second in 100 ns units, 0..9'999'999
};

EpochFields epoch_fields(GpsTime t) {
  constexpr std::int64_t kTick_ns = 100;
  constexpr std::int64_t kTicksPerS = kNsPerS / kTick_ns;
  // Round half away from zero to 100 ns, then split into whole seconds and ticks (floor, so
  // that the fraction is never negative).
  const std::int64_t ticks = (t.ns >= 0 ? t.ns + kTick_ns / 2 : t.ns - kTick_ns / 2) / kTick_ns;
  std::int64_t whole = ticks / kTicksPerS;
  std::int64_t frac = ticks % kTicksPerS;
  if (frac < 0) {
    frac += kTicksPerS;
    --whole;
  }
  EpochFields f;
  f.cal = calendar_from_gps(GpsTime{whole * kNsPerS});
  f.whole_seconds = static_cast<int>(std::lround(f.cal.second));
  f.ticks = frac;
  if (f.cal.year < 1980 || f.cal.year > 9999)
    invalid(fmt::format("epoch year {} outside the I4 field", f.cal.year));
  return f;
}

// TIME OF FIRST OBS / TIME OF LAST OBS: 5I6,F13.7,5X,A3 (time system GPS: the epochs are GPS
// time, RINEX 3.04 section 3.1).
std::string time_of_obs(GpsTime t) {
  const EpochFields f = epoch_fields(t);
  return fmt::format("{:6d}{:6d}{:6d}{:6d}{:6d}{:5d}.{:07d}     GPS", f.cal.year, f.cal.month,
                     f.cal.day, f.cal.hour, f.cal.minute, f.whole_seconds, f.ticks);
}

bool is_phase(const std::string& code) { return !code.empty() && code[0] == 'L'; }

// Satellite identifier A1,I2.2: "G05".
std::string sat_id(const SatObs& s) { return fmt::format("{}{:02d}", s.system, s.number); }

void check_types(const ObsHeader& header) {
  if (header.types.empty()) invalid("SYS / # / OBS TYPES: no observation types in the header");
  for (const auto& [sys, list] : header.types) {
    if (kSystemLetters.find(sys) == std::string_view::npos)
      invalid(fmt::format("SYS / # / OBS TYPES: '{}' is not a satellite system letter (one of {})",
                          sys, kSystemLetters));
    if (list.empty() || list.size() > 999)
      invalid(fmt::format("SYS / # / OBS TYPES: system {} has {} types (1..999 allowed)", sys,
                          list.size()));
    for (const std::string& code : list) {
      const bool ok = code.size() == 3 && std::all_of(code.begin(), code.end(), [](char c) {
                        return c > ' ' && c <= '~';
                      });
      if (!ok)
        invalid(fmt::format("SYS / # / OBS TYPES: system {}: '{}' is not a 3-character "
                            "observation code",
                            sys, code));
    }
  }
}

// ---- header (RINEX 3.04 appendix, observation header section description) ----

void write_header(std::string& out, const ObsHeader& h, const std::vector<ObsEpoch>& epochs,
                  const ObsWriterInfo& info) {
  // RINEX VERSION / TYPE: F9.2,11X,A1,19X,A1,19X. 'M' when more than one system is present.
  const char file_system = h.types.size() == 1 ? h.types.begin()->first : 'M';
  header_line(out, fmt::format("{:9.2f}{:11}{:<20}{}", 3.04, "", "OBSERVATION DATA", file_system),
              "RINEX VERSION / TYPE");

  // PGM / RUN BY / DATE: 3A20; the date is the caller's (section 5.8 form
  // "yyyymmdd hhmmss UTC"), never the wall clock, so that output is reproducible.
  header_line(out,
              text_field(info.program, 20, "PGM / RUN BY / DATE program") +
                  text_field(info.run_by, 20, "PGM / RUN BY / DATE run by") +
                  text_field(info.date, 20, "PGM / RUN BY / DATE date"),
              "PGM / RUN BY / DATE");

  // COMMENT: A60. Long comments continue on further COMMENT records, broken at a blank when
  // there is one; embedded newlines start a new record.
  for (const std::string& comment : info.comments) {
    std::string_view rest(comment);
    do {
      std::string_view piece = rest.substr(0, rest.find('\n'));
      std::size_t consumed = piece.size() + (piece.size() < rest.size() ? 1 : 0);
      if (piece.size() > kContentWidth) {
        const std::size_t cut = piece.substr(0, kContentWidth + 1).rfind(' ');
        if (cut != std::string_view::npos && cut > 0) {
          piece = piece.substr(0, cut);
          consumed = cut + 1;
        } else {
          piece = piece.substr(0, kContentWidth);
          consumed = kContentWidth;
        }
      }
      std::string text = text_field(std::string(piece), kContentWidth, "COMMENT");
      rtrim(text);
      header_line(out, text, "COMMENT");
      rest.remove_prefix(consumed);
    } while (!rest.empty());
  }

  header_line(out, text_field(h.marker_name, 60, "MARKER NAME"), "MARKER NAME");  // A60
  if (info.marker_type.empty()) invalid("MARKER TYPE: empty (section 5.3 keyword required)");
  header_line(out, text_field(info.marker_type, 20, "MARKER TYPE"), "MARKER TYPE");  // A20,40X
  header_line(out,
              text_field(info.observer, 20, "OBSERVER / AGENCY observer") +  // A20,A40
                  text_field(info.agency, 40, "OBSERVER / AGENCY agency"),
              "OBSERVER / AGENCY");
  header_line(out,
              text_field(info.receiver_number, 20, "REC # / TYPE / VERS number") +  // 3A20
                  text_field(info.receiver_type, 20, "REC # / TYPE / VERS type") +
                  text_field(info.receiver_version, 20, "REC # / TYPE / VERS version"),
              "REC # / TYPE / VERS");
  header_line(out,
              text_field(info.antenna_number, 20, "ANT # / TYPE number") +  // 2A20
                  text_field(info.antenna_type, 20, "ANT # / TYPE type"),
              "ANT # / TYPE");

  // APPROX POSITION XYZ and ANTENNA: DELTA H/E/N: 3F14.4 (m).
  std::string pos;
  std::string delta;
  for (int k = 0; k < 3; ++k) {
    pos += fixed(h.approx_position_ecef_m[k], 14, 4, "APPROX POSITION XYZ");
    delta += fixed(h.antenna_delta_hen_m[k], 14, 4, "ANTENNA: DELTA H/E/N");
  }
  header_line(out, pos, "APPROX POSITION XYZ");
  header_line(out, delta, "ANTENNA: DELTA H/E/N");

  // SYS / # / OBS TYPES: A1,2X,I3,13(1X,A3); continuation records 6X,13(1X,A3).
  for (const auto& [sys, list] : h.types) {
    std::string line = fmt::format("{}  {:3d}", sys, list.size());
    for (std::size_t i = 0; i < list.size(); ++i) {
      if (i > 0 && i % kTypesPerLine == 0) {
        header_line(out, line, "SYS / # / OBS TYPES");
        line.assign(6, ' ');
      }
      line += ' ';
      line += list[i];
    }
    header_line(out, line, "SYS / # / OBS TYPES");
  }

  // SIGNAL STRENGTH UNIT: A20 (section 5.7); S observations are C/N0 in dB-Hz.
  header_line(out, "DBHZ", "SIGNAL STRENGTH UNIT");

  // INTERVAL: F10.3 (s), when known.
  if (h.interval_s > 0.0) header_line(out, fixed(h.interval_s, 10, 3, "INTERVAL"), "INTERVAL");

  header_line(out, time_of_obs(epochs.front().time), "TIME OF FIRST OBS");
  header_line(out, time_of_obs(epochs.back().time), "TIME OF LAST OBS");

  // SYS / PHASE SHIFT (required since 3.01): A1,1X,A3,1X,F8.5, satellite list blank = all
  // satellites of the system. The phases are generated already aligned with the reference
  // signal of their band, so the correction applied is 0.00000 for every phase type. A system
  // without phase types gets a record with its letter only (code blank: none applied).
  for (const auto& [sys, list] : h.types) {
    bool any = false;
    for (const std::string& code : list) {
      if (!is_phase(code)) continue;
      header_line(out, fmt::format("{} {} {:8.5f}", sys, code, 0.0), "SYS / PHASE SHIFT");
      any = true;
    }
    if (!any) header_line(out, std::string(1, sys), "SYS / PHASE SHIFT");
  }

  if (h.types.count('R') != 0) {
    // GLONASS SLOT / FRQ #: I3,1X,8(A1,I2.2,1X,I2,1X); continuation 4X,8(...).
    const auto& glo = info.glonass_frequency_numbers;
    std::string line = fmt::format("{:3d} ", glo.size());
    std::size_t n = 0;
    for (const auto& [slot, k] : glo) {
      if (slot < 1 || slot > 99)
        invalid(fmt::format("GLONASS SLOT / FRQ #: slot {} outside 1..99", slot));
      if (k < -7 || k > 13)
        invalid(fmt::format("GLONASS SLOT / FRQ #: R{:02d} frequency number {} outside -7..13",
                            slot, k));
      if (n > 0 && n % kGloSlotsPerLine == 0) {
        rtrim(line);
        header_line(out, line, "GLONASS SLOT / FRQ #");
        line.assign(4, ' ');
      }
      line += fmt::format("R{:02d} {:2d} ", slot, k);
      ++n;
    }
    rtrim(line);
    header_line(out, line, "GLONASS SLOT / FRQ #");

    // GLONASS COD/PHS/BIS: 4(1X,A3,1X,F8.3) (m); code and phase of the simulated signals
    // carry no inter-frequency code-phase bias.
    std::string bis;
    for (const char* code : {"C1C", "C1P", "C2C", "C2P"}) bis += fmt::format(" {} {:8.3f}", code, 0.0);
    header_line(out, bis, "GLONASS COD/PHS/BIS");
  }

  // LEAP SECONDS: I6 (GPS - UTC), when known.
  if (h.leap_seconds) header_line(out, fmt::format("{:6d}", *h.leap_seconds), "LEAP SECONDS");

  header_line(out, "", "END OF HEADER");
}

// ---- data records (RINEX 3.04 appendix, observation data record description) ----

void write_epoch(std::string& out, const ObsHeader& h, const ObsEpoch& epoch) {
  if (epoch.flag != 0 && epoch.flag != 1)
    invalid(fmt::format("epoch flag {}: only 0 (OK) and 1 (power failure) are written",
                        epoch.flag));

  // Satellites of the systems in the header, sorted by system letter then number.
  std::vector<const SatObs*> sats;
  sats.reserve(epoch.sats.size());
  for (const SatObs& s : epoch.sats)
    if (h.types.count(s.system) != 0) sats.push_back(&s);
  std::sort(sats.begin(), sats.end(), [](const SatObs* a, const SatObs* b) {
    return a->system != b->system ? a->system < b->system : a->number < b->number;
  });
  if (sats.size() > 999) invalid(fmt::format("epoch with {} satellites (I3 holds 999)", sats.size()));

  const EpochFields f = epoch_fields(epoch.time);
  const std::string when =
      fmt::format("{:04d}-{:02d}-{:02d} {:02d}:{:02d}:{:02d}", f.cal.year, f.cal.month, f.cal.day,
                  f.cal.hour, f.cal.minute, f.whole_seconds);

  // Epoch record: A1,1X,I4,4(1X,I2.2),F11.7,2X,I1,I3,6X,F15.12 (receiver clock offset, s;
  // written when non-zero).
  std::string line = fmt::format("> {:04d} {:02d} {:02d} {:02d} {:02d}{:3d}.{:07d}  {:1d}{:3d}",
                                 f.cal.year, f.cal.month, f.cal.day, f.cal.hour, f.cal.minute,
                                 f.whole_seconds, f.ticks, epoch.flag, sats.size());
  if (epoch.receiver_clock_offset_s != 0.0)
    line += "      " + fixed(epoch.receiver_clock_offset_s, 15, 12,
                             "receiver clock offset at " + when);
  out += line;
  out += '\n';

  for (std::size_t i = 0; i < sats.size(); ++i) {
    const SatObs& s = *sats[i];
    if (s.number < 1 || s.number > 99)
      invalid(fmt::format("epoch {}: satellite {} number {} outside 1..99", when, s.system, s.number));
    const std::string id = sat_id(s);
    if (i > 0 && sats[i - 1]->system == s.system && sats[i - 1]->number == s.number)
      invalid(fmt::format("epoch {}: satellite {} listed twice", when, id));
    const std::vector<std::string>& types = h.types.at(s.system);
    if (s.values.size() != types.size())
      invalid(fmt::format("epoch {}: satellite {} has {} values for the {} types of system {}",
                          when, id, s.values.size(), types.size(), s.system));
    if ((!s.lli.empty() && s.lli.size() != types.size()) ||
        (!s.ssi.empty() && s.ssi.size() != types.size()))
      invalid(fmt::format("epoch {}: satellite {}: LLI/SSI lists must be empty or have one entry "
                          "per type ({})",
                          when, id, types.size()));

    // Satellite record: A1,I2.2, then per type F14.3 (blank when missing), LLI I1, SSI I1
    // (each blank when 0).
    line = id;
    for (std::size_t k = 0; k < types.size(); ++k) {
      const double v = s.values[k];
      const std::string what = fmt::format("epoch {}: satellite {} {}", when, id, types[k]);
      if (std::isnan(v))
        line.append(14, ' ');
      else
        line += fixed(v, 14, 3, what);
      for (const auto* flags : {&s.lli, &s.ssi}) {
        const int x = flags->empty() ? 0 : (*flags)[k];
        if (x < 0 || x > 9)
          invalid(fmt::format("{}: {} {} is not a single digit", what,
                              flags == &s.lli ? "LLI" : "SSI", x));
        line += x == 0 ? ' ' : static_cast<char>('0' + x);
      }
    }
    rtrim(line);
    out += line;
    out += '\n';
  }
}

}  // namespace

void write_rinex3_obs(std::ostream& out, const ObsHeader& header, const std::vector<ObsEpoch>& epochs,
                      const ObsWriterInfo& info) {
  check_types(header);
  if (epochs.empty()) invalid("no epochs: TIME OF FIRST OBS needs at least one");
  // The whole file is formatted first so that invalid input leaves `out` untouched.
  std::string text;
  write_header(text, header, epochs, info);
  for (const ObsEpoch& e : epochs) write_epoch(text, header, e);
  out << text;
}

}  // namespace navemu
