#include "emulator/imu_channel.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace navemu {

namespace {

// Smallest multiple of `period` at or after t.
std::int64_t first_index_at_or_after(GpsTime t, std::int64_t period_ns) {
  return t.ns / period_ns + (t.ns % period_ns != 0 ? 1 : 0);
}

std::int64_t whole_steps_per_output(const ImuParams& p) {
  const std::int64_t n = std::llround(p.internal_rate_hz / p.output_rate_hz);
  if (n < 1 || std::fabs(static_cast<double>(n) * p.output_rate_hz - p.internal_rate_hz) >
                   1e-9 * p.internal_rate_hz)
    throw std::invalid_argument("internal_rate_hz must be a whole multiple of output_rate_hz");
  return n;
}

}  // namespace

ImuPipeline::ImuPipeline(const ImuParams& params, std::uint64_t seed, GpsTime origin, const IdealImu& initial)
    : model_(params, seed),
      origin_(origin),
      out_ns_(std::llround(1e9 / params.output_rate_hz)),
      steps_per_out_(whole_steps_per_output(params)),
      last_ideal_(initial) {}

GpsTime ImuPipeline::step_time(std::int64_t n) const {
  return GpsTime{origin_.ns + n / steps_per_out_ * out_ns_ + n % steps_per_out_ * out_ns_ / steps_per_out_};
}

bool ImuPipeline::run_to(std::int64_t last, TruthSource& truth, ImuSample& sample, bool& valid) {
  valid = true;
  bool emitted = false;
  for (; next_ <= last; ++next_) {
    const std::int64_t n = next_;
    const GpsTime t = step_time(n);
    if (window_n_ == n - 1) {
      before_ = std::move(now_);
      now_ = std::move(after_);
    } else {
      before_ = truth.at(step_time(n - 1));
      now_ = truth.at(t);
    }
    after_ = truth.at(step_time(n + 1));
    window_n_ = n;
    double temperature_c = model_.params().reference_temperature_c;
    if (now_ && now_->f_body_mps2 && now_->w_ib_body_radps) {
      last_ideal_ = IdealImu{*now_->f_body_mps2, *now_->w_ib_body_radps};
    } else if (now_ && (before_ || after_)) {
      last_ideal_ = ideal_imu_from_kinematics(before_ ? *before_ : *now_, *now_, after_ ? *after_ : *now_);
    } else {
      valid = false;  // no truth: the last ideal output is held and the sample flagged
    }
    if (now_ && now_->temperature_c) temperature_c = *now_->temperature_c;
    if (model_.step(t, last_ideal_, temperature_c, sample)) emitted = true;
  }
  return emitted;
}

ImuChannel::ImuChannel(const ImuParams& params, std::uint64_t seed, const IdealImu& initial,
                       std::unique_ptr<ImuCanOutputs> can, std::vector<std::unique_ptr<SampleRecorder>> recorders,
                       bool offline)
    : pipe_(params, seed, GpsTime{0}, initial),
      drop_rng_(seed, stream_id("imu.drop")),
      duplicate_rng_(seed, stream_id("imu.duplicate")),
      can_(std::move(can)),
      recorders_(std::move(recorders)),
      offline_(offline),
      latency_ns_(std::llround(params.latency_s * 1e9)) {}

void ImuChannel::begin(GpsTime start) {
  start_ = start;
  for (ImuFault& f : faults_) resolve_start(f.window, start);
  if (!faults_.empty()) pipe_.set_faults(faults_, start);
  j_ = j0_ = first_index_at_or_after(start, pipe_.output_period_ns());
  pipe_.resume_at(j_ * pipe_.steps_per_output());
}

std::optional<std::string> unfit_fault(const ImuFault& f, const ImuParams& p) {
  if (fault_fits(f, p)) return std::nullopt;
  return fmt::format("a random vibration from {} to {} Hz: the IMU profile {} samples at {} Hz, so the band must end "
                     "below {} Hz",
                     f.vibration.band_lo_hz, f.vibration.band_hi_hz, p.name, p.internal_rate_hz,
                     p.internal_rate_hz / 2.0);
}

