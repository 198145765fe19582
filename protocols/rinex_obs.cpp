// RINEX observation files.
//
//   RINEX 2.x: RINEX 2.11 Tables A1 (header) and A2 (data record); section 5.4 (event flags),
//     section 6.5 (two-digit years), section 8.1.1 (time system of the epochs).
//   RINEX 3.x: RINEX 3.05 appendix, observation file header description ("SYS / # / OBS TYPES",
//     "TIME OF FIRST OBS") and data record description ("> " epoch line with event flags, one
//     line per satellite); section 3.1 (time).
//
// Observations are F14.3 with a loss-of-lock indicator (I1) and a signal strength indicator
// (I1): 16 columns per value. Blank values are kMissing.

#include <algorithm>
#include <cstddef>
#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "protocols/rinex.hpp"
#include "protocols/rinex_fields.hpp"

namespace navemu {

int ObsHeader::index_of(char system, const std::string& code) const {
  const auto it = types.find(system);
  if (it == types.end()) return -1;
  const auto& list = it->second;
  const auto pos = std::find(list.begin(), list.end(), code);
  return pos == list.end() ? -1 : static_cast<int>(pos - list.begin());
}

namespace {

using rinex::column;
using rinex::fail;
using rinex::is_blank;
using rinex::Lines;
using rinex::NumStatus;
using rinex::req_int;
using rinex::Where;

constexpr std::size_t kValueWidth = 16;  // F14.3 + LLI (I1) + SSI (I1)
constexpr std::size_t kV2ValuesPerLine = 5;
constexpr std::size_t kV2SatsPerLine = 12;
constexpr std::string_view kSystems = "GRESJCI";

bool is_digit(char c) { return c >= '0' && c <= '9'; }

// Collects an observation type list from its header records, with continuation lines:
//   RINEX 2 "# / TYPES OF OBSERV": I6,9(4X,A2), continuation 6X,9(4X,A2) (RINEX 2.11 Table A1)
//   RINEX 3 "SYS / # / OBS TYPES": A1,2X,I3,13(1X,A3), continuation 6X,13(1X,A3)
//     (RINEX 3.05 observation header description)
class TypesCollector {
 public:
  TypesCollector(const std::string& source, bool v2) : src_(source), v2_(v2) {}

  void add(std::string_view line, int n) {
    const char* label = v2_ ? "# / TYPES OF OBSERV" : "SYS / # / OBS TYPES";
    const Where w{src_, n};
    const bool first = v2_ ? !is_blank(column(line, 0, 6)) : !is_blank(column(line, 0, 1));
    if (first) {
      if (pending())
        fail(src_, n, label,
             fmt::format("continuation line expected: {} of {} types listed so far (line {})",
                         cur_.size(), expected_, start_));
      sys_ = v2_ ? '*' : line[0];
      if (!v2_ && (sys_ < 'A' || sys_ > 'Z'))
        fail(src_, n, label, fmt::format("not a satellite system letter: '{}'", sys_));
      expected_ = v2_ ? req_int(w, line, 0, 6, label) : req_int(w, line, 3, 3, label);
      if (expected_ < 1 || expected_ > 999)
        fail(src_, n, label, fmt::format("number of observation types {} out of range", expected_));
      if (types_.count(sys_) != 0)
        fail(src_, n, label,
             v2_ ? std::string("types given twice")
                 : fmt::format("types of system '{}' given twice", sys_));
      cur_.clear();
      start_ = n;
    } else if (!pending()) {
      fail(src_, n, label, "continuation line without a preceding record giving the number of types");
    }
    const std::size_t per_line = v2_ ? 9 : 13;
    const std::size_t width = v2_ ? 6 : 4;
    for (std::size_t k = 0; k < per_line; ++k) {
      const std::string_view code = rinex::trim(column(line, 6 + width * k, width));
      if (code.empty()) continue;
      if (static_cast<int>(cur_.size()) >= expected_)
        fail(src_, n, label,
             fmt::format("more observation types listed than the {} declared", expected_));
      if (code.size() != (v2_ ? 2u : 3u))
        fail(src_, n, label, fmt::format("not an observation code: '{}'", code));
      cur_.emplace_back(code);
    }
    if (static_cast<int>(cur_.size()) == expected_) {
      types_[sys_] = std::move(cur_);
      cur_.clear();
      expected_ = 0;
    }
  }

