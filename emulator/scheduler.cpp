#include "emulator/scheduler.hpp"

#include <fmt/format.h>
#include <fmt/ostream.h>
#include <time.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <ostream>
#include <string_view>

namespace navemu {

namespace {

class RealTimeClock final : public Clock {
 public:
  RealTimeClock(GpsTime start, std::int64_t start_mono_ns) : gps0_(start), mono0_(start_mono_ns) {}
  Kind kind() const override { return Kind::kRealTime; }
  Wait wait_until(GpsTime t, std::int64_t) override {
    const std::int64_t deadline = mono_of(t);
    const timespec ts{static_cast<time_t>(deadline / kNsPerS), static_cast<long>(deadline % kNsPerS)};
    while (!stop_requested()) {
      const int rc = clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr);
      if (rc == 0) return Wait::kReached;
      if (rc != EINTR) return stop_requested() ? Wait::kStopped : Wait::kReached;
    }
    return Wait::kStopped;
  }
  std::int64_t monotonic_now() const override { return monotonic_ns(); }
  std::int64_t mono_of(GpsTime t) const override { return mono0_ + (t.ns - gps0_.ns); }

 protected:
  std::int64_t gps_of_mono(std::int64_t mono_ns) const override { return gps0_.ns + (mono_ns - mono0_); }

 private:
  GpsTime gps0_;
  std::int64_t mono0_;
};

class LockstepClock final : public Clock {
 public:
  explicit LockstepClock(TruthSource& truth) : truth_(truth) {}
  Kind kind() const override { return Kind::kLockstep; }
  Wait wait_until(GpsTime t, std::int64_t wall_tick_ns) override {
    while (!stop_requested()) {
      truth_.poll(std::nullopt);
      const std::optional<GpsTime> newest = truth_.newest();
      if (newest && *newest >= t) return Wait::kReached;
      if (monotonic_ns() >= wall_tick_ns) return Wait::kWallTick;
      timespec ts{0, 2'000'000};  // the next datagram; bounded so signals are seen
      nanosleep(&ts, nullptr);
    }
    return Wait::kStopped;
  }
  std::int64_t monotonic_now() const override { return monotonic_ns(); }
  std::int64_t mono_of(GpsTime t) const override { return t.ns; }  // unused: no deadlines

 protected:
  std::int64_t gps_of_mono(std::int64_t) const override { return truth_.newest().value_or(GpsTime{}).ns; }

 private:
  TruthSource& truth_;
};

class OfflineClock final : public Clock {
 public:
  Kind kind() const override { return Kind::kOffline; }
  Wait wait_until(GpsTime, std::int64_t) override { return stop_requested() ? Wait::kStopped : Wait::kReached; }
  std::int64_t monotonic_now() const override { return monotonic_ns(); }
  std::int64_t mono_of(GpsTime t) const override { return t.ns; }  // unused: no deadlines

 protected:
  std::int64_t gps_of_mono(std::int64_t) const override { return 0; }
};

// The truth's state on the status line. Real time: rejecting when datagrams came during the
// interval and none was taken (the sensors lose the truth timeout_s after the newest taken);
// lost when some event of the interval had no truth (so a loss shorter than the interval is
// never left unreported); extrapolating when the newest accepted sample is more than
// kExtrapolating_s older than the status time; ok otherwise. Lockstep, where time follows the
// stream: paused when nothing came, rejecting when nothing was taken.
constexpr double kExtrapolating_s = 0.25;
struct TruthStatus {
  bool lockstep = false;
  bool lost = false;
  std::uint64_t accepted = 0, rejected = 0;  // during the interval
  double age_s = 0.0;  // status time minus the newest accepted sample's time, when positive
};
const char* truth_state(const TruthStatus& t) {
  if (t.lockstep) return t.accepted ? "ok" : t.rejected ? "rejecting" : "paused";
  if (t.rejected && !t.accepted) return "rejecting";
  if (t.lost) return "lost";
  return t.age_s > kExtrapolating_s ? "extrapolating" : "ok";
}

// " (accepted 120, rejected 3: crc 1, backwards 2; resync 1)"
void format_truth_counts(const TruthCounters& c, fmt::memory_buffer& b) {
  fmt::format_to(std::back_inserter(b), " (accepted {}, rejected {}", c.accepted, c.rejected());
  if (c.rejected() || c.resync) b.append(std::string_view(c.rejected() ? ": " : "; "));
  format_truth_reasons(c, b);
  b.push_back(')');
}

// The status line's layout: the parts of these keys first, in this order, with the text a
// missing one reads; the parts of other keys follow in channel order.
struct StatusSlot {
  std::string_view key, absent;
};
constexpr StatusSlot kStatusLayout[] = {{"gnss", "gnss 0 ep (no epoch)"}, {"imu", "imu 0 smp"}};

}  // namespace

