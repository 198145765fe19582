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

// A source with the truth faults of `events:` or live control (emulator/run_config.hpp
// TruthFault) on it. A frozen state is taken once, at the first query inside the window, from
// the window's start (a streamed source forgets old samples).
class ImpairedTruth final : public TruthSource {
 public:
  explicit ImpairedTruth(std::unique_ptr<TruthSource> inner) : inner_(std::move(inner)) {}
  // The faults from now on, their windows counted from the scenario's `start`.
  void set_faults(std::vector<TruthFault> faults, GpsTime start);
  // More, their windows already counted from the start.
  void add_faults(const std::vector<TruthFault>& faults);

  void poll(std::optional<GpsTime> clock) override { inner_->poll(clock); }
  std::optional<ImuTruth> at(GpsTime t) override;
  std::optional<GpsTime> newest() const override { return inner_->newest(); }
  const TruthCounters* counters() const override { return inner_->counters(); }
  std::optional<std::string> take_warning() override { return inner_->take_warning(); }
  std::string describe() const override { return inner_->describe(); }

 private:
  std::unique_ptr<TruthSource> inner_;
  std::vector<TruthFault> faults_;
  GpsTime start_;
  std::vector<std::optional<ImuTruth>> frozen_;  // per fault
};

// The UDP source's port (for tests and the start-up message), 0 for other sources.
int truth_udp_port(const TruthSource& source);

}  // namespace navemu
