// navemu allan, run in-process: the CSV of Allan deviations, the fitted terms in SI and
// datasheet units, the PNG plot, and the one-line errors bad input files must give.

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "emulator/cli.hpp"
#include "tests/emulator/cli_runner.hpp"
#include "models/random.hpp"
#include "tests/test_support.hpp"

namespace navemu {
namespace {

using test::CliRun;
using test::navemu;

std::string temp_path(const std::string& name) {
  std::string file = "allan_cli_";
  file += name;
  return (std::filesystem::path(::testing::TempDir()) / file).string();
}

std::string write_temp(const std::string& name, const std::string& content) {
  const std::string p = temp_path(name);
  std::ofstream(p) << content;
  return p;
}

constexpr const char* kHeader =
    "time_s,f_x_mps2,f_y_mps2,f_z_mps2,w_x_radps,w_y_radps,w_z_radps,temperature_c\n";

// A file as navemu imu writes it: white noise of density 0.002 m/s^2/sqrt(Hz) on the
// accelerometers (around (0, 0, -9.8)) and 1e-3 rad/s/sqrt(Hz) on the gyroscopes, 100 Hz.
constexpr double kAccelDensity = 0.002, kGyroDensity = 1e-3, kRateHz = 100.0;
std::string imu_csv(int rows) {
  RandomStream rng(5, stream_id("allan-cli"));
  const double dt = 1.0 / kRateHz;
  std::string s = kHeader;
  for (int k = 0; k < rows; ++k) {
    s += std::to_string(k * dt);
    for (int i = 0; i < 3; ++i)
    {
      s += ',';
      s += std::to_string((i == 2 ? -9.8 : 0.0) + kAccelDensity / std::sqrt(dt) * rng.normal());
    }
    for (int i = 0; i < 3; ++i) {
      s += fmt::format(",{:.9e}", kGyroDensity / std::sqrt(dt) * rng.normal());
    }
    s += ",25.0\n";
  }
  return s;
}

std::vector<std::string> lines_of(const std::string& s) {
  std::vector<std::string> out;
  std::istringstream in(s);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

// The first number after the second occurrence of `column` at a line start (the datasheet
// table), e.g. "w_x_radps  3.44 deg/sqrt(h) ...".
double datasheet_value(const std::string& out, const std::string& column) {
  int seen = 0;
  for (const std::string& l : lines_of(out))
    if (l.rfind(column + " ", 0) == 0 && ++seen == 2) return std::stod(l.substr(column.size()));
  return std::nan("");
}

TEST(AllanCli, CurvesAndFittedTermsOfAllSixColumns) {
  const std::string csv = write_temp("white.csv", imu_csv(20000));
  const std::string adev = temp_path("white_adev.csv");
  const CliRun r = navemu({"allan", csv, "--out", adev});
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string content = test::read_file(adev);
  const auto rows = lines_of(content);
  ASSERT_GT(rows.size(), 30u);
  EXPECT_EQ(rows[0], "tau_s,f_x_mps2,f_y_mps2,f_z_mps2,w_x_radps,w_y_radps,w_z_radps");
  // First point: tau = dt, ADEV = density / sqrt(dt) within the m = 1 uncertainty (~1 %).
  std::istringstream first(rows[1]);
  std::vector<double> v;
  for (std::string cell; std::getline(first, cell, ',');) v.push_back(std::stod(cell));
  ASSERT_EQ(v.size(), 7u);
  EXPECT_DOUBLE_EQ(v[0], 0.01);
  for (std::size_t i = 1; i <= 3; ++i) EXPECT_NEAR(v[i] / (kAccelDensity / 0.1), 1.0, 0.05);
  for (std::size_t i = 4; i <= 6; ++i) EXPECT_NEAR(v[i] / (kGyroDensity / 0.1), 1.0, 0.05);

  // The table: SI and datasheet units. 1e-3 rad/s/sqrt(Hz) = 3.4377 deg/sqrt(h);
  // 0.002 m/s^2/sqrt(Hz) = 0.12 m/s/sqrt(h).
  EXPECT_NE(r.out.find("20000 samples at 100 Hz"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("rad/s/sqrt(Hz)"), std::string::npos);
  EXPECT_NE(r.out.find("m/s^2/sqrt(Hz)"), std::string::npos);
  EXPECT_NE(r.out.find("deg/sqrt(h)"), std::string::npos);
  EXPECT_NE(r.out.find("deg/h"), std::string::npos);
  EXPECT_NE(r.out.find("m/s/sqrt(h)"), std::string::npos);
  EXPECT_NE(r.out.find(" mg"), std::string::npos);
  const double arw = datasheet_value(r.out, "w_x_radps");
  const double vrw = datasheet_value(r.out, "f_z_mps2");
  EXPECT_NEAR(arw / (kGyroDensity * 180.0 / std::numbers::pi * 60.0), 1.0, 0.05) << r.out;
  EXPECT_NEAR(vrw / (kAccelDensity * 60.0), 1.0, 0.05) << r.out;
}

TEST(AllanCli, ColumnsRateAndCsvOnStdout) {
  const std::string csv = write_temp("cols.csv", imu_csv(1000));
  const CliRun r = navemu({"allan", csv, "--columns", "w_z_radps,temperature_c", "--rate", "50",
                           "--points-per-decade", "5", "--out", "-"});
  ASSERT_EQ(r.code, 0) << r.err;
  const auto rows = lines_of(r.out);
  ASSERT_GT(rows.size(), 5u);
  EXPECT_EQ(rows[0], "tau_s,w_z_radps,temperature_c");
  EXPECT_EQ(rows[1].rfind("0.02,", 0), 0u) << rows[1];  // --rate 50 overrides time_s
  // 5 per decade from m = 1 to 499: 1 2 3 4 6 10 16 25 40 63 100 158 251 398.
  EXPECT_EQ(rows.size(), 15u);
  // The constant temperature has a zero deviation; the table went to stderr.
  EXPECT_NE(rows[1].find(",0"), std::string::npos);
  EXPECT_NE(r.err.find("w_z_radps"), std::string::npos);
  EXPECT_NE(r.err.find("deg/sqrt(h)"), std::string::npos);
}

TEST(AllanCli, PngPlot) {
  if (!std::filesystem::exists("/usr/bin/gnuplot") && std::system("command -v gnuplot >/dev/null") != 0)
    GTEST_SKIP() << "gnuplot not installed";
  const std::string csv = write_temp("plot.csv", imu_csv(3000));
  const std::string png = temp_path("plot.png");
  std::filesystem::remove(png);
  const CliRun r = navemu({"allan", csv, "--png", png});
  ASSERT_EQ(r.code, 0) << r.err;
  std::ifstream in(png, std::ios::binary);
  std::string head(8, '\0');
  in.read(head.data(), 8);
  EXPECT_EQ(head, std::string("\x89PNG\r\n\x1a\n", 8));
  EXPECT_GT(std::filesystem::file_size(png), 10000u);
}

TEST(AllanCli, MissingGnuplotIsOneLine) {
  const std::string csv = write_temp("nognuplot.csv", imu_csv(100));
  const char* old = std::getenv("PATH");
  const std::string saved = old != nullptr ? old : "";
  const std::string empty_dir = temp_path("empty_path_dir");
  std::filesystem::create_directories(empty_dir);
  ::setenv("PATH", empty_dir.c_str(), 1);
  const CliRun r = navemu({"allan", csv, "--png", temp_path("none.png")});
  ::setenv("PATH", saved.c_str(), 1);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("gnuplot"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

// Runs navemu allan on `content` and expects exit 1 with one line containing `expected`.
void expect_error(const std::string& name, const std::string& content,
                  const std::vector<std::string>& extra, const std::string& expected) {
  const std::string csv = write_temp(name, content);
  std::vector<std::string> args = {"allan", csv};
  args.insert(args.end(), extra.begin(), extra.end());
  const CliRun r = navemu(args);
  EXPECT_EQ(r.code, 1) << name;
  EXPECT_NE(r.err.find(expected), std::string::npos) << name << ": " << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

// Replaces line `line_no` (1-based) of `s`.
std::string with_line(const std::string& s, int line_no, const std::string& replacement) {
  auto rows = lines_of(s);
  rows[static_cast<std::size_t>(line_no - 1)] = replacement;
  std::string out;
  for (const std::string& l : rows) {
    out += l;
    out += '\n';
  }
  return out;
}

TEST(AllanCli, BadInputsAreOneLineErrorsWithFileLineColumn) {
  const std::string good = imu_csv(50);
  {
    const CliRun r = navemu({"allan", temp_path("does_not_exist.csv")});
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("does_not_exist.csv: cannot open"), std::string::npos) << r.err;
  }
  expect_error("nocol.csv", good, {"--columns", "w_x_radps,w_q_radps"},
               "nocol.csv:1: w_q_radps: missing column");
  expect_error("notime.csv", "a,b\n1,2\n", {"--columns", "a"},
               "notime.csv:1: time_s: no such column");
  expect_error("text.csv", with_line(good, 6, "0.04,0,0,-9.8,0.001,abc,0,25"), {},
               "text.csv:6: w_y_radps: not a number: 'abc'");
  expect_error("nan.csv", with_line(good, 7, "0.05,0,nan,-9.8,0.001,0,0,25"), {},
               "nan.csv:7: f_y_mps2: not a finite number");
  expect_error("short.csv", with_line(good, 8, "0.06,0,0,-9.8"), {},
               "short.csv:8: w_x_radps: missing value");
  std::string few = kHeader;
  few += "0,0,0,-9.8,0,0,0,25\n0.01,0,0,-9.8,0,0,0,25\n";
  expect_error("few.csv", few, {}, "2 data rows: the Allan deviation needs at least 10");
  expect_error("decreasing.csv", with_line(good, 9, "0.01,0,0,-9.8,0,0,0,25"), {},
               "decreasing.csv:9: time_s: time 0.01 s does not increase");
  expect_error("gap.csv", with_line(good, 10, "0.0805,0,0,-9.8,0,0,0,25"), {},
               "gap.csv:10: time_s: non-uniform sampling");
  // --rate skips time_s entirely: the same gap is accepted.
  EXPECT_EQ(navemu({"allan", temp_path("gap.csv"), "--rate", "100"}).code, 0);
  // Option values outside their range are usage errors.
  EXPECT_EQ(navemu({"allan", temp_path("gap.csv"), "--points-per-decade", "0"}).code, 2);
  EXPECT_EQ(navemu({"allan", temp_path("gap.csv"), "--rate", "-5"}).code, 2);
}

}  // namespace
}  // namespace navemu
