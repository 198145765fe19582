// The IMU on a SocketCAN interface, as a robot computer sees it: `navemu run` sends every
// sample on vcan0 while can-utils' candump -L records the bus, for 10 s; and for 5 s with
// candump stopped for 1.5 s, a reader falling behind. Needs kernel CAN and
// vcan0 (up, MTU 72): tools/run-in-uml provides both inside user-mode Linux (ctest -L vcan);
// natively these tests skip.
//
// Asserted exactly: navemu's promise (every frame of every sample written to the kernel or
// counted as dropped or failed; on an idle vcan0, all written) and the reader's accounting
// (frames logged + frames candump's socket dropped = frames written; tests/vcan/vcan_support.hpp).
// The reader's own losses (a stalled candump, not navemu) are printed and bounded loosely;
// what arrived decodes to navemu's own log (J1939 within its resolution, the high-resolution
// layouts exactly), and every sample none of whose frames the reader dropped is complete.
// Timing, loose as shared machines demand (TESTING.md): the mean period, fitted against the
// samples' own GPS times so that samples the reader lost do not bias it, robustly so that runs
// of late samples do not either, and the median gap between consecutive samples. p99 and max
// gaps are printed for the record.

#include <gtest/gtest.h>
#include <net/if.h>

#include <fmt/format.h>

#include <algorithm>

#include "tests/vcan/vcan_support.hpp"

