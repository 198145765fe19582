// Truth sources of the loop end to end: a truth CSV replayed from standard input, and lockstep
// mode, where GPS time comes from the datagrams of tools/truth-sender.

#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "protocols/nmea.hpp"
#include "tests/test_support.hpp"

namespace navemu {
namespace {

namespace fs = std::filesystem;

fs::path temp_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("navemu_run_truth_" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

std::vector<std::vector<std::string>> rmc_sentences(const fs::path& log) {
  std::vector<std::vector<std::string>> out;
  std::ifstream in(log);
  for (std::string line; std::getline(in, line);) {
    const auto f = nmea::parse(line + "\n");
    EXPECT_TRUE(f) << line;
    if (f && (*f)[0] == "GPRMC") out.push_back(*f);
  }
  return out;
}

const fs::path kSource = NAVEMU_SOURCE_DIR;

// A UDP port on loopback that was free a moment ago (the kernel's choice for port 0).
int free_udp_port() {
  const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t len = sizeof a;
  ::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a);
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len);
  ::close(fd);
  return ntohs(a.sin_port);
}

TEST(RunTruth, CsvOnStandardInputDrivesTheReceiverUntilItEnds) {
  const fs::path d = temp_dir("stdin");
  std::ofstream(d / "cfg.yaml") << "truth:\n  source: csv\n  csv: {path: \"-\"}\nimu: {enabled: false}\n";
  const auto r = test::run_command(
      test::shell_quote(test::navemu_binary().string()) + " simulate " +
      test::shell_quote((d / "cfg.yaml").string()) +
      " --start 2010-11-17T13:00:00Z --duration 240 --out " + test::shell_quote((d / "out").string()) +
      " < " + test::shell_quote((kSource / "configs/truth/circle_paper.csv").string()) + " 2>&1");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  // The file spans 229.9 s: fixes while it lasts, then the truth is lost (timeout 1 s) and the
  // receiver reports no fix for the rest of the 240 s.
  const auto rmc = rmc_sentences(d / "out" / "nmea.log");
  ASSERT_EQ(rmc.size(), 1200u);
  int valid = 0;
  for (const auto& s : rmc) valid += s[2] == "A";
  EXPECT_GE(valid, 1150);  // 229.9 s + the 1 s timeout
  EXPECT_LE(valid, 1156);
  EXPECT_EQ(rmc.back()[2], "V");
  // The circle runs at 2 m/s: about 3.9 knots in the middle of the file.
  EXPECT_NEAR(std::stod(rmc[600][7]), 3.9, 1.0);
}

// A truth CSV on standard input is a stream (README, "Streamed truth"): a replay whose time
// restarts (two runs of the same file back to back) is re-synchronised after three rows, with
// the refused rows and the re-synchronisation named by line, and the receiver keeps its fix
// through the second run. A row an hour ahead is refused as future.
TEST(RunTruth, CsvOnStandardInputFollowsTheStreamRules) {
  const fs::path d = temp_dir("stdin-resync");
  std::ofstream(d / "cfg.yaml") << "truth:\n  source: csv\n  csv: {path: \"-\"}\nimu: {enabled: false}\n";
  std::ifstream in(kSource / "configs/truth/circle_paper.csv");
  std::string header, line;
  std::getline(in, header);
  std::vector<std::string> rows;
  while (std::getline(in, line)) rows.push_back(line);
  ASSERT_EQ(rows.size(), 2300u);
  {
    std::ofstream twice(d / "twice.csv");
    twice << header << "\n";
    for (std::size_t i = 0; i < rows.size(); ++i) {
      twice << rows[i] << "\n";
      if (i == 1000) twice << "3700.0" << rows[i].substr(rows[i].find(',')) << "\n";  // line 1003
    }
    for (const std::string& r : rows) twice << r << "\n";  // lines 2303 on: the time restarts
  }
  const auto r = test::run_command(
      test::shell_quote(test::navemu_binary().string()) + " simulate " +
      test::shell_quote((d / "cfg.yaml").string()) +
      " --start 2010-11-17T13:00:00Z --duration 455 --out " + test::shell_quote((d / "out").string()) +
      " < " + test::shell_quote((d / "twice.csv").string()) + " 2>&1");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("truth CSV /dev/stdin:1003: time_s 3700: row refused (future)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("truth CSV /dev/stdin:2303: time_s 0: row refused (backwards)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("truth CSV /dev/stdin:2305: time_s 0.2: the rows' time jumped 229.7"), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("re-synchronised after 3 consecutive rows"), std::string::npos) << r.out;
  // 455 s at 5 Hz: a fix in every epoch but the one or two at the re-synchronisation.
  const auto rmc = rmc_sentences(d / "out" / "nmea.log");
  ASSERT_EQ(rmc.size(), 2275u);
  int valid = 0;
  for (const auto& s : rmc) valid += s[2] == "A";
  EXPECT_GE(valid, 2272);
}

TEST(RunTruth, LockstepTakesTimeFromTheTruthStream) {
  const fs::path d = temp_dir("lockstep");
  const int port = free_udp_port();
  std::ofstream(d / "cfg.yaml") << "scenario: {time: lockstep, status_interval_s: 0}\n"
                                << "truth: {source: udp, udp: {port: " << port << "}}\n"
                                << "gnss:\n  outputs: [{type: file, path: " << (d / "gnss.nmea").string()
                                << "}]\nimu: {enabled: false}\n";
  // navemu waits for the first datagram; the sender streams 3 s of GPS-time-stamped truth.
  const auto r = test::run_command(
      "( " + test::shell_quote(test::navemu_binary().string()) + " run " +
      test::shell_quote((d / "cfg.yaml").string()) + " --duration 2 > /dev/null 2>" +
      test::shell_quote((d / "err.txt").string()) + " & pid=$!; sleep 0.5; " +
      test::shell_quote((kSource / "tools/truth-sender").string()) +
      " --stationary 32.3,-90.9,60 --gps-time --rate 50 --duration 3 --quiet --port " +
      std::to_string(port) + "; wait $pid )");
  ASSERT_EQ(r.exit_code, 0);
  // Two seconds of stream time at 5 Hz: ten epochs, each with a fix, 0.2 s apart.
  const auto rmc = rmc_sentences(d / "gnss.nmea");
  ASSERT_EQ(rmc.size(), 10u);
  for (const auto& s : rmc) EXPECT_EQ(s[2], "A");
  std::ifstream err(d / "err.txt");
  std::stringstream ss;
  ss << err.rdbuf();
  EXPECT_NE(ss.str().find("lockstep"), std::string::npos) << ss.str();
  EXPECT_NE(ss.str().find("10 GNSS epochs (10 with a fix"), std::string::npos) << ss.str();
}

}  // namespace
}  // namespace navemu