  // Called when the list must be complete (END OF HEADER, end of an event's header records).
  void finish(int n) const {
    if (pending())
      fail(src_, n, v2_ ? "# / TYPES OF OBSERV" : "SYS / # / OBS TYPES",
           fmt::format("{} observation types declared at line {}, {} listed", expected_, start_,
                       cur_.size()));
  }

  bool empty() const { return types_.empty() && !pending(); }
  // RINEX 2: the single list ('*'); RINEX 3: per system.
  const std::map<char, std::vector<std::string>>& types() const { return types_; }

 private:
  bool pending() const { return expected_ > 0; }

  const std::string& src_;
  bool v2_;
  std::map<char, std::vector<std::string>> types_;
  std::vector<std::string> cur_;
  char sys_ = 0;
  int expected_ = 0;
  int start_ = 0;
};

class ObsParser {
 public:
  ObsParser(const Lines& lines) : lines_(lines), src_(lines.source()) {}

  ObsData run() {
    const rinex::VersionLine vl = rinex::read_version_line(lines_);
    data_.source = src_;
    ObsHeader& h = data_.header;
    h.version = vl.version;
    if (vl.version >= 2.0 && vl.version < 3.0) {
      v2_ = true;
    } else if (vl.version >= 3.0 && vl.version < 4.0) {
      v2_ = false;
    } else {
      fail(src_, 1, "version",
           fmt::format("unsupported RINEX version {} (observation files 2.x and 3.x are read)",
                       vl.version));
    }
    if (vl.type != 'O')
      fail(src_, 1, "file type",
           fmt::format("'{}' is not an observation file type (expected 'O')", vl.type));
    h.file_system = vl.system == ' ' ? 'G' : vl.system;
    if (h.file_system != 'M' && kSystems.find(h.file_system) == std::string_view::npos)
      fail(src_, 1, "satellite system",
           fmt::format("unknown satellite system '{}' in RINEX VERSION / TYPE", h.file_system));

    int n = read_header();
    if (v2_)
      read_v2_body(n);
    else
      read_v3_body(n);
    return std::move(data_);
  }

 private:
  // ---- header (RINEX 2.11 Table A1, RINEX 3.05 observation header description) ----

  int read_header() {
    ObsHeader& h = data_.header;
    TypesCollector types(src_, v2_);
    std::string_view time_system;
    int n = 2;
    for (; n <= lines_.size(); ++n) {
      const std::string_view line = lines_.line(n);
      const std::string_view label = rinex::header_label(line);
      const Where w{src_, n};
      if (label == "END OF HEADER") break;
      if (label == (v2_ ? "# / TYPES OF OBSERV" : "SYS / # / OBS TYPES")) {
        types.add(line, n);
      } else if (label == "MARKER NAME") {
        h.marker_name = std::string(rinex::trim(column(line, 0, 60)));
      } else if (label == "APPROX POSITION XYZ") {
        for (int k = 0; k < 3; ++k)  // 3F14.4
          h.approx_position_ecef_m[k] =
              rinex::req_double(w, line, 14 * static_cast<std::size_t>(k), 14, "APPROX POSITION XYZ");
      } else if (label == "ANTENNA: DELTA H/E/N") {
        for (int k = 0; k < 3; ++k)  // 3F14.4
          h.antenna_delta_hen_m[k] = rinex::req_double(w, line, 14 * static_cast<std::size_t>(k),
                                                       14, "ANTENNA: DELTA H/E/N");
      } else if (label == "INTERVAL") {
        h.interval_s = rinex::req_double(w, line, 0, 10, "INTERVAL");  // F10.3
        if (h.interval_s < 0.0) fail(src_, n, "INTERVAL", "must not be negative");
      } else if (label == "LEAP SECONDS") {
        h.leap_seconds = req_int(w, line, 0, 6, "LEAP SECONDS");  // I6
      } else if (label == "TIME OF FIRST OBS") {
        // 5I6,F13.7,5X,A3: the time system in columns 49-51.
        time_system = rinex::trim(column(line, 48, 3));
        time_line_ = n;
      }
    }
    if (n > lines_.size())
      fail(src_, lines_.size(), "END OF HEADER", "end of file before END OF HEADER");
    types.finish(n);
    if (types.empty())
      fail(src_, n, v2_ ? "# / TYPES OF OBSERV" : "SYS / # / OBS TYPES",
           "no observation types declared in the header");
    if (v2_) {
      // One list for every system the file may contain (RINEX 2.11 Table A1).
      v2_types_ = types.types().at('*');
      const std::string_view systems =
          h.file_system == 'M' ? std::string_view("GRES") : std::string_view(&h.file_system, 1);
      for (const char s : systems) h.types[s] = v2_types_;
    } else {
      h.types = types.types();
    }
    h.time_system = time_system_code(time_system);
    return n + 1;
  }

