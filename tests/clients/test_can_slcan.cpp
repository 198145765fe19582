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
  ASSERT_TRUE(wait_until([&] { return fs::exists(link) && nav.err().find("CAN frames on slcan") != std::string::npos; }, 10.0))
      << nav.diagnostics();
  EXPECT_NE(nav.err().find("CAN frames go to slcan on pty"), std::string::npos) << nav.diagnostics();

  const fs::path script = fs::path(NAVEMU_SOURCE_DIR) / "tests" / "clients" / "slcan_capture.py";
  Child py({"/usr/bin/python3", script.string(), link.string(), (dir / "python.log").string(), "5"},
           dir / "python.stdout", dir / "python.stderr");
  const auto py_status = py.wait_exit(30.0);
  nav.stop_expecting_exit_0();
  ASSERT_TRUE(py_status && WIFEXITED(*py_status) && WEXITSTATUS(*py_status) == 0)
      << describe_status(py_status) << "\n" << slurp(dir / "python.stderr");

  // python-can stops reading at a time, not at a sample's end: drop a last, partial sample.
  std::vector<LoggedFrame> frames = read_candump_log(dir / "python.log");
  const can::highres::Config hr;
  while (!frames.empty() && frames.back().id != hr.base_id + can::highres::kOffsetStatus) frames.pop_back();
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

}  // namespace
}  // namespace navemu::test::clients
