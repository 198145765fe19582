// The IMU on a SocketCAN interface, as a robot computer sees it: `navemu run` sends every
// sample on vcan0 while can-utils' candump -L records the bus, for 10 s. Needs kernel CAN and
// vcan0 (up, MTU 72): tools/run-in-uml provides both inside user-mode Linux (ctest -L vcan);
// natively these tests skip.
//
// Asserted (loose, as timing on shared machines demands; TESTING.md): every sample's frames
// present and decoding to navemu's own log (J1939 within its resolution, the high-resolution
// layouts exactly), the count, the mean period from first to last frame, and the median gap.
// p99 and max gaps are printed for the record.

#include <gtest/gtest.h>
#include <net/if.h>

#include <fmt/format.h>

#include <algorithm>

#include "tests/can_capture.hpp"
#include "tests/clients/client_support.hpp"
#include "transports/can_port.hpp"

namespace navemu::test::clients {
namespace {

#define NAVEMU_REQUIRE_VCAN0()                                                                \
  do {                                                                                        \
    if (!transport::socketcan_available())                                                    \
      GTEST_SKIP() << "no kernel CAN here: run through tools/run-in-uml (ctest -L vcan)";     \
    if (::if_nametoindex("vcan0") == 0) GTEST_SKIP() << "no vcan0 (tools/run-in-uml makes it)"; \
  } while (0)

TEST(ImuVcan, TenSecondsAt125HzEverySampleOnTheBusOnTime) {
  NAVEMU_REQUIRE_VCAN0();
  const std::string candump = find_program("candump");
  if (candump.empty()) GTEST_SKIP() << "can-utils is not installed (tools/install-deps)";
  TempDir dir("vcan");
  Child dump({candump, "-L", "vcan0"}, dir / "candump.log", dir / "candump.stderr");
  sleep_s(1.0);  // candump has bound its socket
  ASSERT_TRUE(dump.running()) << slurp(dir / "candump.stderr");

  // The default job's receiver on a pty as well: 5 Hz GNSS and 125 Hz IMU in one loop.
  NavemuRun nav(dir, "navemu",
                fmt::format("gnss:\n  outputs:\n    - {{type: pty, link: '{}'}}\n"
                            "imu:\n  log: '{}'\n  outputs:\n"
                            "    - {{type: socketcan, interface: vcan0, "
                            "layouts: [j1939, highres, highres-fd]}}\n",
                            (dir / "gnss").string(), (dir / "imu.log").string()),
                10.0);
  const auto st = nav.child().wait_exit(40.0);
  ASSERT_TRUE(st && WIFEXITED(*st) && WEXITSTATUS(*st) == 0) << describe_status(st) << nav.diagnostics();
  sleep_s(0.5);
  dump.signal(SIGINT);
  ASSERT_TRUE(dump.wait_exit(5.0));
  EXPECT_NE(nav.err().find("IMU CAN frames on socketcan vcan0 (CAN FD): j1939, highres, highres-fd"),
            std::string::npos)
      << nav.diagnostics();
  EXPECT_NE(nav.err().find("CAN frames (0 dropped, 0 failed, 0 bus errors)"), std::string::npos) << nav.diagnostics();

  const std::vector<LoggedFrame> frames = read_candump_log(dir / "candump.log");
  const std::vector<ImuRow> rows = read_imu_rows(dir / "imu.log");
  const CanCheck c = check_frames_against_log(frames, rows);
  // 10 s at 125 Hz.
  EXPECT_NEAR(static_cast<double>(rows.size()), 1250.0, 5.0);
  EXPECT_EQ(c.samples, rows.size());
  EXPECT_EQ(c.ari, rows.size());
  EXPECT_EQ(c.accs, rows.size());
  EXPECT_EQ(c.highres, rows.size());
  EXPECT_EQ(c.highres_fd, rows.size());
  EXPECT_EQ(frames.size(), 8 * rows.size());
  EXPECT_EQ(c.mismatches, 0u) << c.first_problem;

  // Timing of the ARI frames as candump stamped them.
  std::vector<double> t;
  for (const LoggedFrame& f : frames)
    if (f.extended && j1939_pgn(f.id) == can::j1939::kPgnAri) t.push_back(f.t_s);
  ASSERT_GE(t.size(), 100u);
  // Mean period: the least-squares slope of arrival time against sample index, which one
  // late first or last frame (a host stall) cannot move the way it moves (last - first) / n.
  double si = 0, sy = 0, sii = 0, sit = 0;
  const double n = static_cast<double>(t.size());
  for (std::size_t i = 0; i < t.size(); ++i) {
    const double x = static_cast<double>(i), y = t[i] - t.front();
    si += x;
    sy += y;
    sii += x * x;
    sit += x * y;
  }
  const double mean_ms = (n * sit - si * sy) / (n * sii - si * si) * 1e3;
  std::vector<double> gaps;
  for (std::size_t i = 1; i < t.size(); ++i) gaps.push_back((t[i] - t[i - 1]) * 1e3);
  std::sort(gaps.begin(), gaps.end());
  const auto pct = [&](double p) {
    return gaps[std::min(gaps.size() - 1, static_cast<std::size_t>(p * static_cast<double>(gaps.size())))];
  };
  fmt::print("vcan0: {} samples, {} frames; ARI mean period (fit) {:.4f} ms, gap p50 {:.3f} p99 {:.3f} "
             "max {:.3f} ms; J1939 max error {:.2e} rad/s {:.2e} m/s^2; high-res {:.2e} rad/s "
             "{:.2e} m/s^2\n",
             c.samples, frames.size(), mean_ms, pct(0.5), pct(0.99), gaps.back(), c.max_rate_err_radps,
             c.max_accel_err_mps2, c.max_hr_rate_err_radps, c.max_hr_accel_err_mps2);
  EXPECT_NEAR(mean_ms, 8.0, 0.01);
  EXPECT_NEAR(pct(0.5), 8.0, 0.5);
}

// Misconfigured interfaces stop navemu at start-up with a one-line error naming them.
TEST(ImuVcan, MissingDownOrClassicOnlyInterfacesAreStartUpErrors) {
  NAVEMU_REQUIRE_VCAN0();
  TempDir dir("vcan-errors");
  ASSERT_EQ(std::system("ip link add dev navemu-down type vcan"), 0);
  ASSERT_EQ(std::system("ip link add dev navemu-cc type vcan && ip link set navemu-cc mtu 16 up"), 0);
  const auto run = [&](const std::string& name, const std::string& output) {
    NavemuRun nav(dir, name, "gnss: {enabled: false}\nimu:\n  outputs:\n    - " + output + "\n", 30.0);
    const auto st = nav.child().wait_exit(10.0);
    EXPECT_TRUE(st && WIFEXITED(*st) && WEXITSTATUS(*st) == 1) << name << ": " << describe_status(st);
    return nav.err();
  };
  const std::string missing = run("missing", "{type: socketcan, interface: vcan9}");
  EXPECT_NE(missing.find("socketcan vcan9: no such interface"), std::string::npos) << missing;
  const std::string down = run("down", "{type: socketcan, interface: navemu-down}");
  EXPECT_NE(down.find("socketcan navemu-down: interface is down"), std::string::npos) << down;
  const std::string classic = run("classic", "{type: socketcan, interface: navemu-cc, layouts: [highres-fd]}");
  EXPECT_NE(classic.find("socketcan navemu-cc: navemu-cc does not carry CAN FD frames"), std::string::npos)
      << classic;
  [[maybe_unused]] const int rc = std::system("ip link del dev navemu-down; ip link del dev navemu-cc");
}

}  // namespace
}  // namespace navemu::test::clients