std::optional<std::string> ImuChannel::add_faults(const std::vector<ImuFault>& faults) {
  for (const ImuFault& f : faults)
    if (std::optional<std::string> why = unfit_fault(f, pipe_.params())) return why;
  faults_.insert(faults_.end(), faults.begin(), faults.end());
  pipe_.set_faults(faults_, start_);
  return std::nullopt;
}

void ImuChannel::clear_faults() {
  faults_.clear();
  pipe_.set_faults(faults_, start_);
}

std::optional<SensorChannel::Event> ImuChannel::next_event(GpsTime end) const {
  if (!(GpsTime{j_ * pipe_.output_period_ns()} < end)) return std::nullopt;
  const GpsTime due{j_ * pipe_.output_period_ns() + latency_ns_};
  return Event{due, due};
}

std::int64_t ImuChannel::max_lateness_ns() const { return std::max(kImuCatchUp_ns, pipe_.output_period_ns()); }

void ImuChannel::skip_event() {
  ++j_;
  ++skipped_;
}

// The internal steps up to the sample's measurement time, then out.
bool ImuChannel::run_event(EventContext& ctx) {
  const GpsTime t_meas{j_ * pipe_.output_period_ns()};
  // After skipped samples, resume at this sample's own internal steps.
  pipe_.resume_at((j_ - 1) * pipe_.steps_per_output() + 1);
  bool valid = true;
  if (pipe_.run_to(j_ * pipe_.steps_per_output(), ctx.truth, sample_, valid)) {
    // One per output period, so that a sample skipped after a stall leaves a gap in the
    // sequence, as a frame lost on the bus does (protocols/can_frames.hpp; wraps).
    const auto sequence = static_cast<std::uint16_t>(j_ - j0_);
    if (fault_hits(ImuFaultKind::kDrop, t_meas, drop_rng_)) {  // measured, then lost: a gap in the sequence
      ++dropped_;
      ++j_;
      return true;
    }
    if (can_bus_faults(t_meas)) {  // the controller is bus-off: the sample's frames are lost
      ++bus_off_lost_;
      ++j_;
      return true;
    }
    ++samples_;
    if (!valid) {
      ++flagged_;
      interval_truth_lost_ = true;
    }
    // A duplicate is the same sample again at once: the same frames, the same log line.
    const int copies = fault_hits(ImuFaultKind::kDuplicate, t_meas, duplicate_rng_) ? 2 : 1;
    duplicated_ += copies - 1;
    if (can_) {
      can::ImuSample cs;
      cs.gps_time_ns = t_meas.ns;
      cs.sequence = sequence;
      for (int i = 0; i < 3; ++i) {
        cs.w_body_radps[static_cast<std::size_t>(i)] = sample_.w_body_radps[i];
        cs.f_body_mps2[static_cast<std::size_t>(i)] = sample_.f_body_mps2[i];
      }
      cs.latency_s = pipe_.params().latency_s;
      cs.truth_lost = !valid;
      cs.gyro_saturated = sample_.gyro_saturated;
      cs.accel_saturated = sample_.accel_saturated;
      for (int c = 0; c < copies; ++c) can_->send(cs, can_stamp_ns(t_meas));
    }
    const SampleRecord record{sample_, seconds_between(sample_.t, start_), valid, t_meas, sequence};
    for (int c = 0; c < copies; ++c)
      for (auto& r : recorders_) r->record(record);
  }
  ++j_;
  return true;
}

