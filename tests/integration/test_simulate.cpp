// navemu simulate: the real-time loop's models and encoders offline, deterministic, and the
// files they write agree with each other and with the physics.

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>

#include "core/time.hpp"
#include "models/event_window.hpp"
#include "protocols/gps_lnav.hpp"
#include "protocols/nmea.hpp"
#include "tests/rinex_data.hpp"
#include "protocols/ubx.hpp"
#include "protocols/ubx_messages.hpp"
#include "tests/can_capture.hpp"
#include "tests/test_support.hpp"

namespace navemu {
namespace {

namespace fs = std::filesystem;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

fs::path temp_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("navemu_simulate_" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

test::CommandResult simulate(const fs::path& config, const fs::path& out, double duration_s,
                             const std::string& extra = "") {
  return test::run_command(test::shell_quote(test::navemu_binary().string()) + " simulate " +
                           test::shell_quote(config.string()) + " --start 2010-11-17T13:00:00Z" +
                           " --duration " + std::to_string(duration_s) + " --out " +
                           test::shell_quote(out.string()) + " " + extra + " 2>&1");
}

const fs::path kDefault = fs::path(NAVEMU_SOURCE_DIR) / "configs" / "default.yaml";

// Runs `config` into a and b: both succeed with the same bytes in each of `files`. The first
// run's result.
test::CommandResult simulate_twice(const fs::path& config, const fs::path& a, const fs::path& b, double duration_s,
                                   std::initializer_list<const char*> files) {
  const auto ra = simulate(config, a, duration_s), rb = simulate(config, b, duration_s);
  EXPECT_EQ(ra.exit_code, 0) << ra.out;
  EXPECT_EQ(rb.exit_code, 0) << rb.out;
  for (const char* f : files) {
    EXPECT_FALSE(slurp(a / f).empty()) << f;
    EXPECT_EQ(slurp(a / f), slurp(b / f)) << f;
  }
  return ra;
}

// `config` without its `events:` section (the last one), written into `dir`.
fs::path without_events(const fs::path& config, const fs::path& dir) {
  const fs::path quiet = dir / "quiet.yaml";
  const std::string text = slurp(config);
  std::ofstream(quiet) << text.substr(0, text.find("\nevents:")) + "\n";
  return quiet;
}

TEST(Simulate, SameSeedGivesIdenticalFilesAndAnotherSeedDoesNot) {
  const fs::path a = temp_dir("a"), b = temp_dir("b"), c = temp_dir("c");
  ASSERT_EQ(simulate(kDefault, a, 30).exit_code, 0);
  ASSERT_EQ(simulate(kDefault, b, 30).exit_code, 0);
  ASSERT_EQ(simulate(kDefault, c, 30, "--seed 2").exit_code, 0);
  for (const char* f : {"nmea.log", "truth.csv", "gnss.csv", "imu.csv", "can.log"}) {
    EXPECT_FALSE(slurp(a / f).empty()) << f;
    EXPECT_EQ(slurp(a / f), slurp(b / f)) << f;
  }
  EXPECT_NE(slurp(a / "gnss.csv"), slurp(c / "gnss.csv"));
  EXPECT_NE(slurp(a / "imu.csv"), slurp(c / "imu.csv"));
  EXPECT_EQ(slurp(a / "truth.csv"), slurp(c / "truth.csv"));  // the truth has no randomness
}

// With events (configs/jammer-drive-by.yaml, 180 s: the jammer rises, holds and fades), the
// same scenario and seed give the same bytes; the jammer costs fixes; without its events the
// run differs.
TEST(Simulate, EventsAreDeterministicAndAct) {
  const fs::path a = temp_dir("events_a"), b = temp_dir("events_b"), c = temp_dir("events_c");
  const fs::path cfg = fs::path(NAVEMU_SOURCE_DIR) / "configs" / "jammer-drive-by.yaml";
  const auto ra = simulate_twice(cfg, a, b, 180, {"ubx.bin", "gnss.csv"});
  const auto rc = simulate(without_events(cfg, c), c, 180);
  ASSERT_EQ(rc.exit_code, 0) << rc.out;
  EXPECT_NE(rc.out.find("180 GNSS epochs (180 with a fix)"), std::string::npos) << rc.out;
  EXPECT_EQ(ra.out.find("180 GNSS epochs (180 with a fix)"), std::string::npos) << ra.out;
  EXPECT_NE(ra.out.find("navemu: event: jamming, wideband on L1, J/S 50 dB"), std::string::npos) << ra.out;
}

// The IMU on a thread of its own (--threads 2, the default on two or more cores) writes the
// same files as one thread, with truth faults (a freeze, a teleport, a time jump: each thread
// has its own truth), a jammer and IMU faults in the run; both runs report the same counts.
TEST(Simulate, TwoThreadsWriteTheFilesOfOne) {
  const fs::path dir = temp_dir("threads"), one = dir / "one", two = dir / "two";
  const fs::path cfg = dir / "faults.yaml";
  std::ofstream(cfg) << slurp(fs::path(NAVEMU_SOURCE_DIR) / "configs" / "imu-stuck-gyro.yaml") <<
      "  - {type: truth, start_s: 20, duration_s: 5, fault: freeze}\n"
      "  - {type: truth, start_s: 30, duration_s: 5, fault: teleport, offset_m: [0, 100, 0]}\n"
      "  - {type: truth, start_s: 40, duration_s: 5, fault: time_jump, jump_s: 3}\n"
      "  - {type: jamming, start_s: 50, duration_s: 40, ramp_s: 10, j_over_s_db: 45, kind: wideband, band: L1}\n";
  const auto r1 = simulate(cfg, one, 120, "--threads 1"), r2 = simulate(cfg, two, 120, "--threads 2");
  ASSERT_EQ(r1.exit_code, 0) << r1.out;
  ASSERT_EQ(r2.exit_code, 0) << r2.out;
  for (const char* f : {"nmea.log", "truth.csv", "gnss.csv", "imu.csv", "can.log"}) {
    EXPECT_FALSE(slurp(one / f).empty()) << f;
    EXPECT_EQ(slurp(one / f), slurp(two / f)) << f;
  }
  const std::string apart = "navemu: the IMU runs on a thread of its own\n";
  EXPECT_EQ(r1.out.find(apart), std::string::npos) << r1.out;
  EXPECT_NE(r2.out.find(apart), std::string::npos) << r2.out;
  const std::regex speed_and_folder(
      R"(scenario in [0-9.]+ s \([0-9]+x real time\)|/(one|two)\b|navemu: the IMU runs on a thread of its own\n)");
  EXPECT_EQ(std::regex_replace(r1.out, speed_and_folder, ""), std::regex_replace(r2.out, speed_and_folder, ""));
  EXPECT_NE(r1.out.find("14750 IMU samples, 250 dropped by a fault"), std::string::npos) << r1.out;
}

// configs/tunnel.yaml: the F9P (1 Hz) loses its fix for the 20 s of the tunnel and the second
// it takes to re-acquire the satellites after it. The same tunnel (and an IMU fault) given by
// GPS time (`at`, 60 s after the 13:00:00 start) gives the same files.
TEST(Simulate, TheTunnelScenarioLosesTheFixForItsLengthAndStartsAtItsGpsTime) {
  const fs::path d = temp_dir("tunnel"), e = temp_dir("tunnel_at");
  std::string text = slurp(fs::path(NAVEMU_SOURCE_DIR) / "configs" / "tunnel.yaml");
  const std::string relative = "  - {type: outage, start_s: 60, duration_s: 20}\n";
  ASSERT_NE(text.find(relative), std::string::npos);
  std::ofstream(d / "tunnel.yaml")
      << text + "  - {type: imu, start_s: 30, duration_s: 5, fault: bias, sensor: gyro, bias_dps: 1}\n";
  text.replace(text.find(relative), relative.size(), "  - {type: outage, at: '1610:306075', duration_s: 20}\n");
  std::ofstream(e / "tunnel.yaml")
      << text + "  - {type: imu, at: '2010-11-17T13:00:30Z', duration_s: 5, fault: bias, sensor: gyro, bias_dps: 1}\n";
  const auto r = simulate(d / "tunnel.yaml", d / "out", 100), s = simulate(e / "tunnel.yaml", e / "out", 100);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  ASSERT_EQ(s.exit_code, 0) << s.out;
  EXPECT_NE(r.out.find("100 GNSS epochs (79 with a fix)"), std::string::npos) << r.out;
  EXPECT_NE(s.out.find("navemu: event: outage, azimuth 0 to 360 deg below 90 deg elevation, from "
                       "2010-11-17T13:01:00Z (1610:306075.000) for 20 s"),
            std::string::npos)
      << s.out;
  for (const char* f : {"gnss.csv", "ubx.bin", "imu.csv"}) {
    EXPECT_FALSE(slurp(d / "out" / f).empty()) << f;
    EXPECT_EQ(slurp(d / "out" / f), slurp(e / "out" / f)) << f;
  }
}

// configs/spoofing-takeover.yaml: the spoofer walks the fix 300 m north over 60 s from 60 s,
// holds it and walks it back; the fix error follows the ramp (level x 300 m, within the
// receiver's own error), the velocity shows the walk's 5 m/s, and the fix never drops.
TEST(Simulate, TheSpoofingScenarioWalksTheFixOffAndBack) {
  const fs::path d = temp_dir("spoofing");
  const auto r = simulate(fs::path(NAVEMU_SOURCE_DIR) / "configs" / "spoofing-takeover.yaml", d, 300);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("300 GNSS epochs (300 with a fix)"), std::string::npos) << r.out;
  const test::CsvTable t(d / "gnss.csv");
  ASSERT_EQ(t.size(), 300u);
  const EventWindow w{60.0, 180.0, 60.0};
  double worst_m = 0.0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const double t_s = t.num(i, "time_s");
    const double pulled_m = 300.0 * event_level(w, t_s);
    worst_m = std::max(worst_m, std::abs(t.num(i, "err_n_m") - pulled_m));
    EXPECT_NEAR(t.num(i, "err_n_m"), pulled_m, 5.0) << t_s << " s";
    // The spoofer acts while its level is above 0: not yet at the ramp's first instant.
    const double walk_mps = pulled_m > 0.0 ? 300.0 * event_level_rate(w, t_s) : 0.0;
    EXPECT_NEAR(t.num(i, "v_n_mps"), walk_mps, 0.5) << t_s << " s";
  }
  fmt::print("spoofed fix: north error within {:.2f} m of the pull (level x 300 m)\n", worst_m);
}

// IMU faults (configs/imu-stuck-gyro.yaml: gyroscope z stuck 60-90 s, samples lost 110-112 s,
// accelerometer noise 150-170 s): the same bytes twice; against the run without its events,
// every sample outside the windows is the same (the faults draw from their own streams), the
// stuck axis holds its last value, the lost samples leave a gap in the sequence.
TEST(Simulate, ImuFaultsAreDeterministicAndActOnlyInTheirWindows) {
  const fs::path a = temp_dir("imu_faults_a"), b = temp_dir("imu_faults_b"), c = temp_dir("imu_faults_c");
  const fs::path cfg = fs::path(NAVEMU_SOURCE_DIR) / "configs" / "imu-stuck-gyro.yaml";
  const auto ra = simulate_twice(cfg, a, b, 180, {"imu.csv", "can.log", "nmea.log"});
  EXPECT_NE(ra.out.find("22250 IMU samples, 250 dropped by a fault"), std::string::npos) << ra.out;
  EXPECT_NE(ra.out.find("navemu: event: IMU stuck output, gyroscope z, from 2010-11-17T13:01:00Z"), std::string::npos)
      << ra.out;
  ASSERT_EQ(simulate(without_events(cfg, c), c, 180).exit_code, 0);

  const std::vector<test::ImuRow> faulty = test::read_imu_rows(a / "imu.csv"), clean = test::read_imu_rows(c / "imu.csv");
  ASSERT_EQ(clean.size(), 22500u);
  ASSERT_EQ(faulty.size(), 22250u);
  std::map<int, const test::ImuRow*> by_sequence;
  for (const test::ImuRow& r : faulty) by_sequence[r.sequence] = &r;
  std::size_t stuck = 0, noisy = 0;
  for (const test::ImuRow& q : clean) {
    const double t_s = q.sequence * 0.008;
    const auto it = by_sequence.find(q.sequence);
    if (t_s >= 110.0 && t_s < 112.0) {
      EXPECT_EQ(it, by_sequence.end()) << "lost at " << t_s << " s";
      continue;
    }
    ASSERT_NE(it, by_sequence.end()) << t_s << " s";
    const test::ImuRow& r = *it->second;
    EXPECT_EQ(r.w_radps[0], q.w_radps[0]);
    EXPECT_EQ(r.gps_time_ns, q.gps_time_ns);
    if (t_s >= 60.0 && t_s < 90.0) {
      EXPECT_EQ(r.w_radps[2], by_sequence.at(7499)->w_radps[2]) << "held at " << t_s << " s";
      stuck += r.w_radps[2] != q.w_radps[2];
    } else {
      EXPECT_EQ(r.w_radps[2], q.w_radps[2]) << t_s << " s";
    }
    if (t_s > 150.0 && t_s < 170.0)
      noisy += r.f_mps2[1] != q.f_mps2[1];
    else
      EXPECT_EQ(r.f_mps2, q.f_mps2) << t_s << " s";
  }
  EXPECT_GT(stuck, 3700u) << "the held rate differs from the turning vehicle's";
  EXPECT_EQ(noisy, 2499u);
}

// The other IMU faults offline, on a BMI160: the same seed gives the same bytes; outside each
// fault's window every sample is the fault-free run's (once the part's 80 Hz output filter has
// forgotten the fault: to 1e-9 from 50 ms after it, 25 time constants); random vibration moves
// gyroscope y only in its window; the temperature column carries the warming; a duplicated
// sample is its row twice.
TEST(Simulate, SaturationVibrationTemperatureAndDuplicatesActOnlyInTheirWindows) {
  const fs::path a = temp_dir("imu_faults2_a"), b = temp_dir("imu_faults2_b"), c = temp_dir("imu_faults2_c");
  const fs::path cfg = a.parent_path() / "navemu_simulate_imu_faults2.yaml";
  std::ofstream(cfg) << "gnss: {enabled: false}\nimu: {profile: bmi160}\nevents:\n"
                        "  - {type: imu, start_s: 2, duration_s: 1, fault: saturation, sensor: gyro, axis: all, range_dps: 0.2}\n"
                        "  - {type: imu, start_s: 4, duration_s: 2, fault: vibration, sensor: gyro, axis: y, "
                        "psd_dps2_per_hz: 0.01, band_hz: [20, 60]}\n"
                        "  - {type: imu, start_s: 7, duration_s: 2, ramp_s: 1, fault: temperature, temperature_c: -20}\n"
                        "  - {type: imu, start_s: 10, duration_s: 1, fault: duplicate, probability: 0.5}\n";
  const auto ra = simulate_twice(cfg, a, b, 12, {"imu.csv", "can.log"});
  EXPECT_NE(ra.out.find("sent twice by a fault"), std::string::npos) << ra.out;
  ASSERT_EQ(simulate(without_events(cfg, c), c, 12).exit_code, 0);
  const test::CsvTable faulty(a / "imu.csv"), clean(c / "imu.csv");
  ASSERT_EQ(clean.size(), 2400u);
  ASSERT_GT(faulty.size(), clean.size() + 60) << "about half of the second's 200 samples twice";
  ASSERT_LT(faulty.size(), clean.size() + 140);
  std::size_t k = 0, twice = 0, clipped = 0;
  double vibration_ss = 0.0;
  constexpr double kRange_radps = 0.2 * 3.14159265358979323846 / 180.0;
  for (std::size_t i = 0; i < clean.size(); ++i, ++k) {
    ASSERT_LT(k, faulty.size());
    if (k + 1 < faulty.size() && faulty.row(k + 1) == faulty.row(k)) {
      const double t_s = static_cast<double>(i) / 200.0;
      EXPECT_TRUE(t_s >= 10.0 && t_s < 11.0) << "sent twice at " << t_s << " s";
      ++twice;
      ++k;
    }
    const double t_s = static_cast<double>(i) / 200.0;
    if (t_s >= 2.0 && t_s < 3.0) {
      for (const char* col : {"w_x_radps", "w_y_radps", "w_z_radps"}) {
        EXPECT_LE(std::abs(faulty.num(k, col)), kRange_radps * (1.0 + 1e-9)) << t_s;
        clipped += std::abs(clean.num(i, col)) > kRange_radps;
      }
    } else if (t_s >= 4.0 && t_s < 6.0) {
      const double d = faulty.num(k, "w_y_radps") - clean.num(i, "w_y_radps");
      vibration_ss += d * d;
      EXPECT_EQ(faulty(k, "w_x_radps"), clean(i, "w_x_radps")) << t_s;
    } else if (t_s > 7.0 && t_s < 9.0) {
      EXPECT_NE(faulty(k, "temperature_c"), clean(i, "temperature_c")) << t_s;
    } else if (!(t_s >= 6.0 && t_s < 6.05) && !(t_s >= 9.0 && t_s < 9.05)) {
      for (std::size_t col = 0; col < clean.row(i).size(); ++col)
        EXPECT_NEAR(std::stod(faulty.row(k)[col]), std::stod(clean.row(i)[col]), 1e-9) << t_s << " s, column " << col;
    }
  }
  EXPECT_EQ(k, faulty.size());
  EXPECT_GT(twice, 60u);
  EXPECT_GT(clipped, 0u) << "the turn-on bias (3 deg/s, 1-sigma) exceeds the 0.2 deg/s range on some axis";
  // rms 0.1 x sqrt(40) = 0.63 deg/s over 400 samples, the output filter (80 Hz) passing the band.
  const double rms_dps = std::sqrt(vibration_ss / 400.0) * 180.0 / 3.14159265358979323846;
  EXPECT_GT(rms_dps, 0.4);
  EXPECT_LT(rms_dps, 0.9);
  EXPECT_NE(ra.out.find(fmt::format("{} sent twice by a fault", twice)), std::string::npos) << ra.out;
}

// The receiver's cable out for 5 s and a hot-start reset, offline (5 Hz NMEA): no sentence
// for the epochs of the cable window; after the reset 0.5 s of silence (its boot), then a
// second of GGA without a fix (the hot start's time to first fix), then fixes again; gnss.csv
// tells the same; the same seed gives the same bytes.
TEST(Simulate, CableOutAndResetSilenceTheReceiverThenItSearches) {
  const fs::path a = temp_dir("cable_a"), b = temp_dir("cable_b");
  const fs::path cfg = a.parent_path() / "navemu_simulate_cable.yaml";
  std::ofstream(cfg) << "imu: {enabled: false}\nevents:\n"
                        "  - {type: cable, start_s: 10, duration_s: 5}\n"
                        "  - {type: reset, start_s: 30, start: hot}\n";
  const auto r = simulate_twice(cfg, a, b, 40, {"nmea.log", "gnss.csv"});
  EXPECT_NE(r.out.find("200 GNSS epochs (192 with a fix, 28 not sent: cable out or resetting)"), std::string::npos)
      << r.out;
  std::map<int, int> gga_quality;  // by epoch (0.2 s) from 13:00:00
  std::istringstream nmea(slurp(a / "nmea.log"));
  for (std::string line; std::getline(nmea, line);) {
    if (line.find("GGA,") == std::string::npos) continue;
    std::vector<std::string> f;
    std::istringstream fields(line);
    for (std::string x; std::getline(fields, x, ',');) f.push_back(x);
    ASSERT_GE(f.size(), 7u) << line;
    const double s = std::stod(f[1].substr(4));  // hhmmss.ss at 13:00: the seconds
    gga_quality[static_cast<int>(std::lround(s * 5.0))] = std::stoi(f[6]);
  }
  for (int k = 0; k < 200; ++k) {
    const double t = k / 5.0;
    const auto q = gga_quality.find(k);
    if ((t >= 10.0 && t < 15.0) || (t >= 30.0 && t < 30.5)) {
      EXPECT_EQ(q, gga_quality.end()) << "sent at " << t << " s";
    } else {
      ASSERT_NE(q, gga_quality.end()) << "nothing at " << t << " s";
      EXPECT_EQ(q->second, t >= 30.5 && t < 31.5 ? 0 : 1) << t << " s";
    }
  }
  const test::CsvTable g(a / "gnss.csv");
  ASSERT_EQ(g.size(), 200u);
  for (std::size_t i = 0; i < g.size(); ++i)
    EXPECT_EQ(g(i, "fix"), g.num(i, "time_s") >= 30.0 && g.num(i, "time_s") < 31.5 ? "0" : "3") << g(i, "time_s");
}

// CAN bus faults offline (the paper's IMU, 125 Hz, J1939 frames in can.log): a bus-off from
// 5 s for 1 s loses the samples of that second (their frames and log lines), with SocketCAN's
// CAN_ERR_BUSOFF error frame (can_id 0x20000040 in candump's log format) at its start and
// CAN_ERR_RESTARTED (0x20000100) at its end; 50 bus errors per second for 2 s from 8 s are 100
// error frames (CAN_ERR_PROT | CAN_ERR_BUSERROR, a stuffing error in data[2]) in that window.
TEST(Simulate, CanBusOffAndErrorFramesInTheCandumpLog) {
  const fs::path a = temp_dir("bus_off");
  const fs::path cfg = a.parent_path() / "navemu_simulate_bus_off.yaml";
  std::ofstream(cfg) << "gnss: {enabled: false}\nevents:\n"
                        "  - {type: imu, start_s: 5, duration_s: 1, fault: bus_off}\n"
                        "  - {type: imu, start_s: 8, duration_s: 2, fault: error_frames, rate_hz: 50}\n";
  const auto r = simulate(cfg, a, 12);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("1375 IMU samples, 125 lost to a CAN bus-off, 100 CAN error frames"), std::string::npos) << r.out;
  const double t0 = static_cast<double>(unix_ns_from_gps(parse_time("2010-11-17T13:00:00Z"))) * 1e-9;
  std::vector<double> bus_off, restarted, errors;
  std::size_t frames_in_bus_off = 0, frames = 0;
  std::istringstream log(slurp(a / "can.log"));
  for (std::string line; std::getline(log, line);) {
    const double t = std::stod(line.substr(1, line.find(')') - 1)) - t0;
    const std::string frame = line.substr(line.rfind(' ') + 1);
    if (frame == "20000040#0000000000000000") {
      bus_off.push_back(t);
    } else if (frame == "20000100#0000000000000000") {
      restarted.push_back(t);
    } else if (frame == "20000088#0000040000000000") {
      errors.push_back(t);
      EXPECT_TRUE(t >= 8.0 && t < 10.1) << t;
    } else {
      ++frames;
      frames_in_bus_off += t > 5.0 + 0.005 && t < 6.0 - 0.005;
    }
  }
  ASSERT_EQ(bus_off.size(), 1u);
  ASSERT_EQ(restarted.size(), 1u);
  EXPECT_NEAR(bus_off[0], 5.0, 0.02);
  EXPECT_NEAR(restarted[0], 6.0, 0.02);
  EXPECT_EQ(errors.size(), 100u);
  EXPECT_EQ(frames_in_bus_off, 0u);
  EXPECT_EQ(frames, 2u * 1375u) << "ARI and ACCS per sample sent";
}

