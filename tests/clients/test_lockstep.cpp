// Lockstep mode (scenario.time: lockstep): GPS time follows the truth stream. One test per
// sentence of the README's lockstep paragraph, in its order, each against `navemu run` on a pty
// with a truth stream of JSON datagrams stamped with the simulator's own GPS time.

#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>

#include "tests/clients/client_support.hpp"

namespace navemu::test::clients {
namespace {

const Geodetic kSite{32.3, -90.9, 60.0};
// The simulator's clock: a scenario in the past, unrelated to the host's clock.
const GpsTime kSimStart = parse_time("2023-01-08T10:00:00.010Z");

std::string lockstep_config(const fs::path& link, const std::string& truth_extra = "") {
  return fmt::format(
      "scenario: {{time: lockstep, status_interval_s: 0.5}}\n"
      "truth: {{source: udp, udp: {{port: 0}}{}}}\n"
      "gnss:\n  outputs:\n    - {{type: pty, link: '{}'}}\n"
      "imu: {{enabled: false}}\n",
      truth_extra, link.string());
}

// A simulator sending its state every 0.02 s of its own time; `pace` is simulated seconds per
// wall second.
struct Simulator {
  TruthSender sender;
  GpsTime t = kSimStart;
  explicit Simulator(int port) : sender(port) {}
  // Sends `seconds` of simulated time at `pace`, reading the pty meanwhile.
  void run(double seconds, double pace, PtyReader& reader, std::vector<Received>& lines) {
    const double wall0 = mono_s();
    const int n = static_cast<int>(std::llround(seconds / 0.02));
    for (int k = 0; k < n; ++k) {
      reader.read_until(wall0 + 0.02 * k / pace, lines);
      sender.send_at(kSite, t);
      t = t.plus_s(0.02);
    }
  }
};

struct Started {
  TempDir dir;
  fs::path link;
  NavemuRun nav;
  int port = 0;
  Started(const std::string& name, const std::string& truth_extra = "", double duration_s = 60)
      : dir(name), link(dir / "gnss"), nav(dir, "navemu", lockstep_config(link, truth_extra), duration_s) {}
  // The ports are there and navemu says where it waits; false (with the reason logged) if not.
  bool ready() {
    const std::optional<int> p = nav.wait_for_udp_port(5.0);
    if (!p || !nav.wait_for_pty(link, 5.0)) {
      ADD_FAILURE() << "navemu not ready" << nav.diagnostics();
      return false;
    }
    port = *p;
    return true;
  }
};

// "The ports are created at start, so clients (gpsd) can attach before the simulator sends
// anything."
TEST(Lockstep, PortsExistBeforeTheFirstDatagram) {
  Started s("lockstep-ports");
  ASSERT_TRUE(s.ready());
  PtyReader reader;
  ASSERT_TRUE(reader.open(s.link)) << "the pty cannot be opened before the first datagram";
  std::vector<Received> lines;
  reader.read_until(mono_s() + 1.0, lines);
  EXPECT_TRUE(lines.empty()) << "output before any truth: " << lines.front().text;
  // The client that attached first receives the epochs once the stream begins.
  Simulator sim(s.port);
  sim.run(1.0, 1.0, reader, lines);
  reader.read_until(mono_s() + 0.5, lines);
  s.nav.stop_expecting_exit_0();
  EXPECT_GE(rmcs(lines).size(), 3u) << s.nav.diagnostics();
}

// "Until the first datagram arrives, the status line says `waiting for truth on udp
// ADDRESS:PORT`."
TEST(Lockstep, WhileWaitingTheStatusLineSaysWhereItWaits) {
  Started s("lockstep-waiting");
  ASSERT_TRUE(s.ready());
  const std::string expected = fmt::format("navemu: waiting for truth on udp 127.0.0.1:{} (", s.port);
  EXPECT_TRUE(wait_until([&] { return count_lines_with(s.nav.err(), expected) >= 2; }, 5.0))
      << s.nav.diagnostics();
  s.nav.stop_expecting_exit_0();
}

// "If none arrives within `truth.first_wait_s` (default 120 s; 0: no limit), navemu stops with
// an error and exit status 1."
TEST(Lockstep, WithoutAnyDatagramItGivesUpAfterFirstWait) {
  Started s("lockstep-give-up", ", first_wait_s: 1.5");
  ASSERT_TRUE(s.ready());
  const std::optional<int> st = s.nav.child().wait_exit(10.0);
  const double after_s = mono_s() - s.nav.started_mono();
  ASSERT_TRUE(st && WIFEXITED(*st) && WEXITSTATUS(*st) == 1) << describe_status(st) << s.nav.diagnostics();
  EXPECT_GE(after_s, 1.5);
  EXPECT_LE(after_s, 6.0);
  EXPECT_NE(s.nav.err().find(fmt::format("no truth datagram on udp 127.0.0.1:{} within 1.5 s", s.port)),
            std::string::npos)
      << s.nav.diagnostics();
  EXPECT_FALSE(fs::exists(fs::symlink_status(s.link))) << "the pty link is left behind";
}

// "The scenario starts at the first datagram's time, and `--duration` counts scenario time
// from there."
TEST(Lockstep, TheScenarioStartsAtTheFirstDatagramAndDurationIsScenarioTime) {
  Started s("lockstep-duration", "", 2.0);
  ASSERT_TRUE(s.ready());
  PtyReader reader;
  ASSERT_TRUE(reader.open(s.link));
  std::vector<Received> lines;
  reader.read_until(mono_s() + 2.5, lines);  // longer than --duration: the wait does not count
  ASSERT_TRUE(s.nav.child().running()) << "stopped before the first datagram" << s.nav.diagnostics();
  Simulator sim(s.port);
  sim.run(3.0, 1.0, reader, lines);
  const std::optional<int> st = s.nav.child().wait_exit(5.0);
  ASSERT_TRUE(st && WIFEXITED(*st) && WEXITSTATUS(*st) == 0) << describe_status(st) << s.nav.diagnostics();
  reader.read_until(mono_s() + 0.2, lines);
  // 2 s of scenario at 5 Hz: the epochs .2 .4 ... after the first datagram's time, 10 of them.
  const std::vector<Rmc> r = rmcs(lines);
  ASSERT_EQ(r.size(), 10u) << s.nav.diagnostics();
  const std::int64_t first_ms = unix_ns_from_gps(kSimStart) / 1'000'000;
  EXPECT_EQ(r.front().unix_ms, (first_ms / 200 + 1) * 200);
  for (std::size_t i = 1; i < r.size(); ++i) EXPECT_EQ(r[i].unix_ms - r[i - 1].unix_ms, 200);
  EXPECT_NE(s.nav.err().find(fmt::format("scenario start {}", format_iso_utc(kSimStart))), std::string::npos)
      << s.nav.diagnostics();
}

// "An epoch is computed once the truth has passed it, so the outputs keep the simulator's pace,
// faster or slower than real time."
TEST(Lockstep, TheOutputsKeepTheSimulatorsPace) {
  Started s("lockstep-pace");
  ASSERT_TRUE(s.ready());
  PtyReader reader;
  ASSERT_TRUE(reader.open(s.link));
  std::vector<Received> lines;
  Simulator sim(s.port);
  const double t0 = mono_s();
  sim.run(20.0, 10.0, reader, lines);  // 20 s of simulation in 2 s
  const double fast_s = mono_s() - t0;
  reader.read_until(mono_s() + 0.3, lines);
  const std::size_t fast_epochs = rmcs(lines).size();
  sim.run(1.0, 0.5, reader, lines);  // 1 s of simulation in 2 s
  reader.read_until(mono_s() + 0.3, lines);
  s.nav.stop_expecting_exit_0();
  const std::vector<Rmc> r = rmcs(lines);
  // Every epoch of the 21 s once (the last one or two may wait for truth past them).
  EXPECT_NEAR(static_cast<double>(fast_epochs), 100.0, 1.0) << "in " << fast_s << " s";
  EXPECT_NEAR(static_cast<double>(r.size()), 105.0, 2.0);
  for (std::size_t i = 1; i < r.size(); ++i) EXPECT_EQ(r[i].unix_ms - r[i - 1].unix_ms, 200);
  for (const Rmc& m : r) EXPECT_TRUE(m.valid);
  // Arrival: the fast part took about 2 s of wall time, the slow second about 2 s.
  std::printf("lockstep pace: 20 s of scenario in %.2f s of wall time (%zu epochs)\n", fast_s, fast_epochs);
}

// "When the stream pauses, time stands still: no epoch goes out, and the status line says
// `truth paused for N s`."
TEST(Lockstep, APauseStandsTimeStillAndIsReportedAsSuch) {
  Started s("lockstep-pause");
  ASSERT_TRUE(s.ready());
  PtyReader reader;
  ASSERT_TRUE(reader.open(s.link));
  std::vector<Received> lines;
  Simulator sim(s.port);
  sim.run(2.0, 1.0, reader, lines);
  reader.read_until(mono_s() + 0.3, lines);  // the epochs the stream has passed
  const std::size_t before = lines.size();
  reader.read_until(mono_s() + 2.5, lines);  // the simulator is paused
  const std::size_t during = lines.size() - before;
  sim.run(2.0, 1.0, reader, lines);  // and goes on where it stopped
  reader.read_until(mono_s() + 0.3, lines);
  s.nav.stop_expecting_exit_0();
  EXPECT_EQ(during, 0u) << "output while the stream was paused";
  const std::vector<Rmc> r = rmcs(lines);
  EXPECT_GE(r.size(), 18u);
  for (std::size_t i = 1; i < r.size(); ++i) EXPECT_EQ(r[i].unix_ms - r[i - 1].unix_ms, 200);
  for (const Rmc& m : r) EXPECT_TRUE(m.valid);
  bool paused = false;
  for (const StatusLine& sl : status_lines(s.nav.err())) paused = paused || sl.truth == "paused";
  EXPECT_TRUE(paused) << s.nav.diagnostics();
  EXPECT_GE(count_lines_with(s.nav.err(), "| truth paused for 2 s"), 1) << s.nav.diagnostics();
}

// "When datagrams come but none can be taken, it says `truth rejecting`."
TEST(Lockstep, DatagramsThatAreAllRefusedAreReportedAsRejecting) {
  Started s("lockstep-rejecting");
  ASSERT_TRUE(s.ready());
  PtyReader reader;
  ASSERT_TRUE(reader.open(s.link));
  std::vector<Received> lines;
  Simulator sim(s.port);
  sim.run(1.0, 1.0, reader, lines);
  // 2 s of datagrams 200 km up: refused (out of range), time stands still.
  const double t0 = mono_s();
  const Geodetic too_high{kSite.lat_deg, kSite.lon_deg, 200e3};
  for (int k = 0; k < 100; ++k) {
    reader.read_until(t0 + 0.02 * k, lines);
    sim.sender.send_at(too_high, sim.t);
    sim.t = sim.t.plus_s(0.02);
  }
  s.nav.stop_expecting_exit_0();
  bool rejecting = false;
  for (const StatusLine& sl : status_lines(s.nav.err()))
    rejecting = rejecting || (sl.truth == "rejecting" && sl.truth_counts.find("range") != std::string::npos);
  EXPECT_TRUE(rejecting) << s.nav.diagnostics();
}

// "A stream whose time jumps is re-synchronised (see the truth paragraph) and continues one
// step after the scenario's time: GPS time never runs backwards."
TEST(Lockstep, AStreamThatJumpsBackIsResynchronisedAndTimeGoesOn) {
  Started s("lockstep-jump");
  ASSERT_TRUE(s.ready());
  PtyReader reader;
  ASSERT_TRUE(reader.open(s.link));
  std::vector<Received> lines;
  Simulator sim(s.port);
  sim.run(2.0, 1.0, reader, lines);
  sim.t = kSimStart;  // the simulator restarts its scenario
  sim.run(2.0, 1.0, reader, lines);
  reader.read_until(mono_s() + 0.3, lines);
  s.nav.stop_expecting_exit_0();
  const std::vector<Rmc> r = rmcs(lines);
  EXPECT_GE(r.size(), 18u);
  for (std::size_t i = 1; i < r.size(); ++i) EXPECT_EQ(r[i].unix_ms - r[i - 1].unix_ms, 200);
  EXPECT_NE(s.nav.err().find("re-synchronised after 3 consistent datagrams"), std::string::npos)
      << s.nav.diagnostics();
  const auto summary = run_summary(s.nav.err());
  ASSERT_TRUE(summary) << s.nav.diagnostics();
  EXPECT_EQ(summary->truth_reasons, "backwards 2; resync 1");
}

}  // namespace
}  // namespace navemu::test::clients
