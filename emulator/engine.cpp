#include "emulator/engine.hpp"

#include <fmt/format.h>
#include <fmt/ostream.h>
#include <sched.h>
#include <sys/mman.h>
#include <time.h>

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <memory>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <thread>
#include <vector>

#include "emulator/commands.hpp"
#include "emulator/run_setup.hpp"
#include "emulator/scheduler.hpp"
#include "emulator/truth_source.hpp"
#include "core/errors.hpp"
#include "transports/byte_port.hpp"

namespace navemu {

namespace {

std::atomic<bool> g_stop{false};
extern "C" void on_stop_signal(int) { g_stop.store(true); }

// Lockstep: waits for the first accepted truth datagram while the outputs are serviced (TCP
// clients accepted, slcan adapter commands answered), with a status line each interval that
// says what navemu waits for. Throws when truth.first_wait_s passes without one (0: waits
// forever); none when a stop was requested.
std::optional<GpsTime> wait_for_first_truth(const RunConfig& cfg, TruthSource& truth, RunOutputs& outputs,
                                            std::ostream& log) {
  const std::string where = fmt::format("udp {}:{}", cfg.truth.udp_address, truth_udp_port(truth));
  fmt::print(log, "navemu: lockstep: waiting for truth on {}; the scenario starts at its first datagram\n",
             where);
  log.flush();
  const std::int64_t t0 = monotonic_ns();
  const std::int64_t status_ns = std::llround(cfg.status_interval_s * 1e9);
  std::int64_t next_status = status_ns > 0 ? t0 + status_ns : INT64_MAX;
  while (!g_stop.load()) {
    truth.poll(std::nullopt);
    if (const std::optional<GpsTime> first = truth.newest()) return first;
    const std::int64_t now = monotonic_ns();
    const double waited_s = static_cast<double>(now - t0) * 1e-9;
    if (cfg.truth.first_wait_s > 0.0 && waited_s > cfg.truth.first_wait_s)
      throw std::runtime_error(fmt::format(
          "lockstep: no truth datagram on {} within {} s (truth.first_wait_s; 0 waits forever): "
          "is the simulator sending there?",
          where, cfg.truth.first_wait_s));
    if (now >= next_status) {
      const TruthCounters* tc = truth.counters();
      fmt::print(log, "navemu: waiting for truth on {} ({:.0f} s{})\n", where, waited_s,
                 tc && tc->rejected() ? fmt::format(", {} datagrams rejected", tc->rejected()) : "");
      log.flush();
      next_status += status_ns;
    }
    outputs.gnss.service();
    if (outputs.can) outputs.can->service();
    timespec ts{0, 2'000'000};
    nanosleep(&ts, nullptr);
  }
  return std::nullopt;
}

void try_realtime_hardening(const RunConfig& cfg, std::ostream& log) {
  if (cfg.lock_memory && mlockall(MCL_CURRENT | MCL_FUTURE) != 0)
    fmt::print(log, "navemu: realtime.lock_memory: mlockall failed ({}); continuing unlocked\n",
               std::strerror(errno));
  if (cfg.cpu) {
    cpu_set_t set;
    CPU_ZERO(&set);
    CPU_SET(static_cast<std::size_t>(*cfg.cpu), &set);
    if (sched_setaffinity(0, sizeof set, &set) != 0)
      fmt::print(log, "navemu: realtime.cpu: cannot pin to CPU {} ({}); continuing unpinned\n",
                 *cfg.cpu, std::strerror(errno));
    else
      fmt::print(log, "navemu: realtime.cpu: loop pinned to CPU {}\n", *cfg.cpu);
  }
  if (cfg.sched_fifo) {
    sched_param sp{};
    sp.sched_priority = 50;
    if (sched_setscheduler(0, SCHED_FIFO, &sp) != 0)
      fmt::print(log,
                 "navemu: realtime.sched_fifo: SCHED_FIFO refused ({}; needs CAP_SYS_NICE or an "
                 "rtprio limit); continuing with normal scheduling\n",
                 std::strerror(errno));
  }
}

void print_truth(const RunConfig& cfg, const TruthSource& truth, std::ostream& log) {
  fmt::print(log, "navemu: truth: {}\n", truth.describe());
  if (cfg.truth.kind == TruthSourceKind::kUdp && !transport::is_loopback_address(cfg.truth.udp_address))
    fmt::print(log,
               "navemu: warning: truth datagrams are accepted on {}, not loopback: any host that "
               "reaches it can move the emulated vehicle\n",
               cfg.truth.udp_address);
}

// The scheduled events, at the times they will happen (they count from the scheduler's start).
void print_events(const RunConfig& cfg, GpsTime start, std::ostream& log) {
  const auto print = [&](const EventWindow& w, const std::string& what) {
    const GpsTime from = w.at ? *w.at : start.plus_s(w.start_s);
    fmt::print(log, "navemu: event: {}, from {} ({}) for {} s{}\n", what, format_iso_utc(from), format_week_tow(from),
               w.duration_s, w.ramp_s > 0.0 ? fmt::format(", ramps {} s", w.ramp_s) : "");
  };
  for (const TruthFault& f : cfg.truth_faults)
    print(f.window, f.kind == TruthFaultKind::kFreeze ? std::string("truth frozen")
                    : f.kind == TruthFaultKind::kTeleport
                        ? fmt::format("truth teleported {} m east, {} m north, {} m up", f.offset_enu_m.x(),
                                      f.offset_enu_m.y(), f.offset_enu_m.z())
                        : fmt::format("truth time jump {:+} s", f.jump_s));
  if (cfg.imu_enabled) {
    constexpr const char* kAxes[] = {"all axes", "x", "y", "z"};
    for (const ImuFault& f : cfg.imu_faults) {
      const bool gyro = f.sensor == ImuSensor::kGyro;
      const std::string sensor = fmt::format("{} {}", gyro ? "gyroscope" : "accelerometer", kAxes[f.axis + 1]);
      switch (f.kind) {
        case ImuFaultKind::kBias:
          print(f.window, gyro ? fmt::format("IMU bias step, {}, {:.6g} deg/s", sensor, f.value * kRadToDeg)
                               : fmt::format("IMU bias step, {}, {:.6g} m/s^2", sensor, f.value));
          break;
        case ImuFaultKind::kScale:
          print(f.window, fmt::format("IMU scale-factor error, {}, {} ppm", sensor, f.value));
          break;
        case ImuFaultKind::kNoise:
          print(f.window, fmt::format("IMU added noise, {}, {} {}/sqrt(Hz)", sensor, f.value, gyro ? "rad/s" : "m/s^2"));
          break;
        case ImuFaultKind::kStuck:
          print(f.window, fmt::format("IMU stuck output, {}", sensor));
          break;
        case ImuFaultKind::kSaturation:
          print(f.window, gyro ? fmt::format("IMU saturation, {}, range {:.6g} deg/s", sensor, f.value * kRadToDeg)
                               : fmt::format("IMU saturation, {}, range {:.6g} m/s^2", sensor, f.value));
          break;
        case ImuFaultKind::kVibration: {
          std::string what = fmt::format("IMU vibration, {}", sensor);
          if (f.vibration.frequency_hz > 0.0)
            what += gyro ? fmt::format(", {:.6g} deg/s at {} Hz", f.value * kRadToDeg, f.vibration.frequency_hz)
                         : fmt::format(", {:.6g} m/s^2 at {} Hz", f.value, f.vibration.frequency_hz);
          if (f.vibration.psd > 0.0)
            what += fmt::format(", random {:.6g} {} rms over {} to {} Hz",
                                std::sqrt(f.vibration.psd * (f.vibration.band_hi_hz - f.vibration.band_lo_hz)) *
                                    (gyro ? kRadToDeg : 1.0),
                                gyro ? "deg/s" : "m/s^2", f.vibration.band_lo_hz, f.vibration.band_hi_hz);
          print(f.window, what);
          break;
        }
        case ImuFaultKind::kTemperature:
          print(f.window, fmt::format("IMU temperature change, {:+} degC", f.value));
          break;
        case ImuFaultKind::kDrop:
          print(f.window, fmt::format("IMU samples dropped, probability {}", f.value));
          break;
        case ImuFaultKind::kDuplicate:
          print(f.window, fmt::format("IMU samples sent twice, probability {}", f.value));
          break;
        case ImuFaultKind::kBusOff:
          print(f.window, "IMU CAN bus-off");
          break;
        case ImuFaultKind::kErrorFrames:
          print(f.window, fmt::format("IMU CAN error frames, {} per second", f.value));
          break;
      }
    }
  }
  if (!cfg.gnss_enabled) return;
  const GnssEvents& ev = cfg.gnss_events;
  constexpr const char* kKinds[] = {"CW", "matched-spectrum", "wideband"};
  constexpr const char* kBands[] = {"L1", "L2", "L5"};
  for (const JammingEvent& j : ev.jamming)
    print(j.window, fmt::format("jamming, {} on {}, J/S {} dB", kKinds[static_cast<int>(j.kind)],
                                kBands[static_cast<int>(j.band)], j.j_over_s_db));
  for (const OutageEvent& o : ev.outages)
    print(o.window, fmt::format("outage, azimuth {} to {} deg below {} deg elevation", o.az_from_deg, o.az_to_deg,
                                o.below_el_deg));
  for (const AntennaEvent& a : ev.antenna)
    print(a.window, a.fault == AntennaFault::kOpen ? "antenna open" : "antenna short");
  for (const SatelliteFaultEvent& f : ev.satellites) {
    std::string what = fmt::format("satellite fault, {}", f.sat.rinex());
    if (f.clock_error_m != 0.0) what += fmt::format(" clock error {} m", f.clock_error_m);
    if (!f.orbit_error_rac_m.isZero())
      what += fmt::format(" orbit error {} m radial, {} m along-track, {} m cross-track", f.orbit_error_rac_m.x(),
                          f.orbit_error_rac_m.y(), f.orbit_error_rac_m.z());
    if (f.unhealthy) what += " flagged unhealthy";
    print(f.window, what);
  }
  for (const IonosphereEvent& i : ev.ionosphere)
    print(i.window, fmt::format("ionospheric storm, delay x{}", i.scale));
  for (const MultipathEvent& m : ev.multipath)
    print(m.window, fmt::format("multipath x{}", m.scale));
  for (const CableEvent& c : ev.cable) print(c.window, "cable unplugged");
  constexpr const char* kStarts[] = {"hot", "warm", "cold"};
  for (const ResetEvent& r : ev.resets)
    print(r.window, fmt::format("receiver reset, {} start: silent {} s, no fix for {} s", kStarts[static_cast<int>(r.kind)],
                                kResetSilence_s, restart_ttff_s(r.kind)));
  for (const SpoofingEvent& s : ev.spoofing)
    print(s.window, fmt::format("spoofing, pull to {} m east, {} m north, {} m up{}, {} dB over the true signals",
                                s.offset_enu_m.x(), s.offset_enu_m.y(), s.offset_enu_m.z(),
                                s.time_offset_s != 0.0 ? fmt::format(", time {:+} s", s.time_offset_s) : "",
                                s.power_advantage_db));
}

}  // namespace

std::int64_t realtime_ns() {
  timespec ts{};
  clock_gettime(CLOCK_REALTIME, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * kNsPerS + ts.tv_nsec;
}

std::int64_t monotonic_ns() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * kNsPerS + ts.tv_nsec;
}

void format_truth_reasons(const TruthCounters& c, fmt::memory_buffer& b) {
  const auto out = std::back_inserter(b);
  const std::pair<const char*, std::uint64_t> reasons[] = {
      {"crc", c.bad_framing}, {"nan", c.not_finite}, {"range", c.out_of_range},
      {"duplicate", c.duplicate}, {"backwards", c.backwards}, {"future", c.future}};
  const char* sep = "";
  for (const auto& [name, n] : reasons) {
    if (n == 0) continue;
    fmt::format_to(out, "{}{} {}", sep, name, n);
    sep = ", ";
  }
  if (c.resync) fmt::format_to(out, "{}resync {}", *sep ? "; " : "", c.resync);
}

void install_stop_handlers() {
  g_stop.store(false);
  struct sigaction sa {};
  sa.sa_handler = on_stop_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = 0;  // no SA_RESTART: clock_nanosleep returns EINTR and the loop sees the flag
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
  signal(SIGPIPE, SIG_IGN);
}

bool stop_requested() { return g_stop.load(); }

namespace {
// A run's truth source, and the wrapper through which truth faults act on it (if any).
struct TruthOfRun {
  std::unique_ptr<TruthSource> source;
  ImpairedTruth* impaired = nullptr;
};
}  // namespace

EngineSummary run_engine(const RunConfig& cfg, GpsTime start, const EngineOptions& opt, std::ostream& log) {
  EngineSummary sum;
  const bool offline = !opt.realtime;
  const bool lockstep = !offline && cfg.time_mode == TimeMode::kLockstep;
  if (offline && cfg.truth.kind == TruthSourceKind::kUdp)
    throw InputError(cfg.file.string(), 0, "truth.source", "simulate needs a generator or a CSV truth, not udp");

  // Host time stamps of truth datagrams map onto the scenario's clock: the scenario's start
  // corresponds to the host's "now" at start (read before setting up, which takes a while).
  const GpsTime host_offset{start.ns - gps_now().ns};
  RunPlan plan = resolve_run(cfg, opt, log);
  // Truth faults (`events:`, live control) act on the truth through ImpairedTruth (the
  // lockstep clock's reference below is to the wrapper, which passes the stream through).
  const bool wrap_truth = !cfg.truth_faults.empty() || (cfg.control && !offline);
  const auto new_truth = [&] {
    TruthOfRun t{make_truth_source(cfg.truth, start, host_offset)};
    if (wrap_truth) {
      auto wrapped = std::make_unique<ImpairedTruth>(std::move(t.source));
      t.impaired = wrapped.get();
      t.source = std::move(wrapped);
    }
    return t;
  };
  TruthOfRun truth_of_run = new_truth();
  TruthSource& truth = *truth_of_run.source;
  ImpairedTruth* const main_impaired = truth_of_run.impaired;
  // Navigation data are checked before anything opens; lockstep knows its start only at the
  // first datagram, so it checks them then.
  NavData nav;
  if (!lockstep) nav = scenario_nav(plan, start, opt, log);
  RunOutputs outputs = open_outputs(cfg, plan, opt, log);
  print_truth(cfg, truth, log);
  print_outputs(cfg, plan, outputs, opt, log);
  if (lockstep) {
    const std::optional<GpsTime> first = wait_for_first_truth(cfg, truth, outputs, log);
    if (!first) return sum;  // stopped while waiting
    start = *first;
    nav = scenario_nav(plan, start, opt, log);
  }
  fmt::print(log, "navemu: scenario start {} ({}), seed {}, {}\n", format_iso_utc(start), format_week_tow(start),
             cfg.seed, offline ? "offline" : lockstep ? "lockstep" : "real time");
  const std::vector<std::unique_ptr<SensorChannel>> channels =
      make_channels(cfg, plan, outputs, std::move(nav), opt, main_impaired, log);
  if (!offline) try_realtime_hardening(cfg, log);

  const std::unique_ptr<Clock> clock =
      offline    ? make_offline_clock()
      : lockstep ? make_lockstep_clock(truth)
                 : make_realtime_clock(start, opt.start_monotonic_ns.value_or(monotonic_ns()));
  const std::int64_t wall0 = monotonic_ns();
  // Setting up took time: in real time the run begins with the first events still ahead (none
  // is skipped as late at start), and the duration counts from there.
  if (clock->realtime()) start = GpsTime{start.ns + std::max<std::int64_t>(0, wall0 - clock->mono_of(start))};
  print_events(cfg, start, log);
  if (main_impaired) main_impaired->set_faults(cfg.truth_faults, start);
  SchedulerOptions so;
  so.start = start;
  so.end = opt.duration_s ? start.plus_s(*opt.duration_s) : GpsTime{INT64_MAX};
  so.status_ns = cfg.status_interval_s > 0.0 ? std::llround(cfg.status_interval_s * 1e9) : 0;
  // The IMU on a thread of its own (EngineOptions::threads), with its own truth and clock; its
  // log lines follow the others'.
  const bool generated = cfg.truth.kind != TruthSourceKind::kCsv && cfg.truth.kind != TruthSourceKind::kUdp;
  std::vector<SensorChannel*> order, apart;
  for (const auto& c : channels)
    (offline && generated && opt.threads >= 2 && c->status_key() == "imu" ? apart : order).push_back(c.get());
  if (order.empty()) std::swap(order, apart);
  std::ostringstream apart_log;
  std::exception_ptr apart_error;
  {
    TruthOfRun apart_truth;
    std::unique_ptr<Clock> apart_clock;
    std::jthread apart_thread;  // declared last: joined before what it uses goes
    if (!apart.empty()) {
      fmt::print(log, "navemu: the IMU runs on a thread of its own\n");
      apart_truth = new_truth();
      if (apart_truth.impaired) apart_truth.impaired->set_faults(cfg.truth_faults, start);
      apart_clock = make_offline_clock();
      apart_thread = std::jthread([&] {
        try {
          Scheduler(*apart_clock, *apart_truth.source, apart, so, apart_log).run();
        } catch (...) {
          apart_error = std::current_exception();
        }
      });
    }
    Scheduler(*clock, truth, order, so, log).run();
  }  // joined
  if (apart_error) std::rethrow_exception(apart_error);
  log << apart_log.str();

  for (const auto& c : channels) c->finish(sum);
  if (const TruthCounters* tc = truth.counters()) sum.truth = *tc;
  sum.wall_s = static_cast<double>(monotonic_ns() - wall0) * 1e-9;
  return sum;
}

}  // namespace navemu