// Whether the faults of `kind` (kDrop, kDuplicate) hit the sample measured at t: independently
// per fault, each with its probability x level; a draw from `rng` only while one is active, so
// runs without agree.
bool ImuChannel::fault_hits(ImuFaultKind kind, GpsTime t, RandomStream& rng) const {
  double missed = 1.0;
  for (const ImuFault& f : faults_)
    if (f.kind == kind) missed *= 1.0 - std::min(1.0, f.value * event_level(f.window, seconds_between(t, start_)));
  return missed < 1.0 && rng.uniform() >= missed;
}

// The CAN bus faults at the sample measured at t (true: bus-off, the sample is lost). A bus-off
// begins with the controller's CAN_ERR_BUSOFF error frame and ends with CAN_ERR_RESTARTED;
// kErrorFrames send bus errors (CAN_ERR_PROT | CAN_ERR_BUSERROR, a stuffing error) at their rate
// x level, spread evenly over the samples (linux/can/error.h).
bool ImuChannel::can_bus_faults(GpsTime t) {
  bool off = false;
  double rate_hz = 0.0;
  for (const ImuFault& f : faults_) {
    const double level = event_level(f.window, seconds_between(t, start_));
    if (f.kind == ImuFaultKind::kBusOff && level > 0.0) off = true;
    if (f.kind == ImuFaultKind::kErrorFrames) rate_hz += f.value * level;
  }
  if (can_) {
    const std::int64_t stamp = can_stamp_ns(t);
    if (off != bus_off_) can_->send_error(off ? kCanErrBusOff : kCanErrRestarted, {}, stamp);
    error_frames_due_ += rate_hz * static_cast<double>(pipe_.output_period_ns()) * 1e-9;
    for (; error_frames_due_ >= 1.0; error_frames_due_ -= 1.0, ++error_frames_)
      can_->send_error(kCanErrProt | kCanErrBusError, {0, 0, kCanErrProtStuff, 0, 0, 0, 0, 0}, stamp);
  }
  bus_off_ = off;
  return off;
}

// Live frames are stamped when they leave; offline ones at their scheduled time, the sample's
// measurement time + the profile's latency.
std::int64_t ImuChannel::can_stamp_ns(GpsTime t_meas) const {
  return offline_ ? unix_ns_from_gps(GpsTime{t_meas.ns + latency_ns_}) : realtime_ns();
}

void ImuChannel::service() {
  if (can_) can_->service();
}

void ImuChannel::status(fmt::memory_buffer& out, ChannelStatus& st) {
  fmt::format_to(std::back_inserter(out), "imu {} smp", samples_);
  if (flagged_) fmt::format_to(std::back_inserter(out), " ({} flagged)", flagged_);
  st.skipped += static_cast<std::uint64_t>(skipped_);
  if (can_) {
    const CanOutputTotals t = can_->totals();
    st.frames_dropped += t.frames_dropped + t.frames_failed;
    st.frames_held += t.frames_held;
  }
  st.truth_lost = st.truth_lost || interval_truth_lost_;
  interval_truth_lost_ = false;
}

void ImuChannel::flush_logs() {
  for (auto& r : recorders_) r->flush();
}

void ImuChannel::finish(EngineSummary& sum) {
  for (auto& r : recorders_) r->close();
  sum.imu_samples = samples_;
  sum.imu_flagged = flagged_;
  sum.imu_skipped = skipped_;
  sum.imu_dropped = dropped_;
  sum.imu_duplicated = duplicated_;
  sum.imu_bus_off = bus_off_lost_;
  sum.can_error_frames = error_frames_;
  if (can_) {
    const CanOutputTotals t = can_->totals();
    sum.can_frames_written = t.frames_written;
    sum.can_frames_dropped = t.frames_dropped;
    sum.can_frames_held = t.frames_held;
    sum.can_frames_failed = t.frames_failed;
    sum.can_bus_errors = t.bus_errors;
  }
  sum.scenario_s = std::max(sum.scenario_s, static_cast<double>(samples_) * 1e-9 *
                                                static_cast<double>(pipe_.output_period_ns()));
}

}  // namespace navemu
