// The IMU's CAN frames without kernel CAN: python-can (Debian's python3-can 4.1,
// interface="slcan") reads navemu's slcan pty as it would a USB-CAN adapter, and every frame
// it receives decodes to the sample navemu logged. The configuration asks for a SocketCAN
// interface that does not exist, with an slcan fallback, as configs/default.yaml does for
// vcan0 on hosts without it.

#include <gtest/gtest.h>

#include <fmt/format.h>

#include "tests/can_capture.hpp"
#include "tests/clients/client_support.hpp"

namespace navemu::test::clients {
namespace {

// python-can (tests/clients/slcan_capture.py) reads navemu's slcan pty `link` for `seconds` into
// dir/python.log once navemu has opened it; `frames` are those up to the last whole sample
// (python-can stops reading at a time, not at a sample's end).
void capture_with_python_can(const TempDir& dir, const fs::path& link, NavemuRun& nav, const char* seconds,
                             std::vector<LoggedFrame>& frames) {
  ASSERT_TRUE(wait_until([&] { return fs::exists(link) && nav.err().find("CAN frames on slcan") != std::string::npos; }, 10.0))
      << nav.diagnostics();
  const fs::path script = fs::path(NAVEMU_SOURCE_DIR) / "tests" / "clients" / "slcan_capture.py";
  Child py({"/usr/bin/python3", script.string(), link.string(), (dir / "python.log").string(), seconds},
           dir / "python.stdout", dir / "python.stderr");
  const auto py_status = py.wait_exit(30.0);
  ASSERT_TRUE(py_status && WIFEXITED(*py_status) && WEXITSTATUS(*py_status) == 0)
      << describe_status(py_status) << "\n" << slurp(dir / "python.stderr");
  frames = read_candump_log(dir / "python.log");
  const can::highres::Config hr;
  while (!frames.empty() && frames.back().id != hr.base_id + can::highres::kOffsetStatus) frames.pop_back();
}

TEST(CanSlcan, PythonCanReceivesEverySampleAndItDecodesToTheLoggedValues) {
  if (!fs::exists("/usr/lib/python3/dist-packages/can"))
    GTEST_SKIP() << "python3-can is not installed (tools/install-deps)";
  TempDir dir("slcan");
  const fs::path link = dir / "imu";
  NavemuRun nav(dir, "navemu",
                fmt::format("gnss: {{enabled: false}}\n"
                            "imu:\n  log: '{}'\n  outputs:\n"
                            "    - {{type: socketcan, interface: navemu-none0, layouts: [j1939, highres],\n"
                            "       fallback: {{type: slcan, link: '{}'}}}}\n",
                            (dir / "imu.log").string(), link.string()),
                60);
  std::vector<LoggedFrame> frames;
  capture_with_python_can(dir, link, nav, "5", frames);
  nav.stop_expecting_exit_0();
  if (HasFatalFailure()) return;
  EXPECT_NE(nav.err().find("CAN frames go to slcan on pty"), std::string::npos) << nav.diagnostics();
  const std::vector<ImuRow> rows = read_imu_rows(dir / "imu.log");
  const CanCheck c = check_frames_against_log(frames, rows);
  fmt::print("python-can received {} samples ({} frames); J1939 max error {:.2e} rad/s, "
             "{:.2e} m/s^2; high resolution {:.2e} rad/s, {:.2e} m/s^2\n",
             c.samples, frames.size(), c.max_rate_err_radps, c.max_accel_err_mps2,
             c.max_hr_rate_err_radps, c.max_hr_accel_err_mps2);
  // 5 s at 125 Hz, less python-can's start-up: hundreds of samples, none missing in between.
  EXPECT_GE(c.samples, 400u);
  EXPECT_LE(c.samples, 640u);
  EXPECT_EQ(c.ari, c.samples);
  EXPECT_EQ(c.accs, c.samples);
  EXPECT_EQ(c.highres, c.samples);
  EXPECT_EQ(frames.size(), 7 * c.samples);
  EXPECT_EQ(c.last_time_ns - c.first_time_ns, static_cast<std::int64_t>(c.samples - 1) * 8'000'000);
  EXPECT_EQ(c.mismatches, 0u) << c.first_problem;
}

// IMU faults of `events:` (issue "impairments") as python-can sees them: a gyroscope bias step,
// an accelerometer axis stuck and a stretch of lost samples, each from its scheduled time to
// its end within one sample period (8 ms at 125 Hz, plus the millisecond navemu prints), and
// what python-can received is what navemu logged.
TEST(CanSlcan, PythonCanSeesImuFaultsComeAndGoOnTime) {
  if (!fs::exists("/usr/lib/python3/dist-packages/can"))
    GTEST_SKIP() << "python3-can is not installed (tools/install-deps)";
  TempDir dir("slcan-faults");
  const fs::path link = dir / "imu";
  NavemuRun nav(dir, "navemu",
                fmt::format("truth: {{source: stationary}}\n"
                            "gnss: {{enabled: false}}\n"
                            "imu:\n  log: '{}'\n  outputs:\n"
                            "    - {{type: slcan, link: '{}', layouts: [highres]}}\n"
                            "events:\n"
                            "  - {{type: imu, start_s: 3, duration_s: 1, fault: bias, sensor: gyro, axis: z, bias_dps: 100}}\n"
                            "  - {{type: imu, start_s: 4.5, duration_s: 1, fault: stuck, sensor: accel, axis: x}}\n"
                            "  - {{type: imu, start_s: 6, duration_s: 0.5, fault: drop}}\n",
                            (dir / "imu.log").string(), link.string()),
                11);
  std::vector<LoggedFrame> frames;
  capture_with_python_can(dir, link, nav, "8", frames);
  if (HasFatalFailure()) return;
  const auto nav_status = nav.child().wait_exit(20.0);
  ASSERT_TRUE(nav_status && WIFEXITED(*nav_status) && WEXITSTATUS(*nav_status) == 0) << nav.diagnostics();

  const std::string err = nav.err();
  const auto bias = announced_event_start(err, "IMU bias step, gyroscope z, 100 deg/s");
  const auto stuck = announced_event_start(err, "IMU stuck output, accelerometer x");
  const auto drop = announced_event_start(err, "IMU samples dropped, probability 1");
  ASSERT_TRUE(bias && stuck && drop) << nav.diagnostics();
  const std::int64_t bias_ns = bias->ns, stuck_ns = stuck->ns, drop_ns = drop->ns;
  const std::vector<ImuRow> rows = read_imu_rows(dir / "imu.log");
  const CanCheck c = check_frames_against_log(frames, rows);
  EXPECT_EQ(c.mismatches, 0u) << c.first_problem;
  ASSERT_GE(c.samples, 700u) << "8 s at 125 Hz, less the lost half second and python-can's start";
  ASSERT_LE(c.first_time_ns, bias_ns - 500'000'000) << "python-can was reading before the first fault";
  ASSERT_GE(c.last_time_ns, drop_ns + 1'000'000'000) << "and after the last";

  constexpr std::int64_t kTol_ns = 8'000'000 + 1'000'000;  // a sample period + the printed ms
  constexpr double kDeg = 3.14159265358979323846 / 180.0;
  const auto seconds = [](std::int64_t ns) { return static_cast<double>(ns) * 1e-9; };
  // Gyroscope z in the half second before the step: the baseline (stationary) and its noise.
  std::vector<double> before;
  for (const ImuRow& r : rows)
    if (r.gps_time_ns >= bias_ns - 500'000'000 && r.gps_time_ns < bias_ns - kTol_ns) before.push_back(r.w_radps[2]);
  ASSERT_GT(before.size(), 50u);
  double base = 0.0, sigma = 0.0;
  for (double w : before) base += w / static_cast<double>(before.size());
  for (double w : before) sigma += (w - base) * (w - base) / static_cast<double>(before.size() - 1);
  sigma = std::sqrt(sigma);
  ASSERT_LT(6.0 * sigma, 50.0 * kDeg) << "the step stands out of the noise";
  std::int64_t first_shifted = -1, last_shifted = -1;
  std::optional<double> held;
  std::size_t stuck_rows = 0, after_stuck_moving = 0;
  std::int64_t before_gap = -1, after_gap = -1;
  int seq_before = 0, seq_after = 0;
  for (const ImuRow& r : rows) {
    const bool shifted = std::abs(r.w_radps[2] - base - 100.0 * kDeg) < 6.0 * sigma;
    if (shifted) {
      if (first_shifted < 0) first_shifted = r.gps_time_ns;
      last_shifted = r.gps_time_ns;
    } else if (r.gps_time_ns > bias_ns + kTol_ns && r.gps_time_ns < bias_ns + 1'000'000'000 - kTol_ns) {
      ADD_FAILURE() << "gyroscope z without the bias step inside its window at " << seconds(r.gps_time_ns - bias_ns)
                    << " s: " << r.w_radps[2] / kDeg << " deg/s";
    }
    if (r.gps_time_ns < stuck_ns + 1'000'000) held = r.f_mps2[0];  // the last sample before it (stuck after it)
    if (r.gps_time_ns > stuck_ns + kTol_ns && r.gps_time_ns < stuck_ns + 1'000'000'000 - kTol_ns) {
      ++stuck_rows;
      EXPECT_EQ(r.f_mps2[0], held.value_or(-1.0)) << "accelerometer x moved while stuck";
    }
    if (held && r.gps_time_ns > stuck_ns + 1'000'000'000 + kTol_ns && r.f_mps2[0] != *held) ++after_stuck_moving;
  }
  // The gap: the longest time between consecutive logged samples. Not split at the announced
  // start, which is printed to the ms while the samples lie on the IMU's own 8 ms grid.
  for (std::size_t i = 1; i < rows.size(); ++i)
    if (rows[i].gps_time_ns - rows[i - 1].gps_time_ns > after_gap - before_gap) {
      before_gap = rows[i - 1].gps_time_ns;
      seq_before = rows[i - 1].sequence;
      after_gap = rows[i].gps_time_ns;
      seq_after = rows[i].sequence;
    }
  fmt::print("bias step seen from {:+.3f} s to {:+.3f} s of its window (1 s); accelerometer x held for {} samples; "
             "samples lost from {:+.3f} s to {:+.3f} s of the drop window (0.5 s), sequence {} -> {}\n",
             seconds(first_shifted - bias_ns), seconds(last_shifted - bias_ns), stuck_rows,
             seconds(before_gap - drop_ns), seconds(after_gap - drop_ns), seq_before, seq_after);
  EXPECT_LE(std::abs(first_shifted - bias_ns), kTol_ns);
  EXPECT_LE(std::abs(last_shifted - (bias_ns + 1'000'000'000)), kTol_ns);
  EXPECT_GE(stuck_rows, 120u);
  EXPECT_GT(after_stuck_moving, 100u) << "accelerometer x moves again after the fault";
  EXPECT_LE(std::abs(before_gap - drop_ns), kTol_ns);
  EXPECT_LE(std::abs(after_gap - (drop_ns + 500'000'000)), kTol_ns);
  EXPECT_EQ(seq_after - seq_before, (after_gap - before_gap) / 8'000'000) << "a gap in the sequence numbers";
  EXPECT_NE(err.find(fmt::format("{} dropped by a fault", (after_gap - before_gap) / 8'000'000 - 1)), std::string::npos)
      << nav.diagnostics();
}

// The other IMU faults as python-can sees them, on a BMI160 (its datasheet temperature
// coefficients; output at 100 Hz here): the accelerometer's z axis saturating at 5 m/s^2 (its
// saturation flag set), a 2 Hz sinusoidal vibration of 20 deg/s on gyroscope x, the part
// warming by 40 degC over a 1 s ramp (gyroscope bias 0.05 deg/s per degC: +2 deg/s), every
// sample sent twice for half a second, then a scale-factor error and added noise; each from its
// scheduled time to its end within one sample period (10 ms, plus the millisecond navemu
// prints), and python-can's frames decode to what navemu logged.
TEST(CanSlcan, PythonCanSeesSaturationVibrationTemperatureAndDuplicates) {
  if (!fs::exists("/usr/lib/python3/dist-packages/can"))
    GTEST_SKIP() << "python3-can is not installed (tools/install-deps)";
  TempDir dir("slcan-faults-2");
  std::string profile = slurp(fs::path(NAVEMU_SOURCE_DIR) / "configs" / "imu" / "bmi160.yaml");
  const std::size_t rate = profile.find("output_rate_hz: 200");
  ASSERT_NE(rate, std::string::npos);
  profile.replace(rate, 19, "output_rate_hz: 100");
  std::ofstream(dir / "bmi160-100hz.yaml") << profile;
  const fs::path link = dir / "imu";
  NavemuRun nav(dir, "navemu",
                fmt::format("truth: {{source: stationary}}\n"
                            "gnss: {{enabled: false}}\n"
                            "imu:\n  profile: '{}'\n  log: '{}'\n  outputs:\n"
                            "    - {{type: slcan, link: '{}', layouts: [highres]}}\n"
                            "events:\n"
                            "  - {{type: imu, start_s: 3, duration_s: 1, fault: saturation, sensor: accel, axis: z, range_mps2: 5}}\n"
                            "  - {{type: imu, start_s: 4.5, duration_s: 1.5, fault: vibration, sensor: gyro, axis: x, "
                            "amplitude_dps: 20, frequency_hz: 2}}\n"
                            "  - {{type: imu, start_s: 6.5, duration_s: 2.5, ramp_s: 1, fault: temperature, temperature_c: 40}}\n"
                            "  - {{type: imu, start_s: 9.2, duration_s: 0.5, fault: duplicate}}\n"
                            "  - {{type: imu, start_s: 10.2, duration_s: 1, fault: scale, sensor: accel, axis: z, "
                            "scale_ppm: 20000}}\n"
                            "  - {{type: imu, start_s: 10.2, duration_s: 1, fault: noise, sensor: gyro, axis: x, "
                            "noise_radps_per_rthz: 0.01}}\n",
                            (dir / "bmi160-100hz.yaml").string(), (dir / "imu.log").string(), link.string()),
                15);
  std::vector<LoggedFrame> frames;
  capture_with_python_can(dir, link, nav, "12", frames);
  if (HasFatalFailure()) return;
  const auto nav_status = nav.child().wait_exit(20.0);
  ASSERT_TRUE(nav_status && WIFEXITED(*nav_status) && WEXITSTATUS(*nav_status) == 0) << nav.diagnostics();
  const std::string err = nav.err();
  const auto saturation = announced_event_start(err, "IMU saturation, accelerometer z, range 5 m/s\\^2");
  const auto vibration = announced_event_start(err, "IMU vibration, gyroscope x, 20 deg/s at 2 Hz");
  const auto warm = announced_event_start(err, "IMU temperature change");
  const auto twice = announced_event_start(err, "IMU samples sent twice, probability 1");
  const auto scale = announced_event_start(err, "IMU scale-factor error, accelerometer z, 20000 ppm");
  const auto noise = announced_event_start(err, "IMU added noise, gyroscope x");
  ASSERT_TRUE(saturation && vibration && warm && twice && scale && noise) << nav.diagnostics();
  const CanCheck c = check_frames_against_log(frames, read_imu_rows(dir / "imu.log"));
  EXPECT_EQ(c.mismatches, 0u) << c.first_problem;

  // The samples python-can received, decoded: five classic frames from TIME to STATUS.
  std::vector<can::highres::Decoded> got;
  std::vector<can::CanFrame> group;
  const can::highres::Config hr;
  for (const LoggedFrame& f : frames) {
    const std::uint32_t offset = f.id - hr.base_id;
    if (offset == can::highres::kOffsetTime) group.clear();
    can::CanFrame cf;
    cf.id = f.id;
    cf.extended = f.extended;
    cf.len = static_cast<std::uint8_t>(f.data.size());
    std::copy(f.data.begin(), f.data.end(), cf.data.begin());
    group.push_back(cf);
    if (offset == can::highres::kOffsetStatus) {
      if (const auto d = can::highres::decode_classic(group, hr)) got.push_back(*d);
      group.clear();
    }
  }
  ASSERT_GE(got.size(), 1150u) << "12 s at 100 Hz, less python-can's start";
  ASSERT_LE(got.front().gps_time_ns, saturation->ns - 500'000'000) << "python-can was reading before the first fault";
  ASSERT_GE(got.back().gps_time_ns, scale->ns + 1'500'000'000) << "and after the last";

  constexpr std::int64_t kTol_ns = 10'000'000 + 1'000'000;  // a sample period + the printed ms
  constexpr double kDeg = 3.14159265358979323846 / 180.0;
  const auto inside = [&](const can::highres::Decoded& d, GpsTime start, double duration_s) {
    return d.gps_time_ns > start.ns + kTol_ns && d.gps_time_ns < start.ns + std::llround(duration_s * 1e9) - kTol_ns;
  };
  const auto outside = [&](const can::highres::Decoded& d, GpsTime start, double duration_s) {
    return d.gps_time_ns < start.ns - kTol_ns || d.gps_time_ns > start.ns + std::llround(duration_s * 1e9) + kTol_ns;
  };
  const auto mean_between = [&](int axis, std::int64_t from_ns, std::int64_t to_ns) {
    double sum = 0.0;
    int n = 0;
    for (const auto& d : got)
      if (d.gps_time_ns >= from_ns && d.gps_time_ns < to_ns) {
        sum += d.w_body_radps[static_cast<std::size_t>(axis)];
        ++n;
      }
    return n ? sum / n : std::nan("");
  };
  // Saturation: |f_z| at 5 m/s^2 and the accelerometer flag (bit 2) in the window, ~g outside.
  std::size_t clipped = 0;
  for (const auto& d : got) {
    const bool flagged = (d.flags & 0x04) != 0;
    if (inside(d, *saturation, 1.0)) {
      ++clipped;
      EXPECT_NEAR(std::abs(d.f_body_mps2[2]), 5.0, 1e-6);
      EXPECT_TRUE(flagged);
    } else if (outside(d, *saturation, 1.0)) {
      EXPECT_GT(std::abs(d.f_body_mps2[2]), 9.0) << "gravity and the part's turn-on bias";
      EXPECT_FALSE(flagged);
    }
  }
  EXPECT_GE(clipped, 97u);
  // Vibration: gyroscope x less its mean of the second before, fitted with the 2 Hz sine and
  // cosine over the window: amplitude 20 deg/s in phase (+-2 %, the output filter's 80 Hz pole
  // shifts 2 Hz by 1.4 deg); after it, back to the baseline.
  const double base_x = mean_between(0, vibration->ns - 1'000'000'000, vibration->ns - kTol_ns);
  double ss = 0.0, sc = 0.0, s2 = 0.0, c2 = 0.0, worst_after = 0.0;
  for (const auto& d : got) {
    const double t_s = static_cast<double>(d.gps_time_ns - vibration->ns) * 1e-9;
    const double y = d.w_body_radps[0] - base_x, sn = std::sin(2.0 * 3.14159265358979323846 * 2.0 * t_s),
                 cs = std::cos(2.0 * 3.14159265358979323846 * 2.0 * t_s);
    if (inside(d, *vibration, 1.5)) {
      ss += y * sn;
      sc += y * cs;
      s2 += sn * sn;
      c2 += cs * cs;
    } else if (t_s > 1.5 + 0.011 && t_s < 2.0) {
      worst_after = std::max(worst_after, std::abs(y));
    }
  }
  const double in_phase_dps = ss / s2 / kDeg, quadrature_dps = sc / c2 / kDeg;
  EXPECT_NEAR(in_phase_dps, 20.0, 0.4);
  EXPECT_NEAR(quadrature_dps, 0.0, 1.0);  // the filter's 1.4 deg and the printed ms's 0.7 deg
  EXPECT_LT(worst_after, 1.0 * kDeg) << "the vibration stopped";
  // Temperature: gyroscope y's bias follows 0.05 deg/s per degC x 40 degC x level: half way up
  // the ramp +1 deg/s, on the plateau (1 s to 1.5 s) +2 deg/s, after the end back.
  const std::int64_t w0 = warm->ns;
  const double base_y = mean_between(1, w0 - 1'000'000'000, w0 - kTol_ns);
  const double mid_ramp = mean_between(1, w0 + 350'000'000, w0 + 650'000'000) - base_y;
  const double plateau = mean_between(1, w0 + 1'100'000'000, w0 + 1'450'000'000) - base_y;
  const double after = mean_between(1, w0 + 2'600'000'000, w0 + 2'900'000'000) - base_y;
  EXPECT_NEAR(mid_ramp / kDeg, 1.0, 0.1);
  EXPECT_NEAR(plateau / kDeg, 2.0, 0.1);
  EXPECT_NEAR(after / kDeg, 0.0, 0.1);
  // Duplicates: the same sequence number twice in a row, only inside the window.
  std::size_t doubled = 0;
  for (std::size_t i = 1; i < got.size(); ++i)
    if (got[i].sequence == got[i - 1].sequence) {
      ++doubled;
      EXPECT_EQ(got[i].gps_time_ns, got[i - 1].gps_time_ns);
      EXPECT_FALSE(outside(got[i], *twice, 0.5)) << "sent twice at " << static_cast<double>(got[i].gps_time_ns - twice->ns) * 1e-9 << " s";
    }
  EXPECT_NEAR(static_cast<double>(doubled), 50.0, 1.0);
  // Scale factor and added noise, 1 s each: accelerometer z's mean x 1.02 (its noise is
  // 0.014 m/s^2 per sample), gyroscope x's standard deviation sqrt(0.05^2 + 0.01^2 x 100) ~ 0.1
  // rad/s against ~0.001 before; after it, both back.
  const auto stats = [&](int axis, bool gyro, std::int64_t from_ns, std::int64_t to_ns) {
    double sum = 0.0, sum2 = 0.0;
    int n = 0;
    for (const auto& d : got)
      if (d.gps_time_ns >= from_ns && d.gps_time_ns < to_ns) {
        const double v = gyro ? d.w_body_radps[static_cast<std::size_t>(axis)] : d.f_body_mps2[static_cast<std::size_t>(axis)];
        sum += v;
        sum2 += v * v;
        ++n;
      }
    const double mean = sum / n;
    return std::pair<double, double>(mean, std::sqrt(std::max(0.0, sum2 / n - mean * mean)));
  };
  const std::int64_t s0 = scale->ns, n0 = noise->ns, kSecond = 1'000'000'000;
  const double fz_before = stats(2, false, s0 - kSecond / 2, s0 - kTol_ns).first;
  const double fz_during = stats(2, false, s0 + kTol_ns, s0 + kSecond - kTol_ns).first;
  const double fz_after = stats(2, false, s0 + kSecond + kTol_ns, s0 + kSecond + kSecond / 2).first;
  EXPECT_NEAR(fz_during / fz_before, 1.02, 0.002);
  EXPECT_NEAR(fz_after / fz_before, 1.0, 0.002);
  const double wx_before_sd = stats(0, true, n0 - kSecond / 2, n0 - kTol_ns).second;
  const double wx_during_sd = stats(0, true, n0 + kTol_ns, n0 + kSecond - kTol_ns).second;
  const double wx_after_sd = stats(0, true, n0 + kSecond + kTol_ns, n0 + kSecond + kSecond / 2).second;
  EXPECT_NEAR(wx_during_sd, 0.1, 0.02) << "0.01 rad/s/sqrt(Hz) at 100 Hz";
  EXPECT_LT(wx_before_sd, 0.01);
  EXPECT_LT(wx_after_sd, 0.01);
  fmt::print("scale 20000 ppm: accelerometer z x{:.4f}, then x{:.4f}; noise 0.01 rad/s/sqrt(Hz): gyroscope x sd {:.4f} "
             "rad/s (before {:.4f}, after {:.4f})\n",
             fz_during / fz_before, fz_after / fz_before, wx_during_sd, wx_before_sd, wx_after_sd);
  fmt::print("saturation: {} samples clipped at 5 m/s^2; vibration: {:.2f} deg/s in phase, {:.2f} in quadrature "
             "(20 deg/s at 2 Hz); temperature +40 degC: gyroscope y +{:.3f} deg/s half way up the ramp, "
             "+{:.3f} on the plateau, {:+.3f} after; {} samples sent twice\n",
             clipped, in_phase_dps, quadrature_dps, mid_ramp / kDeg, plateau / kDeg, after / kDeg, doubled);
  EXPECT_NE(err.find(fmt::format("{} sent twice by a fault", doubled)), std::string::npos) << nav.diagnostics();
}

}  // namespace
}  // namespace navemu::test::clients
