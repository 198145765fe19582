#pragma once
// The IMU's CAN outputs: each sample encoded in the configured layouts (protocols/can_frames)
// and its frames written back to back on every frame port (transports/can_port).

#include <array>
#include <cstdint>
#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

#include "emulator/run_config.hpp"
#include "protocols/can_frames.hpp"
#include "transports/can_port.hpp"

namespace navemu {

struct CanOutputTotals {
  std::uint64_t frames_written = 0, frames_dropped = 0, frames_held = 0, frames_failed = 0, bus_errors = 0,
                errors = 0;
};

// SocketCAN error classes and details (linux/can/error.h): the controller went bus-off and was
// restarted; a protocol violation (data[2]: a bit-stuffing error) seen as a bus error.
inline constexpr std::uint32_t kCanErrBusOff = 0x040, kCanErrRestarted = 0x100;
inline constexpr std::uint32_t kCanErrProt = 0x008, kCanErrBusError = 0x080;
inline constexpr std::uint8_t kCanErrProtStuff = 0x04;

class ImuCanOutputs {
 public:
  // Opens every output. A socketcan output that cannot be opened falls back to its fallback
  // (saying so on `log`) when it has one; otherwise the opening error propagates.
  ImuCanOutputs(const std::vector<CanOutputSpec>& specs, const CanSettings& settings,
                std::ostream& log);

  bool empty() const { return outputs_.empty(); }
  // Sends one sample's frames on every output; `unix_time_ns` stamps them in candump logs.
  void send(const can::ImuSample& sample, std::int64_t unix_time_ns);
  // Sends an error frame of `error_class` (below) with `data` on the outputs that carry them.
  void send_error(std::uint32_t error_class, const std::array<std::uint8_t, 8>& data, std::int64_t unix_time_ns);
  void service();
  // One line per output: "socketcan vcan0: j1939, highres".
  std::vector<std::string> describe() const;
  CanOutputTotals totals() const;

 private:
  struct Output {
    std::unique_ptr<transport::FramePort> port;
    std::vector<CanLayout> layouts;
  };
  std::vector<Output> outputs_;
  can::j1939::Config j1939_;
  can::highres::Config highres_;
  bool uses_j1939_ = false, uses_highres_ = false, uses_fd_ = false;
  std::array<can::CanFrame, 2> j1939_frames_{};
  std::array<can::CanFrame, can::highres::kClassicFrameCount> highres_frames_{};
  can::CanFrame fd_frame_{};
};

// The outputs of an offline run: one candump log at `path` carrying every layout the
// configured outputs use (J1939 when none is configured), with the first socketcan output's
// interface name (can0 when none).
std::vector<CanOutputSpec> offline_can_outputs(const std::vector<CanOutputSpec>& configured,
                                               const std::string& path);

}  // namespace navemu
