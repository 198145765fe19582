// The scheduler (emulator/scheduler.hpp) with a fake clock and test-only channels: events on
// time, late within their bound, skipped beyond it, caught up after a stall, a rate change
// mid-run, and a channel the scheduler has never heard of taking part in the status line.

#include "emulator/scheduler.hpp"

#include <gtest/gtest.h>

#include <sstream>
#include <vector>

namespace navemu {
namespace {

constexpr std::int64_t kMs = 1'000'000;

// Real time on a fake monotonic clock (GPS time 0 = monotonic 0): a wait ends `wake_late_ns`
// after its deadline, and a stall can be scheduled that holds the loop when the clock first
// passes a given instant (as SIGSTOP or a busy host would).
class FakeClock final : public Clock {
 public:
  Kind kind() const override { return Kind::kRealTime; }
  Wait wait_until(GpsTime t, std::int64_t) override {
    if (mono_ < t.ns) mono_ = t.ns + wake_late_ns;
    if (stall_at_ && mono_ >= *stall_at_) {
      mono_ += stall_ns;
      stall_at_.reset();
    }
    return Wait::kReached;
  }
  std::int64_t monotonic_now() const override { return mono_; }
  std::int64_t mono_of(GpsTime t) const override { return t.ns; }
  void stall(std::int64_t at_ns, std::int64_t for_ns) {
    stall_at_ = at_ns;
    stall_ns = for_ns;
  }
  std::int64_t wake_late_ns = 0;

 protected:
  std::int64_t gps_of_mono(std::int64_t mono_ns) const override { return mono_ns; }

 private:
  std::int64_t mono_ = -1;  // just before GPS time 0, so that the first wait is late too
  std::optional<std::int64_t> stall_at_;
  std::int64_t stall_ns = 0;
};

class NoTruth final : public TruthSource {
 public:
  std::optional<ImuTruth> at(GpsTime) override { return std::nullopt; }
  std::string describe() const override { return "none"; }
};

// A channel that records when each of its events ran: event k measured at k * period, due
// `latency` later; the period may change after a given event, as a u-blox CFG-RATE does.
class TestChannel final : public SensorChannel {
 public:
  struct Ran {
    std::int64_t index;
    GpsTime measured;
    std::int64_t late_ns;  // monotonic time when it ran minus its deadline
  };
  TestChannel(std::string key, std::int64_t period_ns, std::int64_t max_late_ns, std::int64_t latency_ns = 0)
      : key_(std::move(key)), period_(period_ns), max_late_(max_late_ns), latency_(latency_ns) {}
  std::string_view status_key() const override { return key_; }
  void begin(GpsTime start) override { k_ = (start.ns + period_ - 1) / period_; }
  std::optional<Event> next_event(GpsTime end) const override {
    if (!(GpsTime{k_ * period_} < end)) return std::nullopt;
    const GpsTime due{k_ * period_ + latency_};
    return Event{due, due};
  }
  std::int64_t max_lateness_ns() const override { return max_late_; }
  void skip_event() override {
    skipped.push_back(k_);
    ++k_;
  }
  bool run_event(EventContext& ctx) override {
    const GpsTime measured{k_ * period_};
    ran.push_back({k_, measured, ctx.clock.monotonic_now() - ctx.clock.mono_of(GpsTime{measured.ns + latency_})});
    ++k_;
    if (change_after && ran.size() == *change_after) {
      period_ = new_period;
      k_ = measured.ns / period_ + 1;  // the next one on the new grid, after this one
    }
    return true;
  }
  void status(fmt::memory_buffer& out, ChannelStatus& st) override {
    fmt::format_to(std::back_inserter(out), "{} {} ev", key_, ran.size());
    st.skipped += skipped.size();
  }
  void finish(EngineSummary&) override {}

  std::vector<Ran> ran;
  std::vector<std::int64_t> skipped;
  std::optional<std::size_t> change_after;
  std::int64_t new_period = 0;