  // Time system of the epochs (RINEX 3.05 header "TIME OF FIRST OBS", RINEX 2.11 section
  // 8.1.1): GPS, GLO (UTC), GAL, QZS, BDT, IRN. When blank, the default of a single-system
  // file is that system's time, otherwise GPS.
  char time_system_code(std::string_view ts) const {
    if (ts.empty()) {
      const char fs = data_.header.file_system;
      return (fs == 'R' || fs == 'E' || fs == 'C' || fs == 'J' || fs == 'I') ? fs : 'G';
    }
    if (ts == "GPS") return 'G';
    if (ts == "GLO") return 'R';
    if (ts == "GAL") return 'E';
    if (ts == "BDT") return 'C';
    if (ts == "QZS") return 'J';
    if (ts == "IRN") return 'I';
    fail(src_, time_line_, "TIME OF FIRST OBS", fmt::format("unknown time system '{}'", ts));
  }

  // Epoch fields are in the file's time system; GpsTime is GPS time. GST, QZSST and IRNWT
  // are steered to GPS time (integer-second aligned); BDT = GPST - 14 s; GLO epochs are UTC
  // (RINEX 2.11 section 8.1.1, RINEX 3.05 section 3.1).
  GpsTime epoch_time(const Where& w, const CalendarTime& c) const {
    const GpsTime t = rinex::epoch_to_gps(w, c, "epoch");
    switch (data_.header.time_system) {
      case 'C':
        return t.plus_s(14.0);
      case 'R':
        return gps_from_utc(c, data_.header.leap_seconds);
      default:
        return t;
    }
  }

  // The header records that follow an event flag 2-5 (RINEX 2.11 section 5.4, RINEX 3.05
  // observation data record, epoch flags): consumed; a repeated observation type list must
  // equal the header's.
  int consume_event(int n, int count) {
    TypesCollector types(src_, v2_);
    const int epoch_line = n;
    for (int k = 1; k <= count; ++k) {
      const int ln = epoch_line + k;
      if (ln > lines_.size())
        fail(src_, ln, "event",
             fmt::format("end of file: the event at line {} announced {} special records, {} "
                         "found",
                         epoch_line, count, k - 1));
      const std::string_view line = lines_.line(ln);
      if (rinex::header_label(line) == (v2_ ? "# / TYPES OF OBSERV" : "SYS / # / OBS TYPES"))
        types.add(line, ln);
    }
    types.finish(epoch_line + count);
    for (const auto& [sys, list] : types.types()) {
      const bool same = v2_ ? list == v2_types_
                            : (data_.header.types.count(sys) != 0 && data_.header.types.at(sys) == list);
      if (!same)
        fail(src_, epoch_line, "event",
             "observation types change within the file (event header records): not supported");
    }
    ++data_.event_records;
    return epoch_line + count + 1;
  }

  // The observation types of a satellite system (`ln` for messages).
  const std::vector<std::string>& types_for(char sys, int ln) {
    auto& types = data_.header.types;
    auto it = types.find(sys);
    if (it == types.end()) {
      if (v2_ && kSystems.find(sys) != std::string_view::npos) {
        // RINEX 2: the one type list applies to every system.
        it = types.emplace(sys, v2_types_).first;
      } else {
        fail(src_, ln, "satellite",
             fmt::format("system '{}' has no observation types in the header", sys));
      }
    }
    return it->second;
  }

