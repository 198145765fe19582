#pragma once
// Live control as a channel of the run (emulator/control.hpp for the commands): its port is
// serviced with the other ports and each command goes to what it acts on, the GNSS receiver,
// the IMU or the truth. It has no events of its own.

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>

#include "emulator/channel.hpp"
#include "emulator/control.hpp"
#include "emulator/gnss_channel.hpp"
#include "emulator/imu_channel.hpp"
#include "emulator/truth_source.hpp"

namespace navemu {

class ControlChannel final : public SensorChannel {
 public:
  // What this run has to act on; null: not in this run (its commands are refused).
  struct Targets {
    GnssChannel* gnss = nullptr;
    ImuChannel* imu = nullptr;
    ImpairedTruth* truth = nullptr;
  };
  ControlChannel(std::unique_ptr<ControlPort> port, Targets targets)
      : port_(std::move(port)), to_(targets) {}

  std::string_view status_key() const override { return "ctl"; }
  void begin(GpsTime start) override { start_ = start; }
  std::optional<Event> next_event(GpsTime) const override { return std::nullopt; }
  std::int64_t max_lateness_ns() const override { return 0; }
  void skip_event() override {}
  bool run_event(EventContext&) override { return true; }
  void service() override;
  bool has_input() const override { return true; }
  void status(fmt::memory_buffer& out, ChannelStatus& status) override;
  void finish(EngineSummary&) override {}

  // One command line's reply (tests call it without a port).
  std::string apply(std::string_view line);

 private:
  std::unique_ptr<ControlPort> port_;
  Targets to_;
  GpsTime start_;
  std::int64_t accepted_ = 0, refused_ = 0;
};

}  // namespace navemu
