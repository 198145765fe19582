#include "emulator/engine.hpp"

#include <fmt/compile.h>
#include <fmt/format.h>
#include <fmt/ostream.h>
#include <poll.h>
#include <sched.h>
#include <sys/mman.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <fstream>
#include <memory>
#include <ostream>
#include <set>
#include <vector>

#include "emulator/commands.hpp"
#include "emulator/geoid_loader.hpp"
#include "emulator/imu_can.hpp"
#include "emulator/imu_profile.hpp"
#include "emulator/gnss_scene.hpp"
#include "emulator/gnss_device.hpp"
#include "emulator/truth_source.hpp"
#include "models/constellation.hpp"
#include "models/errors.hpp"
#include "models/imu_model.hpp"
#include "models/prn_table.hpp"
#include "models/receiver.hpp"
#include "models/rinex.hpp"
#include "transports/byte_port.hpp"

namespace navemu {

namespace {

std::atomic<bool> g_stop{false};
extern "C" void on_stop_signal(int) { g_stop.store(true); }

constexpr std::int64_t kComputeLead_ns = 2'000'000;  // GNSS epoch computed 2 ms before output
constexpr std::int64_t kImuCatchUp_ns = 500'000'000;  // later IMU samples are skipped


// Smallest multiple of `period` at or after t.
std::int64_t first_index_at_or_after(GpsTime t, std::int64_t period_ns) {
  return t.ns / period_ns + (t.ns % period_ns != 0 ? 1 : 0);
}

// The loop's notion of time. Real time: GPS time runs with CLOCK_MONOTONIC from the start;
// lockstep: GPS time is where the truth stream is; offline: time jumps from event to event.
class Clock {
 public:
  enum class Kind { kRealTime, kLockstep, kOffline };
  Clock(Kind kind, GpsTime start, std::int64_t start_mono_ns, TruthSource* truth)
      : kind_(kind), gps0_(start), mono0_(start_mono_ns), truth_(truth) {}
  enum class Wait { kReached, kStopped, kWallTick };
  // Waits until GPS time t. In lockstep, where GPS time stands still while the stream does,
  // also returns kWallTick once the monotonic clock reaches `wall_tick_ns` (the ports are
  // serviced and the status line printed on wall time).
  Wait wait_until(GpsTime t, std::int64_t wall_tick_ns = INT64_MAX) {
    switch (kind_) {
      case Kind::kOffline: return g_stop.load() ? Wait::kStopped : Wait::kReached;
      case Kind::kRealTime: {
        const std::int64_t deadline = mono_of(t);
        const timespec ts{static_cast<time_t>(deadline / kNsPerS),
                          static_cast<long>(deadline % kNsPerS)};
        while (!g_stop.load()) {
          const int rc = clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr);
          if (rc == 0) return Wait::kReached;
          if (rc != EINTR) return g_stop.load() ? Wait::kStopped : Wait::kReached;
        }
        return Wait::kStopped;
      }
      case Kind::kLockstep: {
        while (!g_stop.load()) {
          truth_->poll(std::nullopt);
          const std::optional<GpsTime> newest = truth_->newest();
          if (newest && *newest >= t) return Wait::kReached;
          if (monotonic_ns() >= wall_tick_ns) return Wait::kWallTick;
          timespec ts{0, 2'000'000};  // the next datagram; bounded so signals are seen
          nanosleep(&ts, nullptr);
        }
        return Wait::kStopped;
      }
    }
    return Wait::kStopped;
  }
  // Real time: the scenario time now (where a truth stream's stamps should lie).
  GpsTime now() const { return GpsTime{gps0_.ns + (monotonic_ns() - mono0_)}; }
  bool realtime() const { return kind_ == Kind::kRealTime; }
  std::int64_t mono_of(GpsTime t) const { return mono0_ + (t.ns - gps0_.ns); }

 private:
  Kind kind_;
  GpsTime gps0_;
  std::int64_t mono0_ = 0;
  TruthSource* truth_;
};

// Lockstep: waits for the first accepted truth datagram while the ports are serviced (TCP
// clients accepted, slcan adapter commands answered), with a status line each interval that
// says what navemu waits for. Throws when truth.first_wait_s passes without one (0: waits
// forever); none when a stop was requested.
std::optional<GpsTime> wait_for_first_truth(const RunConfig& cfg, TruthSource& truth,
                                            std::vector<std::unique_ptr<transport::BytePort>>& ports,
                                            ImuCanOutputs* can_out, std::ostream& log) {
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
    for (auto& p : ports) p->service();
    if (can_out) can_out->service();
    timespec ts{0, 2'000'000};
    nanosleep(&ts, nullptr);
  }
  return std::nullopt;
}

// The truth's state on the status line. Real time: rejecting when datagrams came during the
// interval and none was taken (the sensors lose the truth timeout_s after the newest taken);
// lost when some epoch or sample of the interval had no truth (so a loss shorter than the
// interval is never left unreported); extrapolating when the newest accepted sample is more
// than kExtrapolating_s older than the status time; ok otherwise. Lockstep, where time follows
// the stream: paused when nothing came, rejecting when nothing was taken.
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