  // Reads one value field (F14.3, LLI I1, SSI I1) into sat.
  void read_value(std::string_view line, std::size_t col, std::size_t idx, const std::string& code,
                  int ln, SatObs& sat) {
    const std::string_view text = column(line, col, 14);
    double v = 0.0;
    const NumStatus st = rinex::to_double(text, v);
    if (st == NumStatus::ok) {
      rinex::check_right_justified(Where{src_, ln}, text, 14, code);
      sat.values[idx] = v;
    } else if (st != NumStatus::blank) {
      rinex::fail_number(Where{src_, ln}, code, text, st);
    }
    const std::string_view lli = column(line, col + 14, 1);
    const std::string_view ssi = column(line, col + 15, 1);
    if (!lli.empty() && lli[0] != ' ') {
      if (!is_digit(lli[0])) fail(src_, ln, code + " LLI", fmt::format("not a digit: '{}'", lli));
      sat.lli[idx] = lli[0] - '0';
    }
    if (!ssi.empty() && ssi[0] != ' ') {
      if (!is_digit(ssi[0])) fail(src_, ln, code + " SSI", fmt::format("not a digit: '{}'", ssi));
      sat.ssi[idx] = ssi[0] - '0';
    }
  }

  static SatObs make_sat(char sys, int number, std::size_t n_types) {
    SatObs sat;
    sat.system = sys;
    sat.number = number;
    sat.values.assign(n_types, kMissing);
    sat.lli.assign(n_types, 0);
    sat.ssi.assign(n_types, 0);
    return sat;
  }

  int read_flag(std::string_view line, std::size_t col, int n) const {
    const std::string_view f = column(line, col, 1);
    if (f.empty() || f[0] == ' ') return 0;
    if (f[0] < '0' || f[0] > '6')
      fail(src_, n, "epoch flag", fmt::format("must be a digit 0-6, got '{}'", f));
    return f[0] - '0';
  }

  // ---- RINEX 2 data records (RINEX 2.11 Table A2) ----

  // An epoch line: " yy mm dd hh mm ss.sssssss  f nnn" (1X,I2.2,4(1X,I2),F11.7,2X,I1,I3);
  // the date fields may be blank for event records.
  static bool looks_like_v2_epoch(std::string_view line) {
    if (line.size() < 29 || !is_digit(line[28])) return false;
    for (const std::size_t c : {0u, 3u, 6u, 9u, 12u, 26u, 27u})
      if (line[c] != ' ') return false;
    return true;
  }