TEST(Simulate, ASecondRunIntoTheSameFolderReplacesEveryFile) {
  const fs::path once = temp_dir("once"), twice = temp_dir("twice");
  ASSERT_EQ(simulate(kDefault, once, 10).exit_code, 0);
  std::ofstream(twice / "ubx.bin") << "from an earlier u-blox run";
  ASSERT_EQ(simulate(kDefault, twice, 10).exit_code, 0);
  ASSERT_EQ(simulate(kDefault, twice, 10).exit_code, 0);
  for (const char* f : {"nmea.log", "truth.csv", "gnss.csv", "imu.csv", "can.log"}) {
    EXPECT_FALSE(slurp(once / f).empty()) << f;
    EXPECT_EQ(slurp(twice / f), slurp(once / f)) << f;
  }
  EXPECT_FALSE(fs::exists(twice / "ubx.bin"));
}

// Every IMU profile shipped in configs/imu runs in the engine at its output rate, with its
// internal steps (600 Hz inside 100 Hz for `tactical` is not a whole number of nanoseconds).
TEST(Simulate, EveryShippedImuProfileRunsAtItsOutputRate) {
  int profiles = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(NAVEMU_SOURCE_DIR) / "configs" / "imu")) {
    const std::string name = entry.path().stem().string();
    const fs::path d = temp_dir("imu_" + name);
    const fs::path config = d / "run.yaml";
    std::ofstream(config) << "gnss: {enabled: false}\nimu: {profile: " << name << "}\n";
    const auto r = simulate(config, d / "out", 2);
    ASSERT_EQ(r.exit_code, 0) << name << ": " << r.out;
    const test::CsvTable rows(d / "out" / "imu.csv");
    ASSERT_GE(rows.size(), 1u) << name;
    // Consecutive samples one output period apart in GPS time.
    const std::int64_t period_ns = rows.integer(1, "gps_time_ns") - rows.integer(0, "gps_time_ns");
    EXPECT_EQ(static_cast<double>(rows.size()), 2e9 / static_cast<double>(period_ns)) << name;
    for (std::size_t i = 1; i < rows.size(); ++i)
      ASSERT_EQ(rows.integer(i, "gps_time_ns") - rows.integer(i - 1, "gps_time_ns"), period_ns)
          << name << " row " << i + 1;
    ++profiles;
  }
  EXPECT_GE(profiles, 7);
}