 private:
  std::string key_;
  std::int64_t period_, max_late_, latency_;
  std::int64_t k_ = 0;
};

struct Rig {
  FakeClock clock;
  NoTruth truth;
  std::ostringstream log;
  void go(std::vector<SensorChannel*> channels, std::int64_t end_ns, std::int64_t status_ns = 0) {
    SchedulerOptions o;
    o.start = GpsTime{0};
    o.end = GpsTime{end_ns};
    o.status_ns = status_ns;
    Scheduler(clock, truth, std::move(channels), o, log).run();
  }
};

TEST(Scheduler, EventsRunOnTimeInTimeOrderOnTheirGrids) {
  Rig r;
  TestChannel a("gnss", 200 * kMs, 200 * kMs, 50 * kMs), b("imu", 8 * kMs, 500 * kMs);
  r.go({&a, &b}, 1000 * kMs);
  ASSERT_EQ(a.ran.size(), 5u);
  ASSERT_EQ(b.ran.size(), 125u);
  for (std::size_t i = 0; i < a.ran.size(); ++i) {
    EXPECT_EQ(a.ran[i].measured.ns, static_cast<std::int64_t>(i) * 200 * kMs);
    EXPECT_EQ(a.ran[i].late_ns, 0);
  }
  for (std::size_t i = 0; i < b.ran.size(); ++i) EXPECT_EQ(b.ran[i].late_ns, 0);
  EXPECT_TRUE(a.skipped.empty());
  EXPECT_TRUE(b.skipped.empty());
}

TEST(Scheduler, AnEventLateWithinItsBoundStillRuns) {
  Rig r;
  r.clock.wake_late_ns = 30 * kMs;  // every wake-up 30 ms late (a busy host)
  TestChannel a("gnss", 200 * kMs, 200 * kMs);
  r.go({&a}, 1000 * kMs);
  ASSERT_EQ(a.ran.size(), 5u);
  for (const auto& e : a.ran) EXPECT_EQ(e.late_ns, 30 * kMs);
  EXPECT_TRUE(a.skipped.empty());
}

// A stall of 700 ms after the event at 200 ms: the events due more than a period ago are
// skipped (counted), the one within a period runs at once, and the loop is back on its grid.
TEST(Scheduler, EventsBeyondTheirBoundAreSkippedAndTheGridHolds) {
  Rig r;
  r.clock.stall(200 * kMs, 700 * kMs);
  TestChannel a("gnss", 200 * kMs, 200 * kMs);
  r.go({&a}, 2000 * kMs);
  // Ran 0, then the stall; at 900 ms the events 400 and 600 ms are more than 200 ms late.
  EXPECT_EQ(a.skipped, (std::vector<std::int64_t>{1, 2, 3}));
  std::vector<std::int64_t> indices;
  for (const auto& e : a.ran) indices.push_back(e.index);
  EXPECT_EQ(indices, (std::vector<std::int64_t>{0, 4, 5, 6, 7, 8, 9}));
  // After the stall: the first a little late (within a period), then on time again.
  EXPECT_EQ(a.ran[1].late_ns, 100 * kMs);
  for (std::size_t i = 2; i < a.ran.size(); ++i) EXPECT_EQ(a.ran[i].late_ns, 0) << i;
}

// IMU-like catch-up: after a 300 ms stall the samples due meanwhile (within their 500 ms bound)
// all run at once, in order, none skipped; then on time again.
TEST(Scheduler, LateEventsWithinTheirBoundCatchUpBackToBack) {
  Rig r;
  r.clock.stall(100 * kMs, 300 * kMs);
  TestChannel b("imu", 8 * kMs, 500 * kMs);
  r.go({&b}, 1000 * kMs);
  EXPECT_TRUE(b.skipped.empty());
  ASSERT_EQ(b.ran.size(), 125u);
  int caught_up = 0;
  for (std::size_t i = 0; i < b.ran.size(); ++i) {
    EXPECT_EQ(b.ran[i].index, static_cast<std::int64_t>(i));
    if (b.ran[i].late_ns > 0) ++caught_up;
    EXPECT_LE(b.ran[i].late_ns, 300 * kMs);
  }
  EXPECT_NEAR(caught_up, 300 / 8, 1);
  EXPECT_EQ(b.ran.back().late_ns, 0);
}

// After its 3rd event the channel's period goes from 200 ms to 100 ms: the next event lies on
// the new grid after the current one.
TEST(Scheduler, ARateChangeMidRunMovesTheNextEventOntoTheNewGrid) {
  Rig r;
  TestChannel a("gnss", 200 * kMs, 200 * kMs);
  a.change_after = 3;
  a.new_period = 100 * kMs;
  r.go({&a}, 1000 * kMs);
  std::vector<std::int64_t> times_ms;
  for (const auto& e : a.ran) times_ms.push_back(e.measured.ns / kMs);
  EXPECT_EQ(times_ms, (std::vector<std::int64_t>{0, 200, 400, 500, 600, 700, 800, 900}));
  for (const auto& e : a.ran) EXPECT_EQ(e.late_ns, 0);
}

// A channel the scheduler has never heard of (key "baro") runs on its own grid beside the
// others and has its part of the status line, after the gnss and imu parts (absent here).
TEST(Scheduler, ANewKindOfChannelTakesPartWithoutChangesToTheScheduler) {
  Rig r;
  TestChannel baro("baro", 40 * kMs, 40 * kMs), imu("imu", 8 * kMs, 500 * kMs);
  r.go({&baro, &imu}, 2000 * kMs, 1000 * kMs);
  EXPECT_EQ(baro.ran.size(), 50u);
  EXPECT_EQ(imu.ran.size(), 250u);
  const std::string log = r.log.str();
  EXPECT_NE(log.find("00:00:01 UTC gnss 0 ep (no epoch) imu 126 ev baro 26 ev | jitter - | late 0 skipped 0 dropped 0 "
                     "chunks 0 frames | truth ok\n"),
            std::string::npos)
      << log;
}

}  // namespace
}  // namespace navemu
