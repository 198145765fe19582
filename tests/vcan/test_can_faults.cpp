// The IMU on SocketCAN under the faults a bench meets: the interface goes down and comes back
// up mid-run, and the interface's transmit queue is full (ENOBUFS: a bus slower than the
// frames offered). navemu runs on, the GNSS output beside it keeps its 5 Hz cadence, every
// frame is accounted for (written + dropped + failed = one per sample with the CAN FD
// high-resolution layout, whose GPS time stamp matches each frame to its row of navemu's own
// IMU log however many are missing), every frame written reaches candump's log or its
// socket's drop count (the reader's losses, told apart from navemu's: vcan_support.hpp), and
// what reaches the log decodes to that row. Needs kernel CAN (tools/run-in-uml; ctest -L
// vcan); scratch interfaces, so vcan0 stays as the other tests expect it.

#include <gtest/gtest.h>
#include <net/if.h>

#include <fmt/format.h>

#include <regex>

#include "protocols/nmea.hpp"
#include "tests/vcan/vcan_support.hpp"

namespace navemu::test::clients {
namespace {

// A CAN FD vcan interface of the test's own, removed at the end.
class ScratchVcan {
 public:
  explicit ScratchVcan(std::string name) : name_(std::move(name)) {
    [[maybe_unused]] const int old = std::system(("ip link del dev " + name_ + " 2>/dev/null").c_str());
    created_ = std::system(("ip link add dev " + name_ + " type vcan && ip link set dev " + name_ +
                            " mtu 72 up").c_str()) == 0;
  }
  ~ScratchVcan() {
    if (created_ && std::system(("ip link del dev " + name_).c_str()) != 0) ADD_FAILURE() << name_ << " left behind";
  }
  bool created() const { return created_; }
  bool run(const std::string& ip_args) const {
    return std::system(fmt::format(fmt::runtime(ip_args), name_).c_str()) == 0;
  }

