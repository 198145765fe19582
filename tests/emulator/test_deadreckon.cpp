// navemu deadreckon, run in-process on small generated IMU files: stationary drift, gyro-only
// headings, bias removal, the error against a truth file, and bad input.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "emulator/cli.hpp"
#include "tests/emulator/cli_runner.hpp"
#include "models/imu_kinematics.hpp"

namespace navemu {
namespace {

using test::CliRun;
using test::navemu;

const Geodetic kSite{32.3, -90.9, 60.0};

std::string temp_path(const std::string& name) {
  return (std::filesystem::path(::testing::TempDir()) / name).string();
}

std::string write_temp(const std::string& name, const std::string& content) {
  const std::string p = temp_path(name);
  std::ofstream(p) << content;
  return p;
}

const char* kHeader = "time_s,f_x_mps2,f_y_mps2,f_z_mps2,w_x_radps,w_y_radps,w_z_radps,temperature_c\n";

// A stationary IMU file at kSite (level, facing north) with constant added errors.
std::string stationary_csv(const std::string& name, double rate_hz, double duration_s,
                           const Vec3& f_err = Vec3::Zero(), const Vec3& w_err = Vec3::Zero()) {
  const IdealImu imu = ideal_imu_static(kSite, Quat::Identity());
  std::ostringstream s;
  s.precision(17);
  s << kHeader;
  const long long n = std::llround(duration_s * rate_hz);
  for (long long k = 0; k <= n; ++k) {
    const Vec3 f = imu.f_body_mps2 + f_err, w = imu.w_ib_body_radps + w_err;
    s << static_cast<double>(k) / rate_hz << ',' << f.x() << ',' << f.y() << ',' << f.z() << ','
      << w.x() << ',' << w.y() << ',' << w.z() << ",25\n";
  }
  return write_temp(name, s.str());
}

struct Table {
  std::vector<std::string> columns;
  std::vector<std::vector<double>> rows;
  double at(std::size_t row, const std::string& col) const {
    const auto it = std::find(columns.begin(), columns.end(), col);
    EXPECT_NE(it, columns.end()) << col;
    if (it == columns.end()) return NAN;
    return rows.at(row).at(static_cast<std::size_t>(it - columns.begin()));
  }
};

Table read_table(const std::string& text) {
  Table t;
  std::istringstream in(text);
  std::string line;
  std::getline(in, line);
  std::stringstream h(line);
  for (std::string c; std::getline(h, c, ',');) t.columns.push_back(c);
  while (std::getline(in, line)) {
    std::stringstream ls(line);
    std::vector<double> row;
    for (std::string c; std::getline(ls, c, ',');) row.push_back(std::stod(c));
    EXPECT_EQ(row.size(), t.columns.size()) << line;
    t.rows.push_back(row);
  }
  return t;
}

Table read_table_file(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return read_table(ss.str());
}

TEST(Deadreckon, PerfectStationaryImuStaysPut) {
  const std::string in = stationary_csv("dr_perfect.csv", 125.0, 60.0);
  const std::string out = temp_path("dr_perfect_out.csv");
  const CliRun r = navemu({"deadreckon", in, "--out", out});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("attitude drift"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("position drift"), std::string::npos) << r.err;
  const Table t = read_table_file(out);
  const std::vector<std::string> expect = {"time_s", "roll_deg", "pitch_deg", "yaw_deg",
                                           "north_m", "east_m", "down_m", "v_n_mps",
                                           "v_e_mps", "v_d_mps"};
  EXPECT_EQ(t.columns, expect);
  ASSERT_EQ(t.rows.size(), 61u);  // one row per second (the default decimation), 0..60 s
  for (std::size_t i = 0; i < t.rows.size(); ++i) {
    EXPECT_NEAR(t.at(i, "time_s"), static_cast<double>(i), 1e-9);
    for (const char* c : {"roll_deg", "pitch_deg", "yaw_deg"}) EXPECT_NEAR(t.at(i, c), 0.0, 1e-8);
    for (const char* c : {"north_m", "east_m", "down_m"}) EXPECT_NEAR(t.at(i, c), 0.0, 1e-5);
    for (const char* c : {"v_n_mps", "v_e_mps", "v_d_mps"}) EXPECT_NEAR(t.at(i, c), 0.0, 1e-8);
  }
}

TEST(Deadreckon, GyroOnlyHeadingDriftsAtTheGyroBias) {
  // 3 deg/h on each gyroscope (the paper's Fig. 2/3 figure), 20 min at 10 Hz.
  const double b = 3.0 / 3600.0 * kDegToRad;
  const std::string in = stationary_csv("dr_gyro.csv", 10.0, 1200.0, Vec3::Zero(), Vec3(b, -b, b));
  const CliRun r = navemu({"deadreckon", in, "--gyro-only-heading", "--every", "6000"});
  ASSERT_EQ(r.code, 0) << r.err;
  const Table t = read_table(r.out);
  ASSERT_EQ(t.rows.size(), 3u);  // 0, 600 and 1200 s
  EXPECT_NEAR(t.at(2, "time_s"), 1200.0, 1e-9);
  EXPECT_NEAR(t.at(1, "heading_x_deg"), 0.5, 1e-9);
  EXPECT_NEAR(t.at(2, "heading_x_deg"), 1.0, 1e-9);
  EXPECT_NEAR(t.at(2, "heading_y_deg"), -1.0, 1e-9);
  EXPECT_NEAR(t.at(2, "heading_z_deg"), 1.0, 1e-9);
  EXPECT_NE(r.err.find("gyro-only heading drift: x 1.000000 deg (3.0000 deg/h), y -1.000000 deg "
                       "(-3.0000 deg/h), z 1.000000 deg (3.0000 deg/h)"),
            std::string::npos)
      << r.err;
  // The full strapdown solution tilts less: the Schuler loop bounds the tilt from a gyro bias
  // to b sin(w_s t) / w_s, w_s = sqrt(g / R) (Titterton & Weston section 12.3), 0.67 deg here.
  const double ws = std::sqrt(9.794 / 6.372e6);
  const double tilt_deg = 3.0 / 3600.0 * std::sin(ws * 1200.0) / ws;
  EXPECT_NEAR(t.at(2, "roll_deg"), tilt_deg, 0.06);
  EXPECT_NEAR(t.at(2, "pitch_deg"), -tilt_deg, 0.06);
}

TEST(Deadreckon, BiasRemovalCancelsConstantBiases) {
  const Vec3 fb(0.02, -0.03, 0.05);
  const Vec3 wb = Vec3(10.0, -20.0, 30.0) / 3600.0 * kDegToRad;
  const std::string in = stationary_csv("dr_bias.csv", 50.0, 120.0, fb, wb);
  const CliRun raw = navemu({"deadreckon", in, "--truth", "static"});
  ASSERT_EQ(raw.code, 0) << raw.err;
  const Table tr = read_table(raw.out);
  EXPECT_GT(std::abs(tr.at(tr.rows.size() - 1, "err_north_m")), 10.0);
  const CliRun fixed = navemu({"deadreckon", in, "--truth", "static", "--bias-removal", "10"});
  ASSERT_EQ(fixed.code, 0) << fixed.err;
  EXPECT_NE(fixed.err.find("bias over the first 10 s (500 samples)"), std::string::npos)
      << fixed.err;
  const Table t = read_table(fixed.out);
  const std::size_t last = t.rows.size() - 1;
  EXPECT_NEAR(t.at(last, "time_s"), 120.0, 1e-9);
  for (const char* c : {"err_north_m", "err_east_m", "err_down_m"}) EXPECT_NEAR(t.at(last, c), 0.0, 1e-4);
  for (const char* c : {"err_roll_deg", "err_pitch_deg", "err_yaw_deg"})
    EXPECT_NEAR(t.at(last, c), 0.0, 1e-8);
}

TEST(Deadreckon, ErrorAgainstATruthFile) {
  // An accelerometer bias of 0.01 m/s^2 forward on a level, north-facing IMU: after 20 s the
  // north error is b t^2 / 2 = 2 m (the Schuler and Coriolis terms change it by < 1e-3).
  const std::string truth = stationary_csv("dr_truth.csv", 100.0, 20.0);
  const std::string in = stationary_csv("dr_biased.csv", 100.0, 20.0, Vec3(0.01, 0.0, 0.0));
  const CliRun r = navemu({"deadreckon", in, "--truth", truth, "--every", "500",
                           "--at", "32.3,-90.9,60", "--initial-rpy", "0,0,0"});
  ASSERT_EQ(r.code, 0) << r.err;
  const Table t = read_table(r.out);
  ASSERT_EQ(t.rows.size(), 5u);  // 0, 5, 10, 15, 20 s
  EXPECT_EQ(t.columns.size(), 19u);
  EXPECT_NEAR(t.at(4, "err_north_m"), 2.0, 2e-3);
  EXPECT_NEAR(t.at(4, "north_m"), 2.0, 2e-3);
  EXPECT_NEAR(t.at(4, "err_v_n_mps"), 0.2, 2e-4);
  EXPECT_NEAR(t.at(2, "err_north_m"), 0.5, 1e-3);
  // Coriolis pushes the northward error east: (1/3) W sin(lat) b t^3 = 1.04 mm.
  EXPECT_NEAR(t.at(4, "err_east_m"), kOmegaEarth_radps * std::sin(kSite.lat_deg * kDegToRad) *
                                         0.01 * 8000.0 / 3.0,
              1e-4);

  // A truth at a different rate is interpolated between its samples.
  const std::string truth_slow = stationary_csv("dr_truth_slow.csv", 7.0, 30.0);
  const CliRun r2 = navemu({"deadreckon", in, "--truth", truth_slow, "--every", "500"});
  ASSERT_EQ(r2.code, 0) << r2.err;
  EXPECT_NEAR(read_table(r2.out).at(4, "err_north_m"), 2.0, 2e-3);
  // A truth shorter than the data is an error.
  const std::string truth_short = stationary_csv("dr_truth_short.csv", 100.0, 10.0);
  const CliRun r3 = navemu({"deadreckon", in, "--truth", truth_short});
  EXPECT_EQ(r3.code, 1);
  EXPECT_NE(r3.err.find("does not cover"), std::string::npos) << r3.err;
}

TEST(Deadreckon, StartPositionAndAttitudeOptions) {
  // A stationary file generated for a rolled IMU at another place integrates to rest only
  // when the same start and attitude are given.
  const Geodetic where{-45.0, 170.0, 1000.0};
  const Quat q = quat_from_euler_rpy(Vec3(10.0, -5.0, 200.0 - 360.0) * kDegToRad);
  const IdealImu imu = ideal_imu_static(where, q);
  std::ostringstream s;
  s.precision(17);
  s << kHeader;
  for (int k = 0; k <= 300; ++k)
    s << k * 0.1 << ',' << imu.f_body_mps2.x() << ',' << imu.f_body_mps2.y() << ','
      << imu.f_body_mps2.z() << ',' << imu.w_ib_body_radps.x() << ',' << imu.w_ib_body_radps.y()
      << ',' << imu.w_ib_body_radps.z() << ",20\n";
  const std::string in = write_temp("dr_rolled.csv", s.str());
  const CliRun r = navemu({"deadreckon", in, "--start-lat", "-45", "--start-lon", "170",
                           "--start-h", "1000", "--initial-rpy", "10,-5,200"});
  ASSERT_EQ(r.code, 0) << r.err;
  const Table t = read_table(r.out);
  const std::size_t last = t.rows.size() - 1;
  EXPECT_NEAR(t.at(last, "time_s"), 30.0, 1e-9);
  EXPECT_NEAR(t.at(last, "roll_deg"), 10.0, 1e-8);
  EXPECT_NEAR(t.at(last, "pitch_deg"), -5.0, 1e-8);
  EXPECT_NEAR(t.at(last, "yaw_deg"), -160.0, 1e-8);
  EXPECT_NEAR(t.at(last, "north_m"), 0.0, 1e-5);
  EXPECT_NEAR(t.at(last, "down_m"), 0.0, 1e-5);
  // At the default site the same file falls away.
  const CliRun wrong = navemu({"deadreckon", in, "--initial-rpy", "10,-5,200"});
  ASSERT_EQ(wrong.code, 0) << wrong.err;
  const Table tw = read_table(wrong.out);
  EXPECT_GT(std::abs(tw.at(tw.rows.size() - 1, "down_m")), 1.0);
}

TEST(Deadreckon, BadInputGivesOneLineErrors) {
  auto expect_error = [](const std::vector<std::string>& args, const std::string& needle) {
    const CliRun r = navemu(args);
    EXPECT_EQ(r.code, 1) << needle;
    EXPECT_NE(r.err.find(needle), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  };
  const std::string missing = temp_path("dr_does_not_exist.csv");
  expect_error({"deadreckon", missing}, missing + ": cannot open");
  const std::string nocol = write_temp("dr_nocol.csv", "time_s,f_x_mps2,f_y_mps2,f_z_mps2,w_x_radps,w_z_radps\n0,0,0,-9.8,0,0\n");
  expect_error({"deadreckon", nocol}, nocol + ":1: w_y_radps: missing column");
  const std::string text = write_temp("dr_text.csv", std::string(kHeader) + "0,0,0,-9.8,0,0,0,25\n0.1,0,abc,-9.8,0,0,0,25\n");
  expect_error({"deadreckon", text}, text + ":3: f_y_mps2: not a number: 'abc'");
  const std::string nan = write_temp("dr_nan.csv", std::string(kHeader) + "0,0,0,-9.8,0,0,0,25\n0.1,0,0,-9.8,nan,0,0,25\n");
  expect_error({"deadreckon", nan}, nan + ":3: w_x_radps: not a finite number: 'nan'");
  const std::string back = write_temp("dr_back.csv", std::string(kHeader) + "0,0,0,-9.8,0,0,0,25\n0.1,0,0,-9.8,0,0,0,25\n0.1,0,0,-9.8,0,0,0,25\n");
  expect_error({"deadreckon", back}, back + ":4: time_s: time 0.1 s does not increase");
  const std::string shortrow = write_temp("dr_short.csv", std::string(kHeader) + "0,0,0,-9.8,0,0\n");
  expect_error({"deadreckon", shortrow}, shortrow + ":2: w_z_radps: missing value");
  const std::string empty = write_temp("dr_empty.csv", std::string(kHeader));
  expect_error({"deadreckon", empty}, "no samples");
  const std::string ok = stationary_csv("dr_ok.csv", 10.0, 1.0);
  expect_error({"deadreckon", ok, "--initial-rpy", "1,2"}, "--initial-rpy");
  expect_error({"deadreckon", ok, "--at", "95,0,0"}, "--at");
  expect_error({"deadreckon", ok, "--truth", missing}, missing + ": cannot open");
  // Usage errors (CLI11) exit 2.
  EXPECT_EQ(navemu({"deadreckon"}).code, 2);
  EXPECT_EQ(navemu({"deadreckon", ok, "--every", "0"}).code, 2);
  EXPECT_EQ(navemu({"deadreckon", ok, "--bias-removal", "-1"}).code, 2);
}

}  // namespace
}  // namespace navemu
