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
#include "models/reuse.hpp"

namespace navemu {

// The receiver's ports (u-blox port IDs, UBX-13003221 "UBX-CFG-PRT" and the F9 interface
// description's CFG-UART1/UART2/USB/I2C/SPI groups): each output of a run stands for one.
enum class ReceiverPort : std::uint8_t { kI2c = 0, kUart1 = 1, kUart2 = 2, kUsb = 3, kSpi = 4 };
inline constexpr std::size_t kReceiverPorts = 5;

class GnssDevice {
 public:
  virtual ~GnssDevice() = default;
  // The solution and measurements of one navigation epoch (index = whole periods since the GPS
  // epoch); then encode() for each port. While restarting (restart()) the receiver is searching:
  // it has no fix and no satellites whatever the solution was.
  void update(const ReceiverFix& fix, const EpochMeasurements& meas, std::int64_t epoch_index) {
    if (!restarting(fix.t)) return take_epoch(fix, meas, epoch_index);
    reset_keeping_storage(searching_, &ReceiverFix::satellites).t = fix.t;
    searching_meas_ = meas;
    searching_meas_.sats.clear();
    take_epoch(searching_, searching_meas_, epoch_index);
  }
  // The fix the receiver reported at the last update (searching, a held position), until the
  // next update.
  virtual const ReceiverFix& reported_fix() const = 0;
  // Appends the bytes of the last updated epoch that `port` sends.
  virtual void encode(ReceiverPort port, std::string& out) = 0;
  // update() and encode() for UART1.
  void encode_epoch(const ReceiverFix& fix, const EpochMeasurements& meas, std::int64_t epoch_index,
                    std::string& out) {
    update(fix, meas, epoch_index);
    encode(ReceiverPort::kUart1, out);
  }
  // Takes bytes a client sent to `port`; replies (acknowledgements, answers to polls) are
  // appended to `replies` and go out at once on that port.
  virtual void receive(std::span<const std::uint8_t> bytes, ReceiverPort port, std::string& replies) {
    (void)bytes;
    (void)port;
    (void)replies;
  }
  void receive(std::span<const std::uint8_t> bytes, std::string& replies) {
    receive(bytes, ReceiverPort::kUart1, replies);
  }
  // The navigation epoch period; a client may change it (u-blox CFG-RATE).
  virtual std::int64_t period_ns() const = 0;
  // Where the epoch grid lies near GPS time t: epochs are at k * period_ns() + this, in
  // [0, period). 0 is GPS time's own grid; a u-blox client may align it to another time
  // system (CFG-RATE timeRef).
  virtual std::int64_t grid_offset_ns(GpsTime t) const {
    (void)t;
    return 0;
  }
  // A baud rate the client asked for on a UART, to apply after the acknowledgement went out
  // (once).
  virtual std::optional<int> take_baud_change(ReceiverPort port) {
    (void)port;
    return std::nullopt;
  }
  std::optional<int> take_baud_change() { return take_baud_change(ReceiverPort::kUart1); }
  // The position engine's settings as the client configured them (u-blox CFG-NAVSPG,
  // CFG-NAV5), applied from the next epoch; none: the receiver keeps the run profile's.
  virtual const NavEngineSettings* engine_settings() const { return nullptr; }
  // A restart at t (u-blox CFG-RST, a `reset` event; models/measurement.hpp ResetEvent): no fix
  // and no satellites until the time to first fix after it; `hardware`: the processor resets
  // too (a u-blox receiver rebuilds its RAM configuration).
  virtual void restart(RestartKind kind, bool hardware, GpsTime t) {
    (void)hardware;
    restart_until_ = t.plus_s(restart_ttff_s(kind));
  }
  // True until a restart has produced its first fix again.
  bool restarting(GpsTime t) const { return t < restart_until_; }

 private:
  // update() of the device: the epoch as the receiver has it.
  virtual void take_epoch(const ReceiverFix& fix, const EpochMeasurements& meas, std::int64_t epoch_index) = 0;

  GpsTime restart_until_{0};
  ReceiverFix searching_;  // what a restarting receiver has (storage reused)
  EpochMeasurements searching_meas_;
};

// The device a profile describes: u-blox when it has a `ubx` section, NMEA otherwise.
// `nav` must outlive the device.
std::unique_ptr<GnssDevice> make_gnss_device(const GnssProfile& profile, ReceiverMode mode,
                                             const NavData& nav);

}  // namespace navemu
