#pragma once
// What a GNSS receiver says on its port each epoch, and how it answers its client: the
// emulator's device behaviour over the wire codecs. NMEA-only receivers (NmeaDevice) just talk;
// u-blox receivers (emulator/ubx_device.hpp) also take configuration.

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>

#include "emulator/nmea_output.hpp"
#include "emulator/run_config.hpp"
#include "models/ephemeris.hpp"
#include "models/receiver.hpp"

namespace navemu {

class GnssDevice {
 public:
  virtual ~GnssDevice() = default;
  // Appends the bytes of one navigation epoch (index = whole periods since the GPS epoch).
  virtual void encode_epoch(const ReceiverFix& fix, const EpochMeasurements& meas,
                            std::int64_t epoch_index, std::string& out) = 0;
  // Takes bytes from the client; replies (acknowledgements, answers to polls) are appended to
  // `replies` and go out at once.
  virtual void receive(std::span<const std::uint8_t> bytes, std::string& replies) {
    (void)bytes;
    (void)replies;
  }
  // The navigation epoch period; a client may change it (u-blox CFG-RATE).
  virtual std::int64_t period_ns() const = 0;
  // A baud rate the client asked for, to apply after the acknowledgement went out (once).
  virtual std::optional<int> take_baud_change() { return std::nullopt; }
  // True until a client-requested restart has produced its first fix again.
  virtual bool restarting(GpsTime t) const {
    (void)t;
    return false;
  }
};

// The device a profile describes: u-blox when it has a `ubx` section, NMEA otherwise.
// `nav` must outlive the device.
std::unique_ptr<GnssDevice> make_gnss_device(const GnssProfile& profile, ReceiverMode mode,
                                             const NavData& nav);

}  // namespace navemu