// Output lateness statistics of one status interval, without allocating in the loop.
class LatenessStats {
 public:
  LatenessStats() {
    v_.reserve(8192);
    sorted_.reserve(8192);
  }
  void add(double ms) {
    if (v_.size() < v_.capacity()) v_.push_back(ms);
  }
  // p50/p99/max of the interval into `out`, then a fresh interval.
  void summary_and_reset(fmt::memory_buffer& out) {
    if (v_.empty()) {
      out.push_back('-');
      return;
    }
    sorted_.assign(v_.begin(), v_.end());
    std::sort(sorted_.begin(), sorted_.end());
    const auto pct = [&](double p) {
      return sorted_[std::min(sorted_.size() - 1,
                              static_cast<std::size_t>(p * static_cast<double>(sorted_.size())))];
    };
    fmt::format_to(std::back_inserter(out), "{:.2f}/{:.2f}/{:.2f} ms", pct(0.5), pct(0.99),
                   sorted_.back());
    v_.clear();
  }

 private:
  std::vector<double> v_, sorted_;
};

const char* receiver_mode_name(ReceiverMode m) {
  switch (m) {
    case ReceiverMode::kStandalone: return "standalone";
    case ReceiverMode::kDualFrequency: return "dual-frequency";
    case ReceiverMode::kDgps: return "DGPS";
    case ReceiverMode::kRtkFixed: return "RTK";
  }
  return "?";
}

const char* fix_name(FixType f) {
  switch (f) {
    case FixType::kNone: return "no fix";
    case FixType::kDeadReckoning: return "DR";
    case FixType::k2D: return "2D";
    case FixType::k3D: return "3D";
  }
  return "?";
}

// North/east/up error of a fix relative to the truth, metres.
Vec3 enu_error(const ReceiverFix& fix, const ImuTruth& truth) {
  return enu_from_ecef(fix.p_ecef_m, truth.position);
}

