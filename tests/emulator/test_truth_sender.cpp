// tools/truth-sender: its datagrams (written hex-encoded by --dump instead of sent) decode with
// the emulator's decoder (protocols/truth_datagram.hpp), carry the trajectory asked for, the
// time base, sequence and time steps, and the faults asked for.

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "models/geodesy.hpp"
#include "models/imu_kinematics.hpp"
#include "protocols/truth_datagram.hpp"
#include "tests/test_support.hpp"

namespace navemu {
namespace {

namespace td = truth_datagram;

constexpr std::int64_t kGpsEpochUnix_s = 315'964'800;  // 1980-01-06T00:00:00Z
constexpr std::int64_t kLeap_s = 18;                    // GPS - UTC since 2017-01-01

bool have_python() { return test::run_command("python3 -c 'pass' 2>/dev/null").exit_code == 0; }

// Runs the sender with `args` (--quiet added) and returns its standard output's lines.
std::vector<std::string> sender(const std::string& args, int* exit_code = nullptr) {
  const std::string script = std::string(NAVEMU_SOURCE_DIR) + "/tools/truth-sender";
  const test::CommandResult r =
      test::run_command("python3 " + test::shell_quote(script) + " --quiet " + args);
  if (exit_code != nullptr) *exit_code = r.exit_code;
  std::vector<std::string> lines;
  std::istringstream in(r.out);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::vector<std::uint8_t> from_hex(const std::string& hex) {
  std::vector<std::uint8_t> out;
  for (std::size_t i = 0; i + 1 < hex.size(); i += 2)
    out.push_back(static_cast<std::uint8_t>(std::stoul(hex.substr(i, 2), nullptr, 16)));
  return out;
}

td::DecodeResult decode_hex(const std::string& hex, td::Message& m) {
  const std::vector<std::uint8_t> bytes = from_hex(hex);
  return td::decode_binary(bytes, m);
}

std::int64_t unix_now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

Quat quat(const td::Message& m) {
  return Quat(m.attitude[0], m.attitude[1], m.attitude[2], m.attitude[3]);
}

#define NAVEMU_REQUIRE_PYTHON()   \
  if (!have_python()) GTEST_SKIP() << "python3 not found: truth-sender test skipped"

TEST(TruthSender, CircleInGpsTimeDecodes) {
  NAVEMU_REQUIRE_PYTHON();
  const std::vector<std::string> lines =
      sender("--circle 32.3,-90.9,60 --radius 9.144 --speed 2 --count 5 --dump --gps-time");
  ASSERT_EQ(lines.size(), 5u);
  const std::int64_t gps_now_ns = unix_now_ns() + (kLeap_s - kGpsEpochUnix_s) * 1'000'000'000;
  const Geodetic center{32.3, -90.9, 60.0};
  std::int64_t first_ns = 0;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    EXPECT_EQ(lines[i].size(), 2 * td::kBinarySize) << i;
    td::Message m;
    ASSERT_EQ(decode_hex(lines[i], m), td::DecodeResult::kOk) << i << ": " << lines[i];
    EXPECT_EQ(m.sequence, i);
    EXPECT_EQ(m.time_base, td::TimeBase::kGps);
    if (i == 0) first_ns = m.time_ns;
    EXPECT_EQ(m.time_ns - first_ns, static_cast<std::int64_t>(i) * 20'000'000);  // 50 Hz
    EXPECT_EQ(m.position_frame, td::PositionFrame::kGeodetic);
    EXPECT_EQ(m.velocity_frame, td::VelocityFrame::kNed);
    EXPECT_EQ(m.attitude_form, td::AttitudeForm::kQuaternion);
    EXPECT_FALSE(m.has_rates);
    EXPECT_FALSE(m.has_temperature);
    // On the circle, near its southern point, starting from rest toward the east.
    const Geodetic p{m.position[0], m.position[1], m.position[2]};
    const Vec3 enu = enu_from_ecef(ecef_from_geodetic(p), center);
    EXPECT_NEAR(std::hypot(enu.x(), enu.y()), 9.144, 1e-3) << i;
    EXPECT_NEAR(enu.y(), -9.144, 1e-3) << i;
    EXPECT_EQ(p.h_m, 60.0);
    EXPECT_NEAR(m.velocity_mps[1], 0.5 * 0.02 * static_cast<double>(i), 1e-6) << i;  // a t
    EXPECT_NEAR(quat(m).norm(), 1.0, 1e-12);
    EXPECT_NEAR(euler_rpy_from_quat(quat(m)).z() * kRadToDeg, 90.0, 0.02) << i;
  }
  // Stamped with the host clock converted to GPS time: within a minute of now.
  EXPECT_LT(std::abs(first_ns - gps_now_ns), std::int64_t{60'000'000'000});
}

TEST(TruthSender, StationaryInHostUtcWithEulerAngles) {
  NAVEMU_REQUIRE_PYTHON();
  const std::vector<std::string> lines =
      sender("--stationary 48.1,11.6,520 --yaw 30 --euler --rate 100 --count 3 --dump");
  ASSERT_EQ(lines.size(), 3u);
  std::int64_t first_ns = 0;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    td::Message m;
    ASSERT_EQ(decode_hex(lines[i], m), td::DecodeResult::kOk) << i;
    EXPECT_EQ(m.time_base, td::TimeBase::kHostUtc);
    if (i == 0) first_ns = m.time_ns;
    EXPECT_EQ(m.time_ns - first_ns, static_cast<std::int64_t>(i) * 10'000'000);  // 100 Hz
    EXPECT_EQ(m.attitude_form, td::AttitudeForm::kRollPitchYaw);
    EXPECT_EQ(m.position, (std::array<double, 3>{48.1, 11.6, 520.0}));
    EXPECT_EQ(m.velocity_mps, (std::array<double, 3>{0.0, 0.0, 0.0}));
    EXPECT_EQ(m.attitude, (std::array<double, 4>{0.0, 0.0, 30.0, 0.0}));
  }
  EXPECT_LT(std::abs(first_ns - unix_now_ns()), std::int64_t{60'000'000'000});
}

TEST(TruthSender, CorruptsEveryNthCrc) {
  NAVEMU_REQUIRE_PYTHON();
  const std::vector<std::string> lines =
      sender("--stationary 10,20,30 --count 6 --dump --bad-every 3");
  ASSERT_EQ(lines.size(), 6u);
  for (std::size_t i = 0; i < lines.size(); ++i) {
    td::Message m;
    const td::DecodeResult r = decode_hex(lines[i], m);
    EXPECT_EQ(r, (i + 1) % 3 == 0 ? td::DecodeResult::kBadCrc : td::DecodeResult::kOk) << i;
    if (r == td::DecodeResult::kOk) {
      EXPECT_EQ(m.sequence, i);
    }
  }
}

TEST(TruthSender, JsonLinesDecode) {
  NAVEMU_REQUIRE_PYTHON();
  const std::vector<std::string> lines =
      sender("--circle -33.9,151.2,40 --json --gps-time --count 4 --bad-every 4 --dump");
  ASSERT_EQ(lines.size(), 4u);
  for (std::size_t i = 0; i < 3; ++i) {
    td::Message m;
    ASSERT_EQ(td::decode_json(lines[i], m), td::DecodeResult::kOk) << lines[i];
    EXPECT_EQ(m.sequence, i);
    EXPECT_EQ(m.time_base, td::TimeBase::kGps);
    EXPECT_NEAR(m.position[0], -33.9, 1e-3);
    EXPECT_NEAR(quat(m).norm(), 1.0, 1e-12);
  }
  td::Message m;
  EXPECT_NE(td::decode_json(lines[3], m), td::DecodeResult::kOk) << lines[3];
}

TEST(TruthSender, ReplaysACsvFileAtItsOwnTimes) {
  NAVEMU_REQUIRE_PYTHON();
  const auto file = std::filesystem::path(::testing::TempDir()) / "sender_truth.csv";
  std::ofstream(file) << "# a truth file\n"
                         "time_s,lat_deg,lon_deg,h_m,v_n_mps,v_e_mps,v_d_mps,roll_deg,pitch_deg,"
                         "yaw_deg,f_x_mps2,f_y_mps2,f_z_mps2,w_x_radps,w_y_radps,w_z_radps,"
                         "temperature_c\n"
                         "100.0,10,20,30,1,2,3,4,5,6,0.1,0.2,-9.8,0.01,0.02,0.03,20\n"
                         "\n"
                         "100.1,10.1,20,30,1,2,3,4,5,7,0.3,0.2,-9.8,0.01,0.02,0.05,21\n"
                         "100.35,10.2,20,30,1,2,3,4,5,8,0.3,0.2,-9.8,0.01,0.02,0.05,22\n";
  const std::vector<std::string> lines =
      sender("--csv " + test::shell_quote(file.string()) + " --gps-time --dump");
  ASSERT_EQ(lines.size(), 3u);
  std::vector<td::Message> m(3);
  for (std::size_t i = 0; i < 3; ++i) ASSERT_EQ(decode_hex(lines[i], m[i]), td::DecodeResult::kOk);
  EXPECT_EQ(m[1].time_ns - m[0].time_ns, 100'000'000);
  EXPECT_EQ(m[2].time_ns - m[0].time_ns, 350'000'000);
  EXPECT_EQ(m[1].position, (std::array<double, 3>{10.1, 20.0, 30.0}));
  EXPECT_EQ(m[0].velocity_mps, (std::array<double, 3>{1.0, 2.0, 3.0}));
  ASSERT_TRUE(m[1].has_rates && m[1].has_temperature);
  EXPECT_EQ(m[1].f_body_mps2, (std::array<double, 3>{0.3, 0.2, -9.8}));
  EXPECT_EQ(m[1].w_body_radps, (std::array<double, 3>{0.01, 0.02, 0.05}));
  EXPECT_EQ(m[2].temperature_c, 22.0);
  // The quaternion of the row's ZYX Euler angles.
  const Quat want = quat_from_euler_rpy(Vec3(4.0, 5.0, 7.0) * kDegToRad);
  EXPECT_LT(rotation_vector_from_quat(want.conjugate() * quat(m[1])).norm(), 1e-12);
}

TEST(TruthSender, PausesAndResumes) {
  NAVEMU_REQUIRE_PYTHON();
  // 10 Hz over [0, 2] s: 21 instants, silent over [0.5, 1.5) s.
  const std::vector<std::string> lines = sender(
      "--stationary 1,2,3 --rate 10 --duration 2 --pause-after 0.5 --pause-for 1 --dump");
  ASSERT_EQ(lines.size(), 11u);
  std::vector<std::int64_t> t;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    td::Message m;
    ASSERT_EQ(decode_hex(lines[i], m), td::DecodeResult::kOk);
    EXPECT_EQ(m.sequence, i);  // the sequence counts datagrams sent
    t.push_back(m.time_ns);
  }
  EXPECT_EQ(t[4] - t[0], 400'000'000);
  EXPECT_EQ(t[5] - t[0], 1'500'000'000);
  EXPECT_EQ(t[10] - t[0], 2'000'000'000);
}

TEST(TruthSender, HelpAndBadArguments) {
  NAVEMU_REQUIRE_PYTHON();
  int code = -1;
  const std::vector<std::string> help = sender("--help", &code);
  EXPECT_EQ(code, 0);
  std::string text;
  for (const std::string& l : help) text += l + "\n";
  for (const char* option : {"--circle", "--stationary", "--csv", "--rate", "--gps-time",
                             "--pause-after", "--bad-every", "--dump", "--json"})
    EXPECT_NE(text.find(option), std::string::npos) << option;
  sender("--circle 95,0,0 --count 1 --dump 2>/dev/null", &code);
  EXPECT_EQ(code, 2);
  sender("--stationary 0,0,0 --dump 2>/dev/null", &code);  // would never end
  EXPECT_EQ(code, 2);
}

}  // namespace
}  // namespace navemu
