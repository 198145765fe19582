#pragma once
// A sensor channel: one sensor (the GNSS receiver with its device behaviour and ports, the IMU
// with its CAN outputs, later an RTK base or a magnetometer) as the scheduler
// (emulator/scheduler.hpp) sees it: its next event, the event itself run at a GPS time with the
// truth, its ports' input, its part of the status line and of the summary. The scheduler owns
// the clock and the late/skip/catch-up policy and knows no sensor by name.

#include <fmt/format.h>

#include <cstdint>
#include <optional>
#include <string_view>

#include "emulator/engine.hpp"
#include "emulator/truth_source.hpp"
#include "core/time.hpp"

namespace navemu {

// The loop's notion of time. Real time: GPS time runs with the monotonic clock from the start,
// events have deadlines; lockstep: GPS time is where the truth stream is; offline: time jumps
// from event to event.
class Clock {
 public:
  enum class Kind { kRealTime, kLockstep, kOffline };
  enum class Wait { kReached, kStopped, kWallTick };
  virtual ~Clock() = default;
  virtual Kind kind() const = 0;
  // Waits until GPS time t. In lockstep, where GPS time stands still while the stream does,
  // also returns kWallTick once the monotonic clock reaches `wall_tick_ns` (the ports are
  // serviced and the status line printed on wall time).
  virtual Wait wait_until(GpsTime t, std::int64_t wall_tick_ns = INT64_MAX) = 0;
  // The monotonic clock, ns, and the monotonic instant of GPS time t (real time).
  virtual std::int64_t monotonic_now() const = 0;
  virtual std::int64_t mono_of(GpsTime t) const = 0;
  // Real time: the scenario time now (where a truth stream's stamps should lie).
  GpsTime now() const { return GpsTime{gps_of_mono(monotonic_now())}; }
  bool realtime() const { return kind() == Kind::kRealTime; }

 protected:
  virtual std::int64_t gps_of_mono(std::int64_t mono_ns) const = 0;
};

// Output lateness of one status interval (p50/p99/max), without allocating in the loop.
class LatenessStats {
 public:
  LatenessStats();
  void add(double ms);
  // "p50/p99/max ms" of the interval (or "-") into `out`, then a fresh interval.
  void summary_and_reset(fmt::memory_buffer& out);

 private:
  std::vector<double> v_, sorted_;
};

// What an event gets from the scheduler.
struct EventContext {
  Clock& clock;
  TruthSource& truth;
  LatenessStats& lateness;  // output lateness of real-time deadlines, for the status line
};

// A channel's counters for the status line, summed over the channels.
struct ChannelStatus {
  std::uint64_t late = 0, skipped = 0;       // events late / skipped since the start
  std::uint64_t chunks_dropped = 0;          // byte outputs
  std::uint64_t frames_dropped = 0, frames_held = 0;  // frame outputs
  bool truth_lost = false;  // an event of the interval had no truth (or none yet with truth)
};

class SensorChannel {
 public:
  struct Event {
    GpsTime run_at;    // when the scheduler runs it
    GpsTime deadline;  // when its output is due (real time: lateness and skipping)
  };
  virtual ~SensorChannel() = default;
  // The key of its part of the status line ("gnss", "imu"; emulator/scheduler.hpp).
  virtual std::string_view status_key() const = 0;
  // The run starts at `start` (GPS time): the first event lies at or after it, and recorded
  // times count from it. Called once, before the first next_event().
  virtual void begin(GpsTime start) = 0;
  // The next event whose measurement time lies before `end`; none when there is none.
  virtual std::optional<Event> next_event(GpsTime end) const = 0;
  // How far past its deadline an event may still run in real time; later ones are skipped.
  virtual std::int64_t max_lateness_ns() const = 0;
  virtual void skip_event() = 0;
  // Runs the next event. False when a stop was requested while it waited for its deadline.
  virtual bool run_event(EventContext& ctx) = 0;
  // The ports' input (clients' commands), at the service tick.
  virtual void service() {}
  // Whether it has ports to service at all.
  virtual bool has_input() const { return false; }
  // Its part of the status line into `out`, its counters added to `status`; then a new interval.
  virtual void status(fmt::memory_buffer& out, ChannelStatus& status) = 0;
  // Live logs written out once per status interval (tail -f, disk-full reported within a second).
  virtual void flush_logs() {}
  // Files closed and counters added to the summary at the end of the run.
  virtual void finish(EngineSummary& summary) = 0;
};

}  // namespace navemu
