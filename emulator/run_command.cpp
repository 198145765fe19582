// navemu run / navemu simulate: the emulator's loop on a configuration (emulator/engine.hpp).

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <algorithm>
#include <ostream>
#include <thread>

#include "emulator/commands.hpp"
#include "emulator/engine.hpp"
#include "emulator/run_config.hpp"
#include "core/errors.hpp"

namespace navemu {

struct RunOptions {
  std::string config;  // empty: configs/default.yaml
  std::optional<double> duration_s;
  std::string start;  // overrides scenario.start
  std::optional<std::uint64_t> seed;
  std::string out_dir;  // simulate
  int threads = 1;      // simulate
  bool offline = false;
};

namespace {

constexpr const char* kSimulateUbxMessages[] = {"NAV-PVT", "NAV-SAT", "RXM-RAWX", "RXM-SFRBX"};

const char* kConfigHelp =
    "The configuration (YAML; configs/default.yaml documents every key) names the scenario\n"
    "(start time, seed, navigation data), the truth source (built-in stationary, circle, line or\n"
    "waypoints generators, a truth CSV file or standard input, or UDP datagrams from a simulator:\n"
    "docs/truth-protocol.md, tools/truth-sender), the GNSS receiver profile (configs/gnss/) with\n"
    "its outputs (pty, serial, tcp, udp, file) and the IMU profile (configs/imu/).\n";

void add_common(CLI::App* cmd, RunOptions& opt) {
  cmd->add_option("--start", opt.start,
                  "Scenario start, overriding scenario.start: ISO-8601 UTC, GPS WEEK:TOW or now");
  cmd->add_option("--seed", opt.seed, "Scenario seed, overriding scenario.seed");
}

RunConfig load(const RunOptions& opt) {
  RunConfig cfg = load_run_config(opt.config.empty() ? default_run_config()
                                                     : std::filesystem::path(opt.config));
  if (!opt.start.empty()) cfg.start = opt.start;
  if (opt.seed) cfg.seed = *opt.seed;
  return cfg;
}

// What the `events:` cost, for the closing line: GNSS epochs not sent, IMU samples lost or sent
// twice.
std::string gnss_event_counts(const EngineSummary& s) {
  return s.gnss_silent ? fmt::format(", {} not sent: cable out or resetting", s.gnss_silent) : "";
}
std::string imu_event_counts(const EngineSummary& s) {
  std::string out;
  if (s.imu_dropped) out += fmt::format(", {} dropped by a fault", s.imu_dropped);
  if (s.imu_duplicated) out += fmt::format(", {} sent twice by a fault", s.imu_duplicated);
  if (s.imu_bus_off) out += fmt::format(", {} lost to a CAN bus-off", s.imu_bus_off);
  if (s.can_error_frames) out += fmt::format(", {} CAN error frames", s.can_error_frames);
  return out;
}

}  // namespace

std::shared_ptr<RunOptions> add_run_command(CLI::App& app) {
  auto opt = std::make_shared<RunOptions>();
  CLI::App* run = app.add_subcommand("run", "Run the emulator in real time (the main command)");
  run->footer(std::string(kConfigHelp) +
              "The loop sleeps to absolute deadlines on the monotonic clock: every sensor epoch\n"
              "lies on a whole multiple of its period in GPS time and leaves at epoch + the\n"
              "profile's latency. Start-up lines say where each output is (e.g. the pty path to\n"
              "give gpsd); a status line each second reports epochs, fix, DOP, error against the\n"
              "truth, output jitter (p50/p99/max lateness), late/skipped epochs, dropped output\n"
              "and the truth stream's counters. SIGINT or SIGTERM stop it cleanly.\n"
              "Examples:\n"
              "  navemu run                          (configs/default.yaml)\n"
              "  navemu run my.yaml --duration 600\n"
              "  gpsd -N -n /tmp/navemu-gnss; gpspipe -w");
  run->add_option("config", opt->config, "Configuration file (default: configs/default.yaml)");
  run->add_option("--duration", opt->duration_s, "Stop after this many seconds (default: run until stopped)")
      ->check(positive_number());
  add_common(run, *opt);
  return opt;
}

std::shared_ptr<RunOptions> add_simulate_command(CLI::App& app) {
  auto opt = std::make_shared<RunOptions>();
  opt->offline = true;
  CLI::App* sim = app.add_subcommand(
      "simulate", "Run a configuration offline, as fast as possible, into files");
  sim->footer(std::string(kConfigHelp) +
              "Runs the same models and encoders as `navemu run` without sleeping (the truth must\n"
              "be a generator or a CSV file) and writes into --out:\n"
              "  nmea.log   the receiver's byte stream (ubx.bin for a u-blox receiver: its\n"
              "             power-up output and UBX NAV-PVT, NAV-SAT, RXM-RAWX and RXM-SFRBX\n"
              "             every epoch, as a logging client would enable them)\n"
              "  truth.csv  the truth at each GNSS epoch (the truth CSV format: replayable)\n"
              "  gnss.csv   per epoch: truth, fix, satellites, solution, velocity, error (east,\n"
              "             north, up, horizontal), DOPs and the receiver's 1-sigma accuracy\n"
              "             estimates (horizontal, vertical)\n"
              "  imu.csv    per IMU sample: time, specific force, angular rate, temperature, and\n"
              "             truth_valid (0 when the truth was missing and the sample is flagged),\n"
              "             gps_time_ns (time of validity) and the CAN sequence number\n"
              "  can.log    the IMU's CAN frames, candump -L format (imu.outputs' layouts; J1939\n"
              "             when none): log2asc and canplayer read it\n"
              "time_s counts from the scenario start. The same configuration, start and seed give\n"
              "identical files (set scenario.start or --start: 'now' changes every run).\n"
              "Example:\n"
              "  navemu simulate configs/default.yaml --start 2010-11-17T13:00:00Z --duration 3600 --out run1");
  sim->add_option("config", opt->config, "Configuration file")->required();
  sim->add_option("--duration", opt->duration_s, "Scenario length in seconds")
      ->required()
      ->check(positive_number());
  sim->add_option("--out", opt->out_dir, "Output folder (created)")->required();
  opt->threads = std::thread::hardware_concurrency() >= 2 ? 2 : 1;
  sim->add_option("--threads", opt->threads,
                  "Threads: 2 runs the IMU beside the GNSS receiver when the truth is a generator\n"
                  "(identical files; default 2 on a machine with 2 or more cores, else 1)")
      ->check(CLI::Range(1, 64));
  add_common(sim, *opt);
  return opt;
}

int run_run(const RunOptions& opt, std::ostream& out, std::ostream& err) {
  (void)out;
  RunConfig cfg = load(opt);
  // Offline, nobody configures a u-blox receiver: its stream carries what a logging client
  // (u-center, RTKLIB's command files) would enable, every epoch, beside the power-up output.
  if (opt.offline && cfg.gnss.ubx)
    for (const char* name : kSimulateUbxMessages) {
      auto& m = cfg.gnss.ubx->messages;
      if (std::none_of(m.begin(), m.end(), [&](const auto& e) { return e.first == name; })) m.emplace_back(name, 1);
    }
  // A real-time run that starts now follows the system clock: the start and the monotonic
  // clock are read together, before the setup's delay.
  EngineOptions eo;
  GpsTime start;
  if (cfg.start == "now" && !opt.offline) {
    // A preemption between the two reads would offset every deadline from the system clock
    // for the whole run: of three tries, the pair whose monotonic reads bracket the system
    // clock's most tightly, with the monotonic time taken at the bracket's middle.
    std::int64_t best_span = INT64_MAX;
    for (int i = 0; i < 3; ++i) {
      const std::int64_t m0 = monotonic_ns();
      const GpsTime now = gps_now();
      const std::int64_t m1 = monotonic_ns();
      if (m1 - m0 < best_span) {
        best_span = m1 - m0;
        start = now;
        eo.start_monotonic_ns = m0 + (m1 - m0) / 2;
      }
    }
  } else {
    start = time_option(cfg.start, "scenario.start");
  }
  eo.realtime = !opt.offline;
  eo.duration_s = opt.duration_s;
  eo.out_dir = opt.out_dir;
  eo.threads = opt.threads;
  install_stop_handlers();
  const EngineSummary s = run_engine(cfg, start, eo, err);
  if (opt.offline) {
    fmt::print(err,
               "navemu simulate: {:.0f} s of scenario in {:.2f} s ({:.0f}x real time): {} GNSS "
               "epochs ({} with a fix{}), {} IMU samples{}{}; files in {}\n",
               s.scenario_s, s.wall_s, s.wall_s > 0 ? s.scenario_s / s.wall_s : 0.0, s.gnss_epochs,
               s.gnss_fixes, gnss_event_counts(s), s.imu_samples,
               s.imu_flagged ? fmt::format(" ({} flagged: no truth)", s.imu_flagged) : "",
               imu_event_counts(s), opt.out_dir);
  } else {
    const TruthCounters truth = s.truth.value_or(TruthCounters{});
    fmt::memory_buffer reasons;
    format_truth_reasons(truth, reasons);
    fmt::print(err,
               "navemu run: stopped after {:.1f} s: {} GNSS epochs ({} with a fix, {} late, {} "
               "skipped{}), {} IMU samples ({} skipped{}), {} output chunks dropped, {} stale bytes "
               "flushed in {} flushes, {} bytes from clients, {} CAN frames ({} dropped, {} failed, "
               "{} bus errors){}, truth {} accepted / {} rejected / {} lost unread{}\n",
               s.wall_s, s.gnss_epochs, s.gnss_fixes, s.gnss_late, s.gnss_skipped, gnss_event_counts(s),
               s.imu_samples, s.imu_skipped, imu_event_counts(s),
               s.output_chunks_dropped, s.stale_bytes_flushed, s.stale_flushes,
               s.client_bytes_read, s.can_frames_written, s.can_frames_dropped, s.can_frames_failed,
               s.can_bus_errors,
               s.can_frames_held ? fmt::format(", {} CAN frames held back (no client opened the slcan channel)",
                                               s.can_frames_held)
                                 : "",
               truth.accepted, truth.rejected(), truth.lost,
               reasons.size() ? fmt::format(" ({})", fmt::to_string(reasons)) : "");
  }
  return 0;
}

}  // namespace navemu
