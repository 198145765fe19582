// navemu-px4-gps: PX4's u-blox driver (PX4-GPSDrivers src/ubx.cpp, compiled unmodified) on a
// serial device or pty, driven as PX4's GPS module drives it (PX4-Autopilot
// src/drivers/gps/gps.cpp, GPS::run): a fresh GPSDriverUBX per attempt, configure(baud, config)
// with baud 0 (auto-detect) or a fixed rate, then receive() in a loop (1.5 s timeout until the
// first report, 0.5 s after: TIMEOUT_INIT_5HZ and TIMEOUT_5HZ), and on a receive result <= 0
// or a failed configure the port is closed, 0.5 s pass, and it starts again.
//
// The driver's callback (gps_helper.h, GPSCallbackPtr) is implemented here: reads poll(2) for
// at most min(timeout, 50 ms) as PX4's pollOrRead does, writes go out whole, a baud change is a
// tcsetattr (harmless on a pty), RTCM and NAV-RELPOSNED notifications are reported.
//
// Standard output is the report, one JSON object per line, times in seconds since start
// (CLOCK_MONOTONIC, the driver's clock):
//   start      device, requested baud, the driver's settings
//   tx / rx    each UBX frame the driver writes; each ACK-ACK, ACK-NAK, MON-VER, INF-* it reads
//   log        a GPS_INFO/WARN/ERR message of the driver (firmware, protocol version, module)
//   set_baud   a baud change the driver asked for
//   configure  one configure() call: attempt, start and end, result, baud, board, versions
//   gps        one sensor_gps_s report (receive() bit 0)
//   sat        one satellite_info_s report (receive() bit 1)
//   receive_end  receive() returned <= 0: the driver is reconfigured
//   rtcm / relpos / survey_in  the driver's other notifications
//   stop       why and when it stopped, with totals
//
// The last line, `summary`, holds what the acceptance is stated in (issue 21, item 8):
// configure() result of the first attempt, attempts until one succeeded, its duration, the board
// and protocol version detected, every ACK-NAK read during configure() (the class/ID it NAKs),
// the first 3D fix after configure() returned, the rate of 3D reports over a window from that
// fix, each report's eph/epv against the hAcc/vAcc of the NAV-PVT with the same UTC (read here
// from the same bytes), the satellite count against the last NAV-SAT/NAV-SVINFO read, and the
// noise/jamming fields with the MON-HW/MON-RF frames read.
//
// --report prints that summary as a table instead of the JSON lines, for the receiver on
// DEVICE, e.g. `navemu run configs/ublox-m8.yaml` in one shell and
// `navemu-px4-gps --device /tmp/navemu-ublox-m8 --duration 20 --report` in another.
//
// Usage: navemu-px4-gps --device PATH [--baud 0|N] [--duration S] [--window S] [--report]

#include <CLI/CLI.hpp>
#include <fcntl.h>
#include <fmt/format.h>
#include <poll.h>
#include <signal.h>
#include <termios.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <thread>
#include <utility>
#include <vector>

#include "protocols/ubx.hpp"
#include "protocols/ubx_messages.hpp"
#include "ubx.h"  // PX4-GPSDrivers src/ (a system include path: third-party, unmodified)

namespace {

namespace ubx = navemu::ubx;

volatile sig_atomic_t g_stop_signal = 0;
void on_signal(int sig) { g_stop_signal = sig; }

gps_abstime g_start_us = 0;
bool g_jsonl = true;  // false with --report: the table only
double now_s() { return static_cast<double>(gps_absolute_time() - g_start_us) * 1e-6; }

std::string json_string(std::string_view s) {
  std::string out = "\"";
  for (const char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      out += fmt::format("\\u{:04x}", static_cast<unsigned>(static_cast<unsigned char>(c)));
    } else {
      out += c;
    }
  }
  return out + "\"";
}