std::unique_ptr<Clock> make_realtime_clock(GpsTime start, std::int64_t start_mono_ns) {
  return std::make_unique<RealTimeClock>(start, start_mono_ns);
}
std::unique_ptr<Clock> make_lockstep_clock(TruthSource& truth) { return std::make_unique<LockstepClock>(truth); }
std::unique_ptr<Clock> make_offline_clock() { return std::make_unique<OfflineClock>(); }

LatenessStats::LatenessStats() {
  v_.reserve(8192);
  sorted_.reserve(8192);
}

void LatenessStats::add(double ms) {
  if (v_.size() < v_.capacity()) v_.push_back(ms);
}

void LatenessStats::summary_and_reset(fmt::memory_buffer& out) {
  if (v_.empty()) {
    out.push_back('-');
    return;
  }
  sorted_.assign(v_.begin(), v_.end());
  std::sort(sorted_.begin(), sorted_.end());
  const auto pct = [&](double p) {
    return sorted_[std::min(sorted_.size() - 1, static_cast<std::size_t>(p * static_cast<double>(sorted_.size())))];
  };
  fmt::format_to(std::back_inserter(out), "{:.2f}/{:.2f}/{:.2f} ms", pct(0.5), pct(0.99), sorted_.back());
  v_.clear();
}

Scheduler::Scheduler(Clock& clock, TruthSource& truth, std::vector<SensorChannel*> channels,
                     const SchedulerOptions& options, std::ostream& log)
    : clock_(clock), truth_(truth), channels_(std::move(channels)), opt_(options), log_(log),
      scenario_now_(options.start) {
  for (const SensorChannel* c : channels_) has_input_ = has_input_ || c->has_input();
  if (clock_.kind() == Clock::Kind::kLockstep) {
    next_tick_mono_ = truth_moved_mono_ = clock_.monotonic_now();
    if (opt_.status_ns) next_status_mono_ = next_tick_mono_ + opt_.status_ns;
  }
}

void Scheduler::run() {
  const bool realtime = clock_.realtime(), lockstep = clock_.kind() == Clock::Kind::kLockstep;
  // Real time at whole status intervals of GPS time; offline none; lockstep on wall time.
  GpsTime next_status =
      opt_.status_ns && realtime ? GpsTime{opt_.start.ns + opt_.status_ns} : GpsTime{INT64_MAX};
  GpsTime next_service{opt_.start.ns + opt_.service_ns};
  EventContext ctx{clock_, truth_, lateness_};
  for (SensorChannel* c : channels_) c->begin(opt_.start);

  for (;;) {
    GpsTime next{INT64_MAX};
    bool due = false;
    for (const SensorChannel* c : channels_)
      if (const std::optional<SensorChannel::Event> e = c->next_event(opt_.end)) {
        next = std::min(next, e->run_at);
        due = true;
      }
    if (!due) break;
    next = std::min(next, next_status);
    if (has_input_ && realtime) next = std::min(next, next_service);
    if (lockstep) lockstep_tick();
    const Clock::Wait waited = clock_.wait_until(next, lockstep ? next_tick_mono_ : INT64_MAX);
    if (waited == Clock::Wait::kStopped) break;
    if (waited == Clock::Wait::kWallTick) continue;  // the tick runs at the top
    scenario_now_ = next;
    truth_.poll(realtime ? std::optional<GpsTime>(clock_.now()) : std::nullopt);
    while (const std::optional<std::string> w = truth_.take_warning())
      fmt::print(log_, "navemu: warning: {}\n", *w);
    if (realtime && next_service <= next) service();
    if (realtime) skip_late_events();

    for (SensorChannel* c : channels_) {
      const std::optional<SensorChannel::Event> e = c->next_event(opt_.end);
      if (e && e->run_at <= next && !c->run_event(ctx)) return;
    }

    if (next_service <= next) next_service = GpsTime{next.ns + opt_.service_ns};
    if (next_status <= next) {
      print_status(next_status);
      next_status = GpsTime{next_status.ns + opt_.status_ns};
    }
  }
}