TEST(Simulate, FilesHoldEveryEpochOnTheGridWithAPlausibleFix) {
  const fs::path d = temp_dir("grid");
  const auto r = simulate(kDefault, d, 60);
  ASSERT_EQ(r.exit_code, 0) << r.out;

  // 60 s at 5 Hz: epochs at .0 .2 .4 ... from the start, 300 of them.
  const test::CsvTable gnss(d / "gnss.csv");
  ASSERT_EQ(gnss.size(), 300u);
  ASSERT_EQ(gnss.header()[0], "time_s");
  double sum_h = 0.0, max_h = 0.0;
  int fixes = 0;
  for (std::size_t i = 0; i < gnss.size(); ++i) {
    EXPECT_NEAR(gnss.num(i, "time_s"), 0.2 * static_cast<double>(i), 1e-9);
    if (gnss(i, "fix") != "3") continue;
    ++fixes;
    const double h = gnss.num(i, "err_h_m");
    sum_h += h;
    max_h = std::max(max_h, h);
    EXPECT_GE(gnss.integer(i, "num_used"), 4);
  }
  EXPECT_EQ(fixes, 300);
  // A consumer receiver, standalone, Klobuchar residual: metres, not tens of metres.
  EXPECT_LT(sum_h / fixes, 8.0);
  EXPECT_LT(max_h, 25.0);

  // NMEA: every sentence framed and checksummed; one RMC per epoch, 0.2 s apart; GSV once a
  // second (the Garmin profile's divisor).
  std::map<std::string, int> count;
  std::istringstream nmea_text(slurp(d / "nmea.log"));
  std::vector<double> rmc_times;
  for (std::string line; std::getline(nmea_text, line);) {
    const auto f = nmea::parse(line + "\n");
    ASSERT_TRUE(f) << line;
    ++count[(*f)[0]];
    if ((*f)[0] == "GPRMC") {
      const std::string& t = (*f)[1];
      rmc_times.push_back(std::stod(t.substr(0, 2)) * 3600 + std::stod(t.substr(2, 2)) * 60 +
                          std::stod(t.substr(4)));
      EXPECT_EQ((*f)[2], "A");
    }
  }
  EXPECT_EQ(count["GPRMC"], 300);
  EXPECT_EQ(count["GPGGA"], 300);
  EXPECT_EQ(count["GPGSA"], 300);
  EXPECT_EQ(count["PGRME"], 60);
  EXPECT_GE(count["GPGSV"], 60 * 2);
  ASSERT_EQ(rmc_times.size(), 300u);
  EXPECT_NEAR(rmc_times[0], 13 * 3600.0, 1e-6);  // UTC 13:00:00.0
  for (std::size_t i = 1; i < rmc_times.size(); ++i)
    EXPECT_NEAR(rmc_times[i] - rmc_times[i - 1], 0.2, 1e-6);

  // IMU: 125 Hz for 60 s, every sample with truth.
  const test::CsvTable imu(d / "imu.csv");
  ASSERT_EQ(imu.size(), 7500u);
  for (std::size_t i = 0; i < imu.size(); ++i) EXPECT_EQ(imu(i, "truth_valid"), "1");

  // Truth: the paper's 30 ft circle around the site.
  const test::CsvTable truth(d / "truth.csv");
  ASSERT_EQ(truth.size(), 300u);
}

