// navemu simulate: the real-time loop's models and encoders offline, deterministic, and the
// files they write agree with each other and with the physics.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "protocols/nmea.hpp"
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

std::vector<std::vector<std::string>> csv_rows(const fs::path& p) {
  std::vector<std::vector<std::string>> rows;
  std::ifstream in(p);
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> f;
    std::stringstream ss(line);
    for (std::string x; std::getline(ss, x, ',');) f.push_back(x);
    if (!line.empty() && line.back() == ',') f.emplace_back();
    rows.push_back(f);
  }
  return rows;
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

TEST(Simulate, SameSeedGivesIdenticalFilesAndAnotherSeedDoesNot) {
  const fs::path a = temp_dir("a"), b = temp_dir("b"), c = temp_dir("c");
  ASSERT_EQ(simulate(kDefault, a, 30).exit_code, 0);
  ASSERT_EQ(simulate(kDefault, b, 30).exit_code, 0);
  ASSERT_EQ(simulate(kDefault, c, 30, "--seed 2").exit_code, 0);
  for (const char* f : {"nmea.log", "truth.csv", "gnss.csv", "imu.csv"}) {
    EXPECT_FALSE(slurp(a / f).empty()) << f;
    EXPECT_EQ(slurp(a / f), slurp(b / f)) << f;
  }
  EXPECT_NE(slurp(a / "gnss.csv"), slurp(c / "gnss.csv"));
  EXPECT_NE(slurp(a / "imu.csv"), slurp(c / "imu.csv"));
  EXPECT_EQ(slurp(a / "truth.csv"), slurp(c / "truth.csv"));  // the truth has no randomness
}

TEST(Simulate, FilesHoldEveryEpochOnTheGridWithAPlausibleFix) {
  const fs::path d = temp_dir("grid");
  const auto r = simulate(kDefault, d, 60);
  ASSERT_EQ(r.exit_code, 0) << r.out;

  // 60 s at 5 Hz: epochs at .0 .2 .4 ... from the start, 300 of them.
  const auto gnss = csv_rows(d / "gnss.csv");
  ASSERT_EQ(gnss.size(), 301u);
  ASSERT_EQ(gnss[0][0], "time_s");
  double sum_h = 0.0, max_h = 0.0;
  int fixes = 0;
  for (std::size_t i = 1; i < gnss.size(); ++i) {
    EXPECT_NEAR(std::stod(gnss[i][0]), 0.2 * static_cast<double>(i - 1), 1e-9);
    if (gnss[i][6] != "3") continue;
    ++fixes;
    const double h = std::stod(gnss[i][18]);
    sum_h += h;
    max_h = std::max(max_h, h);
    EXPECT_GE(std::stoi(gnss[i][8]), 4);
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
  const auto imu = csv_rows(d / "imu.csv");
  ASSERT_EQ(imu.size(), 7501u);
  for (std::size_t i = 1; i < imu.size(); ++i) EXPECT_EQ(imu[i][8], "1");

  // Truth: the paper's 30 ft circle around the site.
  const auto truth = csv_rows(d / "truth.csv");
  ASSERT_EQ(truth.size(), 301u);
}

TEST(Simulate, RejectsAStreamedTruth) {
  const fs::path dir = temp_dir("udp");
  const fs::path cfg = dir / "udp.yaml";
  std::ofstream(cfg) << "truth:\n  source: udp\n  udp: {port: 0}\n";
  const auto r = simulate(cfg, dir / "out", 10);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.out.find("simulate needs a generator or a CSV truth"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace navemu