// One report line: {"event":"NAME","t":T,FIELDS}.
void emit(std::string_view event, const std::string& fields = {}) {
  if (!g_jsonl) return;
  std::string line = fmt::format("{{\"event\":\"{}\",\"t\":{:.6f}", event, now_s());
  if (!fields.empty()) line += "," + fields;
  line += "}\n";
  std::fwrite(line.data(), 1, line.size(), stdout);
  std::fflush(stdout);
}

std::string hex_msg(std::uint8_t cls, std::uint8_t id) { return fmt::format("{:02X} {:02X}", cls, id); }

template <std::size_t N>
std::string json_array(const std::uint8_t (&a)[N], std::size_t count) {
  std::string out = "[";
  for (std::size_t i = 0; i < std::min(count, N); ++i) out += (i ? "," : "") + std::to_string(a[i]);
  return out + "]";
}

const char* board_name(GPSDriverUBX::Board b) {
  using B = GPSDriverUBX::Board;
  switch (b) {
    case B::unknown: return "unknown";
    case B::u_blox5: return "u_blox5";
    case B::u_blox6: return "u_blox6";
    case B::u_blox7: return "u_blox7";
    case B::u_blox8: return "u_blox8";
    case B::u_blox9: return "u_blox9";
    case B::u_blox9_F9P_L1L2: return "u_blox9_F9P_L1L2";
    case B::u_blox10: return "u_blox10";
    case B::u_blox9_F9P_L1L5: return "u_blox9_F9P_L1L5";
    case B::u_blox10_L1L5: return "u_blox10_L1L5";
    case B::u_blox_X20: return "u_blox_X20";
  }
  return "?";
}

std::optional<speed_t> termios_speed(int baud) {
  static const std::map<int, speed_t> speeds{
      {4800, B4800},     {9600, B9600},     {19200, B19200},   {38400, B38400},
      {57600, B57600},   {115200, B115200}, {230400, B230400}, {460800, B460800},
      {921600, B921600}};
  const auto it = speeds.find(baud);
  if (it == speeds.end()) return std::nullopt;
  return it->second;
}

// What the driver's log lines say about the receiver (ubx.cpp, payloadRxAddMonVer).
struct VersionLog {
  std::string firmware, protocol, module;
};
VersionLog g_versions;

// What the summary line and the table state (see the top of this file).
struct Summary {
  bool in_configure = false;
  long attempts = 0, first_success = 0;  // attempt number; 0: none
  int first_result = 1;                  // 1: configure() never called
  double t_configure_start = -1, t_configured = -1;  // of the first success
  std::string board = "unknown", firmware, protocol;
  std::map<std::string, long> handshake_naks, later_naks;  // NAKed "CC II" -> count
  long acks = 0;
  double t_first_fix = -1;
  std::vector<double> window_fix_t;  // 3D reports from the first fix to the end of the window
  std::map<std::uint64_t, std::pair<std::uint32_t, std::uint32_t>> pvt_acc_mm;  // UTC us -> hAcc, vAcc
  long pvt_read = 0, acc_matched = 0, acc_mismatched = 0, acc_unmatched = 0;
  std::string first_acc_mismatch;
  int last_sat_count = -1, last_sky_sent = -1;  // satellite_info_s count; numSvs/numCh read
  long gps_reports = 0, sat_reports = 0, receive_ends = 0;
  sensor_gps_s last{};
};
Summary g_sum;

// UTC of a NAV-PVT as the driver computes time_utc_usec (ubx.cpp, payloadRxDone: mktime of the
// date and time in UTC, plus nano / 1000).
std::uint64_t pvt_utc_usec(const ubx::NavPvt& m) {
  tm t{};
  t.tm_year = m.year - 1900;
  t.tm_mon = m.month - 1;
  t.tm_mday = m.day;
  t.tm_hour = m.hour;
  t.tm_min = m.min;
  t.tm_sec = m.sec;
  return static_cast<std::uint64_t>(static_cast<std::int64_t>(::timegm(&t)) * 1'000'000 + m.nano_ns / 1000);
}

