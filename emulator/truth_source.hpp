#pragma once
// Where the vehicle's true state comes from during a run: a built-in generator
// (models/trajectory.hpp), a truth CSV file or standard input (emulator/truth_csv.hpp), or
// datagrams from a simulator (protocols/truth_datagram.hpp, docs/truth-protocol.md). All give
// the truth at any scenario GPS time, or nothing when there is none (the stream stopped or has
// not started, the file ended): then the sensors report the loss.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "emulator/run_config.hpp"
#include "emulator/truth_buffer.hpp"
#include "models/imu_kinematics.hpp"
#include "protocols/truth_datagram.hpp"

namespace navemu {

class TruthSource {
 public:
  virtual ~TruthSource() = default;
  // Takes in whatever has arrived; never blocks (a CSV on standard input reads ahead as at()
  // needs it). `clock`: the scenario time now, in real time, where a stream's stamps must lie
  // (emulator/truth_buffer.hpp); none in lockstep, where time follows the stream.
  virtual void poll(std::optional<GpsTime> clock) { (void)clock; }
  // The truth at scenario time t. Queries may come in any order within the last few seconds.
  virtual std::optional<ImuTruth> at(GpsTime t) = 0;
  // The newest sample's time, for sources that stream (lockstep mode follows it).
  virtual std::optional<GpsTime> newest() const { return std::nullopt; }
  virtual const TruthCounters* counters() const { return nullptr; }
  // A line for the user about the stream (a re-synchronisation, a refused CSV row), one per
  // call, oldest first; none when there is nothing new.
  virtual std::optional<std::string> take_warning() { return std::nullopt; }
  virtual std::string describe() const = 0;
};

// A datagram's state in scenario GPS time: GPS time stamps as they are; host UTC stamps
// converted to GPS time and shifted by `host_offset` (scenario time minus host time, so that a
// scenario may start at any date). None when a value is not finite.
std::optional<ImuTruth> truth_from_message(const truth_datagram::Message& m, GpsTime host_offset);

// The source a configuration names, starting at scenario time `start`. `host_offset` as above.
// Opening errors (file, socket) throw InputError/std::runtime_error.
std::unique_ptr<TruthSource> make_truth_source(const TruthSpec& spec, GpsTime start,
                                               GpsTime host_offset);

// `inner` with the truth faults of `events:` (emulator/run_config.hpp TruthFault), their windows
// counted from the scenario's start; `inner` itself when there are none.
std::unique_ptr<TruthSource> impaired_truth(std::unique_ptr<TruthSource> inner, std::vector<TruthFault> faults,
                                            GpsTime start);

// The UDP source's port (for tests and the start-up message), 0 for other sources.
int truth_udp_port(const TruthSource& source);

}  // namespace navemu
