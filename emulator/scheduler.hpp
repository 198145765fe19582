#pragma once
// The scheduler: one loop over the sensor channels (emulator/channel.hpp), the clock and the
// policy of late events, shared by real-time, lockstep and offline runs, which differ only in
// their clock.
//
// Events lie on whole multiples of each channel's period in GPS time and are run in time
// order (ties: in channel order). Real time: the loop sleeps to absolute deadlines on the
// monotonic clock (clock_nanosleep TIMER_ABSTIME), mapped from GPS time by one fixed offset,
// so nothing drifts; before running anything it skips each channel's events whose deadline
// passed more than the channel's max_lateness_ns() ago (counted, never sent late in a burst),
// so after a stall the loop is back on its grid; events within that bound run at once, back
// to back (catch-up). Clients' input is read at a service tick (every 10 ms). A status line
// goes out every status interval of GPS time. Lockstep: GPS time follows the truth stream;
// the service tick and the status line run on wall time, also while the stream pauses.
// Offline: events run back to back, no status line.
//
// The status line: "navemu: HH:MM:SS UTC " and each channel's part in the order of its status
// key (gnss, imu, then others; a missing gnss or imu part reads "gnss 0 ep (no epoch)" or
// "imu 0 smp"), then "| jitter p50/p99/max ms | late L skipped S dropped C chunks F frames[,
// H frames held] | truth STATE (counts)" (emulator/truth_buffer.hpp, README "Streamed truth").

#include <cstdint>
#include <iosfwd>
#include <memory>
#include <vector>

#include "emulator/channel.hpp"

namespace navemu {

struct SchedulerOptions {
  GpsTime start;                         // the scenario's start (status times count from it)
  GpsTime end{INT64_MAX};                // events measured before it run
  std::int64_t status_ns = 0;            // status interval; 0: no status line
  std::int64_t service_ns = 10'000'000;  // how often clients' input is read (real time, lockstep)
};

// The clocks of the three kinds of run. `start_mono_ns`: the monotonic instant of GPS time
// `start`. They return kStopped once stop_requested() (emulator/engine.hpp).
std::unique_ptr<Clock> make_realtime_clock(GpsTime start, std::int64_t start_mono_ns);
std::unique_ptr<Clock> make_lockstep_clock(TruthSource& truth);
std::unique_ptr<Clock> make_offline_clock();

class Scheduler {
 public:
  Scheduler(Clock& clock, TruthSource& truth, std::vector<SensorChannel*> channels,
            const SchedulerOptions& options, std::ostream& log);
  // Runs every channel's events in [start, end); returns early when a stop is requested.
  void run();
  // The last event's GPS time.
  GpsTime scenario_now() const { return scenario_now_; }

 private:
  void skip_late_events();
  void service();
  void lockstep_tick();
  void print_status(GpsTime at);

  Clock& clock_;
  TruthSource& truth_;
  std::vector<SensorChannel*> channels_;
  SchedulerOptions opt_;
  std::ostream& log_;
  bool has_input_ = false;

  LatenessStats lateness_;
  fmt::memory_buffer status_line_, part_;
  TruthCounters truth_at_status_;
  GpsTime scenario_now_;
  // Lockstep's wall-time tick, and when a datagram was last taken.
  std::int64_t next_tick_mono_ = 0, next_status_mono_ = INT64_MAX, truth_moved_mono_ = 0;
  std::uint64_t accepted_seen_ = 0;
};

}  // namespace navemu
