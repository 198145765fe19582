#pragma once
// The GNSS receiver as a sensor channel (emulator/channel.hpp): the receiver model, its device
// behaviour (NMEA, u-blox), its byte ports with the capture mirrors, and its recorders.
//
// Epoch k is measured at k * period + the device's grid offset (GPS time; the offset is 0 unless
// a client aligned the epochs to another time system) and due at that + the profile's output
// latency.
// It is computed kComputeLead before its deadline and written at the deadline; an epoch more
// than one period late is skipped (a receiver outputs the current solution, not old ones). A
// client that changes the navigation rate or time reference (u-blox CFG-RATE) moves the next
// epoch onto the new grid, after the current one, as soon as the command is taken.

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "emulator/channel.hpp"
#include "emulator/gnss_device.hpp"
#include "emulator/recorders.hpp"
#include "emulator/run_config.hpp"
#include "models/ephemeris.hpp"
#include "models/receiver.hpp"
#include "transports/byte_port.hpp"

namespace navemu {

// Where the receiver's bytes go: its ports, each standing for one of the receiver's own
// (outputs' `port`: UART1 unless said), and the mirrors of everything the first one sends and
// receives.
struct GnssPorts {
  std::vector<std::unique_ptr<transport::BytePort>> ports;
  std::vector<ReceiverPort> receiver_ports;  // one per port
  std::unique_ptr<transport::BytePort> capture_out, capture_in;
  void service();  // accepts TCP clients and the like while nothing runs yet (lockstep)
};

class GnssChannel final : public SensorChannel {
 public:
  // The receiver and its device on the navigation data `nav` (which the channel keeps).
  GnssChannel(std::unique_ptr<NavData> nav, const ReceiverParams& receiver, const GnssProfile& profile,
              ReceiverMode mode, GnssPorts ports, std::vector<std::unique_ptr<EpochRecorder>> recorders);

  std::string_view status_key() const override { return "gnss"; }
  void begin(GpsTime start) override;
  std::optional<Event> next_event(GpsTime end) const override;
  std::int64_t max_lateness_ns() const override { return period_ns_; }
  void skip_event() override;
  bool run_event(EventContext& ctx) override;
  void service() override;
  bool has_input() const override { return true; }
  void status(fmt::memory_buffer& out, ChannelStatus& status) override;
  void flush_logs() override;
  void finish(EngineSummary& summary) override;

  // Live control (emulator/control_channel.hpp): events whose windows count from the start; the
  // next epoch's time (what "now" means to them); every event ended.
  void add_events(const GnssEvents& events);
  GpsTime next_epoch() const { return epoch_time(k_); }
  void clear_events();
  // The systems tracked now (system_bit): the profile's, less those the device's configuration
  // has switched off (u-blox CFG-GNSS, CFG-SIGNAL-*).
  std::uint32_t tracked_systems() const;

 private:
  static constexpr std::int64_t kComputeLead_ns = 2'000'000;  // computed 2 ms before output
  void follow_rate(GpsTime last);
  GpsTime epoch_time(std::int64_t k) const { return GpsTime{k * period_ns_ + offset_ns_}; }

  std::unique_ptr<NavData> nav_;  // before the receiver and device, which refer to it
  std::unique_ptr<Receiver> receiver_;
  std::unique_ptr<GnssDevice> device_;
  GnssPorts io_;
  std::vector<std::unique_ptr<EpochRecorder>> recorders_;
  std::int64_t period_ns_, latency_ns_;
  std::int64_t offset_ns_ = 0;  // the epoch grid's offset from GPS time's, in [0, period)
  double nominal_rate_hz_;
  GpsTime start_;
  std::int64_t k_ = 0;  // the next epoch's index: whole periods since the grid's origin

  std::string chunk_, replies_;
  std::array<std::uint8_t, 4096> input_{};
  ReceiverFix last_fix_;
  std::optional<ImuTruth> last_fix_truth_;
  std::int64_t interval_epochs_ = 0;
  bool interval_truth_lost_ = false;
  std::int64_t epochs_ = 0, fixes_ = 0, skipped_ = 0, late_ = 0;
  std::uint64_t chunks_dropped_ = 0;
  // The device's own events (models/measurement.hpp CableEvent, ResetEvent), windows from start_:
  // while the cable is out or the receiver boots, its ports carry nothing either way.
  std::vector<CableEvent> cable_;
  std::vector<ResetEvent> resets_;  // still to come
  GpsTime silent_until_{0};
  bool silent_ = false;  // at the last epoch
  std::int64_t silent_epochs_ = 0;
};

}  // namespace navemu
