// `navemu run` under faults a real installation meets: a client that closes and reopens the pty,
// a pty nobody reads, broken truth datagrams, SIGTERM or SIGINT while it is sending, a second
// navemu on the same pty link and a killed one's link left behind, a full disk under the IMU
// log, a TCP client that comes and goes, a client flooding garbage into a u-blox port, and a
// truth stream that jumps 1000 km or stops for 2 s.

#include <gtest/gtest.h>
#include <pwd.h>

#include <fmt/format.h>

#include <array>
#include <atomic>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <random>
#include <regex>
#include <sstream>
#include <stop_token>
#include <thread>

#include "models/geodesy.hpp"
#include "protocols/nmea.hpp"
#include "protocols/truth_datagram.hpp"
#include "tests/clients/client_support.hpp"

namespace navemu::test::clients {
namespace {

const Geodetic kSite{32.3, -90.9, 60.0};  // the paper's test site

// A stationary truth at kSite, the GNSS `profile` with one output and the IMU section as given
// (YAML flow maps).
std::string stationary_config_with_output(const std::string& output, const std::string& profile,
                                         const std::string& imu = "{enabled: false}") {
  return fmt::format(
      "truth: {{source: stationary, position: {{lat_deg: {}, lon_deg: {}, h_m: {}}}}}\n"
      "gnss:\n  profile: {}\n  outputs:\n    - {}\n"
      "imu: {}\n",
      kSite.lat_deg, kSite.lon_deg, kSite.h_m, profile, output, imu);
}
// The same with the output a pty at `link`.
std::string stationary_config(const fs::path& link, const std::string& profile,
                              const std::string& imu = "{enabled: false}") {
  return stationary_config_with_output(fmt::format("{{type: pty, link: '{}'}}", link.string()),
                                      profile, imu);
}

// Checks one client session: at most a leading fragment (the rest of a sentence an earlier
// client left half-read: on a tty, as on a serial line opened mid-stream, the stream goes on
// where the last reader stopped; not allowed when `fragment_allowed` is false, e.g. on TCP,
// where a new connection starts with the next whole chunk), then only whole, checksum-valid
// sentences, and RMC times `period_ms` apart (0.2 s: the 5 Hz profiles). Returns the number of
// RMCs.
int check_session(const std::vector<Received>& lines, const std::string& what,
                  std::int64_t period_ms = 200, bool fragment_allowed = true) {
  SCOPED_TRACE(what);
  int rmc = 0;
  std::int64_t last = -1;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::string& t = lines[i].text;
    if (i == 0 && fragment_allowed && (t.empty() || t[0] != '$')) continue;
    const auto f = nmea::parse(t);
    EXPECT_TRUE(f) << "line " << i << ": '" << t << "'";
    if (!f || (*f)[0].substr(2) != "RMC") continue;
    const std::int64_t ms = rmc_unix_ms(*f);
    if (last >= 0) {
      EXPECT_EQ(ms - last, period_ms) << "RMC at line " << i;
    }
    last = ms;
    ++rmc;
  }
  return rmc;
}

// (a) A client closes the pty in the middle of a sentence and opens it again, three times:
// after each reopening it receives whole, checksum-valid sentences and every epoch.
TEST(Faults, ClientClosesAndReopensThePtyMidStream) {
  TempDir dir("reopen");
  const fs::path link = dir / "gnss";
  NavemuRun nav(dir, "navemu", stationary_config(link, "garmin-18x-5hz"), 40);
  ASSERT_TRUE(nav.wait_for_pty(link, 5.0)) << nav.diagnostics();

  PtyReader reader;
  ASSERT_TRUE(reader.open(link));
  std::vector<Received> lines;
  reader.read_until(mono_s() + 1.0, lines);
  check_session(lines, "first session");
  int mid_sentence_closes = 0;
  for (int cycle = 0; cycle < 3; ++cycle) {
    // Wait for the next epoch and take only its first 30 bytes: the close lands mid-sentence.
    std::vector<Received> ignored;
    reader.read_some(30, 1.0, ignored);
    if (!reader.partial().empty()) ++mid_sentence_closes;
    reader.close();
    sleep_s(0.3);  // epochs keep coming meanwhile, queued for the next client
    ASSERT_TRUE(reader.open(link)) << "cycle " << cycle;
    lines.clear();
    reader.read_until(mono_s() + 1.5, lines);
    EXPECT_GE(check_session(lines, fmt::format("after reopening {}", cycle)), 7)
        << "1.5 s plus the queued epochs at 5 Hz" << nav.diagnostics();
  }
  EXPECT_GE(mid_sentence_closes, 2) << "the closes should fall inside sentences";
  nav.stop_expecting_exit_0();
  const auto s = run_summary(nav.err());
  ASSERT_TRUE(s) << nav.diagnostics();
  EXPECT_EQ(s->skipped, 0) << nav.diagnostics();
}

// (b) Nobody reads the pty. TESTING.md: a pty with no reader fills after about 17-20 KB and
// then blocks writes. The u-blox profile sends about 2.6 KB/s, so 20 s of silence is more than
// twice what the kernel can hold (checked below from the measured rate): a writer that blocked
// would stall within the first 8 s. (The issue asks for 30 s; 20 s proves the same at this rate
// and keeps the suite within its time budget.) navemu must go on: a status line every second,
// five epochs per second, none skipped; and a reader that comes back gets at most about 4 KB of
// old output (the pty's max_backlog_bytes), the newest epochs only, no stale burst.
TEST(Faults, NobodyReadingNeverBlocksAndNoStaleBurstAfterwards) {
  constexpr double kSilence_s = 20.0;
  TempDir dir("no-reader");
  const fs::path link = dir / "gnss";
  NavemuRun nav(dir, "navemu", stationary_config(link, "ublox-nmea-5hz"), 60);
  ASSERT_TRUE(nav.wait_for_pty(link, 5.0)) << nav.diagnostics();
  const double silence_start = mono_s();
  sleep_s(kSilence_s);
  ASSERT_TRUE(nav.child().running()) << nav.diagnostics();

  // navemu kept going: status lines one second apart, each five epochs on.
  const std::vector<StatusLine> status = status_lines(nav.err());
  EXPECT_GE(status.size(), static_cast<std::size_t>(kSilence_s) - 2) << nav.diagnostics();
  for (std::size_t i = 1; i < status.size(); ++i) {
    EXPECT_EQ((status[i].second_of_day - status[i - 1].second_of_day + 86400) % 86400, 1);
    EXPECT_NEAR(static_cast<double>(status[i].epochs - status[i - 1].epochs), 5.0, 1.0);
  }
  // A blocked write would stall the loop and its missed epochs be skipped; on a busy machine a
  // stall over 200 ms may skip one now and then, so allow 2.
  ASSERT_FALSE(status.empty());
  EXPECT_LE(status.back().skipped, 2) << nav.diagnostics();

  // The reader comes back: what waits for it is one read's worth, the newest epochs.
  PtyReader reader;
  ASSERT_TRUE(reader.open(link));
  const double now_real = real_s();
  std::vector<Received> batch;
  std::string raw;
  reader.drain(batch, &raw);
  std::vector<Received> later;
  const double t_later = mono_s();
  const std::size_t later_bytes = reader.read_until(t_later + 3.0, later);
  nav.stop_expecting_exit_0();

  // The largest epoch (whole seconds carry GSV) bounds what may arrive during the drain itself.
  std::size_t max_epoch = 0, epoch = 0;
  for (const Received& r : later) {
    if (r.is("RMC")) epoch = 0;
    epoch += r.text.size() + 2;
    max_epoch = std::max(max_epoch, epoch);
  }
  EXPECT_LE(raw.size(), 4096 + max_epoch) << "old output waiting for the returning reader";
  EXPECT_FALSE(raw.empty());
  EXPECT_EQ(raw.substr(0, 1), "$") << "the old output starts at a sentence";
  std::int64_t oldest = std::numeric_limits<std::int64_t>::max(), newest = -1;
  for (const Received& r : batch) {
    const auto f = nmea::parse(r.text);
    EXPECT_TRUE(f) << "'" << r.text << "'";
    if (!f || (*f)[0] != "GPRMC") continue;
    oldest = std::min(oldest, rmc_unix_ms(*f));
    newest = std::max(newest, rmc_unix_ms(*f));
  }
  ASSERT_GE(newest, 0) << "no RMC in the first batch";
  // The old output is bounded in bytes (the pty's max_backlog_bytes, 4096, plus the epoch in
  // flight); at this profile's ~2 KB/s that is at most about two seconds of epochs, never the
  // silence's twenty.
  const double later_rate_bps = static_cast<double>(later_bytes) / 3.0;
  const double max_span_ms = 1e3 * static_cast<double>(4096 + max_epoch) / later_rate_bps + 200.0;
  EXPECT_LE(static_cast<double>(newest - oldest), max_span_ms)
      << "RMC times in the first batch span more than the backlog limit holds";
  EXPECT_LE(now_real * 1e3 - static_cast<double>(newest), 1500.0) << "the newest epoch is stale";
  EXPECT_GE(check_session(later, "after the silence"), 13);

  // The premise: at this rate the silence produced more than the pty could ever hold.
  const double rate_bps = static_cast<double>(later_bytes) / 3.0;
  EXPECT_GT(rate_bps * (mono_s() - silence_start - 3.0), 1.5 * 20'000.0)
      << "output rate " << rate_bps << " B/s";
  RecordProperty("first_batch_bytes", static_cast<int>(raw.size()));
  std::printf("silence %.0f s at %.0f B/s; first batch %zu bytes, RMC span %lld ms, newest %.0f ms old\n",
              kSilence_s, rate_bps, raw.size(), static_cast<long long>(newest - oldest),
              now_real * 1e3 - static_cast<double>(newest));
}

// (b2) The counters of outputs nobody takes, in the status and summary lines in the same
// words: a pty nobody reads has its stale output flushed (counted in flushes and bytes), and an
// slcan channel no client opened holds its CAN frames back (counted as held, not as dropped).
TEST(Faults, StatusAndSummaryCountUnreadOutputInTheSameWords) {
  TempDir dir("counters");
  const fs::path link = dir / "gnss", imu_link = dir / "imu";
  NavemuRun nav(dir, "navemu",
                stationary_config(link, "ublox-nmea-5hz",
                                  fmt::format("{{outputs: [{{type: slcan, link: '{}', layouts: [j1939]}}]}}",
                                              imu_link.string())),
                60);
  ASSERT_TRUE(nav.wait_for_pty(link, 5.0)) << nav.diagnostics();
  sleep_s(12.0);  // > 20 KB of NMEA: the pty fills and stale output is flushed
  nav.stop_expecting_exit_0();
  const std::vector<StatusLine> status = status_lines(nav.err());
  ASSERT_GE(status.size(), 8u) << nav.diagnostics();
  EXPECT_EQ(status.back().dropped, 0) << "frames held back counted as dropped" << nav.diagnostics();
  const std::regex held_status(R"(dropped 0 chunks 0 frames, (\d+) frames held \|)");
  std::smatch m;
  std::string last_status;
  std::stringstream lines(nav.err());
  for (std::string l; std::getline(lines, l);)
    if (l.find(" UTC gnss ") != std::string::npos) last_status = l;
  ASSERT_TRUE(std::regex_search(last_status, m, held_status)) << last_status;
  EXPECT_GE(std::stol(m[1]), 2 * 125 * 8);  // two J1939 frames per sample at 125 Hz
  const auto s = run_summary(nav.err());
  ASSERT_TRUE(s) << nav.diagnostics();
  EXPECT_GT(s->stale_flushes, 0) << nav.diagnostics();
  const std::regex held_summary(
      R"(0 CAN frames \(0 dropped, 0 failed, 0 bus errors\), (\d+) CAN frames held back \(no client opened the slcan channel\))");
  const std::string err = nav.err();
  ASSERT_TRUE(std::regex_search(err, m, held_summary)) << nav.diagnostics();
  EXPECT_GE(std::stol(m[1]), 2 * 125 * 10);
}

// (c) Truth datagrams with NaN, a bad CRC or a time going backwards, among good ones: each is
// rejected and counted, none moves the fix. The faulty ones carry a position 1 km away, so one
// that slipped through would show in the fix.
TEST(Faults, BadTruthDatagramsAreRejectedAndTheFixStaysGood) {
  TempDir dir("bad-truth");
  const fs::path link = dir / "gnss";
  NavemuRun nav(dir, "navemu",
                fmt::format("truth: {{source: udp, udp: {{port: 0}}, timeout_s: 1.0}}\n"
                            "gnss:\n  outputs:\n    - {{type: pty, link: '{}'}}\n"
                            "imu: {{enabled: false}}\n",
                            link.string()),
                60);
  const std::optional<int> port = nav.wait_for_udp_port(5.0);
  ASSERT_TRUE(port) << nav.diagnostics();
  ASSERT_TRUE(nav.wait_for_pty(link, 5.0)) << nav.diagnostics();
  PtyReader reader;
  ASSERT_TRUE(reader.open(link));
  reader.discard_queued();
  std::vector<Received> lines;

  const int fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  ASSERT_GE(fd, 0);
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  to.sin_port = htons(static_cast<std::uint16_t>(*port));
  const auto send = [&](std::array<std::uint8_t, truth_datagram::kBinarySize> d) {
    ::sendto(fd, d.data(), d.size(), 0, reinterpret_cast<const sockaddr*>(&to), sizeof to);
  };
  truth_datagram::Message good;
  good.time_base = truth_datagram::TimeBase::kHostUtc;
  good.position = {kSite.lat_deg, kSite.lon_deg, kSite.h_m};
  truth_datagram::Message far = good;
  far.position[0] += 0.009;  // 1 km north

  // 10 Hz of good truth for 8 s; every fifth step one faulty datagram: NaN, bad CRC, backwards.
  int good_sent = 0, nan_sent = 0, crc_sent = 0, backwards_sent = 0;
  std::uint32_t seq = 0;
  const double t0 = mono_s();
  for (int k = 0; k < 80; ++k) {
    reader.read_until(t0 + 0.1 * k, lines);
    const auto now_ns = static_cast<std::int64_t>(std::llround(real_s() * 1e9));
    good.sequence = seq++;
    good.time_ns = now_ns;
    send(truth_datagram::encode_binary(good));
    ++good_sent;
    if (k % 5 != 4) continue;
    far.sequence = seq++;
    switch ((k / 5) % 3) {
      case 0: {
        truth_datagram::Message nan = far;
        nan.time_ns = now_ns + 1'000'000;
        nan.position[0] = std::numeric_limits<double>::quiet_NaN();
        send(truth_datagram::encode_binary(nan));
        ++nan_sent;
        break;
      }
      case 1: {
        far.time_ns = now_ns + 1'000'000;
        auto d = truth_datagram::encode_binary(far);
        d[truth_datagram::kBinarySize - 1] ^= 0xFF;
        send(d);
        ++crc_sent;
        break;
      }
      default:
        far.time_ns = now_ns - 500'000'000;
        send(truth_datagram::encode_binary(far));
        ++backwards_sent;
        break;
    }
  }
  ::close(fd);
  reader.read_until(mono_s() + 0.3, lines);
  nav.stop_expecting_exit_0();
  ASSERT_GT(nan_sent, 0);
  ASSERT_GT(crc_sent, 0);
  ASSERT_GT(backwards_sent, 0);

  const auto s = run_summary(nav.err());
  ASSERT_TRUE(s) << nav.diagnostics();
  EXPECT_EQ(s->truth_accepted, good_sent) << nav.diagnostics();
  EXPECT_EQ(s->truth_rejected, nan_sent + crc_sent + backwards_sent) << nav.diagnostics();

  // From the first fix on, every epoch has one, at the truth (bounds as for gpsd: consumer
  // standalone receiver, 15 m horizontal).
  int fixes = 0;
  bool fixed = false;
  for (const Received& r : lines) {
    const auto f = nmea::parse(r.text);
    EXPECT_TRUE(f) << "'" << r.text << "'";
    if (!f || (*f)[0] != "GPRMC") continue;
    if ((*f)[2] == "A") fixed = true;
    if (!fixed) continue;
    EXPECT_EQ((*f)[2], "A") << r.text;
    if ((*f)[2] != "A") continue;
    ++fixes;
    const Vec3 e = enu_from_ecef(ecef_from_geodetic(Geodetic{nmea_degrees((*f)[3], (*f)[4]),
                                                             nmea_degrees((*f)[5], (*f)[6]),
                                                             kSite.h_m}),
                                 kSite);
    EXPECT_LE(std::hypot(e.x(), e.y()), 15.0) << r.text;
  }
  EXPECT_GE(fixes, 30) << nav.diagnostics();
  bool seen_ok = false;
  for (const StatusLine& sl : status_lines(nav.err())) {
    if (sl.truth_ok) seen_ok = true;
    if (seen_ok) {
      EXPECT_TRUE(sl.truth_ok) << "truth lost while good datagrams kept coming";
    }
  }
}

// (d) SIGTERM, or SIGINT (Ctrl-C), while epochs are going out: navemu exits 0 within 2 s,
// removes its pty link and prints its summary.
void check_stop_signal_during_output(int sig, const std::string& name) {
  TempDir dir(name);
  const fs::path link = dir / "gnss";
  NavemuRun nav(dir, "navemu", stationary_config(link, "garmin-18x-5hz"), 60);
  ASSERT_TRUE(nav.wait_for_pty(link, 5.0)) << nav.diagnostics();
  PtyReader reader;
  ASSERT_TRUE(reader.open(link));
  std::vector<Received> lines;
  reader.read_until(mono_s() + 2.0, lines);
  // The signal goes right after the first bytes of an epoch arrive, while it is being sent.
  std::vector<Received> ignored;
  reader.read_some(20, 1.0, ignored);
  const double t_signal = mono_s();
  nav.child().signal(sig);
  const std::optional<int> st = nav.child().wait_exit(2.0);
  const double took = mono_s() - t_signal;
  ASSERT_TRUE(st) << "still running 2 s after " << name << nav.diagnostics();
  EXPECT_TRUE(WIFEXITED(*st) && WEXITSTATUS(*st) == 0) << describe_status(st);
  EXPECT_LE(took, 2.0);
  EXPECT_EQ(fs::symlink_status(link).type(), fs::file_type::not_found) << "pty link left behind";
  const auto s = run_summary(nav.err());
  ASSERT_TRUE(s) << "no summary line" << nav.diagnostics();
  EXPECT_GE(s->epochs, 10);
  std::printf("exited %.3f s after %s\n", took, name.c_str());
}

TEST(Faults, SigtermDuringOutputExitsCleanly) { check_stop_signal_during_output(SIGTERM, "sigterm"); }

TEST(Faults, SigintDuringOutputExitsCleanly) { check_stop_signal_during_output(SIGINT, "sigint"); }

// The pty slave navemu announced for `link` ("GNSS NMEA on pty LINK -> /dev/pts/N"); empty if
// none.
std::string announced_slave(const std::string& err, const fs::path& link) {
  const std::string key = "on pty " + link.string() + " -> ";
  const std::size_t at = err.find(key);
  if (at == std::string::npos) return {};
  const std::size_t from = at + key.size();
  return err.substr(from, err.find_first_of(",\n", from) - from);
}

// (d2) One owner per pty link. A second navemu on the link of a running one stops at once with
// one line naming the link and the owner's pid, and leaves the first one's link alone: a
// client still gets its sentences. A navemu killed with SIGKILL cannot remove its link (nor
// its lock file): the next navemu takes them over, and exits cleanly removing both.
TEST(Faults, ASecondNavemuOnALinkIsRefusedAndAKilledOnesLinkIsTakenOver) {
  TempDir dir("one-owner");
  const fs::path link = dir / "gnss";
  const fs::path lock = dir / "gnss.lock";
  const std::string config = stationary_config(link, "garmin-18x-5hz");
  NavemuRun first(dir, "first", config, 60);
  ASSERT_TRUE(first.wait_for_pty(link, 5.0)) << first.diagnostics();
  const std::string first_slave = announced_slave(first.err(), link);
  ASSERT_EQ(fs::read_symlink(link).string(), first_slave) << first.diagnostics();

  NavemuRun second(dir, "second", config, 60);
  const std::optional<int> st = second.child().wait_exit(10.0);
  ASSERT_TRUE(st) << "the second navemu is still running" << second.diagnostics();
  EXPECT_TRUE(WIFEXITED(*st) && WEXITSTATUS(*st) == 1) << describe_status(st);
  EXPECT_EQ(second.err(), fmt::format("navemu: error: pty link {} is in use by navemu (pid {})\n",
                                      link.string(), first.child().pid()));

  // RMCs a client of the link gets in 1.5 s (5 Hz: 7 or 8).
  const auto rmcs_on_link = [&](const std::string& what) {
    PtyReader reader;
    if (!reader.open(link)) return 0;
    reader.discard_queued();
    std::vector<Received> lines;
    reader.read_until(mono_s() + 1.5, lines);
    return check_session(lines, what);
  };
  ASSERT_TRUE(first.child().running()) << first.diagnostics();
  EXPECT_EQ(fs::read_symlink(link).string(), first_slave) << "the first navemu's link was touched";
  EXPECT_GE(rmcs_on_link("the first navemu after the second one's attempt"), 6)
      << first.diagnostics();

  first.child().signal(SIGKILL);
  ASSERT_TRUE(first.child().wait_exit(5.0));
  ASSERT_TRUE(fs::is_symlink(link)) << "a killed navemu leaves its link behind";
  ASSERT_TRUE(fs::exists(lock)) << "and its lock file";

  NavemuRun third(dir, "third", config, 60);
  ASSERT_TRUE(third.wait_for_pty(link, 5.0)) << third.diagnostics();
  const std::string third_slave = announced_slave(third.err(), link);
  EXPECT_EQ(fs::read_symlink(link).string(), third_slave) << third.diagnostics();
  EXPECT_EQ(slurp(lock), fmt::format("{}\n", third.child().pid()));
  EXPECT_GE(rmcs_on_link("the navemu that took the link over"), 6) << third.diagnostics();
  third.stop_expecting_exit_0();
  EXPECT_EQ(fs::symlink_status(link).type(), fs::file_type::not_found) << "pty link left behind";
  EXPECT_EQ(fs::symlink_status(lock).type(), fs::file_type::not_found) << "lock file left behind";
}

// (e) The disk of the IMU log is full (/dev/full: every write fails with ENOSPC). navemu says so
// once, in one line naming the log and the error, and goes on: the pty output keeps its 5 Hz
// cadence, and it exits 0 with its summary. (gnss.capture cannot point at /dev/full: navemu
// also opens CAPTURE.in, which cannot be created in /dev.)
TEST(Faults, DiskFullForTheImuLogIsReportedOnceAndOutputGoesOn) {
  TempDir dir("disk-full");
  const fs::path link = dir / "gnss";
  NavemuRun nav(dir, "navemu",
                stationary_config(link, "garmin-18x-5hz", "{enabled: true, log: /dev/full}"), 60);
  ASSERT_TRUE(nav.wait_for_pty(link, 5.0)) << nav.diagnostics();
  PtyReader reader;
  ASSERT_TRUE(reader.open(link));
  reader.discard_queued();
  std::vector<Received> lines;
  const double t0 = mono_s();
  reader.read_until(t0 + 3.0, lines);
  // The error is reported while navemu runs (the live logs are written out once a second),
  // not only when it exits.
  const std::string err_running = nav.err();
  ASSERT_TRUE(nav.child().running()) << nav.diagnostics();
  nav.stop_expecting_exit_0();

  const std::string kError = "log /dev/full: No space left on device";
  EXPECT_EQ(count_lines_with(err_running, kError), 1) << nav.diagnostics();
  EXPECT_EQ(count_lines_with(nav.err(), kError), 1) << "reported once" << nav.diagnostics();
  EXPECT_EQ(count_lines_with(nav.err(), "/dev/full"), 2)
      << "the start-up line and the error line only" << nav.diagnostics();
  EXPECT_GE(check_session(lines, "with the IMU log failing"), 13) << "3 s at 5 Hz" << nav.diagnostics();
  const auto s = run_summary(nav.err());
  ASSERT_TRUE(s) << nav.diagnostics();
  EXPECT_EQ(s->skipped, 0) << nav.diagnostics();
  EXPECT_GE(s->epochs, 13) << nav.diagnostics();  // 3 s at 5 Hz, as above
}

// (e2) navemu itself stalls for 1 s (SIGSTOP, as a loaded host can stop it). IMU samples less
// than 500 ms late go out at once; older ones are skipped, and the sequence numbers (one per
// output period, as on the CAN frames) show the gap exactly as the GPS times do, so a driver
// that checks them sees the loss. The summary counts every skipped sample.
TEST(Faults, AStalledImuSkipsOldSamplesAndItsSequenceShowsTheGap) {
  TempDir dir("imu-stall");
  const fs::path log = dir / "imu.log";
  NavemuRun nav(dir, "navemu",
                fmt::format("gnss: {{enabled: false}}\nimu: {{log: '{}', outputs: []}}\n",
                            log.string()),
                60);
  ASSERT_TRUE(wait_until([&] { return fs::exists(log) && fs::file_size(log) > 0; }, 5.0))
      << nav.diagnostics();  // written out at the first status line
  sleep_s(0.5);
  nav.child().signal(SIGSTOP);
  sleep_s(1.0);
  nav.child().signal(SIGCONT);
  sleep_s(1.5);
  nav.stop_expecting_exit_0();

  // imu.log rows: ..., gps_time_ns (column 10), sequence (column 11).
  std::vector<std::pair<std::int64_t, long>> rows;
  std::stringstream in(slurp(log));
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> f;
    std::stringstream ls(line);
    for (std::string x; std::getline(ls, x, ',');) f.push_back(x);
    if (f.size() != 11 || f[0] == "time_s") continue;
    rows.emplace_back(std::stoll(f[9]), std::stol(f[10]));
  }
  ASSERT_GE(rows.size(), 300u) << "about 3 s at 125 Hz" << nav.diagnostics();
  constexpr std::int64_t kPeriodNs = 8'000'000;
  long skipped = 0;
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const std::int64_t dt = rows[i].first - rows[i - 1].first;
    ASSERT_TRUE(dt > 0 && dt % kPeriodNs == 0) << "row " << i << ": " << dt << " ns";
    const long periods = static_cast<long>(dt / kPeriodNs);
    EXPECT_EQ((rows[i].second - rows[i - 1].second) & 0xFFFF, periods & 0xFFFF) << "row " << i;
    skipped += periods - 1;
  }
  // 1 s stopped: about 0.5 s of samples (62) were too late; a loaded host adds to it.
  EXPECT_GE(skipped, 25);
  EXPECT_LE(skipped, 125);
  std::smatch m;
  const std::string err = nav.err();
  ASSERT_TRUE(std::regex_search(err, m, std::regex(R"((\d+) IMU samples \((\d+) skipped\))")))
      << nav.diagnostics();
  EXPECT_EQ(std::stol(m[1]), static_cast<long>(rows.size()));
  EXPECT_EQ(std::stol(m[2]), skipped);
  std::printf("stall 1 s: %zu samples logged, %ld skipped\n", rows.size(), skipped);
}