// The IMU's CAN frames of an offline run: can.log in candump -L format, one J1939 ARI and ACCS
// per sample (the default configuration's layout), stamped at the samples' output times,
// decoding to the values in imu.csv; can-utils' log2asc converts it.
TEST(Simulate, CanLogHoldsEverySampleAsJ1939FramesThatLog2ascConverts) {
  const fs::path d = temp_dir("can");
  const auto r = simulate(kDefault, d, 20);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const auto rows = test::read_imu_rows(d / "imu.csv");
  ASSERT_EQ(rows.size(), 2500u);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    EXPECT_EQ(rows[i].sequence, static_cast<int>(i));
    EXPECT_EQ(rows[i].gps_time_ns - rows[0].gps_time_ns, static_cast<std::int64_t>(i) * 8'000'000);
  }
  const auto frames = test::read_candump_log(d / "can.log");
  ASSERT_EQ(frames.size(), 5000u);
  // The interface column: the configuration's SocketCAN interface.
  EXPECT_NE(slurp(d / "can.log").find(") vcan0 0CF02A80#"), std::string::npos);
  const test::CanCheck c = test::check_frames_against_log(frames, rows);
  EXPECT_EQ(c.ari, 2500u);
  EXPECT_EQ(c.accs, 2500u);
  EXPECT_EQ(c.mismatches, 0u) << c.first_problem;
  // The comparison covers real motion: on the 30 ft circle at 1 m/s the yaw rate is 0.11 rad/s.
  EXPECT_GT(std::abs(rows.back().w_radps[2]), 0.05);
  // Priority 3, source address 0x80: 0x0CF02A80 and 0x0CF02D80.
  EXPECT_EQ(frames[0].id, 0x0CF02A80u);
  EXPECT_EQ(frames[1].id, 0x0CF02D80u);
  // Time stamps: the sample's output time in Unix seconds, frames of a sample together.
  const double t0 = static_cast<double>(unix_ns_from_gps(GpsTime{rows[0].gps_time_ns})) * 1e-9;
  EXPECT_NEAR(frames[0].t_s - t0, 0.0, 0.01);  // + the profile's latency
  EXPECT_EQ(frames[1].t_s, frames[0].t_s);
  EXPECT_NEAR(frames[4998].t_s - frames[0].t_s, 2499 * 0.008, 2e-6);
  // A reader's hole (candump -d) in a J1939-only log: the frames before it check out, and
  // nothing dates those after it, so they are cut, not mismatched. Dropped: sample 500's ACCS
  // and both frames of sample 501.
  std::vector<test::LoggedFrame> holed(frames.begin(), frames.begin() + 1001);
  holed.insert(holed.end(), frames.begin() + 1004, frames.end());
  holed[1001].dropped_before = 3;
  const test::CanCheck h = test::check_frames_against_log(holed, rows);
  EXPECT_EQ(h.mismatches, 0u) << h.first_problem;
  EXPECT_EQ(h.ari, 501u);
  EXPECT_EQ(h.accs, 500u);
  EXPECT_EQ(h.cut, 2500u - 502);

  const std::string log2asc = "/usr/bin/log2asc";
  if (!fs::exists(log2asc)) GTEST_SKIP() << "can-utils' log2asc is not installed (tools/install-deps)";
  const auto conv = test::run_command(log2asc + " -I " + test::shell_quote((d / "can.log").string()) +
                                      " -O " + test::shell_quote((d / "can.asc").string()) + " vcan0 2>&1");
  ASSERT_EQ(conv.exit_code, 0) << conv.out;
  EXPECT_EQ(conv.out, "");
  std::istringstream asc(slurp(d / "can.asc"));
  int rx = 0;
  for (std::string line; std::getline(asc, line);)
    if (line.find(" Rx ") != std::string::npos) ++rx;
  EXPECT_EQ(rx, 5000);
}