  void read_v2_body(int n) {
    const std::size_t n_types = v2_types_.size();
    const int lines_per_sat = static_cast<int>((n_types + kV2ValuesPerLine - 1) / kV2ValuesPerLine);
    while (n <= lines_.size()) {
      const std::string_view line = lines_.line(n);
      if (is_blank(line)) {
        ++n;
        continue;
      }
      if (!looks_like_v2_epoch(line)) {
        if (epoch_line_ > 0)
          fail(src_, n, "epoch",
               fmt::format("expected an epoch line: the epoch at line {} may announce fewer "
                           "satellites ({}) than it has observation lines",
                           epoch_line_, epoch_count_));
        fail(src_, n, "epoch", "expected an epoch line");
      }
      const Where w{src_, n};
      const int flag = read_flag(line, 28, n);
      const int count = req_int(w, line, 29, 3, "satellite count");
      if (count < 0) fail(src_, n, "satellite count", "must not be negative");
      if (flag >= 2 && flag <= 5) {
        n = consume_event(n, count);
        continue;
      }
      CalendarTime c;
      c.year = rinex::full_year(req_int(w, line, 1, 2, "epoch"));
      c.month = req_int(w, line, 4, 2, "epoch");
      c.day = req_int(w, line, 7, 2, "epoch");
      c.hour = req_int(w, line, 10, 2, "epoch");
      c.minute = req_int(w, line, 13, 2, "epoch");
      c.second = rinex::req_double(w, line, 15, 11, "epoch");
      ObsEpoch epoch;
      epoch.time = epoch_time(w, c);
      epoch.flag = flag;
      epoch.receiver_clock_offset_s =
          rinex::opt_double(w, line, 68, 12, "receiver clock offset").value_or(0.0);  // F12.9
      epoch_line_ = n;
      epoch_count_ = count;

      // Satellite list: 12 per line, continuation lines 32X,12(A1,I2) (RINEX 2.11 Table A2).
      std::vector<std::pair<char, int>> ids;
      ids.reserve(static_cast<std::size_t>(count));
      int ln = n;
      for (int k = 0; k < count; ++k) {
        const std::size_t slot = static_cast<std::size_t>(k) % kV2SatsPerLine;
        if (k > 0 && slot == 0) {
          ++ln;
          if (ln > lines_.size() || !is_blank(column(lines_.line(ln), 0, 32)))
            fail(src_, ln, "satellite count",
                 fmt::format("the epoch at line {} announces {} satellites: continuation line of "
                             "satellite numbers expected",
                             n, count));
        }
        const std::string_view cur = lines_.line(ln);
        const std::string_view id = column(cur, 32 + 3 * slot, 3);
        if (is_blank(id))
          fail(src_, ln, "satellite count",
               fmt::format("the epoch announces {} satellites, only {} listed", count, k));
        const char sys = id[0] == ' ' ? 'G' : id[0];
        int number = 0;
        if (kSystems.find(sys) == std::string_view::npos || id.size() < 3 ||
            rinex::to_int(id.substr(1), number) != NumStatus::ok || number < 1)
          fail(src_, ln, "satellite", fmt::format("not a satellite number: '{}'", id));
        ids.emplace_back(sys, number);
      }
      // Nothing may follow the last satellite number before the clock offset (column 69).
      const std::size_t used = count == 0 ? 0 : (static_cast<std::size_t>(count) - 1) % kV2SatsPerLine + 1;
      if (!is_blank(column(lines_.line(ln), 32 + 3 * used, 3 * (kV2SatsPerLine - used))))
        fail(src_, ln, "satellite count",
             fmt::format("the epoch at line {} announces {} satellites, more are listed", n, count));
      n = ln + 1;

      // Observations: per satellite, 5 values per line (RINEX 2.11 Table A2).
      epoch.sats.reserve(ids.size());
      for (const auto& [sys, number] : ids) {
        const std::vector<std::string>& types = types_for(sys, n);
        SatObs sat = make_sat(sys, number, types.size());
        for (int j = 0; j < lines_per_sat; ++j, ++n) {
          const std::size_t first = static_cast<std::size_t>(j) * kV2ValuesPerLine;
          if (n > lines_.size())
            fail(src_, n, types[first],
                 fmt::format("record truncated: end of file in the observations of {}{:02d} "
                             "(epoch at line {})",
                             sys, number, epoch_line_));
          const std::string_view obs = lines_.line(n);
          if (looks_like_v2_epoch(obs) && !is_blank(column(obs, 0, 28)))
            fail(src_, n, "satellite count",
                 fmt::format("the epoch at line {} announced {} satellites, but an epoch line "
                             "follows after fewer observation lines",
                             epoch_line_, epoch_count_));
          const std::size_t last = std::min(n_types, first + kV2ValuesPerLine);
          for (std::size_t k = first; k < last; ++k)
            read_value(obs, kValueWidth * (k - first), k, types[k], n, sat);
          if (!is_blank(column(obs, kValueWidth * (last - first), 80)))
            fail(src_, n, "observations",
                 fmt::format("more values on the line than the {} observation types", n_types));
        }
        epoch.sats.push_back(std::move(sat));
      }
      if (flag == 6) {
        ++data_.cycle_slip_records;  // cycle-slip records (RINEX 2.11 section 5.4): consumed
      } else {
        data_.epochs.push_back(std::move(epoch));
      }
    }
  }

  // ---- RINEX 3 data records (RINEX 3.05 observation data record description) ----

  static bool looks_like_v3_sat(std::string_view line) {
    return line.size() >= 3 && line[0] >= 'A' && line[0] <= 'Z' &&
           (is_digit(line[1]) || line[1] == ' ') && is_digit(line[2]);
  }