 private:
  std::string name_;
  bool created_ = false;
};

std::string run_config(const TempDir& dir, const std::string& interface) {
  return fmt::format("gnss:\n  outputs:\n    - {{type: pty, link: '{}'}}\n"
                     "imu:\n  log: '{}'\n  outputs:\n"
                     "    - {{type: socketcan, interface: {}, layouts: [highres-fd]}}\n",
                     (dir / "gnss").string(), (dir / "imu.log").string(), interface);
}

// The GNSS output goes on at 5 Hz through the CAN fault: every RMC on the 200 ms grid after
// the one before. An epoch the reader did not receive is navemu's fault only if navemu did not
// report discarding output nobody read (the pty's stale flushes, dropped output chunks: the
// reader stalled, as a user-mode Linux reader on a loaded host does); navemu skips none.
void expect_gnss_cadence(const std::vector<Received>& lines, const std::string& navemu_err) {
  std::int64_t last = -1, missing = 0;
  int rmc = 0;
  for (const Received& r : lines) {
    const auto f = nmea::parse(r.text);
    if (!f || (*f)[0].substr(2) != "RMC") continue;
    const std::int64_t ms = rmc_unix_ms(*f);
    if (last >= 0) {
      EXPECT_TRUE(ms > last && (ms - last) % 200 == 0) << r.text;
      missing += (ms - last) / 200 - 1;
    }
    last = ms;
    ++rmc;
  }
  EXPECT_GE(rmc, 25);
  std::smatch m;
  const std::regex counts(R"((\d+) skipped\), .*?(\d+) output chunks dropped, \d+ stale bytes flushed in (\d+) flushes)");
  ASSERT_TRUE(std::regex_search(navemu_err, m, counts)) << navemu_err;
  EXPECT_EQ(std::stoll(m[1]), 0) << "GNSS epochs skipped by navemu";
  const long long discarded = std::stoll(m[2]) + std::stoll(m[3]);
  if (discarded == 0) {
    EXPECT_EQ(missing, 0) << "epochs missing at the reader while navemu discarded nothing: " << m[0];
  }
  if (missing > 0) std::printf("GNSS: %lld epochs missed by the stalled reader (%lld discards reported)\n",
                               static_cast<long long>(missing), discarded);
}

// Down for 2 s in the middle of 8 s: the frames of those samples fail (ENETDOWN) and are
// counted, navemu says so once and again when frames flow, the GNSS output does not notice,
// and frames flow again once the interface is up.
TEST(CanFaults, InterfaceDownAndUpMidRun) {
  NAVEMU_REQUIRE_KERNEL_CAN();
  if (find_program("candump").empty()) GTEST_SKIP() << "can-utils is not installed (tools/install-deps)";
  ScratchVcan vcan("navemu-flap");
  if (!vcan.created()) GTEST_SKIP() << "cannot create an interface (ip link add needs CAP_NET_ADMIN)";
  TempDir dir("can-flap");
  CandumpRecording dump(dir, "navemu-flap", 125.0);  // one CAN FD frame per sample
  ASSERT_TRUE(dump.receiving()) << dump.diagnostics();
  NavemuRun nav(dir, "navemu", run_config(dir, "navemu-flap"), 8.0);
  ASSERT_TRUE(nav.wait_for_pty(dir / "gnss", 5.0)) << nav.diagnostics();
  PtyReader reader;
  ASSERT_TRUE(reader.open(dir / "gnss"));
  std::vector<Received> lines;
  const double t0 = mono_s();
  reader.read_until(t0 + 2.0, lines);
  ASSERT_TRUE(vcan.run("ip link set dev {} down"));
  reader.read_until(t0 + 4.0, lines);
  ASSERT_TRUE(vcan.run("ip link set dev {} up"));
  const double up_real_s = real_s();
  reader.read_until(t0 + 7.5, lines);
  const auto st = nav.child().wait_exit(20.0);
  ASSERT_TRUE(st && WIFEXITED(*st) && WEXITSTATUS(*st) == 0) << describe_status(st) << nav.diagnostics();
  const CandumpResult rec = dump.finish();
  ASSERT_TRUE(rec.ended) << rec.problem << dump.diagnostics();

  const auto s = can_summary(nav.err());
  ASSERT_TRUE(s) << nav.diagnostics();
  EXPECT_EQ(s->written + s->dropped + s->failed, s->samples) << nav.diagnostics();
  // 2 s down at 125 Hz: about 250 frames failed (the commands take some time).
  EXPECT_GT(s->failed, 150) << nav.diagnostics();
  EXPECT_LT(s->failed, 500) << nav.diagnostics();
  // Every frame written, before the interface went down and after it came back, reached the
  // reader (candump stays through the down, -D) or its socket's drop count.
  EXPECT_EQ(static_cast<long>(rec.frames.size() + rec.dropped), s->written);
  const CanCheck c = check_frames_against_log(rec.frames, read_imu_rows(dir / "imu.log"));
  const auto resumed = std::count_if(rec.frames.begin(), rec.frames.end(),
                                     [&](const LoggedFrame& f) { return f.t_s > up_real_s; });
  EXPECT_GT(resumed, 100) << "frames did not resume after the interface came back up";
  // Said once each way, not per frame.
  const std::string down = "socketcan navemu-flap: Network is down; frames fail until it is back";
  const std::string again = "socketcan navemu-flap: sending again";
  EXPECT_NE(nav.err().find(down), std::string::npos) << nav.diagnostics();
  EXPECT_EQ(nav.err().find(down), nav.err().rfind(down)) << nav.diagnostics();
  EXPECT_NE(nav.err().find(again), std::string::npos) << nav.diagnostics();
  EXPECT_EQ(c.mismatches, 0u) << c.first_problem;
  expect_gnss_cadence(lines, nav.err());
  std::printf("interface down 2 s: %ld samples, %ld frames written, %ld dropped, %ld failed; %zu "
              "logged (%td after it came back), %llu dropped by candump's socket\n",
              s->samples, s->written, s->dropped, s->failed, rec.frames.size(), resumed,
              static_cast<unsigned long long>(rec.dropped));
}

// A token bucket of 40 kbit/s (5000 B/s, about 69 CAN FD frames a second) in front of an
// interface offered 125 frames a second: the queue overflows, the kernel answers ENOBUFS, and
// navemu drops and counts those frames without blocking.
TEST(CanFaults, FullTransmitQueueDropsAndCounts) {
  NAVEMU_REQUIRE_KERNEL_CAN();
  if (find_program("candump").empty()) GTEST_SKIP() << "can-utils is not installed (tools/install-deps)";
  ScratchVcan vcan("navemu-slow");
  if (!vcan.created()) GTEST_SKIP() << "cannot create an interface (ip link add needs CAP_NET_ADMIN)";
  if (!vcan.run("tc qdisc add dev {} root tbf rate 40kbit burst 3600 limit 720"))
    GTEST_SKIP() << "no tbf queueing discipline here (Debian package iproute2, module sch_tbf)";
  TempDir dir("can-slow");
  CandumpRecording dump(dir, "navemu-slow", 125.0);  // at most one CAN FD frame per sample
  ASSERT_TRUE(dump.receiving()) << dump.diagnostics();
  NavemuRun nav(dir, "navemu", run_config(dir, "navemu-slow"), 6.0);
  ASSERT_TRUE(nav.wait_for_pty(dir / "gnss", 5.0)) << nav.diagnostics();
  PtyReader reader;
  ASSERT_TRUE(reader.open(dir / "gnss"));
  std::vector<Received> lines;
  reader.read_until(mono_s() + 5.5, lines);
  const auto st = nav.child().wait_exit(20.0);
  ASSERT_TRUE(st && WIFEXITED(*st) && WEXITSTATUS(*st) == 0) << describe_status(st) << nav.diagnostics();
  const CandumpResult rec = dump.finish();
  ASSERT_TRUE(rec.ended) << rec.problem << dump.diagnostics();

  const auto s = can_summary(nav.err());
  ASSERT_TRUE(s) << nav.diagnostics();
  EXPECT_EQ(s->written + s->dropped + s->failed, s->samples) << nav.diagnostics();
  EXPECT_EQ(s->failed, 0) << nav.diagnostics();
  // 6 s: about 750 frames offered, about 50 + 6 * 69 = 460 through the bucket.
  EXPECT_GT(s->dropped, s->samples / 10) << nav.diagnostics();
  // A frame the queue took is looped back to the local readers at once (net/can/af_can.c
  // can_send), so every frame written reached candump's log or its socket's drop count.
  EXPECT_EQ(static_cast<long>(rec.frames.size() + rec.dropped), s->written);
  EXPECT_GT(rec.frames.size(), 100u);
  const CanCheck c = check_frames_against_log(rec.frames, read_imu_rows(dir / "imu.log"));
  EXPECT_EQ(c.mismatches, 0u) << c.first_problem;
  expect_gnss_cadence(lines, nav.err());
  std::printf("token bucket 40 kbit/s: %ld samples, %ld frames written, %ld dropped (ENOBUFS); "
              "%zu logged, %llu dropped by candump's socket\n",
              s->samples, s->written, s->dropped, rec.frames.size(),
              static_cast<unsigned long long>(rec.dropped));
}

// The CAN bus faults of `events:` on SocketCAN as candump records them (with an error mask): a bus-off for 1 s
// (SocketCAN's CAN_ERR_BUSOFF error frame, can_id 0x20000040, no IMU frame, then
// CAN_ERR_RESTARTED 0x20000100 and the frames again) and 20 bus errors a second for 1 s (error
// frames 0x20000088, a stuffing error in data[2]), each within 0.1 s of its scheduled time;
// the IMU frames decode to navemu's log.
TEST(CanFaults, BusOffAndBusErrorsReachCandumpAsErrorFrames) {
  NAVEMU_REQUIRE_KERNEL_CAN();
  if (find_program("candump").empty()) GTEST_SKIP() << "can-utils is not installed (tools/install-deps)";
  ScratchVcan vcan("navemu-err");
  if (!vcan.created()) GTEST_SKIP() << "cannot create an interface (ip link add needs CAP_NET_ADMIN)";
  TempDir dir("can-errors");
  CandumpRecording dump(dir, "navemu-err", 150.0, kReaderStallS, true);
  ASSERT_TRUE(dump.receiving()) << dump.diagnostics();
  NavemuRun nav(dir, "navemu",
                fmt::format("gnss: {{enabled: false}}\n"
                            "imu:\n  log: '{}'\n  outputs:\n"
                            "    - {{type: socketcan, interface: navemu-err, layouts: [highres-fd]}}\n"
                            "events:\n"
                            "  - {{type: imu, start_s: 2, duration_s: 1, fault: bus_off}}\n"
                            "  - {{type: imu, start_s: 4, duration_s: 1, fault: error_frames, rate_hz: 20}}\n",
                            (dir / "imu.log").string()),
                6.0);
  const auto st = nav.child().wait_exit(30.0);
  ASSERT_TRUE(st && WIFEXITED(*st) && WEXITSTATUS(*st) == 0) << describe_status(st) << nav.diagnostics();
  const CandumpResult rec = dump.finish();
  ASSERT_TRUE(rec.ended) << rec.problem << dump.diagnostics();
  const std::string err = nav.err();
  const auto bus_off = announced_event_start(err, "IMU CAN bus-off");
  const auto errors = announced_event_start(err, "IMU CAN error frames");
  ASSERT_TRUE(bus_off && errors) << nav.diagnostics();
  const double off_s = static_cast<double>(unix_ns_from_gps(*bus_off)) * 1e-9;
  const double errors_s = static_cast<double>(unix_ns_from_gps(*errors)) * 1e-9;

  std::vector<LoggedFrame> samples;
  std::vector<double> off_at, restarted_at, bus_errors_at;
  bool off = false;
  std::size_t frames_while_off = 0;
  for (const LoggedFrame& f : rec.frames) {
    if ((f.id & 0x20000000u) == 0) {
      frames_while_off += off ? 1 : 0;
      samples.push_back(f);
      continue;
    }
    ASSERT_EQ(f.data.size(), 8u);
    if (f.id == 0x20000040u) {
      off_at.push_back(f.t_s);
      off = true;
    } else if (f.id == 0x20000100u) {
      restarted_at.push_back(f.t_s);
      off = false;
    } else if (f.id == 0x20000088u) {
      bus_errors_at.push_back(f.t_s);
      EXPECT_EQ(f.data[2], 0x04) << "a stuffing error";
    } else {
      ADD_FAILURE() << "an error frame of class " << std::hex << f.id;
    }
  }
  ASSERT_EQ(off_at.size(), 1u) << dump.diagnostics();
  ASSERT_EQ(restarted_at.size(), 1u);
  EXPECT_NEAR(off_at[0], off_s, 0.1);
  EXPECT_NEAR(restarted_at[0], off_s + 1.0, 0.1);
  EXPECT_EQ(frames_while_off, 0u);
  // What navemu reports sending (a sample the real-time loop skipped as late sends none).
  std::smatch m;
  static const std::regex sent_re(R"((\d+) lost to a CAN bus-off, (\d+) CAN error frames)");
  ASSERT_TRUE(std::regex_search(err, m, sent_re)) << nav.diagnostics();
  EXPECT_NEAR(std::stod(m[1]), 125.0, 5.0) << "1 s at 125 Hz";
  EXPECT_NEAR(std::stod(m[2]), 20.0, 1.0);
  if (rec.dropped == 0) {
    EXPECT_EQ(bus_errors_at.size(), std::stoul(m[2]));
  }
  for (double t : bus_errors_at) EXPECT_TRUE(t > errors_s - 0.1 && t < errors_s + 1.1) << t - errors_s;
  const CanCheck c = check_frames_against_log(samples, read_imu_rows(dir / "imu.log"));
  EXPECT_EQ(c.mismatches, 0u) << c.first_problem;
  std::printf("bus-off: error frame %+.3f s from its start, restarted %+.3f s after its end, %zu frames between; "
              "%zu bus-error frames; %zu IMU frames decoded, %llu dropped by candump\n",
              off_at[0] - off_s, restarted_at[0] - off_s - 1.0, frames_while_off, bus_errors_at.size(), samples.size(),
              static_cast<unsigned long long>(rec.dropped));
}

}  // namespace
}  // namespace navemu::test::clients