namespace navemu::test::clients {
namespace {

// navemu run for `seconds` with the J1939 and both high-resolution layouts on vcan0 while
// candump records with a receive queue for `reader_queue_s` of frames (0: the kernel's
// default); with `reader_stop_s` > 0, candump is stopped that long from 1 s into the run.
// Checks all of the above; `reader_dropped` gets candump's losses.
void run_and_check(double seconds, double reader_queue_s, double reader_stop_s, std::uint64_t& reader_dropped) {
  TempDir dir("vcan");
  // Per sample two J1939 frames, five classic high-resolution frames and one CAN FD frame.
  constexpr long kFramesPerSample = 8;
  CandumpRecording dump(dir, "vcan0", 125.0 * kFramesPerSample, reader_queue_s);
  ASSERT_TRUE(dump.receiving()) << dump.diagnostics();

  // The default job's receiver on a pty as well: 5 Hz GNSS and 125 Hz IMU in one loop.
  NavemuRun nav(dir, "navemu",
                fmt::format("gnss:\n  outputs:\n    - {{type: pty, link: '{}'}}\n"
                            "imu:\n  log: '{}'\n  outputs:\n"
                            "    - {{type: socketcan, interface: vcan0, "
                            "layouts: [j1939, highres, highres-fd]}}\n",
                            (dir / "gnss").string(), (dir / "imu.log").string()),
                seconds);
  if (reader_stop_s > 0) {
    ASSERT_TRUE(wait_until([&] { return nav.err().find("IMU CAN frames on") != std::string::npos; }, 20.0))
        << nav.diagnostics();
    sleep_s(1.0);
    dump.stall(reader_stop_s);
  }
  const auto st = nav.child().wait_exit(seconds + 30.0);
  ASSERT_TRUE(st && WIFEXITED(*st) && WEXITSTATUS(*st) == 0) << describe_status(st) << nav.diagnostics();
  const CandumpResult rec = dump.finish();
  ASSERT_TRUE(rec.ended) << rec.problem << dump.diagnostics();
  reader_dropped = rec.dropped;
  EXPECT_NE(nav.err().find("IMU CAN frames on socketcan vcan0 (CAN FD): j1939, highres, highres-fd"),
            std::string::npos)
      << nav.diagnostics();

  // navemu's promise, exactly: 125 Hz, every sample in its log, every frame of it handed to
  // the kernel or counted, and on an idle vcan0 none dropped or failed.
  const auto s = can_summary(nav.err());
  ASSERT_TRUE(s) << nav.diagnostics();
  const std::vector<ImuRow> rows = read_imu_rows(dir / "imu.log");
  EXPECT_NEAR(static_cast<double>(rows.size()), 125.0 * seconds, 5.0);
  EXPECT_EQ(s->samples, static_cast<long>(rows.size())) << nav.diagnostics();
  EXPECT_EQ(s->written + s->dropped + s->failed, kFramesPerSample * s->samples) << nav.diagnostics();
  EXPECT_EQ(s->dropped, 0) << nav.diagnostics();
  EXPECT_EQ(s->failed, 0) << nav.diagnostics();
  EXPECT_EQ(s->bus_errors, 0) << nav.diagnostics();

  // The reader, exactly: every frame written is in candump's log or in its socket's drop count.
  EXPECT_EQ(static_cast<long>(rec.frames.size() + rec.dropped), s->written);
  // Its losses, reported; bounded only so that the checks below have material (a reader that
  // lost half the bus sat out half the run).
  ::testing::Test::RecordProperty("reader_dropped", static_cast<int>(rec.dropped));
  EXPECT_LT(static_cast<long>(rec.dropped), s->written / 2) << "candump fell far behind";

  // What arrived, checked against navemu's log. A frame the reader dropped takes at most one
  // sample with it, so all but that many samples arrive whole (all of them when none dropped).
  const CanCheck c = check_frames_against_log(rec.frames, rows);
  EXPECT_EQ(c.mismatches, 0u) << c.first_problem;
  const std::size_t whole = rows.size() - std::min<std::size_t>(rows.size(), rec.dropped);
  for (const auto& [name, n] : {std::pair{"ARI", c.ari}, std::pair{"ACCS", c.accs},
                                std::pair{"high-resolution", c.highres}, std::pair{"CAN FD", c.highres_fd}}) {
    EXPECT_GE(n, whole) << name << " samples";
    EXPECT_LE(n, rows.size()) << name << " samples";
  }

  // Timing of the samples as candump's socket stamped them (when navemu sent them, whenever
  // candump read them). Mean period: the Theil-Sen slope (the median of the slopes between
  // every two samples; H. Theil 1950, P. K. Sen, JASA 63, 1968) of arrival time against the
  // sample's place on the 125 Hz grid, from its own GPS time. Samples lost between two others
  // leave it alone, and so do runs of late samples (a host stall, a reader's catch-up taking
  // the CPU from navemu), which pull a least-squares slope by their lateness over the span.
  ASSERT_GE(c.arrival_s.size(), 100u);
  std::vector<std::pair<double, double>> grid_t;  // (place on the grid, arrival s)
  for (const auto& [gps_ns, t] : c.arrival_s)
    grid_t.emplace_back(static_cast<double>(gps_ns - c.arrival_s.begin()->first) / 8e6, t);
  std::vector<double> slopes;
  slopes.reserve(grid_t.size() * (grid_t.size() - 1) / 2);
  for (std::size_t i = 0; i < grid_t.size(); ++i)
    for (std::size_t j = i + 1; j < grid_t.size(); ++j)
      slopes.push_back((grid_t[j].second - grid_t[i].second) / (grid_t[j].first - grid_t[i].first));
  const auto mid = slopes.begin() + static_cast<std::ptrdiff_t>(slopes.size() / 2);
  std::nth_element(slopes.begin(), mid, slopes.end());
  const double mean_ms = *mid * 1e3;
  // Gaps between consecutive samples only (8 ms apart on the grid).
  std::vector<double> gaps;
  for (auto it = std::next(c.arrival_s.begin()); it != c.arrival_s.end(); ++it)
    if (it->first - std::prev(it)->first == 8'000'000)
      gaps.push_back((it->second - std::prev(it)->second) * 1e3);
  ASSERT_GE(gaps.size(), 100u);
  std::sort(gaps.begin(), gaps.end());
  const auto pct = [&](double p) {
    return gaps[std::min(gaps.size() - 1, static_cast<std::size_t>(p * static_cast<double>(gaps.size())))];
  };
  fmt::print("vcan0: {} samples, {} frames written, {} logged, {} dropped by candump's socket ({} "
             "samples cut); mean period (fit over {} samples) {:.4f} ms, gap p50 {:.3f} p99 {:.3f} "
             "max {:.3f} ms; J1939 max error {:.2e} rad/s {:.2e} m/s^2; high-res {:.2e} rad/s "
             "{:.2e} m/s^2\n",
             rows.size(), s->written, rec.frames.size(), rec.dropped, c.cut, c.arrival_s.size(), mean_ms,
             pct(0.5), pct(0.99), gaps.back(), c.max_rate_err_radps, c.max_accel_err_mps2,
             c.max_hr_rate_err_radps, c.max_hr_accel_err_mps2);
  // 1 %: a wrong rate (100 Hz for 125, a drifting schedule) is far outside it, while the
  // 1-CPU user-mode Linux, stalled by a loaded host, has read 7.958 ms here with every frame
  // delivered (issue-12 decisions: timing is gated on p99 against the bare timer, in
  // tools/, not on these in-UML stamps). The sample count above pins the rate to 0.4 % too.
  EXPECT_NEAR(mean_ms, 8.0, 0.08);
  EXPECT_NEAR(pct(0.5), 8.0, 0.5);
}

TEST(ImuVcan, TenSecondsAt125HzEverySampleOnTheBusOnTime) {
  NAVEMU_REQUIRE_VCAN0();
  if (find_program("candump").empty()) GTEST_SKIP() << "can-utils is not installed (tools/install-deps)";
  std::uint64_t reader_dropped = 0;
  run_and_check(10.0, kReaderStallS, 0.0, reader_dropped);
}

// candump with the kernel's default queue (278 frames, 0.28 s at 1000 frames/s) stopped for
// 1.5 s: it loses about 1200 frames, and says so; navemu loses none, every frame is accounted
// for, and what did arrive, the samples at the hole's edges included, checks out as above.
// (A loss needs navemu to send more than 278 frames in those 1.5 s, which it does unless it
// skips over a second of samples. It stays under half of the 5000 frames, as run_and_check
// wants, even when user-mode Linux as a whole is held up and the stop overruns: navemu is held
// up too and then sends at most 0.5 s of late samples, emulator/engine.cpp kImuCatchUp_ns.)
TEST(ImuVcan, AStalledReaderLosesFramesAndNavemuNone) {
  NAVEMU_REQUIRE_VCAN0();
  if (find_program("candump").empty()) GTEST_SKIP() << "can-utils is not installed (tools/install-deps)";
  std::uint64_t reader_dropped = 0;
  run_and_check(5.0, 0.0, 1.5, reader_dropped);
  EXPECT_GT(reader_dropped, 0u) << "the stall did not outlast candump's queue";
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