// The frames the summary checks the driver's reports against, as they are read.
void note_rx(ubx::MsgId id, std::span<const std::uint8_t> pl) {
  if (id == ubx::kNavPvt) {
    ubx::NavPvt m;
    if (!ubx::decode(pl, m)) return;
    ++g_sum.pvt_read;
    g_sum.pvt_acc_mm[pvt_utc_usec(m)] = {m.h_acc_mm, m.v_acc_mm};
    if (g_sum.pvt_acc_mm.size() > 64) g_sum.pvt_acc_mm.erase(g_sum.pvt_acc_mm.begin());
  } else if (id == ubx::kNavSat || id == ubx::kNavSvinfo) {
    if (pl.size() >= 8) g_sum.last_sky_sent = pl[id == ubx::kNavSat ? 5 : 4];  // numSvs / numCh
  } else if (id == ubx::kAckAck) {
    ++g_sum.acks;
  } else if (id == ubx::kAckNak && pl.size() == 2) {
    ++(g_sum.in_configure ? g_sum.handshake_naks : g_sum.later_naks)[hex_msg(pl[0], pl[1])];
  }
}

// One gps report: the first fix, the window, eph/epv against the NAV-PVT of the same UTC.
void note_gps(const sensor_gps_s& g, double window_s) {
  ++g_sum.gps_reports;
  g_sum.last = g;
  const double t = now_s();
  if (g.fix_type >= 3) {
    if (g_sum.t_first_fix < 0) g_sum.t_first_fix = t;
    if (t <= g_sum.t_first_fix + window_s) g_sum.window_fix_t.push_back(t);
  }
  const auto it = g_sum.pvt_acc_mm.find(g.time_utc_usec);
  if (it == g_sum.pvt_acc_mm.end()) {
    ++g_sum.acc_unmatched;
    return;
  }
  // Within the NAV-PVT's resolution (1 mm): on protocol 27+ NAV-HPPOSLLH (0.1 mm) sets them last.
  const double dh = std::abs(g.eph - it->second.first * 1e-3), dv = std::abs(g.epv - it->second.second * 1e-3);
  if (dh <= 1e-3 && dv <= 1e-3) {
    ++g_sum.acc_matched;
  } else if (g_sum.acc_mismatched++ == 0) {
    g_sum.first_acc_mismatch = fmt::format("eph {} epv {} m vs hAcc {} vAcc {} mm", g.eph, g.epv,
                                           it->second.first, it->second.second);
  }
}

std::string naks_text(const std::map<std::string, long>& naks) {
  std::string s;
  for (const auto& [msg, n] : naks) s += fmt::format("{}{} x{}", s.empty() ? "" : ", ", msg, n);
  return s.empty() ? "none" : s;
}

long count_of(const std::map<std::string, long>& m) {
  long n = 0;
  for (const auto& kv : m) n += kv.second;
  return n;
}

double window_rate_hz() {
  const std::vector<double>& w = g_sum.window_fix_t;
  return w.size() > 1 ? static_cast<double>(w.size() - 1) / (w.back() - w.front()) : 0.0;
}

struct Port {
  std::string path;
  int fd = -1;
  long bytes_read = 0, bytes_written = 0;
  long rtcm = 0, relpos = 0, clock_sets = 0;
  ubx::Parser tx, rx;  // the frames of each direction, for the tx/rx lines
  std::map<std::string, long> rx_counts;  // "01 07" -> frames read

