// PX4's u-blox driver (PX4-GPSDrivers src/ubx.cpp, compiled unmodified with the project's host
// header definitions.h) against `navemu run` on a pty, driven by navemu-px4-gps as PX4's GPS
// module drives it (../shared/TESTING.md, "PX4's u-blox driver"): each u-blox profile, with
// baud 0 (the driver auto-detects) and with the profile's baud fixed. Issue 21's acceptance,
// measured against what navemu sent (gnss.capture, decoded with protocols/ubx):
//
//   - configure() returns 0 at the first attempt, and the driver is never reconfigured after;
//   - the board and the protocol version the driver detects from MON-VER are the profile's;
//   - the first 3D fix is reported <= 1.5 s after configure() returns;
//   - 5 Hz +- 1 % over a window (NAVEMU_PX4_WINDOW_S seconds, default 10; the 60 s
//     with NAVEMU_PX4_WINDOW_S=60), each report's UTC 200 ms after the previous one;
//   - every report's eph/epv are the hAcc/vAcc of the NAV-PVT navemu sent for that epoch
//     (matched by the UTC time the driver derives from it; within NAV-PVT's 1 mm resolution,
//     as NAV-HPPOSLLH sets them last on protocol 27+), satellites_used its numSV;
//   - every satellite report is one of navemu's NAV-SAT (protocol 27+) or NAV-SVINFO (older)
//     messages as the driver converts it;
//   - noise_per_ms and jamming_indicator come from navemu's MON-HW (protocol < 27) or MON-RF
//     (27+): noise non-zero, jamming 0..255;
//   - no ACK-NAK in the whole capture, except those the real part gives (cited per profile).
//
// On failure the messages list what navemu NAKed (with the keys of each NAKed CFG-VALSET),
// which requests got no answer and which of the messages the driver configured never came.
// HarnessRunsTheDriverOnThePty checks the harness itself: the driver built, the pty open, the
// driver's requests reaching navemu intact and navemu's answers reaching the driver.

#include <gtest/gtest.h>

#include <fmt/format.h>

#include <chrono>
#include <deque>
#include <map>
#include <set>

#include "core/satellite.hpp"
#include "models/constellation.hpp"
#include "models/event_window.hpp"
#include "models/geodesy.hpp"
#include "models/orbit.hpp"
#include "tests/clients/client_support.hpp"
#include "tests/clients/ubx_frames.hpp"

