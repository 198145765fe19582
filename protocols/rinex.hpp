#pragma once
// RINEX readers: navigation files 2.10/2.11 (GPS) and 3.0x/4.0x (mixed; GPS records used,
// others parsed past), observation files 2.x and 3.x. All errors are InputError with
// file:line and the field concerned. The readers take a file's text (or a stream of it); the
// emulator reads the files (emulator/rinex_files.hpp).

#include <istream>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/nav_data.hpp"
#include "core/satellite.hpp"
#include "core/time.hpp"
#include "core/vec.hpp"

namespace navemu {

// `text` is the whole file; `source` names it in error messages.
NavData parse_rinex_nav(std::string text, const std::string& source);
NavData parse_rinex_nav(std::istream& in, const std::string& source);

inline constexpr double kMissing = std::numeric_limits<double>::quiet_NaN();

struct ObsHeader {
  double version = 0.0;
  char file_system = 'G';  // 'G', 'R', 'E', 'C', 'J', 'S', 'I' or 'M' (mixed)
  // Observation codes per system, in file order. RINEX 2 codes (C1, P2, L1, ...) are
  // listed under every system letter the file may contain.
  std::map<char, std::vector<std::string>> types;
  std::string marker_name;
  Vec3 approx_position_ecef_m = Vec3::Zero();
  Vec3 antenna_delta_hen_m = Vec3::Zero();
  double interval_s = 0.0;          // 0 when not given
  std::optional<int> leap_seconds;  // GPS - UTC, when given
  char time_system = 'G';           // 'G' (GPS) unless TIME OF FIRST OBS says otherwise

  // Index of `code` in the list for `system`, or -1.
  int index_of(char system, const std::string& code) const;
};

// One satellite's observations. Its name is kept as the file writes it (RINEX 3.05 section
// 3.5): the system letter, which may be any a header declares types for (one simulator writes
// QZSS as 'Q'), and the two-digit number.
struct SatObs {
  char system = 'G';
  int number = 0;
  // The satellite, when the letter is one of the seven systems'.
  std::optional<SatId> sat() const { return SatId::from_rinex(system, number); }
  std::vector<double> values;  // one per header type of this system; kMissing when blank
  std::vector<int> lli;        // loss-of-lock indicator per value (0 when blank)
  std::vector<int> ssi;        // signal strength indicator per value (0 when blank)
};

struct ObsEpoch {
  GpsTime time;
  int flag = 0;  // 0 OK, 1 power failure (observations follow); 2-5 events are consumed
  double receiver_clock_offset_s = 0.0;
  std::vector<SatObs> sats;
};

struct ObsData {
  ObsHeader header;
  std::vector<ObsEpoch> epochs;  // epochs with observations (flags 0 and 1)
  int event_records = 0;         // event-flag 2-5 records consumed
  int cycle_slip_records = 0;    // event-flag 6 (cycle slip) records consumed
  // Irregularities that were tolerated, one "file:line: field: problem" each (e.g. a RINEX 3
  // epoch announcing more satellites than it lists, as some simulators write).
  std::vector<std::string> warnings;
  std::string source;
};

ObsData parse_rinex_obs(std::string text, const std::string& source);
ObsData parse_rinex_obs(std::istream& in, const std::string& source);

}  // namespace navemu