// The high-resolution layouts, classic and CAN FD, carry every sample to full precision with
// its GPS time and sequence number.
TEST(Simulate, HighResolutionFramesDecodeToFullPrecision) {
  const fs::path d = temp_dir("can-hr");
  const fs::path cfg = d / "hr.yaml";
  std::ofstream(cfg) << "imu:\n  outputs:\n    - {type: socketcan, interface: vcan0, "
                        "layouts: [j1939, highres, highres-fd]}\n";
  const auto r = simulate(cfg, d / "out", 4);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const auto rows = test::read_imu_rows(d / "out" / "imu.csv");
  ASSERT_EQ(rows.size(), 500u);
  const auto frames = test::read_candump_log(d / "out" / "can.log");
  ASSERT_EQ(frames.size(), 500u * 8);
  EXPECT_NE(slurp(d / "out" / "can.log").find(") vcan0 510##"), std::string::npos);
  const test::CanCheck c = test::check_frames_against_log(frames, rows);
  EXPECT_EQ(c.samples, 500u);
  EXPECT_EQ(c.ari, 500u);
  EXPECT_EQ(c.highres, 500u);
  EXPECT_EQ(c.highres_fd, 500u);
  EXPECT_EQ(c.mismatches, 0u) << c.first_problem;
  EXPECT_LE(c.max_hr_rate_err_radps, 0.5e-7 + 1e-9);
}