namespace navemu::test::clients {
namespace {

// The paper's test site (Vicksburg, MS), h above the WGS-84 ellipsoid.
const Geodetic kSite{32.3, -90.9, 60.0};

// A NAK the real part gives, with its source.
struct PartNak {
  ubx::MsgId msg;
  const char* source;
};

struct Px4Case {
  const char* profile;  // configs/gnss/PROFILE.yaml
  const char* board;    // GPSDriverUBX::Board the driver must detect (the harness's names)
  std::vector<PartNak> part_naks;
  bool fixed_baud;
};

void PrintTo(const Px4Case& c, std::ostream* os) {
  *os << c.profile << (c.fixed_baud ? ", fixed baud" : ", auto baud");
}

// What the test needs of a profile file: its power-up baud and MON-VER protocol version.
struct ProfileFacts {
  fs::path path;
  int baud = 0;
  std::string protver;
  bool protocol_27 = false;  // configured by CFG-VALSET (the driver's configureDevice)
};

ProfileFacts profile_facts(const std::string& profile) {
  ProfileFacts f;
  f.path = fs::path(NAVEMU_SOURCE_DIR) / "configs" / "gnss" / (profile + ".yaml");
  const YAML::Node y = YAML::LoadFile(f.path.string());
  f.baud = y["baud"].as<int>();
  f.protver = y["ubx"]["protver"].as<std::string>();
  f.protocol_27 = std::stod(f.protver) >= 27.0;
  return f;
}

// `truth`: the truth section's other keys (a stationary receiver at the site unless given).
std::string navemu_config(const fs::path& profile, const fs::path& link, const fs::path& capture,
                          const std::string& truth = "source: stationary") {
  return fmt::format(
      "scenario: {{status_interval_s: 1, start: now}}\n"
      "truth: {{{}, position: {{lat_deg: {}, lon_deg: {}, h_m: {}}}}}\n"
      "gnss:\n"
      "  profile: '{}'\n"
      "  capture: '{}'\n"
      "  outputs:\n"
      "    - {{type: pty, link: '{}'}}\n"
      "imu: {{enabled: false}}\n",
      truth, kSite.lat_deg, kSite.lon_deg, kSite.h_m, profile.string(), capture.string(), link.string());
}

// ---- the harness's report (navemu_px4_gps.cpp: one JSON object per line) -------------------

struct Report {
  std::vector<YAML::Node> configures, gps, sats, receive_ends, logs, tx, rx;
  std::optional<YAML::Node> stop, summary;
};

Report read_report(const fs::path& p) {
  Report r;
  std::stringstream ss(slurp(p));
  for (std::string line; std::getline(ss, line);) {
    if (line.empty() || line[0] != '{') continue;
    const YAML::Node n = YAML::Load(line);
    const std::string e = str(n, "event");
    if (e == "configure") r.configures.push_back(n);
    if (e == "gps") r.gps.push_back(n);
    if (e == "sat") r.sats.push_back(n);
    if (e == "receive_end") r.receive_ends.push_back(n);
    if (e == "log") r.logs.push_back(n);
    if (e == "tx") r.tx.push_back(n);
    if (e == "rx") r.rx.push_back(n);
    if (e == "stop") r.stop = n;
    if (e == "summary") r.summary = n;
  }
  return r;
}

double t_of(const YAML::Node& n) { return n["t"].as<double>(); }

std::vector<int> ints(const YAML::Node& seq) {
  std::vector<int> out;
  for (const YAML::Node& v : seq) out.push_back(v.as<int>());
  return out;
}

// ---- what navemu sent and received ------------------------------------------------------------

std::string msg_name(ubx::MsgId id) {
  const ubx::MessageInfo* m = ubx::find_message(id);
  return fmt::format("{} ({:02X} {:02X})", m != nullptr ? m->name : "?", id.cls, id.id);
}

// One request of the client that navemu answered with ACK-NAK, as text: the message, its length
// and, for CFG-VALSET, its layers and keys with their values.
std::string describe_request(const UbxFrame& f) {
  std::string s = fmt::format("{} {} B", msg_name(f.id), f.payload.size());
  ubx::CfgValset v;
  if (f.id == ubx::kCfgValset && ubx::decode(f.payload, v)) {
    s += fmt::format(" layers 0x{:02X}, keys", v.layers);
    for (const ubx::CfgKeyValue& kv : v.values) s += fmt::format(" 0x{:08X}={}", kv.key_id, kv.value);
  }
  return s;
}

// The acknowledgements of the capture, paired with the requests they answer (the k-th ACK/NAK
// of a class/ID answers the k-th CFG request of that class/ID: navemu handles them in order).
struct Handshake {
  int acks = 0, naks = 0, part_naks = 0;
  std::map<std::string, int> unexpected_naks;  // request described -> how often
  std::map<std::string, int> unanswered;       // CFG requests without ACK/NAK
  int mon_ver_polls = 0, mon_ver_answers = 0;
};

Handshake analyse_handshake(const std::vector<UbxFrame>& to_client,
                            const std::vector<UbxFrame>& from_client, const std::vector<PartNak>& part) {
  Handshake h;
  std::map<std::uint16_t, std::deque<const UbxFrame*>> pending;
  const auto key = [](ubx::MsgId m) { return static_cast<std::uint16_t>(m.cls << 8 | m.id); };
  for (const UbxFrame& f : from_client) {
    if (f.id == ubx::kMonVer && f.payload.empty()) ++h.mon_ver_polls;
    if (f.id.cls == ubx::kClassCfg && f.id != ubx::kCfgRst) pending[key(f.id)].push_back(&f);
  }
  for (const UbxFrame& f : to_client) {
    if (f.id == ubx::kMonVer) ++h.mon_ver_answers;
    if ((f.id != ubx::kAckAck && f.id != ubx::kAckNak) || f.payload.size() != 2) continue;
    const ubx::MsgId of{f.payload[0], f.payload[1]};
    std::deque<const UbxFrame*>& q = pending[key(of)];
    const UbxFrame* request = q.empty() ? nullptr : q.front();
    if (!q.empty()) q.pop_front();
    if (f.id == ubx::kAckAck) {
      ++h.acks;
      continue;
    }
    ++h.naks;
    const bool by_part =
        std::any_of(part.begin(), part.end(), [&](const PartNak& p) { return p.msg == of; });
    if (by_part)
      ++h.part_naks;
    else
      ++h.unexpected_naks[request != nullptr ? describe_request(*request) : msg_name(of) + " (no request seen)"];
  }
  for (const auto& [k, q] : pending)
    for (const UbxFrame* r : q) ++h.unanswered[describe_request(*r)];
  return h;
}

std::string counted(const std::map<std::string, int>& m) {
  std::string s;
  for (const auto& [what, n] : m) s += fmt::format("\n  {} x{}", what, n);
  return s;
}

// UTC of a NAV-PVT as the driver computes time_utc_usec (ubx.cpp, payloadRxDone: the date and
// time through mktime in UTC, plus nano / 1000 with C++'s truncating division).
std::int64_t pvt_utc_usec(const ubx::NavPvt& m) {
  const std::int64_t s =
      ((days_from_civil(m.year, m.month, m.day) * 24 + m.hour) * 60 + m.min) * 60 + m.sec;
  return s * 1'000'000 + m.nano_ns / 1000;
}

// One satellite as the driver stores it in satellite_info_s.
struct SkyEntry {
  int svid = 0, used = 0, elevation = 0, azimuth = 0, snr = 0;
  friend bool operator==(const SkyEntry&, const SkyEntry&) = default;
};
using Sky = std::vector<SkyEntry>;

constexpr std::size_t kSatInfoMax = 40;  // definitions.h, satellite_info_s::SAT_INFO_MAX_SATELLITES

// The driver's byte for an azimuth in degrees (ubx.cpp: azim * 255 / 360 in float, truncated).
int azimuth_byte(int azim_deg) {
  return static_cast<std::uint8_t>(static_cast<float>(azim_deg) * 255.0f / 360.0f);
}

// NAV-SAT as the driver converts it (ubx.cpp, payloadRxAddNavSat): svId in the driver's
// single-number table, which is u-blox's NAV-SVINFO numbering (UBX-13003221 appendix A) except
// for BeiDou, where the driver maps B1-B4 to 159-162 and B5-B37 to svId + 28 (appendix A: B1-B5
// 159-163, B6-B37 33-64); `used` is flags bit 0 (the low bit of qualityInd, not svUsed, bit 3).
Sky sky_of(const ubx::NavSat& m) {
  Sky out;
  for (std::size_t i = 0; i < std::min(m.svs.size(), kSatInfoMax); ++i) {
    const ubx::NavSatSv& s = m.svs[i];
    int svid = 255;
    const int n = s.sv_id;
    if (s.gnss_id == 3) {
      svid = n >= 1 && n <= 4 ? n + 158 : n >= 5 && n <= 37 ? n + 28 : 255;
    } else if (s.gnss_id != 4) {  // IMES: not one of navemu's systems
      const std::optional<SatId> sat = SatId::from_ubx(s.gnss_id, s.sv_id);
      const std::optional<int> legacy = sat ? sat->ubx_legacy_sv_id() : std::nullopt;
      if (legacy && *legacy <= 255 && !(s.gnss_id == 0 && n > 32)) svid = *legacy;
    }
    out.push_back({svid, static_cast<int>(s.flags & 0x01),
                   static_cast<std::uint8_t>(s.elev_deg), azimuth_byte(s.azim_deg), s.cno_dbhz});
  }
  return out;
}

// NAV-SVINFO as the driver converts it (ubx.cpp, payloadRxAddNavSvinfo): `used` is flags bit 3
// (orbitEph in UBX-13003221; svUsed is bit 0).
Sky sky_of(const ubx::NavSvinfo& m) {
  Sky out;
  for (std::size_t i = 0; i < std::min(m.channels.size(), kSatInfoMax); ++i) {
    const ubx::NavSvinfoChannel& c = m.channels[i];
    out.push_back({c.svid, (c.flags >> 3) & 0x01, static_cast<std::uint8_t>(c.elev_deg),
                   azimuth_byte(c.azim_deg), c.cno_dbhz});
  }
  return out;
}

Sky sky_of_report(const YAML::Node& n) {
  const std::vector<int> svid = ints(n["svid"]), used = ints(n["used"]), el = ints(n["elevation"]),
                         az = ints(n["azimuth"]), snr = ints(n["snr"]);
  Sky out;
  for (std::size_t i = 0; i < svid.size(); ++i) out.push_back({svid[i], used[i], el[i], az[i], snr[i]});
  return out;
}

std::string sky_text(const Sky& s) {
  std::string t;
  for (const SkyEntry& e : s) t += fmt::format(" {}:{}/{}/{}/{}", e.svid, e.used, e.elevation, e.azimuth, e.snr);
  return t;
}

// (noisePerMS, jamInd) of every MON-HW (UBX-13003221, 60 bytes) and MON-RF block 0 (ZED-F9P
// Interface Description UBX-18010854, UBX-MON-RF: 4-byte header, 24-byte blocks with flags at
// +1, noisePerMS U2 at +16, jamInd U1 at +20) navemu sent: the driver reads block 0 only.
std::set<std::pair<int, int>> noise_jam_sent(const std::vector<UbxFrame>& frames, bool mon_rf) {
  std::set<std::pair<int, int>> out;
  for (const ubx::MonHw& m : decode_all<ubx::MonHw>(frames, ubx::kMonHw))
    if (!mon_rf) out.insert({m.noise_per_ms, m.jam_ind});
  // The driver reads the first RF block (F9 interface description, UBX-MON-RF).
  for (const ubx::MonRf& m : decode_all<ubx::MonRf>(frames, ubx::kMonRf))
    if (mon_rf && !m.blocks.empty()) out.insert({m.blocks[0].noise_per_ms, m.blocks[0].jam_ind});
  return out;
}

// The periodic messages the driver turns on and waits for (ubx.cpp: configureDevice for
// protocol 27+, configureDevicePreV27 before; RXM-RTCM only comes with RTCM input).
std::vector<std::pair<ubx::MsgId, const char*>> configured_outputs(bool protocol_27) {
  if (protocol_27)
    return {{ubx::kNavPvt, "NAV-PVT"},       {ubx::MsgId{ubx::kClassNav, 0x14}, "NAV-HPPOSLLH"},
            {ubx::kNavDop, "NAV-DOP"},       {ubx::kNavSat, "NAV-SAT"},
            {ubx::kNavStatus, "NAV-STATUS"}, {ubx::kMonRf, "MON-RF"}};
  return {{ubx::kNavPvt, "NAV-PVT"}, {ubx::kNavStatus, "NAV-STATUS"}, {ubx::kNavDop, "NAV-DOP"},
          {ubx::kNavSvinfo, "NAV-SVINFO"}, {ubx::kMonHw, "MON-HW"}};
}

double window_s() {
  const char* env = std::getenv("NAVEMU_PX4_WINDOW_S");
  return env != nullptr ? std::max(5.0, std::atof(env)) : 10.0;
}

// The harness, or why there is none.
const char* const kNoHarness =
    "../shared/clients/px4-gpsdrivers not found: PX4's u-blox driver (and the harness "
    "navemu-px4-gps) is built only when ../shared holds its sources";
bool have_harness() {
  const fs::path harness = NAVEMU_PX4_HARNESS;
  return !harness.empty() && fs::exists(harness);
}

// One run: `navemu run` with the profile on a pty and the harness on it for run_s seconds; the
// harness's report and the frames navemu sent (gnss.capture) and received (CAPTURE.in).
struct Px4Run {
  Report rep;
  std::vector<UbxFrame> sent, received;
  std::string where;
  std::string log;  // navemu's
};

// `more_yaml` adds to navemu's configuration (e.g. `events:`), `truth` replaces its truth (as
// navemu_config); navemu's log goes into out.log.
void run_px4(const TempDir& dir, const ProfileFacts& facts, int baud, double run_s, Px4Run& out,
             const std::string& more_yaml = "", const std::string& truth = "source: stationary") {
  const fs::path link = dir / "gps", capture = dir / "wire.ubx";
  NavemuRun nav(dir, "navemu", navemu_config(facts.path, link, capture, truth) + more_yaml, run_s + 60.0);
  ASSERT_TRUE(nav.wait_for_pty(link, 10.0)) << nav.diagnostics();
  const fs::path report_path = dir / "px4.jsonl";
  Child px4({NAVEMU_PX4_HARNESS, "--device", link.string(), "--baud", std::to_string(baud),
             "--duration", fmt::format("{}", run_s), "--window", fmt::format("{}", window_s())},
            report_path, dir / "px4.stderr");
  const std::optional<int> st = px4.wait_exit(run_s + 40.0);
  EXPECT_TRUE(st && WIFEXITED(*st) && WEXITSTATUS(*st) == 0)
      << "navemu-px4-gps: " << describe_status(st) << "\n" << tail(slurp(dir / "px4.stderr"));
  nav.stop_expecting_exit_0();
  out.log = nav.err();

  out.rep = read_report(report_path);
  ASSERT_TRUE(out.rep.stop.has_value() && out.rep.summary.has_value())
      << "no stop and summary lines in " << report_path << "\n" << tail(slurp(report_path));
  ASSERT_FALSE(out.rep.configures.empty()) << tail(slurp(report_path));
  out.sent = parse_frames(slurp(capture));
  out.received = parse_frames(slurp(fs::path(capture.string() + ".in")));
  out.where = fmt::format("\n(report {}, capture {})", report_path.string(), capture.string());
}

class Px4Driver : public ::testing::TestWithParam<Px4Case> {};

// The harness itself, whatever the device answers: the driver runs on the pty, every UBX frame
// it writes reaches navemu intact and in order (navemu's CAPTURE.in holds exactly the harness's
// tx frames, up to the last one it wrote), and navemu's acknowledgements reach the driver (each
// ACK-ACK/ACK-NAK the harness read is one navemu sent, in order).
TEST_P(Px4Driver, HarnessRunsTheDriverOnThePty) {
  const Px4Case& c = GetParam();
  if (!have_harness()) GTEST_SKIP() << kNoHarness;
  const ProfileFacts facts = profile_facts(c.profile);
  TempDir dir(std::string("px4-harness-") + c.profile);
  Px4Run run;
  run_px4(dir, facts, c.fixed_baud ? facts.baud : 0, 3.0, run);
  if (HasFatalFailure()) return;
  const Report& rep = run.rep;

  std::vector<std::string> written, arrived;
  for (const YAML::Node& t : rep.tx) written.push_back(str(t, "msg") + "/" + str(t, "len"));
  for (const UbxFrame& f : run.received)
    arrived.push_back(fmt::format("{:02X} {:02X}/{}", f.id.cls, f.id.id, f.payload.size()));
  ASSERT_FALSE(written.empty()) << "the driver wrote no UBX frame" << run.where;
  EXPECT_EQ(arrived, written) << "frames navemu received vs frames the driver wrote" << run.where;

  std::vector<std::string> acks_sent, acks_read;
  for (const UbxFrame& f : run.sent)
    if ((f.id == ubx::kAckAck || f.id == ubx::kAckNak) && f.payload.size() == 2)
      acks_sent.push_back(fmt::format("{:02X} {:02X} of {:02X} {:02X}", f.id.cls, f.id.id, f.payload[0], f.payload[1]));
  for (const YAML::Node& r : rep.rx)
    if (str(r, "msg").substr(0, 2) == "05") acks_read.push_back(str(r, "msg") + " of " + str(r, "of"));
  ASSERT_FALSE(acks_read.empty()) << "the driver read no ACK-ACK/ACK-NAK" << run.where;
  ASSERT_LE(acks_read.size(), acks_sent.size()) << run.where;
  acks_sent.resize(acks_read.size());  // navemu may answer after the harness has stopped
  EXPECT_EQ(acks_read, acks_sent) << "acknowledgements the driver read vs those navemu sent" << run.where;
  EXPECT_GE((*rep.summary)["attempts"].as<int>(), 1);
}

TEST_P(Px4Driver, ConfiguresAtOnceAndReportsEveryEpochAsSent) {
  const Px4Case& c = GetParam();
  if (!have_harness()) GTEST_SKIP() << kNoHarness;
  const ProfileFacts facts = profile_facts(c.profile);
  const double window = window_s();
  const double run_s = window + 10.0;  // configure, first fix, the window, margin
  const int baud = c.fixed_baud ? facts.baud : 0;

  TempDir dir(std::string("px4-") + c.profile);
  Px4Run run;
  run_px4(dir, facts, baud, run_s, run);
  if (HasFatalFailure()) return;
  const Report& rep = run.rep;
  const std::vector<UbxFrame>& sent = run.sent;
  const std::vector<UbxFrame>& received = run.received;
  const std::string& where = run.where;

  // configure() at the first attempt; board and protocol version from MON-VER.
  const YAML::Node& first = rep.configures.front();
  const auto success = std::find_if(rep.configures.begin(), rep.configures.end(),
                                    [](const YAML::Node& n) { return n["result"].as<int>() == 0; });
  EXPECT_EQ(first["result"].as<int>(), 0)
      << "configure() failed " << rep.configures.size() << " times in " << run_s << " s"
      << (success != rep.configures.end() ? fmt::format(" (first success: attempt {})", (*success)["attempt"].as<int>()) : "");
  const YAML::Node& detected = success != rep.configures.end() ? *success : rep.configures.back();
  EXPECT_EQ(str(detected, "board"), c.board);
  EXPECT_EQ(str(detected, "protocol_version"), facts.protver);
  EXPECT_TRUE(rep.receive_ends.empty())
      << "receive() returned <= 0 " << rep.receive_ends.size() << " times: the driver reconfigured";

  // Handshake: no ACK-NAK but the part's own; every MON-VER poll answered.
  const Handshake h = analyse_handshake(sent, received, c.part_naks);
  EXPECT_EQ(h.naks - h.part_naks, 0)
      << h.naks << " ACK-NAK (" << h.part_naks << " as the real part gives), NAKed:" << counted(h.unexpected_naks)
      << "\nunanswered CFG requests:" << counted(h.unanswered) << where;
  EXPECT_EQ(h.mon_ver_answers, h.mon_ver_polls) << "MON-VER polls answered";

  // The first 3D fix after configure() returned, then the rate and the UTC step over the window.
  double t_configured = -1, t_fix = -1, rate_hz = 0;
  std::vector<YAML::Node> in_window;
  if (success != rep.configures.end()) {
    t_configured = t_of(*success);
    for (const YAML::Node& g : rep.gps)
      if (t_of(g) >= t_configured && g["fix_type"].as<int>() >= 3) {
        if (t_fix < 0) t_fix = t_of(g);
        if (t_of(g) <= t_fix + window) in_window.push_back(g);
      }
  }
  if (t_fix >= 0) {
    EXPECT_LE(t_fix - t_configured, 1.5) << "first 3D fix after configure() returned";
    const double span = t_of(in_window.back()) - t_of(in_window.front());
    EXPECT_GE(span, window - 0.5) << "3D reports stopped " << span << " s into the " << window << " s window";
    rate_hz = in_window.size() > 1 ? static_cast<double>(in_window.size() - 1) / span : 0.0;
    EXPECT_NEAR(rate_hz, 5.0, 0.05) << in_window.size() << " reports in " << span << " s";
    int bad_steps = 0;
    std::string first_bad;
    for (std::size_t i = 1; i < in_window.size(); ++i) {
      const auto step = static_cast<std::int64_t>(in_window[i]["time_utc_usec"].as<std::uint64_t>() -
                                                  in_window[i - 1]["time_utc_usec"].as<std::uint64_t>());
      if (step != 200'000 && bad_steps++ == 0) first_bad = fmt::format("{} us at report {}", step, i);
    }
    EXPECT_EQ(bad_steps, 0) << "UTC steps other than 200 ms, first: " << first_bad;
  } else {
    ADD_FAILURE() << "no 3D fix reported" << (t_configured < 0 ? " (never configured)" : "");
  }

  // eph/epv and numSV of each report: those of navemu's NAV-PVT for that epoch.
  std::map<std::int64_t, ubx::NavPvt> pvt_by_utc;
  for (const ubx::NavPvt& m : decode_all<ubx::NavPvt>(sent, ubx::kNavPvt)) pvt_by_utc[pvt_utc_usec(m)] = m;
  int pvt_matched = 0, pvt_mismatched = 0;
  std::string first_mismatch;
  for (const YAML::Node& g : rep.gps) {
    const auto it = pvt_by_utc.find(static_cast<std::int64_t>(g["time_utc_usec"].as<std::uint64_t>()));
    const bool same = it != pvt_by_utc.end() &&
                      std::abs(g["eph"].as<double>() - it->second.h_acc_mm * 1e-3) <= 1e-3 &&
                      std::abs(g["epv"].as<double>() - it->second.v_acc_mm * 1e-3) <= 1e-3 &&
                      g["satellites_used"].as<int>() == it->second.num_sv;
    (same ? pvt_matched : pvt_mismatched)++;
    if (!same && first_mismatch.empty())
      first_mismatch = it == pvt_by_utc.end()
                           ? fmt::format("no NAV-PVT at UTC {} us", g["time_utc_usec"].as<std::uint64_t>())
                           : fmt::format("iTOW {} ms: eph {} epv {} numSV {} vs hAcc {} vAcc {} mm numSV {}",
                                         it->second.i_tow_ms, g["eph"].as<float>(), g["epv"].as<float>(),
                                         g["satellites_used"].as<int>(), it->second.h_acc_mm,
                                         it->second.v_acc_mm, it->second.num_sv);
  }
  EXPECT_EQ(pvt_mismatched, 0) << "reports unlike their NAV-PVT, first: " << first_mismatch;

  // Satellite reports: navemu's NAV-SAT / NAV-SVINFO in order, as the driver converts them.
  std::vector<Sky> skies;
  if (facts.protocol_27) {
    for (const ubx::NavSat& m : decode_all<ubx::NavSat>(sent, ubx::kNavSat)) skies.push_back(sky_of(m));
  } else {
    for (const ubx::NavSvinfo& m : decode_all<ubx::NavSvinfo>(sent, ubx::kNavSvinfo)) skies.push_back(sky_of(m));
  }
  std::size_t next = 0;
  int sky_matched = 0, sky_mismatched = 0;
  std::string first_sky;
  for (const YAML::Node& s : rep.sats) {
    const Sky reported = sky_of_report(s);
    const auto it = std::find(skies.begin() + static_cast<std::ptrdiff_t>(std::min(next, skies.size())), skies.end(), reported);
    if (it != skies.end()) {
      next = static_cast<std::size_t>(it - skies.begin()) + 1;
      ++sky_matched;
    } else if (sky_mismatched++ == 0) {
      first_sky = "reported" + sky_text(reported);
    }
  }
  EXPECT_GT(sky_matched, 0) << "no satellite report matches navemu's "
                            << (facts.protocol_27 ? "NAV-SAT" : "NAV-SVINFO") << " (" << skies.size() << " sent)";
  EXPECT_EQ(sky_mismatched, 0) << "satellite reports unlike navemu's, first " << first_sky;

  // Noise and jamming from MON-HW / MON-RF.
  const std::set<std::pair<int, int>> nj = noise_jam_sent(sent, facts.protocol_27);
  const char* mon = facts.protocol_27 ? "MON-RF" : "MON-HW";
  EXPECT_FALSE(nj.empty()) << "navemu sent no " << mon;
  int noise = 0, jam = -1;
  if (!rep.gps.empty()) {
    noise = rep.gps.back()["noise_per_ms"].as<int>();
    jam = rep.gps.back()["jamming_indicator"].as<int>();
    EXPECT_NE(noise, 0) << "noise_per_ms of the last report";
    EXPECT_TRUE(jam >= 0 && jam <= 255) << jam;
    EXPECT_TRUE(nj.empty() || nj.count({noise, jam}) == 1)
        << "noise " << noise << " jamming " << jam << " not from any " << mon << " sent";
  }

  // The periodic messages the driver configured and waits for.
  std::string missing;
  for (const auto& [id, name] : configured_outputs(facts.protocol_27))
    if (std::none_of(sent.begin(), sent.end(), [&](const UbxFrame& f) { return f.id == id; }))
      missing += std::string(" ") + name;
  if (success != rep.configures.end()) {
    EXPECT_EQ(missing, "") << "configured but never sent";
  }

  std::printf("PX4 %s %s: configure %zu attempts (%s), board %s, PROTVER %s; first 3D fix %.2f s after "
              "configure; %.3f Hz over %.1f s (%zu reports); NAV-PVT matched %d/%d; sky matched %d/%zu; "
              "noise %d jamming %d; ACK %d, ACK-NAK %d (%d the part's); missing:%s\n",
              c.profile, c.fixed_baud ? fmt::format("fixed {} baud", baud).c_str() : "auto baud",
              rep.configures.size(),
              success != rep.configures.end() ? fmt::format("first success #{}", (*success)["attempt"].as<int>()).c_str() : "none succeeded",
              str(detected, "board").c_str(), str(detected, "protocol_version").c_str(),
              t_fix >= 0 ? t_fix - t_configured : -1.0, rate_hz, window, in_window.size(), pvt_matched,
              pvt_matched + pvt_mismatched, sky_matched, rep.sats.size(), noise, jam, h.acks, h.naks,
              h.part_naks, missing.empty() ? " none" : missing.c_str());
}

// A protocol-18 receiver has no CFG-VALSET, and the driver probes with one before it falls back
// to CFG-PRT: "When messages from the class CFG are sent to the receiver, the receiver will send
// an acknowledge (ACK-ACK) or a not acknowledge (ACK-NAK) message back to the sender, depending
// on whether or not the message was processed correctly" (u-blox 8 / M8 Receiver Description
// UBX-13003221, section 32.5 "UBX Message Flow", acknowledgement), and a message it does not
// have is not processed.
const std::vector<PartNak> kM8Naks{{ubx::kCfgValset, "UBX-13003221 32.5: no CFG-VALSET in protocol 18"}};

// The jamming detector's sensitivity item, CFG-SEC-JAMDET_SENSITIVITY_HI (0x10f60051), came with
// HPG 1.30: it is in the configuration reference of the F9 HPG 1.32 interface description
// (UBX-22008968) and not in that of HPG 1.13 (UBX-21023318), so an HPG 1.1x part NAKs the
// CFG-VALSET that holds it (VALSET: "an unknown key ... the whole message is rejected").
const std::vector<PartNak> kHpg112Naks{{ubx::kCfgValset, "UBX-21023318: no CFG-SEC-JAMDET_SENSITIVITY_HI before HPG 1.30"}};

std::vector<Px4Case> cases() {
  std::vector<Px4Case> out;
  for (const bool fixed : {false, true}) {
    out.push_back({"ublox-m8", "u_blox8", kM8Naks, fixed});
    out.push_back({"ublox-f9p", "u_blox9_F9P_L1L2", kHpg112Naks, fixed});
    out.push_back({"ublox-f9p-hpg132", "u_blox9_F9P_L1L2", {}, fixed});
  }
  return out;
}

// Impairments as PX4's driver sees them (issue "impairments"), each on the F9P for 5 s:
//  - a wideband jammer of J/S 45 dB on L1: every satellite's C/N0 falls to about 63.1 - 45 =
//    18 dB-Hz, below the 28 dB-Hz tracking threshold; MON-RF's jamming state "critical" (3,
//    interference visible and no fix) and the noise up (of MON-RF the driver reads noise,
//    jamInd and the flags only);
//  - a tunnel (an outage of the whole sky) and an open antenna: every signal blocked, the
//    jamming state stays "ok" (1).
// From the event's start (+- one 200 ms epoch) the driver reports no fix and no satellite.
// After it, the satellites return after the re-acquisition time (1 s) and the fix with them
// (+- one epoch), jamming state "ok".
struct ImpairmentCase {
  const char* name;
  const char* event;  // the `events:` entry, without start and duration
  int jamming_state;  // during the event
};
class Px4Impairment : public ::testing::TestWithParam<ImpairmentCase> {};

TEST_P(Px4Impairment, TheDriverSeesItComeAndGo) {
  const ImpairmentCase& c = GetParam();
  if (!have_harness()) GTEST_SKIP() << kNoHarness;
  const ProfileFacts facts = profile_facts("ublox-f9p-hpg132");
  TempDir dir(std::string("px4-") + c.name);
  Px4Run run;
  constexpr double kOn_s = 6.0, kFor_s = 5.0, kReacquisition_s = 1.0, kEpoch_s = 0.2;
  run_px4(dir, facts, facts.baud, 16.0, run,
          fmt::format("events:\n  - {{{}, start_s: {}, duration_s: {}}}\n", c.event, kOn_s, kFor_s));
  if (HasFatalFailure()) return;
  // The event's start as navemu announced it: "event: ..., from ISO (WEEK:TOW) for 5 s".
  const std::optional<GpsTime> start = announced_event_start(run.log, "");
  ASSERT_TRUE(start) << run.log;
  const GpsTime on = *start, off = on.plus_s(kFor_s);

  struct Seen {
    double t_s;  // from the event's start
    int fix, used, jamming, noise;
  };
  std::vector<Seen> seen;
  for (const YAML::Node& g : run.rep.gps) {
    const auto utc_us = g["time_utc_usec"].as<std::int64_t>();
    if (utc_us == 0) continue;
    seen.push_back({seconds_between(gps_from_unix_ns(utc_us * 1000), on), g["fix_type"].as<int>(),
                    g["satellites_used"].as<int>(), g["jamming_state"].as<int>() & 0x03,
                    g["noise_per_ms"].as<int>()});
  }
  ASSERT_FALSE(seen.empty()) << run.where;
  ASSERT_LT(seen.front().t_s, -2.0) << "reports from before the event" << run.where;
  ASSERT_GT(seen.back().t_s, kFor_s + kReacquisition_s + 2.0) << "reports from after it" << run.where;
  const double end_s = seconds_between(off, on);
  const Seen *before = nullptr, *during = nullptr;
  int jammed = 0, recovered = 0;
  std::optional<double> lost_at, back_at;
  for (const Seen& s : seen) {
    const std::string at_t = fmt::format(" at {:.1f} s from the event's start", s.t_s);
    if (s.t_s < -kEpoch_s && s.fix == 3) {  // the last 3 s before (MON-RF arrives after the first fixes)
      if (s.t_s > -3.0) {
        EXPECT_EQ(s.jamming, 1) << at_t;
      }
      before = &s;
    }
    if (s.t_s >= -kEpoch_s / 2 && s.fix < 2 && !lost_at) lost_at = s.t_s;
    if (s.t_s > end_s && s.fix == 3 && !back_at) back_at = s.t_s;
    if (s.t_s >= kEpoch_s * 1.5 && s.t_s < end_s - kEpoch_s / 2) {  // MON-RF may lag one epoch
      ++jammed;
      EXPECT_LT(s.fix, 2) << at_t;
      EXPECT_EQ(s.used, 0) << at_t;
      EXPECT_EQ(s.jamming, c.jamming_state) << at_t;
      if (before && c.jamming_state == 3) {
        EXPECT_GT(s.noise, 10 * before->noise) << at_t;
      }
      during = &s;
    }
    if (s.t_s >= end_s + kReacquisition_s + 2 * kEpoch_s) {
      ++recovered;
      EXPECT_EQ(s.fix, 3) << at_t;
      EXPECT_EQ(s.jamming, 1) << at_t;
    }
  }
  ASSERT_TRUE(before && during) << "no 3D fix before the event, or no report during it" << run.where;
  EXPECT_GE(jammed, 18) << run.where;
  EXPECT_GE(recovered, 10) << run.where;
  ASSERT_TRUE(lost_at && back_at) << run.where;
  EXPECT_LE(*lost_at, kEpoch_s) << "fix lost at the event's start" << run.where;
  EXPECT_NEAR(*back_at, end_s + kReacquisition_s, kEpoch_s + 1e-3) << "fix back after re-acquisition" << run.where;
  std::printf("PX4 %s: fix lost %.2f s after the event's start, back %.2f s after its end; %d reports during, "
              "jamming state %d, noise %d -> %d\n",
              c.name, *lost_at, *back_at - end_s, jammed, during->jamming, before->noise, during->noise);
}

// A spoofer (issue "impairments"): PX4's driver follows the walk of the fix north and back, the
// fix never drops, and its spoofing_state (NAV-STATUS spoofDetState) says 2 "spoofing
// indicated" from the event's start to its end, within one epoch, and 1 outside.
TEST(Px4Spoofing, TheDriverIsWalkedOffAndSeesTheIndication) {
  if (!have_harness()) GTEST_SKIP() << kNoHarness;
  const ProfileFacts facts = profile_facts("ublox-f9p-hpg132");
  TempDir dir("px4-spoofing");
  Px4Run run;
  constexpr double kOn_s = 6.0, kFor_s = 6.0, kRamp_s = 2.0, kNorth_m = 200.0, kEpoch_s = 0.2;
  run_px4(dir, facts, facts.baud, 16.0, run,
          fmt::format("events:\n  - {{type: spoofing, start_s: {}, duration_s: {}, ramp_s: {}, offset_m: [0, {}, 0], "
                      "power_advantage_db: 6}}\n",
                      kOn_s, kFor_s, kRamp_s, kNorth_m));
  if (HasFatalFailure()) return;
  const std::optional<GpsTime> start = announced_event_start(run.log, "spoofing");
  ASSERT_TRUE(start) << run.log;
  const GpsTime on = *start;
  const EventWindow w{0.0, kFor_s, kRamp_s};
  constexpr double kMetresPerDegLat = 110'852.0;  // at 32.3 deg N (WGS 84 meridian arc)
  std::optional<double> lat0_deg;
  int during = 0, outside = 0, first_indicated = -1;
  double worst_m = 0.0, first_indicated_s = 0.0, last_indicated_s = -1.0;
  for (const YAML::Node& g : run.rep.gps) {
    const auto utc_us = g["time_utc_usec"].as<std::int64_t>();
    if (utc_us == 0 || g["fix_type"].as<int>() < 3) continue;
    const double t_s = seconds_between(gps_from_unix_ns(utc_us * 1000), on);
    const double lat_deg = g["latitude_deg"].as<double>();
    const int spoofing = g["spoofing_state"].as<int>();
    if (t_s < -1.0) lat0_deg = lat_deg;  // the last report a second before: the true place
    if (!lat0_deg || t_s < -1.0) continue;
    const double north_m = (lat_deg - *lat0_deg) * kMetresPerDegLat;
    // NAV-STATUS may come one epoch after NAV-PVT: the state is checked an epoch inside.
    if (t_s >= kEpoch_s && t_s < kFor_s - kEpoch_s) {
      ++during;
      EXPECT_EQ(spoofing, 2) << "at " << t_s << " s";
    } else if (t_s < -kEpoch_s || t_s > kFor_s + kEpoch_s) {
      ++outside;
      EXPECT_EQ(spoofing, 1) << "at " << t_s << " s";
    }
    if (spoofing == 2) {
      if (first_indicated < 0) first_indicated_s = t_s;
      first_indicated = 1;
      last_indicated_s = t_s;
    }
    const double pulled_m = kNorth_m * event_level(w, t_s);
    worst_m = std::max(worst_m, std::abs(north_m - pulled_m));
    EXPECT_NEAR(north_m, pulled_m, 5.0) << "at " << t_s << " s";
  }
  EXPECT_GE(during, 20) << run.where;
  EXPECT_GE(outside, 10) << run.where;
  EXPECT_LE(std::abs(first_indicated_s), 2 * kEpoch_s + 1e-3) << run.where;
  EXPECT_LE(std::abs(last_indicated_s - kFor_s), 2 * kEpoch_s + 1e-3) << run.where;
  std::printf("PX4 spoofing: walked within %.2f m of the pull (level x %.0f m north); spoofing_state 2 from %.2f s "
              "to %.2f s of the %.0f s event, %d reports during\n",
              worst_m, kNorth_m, first_indicated_s, last_indicated_s, kFor_s, during);
}

// A time spoofer (issue "impairments"): PX4's driver reports UTC time pulled 2 s ahead along a
// 2 s ramp and back, against its own monotonic clock (the offset between the two, less its
// value before, is 2 s x the event's level within 30 ms: the report's latency varies by a few
// ms), the position staying (within 3 m) and the spoofing indicated.
TEST(Px4Spoofing, TheDriverSeesTheTimePulledAway) {
  if (!have_harness()) GTEST_SKIP() << kNoHarness;
  const ProfileFacts facts = profile_facts("ublox-f9p-hpg132");
  TempDir dir("px4-time-spoofing");
  Px4Run run;
  constexpr double kOn_s = 6.0, kFor_s = 8.0, kRamp_s = 2.0, kPull_s = 2.0;
  run_px4(dir, facts, facts.baud, 20.0, run,
          fmt::format("events:\n  - {{type: spoofing, start_s: {}, duration_s: {}, ramp_s: {}, time_offset_s: {}, "
                      "power_advantage_db: 6}}\n",
                      kOn_s, kFor_s, kRamp_s, kPull_s));
  if (HasFatalFailure()) return;
  const std::optional<GpsTime> start = announced_event_start(run.log, "spoofing");
  ASSERT_TRUE(start) << run.log;
  const EventWindow w{0.0, kFor_s, kRamp_s};
  struct Seen {
    double t_harness_s, utc_s;
    Vec3 p_ecef_m;
    int spoofing;
  };
  std::vector<Seen> seen;
  for (const YAML::Node& g : run.rep.gps) {
    const auto utc_us = g["time_utc_usec"].as<std::int64_t>();
    if (utc_us == 0 || g["fix_type"].as<int>() < 3) continue;
    seen.push_back({g["t"].as<double>(), static_cast<double>(utc_us) * 1e-6,
                    ecef_from_geodetic({g["latitude_deg"].as<double>(), g["longitude_deg"].as<double>(),
                                        g["altitude_ellipsoid_m"].as<double>()}),
                    g["spoofing_state"].as<int>()});
  }
  // Before: the offset of UTC from the harness's clock and the place (the 2 s up to 1 s before).
  const double start_utc_s = static_cast<double>(unix_ns_from_gps(*start)) * 1e-9;
  double offset0 = 0.0;
  Vec3 p0 = Vec3::Zero();
  int n0 = 0;
  for (const Seen& s : seen)
    if (s.utc_s > start_utc_s - 3.0 && s.utc_s < start_utc_s - 1.0) {
      offset0 += s.utc_s - s.t_harness_s;
      p0 += s.p_ecef_m;
      ++n0;
    }
  ASSERT_GT(n0, 5) << run.where;
  offset0 /= n0;
  p0 /= n0;
  int checked = 0, indicated = 0;
  double worst_s = 0.0, worst_m = 0.0;
  for (const Seen& s : seen) {
    // The event's time of this report: the harness's clock on the scenario's (before the pull).
    const double t = s.t_harness_s + offset0 - start_utc_s;
    if (t < -3.0 || t > kFor_s + 3.0) continue;
    const double pulled_s = (s.utc_s - s.t_harness_s) - offset0;
    EXPECT_NEAR(pulled_s, kPull_s * event_level(w, t), 0.03) << "at " << t << " s";
    worst_s = std::max(worst_s, std::abs(pulled_s - kPull_s * event_level(w, t)));
    worst_m = std::max(worst_m, (s.p_ecef_m - p0).norm());
    EXPECT_LT((s.p_ecef_m - p0).norm(), 3.0) << "at " << t << " s";
    if (t > 0.4 && t < kFor_s - 0.4) indicated += s.spoofing == 2;
    ++checked;
  }
  EXPECT_GE(checked, 60) << run.where;
  EXPECT_GE(indicated, 30) << run.where;
  std::printf("PX4 time spoofing: UTC pulled as the ramp says within %.3f s over %d reports, the position within %.2f m, "
              "spoofing indicated in %d reports\n",
              worst_s, checked, worst_m, indicated);
}

// Satellite faults and a storm as PX4's driver sees them, one after the other in one run on the
// F9P (5 Hz, L1 single-frequency fix, so the ionosphere is not removed):
//  - the highest satellite flagged unhealthy for 4 s: out of the fix from the event's start to
//    its end (+- one epoch) and back after, the fix kept, satellites_used NAV-SAT's count of each
//    epoch (one less than it would be: satellites rising and setting change it as well);
//  - the second highest satellite's clock 300 m off for 4 s (its broadcast data do not show
//    it): the receiver's residual test leaves it out (models/receiver.cpp), so it is out of
//    NAV-SAT's used satellites and the fix stays within 3 m of its place before;
//  - an ionospheric storm (the true delay x 20, the broadcast model quiet) for 4 s: the fix
//    moves by more than 10 m (at night the broadcast model's zenith delay is 1.5 m, IS-GPS-200
//    20.3.3.5.2.5's 5 ns), and comes back within 3 m;
//  - multipath x 300 for 4 s (open sky, the F9P's geodetic class: 0.05 m at the zenith, so
//    15 m / sin(el) per satellite, correlated over a minute): the fix moves by more than 0.5 m,
//    and comes back within 3 m. Some 30 satellites average it down and the move is a 3-D vector
//    whose length can come near zero: offline (`navemu simulate`, this profile at 5 Hz, 600
//    random times in two months and seeds) its least length while the event lasts was 1.5 m at
//    the least, 3.0 m at the 1st percentile, 27 m the median; with the tail's r^3 law, 0.5 m has
//    a chance of some 1e-4. Without the event the least move is 0.16 m at most (200 runs); at
//    x 100 it was under 2 m in a few per cent of runs;
//  - the second highest satellite 300 m off its broadcast orbit, radially, for 4 s (its range
//    longer by ~300 m: the satellite sees the receiver within 14 deg of its nadir): left out and
//    the fix kept in place the same way.
// The satellites are the built-in constellation's at the run's time, as the model computes them
// (a stationary receiver at the site; the choice only, not what is checked).
TEST(Px4SatelliteFaults, TheDriverSeesThemComeAndGo) {
  if (!have_harness()) GTEST_SKIP() << kNoHarness;
  const ProfileFacts facts = profile_facts("ublox-f9p-hpg132");
  const GpsTime soon = gps_from_unix_ns(std::chrono::duration_cast<std::chrono::nanoseconds>(
                                            std::chrono::system_clock::now().time_since_epoch())
                                            .count())
                           .plus_s(10.0);
  const NavData nav = nominal_constellation(soon);
  const Vec3 p_rx = ecef_from_geodetic(kSite);
  std::vector<std::pair<double, int>> sky;  // elevation, PRN
  for (int prn = 1; prn <= 32; ++prn)
    if (const GpsEphemeris* eph = select_ephemeris(nav, gps_sat(prn), soon))
      sky.emplace_back(azimuth_elevation(kSite, p_rx, gps_sat_state(*eph, soon).p_ecef_m).el_rad * kRadToDeg, prn);
  std::sort(sky.rbegin(), sky.rend());
  ASSERT_GE(sky.size(), 2u);
  ASSERT_GT(sky[1].first, 20.0);
  const int sick = sky[0].second, drifting = sky[1].second;
  TempDir dir("px4-satellite-faults");
  Px4Run run;
  constexpr double kFor_s = 4.0, kEpoch_s = 0.2;
  run_px4(dir, facts, facts.baud, 38.0, run,
          fmt::format("events:\n"
                      "  - {{type: satellite, start_s: 6, duration_s: {0}, prn: {1}, unhealthy: true}}\n"
                      "  - {{type: satellite, start_s: 12, duration_s: {0}, prn: {2}, clock_error_m: 300}}\n"
                      "  - {{type: ionosphere, start_s: 18, duration_s: {0}, scale: 20}}\n"
                      "  - {{type: multipath, start_s: 24, duration_s: {0}, scale: 300}}\n"
                      "  - {{type: satellite, start_s: 30, duration_s: {0}, prn: {2}, orbit_error_m: [300, 0, 0]}}\n",
                      kFor_s, sick, drifting));
  if (HasFatalFailure()) return;
  const auto unhealthy = announced_event_start(run.log, fmt::format("satellite fault, G{:02d} flagged unhealthy", sick));
  ASSERT_TRUE(unhealthy) << run.log;
  // The events that move the fix: what navemu announces, and the least move while each lasts.
  // (The faults the residual test removes: min_m 0, the most the fix moves is checked instead.)
  struct Shift {
    std::string what;
    double min_m;
    std::optional<GpsTime> on{};
    Vec3 p0 = Vec3::Zero();
    double least_m = 1e9, most_m = 0.0;
    int drifting_used = 0, drifting_listed = 0;  // NAV-SAT epochs with the satellite used / listed
  };
  std::vector<Shift> shifts{{fmt::format("satellite fault, G{:02d} clock error 300 m", drifting), 0.0},
                            {"ionospheric storm, delay x20", 10.0},
                            {"multipath x300", 0.5},
                            {fmt::format("satellite fault, G{:02d} orbit error 300 m radial", drifting), 0.0}};
  for (Shift& f : shifts) {
    f.on = announced_event_start(run.log, f.what);
    ASSERT_TRUE(f.on) << f.what << "\n" << run.log;
  }

  // What navemu sent for each epoch (by NAV-PVT's UTC): NAV-PVT's numSV, and on the epochs that
  // carry a NAV-SAT (the driver asks for one every 10th) its count of satellites used and
  // whether the sick one is among them. Satellites rise and set during the run (the used count
  // of this profile changes about once in 6 minutes, so within the ~8 s the count is compared a
  // few per cent of runs see one): each report is compared with its own epoch, not with the
  // count before the event.
  struct Sent {
    int num_sv = 0;
    std::optional<int> sat_used;
    std::optional<bool> sick_used;
  };
  std::map<std::uint32_t, std::pair<int, bool>> sat_by_itow;  // used, sick used
  std::map<std::uint32_t, bool> drifting_used_by_itow;  // NAV-SAT's epochs: the drifting one used
  for (const ubx::NavSat& m : decode_all<ubx::NavSat>(run.sent, ubx::kNavSat)) {
    auto& [used, sick_used] = sat_by_itow[m.i_tow_ms];
    for (const ubx::NavSatSv& v : m.svs) {
      if ((v.flags & ubx::NavSatSv::kSvUsed) != 0) {
        ++used;
        sick_used = sick_used || (v.gnss_id == 0 && v.sv_id == sick);
      }
      if (v.gnss_id == 0 && v.sv_id == drifting)
        drifting_used_by_itow[m.i_tow_ms] = (v.flags & ubx::NavSatSv::kSvUsed) != 0;
    }
  }
  for (Shift& f : shifts)
    for (const auto& [itow_ms, used] : drifting_used_by_itow) {
      const double t = seconds_between(from_week_tow(to_week_tow(*f.on).week, itow_ms * 1e-3), *f.on);
      if (f.min_m > 0.0 || t < kEpoch_s || t >= kFor_s - kEpoch_s) continue;
      ++f.drifting_listed;
      f.drifting_used += used;
    }
  std::map<std::int64_t, Sent> sent_by_utc;
  for (const ubx::NavPvt& m : decode_all<ubx::NavPvt>(run.sent, ubx::kNavPvt)) {
    Sent& e = sent_by_utc[pvt_utc_usec(m)];
    e.num_sv = m.num_sv;
    if (const auto it = sat_by_itow.find(m.i_tow_ms); it != sat_by_itow.end()) {
      e.sat_used = it->second.first;
      e.sick_used = it->second.second;
    }
  }

  struct Seen {
    GpsTime t;
    int fix, used;
    Vec3 p_ecef_m;
    std::optional<Sent> sent;
  };
  std::vector<Seen> seen;
  for (const YAML::Node& g : run.rep.gps) {
    const auto utc_us = g["time_utc_usec"].as<std::int64_t>();
    if (utc_us == 0) continue;
    const auto sent = sent_by_utc.find(utc_us);
    seen.push_back({gps_from_unix_ns(utc_us * 1000), g["fix_type"].as<int>(), g["satellites_used"].as<int>(),
                    ecef_from_geodetic({g["latitude_deg"].as<double>(), g["longitude_deg"].as<double>(),
                                        g["altitude_ellipsoid_m"].as<double>()}),
                    sent == sent_by_utc.end() ? std::nullopt : std::optional<Sent>(sent->second)});
  }
  ASSERT_FALSE(seen.empty()) << run.where;
  const GpsTime last_on = *shifts.back().on;
  ASSERT_LT(seconds_between(seen.front().t, *unhealthy), -2.0) << "reports from before the first event" << run.where;
  ASSERT_GT(seconds_between(seen.back().t, last_on), kFor_s + 1.0) << "reports from after the last" << run.where;
  // Before each event (the 2 s up to one epoch before it): the satellites used and the place.
  const auto before = [&](GpsTime on, int& used, Vec3& p) {
    int n = 0;
    p = Vec3::Zero();
    for (const Seen& s : seen) {
      const double t = seconds_between(s.t, on);
      if (t < -2.0 || t >= -kEpoch_s) continue;
      EXPECT_EQ(s.fix, 3) << t << " s before an event";
      used = s.used;
      p += s.p_ecef_m;
      ++n;
    }
    ASSERT_GT(n, 5);
    p /= n;
  };
  int used_before = 0, ignored = 0;
  Vec3 p_unhealthy;
  before(*unhealthy, used_before, p_unhealthy);
  for (Shift& f : shifts) before(*f.on, ignored, f.p0);
  if (HasFatalFailure()) return;
  int fewer = 0, sick_out = 0;
  double most_after_m = 0.0;
  for (const Seen& s : seen) {
    const double tu = seconds_between(s.t, *unhealthy);
    const std::string at = fmt::format(" at {:.1f} s from the first event", tu);
    if (tu >= -2.0 && seconds_between(s.t, last_on) < kFor_s + 1.0) {
      EXPECT_EQ(s.fix, 3) << at;
    }
    // The driver's count is navemu's of that epoch; the sick satellite is out of NAV-SAT's used
    // ones while the event lasts and in them before and after.
    const bool out = tu >= kEpoch_s && tu < kFor_s - kEpoch_s;
    if (out || (tu >= kFor_s + kEpoch_s && seconds_between(s.t, *shifts[0].on) < -kEpoch_s) ||
        (tu > -2.0 && tu < -kEpoch_s)) {
      ASSERT_TRUE(s.sent) << "no NAV-PVT sent for the report" << at << run.where;
      EXPECT_EQ(s.used, s.sent->num_sv) << at;
      if (s.sent->sick_used) {
        EXPECT_EQ(*s.sent->sick_used, !out) << at;
        EXPECT_EQ(s.sent->sat_used, s.sent->num_sv) << at;
        if (out) ++sick_out;
      }
      if (out) ++fewer;
    }
    // Each move while its event lasts; back within 3 m in the 1.5 s after it (the next event
    // starts 2 s after).
    for (Shift& f : shifts) {
      const double t = seconds_between(s.t, *f.on), moved_m = (s.p_ecef_m - f.p0).norm();
      if (t >= kEpoch_s && t < kFor_s - kEpoch_s) {
        f.least_m = std::min(f.least_m, moved_m);
        f.most_m = std::max(f.most_m, moved_m);
      }
      if (t >= kFor_s + kEpoch_s && t < kFor_s + 1.5) most_after_m = std::max(most_after_m, moved_m);
    }
  }
  EXPECT_GE(fewer, 15) << run.where;
  EXPECT_GE(sick_out, 1) << "no NAV-SAT while the satellite was unhealthy" << run.where;
  for (const Shift& f : shifts) {
    if (f.min_m > 0.0) {
      EXPECT_GT(f.least_m, f.min_m) << f.what << run.where;
      continue;
    }
    EXPECT_LT(f.most_m, 3.0) << f.what << run.where;
    EXPECT_GE(f.drifting_listed, 1) << f.what << ": no NAV-SAT while it lasted" << run.where;
    EXPECT_EQ(f.drifting_used, 0) << f.what << run.where;
  }
  EXPECT_LT(most_after_m, 3.0) << run.where;
  std::printf("PX4 satellite faults: G%02d unhealthy, out of the fix in %d reports (%d NAV-SAT; %d used before); G%02d clock +300 m "
              "excluded, the fix moved at most %.2f m; a x20 storm moved it at least %.1f m; multipath x300 at least %.1f m; "
              "G%02d 300 m radial orbit error excluded, at most %.2f m; back within %.2f m after each\n",
              sick, fewer, sick_out, used_before, drifting, shifts[0].most_m, shifts[1].least_m,
              shifts[2].least_m, drifting, shifts[3].most_m, most_after_m);
}

// The receiver's cable out for 3 s, then a hot-start reset, as PX4's driver lives through them
// on the F9P:
//  - cable: no report of an epoch inside the window (the last from before it within two
//    epochs of its start), and reports again once it is back: the driver times out, configures
//    the receiver again (which kept its settings) and goes on;
//  - reset: no 3D fix for the boot (0.5 s) and the hot start's time to first fix (1 s); the
//    reset lost the driver's settings (RAM layer rebuilt from the defaults: no NAV-PVT), so the
//    driver has to configure the receiver again before it reports a fix, and does.
TEST(Px4DeviceEvents, CableOutAndResetTheDriverRecovers) {
  if (!have_harness()) GTEST_SKIP() << kNoHarness;
  const ProfileFacts facts = profile_facts("ublox-f9p-hpg132");
  TempDir dir("px4-cable-reset");
  Px4Run run;
  constexpr double kCable_s = 3.0, kEpoch_s = 0.2, kRestart_s = 0.5 + 1.0;
  run_px4(dir, facts, facts.baud, 30.0, run,
          fmt::format("events:\n  - {{type: cable, start_s: 6, duration_s: {}}}\n  - {{type: reset, start_s: 14, start: hot}}\n",
                      kCable_s));
  if (HasFatalFailure()) return;
  const auto cable = announced_event_start(run.log, "cable unplugged");
  const auto reset = announced_event_start(run.log, "receiver reset, hot start");
  ASSERT_TRUE(cable && reset) << run.log;
  struct Seen {
    double t_harness_s;
    GpsTime t;
    int fix;
  };
  std::vector<Seen> seen;
  for (const YAML::Node& g : run.rep.gps) {
    const auto utc_us = g["time_utc_usec"].as<std::int64_t>();
    if (utc_us == 0) continue;
    seen.push_back({g["t"].as<double>(), gps_from_unix_ns(utc_us * 1000), g["fix_type"].as<int>()});
  }
  ASSERT_FALSE(seen.empty()) << run.where;
  ASSERT_LT(seconds_between(seen.front().t, *cable), -2.0) << run.where;
  ASSERT_GT(seconds_between(seen.back().t, *reset), 8.0) << run.where;
  std::optional<double> last_before_cable, first_after_cable, first_fix_after_reset;
  double harness_at_reset = 0.0;
  for (const Seen& s : seen) {
    const double tc = seconds_between(s.t, *cable), tr = seconds_between(s.t, *reset);
    if (tc < 0.0) last_before_cable = tc;
    if (tc >= kEpoch_s && tc < kCable_s - kEpoch_s) ADD_FAILURE() << "a report from " << tc << " s into the cable window";
    if (tc >= kCable_s && !first_after_cable) first_after_cable = tc - kCable_s;
    if (tr < 0.0) harness_at_reset = s.t_harness_s;
    if (tr >= 0.0 && tr < kRestart_s) {
      EXPECT_NE(s.fix, 3) << "a 3D fix " << tr << " s after the reset";
    }
    if (tr >= 0.0 && s.fix == 3 && !first_fix_after_reset) first_fix_after_reset = tr;
  }
  ASSERT_TRUE(last_before_cable && first_after_cable && first_fix_after_reset) << run.where;
  EXPECT_GE(*last_before_cable, -2 * kEpoch_s - 1e-3) << run.where;
  EXPECT_LT(*first_after_cable, 5.0) << "reports again after the cable is back" << run.where;
  EXPECT_GE(*first_fix_after_reset, kRestart_s - 1e-3) << run.where;
  EXPECT_LT(*first_fix_after_reset, 10.0) << run.where;
  int reconfigured = 0;
  for (const YAML::Node& c : run.rep.configures)
    if (c["t"].as<double>() > harness_at_reset && c["result"].as<int>() == 0) ++reconfigured;
  EXPECT_GE(reconfigured, 1) << "the driver configured the reset receiver again" << run.where;
  std::printf("PX4 cable out 3 s: last report %.2f s before, first again %.2f s after it; hot reset: first 3D fix "
              "%.2f s after it, %d successful configure() after it\n",
              -*last_before_cable, *first_after_cable, *first_fix_after_reset, reconfigured);
}

// Truth faults as PX4's driver sees them, the vehicle driving east at 10 m/s (a straight line
// from the site): positions are measured against the line fitted to the reports outside the
// windows (east = e0 + v t, north constant); the fix's errors (~1 m) are far below the effects:
//  - freeze for 4 s: the position stops where it was at the freeze's start (east behind the
//    line by 10 m/s x the time since, within 3 m) while the velocity stays 10 m/s east;
//  - teleport 200 m north for 4 s: 200 m north of the line (+- 3 m), the velocity unchanged;
//  - time jump +10 s for 4 s: 100 m ahead on the line (+- 3 m);
// each from its start to its end within one epoch, and on the line again after it.
TEST(Px4TruthFaults, TheDriverSeesFreezeTeleportAndTimeJump) {
  if (!have_harness()) GTEST_SKIP() << kNoHarness;
  const ProfileFacts facts = profile_facts("ublox-f9p-hpg132");
  TempDir dir("px4-truth-faults");
  Px4Run run;
  constexpr double kFor_s = 4.0, kEpoch_s = 0.2, kSpeed_mps = 10.0;
  run_px4(dir, facts, facts.baud, 30.0, run,
          fmt::format("events:\n"
                      "  - {{type: truth, start_s: 8, duration_s: {0}, fault: freeze}}\n"
                      "  - {{type: truth, start_s: 14, duration_s: {0}, fault: teleport, offset_m: [0, 200, 0]}}\n"
                      "  - {{type: truth, start_s: 20, duration_s: {0}, fault: time_jump, jump_s: 10}}\n",
                      kFor_s),
          "source: line, line: {heading_deg: 90, length_m: 5000, speed_mps: 10, passes: 1, accel_mps2: 5}");
  if (HasFatalFailure()) return;
  const auto freeze = announced_event_start(run.log, "truth frozen");
  const auto teleport = announced_event_start(run.log, "truth teleported");
  const auto jump = announced_event_start(run.log, "truth time jump");
  ASSERT_TRUE(freeze && teleport && jump) << run.log;
  struct Seen {
    double t_s;  // from the freeze's start
    Vec3 enu_m;  // from the site
    double v_e_mps;
  };
  std::vector<Seen> seen;
  for (const YAML::Node& g : run.rep.gps) {
    const auto utc_us = g["time_utc_usec"].as<std::int64_t>();
    if (utc_us == 0 || g["fix_type"].as<int>() != 3) continue;
    const Vec3 p = ecef_from_geodetic({g["latitude_deg"].as<double>(), g["longitude_deg"].as<double>(),
                                       g["altitude_ellipsoid_m"].as<double>()});
    seen.push_back({seconds_between(gps_from_unix_ns(utc_us * 1000), *freeze), enu_from_ecef(p, kSite),
                    g["vel_e_m_s"].as<double>()});
  }
  const double t_teleport = seconds_between(*teleport, *freeze), t_jump = seconds_between(*jump, *freeze);
  const auto in = [&](double t, double from) { return t >= from - kEpoch_s && t < from + kFor_s + kEpoch_s; };
  // The line: a least-squares fit of east = e0 + v t and the mean north, outside the windows
  // (from 1 s before the freeze, at full speed).
  double n = 0, st = 0, stt = 0, se = 0, ste = 0, north = 0;
  for (const Seen& s : seen)
    if (s.t_s > -3.0 && !in(s.t_s, 0.0) && !in(s.t_s, t_teleport) && !in(s.t_s, t_jump)) {
      n += 1;
      st += s.t_s;
      stt += s.t_s * s.t_s;
      se += s.enu_m.x();
      ste += s.t_s * s.enu_m.x();
      north += s.enu_m.y();
    }
  ASSERT_GT(n, 40) << run.where;
  const double v = (n * ste - st * se) / (n * stt - st * st), e0 = (se - v * st) / n;
  north /= n;
  EXPECT_NEAR(v, kSpeed_mps, 0.1) << run.where;
  int frozen = 0, teleported = 0, jumped = 0, on_line = 0;
  double worst_m = 0.0;
  for (const Seen& s : seen) {
    if (s.t_s < -3.0) continue;
    const double t = s.t_s;
    Vec3 expected(e0 + v * t, north, 0.0);
    bool check = true;
    if (t >= kEpoch_s && t < kFor_s - kEpoch_s) {
      expected.x() = e0;  // stopped where the freeze began
      EXPECT_NEAR(s.v_e_mps, kSpeed_mps, 0.5) << "frozen velocity at " << t;
      ++frozen;
    } else if (t >= t_teleport + kEpoch_s && t < t_teleport + kFor_s - kEpoch_s) {
      expected.y() += 200.0;
      ++teleported;
    } else if (t >= t_jump + kEpoch_s && t < t_jump + kFor_s - kEpoch_s) {
      expected.x() += 10.0 * v;
      ++jumped;
    } else if (in(t, 0.0) || in(t, t_teleport) || in(t, t_jump)) {
      check = false;  // within an epoch of a window's edge
    } else {
      ++on_line;
    }
    if (!check) continue;
    const double d = std::hypot(s.enu_m.x() - expected.x(), s.enu_m.y() - expected.y());
    worst_m = std::max(worst_m, d);
    EXPECT_LT(d, 3.0) << "at " << t << " s from the freeze: east " << s.enu_m.x() - e0 - v * t << " m, north "
                      << s.enu_m.y() - north << " m off the line";
  }
  EXPECT_GE(frozen, 15);
  EXPECT_GE(teleported, 15);
  EXPECT_GE(jumped, 15);
  EXPECT_GE(on_line, 40);
  std::printf("PX4 truth faults: %d frozen, %d teleported, %d time-jumped and %d other reports within %.2f m of "
              "where the faulty truth put them\n",
              frozen, teleported, jumped, on_line, worst_m);
}

INSTANTIATE_TEST_SUITE_P(Events, Px4Impairment,
                         ::testing::Values(ImpairmentCase{"jamming", "type: jamming, j_over_s_db: 45", 3},
                                           ImpairmentCase{"tunnel", "type: outage", 1},
                                           ImpairmentCase{"antenna_open", "type: antenna, fault: open", 1}),
                         [](const ::testing::TestParamInfo<ImpairmentCase>& i) { return std::string(i.param.name); });

INSTANTIATE_TEST_SUITE_P(Profiles, Px4Driver, ::testing::ValuesIn(cases()),
                         [](const ::testing::TestParamInfo<Px4Case>& i) {
                           std::string name = std::string(i.param.profile) +
                                              (i.param.fixed_baud ? "_fixed_baud" : "_auto_baud");
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

}  // namespace
}  // namespace navemu::test::clients
