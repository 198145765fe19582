#pragma once
// The emulator's loop: truth in, the GNSS receiver and the IMU at their own rates against GPS
// time, their output on ports and in logs.
//
// Epochs lie on whole multiples of each sensor's period in GPS time (5 Hz: .0 .2 .4 ...;
// 125 Hz: every 8 ms). In real time the loop sleeps to absolute deadlines on CLOCK_MONOTONIC
// (clock_nanosleep TIMER_ABSTIME): deadline = the epoch + the sensor's output latency, mapped
// from GPS time by one fixed offset taken at start, so nothing drifts. The GNSS epoch is
// computed kComputeLead before its deadline and written at it. A GNSS epoch whose deadline passed
// more than one period ago is skipped and counted, never sent late in a burst; IMU samples
// (which drivers integrate, and which a real IMU never drops) are sent late after a stall and
// skipped only beyond 500 ms. The loop starts with the first events ahead of the moment setup
// is done, so none is skipped at start. Offline
// (`navemu simulate`) the same events run in the same order without sleeping.
//
// Time modes: realtime (GPS time = scenario start + monotonic time elapsed) and lockstep (GPS
// time = the newest truth datagram's time: an epoch is processed once the truth stream has
// passed it; without truth, time stands still).

#include <fmt/format.h>

#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>

#include "emulator/run_config.hpp"
#include "emulator/truth_buffer.hpp"
#include "core/time.hpp"

namespace navemu {

struct EngineOptions {
  bool realtime = true;              // false: offline, as fast as possible (simulate)
  std::optional<double> duration_s;  // none: until SIGINT/SIGTERM
  std::filesystem::path out_dir;     // offline: nmea.log, truth.csv, gnss.csv, imu.csv
  // CLOCK_MONOTONIC read together with the start time (a run that starts "now"), so that GPS
  // time in the loop follows the system clock; unset: the loop's own start.
  std::optional<std::int64_t> start_monotonic_ns;
  // Offline with a generated truth (stationary, circle, line, waypoints): 2 or more runs the
  // IMU channel on a thread of its own beside the others. The files are the same as with one
  // thread: the channels share nothing while they run (each has its own random streams and
  // outputs), and a generator's truth is a function of time, so each thread has its own.
  int threads = 1;
};

// CLOCK_MONOTONIC in nanoseconds.
std::int64_t monotonic_ns();
// CLOCK_REALTIME in nanoseconds since 1970-01-01 UTC.
std::int64_t realtime_ns();

struct EngineSummary {
  std::int64_t gnss_epochs = 0, gnss_fixes = 0, gnss_skipped = 0, gnss_late = 0;
  std::int64_t gnss_silent = 0;  // epochs not sent: the cable out, a reset's boot
  std::int64_t imu_samples = 0, imu_flagged = 0, imu_skipped = 0;
  std::int64_t imu_dropped = 0, imu_duplicated = 0, imu_bus_off = 0;  // by a fault
  std::int64_t can_error_frames = 0;  // sent by a fault
  std::uint64_t output_chunks_dropped = 0;
  // Summed over the GNSS ports (transport::PortCounters): bytes the clients sent (commands, or
  // whatever a client floods in), and unread output discarded as stale (a lower bound, pty).
  std::uint64_t client_bytes_read = 0, stale_flushes = 0, stale_bytes_flushed = 0;
  // CAN: written + dropped (queue full, ENOBUFS) + held (slcan channel not opened by a client)
  // + failed (interface down, ...) = every frame.
  std::uint64_t can_frames_written = 0, can_frames_dropped = 0, can_frames_held = 0,
                can_frames_failed = 0, can_bus_errors = 0;
  std::optional<TruthCounters> truth;  // a streamed truth's counters
  double wall_s = 0.0, scenario_s = 0.0;
};

// The truth's rejections by reason and its re-synchronisations, those that occurred:
// "crc 1, backwards 2; resync 1" (README, "truth").
void format_truth_reasons(const TruthCounters& c, fmt::memory_buffer& out);

// SIGINT and SIGTERM end the loop at its next wake-up (outputs flushed, links removed).
void install_stop_handlers();
bool stop_requested();

// Runs the configuration from GPS time `start`; start-up messages and status lines go to
// `log`. Opening errors (ports, files, profiles) throw before the loop starts.
EngineSummary run_engine(const RunConfig& cfg, GpsTime start, const EngineOptions& opt,
                         std::ostream& log);

}  // namespace navemu
