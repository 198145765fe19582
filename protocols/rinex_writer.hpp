#pragma once
// RINEX 3 observation file writer (RINEX 3.04/3.05 format, observation data file). A pure
// encoder: typed header and epochs in, text out; no clock is read, so the same input gives
// byte-identical files.

#include <map>
#include <ostream>
#include <string>
#include <vector>

#include "protocols/rinex.hpp"

namespace navemu {

struct ObsWriterInfo {
  std::string program = "navemu";
  std::string run_by = "";
  std::string date = "";  // "yyyymmdd hhmmss UTC" for PGM / RUN BY / DATE; caller-provided
  std::string receiver_type = "NAVEMU";
  std::string receiver_version = "";
  std::string antenna_type = "";
  std::vector<std::string> comments;
  // MARKER TYPE keyword (RINEX 3.04 section 5.3, e.g. GEODETIC, NON_GEODETIC, GROUND_CRAFT).
  std::string marker_type = "NON_GEODETIC";
  std::string observer = "";         // OBSERVER / AGENCY
  std::string agency = "";
  std::string receiver_number = "";  // REC # / TYPE / VERS
  std::string antenna_number = "";   // ANT # / TYPE
  // GLONASS SLOT / FRQ # (required when the file has GLONASS types): slot -> frequency
  // number k (-7..+13).
  std::map<int, int> glonass_frequency_numbers;
};

// Writes a RINEX 3.04 observation file with the header's system types (ObsHeader::types),
// marker, approximate position, antenna delta, interval and TIME OF FIRST OBS from the first
// epoch; values that are kMissing are written blank. LLI and SSI are written when non-zero.
// Satellites of systems without types in the header are left out. Throws
// std::invalid_argument (naming the record, satellite and type) for input the format cannot
// hold: a value outside F14.3, a text field longer than its columns, an epoch flag other than
// 0 or 1, no epochs. Nothing is written to `out` when it throws.
void write_rinex3_obs(std::ostream& out, const ObsHeader& header, const std::vector<ObsEpoch>& epochs,
                      const ObsWriterInfo& info);

}  // namespace navemu
