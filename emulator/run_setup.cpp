#include "emulator/run_setup.hpp"

#include <fmt/format.h>
#include <fmt/ostream.h>
#include <fmt/ranges.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <ostream>
#include <set>
#include <stdexcept>
#include <string_view>

#include "emulator/commands.hpp"
#include "emulator/control_channel.hpp"
#include "emulator/geoid_loader.hpp"
#include "emulator/gnss_scene.hpp"
#include "emulator/imu_channel.hpp"
#include "emulator/imu_profile.hpp"
#include "models/constellation.hpp"
#include "core/errors.hpp"
#include "emulator/rinex_files.hpp"
#include "transports/byte_port.hpp"

namespace navemu {

namespace {

// The streams an offline run may write: a folder used before starts without them, so every
// file in it belongs to this run (the byte streams are append-only logs, and a u-blox run's
// ubx.bin must not stay beside a later NMEA run's nmea.log).
constexpr const char* kOfflineFiles[] = {"nmea.log", "ubx.bin", "can.log", "truth.csv", "gnss.csv", "imu.csv"};

void prepare_output_folder(const std::filesystem::path& dir) {
  std::error_code ec;
  if (std::filesystem::exists(dir, ec) && !std::filesystem::is_directory(dir, ec))
    throw InputError(dir.string(), 0, "--out", "exists and is not a folder");
  std::filesystem::create_directories(dir, ec);
  if (ec) throw InputError(dir.string(), 0, "--out", fmt::format("cannot create the output folder ({})", ec.message()));
  if (::access(dir.c_str(), W_OK) != 0)
    throw InputError(dir.string(), 0, "--out",
                     fmt::format("cannot write into the output folder ({})", std::strerror(errno)));
  for (const char* name : kOfflineFiles) std::filesystem::remove(dir / name, ec);
}

std::unique_ptr<transport::BytePort> open_output(const OutputSpec& o, const GnssProfile& profile) {
  if (o.type == "pty") return transport::open_pty({o.link, o.max_backlog_bytes, o.gpsd_socket});
  if (o.type == "serial") return transport::open_serial({o.device, o.baud ? o.baud : profile.baud});
  if (o.type == "tcp") return transport::open_tcp_server({o.address, o.port, 8});
  if (o.type == "udp") return transport::open_udp_sender({o.address, o.port});
  return transport::open_log_file(o.path);
}

ReceiverPort receiver_port(const std::string& name) {
  constexpr std::pair<const char*, ReceiverPort> kPorts[] = {{"i2c", ReceiverPort::kI2c},
                                                             {"uart1", ReceiverPort::kUart1},
                                                             {"uart2", ReceiverPort::kUart2},
                                                             {"usb", ReceiverPort::kUsb},
                                                             {"spi", ReceiverPort::kSpi}};
  for (const auto& [n, p] : kPorts)
    if (name == n) return p;
  return ReceiverPort::kUart1;
}

// The receiver's models from the profile: its class, mask, channels and antenna, the geoid, and
// the scene it sees.
ReceiverParams receiver_params(const RunConfig& cfg, std::ostream& log) {
  const GnssProfile& prof = cfg.gnss;
  ReceiverParams rp;
  rp.measurement.mode = cfg.gnss_mode;
  apply_receiver_class(rp.measurement, prof.receiver_class);
  rp.measurement.elevation_mask_deg = prof.elevation_mask_deg;
  rp.measurement.systems = prof.systems;
  rp.measurement.bands = prof.bands;
  rp.measurement.clock = prof.clock;
  rp.measurement.carrier_smoothing_s = prof.carrier_smoothing_s;
  AntennaPattern antenna = patch_antenna_pattern();
  if (!prof.antenna_gain_db_by_el_deg.empty()) {
    rp.measurement.cn0.gain_db_by_el_deg = prof.antenna_gain_db_by_el_deg;
    antenna.rhcp_gain_db_by_el_deg = prof.antenna_gain_db_by_el_deg;
  }
  antenna.lhcp_rejection_db = prof.antenna_lhcp_rejection_db;
  rp.measurement.seed = cfg.seed;
  rp.measurement.events = cfg.gnss_events;
  rp.max_channels = prof.max_channels;
  rp.ideal_sigma_m = cfg.gnss_ideal_sigma_m;
  // The geoid of the MSL heights (GGA, NAV-PVT, NAV-POSLLH): read once per process.
  const LoadedGeoid& geoid = egm96_geoid();
  if (geoid.grid) rp.geoid = &*geoid.grid;
  if (!cfg.gnss_scene.obj.empty())
    rp.measurement.environment =
        make_scene_environment(cfg.gnss_scene, cfg.truth.position, rp.measurement.tracking, antenna, log);
  return rp;
}

ImuPlan imu_plan(const RunConfig& cfg, const EngineOptions& opt) {
  const ImuProfile p = load_imu_profile(cfg.imu_profile);
  ImuPlan plan{imu_params_for_run(p, opt.duration_s.value_or(3600.0), 0.0),
               ideal_imu_static(cfg.truth.position, Quat::Identity())};
  try {
    ImuPipeline(plan.params, cfg.seed, GpsTime{0}, plan.initial);  // checks the rates
  } catch (const std::invalid_argument&) {
    throw InputError(p.file.string(), 0, "internal_rate_hz", "must be a whole multiple of output_rate_hz");
  }
  return plan;
}

const char* receiver_mode_name(ReceiverMode m) {
  switch (m) {
    case ReceiverMode::kStandalone: return "standalone";
    case ReceiverMode::kDualFrequency: return "dual-frequency";
    case ReceiverMode::kDgps: return "DGPS";
    case ReceiverMode::kRtkFixed: return "RTK";
  }
  return "?";
}

void print_gnss_outputs(const RunConfig& cfg, const GnssPorts& io, bool offline, std::ostream& log) {
  for (const auto& p : io.ports)
    fmt::print(log, "navemu: GNSS {} on {}\n", cfg.gnss.ubx ? "UBX/NMEA" : "NMEA", p->describe());
  if (offline) return;
  if (io.ports.empty()) fmt::print(log, "navemu: GNSS has no output (gnss.outputs)\n");
  for (const OutputSpec& o : cfg.gnss_outputs)
    if (o.type == "tcp" && !transport::is_loopback_address(o.address))
      fmt::print(log,
                 "navemu: warning: the GNSS tcp output listens on {}, not loopback: any host "
                 "that reaches it receives the receiver's output and can configure it\n",
                 o.address);
  if (io.capture_out)
    fmt::print(log, "navemu: GNSS capture: sent bytes to {0}, received bytes to {0}.in\n", cfg.gnss_capture);
}

}  // namespace

RunPlan resolve_run(const RunConfig& cfg, const EngineOptions& opt, std::ostream& log) {
  RunPlan plan;
  if (cfg.gnss_enabled) {
    plan.gnss.emplace();
    if (!cfg.nav_file.empty()) plan.gnss->nav_file = read_rinex_nav(cfg.nav_file);
    plan.gnss->receiver = receiver_params(cfg, log);
  }
  if (cfg.imu_enabled) plan.imu = imu_plan(cfg, opt);
  return plan;
}

RunOutputs open_outputs(const RunConfig& cfg, const RunPlan& plan, const EngineOptions& opt,
                        std::ostream& log) {
  // (`log`: the fallbacks of socketcan outputs say where their frames go instead.)
  const bool offline = !opt.realtime;
  RunOutputs out;
  if (offline) prepare_output_folder(opt.out_dir);
  if (plan.gnss) {
    if (offline) {
      // The receiver's byte stream as on the wire: NMEA, or UBX mixed with NMEA.
      out.gnss.ports.push_back(transport::open_log_file((opt.out_dir / (cfg.gnss.ubx ? "ubx.bin" : "nmea.log")).string()));
      out.gnss.receiver_ports.push_back(ReceiverPort::kUart1);
      out.epoch_recorders.push_back(make_truth_csv(opt.out_dir));
      out.epoch_recorders.push_back(make_gnss_csv(opt.out_dir));
    } else {
      for (const OutputSpec& o : cfg.gnss_outputs) {
        out.gnss.ports.push_back(open_output(o, cfg.gnss));
        out.gnss.receiver_ports.push_back(receiver_port(o.receiver_port));
      }
      if (!cfg.gnss_capture.empty()) {
        out.gnss.capture_out = transport::open_log_file(cfg.gnss_capture);
        out.gnss.capture_in = transport::open_log_file(cfg.gnss_capture + ".in");
      }
    }
  }
  if (cfg.control && !offline)
    out.control =
        std::make_unique<ControlPort>(transport::open_tcp_server({cfg.control->address, cfg.control->port, 4, 65536}));
  if (plan.imu) {
    // The IMU's CAN frames: offline into can.log (candump -L), live on the configured ports.
    const std::vector<CanOutputSpec> specs =
        offline ? offline_can_outputs(cfg.imu_outputs, (opt.out_dir / "can.log").string()) : cfg.imu_outputs;
    if (!specs.empty()) out.can = std::make_unique<ImuCanOutputs>(specs, cfg.imu_can, log);
    if (offline)
      out.sample_recorders.push_back(make_imu_csv(opt.out_dir));
    else if (!cfg.imu_log.empty())
      out.sample_recorders.push_back(make_imu_log(transport::open_log_file(cfg.imu_log)));
  }
  return out;
}

void print_outputs(const RunConfig& cfg, const RunPlan& plan, const RunOutputs& out, const EngineOptions& opt,
                   std::ostream& log) {
  const bool offline = !opt.realtime;
  if (plan.gnss) print_gnss_outputs(cfg, out.gnss, offline, log);
  if (plan.imu) {
    fmt::print(log, "navemu: IMU {} ({} Hz){}\n", cfg.imu_profile, plan.imu->params.output_rate_hz,
               !offline && !cfg.imu_log.empty() ? " samples logged to " + cfg.imu_log : "");
    if (out.can)
      for (const std::string& line : out.can->describe()) fmt::print(log, "navemu: IMU CAN frames on {}\n", line);
    else if (!offline)
      fmt::print(log, "navemu: IMU has no output (imu.outputs; set imu.log to record samples)\n");
  }
  if (out.control) {
    fmt::print(log, "navemu: control on {} (JSON lines: navemu ctl --port {} '{{\"cmd\": \"event\", ...}}')\n",
               out.control->describe(), transport::tcp_server_port(out.control->port()));
    if (!transport::is_loopback_address(cfg.control->address))
      fmt::print(log, "navemu: warning: the control port listens on {}, not loopback: any host that reaches it "
                      "can inject faults\n", cfg.control->address);
  } else if (cfg.control && offline) {
    fmt::print(log, "navemu: note: control: is for navemu run; simulate takes the events: of the configuration\n");
  }
  log.flush();
}

NavData scenario_nav(const RunPlan& plan, GpsTime start, const EngineOptions& opt, std::ostream& log) {
  if (!plan.gnss) return {};
  NavData nav = plan.gnss->nav_file ? *plan.gnss->nav_file
                                    : nominal_constellation(start, plan.gnss->receiver.measurement.systems);
  check_scenario_nav(nav, start, opt.duration_s, log);
  return nav;
}

std::vector<std::unique_ptr<SensorChannel>> make_channels(const RunConfig& cfg, const RunPlan& plan,
                                                          RunOutputs& outputs, NavData nav,
                                                          const EngineOptions& opt, ImpairedTruth* truth,
                                                          std::ostream& log) {
  std::vector<std::unique_ptr<SensorChannel>> channels;
  ControlChannel::Targets targets{nullptr, nullptr, truth};
  if (plan.gnss) {
    // What the data holds, per system (a mixed file is read whole), and what the receiver uses.
    std::string held;
    const auto count = [&](std::string_view system, const auto& records) {
      std::set<SatId> sats;
      for (const auto& e : records) sats.insert(e.sat);
      if (!sats.empty()) held += fmt::format("{}{} {}", held.empty() ? "" : ", ", system, sats.size());
    };
    count("GPS", nav.gps);
    count("Galileo", nav.galileo);
    count("BeiDou", nav.beidou);
    count("QZSS", nav.qzss);
    count("GLONASS", nav.glonass);
    const std::string nav_name = cfg.nav_file.empty() ? "built-in constellation" : cfg.nav_file;
    const int skipped = nav.skipped_records;
    auto gnss = std::make_unique<GnssChannel>(std::make_unique<NavData>(std::move(nav)), plan.gnss->receiver, cfg.gnss,
                                              cfg.gnss_mode, std::move(outputs.gnss),
                                              std::move(outputs.epoch_recorders));
    std::vector<std::string_view> tracked;
    for (const GnssSystemInfo& i : kGnssSystems)
      if (gnss->tracked_systems() & system_bit(i.system)) tracked.emplace_back(i.name);
    fmt::print(log, "navemu: GNSS {} ({} Hz, {} mode, tracking {}), navigation data {}: {} satellites{}\n",
               cfg.gnss.name, cfg.gnss.rate_hz, receiver_mode_name(cfg.gnss_mode), fmt::join(tracked, ", "), nav_name,
               held.empty() ? "no" : held,
               skipped > 0 ? fmt::format("; {} records of SBAS or NavIC not read", skipped) : "");
    fmt::print(log, "navemu: {}\n", egm96_geoid().description);
    targets.gnss = gnss.get();
    channels.push_back(std::move(gnss));
  }
  if (plan.imu) {
    auto imu = std::make_unique<ImuChannel>(plan.imu->params, cfg.seed, plan.imu->initial, std::move(outputs.can),
                                            std::move(outputs.sample_recorders), !opt.realtime);
    for (const ImuFault& f : cfg.imu_faults)
      if (const std::optional<std::string> why = unfit_fault(f, plan.imu->params))
        throw InputError(cfg.file.string(), 0, "band_hz", *why);
    imu->set_faults(cfg.imu_faults);
    targets.imu = imu.get();
    channels.push_back(std::move(imu));
  }
  if (outputs.control) channels.push_back(std::make_unique<ControlChannel>(std::move(outputs.control), targets));
  log.flush();
  return channels;
}

}  // namespace navemu
