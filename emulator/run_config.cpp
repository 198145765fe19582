#include "emulator/run_config.hpp"

#include <fmt/format.h>
#include <sched.h>

#include <algorithm>
#include <array>
#include <string_view>

#include "emulator/imu_profile.hpp"
#include "emulator/ubx_outputs.hpp"
#include "emulator/yaml_reader.hpp"
#include "core/errors.hpp"
#include "protocols/nmea.hpp"

namespace navemu {

namespace {

// A name from a fixed list, or an error listing the choices.
template <typename T>
std::optional<T> choice(YamlMap& m, const std::string& key, const std::map<std::string, T>& choices) {
  const std::optional<std::string> v = m.text(key);
  if (!v) return std::nullopt;
  const auto it = choices.find(*v);
  if (it == choices.end()) {
    std::string names;
    for (const auto& c : choices) names += (names.empty() ? "" : ", ") + c.first;
    m.fail(key, fmt::format("'{}' is not one of {}", *v, names));
  }
  return it->second;
}

// A path relative to the configuration file's folder.
std::string resolve(const std::filesystem::path& config, const std::string& p) {
  if (p.empty() || p == "-" || std::filesystem::path(p).is_absolute()) return p;
  return (config.parent_path() / p).lexically_normal().string();
}

Geodetic position(YamlMap m, const Geodetic& fallback) {
  Geodetic g = fallback;
  if (auto v = m.number("lat_deg")) g.lat_deg = *v;
  if (auto v = m.number("lon_deg")) g.lon_deg = *v;
  if (auto v = m.number("h_m")) g.h_m = *v;
  if (std::abs(g.lat_deg) > 90.0) m.fail("lat_deg", fmt::format("{} outside [-90, 90]", g.lat_deg));
  if (g.lon_deg < -180.0 || g.lon_deg > 360.0)
    m.fail("lon_deg", fmt::format("{} outside [-180, 360]", g.lon_deg));
  if (g.h_m < -1000.0 || g.h_m > 100000.0)
    m.fail("h_m", fmt::format("{} outside [-1000, 100000] m", g.h_m));
  m.reject_unknown_keys();
  return g;
}

OutputSpec output(YamlMap m) {
  OutputSpec o;
  o.type = m.text("type").value_or("");
  const char* receiver_port_key = o.type == "tcp" || o.type == "udp" ? "receiver_port" : "port";
  o.receiver_port = m.text(receiver_port_key).value_or(o.receiver_port);
  static const std::vector<std::string> kPorts = {"i2c", "uart1", "uart2", "usb", "spi"};
  if (std::find(kPorts.begin(), kPorts.end(), o.receiver_port) == kPorts.end())
    m.fail(receiver_port_key, fmt::format("'{}' is not one of i2c, uart1, uart2, usb, spi (the receiver's port "
                                          "this output stands for)",
                                          o.receiver_port));
  static const std::vector<std::string> kTypes = {"pty", "serial", "tcp", "udp", "file"};
  if (std::find(kTypes.begin(), kTypes.end(), o.type) == kTypes.end())
    m.fail("type", fmt::format("'{}' is not one of pty, serial, tcp, udp, file", o.type));
  if (o.type == "pty") {
    o.link = resolve(m.file(), m.text("link").value_or(""));
    if (auto v = m.integer("max_backlog_bytes", 0, 1 << 20)) o.max_backlog_bytes = static_cast<std::size_t>(*v);
    o.gpsd_socket = resolve(m.file(), m.text("gpsd_socket").value_or(""));
  } else if (o.type == "serial") {
    o.device = m.text("device").value_or("");
    if (o.device.empty()) m.fail("device", "required for a serial output (e.g. /dev/ttyUSB0)");
    o.baud = static_cast<int>(m.integer("baud", 300, 4'000'000).value_or(0));
  } else if (o.type == "tcp" || o.type == "udp") {
    o.address = m.text("address").value_or("127.0.0.1");
    o.port = static_cast<int>(m.integer("port", 0, 65535).value_or(0));
    if (o.type == "udp" && o.port == 0) m.fail("port", "required for a udp output");
  } else {
    o.path = resolve(m.file(), m.text("path").value_or(""));
    if (o.path.empty()) m.fail("path", "required for a file output");
  }
  m.reject_unknown_keys();
  return o;
}

CanOutputSpec can_output(YamlMap m, bool is_fallback) {
  CanOutputSpec o;
  o.type = m.text("type").value_or("");
  if (o.type != "socketcan" && o.type != "slcan" && o.type != "candump")
    m.fail("type", fmt::format("'{}' is not one of socketcan, slcan, candump", o.type));
  if (o.type == "socketcan") {
    o.interface = m.text("interface").value_or("");
    if (o.interface.empty()) m.fail("interface", "required for a socketcan output (e.g. vcan0)");
    if (o.interface.size() >= 16) m.fail("interface", "longer than 15 characters (IFNAMSIZ)");
  } else if (o.type == "slcan") {
    o.link = resolve(m.file(), m.text("link").value_or(""));
    o.device = m.text("device").value_or("");
    if (!o.link.empty() && !o.device.empty())
      m.fail("device", "either link (a pty) or device (a serial port), not both");
    o.baud = static_cast<int>(m.integer("baud", 300, 4'000'000).value_or(o.baud));
    o.auto_open = m.boolean("auto_open").value_or(false);
  } else {
    o.path = resolve(m.file(), m.text("path").value_or(""));
    if (o.path.empty()) m.fail("path", "required for a candump output");
    o.interface = m.text("interface").value_or("can0");
  }
  if (!is_fallback) {
    if (auto names = m.text_list("layouts")) {
      o.layouts.clear();
      for (const std::string& n : *names) {
        if (n == "j1939") o.layouts.push_back(CanLayout::kJ1939);
        else if (n == "highres") o.layouts.push_back(CanLayout::kHighRes);
        else if (n == "highres-fd") o.layouts.push_back(CanLayout::kHighResFd);
        else m.fail("layouts", fmt::format("'{}' is not one of j1939, highres, highres-fd", n));
      }
      if (o.layouts.empty()) m.fail("layouts", "at least one layout");
    }
    if (m.has("fallback")) {
      if (o.type != "socketcan") m.fail("fallback", "only a socketcan output has a fallback");
      CanOutputSpec f = can_output(m.map("fallback"), true);
      if (f.type == "socketcan") m.fail("fallback", "the fallback must be slcan or candump");
      f.layouts = o.layouts;
      o.fallback.push_back(f);
    }
  }
  m.reject_unknown_keys();
  return o;
}

SceneSpec scene_spec(YamlMap m) {
  SceneSpec s;
  s.obj = resolve(m.file(), m.text("obj").value_or(""));
  s.materials = resolve(m.file(), m.text("materials").value_or(""));
  if (s.obj.empty() && !s.materials.empty()) m.fail("obj", "required with a material table (a Wavefront OBJ file)");
  if (s.materials.empty()) s.materials = (config_dir() / "scenes" / "materials.yaml").string();
  if (m.has("origin")) s.origin = position(m.map("origin"), Geodetic{});
  if (auto v = m.number_list("offset_enu_m")) {
    if (v->size() != 3) m.fail("offset_enu_m", "three numbers: [east, north, up]");
    s.offset_enu_m = Vec3((*v)[0], (*v)[1], (*v)[2]);
  }
  s.max_order = static_cast<int>(m.integer("max_order", 0, 2).value_or(s.max_order));
  s.max_range_m = m.positive("max_range_m").value_or(s.max_range_m);
  s.response = m.text("response").value_or(s.response);
  if (s.response != "discriminator" && s.response != "paper")
    m.fail("response", fmt::format("'{}' is not one of discriminator, paper", s.response));
  s.cutoff_m = m.positive("cutoff_m").value_or(s.cutoff_m);
  if (auto v = m.positive("chip_spacing")) {
    if (*v > 2.0) m.fail("chip_spacing", fmt::format("{} chips: at most 2", *v));
    s.chip_spacing = *v;
  }
  m.reject_unknown_keys();
  return s;
}

CanSettings can_settings(YamlMap m) {
  CanSettings c;
  YamlMap j = m.map("j1939");
  c.priority = static_cast<std::uint8_t>(j.integer("priority", 0, 7).value_or(c.priority));
  // 254 is the J1939 null address and 255 the global address (SAE J1939-81): not a source.
  c.source_address =
      static_cast<std::uint8_t>(j.integer("source_address", 0, 253).value_or(c.source_address));
  j.reject_unknown_keys();
  YamlMap h = m.map("highres");
  c.extended = h.boolean("extended").value_or(false);
  // The FD frame sits at base_id + 0x10: the whole block must fit the identifier space.
  const std::int64_t max_base = (c.extended ? 0x1FFFFFFF : 0x7FF) - 0x10;
  c.base_id = static_cast<std::uint32_t>(h.integer("base_id", 0, max_base).value_or(c.base_id));
  h.reject_unknown_keys();
  m.reject_unknown_keys();
  return c;
}

TruthSpec truth(YamlMap m) {
  TruthSpec t;
  t.kind = choice<TruthSourceKind>(m, "source",
                                   {{"stationary", TruthSourceKind::kStationary},
                                    {"circle", TruthSourceKind::kCircle},
                                    {"line", TruthSourceKind::kLine},
                                    {"waypoints", TruthSourceKind::kWaypoints},
                                    {"csv", TruthSourceKind::kCsv},
                                    {"udp", TruthSourceKind::kUdp}})
               .value_or(t.kind);
  t.position = position(m.map("position"), t.position);
  t.yaw_deg = m.number("yaw_deg").value_or(0.0);
  t.timeout_s = m.positive("timeout_s").value_or(t.timeout_s);
  t.max_jump_s = m.positive("max_jump_s").value_or(t.max_jump_s);
  t.resync_samples = static_cast<int>(m.integer("resync_samples", 2, 1000).value_or(t.resync_samples));
  t.first_wait_s = m.positive("first_wait_s", true).value_or(t.first_wait_s);

  YamlMap c = m.map("circle");
  t.circle.center = t.position;
  if (auto v = c.positive("radius_m")) t.circle.radius_m = *v;
  if (auto v = c.positive("speed_mps")) t.circle.speed_mps = *v;
  if (auto v = c.integer("loops", 0, 1'000'000)) t.circle.loops = static_cast<int>(*v);
  if (auto v = c.boolean("clockwise")) t.circle.clockwise = *v;
  if (auto v = c.positive("accel_mps2")) t.circle.accel_mps2 = *v;
  c.reject_unknown_keys();

  YamlMap l = m.map("line");
  t.line.start = t.position;
  if (auto v = l.number("heading_deg")) t.line.heading_deg = *v;
  if (auto v = l.positive("length_m")) t.line.length_m = *v;
  if (auto v = l.positive("speed_mps")) t.line.speed_mps = *v;
  if (auto v = l.integer("passes", 0, 1'000'000)) t.line.passes = static_cast<int>(*v);
  if (auto v = l.positive("accel_mps2")) t.line.accel_mps2 = *v;
  if (auto v = l.positive("turn_rate_dps")) t.line.turn_rate_dps = *v;
  l.reject_unknown_keys();

  YamlMap w = m.map("waypoints");
  if (auto v = w.positive("speed_mps")) t.waypoints.speed_mps = *v;
  if (auto v = w.positive("accel_mps2")) t.waypoints.accel_mps2 = *v;
  if (auto v = w.positive("turn_rate_dps")) t.waypoints.turn_rate_dps = *v;
  for (YamlMap& p : w.map_list("points")) {
    t.waypoints.stop_s.push_back(p.positive("stop_s", true).value_or(0.0));
    t.waypoints.waypoints.push_back(position(p, t.position));
  }
  if (t.kind == TruthSourceKind::kWaypoints && t.waypoints.waypoints.size() < 2)
    w.fail("points", "at least two waypoints are needed");
  w.reject_unknown_keys();

  YamlMap csv = m.map("csv");
  t.csv_path = resolve(m.file(), csv.text("path").value_or(""));
  if (t.kind == TruthSourceKind::kCsv && t.csv_path.empty())
    csv.fail("path", "required for source csv (a truth CSV file, or - for standard input)");
  csv.reject_unknown_keys();

  YamlMap udp = m.map("udp");
  t.udp_address = udp.text("address").value_or(t.udp_address);
  t.udp_port = static_cast<int>(udp.integer("port", 0, 65535).value_or(t.udp_port));
  udp.reject_unknown_keys();
  m.reject_unknown_keys();
  return t;
}

}  // namespace

const char* can_layout_name(CanLayout layout) {
  switch (layout) {
    case CanLayout::kJ1939: return "j1939";
    case CanLayout::kHighRes: return "highres";
    case CanLayout::kHighResFd: return "highres-fd";
  }
  return "?";
}

const std::vector<std::string>& known_nmea_sentences() {
  static const std::vector<std::string> k = {"RMC", "GGA", "GSA", "GSV", "VTG",
                                             "GLL", "GST", "ZDA", "PGRME"};
  return k;
}

const std::vector<std::string>& known_ubx_outputs() {
  static const std::vector<std::string> k = [] {
    std::vector<std::string> names;
    for (const UbxOutput& o : ubx_outputs())
      if (const ubx::MessageInfo* m = ubx::find_message(o.id)) names.emplace_back(m->name);
    return names;
  }();
  return k;
}

std::vector<std::string> available_gnss_profiles() {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(config_dir() / "gnss", ec))
    if (e.is_regular_file() && e.path().extension() == ".yaml")
      names.push_back(e.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

GnssProfile load_gnss_profile(const std::string& name_or_path) {
  std::filesystem::path file = name_or_path;
  if (file.extension() != ".yaml") file = config_dir() / "gnss" / (name_or_path + ".yaml");
  if (!std::filesystem::is_regular_file(file)) {
    std::string names;
    for (const std::string& n : available_gnss_profiles()) names += (names.empty() ? "" : ", ") + n;
    throw InputError(file.string(), 0, "",
                     fmt::format("no such GNSS profile (available: {})", names));
  }
  YamlMap m = load_yaml_file(file);
  GnssProfile p;
  p.file = file;
  p.name = file.stem().string();
  p.description = m.text("description").value_or("");
  (void)m.text("name");
  p.rate_hz = m.positive("rate_hz").value_or(p.rate_hz);
  if (p.rate_hz > 50.0) m.fail("rate_hz", fmt::format("{} Hz above 50 Hz", p.rate_hz));
  const double period_ns = 1e9 / p.rate_hz;
  if (std::abs(period_ns - std::round(period_ns)) > 1e-6)
    m.fail("rate_hz", "the epoch period must be a whole number of nanoseconds");
  p.output_latency_s = m.positive("output_latency_s", true).value_or(0.0);
  if (p.output_latency_s >= 1.0 / p.rate_hz)
    m.fail("output_latency_s", "must be shorter than one epoch");
  p.baud = static_cast<int>(m.integer("baud", 300, 4'000'000).value_or(p.baud));
  if (auto names = m.text_list("systems")) {
    p.systems = 0;
    for (const std::string& n : *names) {
      const auto it = std::find_if(kGnssSystems.begin(), kGnssSystems.end(), [&](const GnssSystemInfo& i) {
        return n == i.name && (i.system == GnssSystem::kGps || i.system == GnssSystem::kGlonass ||
                               i.system == GnssSystem::kGalileo || i.system == GnssSystem::kBeidou ||
                               i.system == GnssSystem::kQzss);
      });
      if (it == kGnssSystems.end())
        m.fail("systems", fmt::format("unknown system '{}': GPS, GLONASS, Galileo, BeiDou or QZSS", n));
      p.systems |= system_bit(it->system);
    }
    if (p.systems == 0) m.fail("systems", "at least one system");
  }
  if (auto names = m.text_list("bands")) {
    constexpr std::pair<std::string_view, Band> kBands[] = {{"L1", Band::kL1}, {"L2", Band::kL2}, {"L5", Band::kL5}};
    p.bands = 0;
    for (const std::string& n : *names) {
      const auto it = std::find_if(std::begin(kBands), std::end(kBands), [&](const auto& b) { return n == b.first; });
      if (it == std::end(kBands)) m.fail("bands", fmt::format("unknown band '{}': L1, L2 or L5", n));
      p.bands |= band_bit(it->second);
    }
    if (!(p.bands & band_bit(Band::kL1))) m.fail("bands", "L1 is needed: the receiver acquires on it");
  }
  p.talker = m.text("talker").value_or(std::string(nmea::main_talker(p.systems)));
  if (p.talker.size() != 2) m.fail("talker", "two letters, e.g. GP or GN");
  p.style = m.text("style").value_or(p.style);
  if (p.style != "ublox" && p.style != "garmin") m.fail("style", "ublox or garmin");
  if (auto v = m.integer("time_decimals", 0, 3)) p.time_decimals = static_cast<int>(*v);
  if (!p.time_decimals && p.rate_hz > 1.0 && p.style == "garmin")
    m.fail("time_decimals", "needed above 1 Hz: the Garmin style sends whole seconds");
  p.receiver_class = choice<ReceiverClass>(m, "receiver_class",
                                           {{"consumer", ReceiverClass::kConsumer},
                                            {"geodetic", ReceiverClass::kGeodetic}})
                         .value_or(p.receiver_class);
  p.elevation_mask_deg = m.positive("elevation_mask_deg", true).value_or(p.elevation_mask_deg);
  p.max_channels = static_cast<int>(m.integer("max_channels", 4, 64).value_or(p.max_channels));
  YamlMap ant = m.map("antenna");
  if (auto g = ant.number_pairs("gain_db_by_el_deg")) {
    if (g->empty()) ant.fail("gain_db_by_el_deg", "at least one [elevation_deg, gain_db] pair");
    for (std::size_t i = 0; i < g->size(); ++i) {
      const double el = (*g)[i].first;
      if (el < -90.0 || el > 90.0 || (i > 0 && el <= (*g)[i - 1].first))
        ant.fail("gain_db_by_el_deg", "elevations must rise from -90 to 90 deg");
    }
    p.antenna_gain_db_by_el_deg = *g;
  }
  p.antenna_lhcp_rejection_db = ant.positive("lhcp_rejection_db", true).value_or(p.antenna_lhcp_rejection_db);
  ant.reject_unknown_keys();
  YamlMap clk = m.map("clock");
  if (auto b = clk.positive("initial_bias_max_ms", true)) {
    if (*b > 1000.0) clk.fail("initial_bias_max_ms", "at most 1000 (one second)");
    p.clock.initial_bias_max_s = *b * 1e-3;
  }
  if (auto f = clk.positive("frequency_offset_sigma_ppb", true)) {
    if (*f > 1e5) clk.fail("frequency_offset_sigma_ppb", "at most 100000 (100 ppm)");
    p.clock.frequency_offset_sigma_sps = *f * 1e-9;
  }
  clk.reject_unknown_keys();
  p.carrier_smoothing_s = m.positive("carrier_smoothing_s", true).value_or(0.0);
  if (p.carrier_smoothing_s > 3600.0) m.fail("carrier_smoothing_s", "at most 3600 (one hour)");

  YamlMap s = m.map("sentences");
  if (!m.has("sentences")) m.fail("sentences", "required: sentence names with divisors, e.g. {RMC: 1, GSV: 5}");
  for (const std::string& name : known_nmea_sentences())
    if (auto d = s.integer(name, 0, 1000); d && *d > 0) p.sentences.emplace_back(name, static_cast<int>(*d));
  s.reject_unknown_keys();

  if (m.has("ubx")) {
    YamlMap u = m.map("ubx");
    UbxSettings x;
    x.protver = u.text("protver").value_or("");
    if (x.protver.size() != 5 || x.protver[2] != '.')
      u.fail("protver", "the protocol version as MON-VER gives it, e.g. \"18.00\"");
    x.sw_version = u.text("sw_version").value_or("");
    x.hw_version = u.text("hw_version").value_or("");
    x.extensions = u.text_list("extensions").value_or(std::vector<std::string>{});
    if (x.sw_version.size() > 29) u.fail("sw_version", "at most 29 characters (MON-VER field)");
    if (x.hw_version.size() > 9) u.fail("hw_version", "at most 9 characters (MON-VER field)");
    for (const std::string& e : x.extensions)
      if (e.size() > 29) u.fail("extensions", fmt::format("'{}' longer than 29 characters", e));
    YamlMap msgs = u.map("messages");
    for (const std::string& name : known_ubx_outputs())
      if (auto d = msgs.integer(name, 0, 255); d && *d > 0) x.messages.emplace_back(name, static_cast<int>(*d));
    msgs.reject_unknown_keys();
    x.nmea_out = u.boolean("nmea_out").value_or(true);
    u.reject_unknown_keys();
    p.ubx = x;
  }
  m.reject_unknown_keys();
  return p;
}

std::filesystem::path default_run_config() { return config_dir() / "default.yaml"; }

namespace {

// A required number of an event (`what` says what it is, for the error).
double required(YamlMap& m, const std::string& key, const char* what) {
  const std::optional<double> v = m.number(key);
  if (!v) m.fail(key, fmt::format("missing: {}", what));
  return *v;
}

}  // namespace

namespace {

// An `events:` entry of type imu (models/imu_model.hpp ImuFault), its window already read.
ImuFault imu_fault(YamlMap& m, const EventWindow& w) {
  ImuFault f{w};
  const auto kind = choice<ImuFaultKind>(m, "fault", {{"bias", ImuFaultKind::kBias},
                                                      {"scale", ImuFaultKind::kScale},
                                                      {"noise", ImuFaultKind::kNoise},
                                                      {"stuck", ImuFaultKind::kStuck},
                                                      {"saturation", ImuFaultKind::kSaturation},
                                                      {"vibration", ImuFaultKind::kVibration},
                                                      {"temperature", ImuFaultKind::kTemperature},
                                                      {"drop", ImuFaultKind::kDrop},
                                                      {"duplicate", ImuFaultKind::kDuplicate},
                                                      {"bus_off", ImuFaultKind::kBusOff},
                                                      {"error_frames", ImuFaultKind::kErrorFrames}});
  if (!kind)
    m.fail("fault", "missing: bias, scale, noise, stuck, saturation, vibration, temperature, drop, duplicate, "
                    "bus_off or error_frames");
  f.kind = *kind;
  if (f.kind == ImuFaultKind::kBusOff) return f;  // the bus: no sensor or axis
  if (f.kind == ImuFaultKind::kErrorFrames) {
    f.value = m.positive("rate_hz").value_or(10.0);
    return f;
  }
  if (channel_fault(f.kind)) {  // whole samples: no sensor or axis
    f.value = m.positive("probability").value_or(1.0);
    if (f.value > 1.0) m.fail("probability", "must be at most 1 (each sample's chance to be hit)");
    return f;
  }
  if (f.kind == ImuFaultKind::kTemperature) {  // the part's temperature: both triads
    f.value = required(m, "temperature_c", "the temperature change at full level, degC");
    return f;
  }
  const auto sensor = choice<ImuSensor>(m, "sensor", {{"gyro", ImuSensor::kGyro}, {"accel", ImuSensor::kAccel}});
  if (!sensor) m.fail("sensor", "missing: gyro or accel");
  f.sensor = *sensor;
  f.axis = choice<int>(m, "axis", {{"x", 0}, {"y", 1}, {"z", 2}, {"all", -1}}).value_or(-1);
  const bool gyro = f.sensor == ImuSensor::kGyro;
  // A value in the sensor's configuration unit (deg/s-based for the gyroscope, m/s^2 for the
  // accelerometer), to the model's (rad/s, m/s^2).
  const auto in_unit = [&](double v) { return gyro ? v * kDegToRad : v; };
  switch (f.kind) {
    case ImuFaultKind::kBias:
      f.value = in_unit(gyro ? required(m, "bias_dps", "the gyroscope's bias step, deg/s")
                             : required(m, "bias_mps2", "the accelerometer's bias step, m/s^2"));
      break;
    case ImuFaultKind::kScale:
      f.value = required(m, "scale_ppm", "the scale-factor error, ppm");
      break;
    case ImuFaultKind::kNoise: {
      const char* key = gyro ? "noise_radps_per_rthz" : "noise_mps2_per_rthz";
      const std::optional<double> d = m.positive(key);
      if (!d) m.fail(key, "missing: the added white noise's density");
      f.value = *d;
      break;
    }
    case ImuFaultKind::kSaturation: {
      const char* key = gyro ? "range_dps" : "range_mps2";
      const std::optional<double> r = m.positive(key);
      if (!r) m.fail(key, "missing: the range the output clips at while the fault lasts");
      f.value = in_unit(*r);
      break;
    }
    case ImuFaultKind::kVibration: {
      // A sinusoid (amplitude and frequency) and/or random vibration (a PSD over a band).
      const char* amplitude_key = gyro ? "amplitude_dps" : "amplitude_mps2";
      const char* psd_key = gyro ? "psd_dps2_per_hz" : "psd_g2_per_hz";
      f.value = in_unit(m.positive(amplitude_key, true).value_or(0.0));
      f.vibration.frequency_hz = m.positive("frequency_hz").value_or(0.0);
      if ((f.value > 0.0) != (f.vibration.frequency_hz > 0.0))
        m.fail(f.value > 0.0 ? "frequency_hz" : amplitude_key, "a sinusoid needs both its amplitude and frequency_hz");
      const double psd = m.positive(psd_key, true).value_or(0.0);
      f.vibration.psd = gyro ? psd * kDegToRad * kDegToRad : psd * kStandardGravity_mps2 * kStandardGravity_mps2;
      const auto band = m.number_list("band_hz");
      if ((psd > 0.0) != band.has_value())
        m.fail(psd > 0.0 ? "band_hz" : psd_key, "random vibration needs both its PSD and band_hz [low, high]");
      if (band) {
        if (band->size() != 2 || !((*band)[0] > 0.0) || !((*band)[0] < (*band)[1]))
          m.fail("band_hz", "must be [low, high], Hz, 0 < low < high");
        f.vibration.band_lo_hz = (*band)[0];
        f.vibration.band_hi_hz = (*band)[1];
      }
      if (f.value <= 0.0 && psd <= 0.0)
        m.fail("type", fmt::format("a vibration needs {} and frequency_hz (a sinusoid), or {} and band_hz "
                                   "(random vibration), or both", amplitude_key, psd_key));
      break;
    }
    default:
      break;
  }
  return f;
}

}  // namespace

void add_event(YamlMap& m, GnssEvents& out, std::vector<ImuFault>& imu, std::vector<TruthFault>& truth) {
  const std::optional<std::string> type = m.text("type");
  constexpr std::array<std::string_view, 11> kTypes = {"jamming",   "outage",    "antenna", "satellite",
                                                        "spoofing",  "ionosphere", "multipath", "cable",
                                                        "reset",     "imu",       "truth"};
  const std::string types = fmt::format("{}", fmt::join(kTypes, ", "));
  if (!type) m.fail("type", fmt::format("missing: the event's type ({})", types));
  if (std::find(kTypes.begin(), kTypes.end(), *type) == kTypes.end())
    m.fail("type", fmt::format("'{}' is not an event type navemu knows ({})", *type, types));
  EventWindow w;
  w.start_s = m.positive("start_s", true).value_or(0.0);
  if (const std::optional<std::string> at = m.text("at")) {  // GPS time instead of start_s
    if (m.has("start_s")) m.fail("at", "give either at (a GPS time) or start_s (seconds from the start), not both");
    try {
      w.at = parse_time(*at, "at");
    } catch (const InputError&) {
      m.fail("at", fmt::format("'{}' is not a time: ISO-8601 UTC (2026-11-27T12:00:00Z) or GPS WEEK:TOW (2394:475200)", *at));
    }
  }
  if (*type == "reset") {  // lasts as long as the restart does
    if (m.has("duration_s")) m.fail("duration_s", "a reset lasts as long as the receiver's start: no duration_s");
    ResetEvent e{w};
    e.kind = choice<RestartKind>(m, "start", {{"hot", RestartKind::kHot},
                                              {"warm", RestartKind::kWarm},
                                              {"cold", RestartKind::kCold}})
                 .value_or(RestartKind::kCold);
    e.window.duration_s = kResetSilence_s + restart_ttff_s(e.kind);
    out.resets.push_back(e);
    m.reject_unknown_keys();
    return;
  }
  const std::optional<double> duration = m.positive("duration_s");
  if (!duration) m.fail("duration_s", "missing: how long the event lasts, s");
  w.duration_s = *duration;
  const auto ramp = [&] {  // only where a level between on and off means something
    w.ramp_s = m.positive("ramp_s", true).value_or(0.0);
    if (2.0 * w.ramp_s > w.duration_s)
      m.fail("ramp_s", "ramp-in and ramp-out together would last longer than duration_s");
  };
  if (*type == "truth") {
    TruthFault f{w};
    const auto kind = choice<TruthFaultKind>(m, "fault", {{"freeze", TruthFaultKind::kFreeze},
                                                         {"teleport", TruthFaultKind::kTeleport},
                                                         {"time_jump", TruthFaultKind::kTimeJump}});
    if (!kind) m.fail("fault", "missing: freeze, teleport or time_jump");
    f.kind = *kind;
    if (f.kind == TruthFaultKind::kTeleport) {
      const auto offset = m.number_list("offset_m");
      if (!offset || offset->size() != 3) m.fail("offset_m", "must be [east, north, up], metres: where the vehicle jumps to");
      f.offset_enu_m = Vec3((*offset)[0], (*offset)[1], (*offset)[2]);
    } else if (f.kind == TruthFaultKind::kTimeJump) {
      f.jump_s = required(m, "jump_s", "how far the simulator's clock steps, s (negative: back)");
    }
    truth.push_back(f);
  } else if (*type == "imu") {
    const std::optional<std::string> fault = m.text("fault");
    if (fault != "stuck" && fault != "saturation" && fault != "bus_off") ramp();
    imu.push_back(imu_fault(m, w));
  } else if (*type == "jamming") {
    ramp();
    JammingEvent e{w, required(m, "j_over_s_db", "the jammer-to-signal ratio at full power, dB")};
    e.kind = choice<InterferenceKind>(m, "kind", {{"cw", InterferenceKind::kCw},
                                                  {"matched", InterferenceKind::kMatchedSpectrum},
                                                  {"wideband", InterferenceKind::kWideband}})
                 .value_or(e.kind);
    e.band = choice<Band>(m, "band", {{"L1", Band::kL1}, {"L2", Band::kL2}, {"L5", Band::kL5}}).value_or(e.band);
    out.jamming.push_back(e);
  } else if (*type == "spoofing") {
    ramp();
    SpoofingEvent e{w};
    const auto offset = m.number_list("offset_m");
    e.time_offset_s = m.number("time_offset_s").value_or(0.0);
    if (!offset && e.time_offset_s == 0.0)
      m.fail("offset_m", "missing: [east, north, up], metres from the antenna at full level (or time_offset_s, s)");
    if (offset && offset->size() != 3) m.fail("offset_m", "must be [east, north, up], metres");
    if (offset) e.offset_enu_m = Vec3((*offset)[0], (*offset)[1], (*offset)[2]);
    e.power_advantage_db = m.positive("power_advantage_db", true).value_or(e.power_advantage_db);
    out.spoofing.push_back(e);
  } else if (*type == "outage") {
    OutageEvent e{w};
    if (const auto az = m.number_list("azimuth_deg")) {
      if (az->size() != 2 || (*az)[0] < 0.0 || (*az)[0] > 360.0 || (*az)[1] < 0.0 || (*az)[1] > 360.0)
        m.fail("azimuth_deg", "must be [from, to], degrees 0..360 clockwise from north");
      e.az_from_deg = (*az)[0];
      e.az_to_deg = (*az)[1];
    }
    e.below_el_deg = m.positive("below_elevation_deg").value_or(e.below_el_deg);
    out.outages.push_back(e);
  } else if (*type == "cable") {
    out.cable.push_back({w});
  } else if (*type == "antenna") {
    const auto fault = choice<AntennaFault>(m, "fault", {{"open", AntennaFault::kOpen}, {"short", AntennaFault::kShort}});
    if (!fault) m.fail("fault", "missing: open or short");
    out.antenna.push_back({w, *fault});
  } else if (*type == "ionosphere" || *type == "multipath") {
    ramp();
    const std::optional<double> scale = m.positive("scale", true);
    if (!scale) m.fail("scale", *type == "ionosphere" ? "missing: the true ionospheric delay's factor at full level"
                                                      : "missing: the multipath errors' factor at full level");
    if (*type == "ionosphere")
      out.ionosphere.push_back({w, *scale});
    else
      out.multipath.push_back({w, *scale});
  } else {  // satellite
    ramp();
    const std::optional<std::int64_t> prn = m.integer("prn", 1, 32);
    if (!prn) m.fail("prn", "missing: the GPS satellite's PRN");
    SatelliteFaultEvent e{w, gps_sat(static_cast<int>(*prn))};
    e.clock_error_m = m.number("clock_error_m").value_or(0.0);
    if (const auto orbit = m.number_list("orbit_error_m")) {
      if (orbit->size() != 3) m.fail("orbit_error_m", "must be [radial, along-track, cross-track], metres");
      e.orbit_error_rac_m = Vec3((*orbit)[0], (*orbit)[1], (*orbit)[2]);
    }
    e.unhealthy = m.boolean("unhealthy").value_or(false);
    if (e.clock_error_m == 0.0 && e.orbit_error_rac_m.isZero() && !e.unhealthy)
      m.fail("type", "a satellite fault needs clock_error_m (m), orbit_error_m ([radial, along, cross], m) or "
                     "unhealthy: true");
    out.satellites.push_back(e);
  }
  m.reject_unknown_keys();
}

RunConfig load_run_config(const std::filesystem::path& file) {
  YamlMap root = load_yaml_file(file);
  if (root.empty())
    throw InputError(file.string(), 0, "",
                     "empty configuration: it names none of the sections scenario, truth, gnss, imu, "
                     "realtime (configs/default.yaml documents every key; navemu run without a file "
                     "runs that default)");
  RunConfig c;
  c.file = file;
  c.description = root.text("description").value_or("");

  YamlMap sc = root.map("scenario");
  c.start = sc.text("start").value_or(c.start);
  c.time_mode = choice<TimeMode>(sc, "time", {{"realtime", TimeMode::kRealTime},
                                              {"lockstep", TimeMode::kLockstep}})
                    .value_or(c.time_mode);
  c.seed = static_cast<std::uint64_t>(sc.integer("seed", 0, INT64_MAX).value_or(1));
  c.nav_file = resolve(file, sc.text("nav").value_or(""));
  c.status_interval_s = sc.positive("status_interval_s", true).value_or(c.status_interval_s);
  sc.reject_unknown_keys();

  c.truth = truth(root.map("truth"));
  if (c.time_mode == TimeMode::kLockstep && c.truth.kind != TruthSourceKind::kUdp)
    sc.fail("time", "lockstep takes GPS time from a streamed truth: it needs truth.source udp");

  YamlMap g = root.map("gnss");
  c.gnss_enabled = g.boolean("enabled").value_or(true);
  c.gnss = load_gnss_profile(g.text("profile").value_or("garmin-18x-5hz"));
  c.gnss_mode = choice<ReceiverMode>(g, "mode", {{"standalone", ReceiverMode::kStandalone},
                                                 {"dual", ReceiverMode::kDualFrequency},
                                                 {"dgps", ReceiverMode::kDgps},
                                                 {"rtk", ReceiverMode::kRtkFixed}})
                    .value_or(c.gnss_mode);
  for (YamlMap& o : g.map_list("outputs")) c.gnss_outputs.push_back(output(o));
  c.gnss_capture = resolve(file, g.text("capture").value_or(""));
  c.gnss_scene = scene_spec(g.map("scene"));
  c.gnss_ideal_sigma_m = g.positive("ideal_sigma_m");
  g.reject_unknown_keys();

  YamlMap imu = root.map("imu");
  c.imu_enabled = imu.boolean("enabled").value_or(true);
  c.imu_profile = imu.text("profile").value_or(c.imu_profile);
  c.imu_log = resolve(file, imu.text("log").value_or(""));
  c.imu_can = can_settings(imu.map("can"));
  for (YamlMap& o : imu.map_list("outputs")) c.imu_outputs.push_back(can_output(o, false));
  imu.reject_unknown_keys();

  for (YamlMap& e : root.map_list("events")) add_event(e, c.gnss_events, c.imu_faults, c.truth_faults);
  if (root.has("control")) {
    YamlMap ctl = root.map("control");
    c.control.emplace();
    c.control->address = ctl.text("address").value_or(c.control->address);
    c.control->port = static_cast<int>(ctl.integer("port", 0, 65535).value_or(0));
    ctl.reject_unknown_keys();
  }

  YamlMap rt = root.map("realtime");
  c.sched_fifo = rt.boolean("sched_fifo").value_or(false);
  c.lock_memory = rt.boolean("lock_memory").value_or(false);
  if (const auto cpu = rt.integer("cpu", 0, CPU_SETSIZE - 1)) c.cpu = static_cast<int>(*cpu);
  rt.reject_unknown_keys();
  root.reject_unknown_keys();
  return c;
}

}  // namespace navemu