// A TCP client of navemu's GNSS output: connect to 127.0.0.1:port, read lines with a deadline.
class TcpLineReader {
 public:
  ~TcpLineReader() { close(); }
  bool connect(int port) {
    close();
    fd_ = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    a.sin_port = htons(static_cast<std::uint16_t>(port));
    line_.clear();
    return fd_ >= 0 && ::connect(fd_, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0;
  }
  void close() {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
  }
  const std::string& partial() const { return line_; }
  // Reads until monotonic time `until` or until the server closes (false); complete lines are
  // appended to `out`. With `max_read` > 0: one recv(2) of at most that many bytes once data is
  // there.
  bool read_until(double until, std::vector<Received>& out, std::size_t max_read = 0) {
    for (;;) {
      const double left = until - mono_s();
      if (left <= 0) return true;
      pollfd p{fd_, POLLIN, 0};
      if (::poll(&p, 1, static_cast<int>(std::ceil(left * 1000.0))) <= 0) continue;
      char buf[4096];
      const std::size_t want = max_read > 0 ? std::min(max_read, sizeof buf) : sizeof buf;
      const ssize_t n = ::recv(fd_, buf, want, 0);
      if (n <= 0) return false;
      const double tm = mono_s(), tr = real_s();
      for (ssize_t i = 0; i < n; ++i) {
        if (line_.empty()) {
          t_mono_ = tm;
          t_real_ = tr;
        }
        line_ += buf[i];
        if (buf[i] != '\n') continue;
        std::string text = line_;
        while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
        out.push_back({text, t_mono_, t_real_});
        line_.clear();
      }
      if (max_read > 0) return true;
    }
  }

 private:
  int fd_ = -1;
  std::string line_;
  double t_mono_ = 0, t_real_ = 0;
};

// The port of navemu's TCP output, from its start-up line "GNSS NMEA on tcp 127.0.0.1:N"
// (configured as port 0: the kernel picks a free one, so parallel tests never collide).
std::optional<int> wait_for_tcp_port(NavemuRun& nav, double timeout_s) {
  static const std::regex re(R"(GNSS NMEA on tcp 127\.0\.0\.1:(\d+))");
  std::optional<int> port;
  wait_until(
      [&] {
        const std::string e = nav.err();
        std::smatch m;
        if (std::regex_search(e, m, re)) port = std::stoi(m[1]);
        return port.has_value() || !nav.child().running();
      },
      timeout_s);
  return port;
}

// (f) A TCP client reads for 1.5 s, disconnects in the middle of an epoch (its rest unread in
// the socket) and reconnects, three times. transports/byte_port.hpp: a chunk (one epoch) goes to a client whole
// or not at all, and a new connection gets the chunks written after it was accepted; so every
// session starts at a sentence (no leading fragment, unlike a pty) and holds only whole,
// checksum-valid sentences with RMC times 0.2 s apart. navemu keeps running and exits 0; the
// client sent nothing, so the summary counts 0 bytes from clients.
TEST(Faults, TcpClientDisconnectsAndReconnects) {
  TempDir dir("tcp-reconnect");
  NavemuRun nav(dir, "navemu",
                stationary_config_with_output("{type: tcp, address: 127.0.0.1, port: 0}",
                                              "garmin-18x-5hz"),
                60);
  const std::optional<int> port = wait_for_tcp_port(nav, 5.0);
  ASSERT_TRUE(port) << nav.diagnostics();

  TcpLineReader client;
  int sessions = 0, mid_epoch_closes = 0;
  for (int cycle = 0; cycle < 4; ++cycle) {
    ASSERT_TRUE(client.connect(*port)) << "cycle " << cycle << nav.diagnostics();
    std::vector<Received> lines;
    EXPECT_TRUE(client.read_until(mono_s() + 1.5, lines)) << "navemu closed the connection";
    // 1.5 s at 5 Hz is 7 or 8 epochs; the first may be missed while navemu accepts.
    EXPECT_GE(check_session(lines, fmt::format("session {}", cycle), 200, false), 6)
        << nav.diagnostics();
    ASSERT_FALSE(lines.empty());
    EXPECT_EQ(lines.front().text.substr(0, 1), "$") << "a session starts at a sentence";
    // Take only the first 30 bytes of the next epoch and close: the rest stays unread (the
    // kernel answers navemu's next send with a reset).
    std::vector<Received> ignored;
    client.read_until(mono_s() + 1.0, ignored, 30);
    if (!client.partial().empty()) ++mid_epoch_closes;
    client.close();
    ++sessions;
    ASSERT_TRUE(nav.child().running()) << nav.diagnostics();
    sleep_s(0.3);  // epochs go out meanwhile with nobody connected
  }
  nav.stop_expecting_exit_0();
  const auto s = run_summary(nav.err());
  ASSERT_TRUE(s) << nav.diagnostics();
  EXPECT_EQ(sessions, 4);
  EXPECT_GE(mid_epoch_closes, 3) << "the closes should fall inside epochs";
  EXPECT_EQ(s->skipped, 0) << nav.diagnostics();
  EXPECT_EQ(s->client_bytes, 0) << nav.diagnostics();
}

// (g) A client floods pseudo-random bytes (a fixed seed) into the u-blox receiver's pty as fast
// as the pty takes them for 3 s, while another client reads. navemu parses every byte as
// possible UBX/NMEA input, at most 16 reads of 4 KB per 10 ms service tick, so the flood cannot
// hold its loop: the NMEA output keeps the profile's 1 Hz cadence (configs/gnss/ublox-m8.yaml:
// NMEA at 1 Hz after power-up), no epoch is skipped, and navemu exits 0. Counters exact: after
// the flood navemu gets 0.5 s (50 ticks, far more than the ~21 KB the pty can hold needs) to
// read what is left, and then its summary's "bytes from clients" equals what the flooder wrote.
// Resident memory grows by less than 1 MB over the flood.
TEST(Faults, GarbageFloodIntoTheUbloxPortKeepsTheCadence) {
  constexpr double kFlood_s = 3.0;
  TempDir dir("flood");
  const fs::path link = dir / "gnss";
  NavemuRun nav(dir, "navemu", stationary_config(link, "ublox-m8"), 60);
  ASSERT_TRUE(nav.wait_for_pty(link, 5.0)) << nav.diagnostics();
  PtyReader reader;
  ASSERT_TRUE(reader.open(link));
  reader.discard_queued();
  const int wfd = ::open(link.c_str(), O_WRONLY | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  ASSERT_GE(wfd, 0) << std::strerror(errno);

  std::vector<Received> lines;
  std::uint64_t written_bytes = 0, write_calls = 0;
  int write_errno = 0;
  reader.read_until(mono_s() + 1.0, lines);  // warmed up
  const long rss_before_kb = rss_kb(nav.child().pid());
  const double flood_end = mono_s() + kFlood_s;
  {
    std::jthread flooder([&](std::stop_token stop) {
      std::mt19937 rng(20260611u);
      std::array<std::uint8_t, 4096> buf{};
      std::size_t off = buf.size();  // bytes of buf already written
      while (!stop.stop_requested() && mono_s() < flood_end) {
        if (off == buf.size()) {
          for (std::uint8_t& b : buf) b = static_cast<std::uint8_t>(rng());
          off = 0;
        }
        const ssize_t n = ::write(wfd, buf.data() + off, buf.size() - off);
        if (n > 0) {
          off += static_cast<std::size_t>(n);
          written_bytes += static_cast<std::uint64_t>(n);
          ++write_calls;
          continue;
        }
        if (n < 0 && errno != EAGAIN && errno != EINTR) {
          write_errno = errno;
          return;
        }
        pollfd p{wfd, POLLOUT, 0};  // full: go on as soon as navemu has read some
        ::poll(&p, 1, 5);
      }
    });
    reader.read_until(flood_end, lines);
  }  // the flooder has stopped (and is joined)
  reader.read_until(mono_s() + 0.5, lines);
  ::close(wfd);
  ASSERT_TRUE(nav.child().running()) << nav.diagnostics();
  // Memory bounded: the parser's buffer is fixed, so megabytes of garbage leave no trace.
  const long rss_growth_kb = rss_kb(nav.child().pid()) - rss_before_kb;
  EXPECT_GT(rss_before_kb, 0);
  EXPECT_LT(rss_growth_kb, 1024) << "resident memory grew during the flood";
  nav.stop_expecting_exit_0();
  EXPECT_EQ(write_errno, 0) << std::strerror(write_errno);

  // 3.5 s at 1 Hz: at least 3 RMCs, 1 s apart, every sentence whole and valid.
  EXPECT_GE(check_session(lines, "during the flood", 1000), 3) << nav.diagnostics();
  const auto s = run_summary(nav.err());
  ASSERT_TRUE(s) << nav.diagnostics();
  EXPECT_EQ(s->skipped, 0) << nav.diagnostics();
  EXPECT_GT(written_bytes, 100'000u) << "the flood should be more than a trickle";
  EXPECT_EQ(s->client_bytes, static_cast<long>(written_bytes)) << nav.diagnostics();
  RecordProperty("flood_bytes", std::to_string(written_bytes));
  std::printf("flood: %llu bytes in %llu writes in %.1f s (%.2f MB/s); navemu read %ld; stale "
              "flushed %ld; resident memory %+ld kB\n",
              static_cast<unsigned long long>(written_bytes),
              static_cast<unsigned long long>(write_calls), kFlood_s,
              static_cast<double>(written_bytes) / kFlood_s * 1e-6, s->client_bytes,
              s->stale_bytes_flushed, rss_growth_kb);
}

std::string udp_truth_config(const fs::path& link) {
  return fmt::format(
      "truth: {{source: udp, udp: {{port: 0}}, timeout_s: 1.0}}\n"
      "gnss:\n  outputs:\n    - {{type: pty, link: '{}'}}\n"
      "imu: {{enabled: false}}\n",
      link.string());
}

// (h) The truth stream jumps 1000 km (9 degrees north) and goes on from there, as when a
// simulator is reset to another scenario. The jump is no fault of the datagrams: all are
// accepted (counted exactly). The output keeps its cadence throughout, and the fix follows to
// the new place within kMaxEpochs epochs of the first datagram there; from then on every fix is
// within 15 m of the new truth. Measured: the first epoch after the jump is already there (the
// receiver solves each epoch afresh from the truth, and the epoch is computed 48 ms after its
// time, when the datagram has arrived); 2 epochs allow for a datagram that a busy machine
// delivers late. (Epochs in the 0.1 s before the jump may lie anywhere between the two places:
// the truth is interpolated between the last old and the first new datagram.)
TEST(Faults, TruthJumps1000KmAndTheFixFollows) {
  constexpr int kMaxEpochs = 2;
  TempDir dir("truth-jump");
  const fs::path link = dir / "gnss";
  NavemuRun nav(dir, "navemu", udp_truth_config(link), 60);
  const std::optional<int> port = nav.wait_for_udp_port(5.0);
  ASSERT_TRUE(port) << nav.diagnostics();
  ASSERT_TRUE(nav.wait_for_pty(link, 5.0)) << nav.diagnostics();
  PtyReader reader;
  ASSERT_TRUE(reader.open(link));
  reader.discard_queued();
  TruthSender sender(*port);
  ASSERT_TRUE(sender.ok());

  const Geodetic far{kSite.lat_deg + 9.0, kSite.lon_deg, kSite.h_m};
  ASSERT_GT(horizontal_error_m(far, kSite), 990e3);
  std::vector<Received> lines;
  double jump_real_s = 0;
  const double t0 = mono_s();
  for (int k = 0; k < 80; ++k) {  // 10 Hz: 3 s at the site, then 5 s at the new place
    reader.read_until(t0 + 0.1 * k, lines);
    const double t = sender.send(k < 30 ? kSite : far);
    if (k == 30) jump_real_s = t;
  }
  reader.read_until(mono_s() + 0.3, lines);  // navemu takes in the last datagram
  nav.stop_expecting_exit_0();
  EXPECT_GE(check_session(lines, "across the jump"), 35) << nav.diagnostics();
  const auto s = run_summary(nav.err());
  ASSERT_TRUE(s) << nav.diagnostics();
  EXPECT_EQ(s->truth_accepted, sender.sent()) << nav.diagnostics();
  EXPECT_EQ(s->truth_rejected, 0) << nav.diagnostics();

  // Epochs from the first one at or after the jump: the first fix within 15 m of the new
  // place, then every epoch a fix there.
  const std::vector<Rmc> r = rmcs(lines);
  const auto jump_ms = static_cast<std::int64_t>(std::ceil(jump_real_s * 1e3));
  std::optional<int> followed;  // epochs after the jump until the fix was at the new place
  int epochs_after = 0, good_after = 0;
  bool fixed_before = false;
  for (const Rmc& m : r) {
    if (m.unix_ms < jump_ms) {
      if (m.valid && horizontal_error_m(m.position, kSite) <= 15.0) fixed_before = true;
      continue;
    }
    if (!followed) {
      if (m.valid && horizontal_error_m(m.position, far) <= 15.0)
        followed = epochs_after;
      ++epochs_after;
      continue;
    }
    ++epochs_after;
    EXPECT_TRUE(m.valid) << "epoch " << epochs_after << " after the jump";
    if (!m.valid) continue;
    const double e = horizontal_error_m(m.position, far);
    EXPECT_LE(e, 15.0) << "epoch " << epochs_after << " after the jump";
    good_after += e <= 15.0 ? 1 : 0;
  }
  EXPECT_TRUE(fixed_before) << "no fix at the site before the jump" << nav.diagnostics();
  ASSERT_TRUE(followed) << "the fix never reached the new place" << nav.diagnostics();
  EXPECT_LE(*followed, kMaxEpochs);
  EXPECT_GE(good_after, 15) << "fixes at the new place after the jump";
  std::printf("truth jump 1000 km: the fix followed after %d epochs (%d epochs after the jump)\n",
              *followed, epochs_after);
}

// (i) The truth stream stops for 2 s and resumes. navemu extrapolates the truth for timeout_s
// (1 s) and then reports its loss: the receiver has no fix (models/receiver.hpp: "without truth
// the receiver reports no fix"), so RMC says V, and a status line says "truth lost" within
// timeout_s + one epoch + 1 s (the status interval) of the last datagram (the status line reports
// a loss in any epoch of its interval, so even this short one is never missed). Epochs keep coming
// at their cadence throughout. When the stream resumes the fix returns within a few epochs,
// and the status lines say "truth ok" again. Counters exact: every datagram is accepted.
TEST(Faults, TruthStreamStopsFor2SecondsThenResumes) {
  constexpr double kTimeout_s = 1.0, kGap_s = 2.0;
  constexpr int kMaxEpochsToReturn = 10;
  TempDir dir("truth-gap");
  const fs::path link = dir / "gnss";
  NavemuRun nav(dir, "navemu", udp_truth_config(link), 60);
  const std::optional<int> port = nav.wait_for_udp_port(5.0);
  ASSERT_TRUE(port) << nav.diagnostics();
  ASSERT_TRUE(nav.wait_for_pty(link, 5.0)) << nav.diagnostics();
  PtyReader reader;
  ASSERT_TRUE(reader.open(link));
  reader.discard_queued();
  TruthSender sender(*port);
  ASSERT_TRUE(sender.ok());

  std::vector<Received> lines;
  double t = mono_s();
  for (int k = 0; k < 30; ++k) {  // 3 s at 10 Hz
    reader.read_until(t, lines);
    sender.send(kSite);
    t += 0.1;
  }
  // The last datagram went out at t - 0.1; from then on, watch stderr for "truth lost" (the
  // status line that reports it may come just after the stream resumes: it covers the epochs
  // of the interval before it).
  const double last_mono = t - 0.1;
  const double last_real = real_s() - (mono_s() - last_mono);
  const auto lost_lines = [&] {
    return static_cast<std::size_t>(count_lines_with(nav.err(), "| truth lost"));
  };
  const std::size_t lost_before = lost_lines();
  // Before the stream began, the first status line may have said lost; the last one before the
  // gap covers a second of steady truth.
  const std::vector<StatusLine> status_before = status_lines(nav.err());
  std::optional<double> lost_after_s;
  const auto watch = [&] {
    if (!lost_after_s && lost_lines() > lost_before) lost_after_s = mono_s() - last_mono;
  };
  const double resume = last_mono + kGap_s;
  while (mono_s() < resume) {
    reader.read_until(std::min(resume, mono_s() + 0.02), lines);
    watch();
  }
  const double resume_real = real_s();
  t = mono_s();
  // 5 s at 10 Hz: several status lines after the resumption; navemu stops while the stream
  // still flows (so the last status line has truth).
  for (int k = 0; k < 50; ++k) {
    while (mono_s() < t) {
      reader.read_until(std::min(t, mono_s() + 0.02), lines);
      watch();
    }
    sender.send(kSite);
    t += 0.1;
  }
  reader.read_until(mono_s() + 0.3, lines);  // navemu takes in the last datagram
  nav.stop_expecting_exit_0();
  ASSERT_FALSE(status_before.empty()) << nav.diagnostics();
  EXPECT_TRUE(status_before.back().truth_ok) << nav.diagnostics();
  ASSERT_TRUE(lost_after_s) << "no 'truth lost' status line during the gap" << nav.diagnostics();
  // The first epoch without truth lies up to one epoch (0.2 s) past the timeout, and the status
  // line after it up to one status interval (1 s) later; 0.2 s for the output latency (0.05 s),
  // the watch's 0.02 s polling and a busy machine. (Measured: 1.1 to 2.1 s, by the phase of the
  // status lines.)
  EXPECT_LE(*lost_after_s, kTimeout_s + 0.2 + 1.0 + 0.2)
      << "timeout + one epoch + status interval" << nav.diagnostics();

  // Epochs every 0.2 s throughout, whole and valid.
  EXPECT_GE(check_session(lines, "across the gap"), 45) << nav.diagnostics();
  const auto s = run_summary(nav.err());
  ASSERT_TRUE(s) << nav.diagnostics();
  EXPECT_EQ(s->truth_accepted, sender.sent()) << nav.diagnostics();
  EXPECT_EQ(s->truth_rejected, 0) << nav.diagnostics();
  EXPECT_EQ(s->skipped, 0) << nav.diagnostics();

  // RMC by epoch time: a fix until timeout_s after the last datagram (extrapolated truth), no
  // fix (V) from one epoch past that until the stream resumed, and the fix back within
  // kMaxEpochsToReturn epochs after the first datagram of the resumed stream. An epoch is
  // computed output_latency_s (0.05 s for this profile) after its time, so one that lies less
  // than that before the first resumed datagram may already see it (the truth is then
  // interpolated across the gap): the last 0.1 s before the resumption is not checked.
  const auto last_ms = static_cast<std::int64_t>(std::llround(last_real * 1e3));
  const auto timeout_ms = static_cast<std::int64_t>(std::llround(kTimeout_s * 1e3));
  const auto resume_ms = static_cast<std::int64_t>(std::llround(resume_real * 1e3));
  int v_in_gap = 0, a_before_timeout = 0;
  std::optional<int> returned;
  int epochs_after_resume = 0;
  for (const Rmc& m : rmcs(lines)) {
    if (m.unix_ms > last_ms - 2000 && m.unix_ms <= last_ms + 800) {
      EXPECT_TRUE(m.valid) << "lost the fix within the truth timeout, epoch "
                           << m.unix_ms - last_ms << " ms after the last datagram";
      a_before_timeout += m.valid ? 1 : 0;
    } else if (m.unix_ms > last_ms + timeout_ms + 250 && m.unix_ms < resume_ms - 100) {
      EXPECT_FALSE(m.valid) << "a fix without truth, epoch " << m.unix_ms - last_ms
                            << " ms after the last datagram";
      v_in_gap += m.valid ? 0 : 1;
    } else if (m.unix_ms >= resume_ms) {
      if (!returned && m.valid) returned = epochs_after_resume;
      ++epochs_after_resume;
      if (returned) {
        EXPECT_TRUE(m.valid) << "fix lost again after it returned";
        if (m.valid) {
          EXPECT_LE(horizontal_error_m(m.position, kSite), 15.0);
        }
      }
    }
  }
  EXPECT_GE(a_before_timeout, 10);
  EXPECT_GE(v_in_gap, 3) << "about 0.75 s of the gap is past the timeout";
  ASSERT_TRUE(returned) << "the fix never came back" << nav.diagnostics();
  EXPECT_LE(*returned, kMaxEpochsToReturn);

  // The status lines: ok before the gap (checked above), lost, then ok again at the end.
  const std::vector<StatusLine> status = status_lines(nav.err());
  ASSERT_GE(status.size(), 8u);
  EXPECT_TRUE(status.back().truth_ok) << nav.diagnostics();
  std::printf("truth gap %.1f s: lost on stderr %.2f s after the last datagram; %d epochs V; "
              "fix back %d epochs after the stream resumed\n",
              kGap_s, *lost_after_s, v_in_gap, *returned);
}

// Reads the pty for `seconds` while one datagram goes out every 0.1 s, made by `send_one(k)`.
void stream_for(PtyReader& reader, std::vector<Received>& lines, int datagrams,
                const std::function<void(int)>& send_one) {
  const double t0 = mono_s();
  for (int k = 0; k < datagrams; ++k) {
    reader.read_until(t0 + 0.1 * k, lines);
    send_one(k);
  }
}

// (k) One datagram stamped an hour ahead among good ones (a sender whose clock glitched once):
// it is rejected and counted as future, the stream goes on, the fix stays at the truth and the
// status line says ok throughout. (Before, the outlier became the newest sample: every later
// datagram was refused as backwards and the receiver interpolated towards the outlier.)
TEST(Faults, ATruthDatagramAnHourAheadIsRejectedAsFutureAndTheStreamGoesOn) {
  TempDir dir("truth-future");
  const fs::path link = dir / "gnss";
  NavemuRun nav(dir, "navemu", udp_truth_config(link), 60);
  const std::optional<int> port = nav.wait_for_udp_port(5.0);
  ASSERT_TRUE(port) << nav.diagnostics();
  ASSERT_TRUE(nav.wait_for_pty(link, 5.0)) << nav.diagnostics();
  PtyReader reader;
  ASSERT_TRUE(reader.open(link));
  reader.discard_queued();
  TruthSender sender(*port);
  ASSERT_TRUE(sender.ok());
  const Geodetic far{kSite.lat_deg + 0.009, kSite.lon_deg, kSite.h_m};  // 1 km north
  std::vector<Received> lines;
  stream_for(reader, lines, 60, [&](int k) {
    sender.send(kSite);
    if (k == 20) sender.send(far, 3600.0);
  });
  reader.read_until(mono_s() + 0.3, lines);
  nav.stop_expecting_exit_0();

  const auto s = run_summary(nav.err());
  ASSERT_TRUE(s) << nav.diagnostics();
  EXPECT_EQ(s->truth_accepted, sender.sent() - 1) << nav.diagnostics();
  EXPECT_EQ(s->truth_rejected, 1) << nav.diagnostics();
  EXPECT_EQ(s->truth_reasons, "future 1") << nav.diagnostics();
  int fixes = 0;
  bool fixed = false;
  for (const Rmc& m : rmcs(lines)) {
    fixed = fixed || m.valid;
    if (!fixed) continue;
    EXPECT_TRUE(m.valid) << "fix lost at " << m.unix_ms;
    if (!m.valid) continue;
    ++fixes;
    EXPECT_LE(horizontal_error_m(m.position, kSite), 15.0);
  }
  EXPECT_GE(fixes, 20) << nav.diagnostics();
  bool seen_ok = false, seen_future = false;
  for (const StatusLine& sl : status_lines(nav.err())) {
    seen_ok = seen_ok || sl.truth == "ok";
    if (seen_ok) {  // ok, or extrapolating when a busy machine delays a datagram
      EXPECT_TRUE(sl.truth_ok) << nav.diagnostics();
    }
    seen_future = seen_future || sl.truth_counts.find("future 1") != std::string::npos;
  }
  EXPECT_TRUE(seen_future) << "no status line counts the future datagram" << nav.diagnostics();
}

// (l) A simulator reset: its clock starts again 100 s earlier, at a place 1000 km away, sent as
// JSON with GPS time stamps. The first datagrams of the new stream are refused as backwards;
// after three consistent ones the stream is re-synchronised (a warning line, counted as resync)
// and the fix follows it to the new place. (Before, every datagram after the reset was refused
// for the rest of the run and the receiver lost its fix for good.)
TEST(Faults, ATruthStreamThatJumpsBackIsResynchronisedAndTheFixFollows) {
  TempDir dir("truth-resync");
  const fs::path link = dir / "gnss";
  NavemuRun nav(dir, "navemu", udp_truth_config(link), 60);
  const std::optional<int> port = nav.wait_for_udp_port(5.0);
  ASSERT_TRUE(port) << nav.diagnostics();
  ASSERT_TRUE(nav.wait_for_pty(link, 5.0)) << nav.diagnostics();
  PtyReader reader;
  ASSERT_TRUE(reader.open(link));
  reader.discard_queued();
  TruthSender sender(*port);
  ASSERT_TRUE(sender.ok());
  const Geodetic far{kSite.lat_deg + 9.0, kSite.lon_deg, kSite.h_m};
  std::vector<Received> lines;
  double reset_real_s = 0;
  stream_for(reader, lines, 80, [&](int k) {  // 3 s before the reset, 5 s after
    const double t = k < 30 ? sender.send(kSite, 0.0, true) : sender.send(far, -100.0, true);
    if (k == 30) reset_real_s = t;
  });
  reader.read_until(mono_s() + 0.3, lines);
  nav.stop_expecting_exit_0();

  const auto s = run_summary(nav.err());
  ASSERT_TRUE(s) << nav.diagnostics();
  EXPECT_EQ(s->truth_accepted, sender.sent() - 2) << nav.diagnostics();
  EXPECT_EQ(s->truth_rejected, 2) << nav.diagnostics();
  EXPECT_EQ(s->truth_reasons, "backwards 2; resync 1") << nav.diagnostics();
  EXPECT_EQ(count_lines_with(nav.err(), "navemu: warning: truth datagrams on udp port"), 1) << nav.diagnostics();
  EXPECT_NE(nav.err().find("jumped 100."), std::string::npos) << nav.diagnostics();
  EXPECT_NE(nav.err().find("re-synchronised after 3 consistent datagrams"), std::string::npos);
  // After the reset the fix reaches the new place within a few epochs (three datagrams, 0.2 s,
  // and the truth timeout bridge the re-synchronisation) and stays there.
  const auto reset_ms = static_cast<std::int64_t>(std::ceil(reset_real_s * 1e3));
  std::optional<int> followed;
  int epochs_after = 0;
  for (const Rmc& m : rmcs(lines)) {
    if (m.unix_ms < reset_ms) continue;
    ++epochs_after;
    if (!followed) {
      if (m.valid && horizontal_error_m(m.position, far) <= 15.0) followed = epochs_after;
      continue;
    }
    EXPECT_TRUE(m.valid && horizontal_error_m(m.position, far) <= 15.0)
        << "epoch " << epochs_after << " after the reset";
  }
  ASSERT_TRUE(followed) << "the fix never reached the new place" << nav.diagnostics();
  EXPECT_LE(*followed, 4);
  EXPECT_GE(epochs_after - *followed, 15);
  const std::vector<StatusLine> status = status_lines(nav.err());
  ASSERT_FALSE(status.empty());
  EXPECT_EQ(status.back().truth, "ok") << nav.diagnostics();
  EXPECT_NE(status.back().truth_counts.find("resync 1"), std::string::npos) << nav.diagnostics();
  std::printf("truth stream reset: the fix was at the new place %d epochs after it\n", *followed);
}

// (m) Datagrams keep arriving but none can be taken (their times jump about, each far from the
// last): the receiver loses its fix once the newest accepted truth is older than timeout_s, and
// the status line says "rejecting" while no datagram is taken. Good datagrams bring the fix
// back. (Before, the first outlier an hour ahead was accepted and the receiver kept a fix on a
// frozen truth.)
TEST(Faults, TruthThatIsAllRejectedEndsTheFixAfterTheTimeoutThoughDatagramsArrive) {
  TempDir dir("truth-rejecting");
  const fs::path link = dir / "gnss";
  NavemuRun nav(dir, "navemu", udp_truth_config(link), 60);
  const std::optional<int> port = nav.wait_for_udp_port(5.0);
  ASSERT_TRUE(port) << nav.diagnostics();
  ASSERT_TRUE(nav.wait_for_pty(link, 5.0)) << nav.diagnostics();
  PtyReader reader;
  ASSERT_TRUE(reader.open(link));
  reader.discard_queued();
  TruthSender sender(*port);
  ASSERT_TRUE(sender.ok());
  std::vector<Received> lines;
  double bad_from_s = 0, bad_until_s = 0;
  stream_for(reader, lines, 100, [&](int k) {  // 3 s good, 4 s bad, 3 s good
    if (k < 30 || k >= 70) {
      const double t = sender.send(kSite);
      if (k == 70) bad_until_s = t;
    } else {
      const double t = sender.send(kSite, (k % 2 ? 3600.0 : -3600.0) * (1 + k % 3));
      if (k == 30) bad_from_s = t;
    }
  });
  reader.read_until(mono_s() + 0.3, lines);
  nav.stop_expecting_exit_0();

  const auto s = run_summary(nav.err());
  ASSERT_TRUE(s) << nav.diagnostics();
  EXPECT_EQ(s->truth_accepted, sender.sent() - 40) << nav.diagnostics();
  EXPECT_EQ(s->truth_rejected, 40) << nav.diagnostics();
  const auto from_ms = static_cast<std::int64_t>(std::llround(bad_from_s * 1e3));
  const auto until_ms = static_cast<std::int64_t>(std::llround(bad_until_s * 1e3));
  int valid_before = 0, void_in_bad = 0, valid_after = 0;
  for (const Rmc& m : rmcs(lines)) {
    // The last good datagram went out 0.1 s before bad_from; then 1 s of extrapolation.
    if (m.unix_ms > from_ms + 1200 && m.unix_ms < until_ms - 100) {
      EXPECT_FALSE(m.valid) << "a fix " << m.unix_ms - from_ms << " ms into the rejected stream";
      void_in_bad += m.valid ? 0 : 1;
    } else if (m.unix_ms < from_ms - 200) {
      valid_before += m.valid ? 1 : 0;
    } else if (m.unix_ms > until_ms + 1000) {
      EXPECT_TRUE(m.valid) << "no fix " << m.unix_ms - until_ms << " ms after good truth returned";
      valid_after += m.valid ? 1 : 0;
    }
  }
  EXPECT_GE(valid_before, 8);
  EXPECT_GE(void_in_bad, 10);
  EXPECT_GE(valid_after, 5);
  std::string states;
  const std::vector<StatusLine> status = status_lines(nav.err());
  for (const StatusLine& sl : status) states += sl.truth + " ";
  EXPECT_NE(states.find("rejecting rejecting"), std::string::npos) << states;
  ASSERT_FALSE(status.empty());
  EXPECT_TRUE(status.back().truth_ok) << states;  // ok, or extrapolating on a busy machine
}

// (n) A slow truth stream (1.5 Hz, within the 1 s timeout): every epoch has truth and a fix,
// and the status line says "extrapolating" when the newest sample is more than 0.25 s old,
// never "lost".
TEST(Faults, ASlowTruthStreamIsReportedAsExtrapolatingNotLost) {
  TempDir dir("truth-slow");
  const fs::path link = dir / "gnss";
  NavemuRun nav(dir, "navemu", udp_truth_config(link), 60);
  const std::optional<int> port = nav.wait_for_udp_port(5.0);
  ASSERT_TRUE(port) << nav.diagnostics();
  ASSERT_TRUE(nav.wait_for_pty(link, 5.0)) << nav.diagnostics();
  PtyReader reader;
  ASSERT_TRUE(reader.open(link));
  reader.discard_queued();
  TruthSender sender(*port);
  ASSERT_TRUE(sender.ok());
  std::vector<Received> lines;
  const double t0 = mono_s();
  for (int k = 0; k < 10; ++k) {  // 6 s at 1.5 Hz
    reader.read_until(t0 + k / 1.5, lines);
    sender.send(kSite);
  }
  reader.read_until(mono_s() + 0.2, lines);
  nav.stop_expecting_exit_0();
  int fixes = 0;
  bool fixed = false;
  for (const Rmc& m : rmcs(lines)) {
    fixed = fixed || m.valid;
    if (fixed) {
      EXPECT_TRUE(m.valid) << m.unix_ms;
    }
    fixes += m.valid ? 1 : 0;
  }
  EXPECT_GE(fixes, 20);
  int extrapolating = 0, after_first_ok = 0;
  bool seen_ok = false;
  for (const StatusLine& sl : status_lines(nav.err())) {
    extrapolating += sl.truth == "extrapolating" ? 1 : 0;
    if (seen_ok) {
      EXPECT_NE(sl.truth, "lost") << nav.diagnostics();
      ++after_first_ok;
    }
    seen_ok = seen_ok || sl.truth == "ok" || sl.truth == "extrapolating";
  }
  EXPECT_GE(after_first_ok, 3);
  EXPECT_GE(extrapolating, 1) << nav.diagnostics();
}

// (j) Truth at 10 kHz for 3 s (a simulator sending every physics step), then at 10 Hz for 1 s.
// navemu takes in what reaches it and counts the rest: every datagram sent is accepted,
// rejected or lost unread (dropped by the kernel when the socket's queue was full, which the
// 10 Hz tail reports, socket(7) SO_RXQ_OVFL), and none is rejected. The fix stays at the site
// and the output keeps its cadence.
TEST(Faults, TruthAt10kHzIsTakenInAndCounted) {
  TempDir dir("truth-10khz");
  const fs::path link = dir / "gnss";
  NavemuRun nav(dir, "navemu", udp_truth_config(link), 60);
  const std::optional<int> port = nav.wait_for_udp_port(5.0);
  ASSERT_TRUE(port) << nav.diagnostics();
  ASSERT_TRUE(nav.wait_for_pty(link, 5.0)) << nav.diagnostics();
  PtyReader reader;
  ASSERT_TRUE(reader.open(link));
  reader.discard_queued();
  TruthSender sender(*port);
  ASSERT_TRUE(sender.ok());

  std::atomic<bool> done{false};
  double burst_s = 0;
  std::thread send_thread([&] {
    timespec next{};
    clock_gettime(CLOCK_MONOTONIC, &next);
    const double start = mono_s();
    for (int k = 0; k < 30'000; ++k) {  // 10 kHz on absolute deadlines: no drift
      sender.send(kSite);
      next.tv_nsec += 100'000;
      if (next.tv_nsec >= 1'000'000'000) {
        next.tv_nsec -= 1'000'000'000;
        ++next.tv_sec;
      }
      clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &next, nullptr);
    }
    burst_s = mono_s() - start;
    for (int k = 0; k < 10; ++k) {
      sleep_s(0.1);
      sender.send(kSite);
    }
    done = true;
  });
  std::vector<Received> lines;
  const double deadline = mono_s() + 20.0;
  while (!done && mono_s() < deadline) reader.read_until(mono_s() + 0.1, lines);
  send_thread.join();
  reader.read_until(mono_s() + 0.3, lines);  // navemu takes in the last datagram
  nav.stop_expecting_exit_0();

  const auto s = run_summary(nav.err());
  ASSERT_TRUE(s) << nav.diagnostics();
  EXPECT_EQ(s->truth_accepted + s->truth_rejected + s->truth_lost, sender.sent()) << nav.diagnostics();
  EXPECT_EQ(s->truth_rejected, 0) << nav.diagnostics();
  EXPECT_GE(s->truth_accepted, sender.sent() / 2) << nav.diagnostics();
  EXPECT_GE(check_session(lines, "during 10 kHz truth"), 15) << nav.diagnostics();
  int fixes = 0;
  for (const Rmc& m : rmcs(lines)) {
    if (!m.valid) continue;
    ++fixes;
    EXPECT_LE(horizontal_error_m(m.position, kSite), 15.0);
  }
  EXPECT_GE(fixes, 15) << nav.diagnostics();
  std::printf("truth at %.0f Hz for %.1f s: %ld sent, %ld accepted, %ld rejected, %ld lost unread\n",
              30'000 / burst_s, burst_s, sender.sent(), s->truth_accepted, s->truth_rejected,
              s->truth_lost);
}

// (k) navemu needs no root: ptys (and SocketCAN raw sockets on an existing interface) are open
// to every user. When the tests run as root, navemu runs as user nobody (setpriv, util-linux)
// in a folder it may write; it opens its pty and sends the 5 Hz output a client reads.
TEST(Faults, RunsWithoutRoot) {
  TempDir dir("no-root");
  std::vector<std::string> prefix;
  if (::geteuid() == 0) {
    const std::string setpriv = find_program("setpriv");
    if (setpriv.empty()) GTEST_SKIP() << "setpriv (util-linux) not found";
    prefix = {setpriv, "--reuid=nobody", "--regid=nogroup", "--clear-groups"};
    std::vector<std::string> check = prefix;
    for (const char* a : {"test", "-x"}) check.emplace_back(a);
    check.push_back(navemu_binary().string());
    Child probe(check, dir / "probe.out", dir / "probe.err");
    const auto st = probe.wait_exit(5.0);
    if (!st || !WIFEXITED(*st) || WEXITSTATUS(*st) != 0)
      GTEST_SKIP() << "user nobody cannot run " << navemu_binary() << " (a folder on its path is private)";
    ASSERT_EQ(::chmod(dir.path().c_str(), 0777), 0);  // for the pty link
  }
  const fs::path link = dir / "gnss";
  NavemuRun nav(dir, "navemu", stationary_config(link, "garmin-18x-5hz"), 60, {}, prefix);
  ASSERT_TRUE(nav.wait_for_pty(link, 5.0)) << nav.diagnostics();
  // The process that runs is navemu (setpriv execs it), with the user's real and effective ids.
  std::string uid_line;
  std::ifstream status("/proc/" + std::to_string(nav.child().pid()) + "/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind("Uid:", 0) == 0) uid_line = line;
  const passwd* nobody = ::getpwnam("nobody");
  ASSERT_NE(nobody, nullptr);
  const unsigned expected_uid = prefix.empty() ? ::geteuid() : nobody->pw_uid;
  EXPECT_EQ(uid_line, fmt::format("Uid:\t{0}\t{0}\t{0}\t{0}", expected_uid));
  PtyReader reader;
  ASSERT_TRUE(reader.open(link));
  reader.discard_queued();
  std::vector<Received> lines;
  reader.read_until(mono_s() + 2.0, lines);
  nav.stop_expecting_exit_0();
  EXPECT_GE(check_session(lines, "as an unprivileged user"), 8) << nav.diagnostics();
  EXPECT_EQ(fs::symlink_status(link).type(), fs::file_type::not_found) << "pty link left behind";
}

}  // namespace
}  // namespace navemu::test::clients