  void read_v3_body(int n) {
    while (n <= lines_.size()) {
      const std::string_view line = lines_.line(n);
      if (is_blank(line)) {
        ++n;
        continue;
      }
      if (line[0] != '>') {
        if (epoch_line_ > 0 && looks_like_v3_sat(line))
          fail(src_, n, "satellite count",
               fmt::format("the epoch at line {} announced {} satellites, more satellite lines "
                           "follow",
                           epoch_line_, epoch_count_));
        fail(src_, n, "epoch", "expected an epoch line starting with '>'");
      }
      // "> yyyy mm dd hh mm ss.sssssss  f nnn      clock" :
      // A1,1X,I4,4(1X,I2.2),F11.7,2X,I1,I3,6X,F15.12
      const Where w{src_, n};
      const int flag = read_flag(line, 31, n);
      const int count = req_int(w, line, 32, 3, "satellite count");
      if (count < 0) fail(src_, n, "satellite count", "must not be negative");
      if (flag >= 2 && flag <= 5) {
        n = consume_event(n, count);
        continue;
      }
      CalendarTime c;
      c.year = req_int(w, line, 2, 4, "epoch");
      c.month = req_int(w, line, 7, 2, "epoch");
      c.day = req_int(w, line, 10, 2, "epoch");
      c.hour = req_int(w, line, 13, 2, "epoch");
      c.minute = req_int(w, line, 16, 2, "epoch");
      c.second = rinex::req_double(w, line, 18, 11, "epoch");
      ObsEpoch epoch;
      epoch.time = epoch_time(w, c);
      epoch.flag = flag;
      epoch.receiver_clock_offset_s =
          rinex::opt_double(w, line, 41, 15, "receiver clock offset").value_or(0.0);
      epoch_line_ = n;
      epoch_count_ = count;

      epoch.sats.reserve(static_cast<std::size_t>(count));
      int found = 0;
      for (; found < count; ++found) {
        const int ln = n + 1 + found;
        if (ln > lines_.size())
          fail(src_, ln, "satellite count",
               fmt::format("end of file: the epoch at line {} announced {} satellites, {} found",
                           n, count, found));
        const std::string_view sl = lines_.line(ln);
        if (!sl.empty() && sl[0] == '>') {
          // The next epoch starts early. Some writers count satellites they then leave out
          // (e.g. a system without SYS / # / OBS TYPES); the satellites listed are complete,
          // so the epoch is kept and the discrepancy reported in `warnings`.
          data_.warnings.push_back(fmt::format(
              "{}:{}: satellite count: epoch announced {} satellites, {} satellite lines follow",
              src_, n, count, found));
          break;
        }
        if (!looks_like_v3_sat(sl))
          fail(src_, ln, "satellite",
               fmt::format("not a satellite number: '{}'", column(sl, 0, 3)));
        const char sys = sl[0];
        int number = 0;
        if (rinex::to_int(sl.substr(1, 2), number) != NumStatus::ok || number < 1)
          fail(src_, ln, "satellite", fmt::format("not a satellite number: '{}'", column(sl, 0, 3)));
        const std::vector<std::string>& types = types_for(sys, ln);
        SatObs sat = make_sat(sys, number, types.size());
        for (std::size_t i = 0; i < types.size(); ++i)
          read_value(sl, 3 + kValueWidth * i, i, types[i], ln, sat);
        if (!is_blank(column(sl, 3 + kValueWidth * types.size(), std::string_view::npos)))
          fail(src_, ln, "observations",
               fmt::format("more values than the {} observation types of system '{}'",
                           types.size(), sys));
        epoch.sats.push_back(std::move(sat));
      }
      n += found + 1;
      if (flag == 6) {
        ++data_.cycle_slip_records;  // cycle-slip records (RINEX 3.05 epoch flag 6): consumed
      } else {
        data_.epochs.push_back(std::move(epoch));
      }
    }
  }

  const Lines& lines_;
  const std::string& src_;
  ObsData data_;
  bool v2_ = false;
  std::vector<std::string> v2_types_;
  int time_line_ = 0;
  int epoch_line_ = 0;   // line of the last epoch read, for messages
  int epoch_count_ = 0;  // its satellite count
};

ObsData parse_obs_text(std::string text, const std::string& source) {
  const Lines lines(std::move(text), source);
  return ObsParser(lines).run();
}

}  // namespace

ObsData parse_rinex_obs(std::string text, const std::string& source) {
  return parse_obs_text(std::move(text), source);
}

ObsData parse_rinex_obs(std::istream& in, const std::string& source) {
  return parse_obs_text(rinex::read_stream(in, source), source);
}

}  // namespace navemu
