#pragma once
// One receiver epoch as the NMEA sentences of a GNSS profile (configs/gnss/): the receiver's
// fix (models/receiver.hpp) turned into the encoders' fields (protocols/nmea.hpp).

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/satellite.hpp"
#include "emulator/run_config.hpp"
#include "models/receiver.hpp"
#include "protocols/nmea.hpp"

namespace navemu {

class NmeaOutput {
 public:
  // `nmea_version`: the NMEA version a client chose (u-blox CFG-NMEA-PROTVER: 21, 23, 40, 41,
  // 42 for 2.1 ... 4.11); none: the profile style's. `high_precision`: u-blox NMEA high
  // precision mode (nmea::Format::high_precision).
  NmeaOutput(const GnssProfile& profile, ReceiverMode mode, std::optional<int> nmea_version = {},
             bool high_precision = false);
  // Appends the sentences due at this epoch (those whose divisor divides epoch_index) to `out`.
  void encode(const ReceiverFix& fix, std::int64_t epoch_index, std::string& out);

 private:
  GnssProfile profile_;
  nmea::Format format_;
  NmeaNumbering numbering_ = NmeaNumbering::kV411;  // NMEA 4.11 with system IDs, else 4.10
  int quality_ = 1;  // GGA quality of a fix in this mode
  char mode_ = 'A';  // NMEA 2.3 mode indicator of a fix in this mode
  GnssSystem gsv_system(GnssSystem s) const;

  std::vector<nmea::GsvSatellite> gsv_;
  nmea::GsaFields gsa_;  // its satellite list is reused from epoch to epoch
};

}  // namespace navemu