  bool open() {
    fd = ::open(path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
    tx.reset();
    rx.reset();
    if (fd < 0) return false;
    termios t{};
    if (::tcgetattr(fd, &t) == 0) {  // raw 8N1, as PX4's Serial configures a UART
      ::cfmakeraw(&t);
      t.c_cflag |= CLOCAL | CREAD;
      ::tcsetattr(fd, TCSANOW, &t);
    }
    return true;
  }
  void close() {
    if (fd >= 0) ::close(fd);
    fd = -1;
  }

  int read(std::uint8_t* buf, int len, int timeout_ms) {
    pollfd p{fd, POLLIN, 0};
    const int ready = ::poll(&p, 1, std::clamp(timeout_ms, 0, 50));
    if (ready < 0) return errno == EINTR ? 0 : -1;
    if (ready == 0) return 0;
    const ssize_t n = ::read(fd, buf, static_cast<std::size_t>(len));
    if (n < 0) return errno == EAGAIN || errno == EINTR ? 0 : -1;
    bytes_read += n;
    rx.feed(std::span<const std::uint8_t>(buf, static_cast<std::size_t>(n)), [&](ubx::Parser::Result r) {
      if (r != ubx::Parser::Result::kFrame) return;
      const std::uint8_t c = rx.cls(), i = rx.id();
      const std::span<const std::uint8_t> pl = rx.payload();
      const std::string msg = hex_msg(c, i);
      ++rx_counts[msg];
      note_rx({c, i}, pl);
      if (c == 0x05 && pl.size() >= 2)  // ACK-ACK / ACK-NAK: the acknowledged class and ID
        emit("rx", fmt::format("\"msg\":\"{}\",\"name\":\"{}\",\"of\":\"{}\"", msg,
                               i == 1 ? "ACK-ACK" : "ACK-NAK", hex_msg(pl[0], pl[1])));
      else if (c == 0x0A && i == 0x04)
        emit("rx", fmt::format("\"msg\":\"{}\",\"name\":\"MON-VER\",\"len\":{}", msg, pl.size()));
      else if (c == 0x04)
        emit("rx", fmt::format("\"msg\":\"{}\",\"name\":\"INF\",\"text\":{}", msg,
                               json_string(std::string(pl.begin(), pl.end()))));
    });
    return static_cast<int>(n);
  }

  int write(const std::uint8_t* buf, int len) {
    tx.feed(std::span<const std::uint8_t>(buf, static_cast<std::size_t>(len)), [&](ubx::Parser::Result r) {
      if (r == ubx::Parser::Result::kFrame)
        emit("tx", fmt::format("\"msg\":\"{}\",\"len\":{}", hex_msg(tx.cls(), tx.id()), tx.payload().size()));
    });
    int done = 0;
    const gps_abstime end = gps_absolute_time() + 1'000'000;
    while (done < len && gps_absolute_time() < end) {
      const ssize_t n = ::write(fd, buf + done, static_cast<std::size_t>(len - done));
      if (n > 0) {
        done += static_cast<int>(n);
        continue;
      }
      if (n < 0 && errno != EAGAIN && errno != EINTR) return -1;
      pollfd p{fd, POLLOUT, 0};
      ::poll(&p, 1, 10);
    }
    bytes_written += done;
    return done;
  }

  int set_baud(int baud) {
    const std::optional<speed_t> s = termios_speed(baud);
    termios t{};
    const bool ok = s && ::tcgetattr(fd, &t) == 0 && ::cfsetispeed(&t, *s) == 0 &&
                    ::cfsetospeed(&t, *s) == 0 && ::tcsetattr(fd, TCSANOW, &t) == 0;
    emit("set_baud", fmt::format("\"baud\":{},\"ok\":{}", baud, ok));
    return ok ? 0 : -1;
  }
};

int callback(GPSCallbackType type, void* data1, int data2, void* user) {
  Port& port = *static_cast<Port*>(user);
  switch (type) {
    case GPSCallbackType::readDeviceData: {
      int timeout_ms = 0;
      std::memcpy(&timeout_ms, data1, sizeof timeout_ms);
      return port.read(static_cast<std::uint8_t*>(data1), data2, timeout_ms);
    }
    case GPSCallbackType::writeDeviceData:
      return port.write(static_cast<const std::uint8_t*>(data1), data2);
    case GPSCallbackType::setBaudrate:
      return port.set_baud(data2);
    case GPSCallbackType::gotRTCMMessage:
      ++port.rtcm;
      emit("rtcm", fmt::format("\"len\":{}", data2));
      return 0;
    case GPSCallbackType::gotRelativePositionMessage: {
      ++port.relpos;
      const auto& r = *static_cast<const sensor_gnss_relative_s*>(data1);
      emit("relpos", fmt::format("\"n_m\":{},\"e_m\":{},\"d_m\":{},\"heading_valid\":{}",
                                 r.position[0], r.position[1], r.position[2], r.heading_valid));
      return 0;
    }
    case GPSCallbackType::surveyInStatus: {
      const auto& s = *static_cast<const SurveyInStatus*>(data1);
      emit("survey_in", fmt::format("\"duration_s\":{},\"mean_accuracy_mm\":{},\"flags\":{}",
                                    s.duration, s.mean_accuracy, s.flags));
      return 0;
    }
    case GPSCallbackType::setClock:  // the host clock is left alone; counted only
      ++port.clock_sets;
      return 0;
  }
  return -1;
}

void emit_gps(const sensor_gps_s& g, int ret) {
  emit("gps",
       fmt::format("\"ret\":{},\"fix_type\":{},\"time_utc_usec\":{},\"latitude_deg\":{:.9f},"
                   "\"longitude_deg\":{:.9f},\"altitude_msl_m\":{:.4f},\"altitude_ellipsoid_m\":{:.4f},"
                   "\"eph\":{},\"epv\":{},\"hdop\":{},\"vdop\":{},\"satellites_used\":{},"
                   "\"vel_m_s\":{},\"vel_n_m_s\":{},\"vel_e_m_s\":{},\"vel_d_m_s\":{},"
                   "\"vel_ned_valid\":{},\"cog_rad\":{},\"s_variance_m_s\":{},\"c_variance_rad\":{},"
                   "\"noise_per_ms\":{},\"automatic_gain_control\":{},\"jamming_indicator\":{},"
                   "\"jamming_state\":{},\"spoofing_state\":{},\"timestamp_time_relative\":{}",
                   ret, g.fix_type, g.time_utc_usec, g.latitude_deg, g.longitude_deg,
                   g.altitude_msl_m, g.altitude_ellipsoid_m, g.eph, g.epv, g.hdop, g.vdop,
                   g.satellites_used, g.vel_m_s, g.vel_n_m_s, g.vel_e_m_s, g.vel_d_m_s,
                   g.vel_ned_valid, g.cog_rad, g.s_variance_m_s, g.c_variance_rad, g.noise_per_ms,
                   g.automatic_gain_control, g.jamming_indicator, g.jamming_state,
                   g.spoofing_state, g.timestamp_time_relative));
}

void emit_sat(const satellite_info_s& s) {
  emit("sat", fmt::format("\"count\":{},\"svid\":{},\"used\":{},\"elevation\":{},\"azimuth\":{},"
                          "\"snr\":{},\"prn\":{}",
                          s.count, json_array(s.svid, s.count), json_array(s.used, s.count),
                          json_array(s.elevation, s.count), json_array(s.azimuth, s.count),
                          json_array(s.snr, s.count), json_array(s.prn, s.count)));
}

// PX4's defaults (../shared/TESTING.md; PX4-Autopilot gps.cpp and params.c): dynamic model 7
// (airborne < 2 g), UART2 230400, jamming detection sensitivity high (GPS_UBX_JAM_DET 1),
// output rate 0 (the driver picks it per board), normal (non-heading) mode.
GPSDriverUBX::Settings px4_settings() {
  GPSDriverUBX::Settings s{};
  s.dynamic_model = 7;
  s.dgnss_timeout = 0;
  s.min_cno = 0;
  s.min_elev = 0;
  s.output_rate = 0;
  s.heading_offset = 0.0f;
  s.uart2_baudrate = 230400;
  s.ppk_output = false;
  s.jam_det_sensitivity_hi = true;
  s.mode = GPSDriverUBX::UBXMode::Normal;
  return s;
}

}  // namespace

