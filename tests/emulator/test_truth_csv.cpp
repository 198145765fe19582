// Truth CSV files (emulator/truth_csv.hpp): bad input names file, line and column; the
// interpolation (cubic Hermite position and velocity, quaternion slerp) reproduces an analytic
// circle sampled at 10 Hz when evaluated at 200 Hz.

#include "emulator/truth_csv.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/errors.hpp"

namespace navemu {
namespace {

constexpr double kPi = 3.14159265358979323846;
const std::string kHeader =
    "time_s,lat_deg,lon_deg,h_m,v_n_mps,v_e_mps,v_d_mps,roll_deg,pitch_deg,yaw_deg\n";

std::string temp_file(const std::string& name, const std::string& content) {
  const auto p = std::filesystem::path(::testing::TempDir()) / name;
  std::ofstream(p) << content;
  return p.string();
}

// The message of the InputError that reading the whole file raises ("" when none).
std::string read_error(const std::string& name, const std::string& content) {
  const std::string file = temp_file(name, content);
  try {
    scan_truth_csv(file);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

const std::string kRow0 = "0,32.3,-90.9,60,0,0,0,0,0,0\n";
const std::string kRow1 = "0.1,32.3,-90.9,60,0,0,0,0,0,0\n";
const std::string kRow2 = "0.2,32.3,-90.9,60,0,0,0,0,0,0\n";

TEST(TruthCsv, BadInputNamesFileLineAndColumn) {
  auto expect_error = [](const std::string& name, const std::string& content,
                         const std::string& expected_tail) {
    const std::string msg = read_error(name, content);
    const std::string file = (std::filesystem::path(::testing::TempDir()) / name).string();
    EXPECT_EQ(msg, file + ":" + expected_tail) << name;
  };
  expect_error("missing_col.csv",
               "time_s,lat_deg,lon_deg,h_m,v_n_mps,v_e_mps,roll_deg,pitch_deg,yaw_deg\n",
               "1: v_d_mps: missing column (the header has: time_s,lat_deg,lon_deg,h_m,"
               "v_n_mps,v_e_mps,roll_deg,pitch_deg,yaw_deg)");
  expect_error("non_numeric.csv", kHeader + kRow0 + "0.1,abc,-90.9,60,0,0,0,0,0,0\n" + kRow2,
               "3: lat_deg: not a number: 'abc'");
  expect_error("nan.csv", kHeader + kRow0 + kRow1 + "0.2,32.3,-90.9,60,0,nan,0,0,0,0\n",
               "4: v_e_mps: not a finite number: 'nan'");
  expect_error("inf.csv", kHeader + kRow0 + "0.1,32.3,-90.9,60,0,0,0,0,-inf,0\n" + kRow2,
               "3: pitch_deg: not a finite number: '-inf'");
  expect_error("not_increasing.csv", kHeader + kRow0 + kRow1 + kRow1,
               "4: time_s: time 0.1 s does not increase (previous row 0.1 s)");
  expect_error("latitude.csv", kHeader + "0,91,-90.9,60,0,0,0,0,0,0\n" + kRow1 + kRow2,
               "2: lat_deg: latitude out of range (-90, 90): 91");
  expect_error("two_rows.csv", kHeader + kRow0 + kRow1,
               "3: fewer than 3 rows of truth (got 2); cubic interpolation needs at least 3");
  expect_error("short_row.csv", kHeader + kRow0 + "0.1,32.3,-90.9,60,0,0,0,0,0\n" + kRow2,
               "3: yaw_deg: missing value (the row has 9 fields)");
  expect_error("empty_cell.csv", kHeader + kRow0 + "0.1,32.3,-90.9,,0,0,0,0,0,0\n" + kRow2,
               "3: h_m: empty value");
  expect_error("partial_rates.csv",
               "time_s,lat_deg,lon_deg,h_m,v_n_mps,v_e_mps,v_d_mps,roll_deg,pitch_deg,yaw_deg,"
               "f_x_mps2,f_y_mps2,f_z_mps2\n",
               "1: w_x_radps: missing column (f_x_mps2..f_z_mps2 and w_x_radps..w_z_radps: all "
               "six or none)");
  expect_error("twice.csv", "time_s,lat_deg,lon_deg,h_m,v_n_mps,v_e_mps,v_d_mps,roll_deg,"
                            "pitch_deg,yaw_deg,h_m\n",
               "1: h_m: column named twice in the header");
  expect_error("empty.csv", "# nothing\n\n", "2: no header row");
  // Comments, blank lines, extra columns, '+' signs and column order are fine.
  EXPECT_EQ(read_error("fine.csv",
                       "# a truth file\n"
                       "yaw_deg,time_s,lat_deg,lon_deg,h_m,v_n_mps,v_e_mps,v_d_mps,roll_deg,"
                       "pitch_deg,speed_mps\n"
                       "0,0,32.3,-90.9,60,0,0,0,0,0,0\n\n"
                       "0,0.1,+32.3,-90.9,60,0,0,0,0,0,0\n"
                       "0,0.2,32.3,-90.9,60,0,0,0,0,0,0\n"),
            "");
  try {
    scan_truth_csv("/nonexistent/truth.csv");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "/nonexistent/truth.csv: cannot open for reading");
  }
}

TEST(TruthCsv, ReadsOptionalColumns) {
  const std::string file = temp_file(
      "rates.csv",
      "time_s,lat_deg,lon_deg,h_m,v_n_mps,v_e_mps,v_d_mps,roll_deg,pitch_deg,yaw_deg,"
      "f_x_mps2,f_y_mps2,f_z_mps2,w_x_radps,w_y_radps,w_z_radps,temperature_c\n"
      "0,10,20,30,1,2,3,4,5,6,0.1,0.2,-9.8,0.01,0.02,0.03,20\n"
      "1,10,20,30,1,2,3,4,5,6,0.3,0.2,-9.8,0.01,0.02,0.05,30\n"
      "2,10,20,30,1,2,3,4,5,6,0.3,0.2,-9.8,0.01,0.02,0.05,30\n");
  TruthCsvReader reader(file);
  EXPECT_TRUE(reader.has_rates());
  EXPECT_TRUE(reader.has_temperature());
  TruthRow row;
  ASSERT_TRUE(reader.next(row));
  EXPECT_EQ(row.position.lon_deg, 20.0);
  EXPECT_NEAR(row.rpy_rad.z(), 6.0 * kPi / 180.0, 1e-15);
  ASSERT_TRUE(row.w_ib_body_radps.has_value());
  EXPECT_EQ(row.w_ib_body_radps->z(), 0.03);
  EXPECT_EQ(row.temperature_c.value_or(0.0), 20.0);
  // Linear in between.
  TruthTrack track(file);
  const ImuTruth mid = track.at(0.25);
  ASSERT_TRUE(mid.f_body_mps2 && mid.w_ib_body_radps && mid.temperature_c);
  EXPECT_NEAR(mid.f_body_mps2->x(), 0.15, 1e-15);
  EXPECT_NEAR(mid.w_ib_body_radps->z(), 0.035, 1e-15);
  EXPECT_NEAR(*mid.temperature_c, 22.5, 1e-12);
}

// The paper's circle (9.144 m radius, 2 m/s, clockwise seen from above, level, heading tangent)
// laid out in the local north/east plane of the centre, as tools/make_circle_truth.py does.
struct Circle {
  double lat0_deg = 32.3, lon0_deg = -90.9, h_m = 60.0;
  double r_m = 9.144, v_mps = 2.0;
  double rn = meridian_radius_m(32.3) + 60.0;
  double re = transverse_radius_m(32.3) + 60.0;
  double omega() const { return v_mps / r_m; }
  Vec3 ne(double t) const {  // north, east offsets of the vehicle from the centre
    const double phi = omega() * t;
    return Vec3(r_m * std::cos(phi), r_m * std::sin(phi), 0.0);
  }
  Geodetic position(double t) const {
    const Vec3 p = ne(t);
    return Geodetic{lat0_deg + p.x() / rn * 180.0 / kPi,
                    lon0_deg + p.y() / (re * std::cos(lat0_deg * kPi / 180.0)) * 180.0 / kPi,
                    h_m};
  }
  Vec3 v_ned(double t) const {
    const double phi = omega() * t;
    return Vec3(-v_mps * std::sin(phi), v_mps * std::cos(phi), 0.0);
  }
  double yaw(double t) const { return omega() * t + kPi / 2.0; }
};

TEST(TruthCsv, HermiteAndSlerpReproduceACircle) {
  const Circle c;
  std::string text = kHeader;
  const int rows = 300;  // 30 s at 10 Hz, about one loop
  for (int k = 0; k < rows; ++k) {
    const double t = k / 10.0;
    const Geodetic p = c.position(t);
    const Vec3 v = c.v_ned(t);
    double yaw_deg = c.yaw(t) * 180.0 / kPi;
    yaw_deg -= 360.0 * std::floor((yaw_deg + 180.0) / 360.0);
    text += fmt::format("{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},0,0,{:.17g}\n", t,
                        p.lat_deg, p.lon_deg, p.h_m, v.x(), v.y(), v.z(), yaw_deg);
  }
  const std::string file = temp_file("circle.csv", text);
  TruthTrack track(file);
  double max_pos_m = 0.0, max_vel_mps = 0.0, max_att_rad = 0.0;
  const int n = (rows - 1) * 20;  // 200 Hz over the span
  for (int i = 0; i <= n; ++i) {
    const double t = i / 200.0;
    const ImuTruth got = track.at(t);
    const Geodetic want = c.position(t);
    const double dn = (got.position.lat_deg - want.lat_deg) * kPi / 180.0 * c.rn;
    const double de = (got.position.lon_deg - want.lon_deg) * kPi / 180.0 * c.re *
                      std::cos(c.lat0_deg * kPi / 180.0);
    const double dd = got.position.h_m - want.h_m;
    max_pos_m = std::max(max_pos_m, std::sqrt(dn * dn + de * de + dd * dd));
    max_vel_mps = std::max(max_vel_mps, (got.v_ned_mps - c.v_ned(t)).norm());
    const Quat q_want = quat_from_euler_rpy(Vec3(0.0, 0.0, c.yaw(t)));
    max_att_rad = std::max(
        max_att_rad, rotation_vector_from_quat(q_want.conjugate() * got.q_ned_from_body).norm());
  }
  RecordProperty("max_position_error_m", fmt::format("{:.3g}", max_pos_m));
  RecordProperty("max_velocity_error_mps", fmt::format("{:.3g}", max_vel_mps));
  RecordProperty("max_attitude_error_rad", fmt::format("{:.3g}", max_att_rad));
  std::printf(
      "circle at 200 Hz from 10 Hz: position %.3g m, velocity %.3g m/s, attitude %.3g rad\n",
      max_pos_m, max_vel_mps, max_att_rad);
  EXPECT_LT(max_pos_m, 1e-3);
  EXPECT_LT(max_att_rad, 1e-6);
  EXPECT_LT(max_vel_mps, 1e-4);
}

TEST(TruthCsv, UnwrapsLongitudeAcrossTheAntimeridian) {
  const std::string file = temp_file("dateline.csv",
                                     kHeader + "0,0,179.99995,0,0,10,0,0,0,90\n"
                                               "1,0,-179.99996,0,0,10,0,0,0,90\n"
                                               "2,0,-179.99987,0,0,10,0,0,0,90\n");
  TruthTrack track(file);
  const ImuTruth mid = track.at(0.5);
  EXPECT_GT(std::abs(mid.position.lon_deg), 179.999);
  const ImuTruth later = track.at(1.5);
  EXPECT_NEAR(later.position.lon_deg, -179.999915, 1e-5);
}

}  // namespace
}  // namespace navemu