std::unique_ptr<transport::BytePort> open_output(const OutputSpec& o, const GnssProfile& profile) {
  if (o.type == "pty") return transport::open_pty({o.link, o.max_backlog_bytes, o.gpsd_socket});
  if (o.type == "serial") return transport::open_serial({o.device, o.baud ? o.baud : profile.baud});
  if (o.type == "tcp") return transport::open_tcp_server({o.address, o.port, 8});
  if (o.type == "udp") return transport::open_udp_sender({o.address, o.port});
  return transport::open_log_file(o.path);
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

// A CSV file of the offline run, written through one buffer. The buffer is flushed past
// kFlushBytes and holds twice that from the start, so it never grows (rows are short).
class CsvFile {
 public:
  static constexpr std::size_t kFlushBytes = 1u << 16;
  CsvFile(const std::filesystem::path& path, std::string_view header) : path_(path), out_(path) {
    if (!out_) throw InputError(path.string(), 0, "--out", "cannot open for writing");
    buf_.reserve(2 * kFlushBytes);
    buf_.append(header);
  }
  ~CsvFile() { flush(); }
  fmt::memory_buffer& buf() { return buf_; }
  void maybe_flush() {
    if (buf_.size() > kFlushBytes) flush();
  }
  void flush() {
    out_.write(buf_.data(), static_cast<std::streamsize>(buf_.size()));
    buf_.clear();
    out_.flush();
  }
  void close() {
    flush();
    out_.close();
    if (!out_) throw InputError(path_.string(), 0, "--out", "write failed (disk full?)");
  }

 private:
  std::filesystem::path path_;
  std::ofstream out_;
  fmt::memory_buffer buf_;
};

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

EngineSummary run_engine(const RunConfig& cfg, GpsTime start, const EngineOptions& opt,
                         std::ostream& log) {
  EngineSummary sum;
  const bool offline = !opt.realtime;

  // Host time stamps of truth datagrams map onto the scenario's clock: the scenario's start
  // corresponds to the host's "now" at start.
  const GpsTime host_now = gps_now();
  const GpsTime host_offset{start.ns - host_now.ns};
  if (offline && cfg.truth.kind == TruthSourceKind::kUdp)
    throw InputError(cfg.file.string(), 0, "truth.source",
                     "simulate needs a generator or a CSV truth, not udp");
  std::unique_ptr<TruthSource> truth = make_truth_source(cfg.truth, start, host_offset);
  const bool lockstep = !offline && cfg.time_mode == TimeMode::kLockstep;
  if (offline) {
    std::error_code ec;
    if (std::filesystem::exists(opt.out_dir, ec) && !std::filesystem::is_directory(opt.out_dir, ec))
      throw InputError(opt.out_dir.string(), 0, "--out", "exists and is not a folder");
    std::filesystem::create_directories(opt.out_dir, ec);
    if (ec)
      throw InputError(opt.out_dir.string(), 0, "--out",
                       fmt::format("cannot create the output folder ({})", ec.message()));
    if (::access(opt.out_dir.c_str(), W_OK) != 0)
      throw InputError(opt.out_dir.string(), 0, "--out",
                       fmt::format("cannot write into the output folder ({})", std::strerror(errno)));
    // The byte streams are written through append-only log ports: a folder used before starts
    // them empty, as the CSVs are, and loses a stream this run does not write (ubx.bin after a
    // u-blox run, when this one sends NMEA), so every file in it belongs to this run.
    for (const char* name : {"nmea.log", "ubx.bin", "can.log"}) std::filesystem::remove(opt.out_dir / name, ec);
  }

  // --- Navigation data, checked against the scenario before any port opens (in lockstep the
  // start is known only at the first datagram).
  NavData nav;
  if (cfg.gnss_enabled && !lockstep) nav = load_scenario_nav(cfg.nav_file, start, opt.duration_s, log);

  // --- GNSS outputs (the receiver itself comes once the start is known).
  std::unique_ptr<Receiver> receiver;
  std::unique_ptr<GnssDevice> device;
  std::vector<std::unique_ptr<transport::BytePort>> ports;
  std::unique_ptr<transport::BytePort> capture_out, capture_in;  // mirrors of the wire
  const GnssProfile& prof = cfg.gnss;
  std::int64_t gnss_period_ns = std::llround(1e9 / prof.rate_hz);
  const std::int64_t gnss_latency_ns = std::llround(prof.output_latency_s * 1e9);
  if (cfg.gnss_enabled) {
    if (offline) {
      // The receiver's byte stream as on the wire: NMEA, or UBX mixed with NMEA.
      ports.push_back(transport::open_log_file((opt.out_dir / (prof.ubx ? "ubx.bin" : "nmea.log")).string()));
    } else {
      for (const OutputSpec& o : cfg.gnss_outputs) ports.push_back(open_output(o, prof));
      if (!cfg.gnss_capture.empty()) {
        capture_out = transport::open_log_file(cfg.gnss_capture);
        capture_in = transport::open_log_file(cfg.gnss_capture + ".in");
      }
    }
  }

  // --- IMU.
  std::unique_ptr<ImuModel> imu;
  ImuParams imu_params;
  // Output sample j is measured at j * imu_out_ns; the internal steps divide each output period
  // into imu_steps_per_out equal parts, on the nanosecond below when the part is not a whole
  // number of nanoseconds (600 Hz inside 100 Hz: 1,666,666 or 1,666,667 ns apart).
  std::int64_t imu_out_ns = 0, imu_steps_per_out = 1;
  if (cfg.imu_enabled) {
    const ImuProfile p = load_imu_profile(cfg.imu_profile);
    imu_params = imu_params_for_run(p, opt.duration_s.value_or(3600.0), 0.0);
    imu_out_ns = std::llround(1e9 / imu_params.output_rate_hz);
    imu_steps_per_out = std::llround(imu_params.internal_rate_hz / imu_params.output_rate_hz);
    if (imu_steps_per_out < 1 ||
        std::fabs(static_cast<double>(imu_steps_per_out) * imu_params.output_rate_hz -
                  imu_params.internal_rate_hz) > 1e-9 * imu_params.internal_rate_hz)
      throw InputError(p.file.string(), 0, "internal_rate_hz",
                       "must be a whole multiple of output_rate_hz");
    imu = std::make_unique<ImuModel>(imu_params, cfg.seed);
  }
  const auto imu_step_time = [&](std::int64_t n) {
    return GpsTime{n / imu_steps_per_out * imu_out_ns +
                   n % imu_steps_per_out * imu_out_ns / imu_steps_per_out};
  };

  // --- The IMU's CAN frames: offline into can.log (candump -L), live on the configured ports.
  std::unique_ptr<ImuCanOutputs> can_out;
  if (imu) {
    const std::vector<CanOutputSpec> specs =
        offline ? offline_can_outputs(cfg.imu_outputs, (opt.out_dir / "can.log").string())
                : cfg.imu_outputs;
    if (!specs.empty()) can_out = std::make_unique<ImuCanOutputs>(specs, cfg.imu_can, log);
  }

  // --- Offline files and the live IMU log.
  std::unique_ptr<CsvFile> truth_csv, gnss_csv, imu_csv;
  std::unique_ptr<transport::BytePort> imu_log;
  static constexpr std::string_view kImuHeader =
      "time_s,f_x_mps2,f_y_mps2,f_z_mps2,w_x_radps,w_y_radps,w_z_radps,temperature_c,"
      "truth_valid,gps_time_ns,sequence\n";
  if (offline) {
    truth_csv = std::make_unique<CsvFile>(
        opt.out_dir / "truth.csv",
        "time_s,lat_deg,lon_deg,h_m,v_n_mps,v_e_mps,v_d_mps,roll_deg,pitch_deg,yaw_deg\n");
    if (cfg.gnss_enabled)
      gnss_csv = std::make_unique<CsvFile>(
          opt.out_dir / "gnss.csv",
          "time_s,gps_week,gps_tow_s,truth_lat_deg,truth_lon_deg,truth_h_m,fix,num_tracked,"
          "num_used,lat_deg,lon_deg,h_m,v_n_mps,v_e_mps,v_d_mps,err_e_m,err_n_m,err_u_m,"
          "err_h_m,pdop,hdop,vdop,sigma_h_m,sigma_v_m\n");
    if (imu) imu_csv = std::make_unique<CsvFile>(opt.out_dir / "imu.csv", kImuHeader);
  } else if (imu && !cfg.imu_log.empty()) {
    imu_log = transport::open_log_file(cfg.imu_log);
    imu_log->write(kImuHeader);
  }

  // --- Start-up messages: where everything is (before lockstep waits, so clients know where
  // to attach).
  fmt::print(log, "navemu: truth: {}\n", truth->describe());
  if (cfg.truth.kind == TruthSourceKind::kUdp && !transport::is_loopback_address(cfg.truth.udp_address))
    fmt::print(log,
               "navemu: warning: truth datagrams are accepted on {}, not loopback: any host that "
               "reaches it can move the emulated vehicle\n",
               cfg.truth.udp_address);
  if (cfg.gnss_enabled) {
    for (const auto& p : ports)
      fmt::print(log, "navemu: GNSS {} on {}\n", prof.ubx ? "UBX/NMEA" : "NMEA", p->describe());
    if (!offline && ports.empty()) fmt::print(log, "navemu: GNSS has no output (gnss.outputs)\n");
    if (!offline)
      for (const OutputSpec& o : cfg.gnss_outputs)
        if (o.type == "tcp" && !transport::is_loopback_address(o.address))
          fmt::print(log,
                     "navemu: warning: the GNSS tcp output listens on {}, not loopback: any host "
                     "that reaches it receives the receiver's output and can configure it\n",
                     o.address);
    if (capture_out)
      fmt::print(log, "navemu: GNSS capture: sent bytes to {0}, received bytes to {0}.in\n",
                 cfg.gnss_capture);
  }
  if (imu) {
    fmt::print(log, "navemu: IMU {} ({} Hz){}\n", cfg.imu_profile, imu_params.output_rate_hz,
               imu_log ? " samples logged to " + cfg.imu_log : "");
    if (can_out)
      for (const std::string& line : can_out->describe())
        fmt::print(log, "navemu: IMU CAN frames on {}\n", line);
    else if (!offline)
      fmt::print(log, "navemu: IMU has no output (imu.outputs; set imu.log to record samples)\n");
  }
  log.flush();

  // --- Lockstep: the scenario starts where the truth stream does. The ports are open already,
  // so clients can attach while navemu waits (their commands are answered once it starts).
  if (lockstep) {
    const std::optional<GpsTime> first = wait_for_first_truth(cfg, *truth, ports, can_out.get(), log);
    if (!first) return sum;  // stopped while waiting
    start = *first;
  }

  // --- The GNSS receiver: its navigation data and models from the scenario's start on.
  if (cfg.gnss_enabled) {
    if (lockstep) nav = load_scenario_nav(cfg.nav_file, start, opt.duration_s, log);
    ReceiverParams rp;
    rp.measurement.mode = cfg.gnss_mode;
    apply_receiver_class(rp.measurement, prof.receiver_class);
    rp.measurement.elevation_mask_deg = prof.elevation_mask_deg;
    AntennaPattern antenna = patch_antenna_pattern();
    if (!prof.antenna_gain_db_by_el_deg.empty()) {
      rp.measurement.cn0.gain_db_by_el_deg = prof.antenna_gain_db_by_el_deg;
      antenna.rhcp_gain_db_by_el_deg = prof.antenna_gain_db_by_el_deg;
    }
    antenna.lhcp_rejection_db = prof.antenna_lhcp_rejection_db;
    rp.measurement.seed = cfg.seed;
    rp.max_channels = prof.max_channels;
    rp.ideal_sigma_m = cfg.gnss_ideal_sigma_m;
    // The geoid of the MSL heights (GGA, NAV-PVT, NAV-POSLLH): read once per process, here,
    // before the loop.
    const LoadedGeoid& geoid = egm96_geoid();
    if (geoid.grid) rp.geoid = &*geoid.grid;
    if (!cfg.gnss_scene.obj.empty())
      rp.measurement.environment = make_scene_environment(cfg.gnss_scene, cfg.truth.position,
                                                          rp.measurement.tracking, antenna, log);
    receiver = std::make_unique<Receiver>(nav, rp);
    device = make_gnss_device(prof, cfg.gnss_mode, nav);
    gnss_period_ns = device->period_ns();
  }

  fmt::print(log, "navemu: scenario start {} ({}), seed {}, {}\n", format_iso_utc(start),
             format_week_tow(start), cfg.seed,
             offline ? "offline" : lockstep ? "lockstep" : "real time");
  if (receiver) {
    std::set<int> prns;
    for (const GpsEphemeris& e : nav.gps) prns.insert(e.prn);
    fmt::print(log, "navemu: GNSS {} ({} Hz, {} mode), navigation data {} ({} satellites)\n",
               prof.name, prof.rate_hz, receiver_mode_name(cfg.gnss_mode),
               cfg.nav_file.empty() ? "built-in constellation" : cfg.nav_file, prns.size());
    fmt::print(log, "navemu: {}\n", egm96_geoid().description);
  }
  log.flush();
  if (!offline) try_realtime_hardening(cfg, log);

  const Clock::Kind kind = offline    ? Clock::Kind::kOffline
                           : lockstep ? Clock::Kind::kLockstep
                                      : Clock::Kind::kRealTime;
  Clock clock(kind, start,
              opt.start_monotonic_ns && !lockstep ? *opt.start_monotonic_ns : monotonic_ns(),
              truth.get());
  const std::int64_t wall0 = monotonic_ns();
  // Setting up took time: in real time the run begins with the first events still ahead (none
  // is skipped as late at start), and the duration counts from there.
  if (clock.realtime()) start = GpsTime{start.ns + std::max<std::int64_t>(0, wall0 - clock.mono_of(start))};
  const GpsTime end = opt.duration_s ? start.plus_s(*opt.duration_s) : GpsTime{INT64_MAX};

  // --- Event state. Indices count whole periods since the GPS epoch.
  std::int64_t gnss_k = first_index_at_or_after(start, gnss_period_ns);
  std::int64_t imu_j = imu ? first_index_at_or_after(start, imu_out_ns) : 0;
  const std::int64_t imu_j0 = imu_j;  // sample sequence numbers count output periods from here
  std::int64_t imu_n = imu_j * imu_steps_per_out;  // the next internal step
  const std::int64_t status_ns =
      cfg.status_interval_s > 0.0 ? std::llround(cfg.status_interval_s * 1e9) : 0;
  // Real time (and offline, which prints none) at GPS-time intervals; lockstep on wall time.
  GpsTime next_status =
      status_ns && !lockstep ? start.plus_s(cfg.status_interval_s) : GpsTime{INT64_MAX};

  std::string chunk, replies;
  chunk.reserve(65536);
  replies.reserve(4096);
  std::array<std::uint8_t, 4096> input{};
  // Clients' commands are read this often between epochs (u-blox replies within 100 ms).
  const std::int64_t service_ns = 10'000'000;
  GpsTime next_service{start.ns + service_ns};
  LatenessStats lateness;
  ReceiverFix last_fix;
  last_fix.satellites.reserve(kMaxPrn);  // copied every epoch: no allocation
  std::optional<ImuTruth> last_fix_truth;
  std::int64_t interval_epochs = 0;
  // Some GNSS epoch or IMU sample of the status interval had no truth (truth_state()).
  bool interval_truth_lost = false;
  std::optional<ImuTruth> imu_before, imu_now, imu_after;
  std::int64_t window_n = -2;  // the internal step imu_now belongs to
  fmt::memory_buffer imu_line, status_line;
  IdealImu last_ideal = ideal_imu_static(cfg.truth.position, Quat::Identity());
  ImuSample sample;
  const auto t_rel = [&](GpsTime t) { return seconds_between(t, start); };

  const auto gnss_epoch = [&](std::int64_t k) { return GpsTime{k * gnss_period_ns}; };
  const auto gnss_compute_time = [&](std::int64_t k) {
    return GpsTime{k * gnss_period_ns + gnss_latency_ns -
                   std::min(kComputeLead_ns, gnss_period_ns / 2)};
  };
  const auto imu_event = [&](std::int64_t j) {
    return GpsTime{j * imu_out_ns + std::llround(imu_params.latency_s * 1e9)};
  };

  // Clients' input: commands answered on the port they came from, slcan adapter commands, bus
  // errors. At the service tick, not at every wake-up: at 1 kHz each read is a system call per
  // millisecond for nothing.
  const auto service_ports = [&] {
    if (can_out) can_out->service();
    if (!device) return;
    for (auto& p : ports) {
      for (int n = 0; n < 16; ++n) {  // bounded: a flooding client cannot hold the loop
        const std::size_t len = p->read(input);
        if (len == 0) break;
        replies.clear();
        const std::span<const std::uint8_t> in(input.data(), len);
        device->receive(in, replies);
        if (capture_in) capture_in->write(in);
        if (!replies.empty()) {
          p->write(replies);
          if (capture_out) capture_out->write(replies);
        }
      }
    }
    if (const std::optional<int> baud = device->take_baud_change())
      for (auto& p : ports) transport::set_serial_baud(*p, *baud);
  };

  // --- Status line, formatted into one reused buffer: no allocation. In real time at whole
  // status intervals of GPS time; in lockstep on wall time, as GPS time stands still while the
  // stream does.
  TruthCounters truth_at_status;  // the counters at the previous status line
  std::int64_t truth_moved_mono = monotonic_ns();  // lockstep: when a datagram was last taken
  GpsTime scenario_now = start;  // the last event's time
  const auto print_status = [&](GpsTime at) {
    // The live logs (IMU samples, the capture mirrors) are written out once per status interval
    // as well as when their buffer fills, so they can be followed (tail -f) and a write error
    // (disk full) is reported within a second, not only after 64 KB.
    for (transport::BytePort* l : {imu_log.get(), capture_out.get(), capture_in.get()})
      if (l != nullptr) l->service();
    status_line.clear();
    const auto out = std::back_inserter(status_line);
    const CalendarTime c = utc_from_gps(at);
    fmt::format_to(out, "navemu: {:02}:{:02}:{:02.0f} UTC gnss {} ep (", c.hour, c.minute,
                   std::floor(c.second), sum.gnss_epochs);
    if (!receiver || interval_epochs == 0) {
      fmt::format_to(out, "no epoch");
    } else {
      fmt::format_to(out, "{} {}/{} sv", fix_name(last_fix.fix), last_fix.num_used,
                     last_fix.satellites.size());
      if (last_fix.fix != FixType::kNone) {
        fmt::format_to(out, " PDOP {:.1f}", last_fix.dops.pdop);
        if (last_fix_truth) {
          const Vec3 e = enu_error(last_fix, *last_fix_truth);
          fmt::format_to(out, " err {:.1f} m h {:.1f} m v", std::hypot(e.x(), e.y()),
                         std::abs(e.z()));
        }
      }
    }
    fmt::format_to(out, ") imu {} smp", sum.imu_samples);
    if (sum.imu_flagged) fmt::format_to(out, " ({} flagged)", sum.imu_flagged);
    fmt::format_to(out, " | jitter ");
    lateness.summary_and_reset(status_line);
    std::uint64_t chunks_dropped = 0;
    for (const auto& p : ports) chunks_dropped += p->counters().chunks_dropped;
    const CanOutputTotals can = can_out ? can_out->totals() : CanOutputTotals{};
    fmt::format_to(out, " | late {} skipped {} dropped {} chunks {} frames", sum.gnss_late,
                   sum.gnss_skipped + sum.imu_skipped, chunks_dropped,
                   can.frames_dropped + can.frames_failed);
    if (can.frames_held) fmt::format_to(out, ", {} frames held", can.frames_held);
    const TruthCounters* tc = truth->counters();
    const TruthCounters now_counts = tc ? *tc : TruthCounters{};
    const std::optional<GpsTime> newest = truth->newest();
    TruthStatus ts;
    ts.lockstep = lockstep;
    ts.lost = (receiver && !last_fix_truth) || interval_truth_lost;
    ts.accepted = now_counts.accepted - truth_at_status.accepted;
    ts.rejected = now_counts.rejected() - truth_at_status.rejected();
    if (newest && at > *newest) ts.age_s = seconds_between(at, *newest);
    fmt::format_to(out, " | truth {}", truth_state(ts));
    if (lockstep && ts.accepted == 0)
      fmt::format_to(out, " for {:.0f} s", static_cast<double>(monotonic_ns() - truth_moved_mono) * 1e-9);
    if (tc) format_truth_counts(now_counts, status_line);
    truth_at_status = now_counts;
    status_line.push_back('\n');
    log.write(status_line.data(), static_cast<std::streamsize>(status_line.size()));
    log.flush();
    interval_epochs = 0;
    interval_truth_lost = false;
  };

  // Lockstep's wall-time tick: the ports' input and the status line, also while the stream
  // pauses.
  std::int64_t next_tick_mono = monotonic_ns();
  std::int64_t next_status_mono = status_ns ? next_tick_mono + status_ns : INT64_MAX;
  std::uint64_t accepted_seen = 0;
  const auto lockstep_tick = [&] {
    const std::int64_t now = monotonic_ns();
    if (const TruthCounters* tc = truth->counters(); tc && tc->accepted != accepted_seen) {
      accepted_seen = tc->accepted;
      truth_moved_mono = now;
    }
    if (now < next_tick_mono) return;
    service_ports();
    next_tick_mono = now + service_ns;
    if (now >= next_status_mono) {
      print_status(scenario_now);
      next_status_mono = std::max(next_status_mono + status_ns, now);
    }
  };

  for (;;) {
    // The run covers the epochs measured in [start, end).
    const bool gnss_due = receiver && gnss_epoch(gnss_k) < end;
    const bool imu_due = imu && GpsTime{imu_j * imu_out_ns} < end;
    if (!gnss_due && !imu_due) break;
    GpsTime next{INT64_MAX};
    if (gnss_due) next = std::min(next, gnss_compute_time(gnss_k));
    if (imu_due) next = std::min(next, imu_event(imu_j));
    next = std::min(next, next_status);
    if ((device || can_out) && clock.realtime()) next = std::min(next, next_service);
    if (lockstep) lockstep_tick();
    const Clock::Wait waited = clock.wait_until(next, lockstep ? next_tick_mono : INT64_MAX);
    if (waited == Clock::Wait::kStopped) break;
    if (waited == Clock::Wait::kWallTick) continue;  // the tick runs at the top
    scenario_now = next;
    truth->poll(clock.realtime() ? std::optional<GpsTime>(clock.now()) : std::nullopt);
    while (const std::optional<std::string> w = truth->take_warning())
      fmt::print(log, "navemu: warning: {}\n", *w);
    if (clock.realtime() && next_service <= next) service_ports();

    // A GNSS epoch whose output deadline passed more than a period ago is skipped, not sent
    // late. IMU samples are what a driver integrates, and a real IMU never drops one: after a
    // stall the late ones go out at once (each with its own time of validity), and only those
    // more than kImuCatchUp late are skipped.
    if (clock.realtime()) {
      const std::int64_t now_mono = monotonic_ns();
      while (receiver && now_mono > clock.mono_of(gnss_epoch(gnss_k)) + gnss_latency_ns + gnss_period_ns) {
        ++gnss_k;
        ++sum.gnss_skipped;
      }
      while (imu && now_mono > clock.mono_of(imu_event(imu_j)) + std::max(kImuCatchUp_ns, imu_out_ns)) {
        ++imu_j;
        ++sum.imu_skipped;
      }
    }

    // --- GNSS epoch: compute ahead, write at the deadline.
    if (gnss_due && gnss_compute_time(gnss_k) <= next) {
      const GpsTime te = gnss_epoch(gnss_k);
      const std::optional<ImuTruth> tr = truth->at(te);
      const ReceiverFix& fix = receiver->update(te, tr ? &*tr : nullptr);
      chunk.clear();
      device->encode_epoch(fix, receiver->measurements(), gnss_k, chunk);
      const GpsTime deadline{te.ns + gnss_latency_ns};
      if (clock.realtime() && clock.wait_until(deadline) == Clock::Wait::kStopped) break;
      for (auto& p : ports) {
        p->service();
        if (!p->write(chunk)) ++sum.output_chunks_dropped;
      }
      if (capture_out) capture_out->write(chunk);
      if (clock.realtime()) {
        const double late_ms = static_cast<double>(monotonic_ns() - clock.mono_of(deadline)) * 1e-6;
        lateness.add(late_ms);
        if (late_ms > 0.5 * static_cast<double>(gnss_period_ns) * 1e-6) ++sum.gnss_late;
      }
      ++sum.gnss_epochs;
      ++interval_epochs;
      if (!tr) interval_truth_lost = true;
      if (fix.fix != FixType::kNone) ++sum.gnss_fixes;
      last_fix = fix;
      last_fix_truth = tr;
      if (offline) {
        const WeekTow wt = to_week_tow(te);
        if (tr) {
          const Vec3 rpy = euler_rpy_from_quat(tr->q_ned_from_body) * kRadToDeg;
          fmt::format_to(std::back_inserter(truth_csv->buf()),
                         "{:.3f},{:.9f},{:.9f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f}\n",
                         t_rel(te), tr->position.lat_deg, tr->position.lon_deg, tr->position.h_m,
                         tr->v_ned_mps.x(), tr->v_ned_mps.y(), tr->v_ned_mps.z(), rpy.x(), rpy.y(),
                         rpy.z());
          truth_csv->maybe_flush();
        }
        auto& b = gnss_csv->buf();
        fmt::format_to(std::back_inserter(b), "{:.3f},{},{:.3f},", t_rel(te), wt.week, wt.tow_s);
        if (tr)
          fmt::format_to(std::back_inserter(b), "{:.9f},{:.9f},{:.4f},", tr->position.lat_deg,
                         tr->position.lon_deg, tr->position.h_m);
        else
          fmt::format_to(std::back_inserter(b), ",,,");
        fmt::format_to(std::back_inserter(b), "{},{},{},", static_cast<int>(fix.fix),
                       fix.satellites.size(), fix.num_used);
        if (fix.fix != FixType::kNone && tr) {
          const Vec3 v = fix.v_ned_mps.value_or(Vec3::Zero());
          const Vec3 e = enu_error(fix, *tr);
          fmt::format_to(std::back_inserter(b),
                         "{:.9f},{:.9f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},"
                         "{:.3f},{:.3f},{:.3f},{:.3f},{:.3f}\n",
                         fix.position.lat_deg, fix.position.lon_deg, fix.position.h_m, v.x(), v.y(),
                         v.z(), e.x(), e.y(), e.z(), std::hypot(e.x(), e.y()), fix.dops.pdop,
                         fix.dops.hdop, fix.dops.vdop, fix.sigma_h_m, fix.sigma_v_m);
        } else {
          fmt::format_to(std::back_inserter(b), ",,,,,,,,,,,,,,\n");
        }
        gnss_csv->maybe_flush();
      }
      ++gnss_k;
      // A client changed the navigation rate (u-blox CFG-RATE): the next epoch lies on the new
      // grid, after this one.
      if (device->period_ns() != gnss_period_ns) {
        gnss_period_ns = device->period_ns();
        gnss_k = te.ns / gnss_period_ns + 1;
      }
    }

    // --- IMU output sample: the internal steps up to its measurement time, then out.
    if (imu_due && imu_event(imu_j) <= next) {
      const GpsTime t_meas{imu_j * imu_out_ns};
      // After skipped samples, resume at this sample's own internal steps.
      imu_n = std::max(imu_n, (imu_j - 1) * imu_steps_per_out + 1);
      bool valid = true;
      bool emitted = false;
      for (; imu_n <= imu_j * imu_steps_per_out; ++imu_n) {
        const GpsTime t = imu_step_time(imu_n);
        // A rolling window of the truth at the instants around t (the kinematic derivation
        // differences its neighbours, models/imu_kinematics.hpp).
        if (window_n == imu_n - 1) {
          imu_before = std::move(imu_now);
          imu_now = std::move(imu_after);
        } else {
          imu_before = truth->at(imu_step_time(imu_n - 1));
          imu_now = truth->at(t);
        }
        imu_after = truth->at(imu_step_time(imu_n + 1));
        window_n = imu_n;
        double temperature_c = imu_params.reference_temperature_c;
        if (imu_now && imu_now->f_body_mps2 && imu_now->w_ib_body_radps) {
          last_ideal = IdealImu{*imu_now->f_body_mps2, *imu_now->w_ib_body_radps};
        } else if (imu_now && imu_before && imu_after) {
          last_ideal = ideal_imu_from_kinematics(*imu_before, *imu_now, *imu_after);
        } else {
          valid = false;  // no truth: the last ideal output is held and the sample flagged
        }
        if (imu_now && imu_now->temperature_c) temperature_c = *imu_now->temperature_c;
        if (imu->step(t, last_ideal, temperature_c, sample)) emitted = true;
      }
      if (emitted) {
        // One per output period, so that a sample skipped after a stall leaves a gap in the
        // sequence, as a frame lost on the bus does (protocols/can_frames.hpp; wraps).
        const auto sequence = static_cast<std::uint16_t>(imu_j - imu_j0);
        ++sum.imu_samples;
        if (!valid) {
          ++sum.imu_flagged;
          interval_truth_lost = true;
        }
        if (can_out) {
          can::ImuSample cs;
          cs.gps_time_ns = t_meas.ns;
          cs.sequence = sequence;
          for (int i = 0; i < 3; ++i) {
            cs.w_body_radps[static_cast<std::size_t>(i)] = sample.w_body_radps[i];
            cs.f_body_mps2[static_cast<std::size_t>(i)] = sample.f_body_mps2[i];
          }
          cs.latency_s = imu_params.latency_s;
          cs.truth_lost = !valid;
          cs.gyro_saturated = sample.gyro_saturated;
          cs.accel_saturated = sample.accel_saturated;
          // Live frames are stamped when they leave; offline ones at their scheduled time.
          can_out->send(cs, offline ? unix_ns_from_gps(sample.t) : realtime_ns());
        }
        fmt::memory_buffer* b = nullptr;
        if (imu_csv) b = &imu_csv->buf();
        if (imu_log) {
          imu_line.clear();
          b = &imu_line;
        }
        if (b) {
          fmt::format_to(std::back_inserter(*b),
                         FMT_COMPILE("{:.6f},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.4g},{},{},{}\n"),
                         t_rel(sample.t), sample.f_body_mps2.x(), sample.f_body_mps2.y(),
                         sample.f_body_mps2.z(), sample.w_body_radps.x(), sample.w_body_radps.y(),
                         sample.w_body_radps.z(), sample.temperature_c, valid ? 1 : 0, t_meas.ns,
                         sequence);
          if (imu_csv) imu_csv->maybe_flush();
          if (imu_log) imu_log->write(std::string_view(imu_line.data(), imu_line.size()));
        }
      }
      ++imu_j;
    }

    if (next_service <= next) next_service = GpsTime{next.ns + service_ns};

    if (next_status <= next) {
      if (!offline) print_status(next_status);
      next_status = GpsTime{next_status.ns + status_ns};
    }
  }

  // --- Wrap up.
  if (truth_csv) truth_csv->close();
  if (gnss_csv) gnss_csv->close();
  if (imu_csv) imu_csv->close();
  if (can_out) {
    const CanOutputTotals t = can_out->totals();
    sum.can_frames_written = t.frames_written;
    sum.can_frames_dropped = t.frames_dropped;
    sum.can_frames_held = t.frames_held;
    sum.can_frames_failed = t.frames_failed;
    sum.can_bus_errors = t.bus_errors;
  }
  for (const auto& p : ports) {
    sum.client_bytes_read += p->counters().bytes_read;
    sum.stale_flushes += p->counters().stale_flushes;
    sum.stale_bytes_flushed += p->counters().stale_bytes_flushed;
  }
  if (const TruthCounters* tc = truth->counters()) sum.truth = *tc;
  sum.wall_s = static_cast<double>(monotonic_ns() - wall0) * 1e-9;
  sum.scenario_s = receiver ? static_cast<double>(sum.gnss_epochs) / prof.rate_hz
                            : static_cast<double>(sum.imu_samples) / std::max(imu_params.output_rate_hz, 1.0);
  return sum;
}

}  // namespace navemu