// A reader that falls behind leaves holes in its log (candump -d: a DROPCOUNT line before the
// first frame after them; tests/can_capture.hpp). Cut anywhere and at any length, what is left
// still checks out against the IMU log: no mismatch, and every frame that is left and can be
// dated checked (the J1939 frames before a hole dated by the sample before them, the rest of a
// sample after one by its CAN FD frame), so each layout counts exactly the samples that kept
// its frames.
TEST(Simulate, FramesLeftAroundAReadersHoleAllCheckOut) {
  const fs::path d = temp_dir("can-holes");
  const fs::path cfg = d / "hr.yaml";
  std::ofstream(cfg) << "imu:\n  outputs:\n    - {type: socketcan, interface: vcan0, "
                        "layouts: [j1939, highres, highres-fd]}\n";
  ASSERT_EQ(simulate(cfg, d / "out", 1).exit_code, 0);
  const auto rows = test::read_imu_rows(d / "out" / "imu.csv");
  const auto frames = test::read_candump_log(d / "out" / "can.log");
  ASSERT_EQ(rows.size(), 125u);
  ASSERT_EQ(frames.size(), 125u * 8);  // per sample: ARI, ACCS, 5 classic high-resolution, FD
  for (std::size_t start = 0; start < 3 * 8; ++start) {
    for (const std::size_t length : std::initializer_list<std::size_t>{1, 2, 4, 5, 7, 8, 9, 23}) {
      for (const bool at_end : {false, true}) {
        const std::size_t from = at_end ? frames.size() - length : start + 8 * 60;
        if (at_end && start > 0) continue;
        const auto at = [&](std::size_t i) { return frames.begin() + static_cast<std::ptrdiff_t>(i); };
        std::vector<test::LoggedFrame> left(frames.begin(), at(from));
        left.insert(left.end(), at(from + length), frames.end());
        if (at_end) {
          left.back().dropped_after = length;
        } else {
          left[from].dropped_before = length;
        }
        const auto kept = [&](std::size_t k, std::size_t first, std::size_t n) {
          return 8 * k + first + n <= from || 8 * k + first >= from + length;
        };
        std::size_t ari = 0, accs = 0, highres = 0, fd = 0;
        for (std::size_t k = 0; k < rows.size(); ++k) {
          if (kept(k, 0, 1)) ++ari;
          if (kept(k, 1, 1)) ++accs;
          if (kept(k, 2, 5)) ++highres;
          if (kept(k, 7, 1)) ++fd;
        }
        const test::CanCheck c = test::check_frames_against_log(left, rows);
        const std::string where =
            std::to_string(length) + " frames dropped after frame " + std::to_string(from);
        EXPECT_EQ(c.mismatches, 0u) << where << ": " << c.first_problem;
        EXPECT_EQ(c.ari, ari) << where;
        EXPECT_EQ(c.accs, accs) << where;
        EXPECT_EQ(c.highres, highres) << where;
        EXPECT_EQ(c.highres_fd, fd) << where;
        EXPECT_EQ(test::reader_dropped(left), length) << where;
      }
    }
  }
}

