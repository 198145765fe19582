#pragma once
// The IMU as a sensor channel (emulator/channel.hpp), and the signal path it shares with
// `navemu imu`: truth window -> ideal IMU -> error model.
//
// Output sample j is measured at origin + j * output period; the internal steps divide each
// output period into equal parts, on the nanosecond below when a part is not a whole number of
// nanoseconds (600 Hz inside 100 Hz: 1,666,666 or 1,666,667 ns apart). A sample is due at its
// time + the profile's latency; after a stall the late ones go out at once, each with its own
// time of validity (a driver integrates them; a real IMU never drops one), and only those more
// than kImuCatchUp late are skipped. Sequence numbers count output periods, so a skipped sample
// leaves a gap in them, as a frame lost on the bus does.

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "emulator/channel.hpp"
#include "emulator/imu_can.hpp"
#include "emulator/recorders.hpp"
#include "models/imu_kinematics.hpp"
#include "models/imu_model.hpp"

namespace navemu {

// Truth -> ideal IMU -> error model at the internal rate. At each internal instant it holds a
// rolling window of the truth at the instants before and after (the kinematic derivation
// differences its neighbours, models/imu_kinematics.hpp; one-sided where one of them is
// missing); the truth's own f and w take precedence. Without truth at an instant the last ideal
// output is held and the sample is not valid.
class ImuPipeline {
 public:
  // std::invalid_argument unless the internal rate is a whole multiple of the output rate.
  ImuPipeline(const ImuParams& params, std::uint64_t seed, GpsTime origin, const IdealImu& initial);
  std::int64_t steps_per_output() const { return steps_per_out_; }
  std::int64_t output_period_ns() const { return out_ns_; }
  const ImuParams& params() const { return model_.params(); }
  // Internal instant n.
  GpsTime step_time(std::int64_t n) const;
  void set_faults(std::vector<ImuFault> faults, GpsTime origin) { model_.set_faults(std::move(faults), origin); }
  // Continues at internal step n at the earliest (after skipped output samples).
  void resume_at(std::int64_t n) { next_ = std::max(next_, n); }
  // Runs the internal steps up to `last`; true when the model emitted an output sample into
  // `sample`. `valid` is false when a step of them had no truth.
  bool run_to(std::int64_t last, TruthSource& truth, ImuSample& sample, bool& valid);

 private:
  ImuModel model_;
  GpsTime origin_;
  std::int64_t out_ns_, steps_per_out_;
  std::int64_t next_ = 0;        // the next internal step
  std::int64_t window_n_ = -2;   // the step `now_` belongs to
  std::optional<ImuTruth> before_, now_, after_;
  IdealImu last_ideal_;
};

// Why a fault cannot act on this sensor (models/imu_model.hpp fault_fits), for the user; none
// when it can.
std::optional<std::string> unfit_fault(const ImuFault& f, const ImuParams& p);

class ImuChannel final : public SensorChannel {
 public:
  // `can`: the CAN outputs (none: null); `recorders`: imu.csv or the live log; `offline`: CAN
  // frames stamped with their scheduled time rather than when they leave.
  ImuChannel(const ImuParams& params, std::uint64_t seed, const IdealImu& initial,
             std::unique_ptr<ImuCanOutputs> can, std::vector<std::unique_ptr<SampleRecorder>> recorders,
             bool offline);

  // The sensor faults of `events:` (type imu), counted from the run's start (begin()).
  void set_faults(std::vector<ImuFault> faults) { faults_ = std::move(faults); }
  // Live control (emulator/control_channel.hpp): faults whose windows count from the start (the
  // sensor's fault state starts over: a random vibration's filter from rest); the next
  // sample's measurement time (what "now" means to them); every fault ended.
  // Refused (the reason) when one does not fit the sensor (unfit_fault).
  std::optional<std::string> add_faults(const std::vector<ImuFault>& faults);
  GpsTime next_sample() const { return GpsTime{j_ * pipe_.output_period_ns()}; }
  void clear_faults();

  std::string_view status_key() const override { return "imu"; }
  void begin(GpsTime start) override;
  std::optional<Event> next_event(GpsTime end) const override;
  std::int64_t max_lateness_ns() const override;
  void skip_event() override;
  bool run_event(EventContext& ctx) override;
  void service() override;
  bool has_input() const override { return can_ != nullptr; }
  void status(fmt::memory_buffer& out, ChannelStatus& status) override;
  void flush_logs() override;
  void finish(EngineSummary& summary) override;

 private:
  static constexpr std::int64_t kImuCatchUp_ns = 500'000'000;  // later samples are skipped
  bool fault_hits(ImuFaultKind kind, GpsTime t, RandomStream& rng) const;
  bool can_bus_faults(GpsTime t);
  std::int64_t can_stamp_ns(GpsTime t_meas) const;  // a CAN frame's stamp (candump logs)

  ImuPipeline pipe_;
  std::vector<ImuFault> faults_;
  RandomStream drop_rng_;       // "imu.drop": which samples a kDrop fault loses
  RandomStream duplicate_rng_;  // "imu.duplicate": which a kDuplicate fault sends twice
  bool bus_off_ = false;        // at the last sample (kBusOff)
  double error_frames_due_ = 0.0;  // kErrorFrames: owed, fractions carried from sample to sample
  std::unique_ptr<ImuCanOutputs> can_;
  std::vector<std::unique_ptr<SampleRecorder>> recorders_;
  GpsTime start_;
  bool offline_;
  std::int64_t latency_ns_;
  std::int64_t j_ = 0, j0_ = 0;  // the next output sample's index; the first one's (sequence 0)
  ImuSample sample_;
  bool interval_truth_lost_ = false;
  std::int64_t samples_ = 0, flagged_ = 0, skipped_ = 0, dropped_ = 0, duplicated_ = 0, bus_off_lost_ = 0,
               error_frames_ = 0;
};

}  // namespace navemu
