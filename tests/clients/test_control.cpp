// Live control of `navemu run` (emulator/control.hpp) as a test script uses it: `navemu ctl`
// sends an outage while navemu runs, and the receiver's NMEA output loses its fix from the
// epoch the reply names until a re-acquisition time (1 s) after the outage; a flood of commands
// is answered without one epoch late or skipped. IMU and truth faults sent the same way act
// from the time the reply names.

#include <gtest/gtest.h>

#include <fmt/format.h>

#include <regex>
#include <sstream>

#include "core/time.hpp"
#include "tests/can_capture.hpp"
#include "tests/clients/client_support.hpp"

namespace navemu::test::clients {
namespace {

// `navemu ctl --port PORT COMMANDS...`: its exit code and standard output.
std::pair<std::optional<int>, std::string> ctl(const TempDir& dir, int port, const std::vector<std::string>& commands,
                                               const std::string& name) {
  std::vector<std::string> argv{navemu_binary().string(), "ctl", "--port", std::to_string(port)};
  argv.insert(argv.end(), commands.begin(), commands.end());
  Child c(argv, dir / (name + ".out"), dir / (name + ".err"));
  const std::optional<int> st = c.wait_exit(20.0);
  return {st && WIFEXITED(*st) ? std::optional<int>(WEXITSTATUS(*st)) : std::nullopt, slurp(dir / (name + ".out"))};
}

// The GGA sentences of an NMEA log: each one's fields and its time (UTC time of day) in ms from
// `from`'s.
std::vector<std::pair<std::int64_t, std::vector<std::string>>> gga_from(const fs::path& nmea, GpsTime from) {
  const CalendarTime utc = utc_from_gps(from);
  const std::int64_t from_ms = ((utc.hour * 60 + utc.minute) * 60) * 1000 + std::llround(utc.second * 1000.0);
  std::vector<std::pair<std::int64_t, std::vector<std::string>>> out;
  std::stringstream ss(slurp(nmea));
  for (std::string line; std::getline(ss, line);) {
    if (line.size() < 7 || line.compare(3, 4, "GGA,") != 0) continue;
    std::vector<std::string> f;
    std::stringstream ls(line);
    for (std::string x; std::getline(ls, x, ',');) f.push_back(x);
    if (f.size() < 7) continue;
    out.emplace_back(nmea_ms_of_day(f[1]) - from_ms, std::move(f));
  }
  return out;
}

TEST(LiveControl, AnOutageSentWhileRunningCutsTheFixFromTheNamedEpoch) {
  TempDir dir("live-control");
  const fs::path nmea = dir / "nmea.log";
  NavemuRun nav(dir, "navemu",
                fmt::format("scenario: {{status_interval_s: 0}}\n"
                            "truth: {{source: stationary}}\n"
                            "gnss:\n  profile: ublox-nmea-5hz\n  outputs:\n    - {{type: file, path: '{}'}}\n"
                            "imu: {{enabled: false}}\n"
                            "control: {{port: 0}}\n",
                            nmea.string()),
                11.0);
  static const std::regex port_re(R"(navemu: control on tcp 127\.0\.0\.1:(\d+))");
  std::smatch m;
  std::string log;
  ASSERT_TRUE(wait_until([&] { log = nav.err(); return std::regex_search(log, m, port_re); }, 10.0)) << nav.diagnostics();
  const int port = std::stoi(m[1]);
  sleep_s(2.5);

  // One good command and one refused: exit code 1, a reply each, in order.
  const auto [code, replies] =
      ctl(dir, port, {R"({"cmd": "event", "type": "outage", "duration_s": 2})", R"({"cmd": "event", "type": "tunnel"})"},
          "ctl");
  EXPECT_EQ(code, 1);
  static const std::regex ok_re(R"re(^\{"ok": true, "from": "[^"]+", "gps": "(\d+):([0-9.]+)"\}\n\{"ok": false, "error": "[^"]*'tunnel' is not an event type)re");
  std::smatch r;
  ASSERT_TRUE(std::regex_search(replies, r, ok_re)) << replies;
  const GpsTime from = from_week_tow(std::stoi(r[1]), std::stod(r[2]));

  // A flood: 1000 commands at once (refused ones, which cost the most), answered within the
  // run, no epoch late or skipped.
  sleep_s(4.0);
  const auto [flood_code, flood] = ctl(dir, port, std::vector<std::string>(1000, R"({"cmd": "event"})"), "flood");
  EXPECT_EQ(flood_code, 1);
  EXPECT_EQ(std::count(flood.begin(), flood.end(), '\n'), 1000);
  nav.stop_expecting_exit_0();
  const std::optional<RunSummary> sum = run_summary(nav.err());
  ASSERT_TRUE(sum) << nav.diagnostics();
  EXPECT_EQ(sum->late, 0);
  EXPECT_EQ(sum->skipped, 0);

  // GGA quality by epoch (UTC time of day in the sentence), against the outage's epochs.
  int before = 0, during = 0, reacquiring = 0, after = 0;
  for (const auto& [dt_ms, f] : gga_from(nmea, from)) {
    const int quality = std::stoi(f[6]);
    if (dt_ms >= -1000 && dt_ms < 0) before += quality == 1 ? 1 : -100;
    if (dt_ms >= 0 && dt_ms < 2000) during += quality == 0 ? 1 : -100;
    if (dt_ms >= 2000 && dt_ms < 3000) reacquiring += quality == 0 ? 1 : -100;
    if (dt_ms >= 3000 && dt_ms < 4000) after += quality == 1 ? 1 : -100;
  }
  EXPECT_EQ(before, 5) << "fixes in the second before";
  EXPECT_EQ(during, 10) << "no fix from the named epoch for 2 s";
  EXPECT_EQ(reacquiring, 5) << "re-acquiring for 1 s";
  EXPECT_EQ(after, 5) << "the fix back";
}

// The port's address from navemu's start-up line.
int control_port(NavemuRun& nav) {
  static const std::regex port_re(R"(navemu: control on tcp 127\.0\.0\.1:(\d+))");
  std::smatch m;
  std::string log;
  if (!wait_until([&] { log = nav.err(); return std::regex_search(log, m, port_re); }, 10.0)) return 0;
  return std::stoi(m[1]);
}

// The reply's start ("gps": "WEEK:TOW").
std::optional<GpsTime> reply_start(const std::string& reply) {
  static const std::regex re(R"re("ok": true, "from": "[^"]+", "gps": "(\d+):([0-9.]+)")re");
  std::smatch r;
  if (!std::regex_search(reply, r, re)) return std::nullopt;
  return from_week_tow(std::stoi(r[1]), std::stod(r[2]));
}

// A gyroscope bias step and a teleport of the truth, sent while navemu runs: the IMU's samples
// (its log, 125 Hz) carry the step from the named time to its end within one sample; the
// receiver's GGA (5 Hz) lies 300 m north of its place from the named epoch for 2 s, and back
// after.
TEST(LiveControl, ImuAndTruthFaultsSentWhileRunningActFromTheNamedTime) {
  TempDir dir("live-control-imu-truth");
  const fs::path nmea = dir / "nmea.log", imu = dir / "imu.log";
  NavemuRun nav(dir, "navemu",
                fmt::format("scenario: {{status_interval_s: 0}}\n"
                            "truth: {{source: stationary}}\n"
                            "gnss:\n  profile: ublox-nmea-5hz\n  outputs:\n    - {{type: file, path: '{}'}}\n"
                            "imu: {{profile: xsens_mti100, log: '{}'}}\n"
                            "control: {{port: 0}}\n",
                            nmea.string(), imu.string()),
                10.0);
  const int port = control_port(nav);
  ASSERT_GT(port, 0) << nav.diagnostics();
  sleep_s(2.5);
  const auto [code, replies] =
      ctl(dir, port,
          {R"({"cmd": "event", "type": "imu", "duration_s": 1, "fault": "bias", "sensor": "gyro", "axis": "z", "bias_dps": 50})",
           R"({"cmd": "event", "type": "truth", "duration_s": 2, "fault": "teleport", "offset_m": [0, 300, 0]})"},
          "ctl");
  EXPECT_EQ(code, 0) << replies;
  std::stringstream lines(replies);
  std::string bias_reply, teleport_reply;
  std::getline(lines, bias_reply);
  std::getline(lines, teleport_reply);
  const std::optional<GpsTime> bias_at = reply_start(bias_reply), teleport_at = reply_start(teleport_reply);
  ASSERT_TRUE(bias_at && teleport_at) << replies;
  sleep_s(4.0);
  nav.stop_expecting_exit_0();

  // The IMU log: gyroscope z against its mean before the step.
  constexpr double kDeg = 3.14159265358979323846 / 180.0;
  const std::vector<ImuRow> rows = read_imu_rows(imu);
  double base = 0.0;
  int n = 0;
  for (const ImuRow& r : rows)
    if (r.gps_time_ns < bias_at->ns - 20'000'000 && r.gps_time_ns > bias_at->ns - 1'000'000'000) {
      base += r.w_radps[2];
      ++n;
    }
  ASSERT_GT(n, 50) << "samples in the second before";
  base /= n;
  constexpr std::int64_t kTol_ns = 10'000'000 + 1'000'000;  // one sample (100 Hz) + the printed ms
  int stepped = 0;
  for (const ImuRow& r : rows) {
    const std::int64_t dt = r.gps_time_ns - bias_at->ns;
    const bool shifted = std::abs(r.w_radps[2] - base - 50.0 * kDeg) < 1.0 * kDeg;
    if (dt > kTol_ns && dt < 1'000'000'000 - kTol_ns) {
      EXPECT_TRUE(shifted) << static_cast<double>(dt) * 1e-9 << " s";
      ++stepped;
    } else if (dt < -kTol_ns || dt > 1'000'000'000 + kTol_ns) {
      EXPECT_FALSE(shifted) << static_cast<double>(dt) * 1e-9 << " s";
    }
  }
  EXPECT_GE(stepped, 97);
  // GGA latitude against the mean of the second before: 12 m, some 5 sigma of this
  // consumer-class receiver's north error.
  std::vector<std::pair<std::int64_t, double>> gga;  // ms from the teleport, latitude
  for (const auto& [dt_ms, f] : gga_from(nmea, *teleport_at))
    if (!f[2].empty()) gga.emplace_back(dt_ms, std::stod(f[2].substr(0, 2)) + std::stod(f[2].substr(2)) / 60.0);
  double lat0 = 0.0;
  int before = 0, moved = 0, back = 0;
  for (const auto& [dt_ms, lat] : gga)
    if (dt_ms >= -1000 && dt_ms < 0) {
      lat0 += lat;
      ++before;
    }
  ASSERT_EQ(before, 5) << "the second before at 5 Hz";
  lat0 /= before;
  for (const auto& [dt_ms, lat] : gga) {
    const double north_m = (lat - lat0) * 110'852.0;  // m per degree of latitude at 32.3 deg
    if (dt_ms >= 0 && dt_ms < 2000) {
      EXPECT_NEAR(north_m, 300.0, 12.0) << dt_ms << " ms";
      ++moved;
    } else if (dt_ms >= 2000 && dt_ms < 3000) {
      EXPECT_NEAR(north_m, 0.0, 12.0) << dt_ms << " ms";
      ++back;
    }
  }
  EXPECT_EQ(moved, 10) << "2 s at 5 Hz";
  EXPECT_EQ(back, 5);
}

}  // namespace
}  // namespace navemu::test::clients