// A scene in the loop: the same seed and scene give identical files; the street canyon costs
// satellites against open sky; a missing scene file stops navemu with its name.
TEST(Simulate, SceneRunsAreDeterministicAndCostSatellites) {
  const fs::path d = temp_dir("scene");
  const auto gen = test::run_command(test::shell_quote(test::navemu_binary().string()) +
                                     " scene urban-canyon --building-height-m 40 --out " +
                                     test::shell_quote((d / "canyon.obj").string()) + " 2>&1");
  ASSERT_EQ(gen.exit_code, 0) << gen.out;
  const std::string base =
      "truth:\n  source: line\n  line: {heading_deg: 0, length_m: 100, speed_mps: 2, passes: 2}\n"
      "  position: {lat_deg: 32.3, lon_deg: -90.9, h_m: 61.5}\n";
  std::ofstream(d / "open.yaml") << base;
  std::ofstream(d / "canyon.yaml") << base << "gnss:\n  scene: {obj: canyon.obj, origin: {lat_deg: 32.3, "
                                              "lon_deg: -90.9, h_m: 60}}\n";
  std::ofstream(d / "missing.yaml") << base << "gnss:\n  scene: {obj: nowhere.obj}\n";
  ASSERT_EQ(simulate(d / "open.yaml", d / "open", 60).exit_code, 0);
  const auto r1 = simulate(d / "canyon.yaml", d / "c1", 60);
  ASSERT_EQ(r1.exit_code, 0) << r1.out;
  EXPECT_NE(r1.out.find("navemu: scene "), std::string::npos) << r1.out;
  ASSERT_EQ(simulate(d / "canyon.yaml", d / "c2", 60).exit_code, 0);
  for (const char* f : {"nmea.log", "gnss.csv"}) EXPECT_EQ(slurp(d / "c1" / f), slurp(d / "c2" / f)) << f;

  const test::CsvTable open(d / "open" / "gnss.csv");
  const test::CsvTable canyon(d / "c1" / "gnss.csv");
  ASSERT_EQ(open.size(), canyon.size());
  double open_sats = 0, canyon_sats = 0;
  for (std::size_t i = 0; i < open.size(); ++i) {
    open_sats += open.num(i, "num_tracked");
    canyon_sats += canyon.num(i, "num_tracked");
  }
  EXPECT_LT(canyon_sats, 0.8 * open_sats);

  const auto bad = simulate(d / "missing.yaml", d / "bad", 10);
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.out.find("nowhere.obj"), std::string::npos) << bad.out;
}

// The ready u-blox scenarios offline: the circle goes on forever, as in configs/default.yaml
// (past the 8 loops, 462 s, of the circle's own default), and ubx.bin holds the UBX a logging
// client would enable (NAV-PVT, NAV-SAT, RXM-RAWX, RXM-SFRBX every epoch) beside the power-up
// NMEA. RTKLIB's convbin, an independent decoder, turns it into observations and ephemerides.
TEST(Simulate, UbloxScenariosDriveForeverAndWriteUbxIntoUbxBin) {
  const std::string convbin = test::find_program("convbin");
  for (const char* scenario : {"ublox-m8", "ublox-f9p"}) {
    SCOPED_TRACE(scenario);
    const fs::path out = temp_dir(std::string("ublox-") + scenario);
    const test::CommandResult r =
        simulate(fs::path(NAVEMU_SOURCE_DIR) / "configs" / (std::string(scenario) + ".yaml"), out, 600);
    ASSERT_EQ(r.exit_code, 0) << r.out;
    EXPECT_NE(r.out.find("circle r 9.144 m at 1 m/s, forever"), std::string::npos) << r.out;
    // Still moving at 1 m/s after 500 s.
    const test::CsvTable truth(out / "truth.csv");
    ASSERT_GT(truth.size(), 589u);
    for (std::size_t i = 499; i < truth.size(); i += 10)  // 4 decimals
      EXPECT_NEAR(std::hypot(truth.num(i, "v_n_mps"), truth.num(i, "v_e_mps")), 1.0, 1e-3) << truth(i, "time_s");

    // UBX frames by class and id (u-blox 8 / F9 interface descriptions: sync B5 62, class,
    // id, little-endian length, payload, 2-byte checksum).
    const std::string bin = slurp(out / "ubx.bin");
    std::map<std::pair<int, int>, int> count;
    for (std::size_t i = bin.find("\xb5\x62"); i != std::string::npos && i + 6 <= bin.size();
         i = bin.find("\xb5\x62", i + 1)) {
      const auto u8 = [&](std::size_t k) { return static_cast<unsigned char>(bin[i + k]); };
      ++count[{u8(2), u8(3)}];
      i += 6u + static_cast<std::size_t>(u8(4) | u8(5) << 8) + 1u;
    }
    EXPECT_EQ((count[{0x01, 0x07}]), 600) << "NAV-PVT";
    EXPECT_EQ((count[{0x01, 0x35}]), 600) << "NAV-SAT";
    EXPECT_EQ((count[{0x02, 0x15}]), 600) << "RXM-RAWX";
    EXPECT_GE((count[{0x02, 0x13}]), 100) << "RXM-SFRBX";
    EXPECT_NE(bin.find("$GNGGA"), std::string::npos) << "the power-up NMEA (several systems: GN)";
    if (convbin.empty()) continue;
    const test::CommandResult c = test::run_command(
        test::shell_quote(convbin) + " -r ubx -v 3.04 -o " + test::shell_quote((out / "ubx.obs").string()) +
        " -n " + test::shell_quote((out / "ubx.nav").string()) + " " + test::shell_quote((out / "ubx.bin").string()) +
        " 2>&1");
    EXPECT_EQ(c.exit_code, 0) << c.out;
    const std::string obs = slurp(out / "ubx.obs"), nav = slurp(out / "ubx.nav");
    std::size_t epochs = 0;
    for (std::size_t at = obs.find("\n> "); at != std::string::npos; at = obs.find("\n> ", at + 1)) ++epochs;
    EXPECT_GE(epochs, 590u) << c.out;
    EXPECT_NE(nav.find("END OF HEADER"), std::string::npos);
    EXPECT_GT(nav.size(), 2000u) << "no ephemerides decoded from RXM-SFRBX";
    // Every system the part tracks by default has its ephemerides rebuilt from the RXM-SFRBX
    // it sends: LNAV subframes, GLONASS strings, and on the F9P Galileo I/NAV pages and
    // BeiDou D1/D2 subframes (no QZSS above this site in 2010).
    const NavData records = test::rinex_nav_file(out / "ubx.nav");
    EXPECT_GE(records.gps.size(), 6u);
    EXPECT_GE(records.glonass.size(), 4u);
    const bool f9p = std::string(scenario) == "ublox-f9p";
    EXPECT_GE(records.galileo.size(), f9p ? 4u : 0u);
    EXPECT_GE(records.beidou.size(), f9p ? 4u : 0u);
    std::printf("%s: RTKLIB rebuilt %zu GPS, %zu GLONASS, %zu Galileo, %zu BeiDou ephemerides from RXM-SFRBX\n",
                scenario, records.gps.size(), records.glonass.size(), records.galileo.size(), records.beidou.size());
  }
}