// An event whose deadline passed more than the channel's bound ago is skipped, not run late.
void Scheduler::skip_late_events() {
  const std::int64_t now = clock_.monotonic_now();
  for (SensorChannel* c : channels_)
    for (std::optional<SensorChannel::Event> e = c->next_event(opt_.end);
         e && now > clock_.mono_of(e->deadline) + c->max_lateness_ns(); e = c->next_event(opt_.end))
      c->skip_event();
}

void Scheduler::service() {
  for (SensorChannel* c : channels_) c->service();
}

// Lockstep's wall-time tick: the ports' input and the status line, also while the stream
// pauses.
void Scheduler::lockstep_tick() {
  const std::int64_t now = clock_.monotonic_now();
  if (const TruthCounters* tc = truth_.counters(); tc && tc->accepted != accepted_seen_) {
    accepted_seen_ = tc->accepted;
    truth_moved_mono_ = now;
  }
  if (now < next_tick_mono_) return;
  service();
  next_tick_mono_ = now + opt_.service_ns;
  if (now >= next_status_mono_) {
    print_status(scenario_now_);
    next_status_mono_ = std::max(next_status_mono_ + opt_.status_ns, now);
  }
}

void Scheduler::print_status(GpsTime at) {
  for (SensorChannel* c : channels_) c->flush_logs();
  status_line_.clear();
  const auto out = std::back_inserter(status_line_);
  const CalendarTime cal = utc_from_gps(at);
  fmt::format_to(out, "navemu: {:02}:{:02}:{:02.0f} UTC", cal.hour, cal.minute, std::floor(cal.second));
  ChannelStatus st;
  const auto add_part = [&](SensorChannel& c) {
    part_.clear();
    c.status(part_, st);
    status_line_.push_back(' ');
    status_line_.append(part_);
  };
  for (const StatusSlot& slot : kStatusLayout) {
    const auto it = std::find_if(channels_.begin(), channels_.end(),
                                 [&](const SensorChannel* c) { return c->status_key() == slot.key; });
    if (it != channels_.end()) {
      add_part(**it);
    } else {
      status_line_.push_back(' ');
      status_line_.append(slot.absent);
    }
  }
  for (SensorChannel* c : channels_)
    if (std::none_of(std::begin(kStatusLayout), std::end(kStatusLayout),
                     [&](const StatusSlot& s) { return s.key == c->status_key(); }))
      add_part(*c);

  fmt::format_to(out, " | jitter ");
  lateness_.summary_and_reset(status_line_);
  fmt::format_to(out, " | late {} skipped {} dropped {} chunks {} frames", st.late, st.skipped,
                 st.chunks_dropped, st.frames_dropped);
  if (st.frames_held) fmt::format_to(out, ", {} frames held", st.frames_held);

  const bool lockstep = clock_.kind() == Clock::Kind::kLockstep;
  const TruthCounters* tc = truth_.counters();
  const TruthCounters now_counts = tc ? *tc : TruthCounters{};
  const std::optional<GpsTime> newest = truth_.newest();
  TruthStatus ts;
  ts.lockstep = lockstep;
  ts.lost = st.truth_lost;
  ts.accepted = now_counts.accepted - truth_at_status_.accepted;
  ts.rejected = now_counts.rejected() - truth_at_status_.rejected();
  if (newest && at > *newest) ts.age_s = seconds_between(at, *newest);
  fmt::format_to(out, " | truth {}", truth_state(ts));
  if (lockstep && ts.accepted == 0)
    fmt::format_to(out, " for {:.0f} s", static_cast<double>(clock_.monotonic_now() - truth_moved_mono_) * 1e-9);
  if (tc) format_truth_counts(now_counts, status_line_);
  truth_at_status_ = now_counts;
  status_line_.push_back('\n');
  log_.write(status_line_.data(), static_cast<std::streamsize>(status_line_.size()));
  log_.flush();
}

}  // namespace navemu