void navemu_px4_log(char level, const char* format, ...) {
  char text[512];
  va_list args;
  va_start(args, format);
  std::vsnprintf(text, sizeof text, format, args);
  va_end(args);
  const std::string_view t(text);
  for (const auto& [prefix, field] : {std::pair<std::string_view, std::string*>{"u-blox firmware version: ", &g_versions.firmware},
                                      {"u-blox protocol version: ", &g_versions.protocol},
                                      {"u-blox module: ", &g_versions.module}})
    if (t.substr(0, prefix.size()) == prefix) *field = std::string(t.substr(prefix.size()));
  emit("log", fmt::format("\"level\":\"{}\",\"text\":{}", level, json_string(t)));
}

int main(int argc, char** argv) {
  CLI::App app{"PX4's u-blox driver (PX4-GPSDrivers, unmodified) on a serial device or pty, as "
               "PX4's GPS module runs it; prints a JSON-lines report on standard output"};
  std::string device;
  unsigned configured_baud = 0;
  double duration_s = 0, window_s = 10;
  bool report = false;
  app.add_option("--device", device, "serial device or pty")->required();
  app.add_option("--baud", configured_baud, "0: auto-detect (the driver tries 7 rates); else fixed");
  app.add_option("--duration", duration_s, "stop after this many seconds (0: at SIGINT/SIGTERM)");
  app.add_option("--window", window_s, "seconds of 3D reports the rate is measured over, from the first fix");
  app.add_flag("--report", report, "print the summary as a table instead of the JSON lines");
  CLI11_PARSE(app, argc, argv);
  g_jsonl = !report;

  // The driver converts NAV-PVT's UTC date with mktime(3), which reads local time: UTC here,
  // as on PX4's boards.
  ::setenv("TZ", "UTC", 1);
  ::tzset();
  struct sigaction sa {};
  sa.sa_handler = on_signal;
  ::sigaction(SIGINT, &sa, nullptr);
  ::sigaction(SIGTERM, &sa, nullptr);

  g_start_us = gps_absolute_time();
  timespec real{};
  ::clock_gettime(CLOCK_REALTIME, &real);
  const GPSDriverUBX::Settings settings = px4_settings();
  emit("start", fmt::format("\"device\":{},\"baud\":{},\"duration_s\":{},\"realtime_s\":{}.{:09d},"
                            "\"dynamic_model\":{},\"jam_det_sensitivity_hi\":{},\"uart2_baudrate\":{},"
                            "\"output_rate\":{},\"gnss_systems\":0,\"interface_protocols\":0,\"cfg_wipe\":false",
                            json_string(device), configured_baud, duration_s, real.tv_sec, real.tv_nsec,
                            settings.dynamic_model, settings.jam_det_sensitivity_hi,
                            settings.uart2_baudrate, settings.output_rate));

  const auto expired = [&] {
    return g_stop_signal != 0 || (duration_s > 0 && now_s() >= duration_s);
  };
  Port port;
  port.path = device;
  sensor_gps_s gps{};
  satellite_info_s sat{};
  long attempts = 0, gps_reports = 0, sat_reports = 0;
  while (!expired()) {
    if (port.fd < 0 && !port.open()) {
      emit("open_failed", fmt::format("\"device\":{},\"error\":{}", json_string(device),
                                      json_string(std::strerror(errno))));
      std::this_thread::sleep_for(std::chrono::seconds(1));
      continue;
    }
    if (configured_baud != 0) port.set_baud(static_cast<int>(configured_baud));

    GPSDriverUBX driver(GPSHelper::Interface::UART, callback, &port, &gps, &sat, settings);
    GPSHelper::GPSConfig config{};
    config.output_mode = GPSHelper::OutputMode::GPS;
    config.gnss_systems = GPSHelper::GNSSSystemsMask::RECEIVER_DEFAULTS;
    config.interface_protocols = GPSHelper::InterfaceProtocolsMask::ALL_DISABLED;
    config.cfg_wipe = false;
    unsigned baud = configured_baud;
    g_versions = {};
    const double t_start = now_s();
    g_sum.in_configure = true;
    const int result = driver.configure(baud, config);
    g_sum.in_configure = false;
    ++attempts;
    if (attempts == 1) g_sum.first_result = result;
    if (result == 0 && g_sum.first_success == 0) {
      g_sum.first_success = attempts;
      g_sum.t_configure_start = t_start;
      g_sum.t_configured = now_s();
      g_sum.board = board_name(driver.board());
      g_sum.firmware = g_versions.firmware;
      g_sum.protocol = g_versions.protocol;
    }
    emit("configure",
         fmt::format("\"attempt\":{},\"t_start\":{:.6f},\"result\":{},\"baud\":{},\"board\":\"{}\","
                     "\"firmware\":{},\"protocol_version\":{},\"module\":{}",
                     attempts, t_start, result, baud, board_name(driver.board()),
                     json_string(g_versions.firmware), json_string(g_versions.protocol),
                     json_string(g_versions.module)));
    if (result == 0) {
      gps = sensor_gps_s{};
      driver.resetUpdateRates();
      unsigned timeout_ms = 1500;  // TIMEOUT_INIT_5HZ until the first report, then TIMEOUT_5HZ
      int ret = 0;
      while (!expired() && (ret = driver.receive(timeout_ms)) > 0) {
        if (ret & 1) {
          ++gps_reports;
          note_gps(gps, window_s);
          emit_gps(gps, ret);
        }
        if (ret & 2) {
          ++sat_reports;
          g_sum.last_sat_count = sat.count;
          emit_sat(sat);
        }
        timeout_ms = 500;
      }
      if (ret <= 0) {
        ++g_sum.receive_ends;
        emit("receive_end", fmt::format("\"ret\":{}", ret));
      }
    }
    port.close();
    if (!expired()) std::this_thread::sleep_for(std::chrono::milliseconds(500));
  }
  std::string rx_counts;
  for (const auto& [msg, n] : port.rx_counts)
    rx_counts += fmt::format("{}\"{}\":{}", rx_counts.empty() ? "" : ",", msg, n);
  emit("stop", fmt::format("\"reason\":\"{}\",\"configure_attempts\":{},\"gps_reports\":{},"
                           "\"sat_reports\":{},\"bytes_read\":{},\"bytes_written\":{},\"rtcm\":{},"
                           "\"relpos\":{},\"clock_sets\":{},\"rx_frames\":{{{}}}",
                           g_stop_signal != 0 ? "signal" : "duration", attempts, gps_reports,
                           sat_reports, port.bytes_read, port.bytes_written, port.rtcm, port.relpos,
                           port.clock_sets, rx_counts));
  g_sum.attempts = attempts;
  g_sum.sat_reports = sat_reports;
  const auto rx_of = [&](const char* msg) {
    const auto it = port.rx_counts.find(msg);
    return it == port.rx_counts.end() ? 0L : it->second;
  };
  const Summary& m = g_sum;
  const double to_fix = m.t_first_fix >= 0 && m.t_configured >= 0 ? m.t_first_fix - m.t_configured : -1;
  const double window_span = m.window_fix_t.size() > 1 ? m.window_fix_t.back() - m.window_fix_t.front() : 0;
  emit("summary",
       fmt::format("\"first_result\":{},\"attempts\":{},\"first_success\":{},\"configure_s\":{:.3f},"
                   "\"board\":\"{}\",\"firmware\":{},\"protocol_version\":{},\"handshake_naks\":{},"
                   "\"handshake_naked\":{},\"later_naks\":{},\"acks\":{},\"first_fix_after_configure_s\":{:.3f},"
                   "\"window_s\":{:.3f},\"window_reports\":{},\"rate_hz\":{:.4f},\"receive_ends\":{},"
                   "\"pvt_read\":{},\"acc_matched\":{},\"acc_mismatched\":{},\"acc_unmatched\":{},"
                   "\"sat_count\":{},\"sky_sent\":{},\"noise_per_ms\":{},\"jamming_indicator\":{},"
                   "\"agc\":{},\"mon_hw_read\":{},\"mon_rf_read\":{}",
                   m.first_result, m.attempts, m.first_success,
                   m.t_configured >= 0 ? m.t_configured - m.t_configure_start : -1.0, m.board,
                   json_string(m.firmware), json_string(m.protocol), count_of(m.handshake_naks),
                   json_string(naks_text(m.handshake_naks)), count_of(m.later_naks), m.acks, to_fix,
                   window_span, m.window_fix_t.size(), window_rate_hz(), m.receive_ends, m.pvt_read,
                   m.acc_matched, m.acc_mismatched, m.acc_unmatched, m.last_sat_count,
                   m.last_sky_sent, m.last.noise_per_ms, m.last.jamming_indicator,
                   m.last.automatic_gain_control, rx_of("0A 09"), rx_of("0A 38")));
  if (report) {
    const auto row = [](std::string_view what, const std::string& value) {
      std::printf("%-40s %s\n", std::string(what).c_str(), value.c_str());
    };
    const auto opt_s = [](double s) { return s >= 0 ? fmt::format("{:.3f} s", s) : std::string("-"); };
    std::printf("PX4 u-blox driver on %s, %s, %.1f s\n", device.c_str(),
                configured_baud != 0 ? fmt::format("fixed {} baud", configured_baud).c_str() : "auto baud",
                now_s());
    row("configure() first attempt", m.first_result == 0 ? "0" : fmt::format("{}", m.first_result));
    row("configure() attempts", m.first_success != 0 ? fmt::format("{} (first success #{})", m.attempts, m.first_success)
                                                      : fmt::format("{} (none succeeded)", m.attempts));
    row("time to configure", opt_s(m.t_configured >= 0 ? m.t_configured - m.t_configure_start : -1));
    row("board / protocol version", fmt::format("{} / {} ({})", m.board, m.protocol.empty() ? "-" : m.protocol,
                                                m.firmware.empty() ? "-" : m.firmware));
    row("ACK-NAK in handshake (NAKed msg)", fmt::format("{}: {}", count_of(m.handshake_naks), naks_text(m.handshake_naks)));
    row("ACK-NAK after configure / ACK-ACK", fmt::format("{} / {}", count_of(m.later_naks), m.acks));
    row("first 3D fix after configure", opt_s(to_fix));
    row("3D report rate over window", fmt::format("{:.3f} Hz ({} reports in {:.2f} s of {:.0f} s)", window_rate_hz(),
                                                  m.window_fix_t.size(), window_span, window_s));
    row("receive() <= 0 (reconfigured)", fmt::format("{}", m.receive_ends));
    row("eph/epv = hAcc/vAcc (same UTC)", fmt::format("{} match, {} differ{}, {} without NAV-PVT ({} read)",
                                                      m.acc_matched, m.acc_mismatched,
                                                      m.first_acc_mismatch.empty() ? "" : " (" + m.first_acc_mismatch + ")",
                                                      m.acc_unmatched, m.pvt_read));
    const auto opt_n = [](int n) { return n >= 0 ? std::to_string(n) : std::string("-"); };
    row("satellite info count / NAV-SAT|SVINFO", fmt::format("{} / {} ({} reports)", opt_n(m.last_sat_count),
                                                             opt_n(m.last_sky_sent), m.sat_reports));
    row("noise_per_ms / jamming / AGC", fmt::format("{} / {} / {} (MON-HW {}, MON-RF {} read)", m.last.noise_per_ms,
                                                    m.last.jamming_indicator, m.last.automatic_gain_control,
                                                    rx_of("0A 09"), rx_of("0A 38")));
  }
  return 0;
}