TEST(Simulate, RejectsAStreamedTruth) {
  const fs::path dir = temp_dir("udp");
  const fs::path cfg = dir / "udp.yaml";
  std::ofstream(cfg) << "truth:\n  source: udp\n  udp: {port: 0}\n";
  const auto r = simulate(cfg, dir / "out", 10);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.out.find("simulate needs a generator or a CSV truth"), std::string::npos) << r.out;
}

// Every RXM-SFRBX subframe in a u-blox byte stream, by PRN in the order sent.
std::map<int, std::vector<lnav::LnavSubframe>> sfrbx_subframes(const std::string& bytes) {
  std::map<int, std::vector<lnav::LnavSubframe>> out;
  ubx::Parser parser(65535);
  const auto* p = reinterpret_cast<const std::uint8_t*>(bytes.data());
  parser.feed(std::span<const std::uint8_t>(p, bytes.size()), [&](ubx::Parser::Result r) {
    ubx::RxmSfrbx m;
    if (r != ubx::Parser::Result::kFrame || ubx::MsgId{parser.cls(), parser.id()} != ubx::kRxmSfrbx ||
        !ubx::decode(parser.payload(), m) || m.words.size() != 10)
      return;
    lnav::LnavSubframe words{};
    std::copy(m.words.begin(), m.words.end(), words.begin());
    out[m.sv_id].push_back(words);
  });
  return out;
}

// The built-in constellation over more than a day (30 h; the data made for the start alone
// last 29 h): a u-blox M8 sending RXM-SFRBX keeps its 3D fix at every epoch, and its subframes
// decode (parity, and the IODC/IODE of subframes 1-3 agreeing: no data set cutover inside a
// frame, IS-GPS-200 20.3.4.4) into data sets uploaded every 2 h: each PRN's IODE goes up by one
// per upload, and a set is sent from 1 h before its toe to 1 h after.
TEST(Simulate, BuiltInConstellationKeepsAFixForThirtyHoursWithNewUploads) {
  const fs::path d = temp_dir("30h");
  std::string profile = slurp(fs::path(NAVEMU_SOURCE_DIR) / "configs" / "gnss" / "ublox-m8.yaml");
  profile = std::regex_replace(profile, std::regex(R"(\n  messages: \{\}[^\n]*)"), "\n  messages: {RXM-SFRBX: 1}");
  profile = std::regex_replace(profile, std::regex(R"(\n  nmea_out: true)"), "\n  nmea_out: false");
  ASSERT_NE(profile.find("{RXM-SFRBX: 1}"), std::string::npos);
  ASSERT_NE(profile.find("nmea_out: false"), std::string::npos);
  std::ofstream(d / "m8.yaml") << profile;
  std::ofstream(d / "30h.yaml") << "truth: {source: stationary, position: {lat_deg: 32.3, lon_deg: -90.9, h_m: 60}}\n"
                                   "gnss: {profile: '" << (d / "m8.yaml").string() << "', outputs: []}\n"
                                   "imu: {enabled: false}\n";
  const auto r = simulate(d / "30h.yaml", d / "out", 108000);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("108000 GNSS epochs (108000 with a fix)"), std::string::npos) << r.out;
  const test::CsvTable gnss(d / "out" / "gnss.csv");
  ASSERT_EQ(gnss.size(), 108000u);
  int fixes = 0;
  for (std::size_t i = 0; i < gnss.size(); ++i) fixes += gnss(i, "fix") == "3";
  EXPECT_EQ(fixes, 108000);

  int frames = 0, failed = 0, uploads = 0;
  std::set<int> iodes;
  double max_from_toe_s = 0.0;
  for (const auto& [prn, subframes] : sfrbx_subframes(slurp(d / "out" / "ubx.bin"))) {
    std::optional<lnav::LnavEphemeris> last;
    std::uint32_t last_tow = 0;
    for (std::size_t i = 0; i + 2 < subframes.size(); ++i) {
      const lnav::LnavTlmHow how = lnav::decode_tlm_how(subframes[i]);
      if (how.subframe_id != 1 || lnav::decode_tlm_how(subframes[i + 2]).tow_count != how.tow_count + 2)
        continue;  // not the start of a whole frame
      ++frames;
      const auto eph = lnav::decode_ephemeris(subframes[i], subframes[i + 1], subframes[i + 2], 1610);
      if (!eph) {
        ++failed;
        continue;
      }
      iodes.insert(eph->iode);
      // The frame began 6 s before subframe 1's HOW count (the next subframe's start).
      const double frame_tow_s = 6.0 * (how.tow_count - 1);
      max_from_toe_s = std::max(max_from_toe_s, std::abs(frame_tow_s - eph->toe_s));
      if (last && eph->iode != last->iode) {
        ++uploads;
        EXPECT_EQ(eph->toe_s - last->toe_s, 7200.0 * ((eph->iode - last->iode + 256) % 256)) << "PRN " << prn;
        if (how.tow_count - last_tow < 7200 / 6) {  // seen without a gap: the next upload
          EXPECT_EQ(eph->iode, (last->iode + 1) % 256) << "PRN " << prn;
        }
      }
      last = eph;
      last_tow = how.tow_count;
    }
  }
  EXPECT_GT(frames, 10000);  // ~9 satellites, a frame every 30 s
  EXPECT_EQ(failed, 0);
  // From 13:00 to 19:00 the next day: the sets with toe 14:00 (taken from 13:00, midway to the
  // one of 12:00) to 18:00, every 2 h.
  EXPECT_EQ(iodes.size(), 15u);
  EXPECT_GT(uploads, 100);
  EXPECT_LE(max_from_toe_s, 3600.0);
  std::printf("[ 30 h ] %d frames decoded, %zu IODEs, %d uploads seen, max |frame - toe| %.0f s\n",
              frames, iodes.size(), uploads, max_from_toe_s);
}

}  // namespace
}  // namespace navemu
