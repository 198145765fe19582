// `navemu run` with a u-blox profile against the real u-blox clients of Debian 12: gpsd 3.22 in
// its u-blox mode, ubxtool (python3-gps 3.22) and RTKLIB 2.4.3 (str2str, convbin, rnx2rtkp),
// each used as ../shared/TESTING.md describes. Each test skips with a message when its tool is
// missing. Every wait has a deadline; children are stopped by RAII (client_support.hpp).
//
// What navemu sent is known exactly: every run has a `file` output beside the pty, the same
// byte stream (replies to clients go only to the port they came from), parsed here with
// ubx::Parser and compared with what the client reports.

#include <gtest/gtest.h>

#include <fmt/format.h>

#include <map>
#include <thread>
#include <set>

#include "emulator/commands.hpp"
#include "models/constellation.hpp"
#include "models/geodesy.hpp"
#include "emulator/rinex_files.hpp"
#include "protocols/beidou_nav.hpp"
#include "protocols/galileo_inav.hpp"
#include "protocols/glonass_nav.hpp"
#include "protocols/gps_lnav.hpp"
#include "protocols/ubx.hpp"
#include "protocols/ubx_messages.hpp"
#include "tests/clients/client_support.hpp"
#include "tests/clients/ubx_frames.hpp"

namespace navemu::test::clients {
namespace {

// The paper's test site (Vicksburg, MS), h above the WGS-84 ellipsoid.
const Geodetic kUbxSite{32.3, -90.9, 60.0};

#define NAVEMU_REQUIRE_TOOL(var, name, package)                                          \
  const std::string var = find_program(name);                                            \
  if (var.empty())                                                                       \
    GTEST_SKIP() << name << " not found on PATH (nor in /usr/sbin): install Debian's "   \
                 << package << " to run this client test"

// ---- navemu with a u-blox profile ------------------------------------------------------------

// A profile file in the test's folder: configs/gnss/BASE.yaml with its `messages:` line (the
// UBX messages on at power-up) replaced; the other keys are the shipped profile's.
fs::path write_profile(const TempDir& dir, const std::string& base, const std::string& messages) {
  const std::string text = slurp(fs::path(NAVEMU_SOURCE_DIR) / "configs" / "gnss" / (base + ".yaml"));
  static const std::regex re(R"(\n  messages:[^\n]*)");
  EXPECT_TRUE(std::regex_search(text, re)) << base << ".yaml has no ubx.messages line";
  const fs::path p = dir / (base + "-test.yaml");
  std::ofstream(p) << std::regex_replace(text, re, "\n  messages: {" + messages + "}");
  return p;
}

// `capture`: gnss.capture, a mirror of every byte sent (replies included) and, in CAPTURE.in,
// of every byte received from the clients.
std::string ubx_config(const fs::path& profile, const fs::path& link, const fs::path& log,
                       const std::string& start = "now", const fs::path& capture = {},
                       const std::string& port = "uart1") {
  return fmt::format(
      "scenario: {{status_interval_s: 1, start: '{}'}}\n"
      "truth: {{source: stationary, position: {{lat_deg: {}, lon_deg: {}, h_m: {}}}}}\n"
      "gnss:\n"
      "  profile: '{}'\n"
      "{}"
      "  outputs:\n"
      "    - {{type: pty, link: '{}', port: {}}}\n"
      "    - {{type: file, path: '{}'}}\n"
      "imu: {{enabled: false}}\n",
      start, kUbxSite.lat_deg, kUbxSite.lon_deg, kUbxSite.h_m, profile.string(),
      capture.empty() ? std::string{} : fmt::format("  capture: '{}'\n", capture.string()),
      link.string(), port, log.string());
}

// ---- UBX frames (tests/clients/ubx_frames.hpp) -------------------------------------------

std::vector<std::uint8_t> ubx_poll(ubx::MsgId id) {
  std::vector<std::uint8_t> out;
  ubx::append_poll(id, out);
  return out;
}

// A client of the pty that reads and writes it (raw mode is navemu's, TESTING.md): UBX frames
// time-stamped at arrival, NMEA sentences counted.
class PtyClient {
 public:
  ~PtyClient() { close(); }
  bool open(const fs::path& path) {
    fd_ = ::open(path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
    return fd_ >= 0;
  }
  void close() {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
  }

  // Reads until monotonic time `until`, or until `stop()` is true after a read.
  template <class Stop>
  void read_until(double until, Stop stop) {
    for (;;) {
      const double left = until - mono_s();
      if (left <= 0 || fd_ < 0) return;
      pollfd p{fd_, POLLIN, 0};
      if (::poll(&p, 1, static_cast<int>(std::ceil(left * 1000.0))) <= 0) continue;
      if (read_once() && stop()) return;
    }
  }
  void read_until(double until) {
    read_until(until, [] { return false; });
  }

  // Writes all of `bytes` (waiting for room up to `timeout_s`, reading meanwhile so that the
  // other direction never fills). False when the deadline passed first.
  bool write_all(std::span<const std::uint8_t> bytes, double timeout_s = 5.0) {
    const double end = mono_s() + timeout_s;
    std::size_t done = 0;
    while (done < bytes.size()) {
      const ssize_t n = ::write(fd_, bytes.data() + done, bytes.size() - done);
      if (n > 0) {
        done += static_cast<std::size_t>(n);
        continue;
      }
      if (n < 0 && errno != EAGAIN && errno != EINTR) return false;
      if (mono_s() >= end) return false;
      pollfd p{fd_, POLLOUT | POLLIN, 0};
      ::poll(&p, 1, 10);
      if (p.revents & POLLIN) read_once();
    }
    return true;
  }

  const std::vector<UbxFrame>& frames() const { return frames_; }
  // Arrival times of the NMEA sentences of one type ("RMC").
  std::vector<double> nmea_times(const std::string& type) const {
    std::vector<double> out;
    for (const auto& [t, s] : nmea_)
      if (s.size() > 6 && s.compare(3, 3, type) == 0) out.push_back(t);
    return out;
  }
  std::size_t bytes_read() const { return bytes_; }
  const ubx::Parser::Counters& parser_counters() const { return parser_.counters(); }

 private:
  bool read_once() {
    std::uint8_t buf[8192];
    const ssize_t n = ::read(fd_, buf, sizeof buf);
    if (n <= 0) return false;
    const double t = mono_s();
    bytes_ += static_cast<std::size_t>(n);
    for (ssize_t i = 0; i < n; ++i) {
      // NMEA: '$' to LF outside UBX frames (UBX payloads may hold '$': only lines that end
      // within 100 bytes and start right after a frame or a line end count).
      const auto c = static_cast<char>(buf[i]);
      if (c == '$' && line_.empty()) in_line_ = true;
      if (in_line_) {
        line_ += c;
        if (c == '\n' || line_.size() > 100) {
          if (c == '\n') nmea_.emplace_back(t, line_);
          line_.clear();
          in_line_ = false;
        }
      }
      for (ubx::Parser::Result r = parser_.feed(buf[i]); r != ubx::Parser::Result::kNeedMore;
           r = parser_.poll()) {
        if (r != ubx::Parser::Result::kFrame) continue;
        frames_.push_back({{parser_.cls(), parser_.id()}, {parser_.payload().begin(), parser_.payload().end()}, t});
        line_.clear();
        in_line_ = false;
      }
    }
    return true;
  }

  int fd_ = -1;
  ubx::Parser parser_{65535};
  std::vector<UbxFrame> frames_;
  std::vector<std::pair<double, std::string>> nmea_;
  std::string line_;
  bool in_line_ = false;
  std::size_t bytes_ = 0;
};

// ---- time ------------------------------------------------------------------------------------

// gpsd's ISO-8601 UTC "2026-11-22T13:08:03.000Z" as GPS time of week in milliseconds; -1 if
// malformed.
std::int64_t iso_gps_tow_ms(const std::string& iso) {
  int y = 0, mo = 0, d = 0, h = 0, mi = 0;
  double s = 0;
  if (std::sscanf(iso.c_str(), "%d-%d-%dT%d:%d:%lfZ", &y, &mo, &d, &h, &mi, &s) != 6) return -1;
  return std::llround(to_week_tow(gps_from_utc(CalendarTime{y, mo, d, h, mi, s})).tow_s * 1000.0);
}

double mean(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return v.empty() ? 0.0 : s / static_cast<double>(v.size());
}

// ---- gpsd with a raw watch -------------------------------------------------------------------

// ---- gpsd in u-blox mode ------------------------------------------------------------------

// gpsd on the pty of a u-blox M8 whose profile turns on NAV-PVT, NAV-SAT, NAV-TIMEGPS, NAV-DOP,
// RXM-RAWX and RXM-SFRBX at 1 Hz (what gpsd needs for fix, sky, time, RAW and SUBFRAME,
// TESTING.md). gpsd must switch to its u-blox driver on the first valid UBX frame, show the
// profile's PROTVER in ?DEVICES, report a 3D fix within 3 sigma of the truth by its own
// accuracy figures (eph/epv, which gpsd takes from NAV-PVT hAcc/vAcc in u-blox mode), a sky
// equal to navemu's NAV-SAT, RAW pseudoranges equal to navemu's RXM-RAWX and SUBFRAMEs of
// navemu's RXM-SFRBX (gpsd checks their parity).
TEST(UbxGpsd, UbloxDriverFixSkyRawAndSubframes) {
  NAVEMU_REQUIRE_TOOL(gpsd, "gpsd", "gpsd 3.22");
  TempDir dir("ubx-gpsd");
  const fs::path link = dir / "gnss", log = dir / "gnss.ubx";
  const fs::path profile = write_profile(
      dir, "ublox-m8", "NAV-PVT: 1, NAV-SAT: 1, NAV-TIMEGPS: 1, NAV-DOP: 1, RXM-RAWX: 1, RXM-SFRBX: 1");
  const fs::path capture = dir / "wire.ubx";
  NavemuRun nav(dir, "navemu", ubx_config(profile, link, log, "now", capture), 60);
  ASSERT_TRUE(nav.wait_for_pty(link, 5.0)) << nav.diagnostics();
  Gpsd g;
  ASSERT_TRUE(g.start(gpsd, dir, link, 5.0)) << g.diagnostics() << nav.diagnostics();
  const double gpsd_start = mono_s();
  GpsdClient w;
  ASSERT_TRUE(w.connect(g.port(), "?WATCH={\"enable\":true,\"json\":true,\"raw\":1}\n")) << g.diagnostics();

  // Watch until the driver is u-blox, 8 distinct 3D fixes, RAW and SUBFRAMEs of two subframe
  // epochs (every 6 s) are in, then ask ?DEVICES; at most 30 s.
  std::string driver;
  std::optional<double> driver_after_s, first_fix_after_s;
  std::map<std::int64_t, YAML::Node> tpvs;  // by GPS tow ms; the last report of an epoch
  std::optional<std::int64_t> switch_tow;
  std::vector<YAML::Node> skies, raws, subframes;
  std::set<long> subframe_tows;
  std::optional<YAML::Node> devices;
  bool asked = false;
  const double end = gpsd_start + 30.0;
  double stop_at = end;
  while (const auto n = w.next(std::min(end, stop_at))) {
    const std::string cls = str(*n, "class");
    if (cls == "DEVICE" && !str(*n, "driver").empty()) {
      driver = str(*n, "driver");
      if (driver == "u-blox" && !driver_after_s) driver_after_s = mono_s() - gpsd_start;
    } else if (cls == "TPV") {
      // Before the switch gpsd is in NMEA mode, with eph/epv of its own (DOP x UERE); the
      // epoch during which it switches still carries those: u-blox mode from the next one.
      const std::int64_t tow = iso_gps_tow_ms(str(*n, "time"));
      if (driver == "u-blox" && !switch_tow) switch_tow = tow;
      if (tow >= 0 && switch_tow && tow > *switch_tow) tpvs[tow] = *n;
      if (num(*n, "mode").value_or(0) == 3 && !first_fix_after_s) first_fix_after_s = mono_s() - gpsd_start;
    } else if (cls == "SKY") {
      skies.push_back(*n);
    } else if (cls == "RAW") {
      raws.push_back(*n);
    } else if (cls == "SUBFRAME") {
      subframes.push_back(*n);
      subframe_tows.insert(static_cast<long>(num(*n, "TOW17").value_or(-1)));
    } else if (cls == "DEVICES") {
      for (const auto& d : (*n)["devices"])
        if (str(d, "driver") == "u-blox") devices = *n;
      if (devices) break;
    }
    std::size_t fixes = 0;
    for (const auto& [t, v] : tpvs) fixes += num(v, "mode").value_or(0) == 3 ? 1u : 0u;
    if (!asked && driver == "u-blox" && fixes >= 8 && !raws.empty() && subframe_tows.size() >= 2) {
      // The subtype appears once MON-VER has been answered; ask now.
      ASSERT_TRUE(w.send("?DEVICES;\n"));
      asked = true;
      stop_at = mono_s() + 3.0;
    }
  }
  g.child().stop();
  nav.stop_expecting_exit_0();
  EXPECT_TRUE(w.bad_lines().empty()) << w.bad_lines().front();

  // What navemu sent (the file output).
  const std::vector<UbxFrame> sent = parse_frames(slurp(log));
  std::map<std::uint32_t, ubx::NavPvt> pvt_by_tow;
  for (const auto& m : decode_all<ubx::NavPvt>(sent, ubx::kNavPvt)) pvt_by_tow[m.i_tow_ms] = m;
  std::map<std::uint32_t, ubx::NavSat> sat_by_tow;
  for (const auto& m : decode_all<ubx::NavSat>(sent, ubx::kNavSat)) sat_by_tow[m.i_tow_ms] = m;
  const std::vector<ubx::RxmRawx> rawx = decode_all<ubx::RxmRawx>(sent, ubx::kRxmRawx);
  std::set<std::tuple<int, long, int>> sfrbx;  // (PRN, HOW TOW count, subframe ID)
  for (const auto& m : decode_all<ubx::RxmSfrbx>(sent, ubx::kRxmSfrbx)) {
    if (m.words.size() != 10) continue;
    lnav::LnavSubframe words{};
    std::copy(m.words.begin(), m.words.end(), words.begin());
    const lnav::LnavTlmHow how = lnav::decode_tlm_how(words);
    sfrbx.insert({m.sv_id, static_cast<long>(how.tow_count), how.subframe_id});
  }
  ASSERT_FALSE(pvt_by_tow.empty()) << "navemu's log has no NAV-PVT" << nav.diagnostics();

  // Driver and identity. gpsd's ?DEVICES subtype carries MON-VER's sw/hw versions, subtype1
  // its extensions (PROTVER=18.00 from the profile).
  ASSERT_EQ(driver, "u-blox") << "gpsd did not switch to its u-blox driver" << g.diagnostics();
  ASSERT_TRUE(devices.has_value()) << "no ?DEVICES answer with the u-blox driver" << g.diagnostics();
  std::string subtype;
  for (const auto& d : (*devices)["devices"])
    if (str(d, "driver") == "u-blox") subtype = str(d, "subtype") + "," + str(d, "subtype1");
  EXPECT_NE(subtype.find("PROTVER=18.00"), std::string::npos) << subtype;
  EXPECT_NE(subtype.find("ROM CORE 3.01 (107888)"), std::string::npos) << subtype;
  // Measured from gpsd's start: gpsd 3.22 first runs its blocking probes of other receivers
  // (Garmin USB, GeoStar, Trimble TSIP, iSync; about 6.5 s on a pty, gpsd -D 5), then switches
  // on the first UBX frame it reads.
  RecordProperty("driver_switch_s", fmt::format("{:.2f}", driver_after_s.value_or(-1)));
  EXPECT_LT(driver_after_s.value_or(99), 15.0);

  // TPV: mode 3; position within 3 x gpsd's eph (horizontal) and 3 x epv (vertical); eph and
  // epv equal to the NAV-PVT hAcc/vAcc of that epoch, lat/lon to NAV-PVT's.
  double max_h_ratio = 0, max_v_ratio = 0, max_h_err = 0, max_v_err = 0;
  std::size_t fixes = 0;
  for (const auto& [tow, v] : tpvs) {
    if (num(v, "mode").value_or(0) != 3) continue;
    ++fixes;
    SCOPED_TRACE(fmt::format("TPV {}", str(v, "time")));
    const auto lat = num(v, "lat"), lon = num(v, "lon"), alt = num(v, "altHAE");
    const auto eph = num(v, "eph"), epv = num(v, "epv");
    ASSERT_TRUE(lat && lon && alt && eph && epv);
    const Vec3 e = enu_from_ecef(ecef_from_geodetic(Geodetic{*lat, *lon, *alt}), kUbxSite);
    const double h_err = std::hypot(e.x(), e.y()), v_err = std::abs(*alt - kUbxSite.h_m);
    max_h_err = std::max(max_h_err, h_err);
    max_v_err = std::max(max_v_err, v_err);
    max_h_ratio = std::max(max_h_ratio, h_err / *eph);
    max_v_ratio = std::max(max_v_ratio, v_err / *epv);
    EXPECT_LE(h_err, 3.0 * *eph) << "horizontal error " << h_err << " m, eph " << *eph << " m";
    EXPECT_LE(v_err, 3.0 * *epv) << "vertical error " << v_err << " m, epv " << *epv << " m";
    const auto it = pvt_by_tow.find(static_cast<std::uint32_t>(tow));
    if (it == pvt_by_tow.end()) continue;
    EXPECT_NEAR(*eph, it->second.h_acc_mm * 1e-3, 0.0015) << "eph is NAV-PVT hAcc";
    EXPECT_NEAR(*epv, it->second.v_acc_mm * 1e-3, 0.0015) << "epv is NAV-PVT vAcc";
    // gpsd also reads the GGA of the epoch (NMEA stays on), which has 1e-7 minutes.
    EXPECT_NEAR(*lat, it->second.lat_1e7deg * 1e-7, 2e-7);
    EXPECT_NEAR(*lon, it->second.lon_1e7deg * 1e-7, 2e-7);
  }
  EXPECT_GE(fixes, 8u);
  RecordProperty("first_fix_s", fmt::format("{:.2f}", first_fix_after_s.value_or(-1)));
  RecordProperty("max_h_err_over_eph", fmt::format("{:.2f}", max_h_ratio));
  RecordProperty("max_v_err_over_epv", fmt::format("{:.2f}", max_v_ratio));
  std::printf("gpsd u-blox: driver after %.2f s, first 3D fix after %.2f s, %zu fixes; max horizontal "
              "error %.2f m = %.2f eph, max vertical error %.2f m = %.2f epv\n",
              driver_after_s.value_or(-1), first_fix_after_s.value_or(-1), fixes, max_h_err,
              max_h_ratio, max_v_err, max_v_ratio);

  // SKY: the satellites, used flags, elevations, azimuths and C/N0 of navemu's NAV-SAT of the
  // same epoch (NMEA GSV/GSA of the epoch, which gpsd also reads, carry the same sky).
  std::size_t sky_matched = 0;
  for (const YAML::Node& s : skies) {
    const YAML::Node sats = s["satellites"];
    if (!sats || !sats.IsSequence() || sats.size() == 0) continue;
    const std::int64_t tow = iso_gps_tow_ms(str(s, "time"));
    const auto it = sat_by_tow.find(static_cast<std::uint32_t>(tow));
    if (it == sat_by_tow.end()) continue;
    SCOPED_TRACE(fmt::format("SKY {}", str(s, "time")));
    const ubx::NavSat& ns = it->second;
    ASSERT_EQ(sats.size(), ns.svs.size());
    // By gpsd's gnssid and svid (u-blox's numbering; the M8 tracks GPS, GLONASS and QZSS).
    std::map<std::pair<int, int>, YAML::Node> by_sat;
    for (std::size_t i = 0; i < sats.size(); ++i)
      if (const auto gnss = num(sats[i], "gnssid"), sv = num(sats[i], "svid"); gnss && sv)
        by_sat[{static_cast<int>(*gnss), static_cast<int>(*sv)}] = sats[i];
    for (const ubx::NavSatSv& sv : ns.svs) {
      SCOPED_TRACE(fmt::format("gnssId {} svId {}", sv.gnss_id, sv.sv_id));
      const auto gs = by_sat.find({sv.gnss_id, sv.sv_id});
      ASSERT_NE(gs, by_sat.end()) << "satellite of NAV-SAT missing in SKY";
      const YAML::Node& g_sat = gs->second;
      EXPECT_EQ(str(g_sat, "used"), (sv.flags & ubx::NavSatSv::kSvUsed) != 0 ? "true" : "false")
          << YAML::Dump(g_sat);
      EXPECT_EQ(num(g_sat, "el"), std::optional<double>(sv.elev_deg)) << YAML::Dump(g_sat);
      // gpsd keeps a NAV-SAT azimuth only below 359 (driver_ubx.c ubx_msg_nav_sat: "359 > az"),
      // though the message's range is 0-360: a satellite at 359 deg comes without one.
      EXPECT_EQ(num(g_sat, "az"), sv.azim_deg == 359 ? std::nullopt : std::optional<double>(sv.azim_deg))
          << YAML::Dump(g_sat);
      EXPECT_EQ(num(g_sat, "ss"), std::optional<double>(sv.cno_dbhz)) << YAML::Dump(g_sat);
    }
    ++sky_matched;
  }
  EXPECT_GE(sky_matched, 5u) << skies.size() << " SKY reports";

  // RAW: each RAW's pseudoranges are those of one of navemu's RXM-RAWX (gpsd prints 6 decimals).
  std::size_t raw_matched = 0;
  for (const YAML::Node& r : raws) {
    const YAML::Node data = r["rawdata"];
    if (!data || !data.IsSequence()) continue;
    std::map<std::pair<int, int>, double> pr;  // by (gnssid, svid)
    for (std::size_t i = 0; i < data.size(); ++i) {
      const auto gnss = num(data[i], "gnssid"), sv = num(data[i], "svid"), p = num(data[i], "pseudorange");
      EXPECT_TRUE(gnss && sv && p) << YAML::Dump(data[i]);
      if (gnss && sv && p) pr[{static_cast<int>(*gnss), static_cast<int>(*sv)}] = *p;
    }
    const bool found = std::any_of(rawx.begin(), rawx.end(), [&](const ubx::RxmRawx& x) {
      if (x.meas.size() != pr.size()) return false;
      for (const auto& m : x.meas) {
        const auto it = pr.find({m.gnss_id, m.sv_id});
        if (it == pr.end() || std::abs(it->second - m.pr_mes_m) > 1e-5) return false;
      }
      return true;
    });
    EXPECT_TRUE(found) << "a RAW report whose pseudoranges navemu did not send";
    raw_matched += found ? 1u : 0u;
  }
  EXPECT_GE(raw_matched, 5u) << raws.size() << " RAW reports";

  // SUBFRAME: every one gpsd decoded (after its parity check) is one navemu sent, and all the
  // satellites of a subframe epoch came through.
  std::size_t sub_matched = 0;
  std::map<long, std::size_t> per_tow;
  for (const YAML::Node& s : subframes) {
    const int sv = static_cast<int>(num(s, "tSV").value_or(-1));
    const long tow17 = static_cast<long>(num(s, "TOW17").value_or(-1));
    const int sf = static_cast<int>(num(s, "frame").value_or(-1));
    // gpsd 3.22 prints TOW17 as seconds: the HOW's 17-bit TOW count times 6.
    const bool found = tow17 % 6 == 0 && sfrbx.count({sv, tow17 / 6, sf}) > 0;
    EXPECT_TRUE(found) << "SUBFRAME tSV " << sv << " TOW17 " << tow17 << " frame " << sf;
    sub_matched += found ? 1u : 0u;
    ++per_tow[tow17];
  }
  std::size_t sats_per_epoch = 0;
  for (const auto& [tow, n] : per_tow) sats_per_epoch = std::max(sats_per_epoch, n);
  EXPECT_GE(sats_per_epoch, 6u) << "SUBFRAMEs of one subframe epoch";
  std::printf("gpsd u-blox: %zu/%zu SKY matched NAV-SAT, %zu/%zu RAW matched RXM-RAWX, %zu/%zu "
              "SUBFRAME matched RXM-SFRBX (%zu subframe epochs)\n",
              sky_matched, skies.size(), raw_matched, raws.size(), sub_matched, subframes.size(),
              per_tow.size());

  // gpsd's configuration burst (TESTING.md: CFG-PRT and 3-byte CFG-MSG, sent without waiting):
  // every CFG message is answered with exactly one ACK-ACK or ACK-NAK, in order (the capture
  // mirrors both directions), and MON-VER polls with MON-VER. The NAKed ones are listed.
  const std::vector<UbxFrame> from_gpsd = parse_frames(slurp(fs::path(capture.string() + ".in")));
  const std::vector<UbxFrame> to_gpsd = parse_frames(slurp(capture));
  std::vector<const UbxFrame*> cfg, answers;
  std::size_t mon_ver_polls = 0, mon_ver_answers = 0;
  for (const UbxFrame& f : from_gpsd) {
    if (f.id.cls == ubx::kClassCfg && f.id != ubx::kCfgRst) cfg.push_back(&f);
    mon_ver_polls += f.id == ubx::kMonVer && f.payload.empty() ? 1u : 0u;
  }
  for (const UbxFrame& f : to_gpsd) {
    if (f.id == ubx::kAckAck || f.id == ubx::kAckNak) answers.push_back(&f);
    mon_ver_answers += f.id == ubx::kMonVer ? 1u : 0u;
  }
  EXPECT_GE(cfg.size(), 10u) << "gpsd's configuration burst";
  EXPECT_EQ(answers.size(), cfg.size()) << "one ACK-ACK or ACK-NAK per CFG message";
  EXPECT_EQ(mon_ver_answers, mon_ver_polls);
  std::string naked;
  for (std::size_t i = 0; i < std::min(cfg.size(), answers.size()); ++i) {
    const UbxFrame& c = *cfg[i];
    const UbxFrame& a = *answers[i];
    EXPECT_TRUE(a.payload.size() == 2 && a.payload[0] == c.id.cls && a.payload[1] == c.id.id)
        << "answer " << i << " is not for CFG message " << i;
    if (a.id != ubx::kAckNak) continue;
    std::string hex;
    for (std::uint8_t b : c.payload) hex += fmt::format("{:02x}", b);
    naked += fmt::format(" {:02x}/{:02x}:{}", c.id.cls, c.id.id, hex);
  }
  std::printf("gpsd u-blox: %zu CFG messages from gpsd, %zu answered; NAKed (class/id:payload):%s\n",
              cfg.size(), answers.size(), naked.empty() ? " none" : naked.c_str());
}

// ---- ubxtool ---------------------------------------------------------------------------------

// One ubxtool run straight on the pty (`ubxtool -f PTY -w WAIT -P PROTVER ARGS`); its output.
// Its exit code is always 0 (TESTING.md): callers check the text.
std::string run_ubxtool(const std::string& ubxtool, const TempDir& dir, const fs::path& pty,
                        const std::string& protver, const std::vector<std::string>& args,
                        double wait_s = 1.0) {
  static int n = 0;
  const fs::path out = dir / fmt::format("ubxtool-{}.out", n++);
  std::vector<std::string> argv{"/usr/bin/python3", ubxtool, "-f", pty.string(), "-w",
                                fmt::format("{}", wait_s), "-P", protver};
  argv.insert(argv.end(), args.begin(), args.end());
  Child c(argv, out, out);
  const auto st = c.wait_exit(wait_s + 15.0);
  EXPECT_TRUE(st.has_value()) << "ubxtool did not exit";
  c.stop();
  return slurp(out);
}

// The output's messages as "UBX-XXX-YYY:" headers followed by their indented lines.
std::vector<std::string> ubxtool_messages(const std::string& text, const std::string& header) {
  std::vector<std::string> out;
  std::stringstream ss(text);
  std::string line, cur;
  bool in = false;
  while (std::getline(ss, line)) {
    if (!line.empty() && line[0] != ' ') {
      if (in) out.push_back(cur);
      in = line.rfind(header, 0) == 0;
      cur = line + "\n";
    } else if (in) {
      cur += line + "\n";
    }
  }
  if (in) out.push_back(cur);
  return out;
}

bool has_message(const std::string& text, const std::string& header, const std::string& content) {
  for (const std::string& m : ubxtool_messages(text, header))
    if (m.find(content) != std::string::npos) return true;
  return false;
}

// ubxtool on the shipped M8 profile (NMEA only at power-up): MON-VER gives the profile's
// versions; CFG-MSG,1,7,1 turns NAV-PVT on (ACK-ACK), CFG-MSG,1,7 reads its rate back (the
// 2-byte poll: reply then ACK); CFG-RATE,100,1 is acknowledged and NAV-PVT then comes at 10 Hz
// (100 +- 3 in 10 s, iTOW 100 ms apart); an invalid CFG-RATE (10 ms) and a CFG message the part
// does not have (CFG-DGNSS) get ACK-NAK and change nothing; a CFG-TP5 set is acknowledged.
TEST(UbxTool, M8PollsRateChangeAndRefusals) {
  NAVEMU_REQUIRE_TOOL(ubxtool, "ubxtool", "python3-gps 3.22 (gpsd-clients)");
  TempDir dir("ubxtool-m8");
  const fs::path link = dir / "gnss", log = dir / "gnss.ubx";
  NavemuRun nav(dir, "navemu",
                ubx_config(fs::path(NAVEMU_SOURCE_DIR) / "configs" / "gnss" / "ublox-m8.yaml", link, log), 90);
  ASSERT_TRUE(nav.wait_for_pty(link, 5.0)) << nav.diagnostics();
  const double t0 = mono_s();

  std::string out = run_ubxtool(ubxtool, dir, link, "18", {"-p", "MON-VER"});
  EXPECT_TRUE(has_message(out, "UBX-MON-VER:", "swVersion ROM CORE 3.01 (107888)")) << out;
  EXPECT_TRUE(has_message(out, "UBX-MON-VER:", "hwVersion 00080000")) << out;
  EXPECT_TRUE(has_message(out, "UBX-MON-VER:", "extension PROTVER=18.00")) << out;
  EXPECT_TRUE(has_message(out, "UBX-MON-VER:", "extension FWVER=SPG 3.01")) << out;
  EXPECT_EQ(out.find("WARNING:  protVer"), std::string::npos) << out;

  out = run_ubxtool(ubxtool, dir, link, "18", {"-p", "CFG-MSG,1,7,1"});
  EXPECT_TRUE(has_message(out, "UBX-ACK-ACK:", "ACK to Class x06 (CFG) ID x01 (MSG)")) << out;
  EXPECT_TRUE(has_message(out, "UBX-NAV-PVT:", "fixType 3")) << "NAV-PVT once a second now\n" << out;

  out = run_ubxtool(ubxtool, dir, link, "18", {"-p", "CFG-MSG,1,7"});
  EXPECT_TRUE(has_message(out, "UBX-CFG-MSG:", "Class x01 (NAV) ID x07 (PVT) Rates 0 1 0 0 0 0")) << out;
  EXPECT_TRUE(has_message(out, "UBX-ACK-ACK:", "ACK to Class x06 (CFG) ID x01 (MSG)")) << out;

  out = run_ubxtool(ubxtool, dir, link, "18", {"-p", "CFG-RATE,100,1"});
  EXPECT_TRUE(has_message(out, "UBX-ACK-ACK:", "ACK to Class x06 (CFG) ID x08 (RATE)")) << out;
  out = run_ubxtool(ubxtool, dir, link, "18", {"-p", "CFG-RATE"});
  EXPECT_TRUE(has_message(out, "UBX-CFG-RATE:", "measRate 100 navRate 1")) << out;

  // measRate 10 ms: above any u-blox 8 rate; CFG-DGNSS: a high-precision message the
  // standard-precision M8 does not have (UBX-13003221 32.10.5); CFG-TP5 with its 32 bytes: kept.
  out = run_ubxtool(ubxtool, dir, link, "18", {"-c", "0x06,0x08,0x0a,0x00,0x01,0x00,0x01,0x00"}, 0.5);
  EXPECT_TRUE(has_message(out, "UBX-ACK-NAK:", "NAK to Class x06 (CFG) ID x08 (RATE)")) << out;
  out = run_ubxtool(ubxtool, dir, link, "18", {"-c", "0x06,0x70,0x03,0x00,0x00,0x00"}, 0.5);
  EXPECT_TRUE(has_message(out, "UBX-ACK-NAK:", "NAK to Class x06 (CFG) ID x70 (DGNSS)")) << out;
  std::string tp5 = "0x06,0x31";
  for (int i = 0; i < 32; ++i) tp5 += ",0x00";
  out = run_ubxtool(ubxtool, dir, link, "18", {"-c", tp5}, 0.5);
  EXPECT_TRUE(has_message(out, "UBX-ACK-ACK:", "ACK to Class x06 (CFG) ID x31 (TP5)")) << out;
  out = run_ubxtool(ubxtool, dir, link, "18", {"-p", "CFG-RATE"}, 0.5);
  EXPECT_TRUE(has_message(out, "UBX-CFG-RATE:", "measRate 100 navRate 1")) << "the NAKed rate changed nothing\n" << out;
  const double ubxtool_s = mono_s() - t0;

  // NAV-PVT at 10 Hz: count the frames arriving in 10 s on the pty.
  PtyClient pty;
  ASSERT_TRUE(pty.open(link));
  pty.read_until(mono_s() + 1.0);  // settle: the first reads may hold a backlog
  const std::size_t before = pty.frames().size();
  const double w0 = mono_s();
  pty.read_until(w0 + 10.0);
  std::vector<std::uint32_t> tows;
  for (std::size_t i = before; i < pty.frames().size(); ++i) {
    ubx::NavPvt m;
    if (pty.frames()[i].id == ubx::kNavPvt && ubx::decode(pty.frames()[i].payload, m)) tows.push_back(m.i_tow_ms);
  }
  pty.close();
  nav.stop();
  std::size_t steps_100ms = 0;
  for (std::size_t i = 1; i < tows.size(); ++i) steps_100ms += tows[i] - tows[i - 1] == 100 ? 1u : 0u;
  EXPECT_NEAR(static_cast<double>(tows.size()), 100.0, 3.0) << "NAV-PVT frames in 10 s";
  EXPECT_EQ(steps_100ms + 1, tows.size()) << "consecutive NAV-PVT iTOW 100 ms apart";
  RecordProperty("nav_pvt_in_10s", static_cast<int>(tows.size()));
  std::printf("ubxtool M8: 8 ubxtool runs in %.1f s; NAV-PVT after CFG-RATE,100,1: %zu in 10 s "
              "(%zu steps of 100 ms)\n",
              ubxtool_s, tows.size(), steps_100ms);
}

// ubxtool on the ZED-F9P profile (protocol 27.11): MON-VER shows PROTVER=27.11; VALSET
// CFG-RATE-MEAS 200 (RAM) is acknowledged and VALGET reads 200 back; a key navemu does not
// model (CFG-TP-PERIOD_TP1) is stored and read back; a value out of range gets ACK-NAK
// (F9 HPG 1.13 description, UBX-CFG-VALSET); NAV-PVT switched on by
// CFG-MSGOUT-UBX_NAV_PVT_UART1 then comes at 5 Hz.
TEST(UbxTool, F9pValsetValget) {
  NAVEMU_REQUIRE_TOOL(ubxtool, "ubxtool", "python3-gps 3.22 (gpsd-clients)");
  TempDir dir("ubxtool-f9p");
  const fs::path link = dir / "gnss", log = dir / "gnss.ubx";
  NavemuRun nav(dir, "navemu",
                ubx_config(fs::path(NAVEMU_SOURCE_DIR) / "configs" / "gnss" / "ublox-f9p.yaml", link, log), 60);
  ASSERT_TRUE(nav.wait_for_pty(link, 5.0)) << nav.diagnostics();

  std::string out = run_ubxtool(ubxtool, dir, link, "27", {"-p", "MON-VER"});
  EXPECT_TRUE(has_message(out, "UBX-MON-VER:", "extension PROTVER=27.11")) << out;
  EXPECT_TRUE(has_message(out, "UBX-MON-VER:", "extension MOD=ZED-F9P")) << out;

  out = run_ubxtool(ubxtool, dir, link, "27", {"-z", "CFG-RATE-MEAS,200,1"});
  EXPECT_TRUE(has_message(out, "UBX-ACK-ACK:", "ACK to Class x06 (CFG) ID x8a (VALSET)")) << out;
  out = run_ubxtool(ubxtool, dir, link, "27", {"-g", "CFG-RATE-MEAS"});
  EXPECT_TRUE(has_message(out, "UBX-CFG-VALGET:", "item CFG-RATE-MEAS/0x30210001 val 200")) << out;
  EXPECT_TRUE(has_message(out, "UBX-ACK-ACK:", "ACK to Class x06 (CFG) ID x8b (VALGET)")) << out;

  // A key navemu does not model is stored and read back as on the part.
  out = run_ubxtool(ubxtool, dir, link, "27", {"-z", "CFG-TP-PERIOD_TP1,500000,1"}, 0.5);
  EXPECT_TRUE(has_message(out, "UBX-ACK-ACK:", "ACK to Class x06 (CFG) ID x8a (VALSET)")) << out;
  out = run_ubxtool(ubxtool, dir, link, "27", {"-g", "CFG-TP-PERIOD_TP1"});
  EXPECT_TRUE(has_message(out, "UBX-CFG-VALGET:", "item CFG-TP-PERIOD_TP1/0x40050002 val 500000")) << out;
  // A value below the item's range (CFG-RATE-MEAS: 25 ms at least) is refused.
  out = run_ubxtool(ubxtool, dir, link, "27", {"-z", "CFG-RATE-MEAS,10,1"}, 0.5);
  EXPECT_TRUE(has_message(out, "UBX-ACK-NAK:", "NAK to Class x06 (CFG) ID x8a (VALSET)")) << out;

  out = run_ubxtool(ubxtool, dir, link, "27", {"-z", "CFG-MSGOUT-UBX_NAV_PVT_UART1,1,1"}, 0.5);
  EXPECT_TRUE(has_message(out, "UBX-ACK-ACK:", "ACK to Class x06 (CFG) ID x8a (VALSET)")) << out;

  PtyClient pty;
  ASSERT_TRUE(pty.open(link));
  pty.read_until(mono_s() + 1.0);
  const std::size_t before = pty.frames().size();
  pty.read_until(mono_s() + 4.0);
  std::vector<std::uint32_t> tows;
  for (std::size_t i = before; i < pty.frames().size(); ++i) {
    ubx::NavPvt m;
    if (pty.frames()[i].id == ubx::kNavPvt && ubx::decode(pty.frames()[i].payload, m)) tows.push_back(m.i_tow_ms);
  }
  nav.stop();
  EXPECT_NEAR(static_cast<double>(tows.size()), 20.0, 2.0) << "NAV-PVT at 5 Hz over 4 s";
  for (std::size_t i = 1; i < tows.size(); ++i) EXPECT_EQ(tows[i] - tows[i - 1], 200u);
  std::printf("ubxtool F9P: NAV-PVT after CFG-RATE-MEAS 200: %zu in 4 s\n", tows.size());
}

// ubxtool -d GALILEO / -e GALILEO (CFG-GNSS, as ubxtool 3.22 sends it to every protocol
// version) on the F9P profile (five systems), at the ESBC station's hour with its real
// broadcast file: NAV-SAT loses the Galileo satellites and gets them back, GPS stays.
TEST(UbxTool, GalileoSwitchedOffAndOnChangesNavSat) {
  NAVEMU_REQUIRE_TOOL(ubxtool, "ubxtool", "python3-gps 3.22 (gpsd-clients)");
  NAVEMU_REQUIRE_SHARED();
  TempDir dir("ubxtool-gnss");
  const fs::path link = dir / "gnss", log = dir / "gnss.ubx";
  NavemuRun nav(dir, "navemu",
                fmt::format("scenario: {{status_interval_s: 1, start: '2020-06-25T00:10:00Z', nav: '{}'}}\n"
                            "truth: {{source: stationary, position: {{lat_deg: 55.4936, lon_deg: 8.4568, h_m: 60}}}}\n"
                            "gnss:\n  profile: ublox-f9p\n  outputs:\n    - {{type: pty, link: '{}'}}\n"
                            "    - {{type: file, path: '{}'}}\nimu: {{enabled: false}}\n",
                            shared_data("gnss/esbc_20200625/ESBC00DNK_R_20201770000_01D_MN.rnx").string(),
                            link.string(), log.string()),
                60);
  ASSERT_TRUE(nav.wait_for_pty(link, 5.0)) << nav.diagnostics();
  // Satellites per gnssId in the NAV-SAT ubxtool polls 2.5 s on (the 1 Hz receiver's
  // answer is its latest epoch; a system switched on is re-acquired 1 s after the switch).
  const auto nav_sat = [&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(2500));
    const std::vector<std::string> m = ubxtool_messages(run_ubxtool(ubxtool, dir, link, "27", {"-p", "NAV-SAT"}), "UBX-NAV-SAT:");
    std::map<int, int> n;
    if (m.empty()) return n;
    std::stringstream ss(m.back());
    for (std::string line; std::getline(ss, line);)
      if (const std::size_t k = line.find("gnssId "); k != std::string::npos) ++n[std::stoi(line.substr(k + 7))];
    return n;
  };
  std::map<int, int> before = nav_sat();
  EXPECT_GE(before[0], 4);
  EXPECT_GE(before[2], 4) << "Galileo tracked at the start";
  std::string out = run_ubxtool(ubxtool, dir, link, "27", {"-d", "GALILEO"});
  EXPECT_TRUE(has_message(out, "UBX-ACK-ACK:", "ACK to Class x06 (CFG) ID x3e (GNSS)")) << out;
  std::map<int, int> off = nav_sat();
  EXPECT_EQ(off[2], 0) << "no Galileo satellite after -d GALILEO";
  EXPECT_GE(off[0], before[0]) << "GPS stays (with the channels Galileo freed: 32 in all)";
  out = run_ubxtool(ubxtool, dir, link, "27", {"-e", "GALILEO"});
  EXPECT_TRUE(has_message(out, "UBX-ACK-ACK:", "ACK to Class x06 (CFG) ID x3e (GNSS)")) << out;
  std::map<int, int> on = nav_sat();
  EXPECT_EQ(on[2], before[2]);
  nav.stop();
  std::printf("ubxtool F9P NAV-SAT satellites GPS/Galileo: %d/%d, after -d GALILEO %d/%d, after -e GALILEO %d/%d\n",
              before[0], before[2], off[0], off[2], on[0], on[2]);
}

// ---- RTKLIB ----------------------------------------------------------------------------------

// The satellites tracked from the capture's start (its first RXM-RAWX): they have had the
// whole capture to send their ephemerides (one acquired later may not have had a frame's).
std::set<SatId> tracked_from_start(const std::vector<ubx::RxmRawx>& rawx) {
  std::set<SatId> out;
  if (rawx.empty()) return out;
  for (const auto& m : rawx.front().meas)
    if (const std::optional<SatId> sat = SatId::from_ubx(m.gnss_id, m.sv_id)) out.insert(*sat);
  return out;
}

// RTKLIB end to end: str2str captures what navemu sends on its pty for `capture_s` seconds
// (RTKLIB prefixes /dev/ to a serial path, TESTING.md) and convbin makes RINEX 3.04
// observation and navigation files of it; the frames captured are checked as RTKLIB needs
// them (TESTING.md): RAWX week != 0 and lock times never decreasing.
struct RtklibCapture {
  fs::path obs, nav;
  std::vector<UbxFrame> frames;
  std::vector<ubx::RxmRawx> rawx;
  std::vector<ubx::RxmSfrbx> sfrbx;
};
void capture_and_convert(const TempDir& dir, const fs::path& profile, WeekTow start, double capture_s, RtklibCapture& out) {
  const std::string str2str = test::find_program("str2str"), convbin = test::find_program("convbin");
  const fs::path link = dir / "gnss", log = dir / "gnss.ubx";
  NavemuRun nav(dir, "navemu", ubx_config(profile, link, log, fmt::format("{}:{:.0f}", start.week, start.tow_s)),
                capture_s + 30.0);
  ASSERT_TRUE(nav.wait_for_pty(link, 5.0)) << nav.diagnostics();
  const fs::path capture = dir / "capture.ubx";
  const std::string serial = "serial://.." + link.string() + ":115200#ubx";
  Child s2s({str2str, "-in", serial, "-out", "file://" + capture.string()}, dir / "str2str.out", dir / "str2str.err");
  sleep_s(capture_s);
  s2s.signal(SIGINT);
  const auto s2s_status = s2s.wait_exit(5.0);
  s2s.stop();
  nav.stop();
  EXPECT_TRUE(s2s_status.has_value()) << "str2str ignored SIGINT";
  ASSERT_TRUE(fs::exists(capture) && fs::file_size(capture) > 0) << slurp(dir / "str2str.err") << nav.diagnostics();

  ubx::Parser::Counters pc;
  out.frames = parse_frames(slurp(capture), &pc);
  EXPECT_EQ(pc.checksum_errors, 0u);
  out.rawx = decode_all<ubx::RxmRawx>(out.frames, ubx::kRxmRawx);
  out.sfrbx = decode_all<ubx::RxmSfrbx>(out.frames, ubx::kRxmSfrbx);
  EXPECT_GE(out.rawx.size(), static_cast<std::size_t>(capture_s - 5.0));
  std::map<std::pair<int, int>, std::uint16_t> lock;  // by (gnssId, svId)
  for (const auto& r : out.rawx) {
    EXPECT_NE(r.week, 0);
    for (const auto& m : r.meas) {
      const std::pair<int, int> sat{m.gnss_id, m.sv_id};
      EXPECT_GE(m.locktime_ms, lock[sat]) << "lock time of gnssId " << sat.first << " svId " << sat.second << " went back";
      lock[sat] = m.locktime_ms;
    }
  }
  out.obs = dir / "out.obs";
  out.nav = dir / "out.nav";
  Child cb({convbin, "-r", "ubx", "-v", "3.04", "-od", "-os", "-o", out.obs.string(), "-n", out.nav.string(), capture.string()},
           dir / "convbin.out", dir / "convbin.err");
  const auto cb_status = cb.wait_exit(60.0);
  ASSERT_TRUE(cb_status && WIFEXITED(*cb_status) && WEXITSTATUS(*cb_status) == 0)
      << describe_status(cb_status) << tail(slurp(dir / "convbin.err"));
  ASSERT_TRUE(fs::exists(out.obs) && fs::exists(out.nav));
}

// rnx2rtkp's single-point solutions (-p 0, ECEF output) of the capture's files with the
// options of `conf_text`. rnx2rtkp's own defaults apply no atmospheric model: a single-point
// user turns on the broadcast Klobuchar model and Saastamoinen (pos1-ionoopt, pos1-tropopt).
// The systems are chosen with pos1-navsys (1 GPS, 4 GLONASS, 8 Galileo, 32 BeiDou): its -sys
// option adds to the configured ones rather than replacing them.
std::vector<RtklibFix> rtklib_spp(const TempDir& dir, const RtklibCapture& c, const std::string& name,
                                  const std::string& conf_text) {
  const fs::path conf = dir / (name + ".conf"), pos = dir / (name + ".pos");
  std::ofstream(conf) << conf_text;
  std::vector<std::string> argv{test::find_program("rnx2rtkp"), "-k", conf.string(), "-p", "0",
                                "-e", "-o", pos.string(), c.obs.string(), c.nav.string()};
  Child rk(argv, dir / (name + ".out"), dir / (name + ".err"));
  const auto rk_status = rk.wait_exit(60.0);
  EXPECT_TRUE(rk_status && WIFEXITED(*rk_status)) << describe_status(rk_status);
  return read_rtklib_ecef_pos(pos);
}

// 3D, horizontal and up errors of RTKLIB's solutions against the emulator's fixed site.
struct FixErrors {
  std::vector<double> d3, h, up;
};
FixErrors errors_of(const std::vector<RtklibFix>& fixes) {
  FixErrors e;
  const Vec3 truth = ecef_from_geodetic(kUbxSite);
  for (const RtklibFix& f : fixes) {
    e.d3.push_back((f.p_ecef_m - truth).norm());
    const Vec3 enu = enu_from_ecef(f.p_ecef_m, kUbxSite);
    e.h.push_back(std::hypot(enu.x(), enu.y()));
    e.up.push_back(enu.z());
  }
  return e;
}

const std::string kRtklibSppOptions = "pos1-ionoopt       =brdc\npos1-tropopt       =saas\n";
const std::string kRtklibGpsOnly = "pos1-navsys        =1\n";

// The M8 (GPS, GLONASS, QZSS): RXM-RAWX + RXM-SFRBX (1 Hz) through str2str and convbin, and
// rnx2rtkp's single-point solutions (GPS, broadcast ionosphere and Saastamoinen
// troposphere) must lie within 5 m (mean 3D) of the truth; the broadcast
// ephemerides RTKLIB rebuilt from the subframes are navemu's (IODE, toe, sqrt(A), e, i0 to
// their LNAV quantisation).
//
// Capture length: NAVEMU_UBX_CAPTURE_S seconds (default 45; 120 is the full acceptance run).
// A 30 s LNAV frame carries subframes 1-3 once, so a capture of arbitrary phase needs up to
// 48 s for a complete ephemeris. The scenario's start is chosen instead: 10 s before a 30 s
// frame boundary, so subframe 1 ends 16 s and subframe 3 28 s
// into the run, and RTKLIB has every tracked satellite's ephemeris within the first 30 s;
// the remaining epochs give the mean. The 16 s leave str2str time to open the pty on a loaded
// machine: output nobody reads yet is flushed as stale, so a subframe sent before it attaches
// is lost to the capture. rnx2rtkp solves every epoch of the observation file
// with the navigation file, so the early epochs count too.
TEST(UbxRtklib, CaptureConvertAndSinglePointSolution) {
  NAVEMU_REQUIRE_TOOL(str2str, "str2str", "rtklib");
  NAVEMU_REQUIRE_TOOL(convbin, "convbin", "rtklib");
  NAVEMU_REQUIRE_TOOL(rnx2rtkp, "rnx2rtkp", "rtklib");
  const char* env = std::getenv("NAVEMU_UBX_CAPTURE_S");
  const double capture_s = env != nullptr ? std::max(30.0, std::atof(env)) : 45.0;

  TempDir dir("ubx-rtklib");
  const fs::path profile = write_profile(dir, "ublox-m8", "NAV-PVT: 1, RXM-RAWX: 1, RXM-SFRBX: 1");
  // A fixed scenario date (the paper's, 2010-11-17 about 13:00 UTC) rather than now, so that
  // the sky and with it RTKLIB's error are the same on every run: 10 s before a frame boundary.
  const WeekTow wt{1610, 306020.0};
  const GpsTime start = from_week_tow(wt.week, wt.tow_s);
  RtklibCapture cap;
  capture_and_convert(dir, profile, wt, capture_s, cap);
  if (HasFatalFailure()) return;
  const auto& rawx = cap.rawx;
  const auto& sfrbx = cap.sfrbx;
  // LNAV subframes of GPS (gnssId 0) and QZSS (5), by satellite, with 10 words passing the
  // parity check; the GLONASS strings are counted.
  std::map<SatId, std::vector<lnav::LnavSubframe>> subs;
  std::size_t glonass_strings = 0;
  for (const auto& s : sfrbx) {
    const std::optional<SatId> sat = SatId::from_ubx(s.gnss_id, s.sv_id);
    ASSERT_TRUE(sat.has_value());
    if (sat->system() == GnssSystem::kGlonass) {
      ++glonass_strings;
      continue;
    }
    ASSERT_TRUE(sat->system() == GnssSystem::kGps || sat->system() == GnssSystem::kQzss);
    ASSERT_EQ(s.words.size(), 10u);
    lnav::LnavSubframe w{};
    std::copy(s.words.begin(), s.words.end(), w.begin());
    EXPECT_TRUE(lnav::lnav_parity_ok(w));
    subs[*sat].push_back(w);
  }
  EXPECT_GT(glonass_strings, 0u);

  // Without the atmospheric models the ionosphere and troposphere go straight into the
  // solution (mean up error +13.6 m measured on such a capture): that run is made too and
  // reported.
  const std::vector<RtklibFix> fixes = rtklib_spp(dir, cap, "spp", kRtklibSppOptions + kRtklibGpsOnly);
  const std::vector<RtklibFix> plain = rtklib_spp(dir, cap, "no-atmosphere", kRtklibGpsOnly);
  ASSERT_GE(fixes.size(), static_cast<std::size_t>(capture_s - 10.0)) << "solutions of " << cap.obs;
  const FixErrors err = errors_of(fixes);
  const double mean3d = mean(err.d3);
  RecordProperty("rtklib_epochs", static_cast<int>(fixes.size()));
  RecordProperty("rtklib_mean_3d_error_m", fmt::format("{:.2f}", mean3d));
  std::printf("RTKLIB: %.0f s capture, %zu RAWX, %zu SFRBX, %zu solutions: mean 3D error %.2f m "
              "(mean horizontal %.2f m, mean up %+.2f m, max 3D %.2f m); without atmospheric "
              "models %.2f m\n",
              capture_s, rawx.size(), sfrbx.size(), fixes.size(), mean3d, mean(err.h), mean(err.up),
              *std::max_element(err.d3.begin(), err.d3.end()), mean(errors_of(plain).d3));
  EXPECT_LE(mean3d, 5.0) << "mean 3D error of rnx2rtkp's single-point solutions vs the truth";

  // The ephemerides in the navigation file are navemu's: the built-in constellation at the
  // scenario's start (IODE and toe identify the record; sqrt(A), e, i0 to their LNAV LSBs), for
  // GPS and QZSS, whose LNAV subframes navemu sends.
  const NavData rinex = read_rinex_nav(cap.nav);
  const NavData truth_nav = nominal_constellation(start, system_bit(GnssSystem::kGps) | system_bit(GnssSystem::kQzss));
  std::set<SatId> sats_in_file;
  for (const auto* records : {&rinex.gps, &rinex.qzss})
    for (const GpsEphemeris& r : *records) {
      SCOPED_TRACE(fmt::format("{} IODE {}", r.sat.rinex(), r.iode));
      sats_in_file.insert(r.sat);
      const GpsEphemeris* sent = nullptr;
      for (const auto* made : {&truth_nav.gps, &truth_nav.qzss})
        for (const GpsEphemeris& e : *made)
          if (e.sat == r.sat && (e.iode & 0xFF) == r.iode && std::abs(seconds_between(e.toe, r.toe)) < 16.0) sent = &e;
      ASSERT_NE(sent, nullptr) << "no record of the built-in constellation has this IODE and toe";
      EXPECT_NEAR(r.sqrt_a_sqrtm, sent->sqrt_a_sqrtm, std::ldexp(1.0, -19));
      EXPECT_NEAR(r.e, sent->e, std::ldexp(1.0, -33));
      EXPECT_NEAR(r.i0_rad, sent->i0_rad, std::ldexp(lnav::kGpsPi, -31) * 1.01);
      EXPECT_NEAR(r.omega0_rad, std::remainder(sent->omega0_rad, 2 * lnav::kGpsPi), std::ldexp(lnav::kGpsPi, -31) * 1.01);
      // And the subframes in the capture decode to the same record.
      const auto& w = subs[r.sat];
      for (std::size_t i = 0; i + 2 < w.size(); ++i) {
        if (lnav::decode_tlm_how(w[i]).subframe_id != 1) continue;
        const auto l = lnav::decode_ephemeris(w[i], w[i + 1], w[i + 2], wt.week);
        ASSERT_TRUE(l.has_value());
        EXPECT_EQ(l->iode, r.iode);
        EXPECT_NEAR(l->toe_s, to_week_tow(r.toe).tow_s, 1e-6);
        break;
      }
    }
  // Every satellite tracked from the start has its ephemeris in the file, GLONASS's rebuilt
  // from the strings.
  const std::set<SatId> tracked = tracked_from_start(rawx);
  for (const GlonassEphemeris& r : rinex.glonass) sats_in_file.insert(r.sat);
  for (SatId sat : tracked) EXPECT_TRUE(sats_in_file.count(sat)) << "no ephemeris for tracked " << sat.rinex();
  std::printf("RTKLIB: %zu GPS, %zu QZSS and %zu GLONASS ephemerides in the navigation file for %zu "
              "satellites tracked from the start (%zu GLONASS strings)\n",
              rinex.gps.size(), rinex.qzss.size(), rinex.glonass.size(), tracked.size(), glonass_strings);
}

// The F9P with GPS, GLONASS, Galileo and BeiDou (its default configuration; no QZSS above the
// site in 2010): RXM-SFRBX of every system through str2str and convbin (Galileo I/NAV pages
// with their CRC, GLONASS strings with their Hamming code, BeiDou D1/D2 subframes with their
// BCH codes), a RINEX 3 mixed navigation file whose records are navemu's ephemerides to the
// messages' quantisation, and rnx2rtkp's single-point solutions with all four systems within
// 3 m (mean 3D) of the truth (the GPS-only ones are reported beside them).
//
// The start (tow 306018, 28 s into a 30 s period) puts the first frame starts after str2str
// has attached (16 s, as above) at +16 s (BDT's), +17 s (GLONASS's), +32 s (GPS's) and +33 s
// (Galileo's sub-frame): the last ephemeris set, Galileo's word 5, is complete 59 s into the
// run. Capture length NAVEMU_UBX_CAPTURE_S seconds if above 65, else 65.
TEST(UbxRtklib, FourSystemsCaptureConvertAndSinglePointSolution) {
  NAVEMU_REQUIRE_TOOL(str2str, "str2str", "rtklib");
  NAVEMU_REQUIRE_TOOL(convbin, "convbin", "rtklib");
  NAVEMU_REQUIRE_TOOL(rnx2rtkp, "rnx2rtkp", "rtklib");
  const char* env = std::getenv("NAVEMU_UBX_CAPTURE_S");
  const double capture_s = std::max(65.0, env != nullptr ? std::atof(env) : 0.0);

  TempDir dir("ubx-rtklib-gnss");
  const fs::path profile = write_profile(dir, "ublox-f9p", "NAV-PVT: 1, RXM-RAWX: 1, RXM-SFRBX: 1");
  const WeekTow wt{1610, 306018.0};
  const GpsTime start = from_week_tow(wt.week, wt.tow_s);
  RtklibCapture cap;
  capture_and_convert(dir, profile, wt, capture_s, cap);
  if (HasFatalFailure()) return;

  // Each message passes its own check.
  std::map<GnssSystem, std::size_t> units;
  for (const auto& m : cap.sfrbx) {
    const std::optional<SatId> sat = SatId::from_ubx(m.gnss_id, m.sv_id);
    ASSERT_TRUE(sat.has_value());
    ++units[sat->system()];
    const std::span<const std::uint32_t> w(m.words);
    switch (sat->system()) {
      case GnssSystem::kGps: {
        ASSERT_EQ(w.size(), 10u);
        lnav::LnavSubframe sf{};
        std::copy(w.begin(), w.end(), sf.begin());
        EXPECT_TRUE(lnav::lnav_parity_ok(sf)) << sat->rinex();
        break;
      }
      case GnssSystem::kGalileo: EXPECT_TRUE(inav::decode_inav_page(w).has_value()) << sat->rinex(); break;
      case GnssSystem::kGlonass: {
        ASSERT_EQ(w.size(), 4u);
        EXPECT_TRUE(gnav::glonass_hamming_ok({w[0], w[1], w[2], w[3]})) << sat->rinex();
        break;
      }
      case GnssSystem::kBeidou: {
        const auto sf = bdnav::subframe_from_words(w);
        ASSERT_TRUE(sf.has_value());
        EXPECT_TRUE(bdnav::bch_ok(*sf)) << sat->rinex();
        break;
      }
      default: ADD_FAILURE() << "unexpected " << sat->rinex();
    }
  }

  // The navigation file's records are the built-in constellation's (the record of the same
  // satellite and reference time), to the LSBs of each message.
  const NavData rinex = read_rinex_nav(cap.nav);
  const NavData made = nominal_constellation(start, system_bit(GnssSystem::kGps) | system_bit(GnssSystem::kGlonass) |
                                                        system_bit(GnssSystem::kGalileo) | system_bit(GnssSystem::kBeidou));
  std::set<SatId> in_file;
  const double semicircle_lsb_31 = std::ldexp(lnav::kGpsPi, -31) * 1.01;
  const auto same_kepler = [&](const KeplerEphemeris& r, const KeplerEphemeris& e) {
    EXPECT_NEAR(r.sqrt_a_sqrtm, e.sqrt_a_sqrtm, std::ldexp(1.0, -19));
    EXPECT_NEAR(r.e, e.e, std::ldexp(1.0, -33));
    EXPECT_NEAR(r.i0_rad, e.i0_rad, semicircle_lsb_31);
    EXPECT_NEAR(r.m0_rad, std::remainder(e.m0_rad, 2 * lnav::kGpsPi), semicircle_lsb_31);
  };
  const auto find_kepler = [](const auto& records, const KeplerEphemeris& r) {
    for (const auto& e : records)
      if (e.sat == r.sat && std::abs(seconds_between(e.toe, r.toe)) < 16.0) return &e;
    return static_cast<decltype(&records.front())>(nullptr);
  };
  const auto check_kepler = [&](const auto& records, const auto& made_records, auto&& same_issue) {
    for (const auto& r : records) {
      in_file.insert(r.sat);
      const auto* e = find_kepler(made_records, r);
      ASSERT_NE(e, nullptr) << r.sat.rinex() << " record not made by navemu";
      same_issue(r, *e);
      same_kepler(r, *e);
    }
  };
  check_kepler(rinex.gps, made.gps, [](const GpsEphemeris& r, const GpsEphemeris& e) { EXPECT_EQ(e.iode & 0xFF, r.iode); });
  check_kepler(rinex.galileo, made.galileo,
               [](const GalileoEphemeris& r, const GalileoEphemeris& e) { EXPECT_EQ(e.iod_nav & 0x3FF, r.iod_nav); });
  check_kepler(rinex.beidou, made.beidou, [](const BeidouEphemeris&, const BeidouEphemeris&) {});
  for (const GlonassEphemeris& r : rinex.glonass) {
    in_file.insert(r.sat);
    const GlonassEphemeris* e = nullptr;
    for (const GlonassEphemeris& m : made.glonass)
      if (m.sat == r.sat && m.tb == r.tb) e = &m;
    ASSERT_NE(e, nullptr) << r.sat.rinex() << " record not made by navemu";
    EXPECT_LE((r.p_pz90_m - e->p_pz90_m).cwiseAbs().maxCoeff(), std::ldexp(1000.0, -11));  // 2^-11 km
    EXPECT_LE((r.v_pz90_mps - e->v_pz90_mps).cwiseAbs().maxCoeff(), std::ldexp(1000.0, -20));
    EXPECT_EQ(r.frequency_channel, e->frequency_channel);
  }
  const std::set<SatId> tracked = tracked_from_start(cap.rawx);
  for (SatId sat : tracked) EXPECT_TRUE(in_file.count(sat)) << "no ephemeris for tracked " << sat.rinex();

  const std::vector<RtklibFix> all = rtklib_spp(dir, cap, "grec", kRtklibSppOptions + "pos1-navsys        =45\n");
  const std::vector<RtklibFix> gps = rtklib_spp(dir, cap, "g", kRtklibSppOptions + kRtklibGpsOnly);
  ASSERT_GE(all.size(), static_cast<std::size_t>(capture_s - 10.0)) << "solutions of " << cap.obs;
  const FixErrors err = errors_of(all);
  std::printf("RTKLIB four systems: %.0f s capture, RXM-SFRBX GPS %zu, GLONASS %zu, Galileo %zu, BeiDou %zu; "
              "records GPS %zu, GLONASS %zu, Galileo %zu, BeiDou %zu for %zu satellites tracked from the start; %zu solutions: "
              "mean 3D error %.2f m (horizontal %.2f m, up %+.2f m, max 3D %.2f m); GPS alone %.2f m\n",
              capture_s, units[GnssSystem::kGps], units[GnssSystem::kGlonass], units[GnssSystem::kGalileo],
              units[GnssSystem::kBeidou], rinex.gps.size(), rinex.glonass.size(), rinex.galileo.size(),
              rinex.beidou.size(), tracked.size(), all.size(), mean(err.d3), mean(err.h), mean(err.up),
              *std::max_element(err.d3.begin(), err.d3.end()), mean(errors_of(gps).d3));
  RecordProperty("rtklib_four_systems_mean_3d_error_m", fmt::format("{:.2f}", mean(err.d3)));
  EXPECT_LE(mean(err.d3), 3.0) << "mean 3D error of rnx2rtkp's four-system single-point solutions vs the truth";
}

// RTKLIB's stock u-blox command files (../shared/clients/rtklib-ubx-cmd, RTKLIB 2.4.3's
// data/ubx_m8t_*.cmd) sent by `str2str -c FILE` to the shipped M8 profile (no UBX at power-up).
// Each file's `!UBX CFG-MSG 2 21 0 0 0 1 0 0` / `2 19 ...` sets RXM-RAWX and RXM-SFRBX to 1 per
// solution on the fourth port slot only, USB (UBX-CFG-MSG rates: DDC, UART1, UART2, USB, SPI,
// reserved; u-blox 8 interface description UBX-13003221, 32.10.18.3), and the 5 Hz files send
// `CFG-RATE 200 1 1`. So on a pty configured `port: usb` (a receiver on /dev/ttyACM0) RAWX
// comes at the file's rate, every epoch, with SFRBX subframes; on UART1 the part sends neither
// (their UART1 rate stays 0). Counts are taken over the capture's own receiver times (RAWX
// rcvTow), so a loaded machine does not change them.
struct RtklibCmdCase {
  const char* file;
  double rate_hz;
};

class UbxRtklibCmd : public ::testing::TestWithParam<RtklibCmdCase> {};

TEST_P(UbxRtklibCmd, UsbPortGivesRawAtTheRequestedRateUart1GivesNone) {
  NAVEMU_REQUIRE_TOOL(str2str, "str2str", "rtklib");
  const fs::path cmd = fs::path(NAVEMU_SOURCE_DIR) / ".." / "shared" / "clients" / "rtklib-ubx-cmd" / GetParam().file;
  if (!fs::exists(cmd)) GTEST_SKIP() << cmd << " not found (../shared/clients/rtklib-ubx-cmd)";
  const double rate_hz = GetParam().rate_hz;
  const double capture_s = 12.0;
  for (const std::string port : {"usb", "uart1"}) {
    SCOPED_TRACE("port: " + port);
    TempDir dir("ubx-rtklib-cmd-" + port);
    const fs::path link = dir / "gnss", log = dir / "gnss.ubx";
    NavemuRun nav(dir, "navemu",
                  ubx_config(fs::path(NAVEMU_SOURCE_DIR) / "configs" / "gnss" / "ublox-m8.yaml", link,
                             log, "now", {}, port),
                  capture_s + 20.0);
    ASSERT_TRUE(nav.wait_for_pty(link, 5.0)) << nav.diagnostics();
    const fs::path capture = dir / "capture.ubx";
    Child s2s({str2str, "-in", "serial://.." + link.string() + ":115200#ubx", "-c", cmd.string(), "-out",
               "file://" + capture.string()},
              dir / "str2str.out", dir / "str2str.err");
    sleep_s(capture_s);
    s2s.signal(SIGINT);
    const auto s2s_status = s2s.wait_exit(5.0);
    s2s.stop();
    nav.stop();
    EXPECT_TRUE(s2s_status.has_value()) << "str2str ignored SIGINT";

    const std::vector<UbxFrame> frames = fs::exists(capture) ? parse_frames(slurp(capture)) : std::vector<UbxFrame>{};
    const auto rawx = decode_all<ubx::RxmRawx>(frames, ubx::kRxmRawx);
    const auto sfrbx = decode_all<ubx::RxmSfrbx>(frames, ubx::kRxmSfrbx);
    std::size_t acks = 0, naks = 0;
    for (const UbxFrame& f : frames) {
      acks += f.id == ubx::kAckAck ? 1u : 0u;
      naks += f.id == ubx::kAckNak ? 1u : 0u;
    }
    if (port == "uart1") {
      EXPECT_EQ(rawx.size(), 0u) << "the file sets RAWX on USB only";
      EXPECT_EQ(sfrbx.size(), 0u) << "the file sets SFRBX on USB only";
      std::printf("RTKLIB %s on UART1: %zu RAWX, %zu SFRBX, %zu ACK, %zu NAK\n", GetParam().file,
                  rawx.size(), sfrbx.size(), acks, naks);
      continue;
    }
    ASSERT_GE(rawx.size(), 2u) << tail(slurp(dir / "str2str.err")) << nav.diagnostics();
    // RAWX every epoch at the requested interval, from the first to the last one captured.
    const double step_s = 1.0 / rate_hz;
    std::size_t at_rate = 0;
    for (std::size_t i = 1; i < rawx.size(); ++i)
      at_rate += std::abs(rawx[i].rcv_tow_s - rawx[i - 1].rcv_tow_s - step_s) < 1e-3 ? 1u : 0u;
    const double span_s = rawx.back().rcv_tow_s - rawx.front().rcv_tow_s;
    const double measured_hz = static_cast<double>(rawx.size() - 1) / span_s;
    EXPECT_EQ(at_rate + 1, rawx.size()) << "consecutive RAWX " << step_s << " s apart";
    EXPECT_NEAR(measured_hz, rate_hz, 0.01 * rate_hz);
    // Seconds of RAWX: the capture less str2str's start-up and the rate change (loose bound).
    EXPECT_GE(span_s, capture_s - 6.0);
    // Subframes every 6 s per tracked satellite: at least one full 6 s period was captured.
    EXPECT_GE(sfrbx.size(), 4u) << "RXM-SFRBX";
    std::printf("RTKLIB %s on USB: %zu RAWX over %.1f s (%.3f Hz, %zu of %zu steps of %.0f ms), %zu SFRBX, "
                "%zu ACK, %zu NAK\n",
                GetParam().file, rawx.size(), span_s, measured_hz, at_rate, rawx.size() - 1, step_s * 1e3,
                sfrbx.size(), acks, naks);
  }
}

INSTANTIATE_TEST_SUITE_P(StockCommandFiles, UbxRtklibCmd,
                         ::testing::Values(RtklibCmdCase{"ubx_m8t_glo_raw_5hz.cmd", 5.0},
                                           RtklibCmdCase{"ubx_m8t_bds_raw_1hz.cmd", 1.0}),
                         [](const ::testing::TestParamInfo<RtklibCmdCase>& p) {
                           const std::string n = p.param.file;
                           return n.substr(0, n.find('.'));
                         });

// ---- faults on the wire ----------------------------------------------------------------------

// A client writing garbage into the pty: random bytes, gpsd-style probes, truncated frames,
// wrong checksums, lengths above the receiver's buffer (0xFFFF) and plausible lengths never
// completed. navemu must not crash, its output must keep coming (NMEA and UBX every epoch), no
// configuration may change (every CFG in the garbage is corrupt), and a MON-VER poll afterwards
// is answered. A frame header with a plausible length holds the bytes that follow until that
// many arrived (as on a real receiver), so 4200 filler bytes precede the poll.
TEST(UbxFaults, GarbageFromTheClientNeverStopsTheOutput) {
  TempDir dir("ubx-faults");
  const fs::path link = dir / "gnss", log = dir / "gnss.ubx";
  const fs::path profile = write_profile(dir, "ublox-m8", "NAV-PVT: 1");
  NavemuRun nav(dir, "navemu", ubx_config(profile, link, log), 60);
  ASSERT_TRUE(nav.wait_for_pty(link, 5.0)) << nav.diagnostics();
  PtyClient pty;
  ASSERT_TRUE(pty.open(link));
  pty.read_until(mono_s() + 2.0);

  std::uint32_t x = 987654321;
  const auto rnd = [&] {
    x = x * 1664525u + 1013904223u;
    return static_cast<std::uint8_t>(x >> 24);
  };
  std::vector<std::uint8_t> good_rate;
  ubx::append(ubx::CfgRate{100, 1, ubx::CfgRate::kTimeRefGps}, good_rate);
  ubx::CfgPrt prt;
  prt.port_id = ubx::kPortUart1;
  prt.mode = ubx::CfgPrt::kMode8N1;
  prt.baud_rate = 115200;
  prt.in_proto_mask = ubx::kProtoUbx;
  prt.out_proto_mask = ubx::kProtoUbx;  // would stop NMEA if it were accepted
  std::vector<std::uint8_t> good_prt;
  ubx::append(prt, good_prt);

  const double g0 = mono_s();
  std::size_t garbage_bytes = 0;
  int bursts = 0;
  bool writes_ok = true;
  while (mono_s() < g0 + 6.0) {
    std::vector<std::uint8_t> b;
    for (int i = 0; i < 300; ++i) {
      const std::uint8_t c = rnd();
      b.push_back(c == ubx::kSync1 ? 0x00 : c);
    }
    const std::string probe = "$PASHQ,RID*28\r\n@F0.3=1*67\r\n$PMTK605*31\r\n";
    b.insert(b.end(), probe.begin(), probe.end());
    switch (bursts % 5) {
      case 0:  // truncated CFG-RATE
        b.insert(b.end(), good_rate.begin(), good_rate.begin() + 9);
        break;
      case 1: {  // wrong checksums
        std::vector<std::uint8_t> r = good_rate, p = good_prt;
        r[r.size() - 2] ^= 0x55;
        p.back() ^= 0x01;
        b.insert(b.end(), r.begin(), r.end());
        b.insert(b.end(), p.begin(), p.end());
        break;
      }
      case 2:  // lengths above the buffer
        for (const std::uint8_t hi : std::array<std::uint8_t, 3>{0xFF, 0x80, 0x11})
          b.insert(b.end(), {ubx::kSync1, ubx::kSync2, 0x06, 0x00, 0xFF, hi, 0x01, 0x02, 0x03});
        break;
      case 3:  // a plausible length (3000) never completed before the junk that follows
        b.insert(b.end(), {ubx::kSync1, ubx::kSync2, 0x06, 0x00, 0xB8, 0x0B, 0x01});
        break;
      default:  // a complete frame whose payload is cut: length 20, 10 bytes, then a new sync
        b.insert(b.end(), good_prt.begin(), good_prt.begin() + 16);
        b.insert(b.end(), good_rate.begin(), good_rate.begin() + 3);
        break;
    }
    writes_ok = writes_ok && pty.write_all(b, 2.0);
    garbage_bytes += b.size();
    ++bursts;
    pty.read_until(mono_s() + 0.05);
  }
  const double g1 = mono_s();
  EXPECT_TRUE(writes_ok) << "navemu stopped reading its port (writes blocked for 2 s)";
  EXPECT_TRUE(nav.child().running()) << nav.diagnostics();

  // Filler, then the poll; the answer must come within 1 s.
  const std::vector<std::uint8_t> filler(4200, 'z');
  ASSERT_TRUE(pty.write_all(filler));
  const std::size_t frames_before_poll = pty.frames().size();
  const std::vector<std::uint8_t> poll = ubx_poll(ubx::kMonVer);
  const double p0 = mono_s();
  ASSERT_TRUE(pty.write_all(poll));
  std::optional<double> answered_s;
  pty.read_until(p0 + 2.0, [&] {
    for (std::size_t i = frames_before_poll; i < pty.frames().size(); ++i)
      if (pty.frames()[i].id == ubx::kMonVer) {
        answered_s = pty.frames()[i].t_mono - p0;
        return true;
      }
    return false;
  });
  pty.read_until(mono_s() + 2.0);
  const double end_t = mono_s();
  pty.close();
  nav.stop_expecting_exit_0();

  ASSERT_TRUE(answered_s.has_value()) << "MON-VER poll after the garbage not answered" << nav.diagnostics();
  EXPECT_LT(*answered_s, 1.0);

  // Output never stopped: NAV-PVT and RMC once a second throughout, NAV-PVT epochs consecutive
  // (1 s: the corrupt CFG-RATE did not apply; NMEA on: the corrupt CFG-PRT did not apply).
  std::vector<double> pvt_t;
  std::vector<std::uint32_t> tows;
  for (const UbxFrame& f : pty.frames()) {
    ubx::NavPvt m;
    if (f.id == ubx::kNavPvt && ubx::decode(f.payload, m)) {
      pvt_t.push_back(f.t_mono);
      tows.push_back(m.i_tow_ms);
    }
  }
  const std::vector<double> rmc_t = pty.nmea_times("RMC");
  const auto max_gap = [&](const std::vector<double>& t) {
    double g = 0;
    for (std::size_t i = 1; i < t.size(); ++i) g = std::max(g, t[i] - t[i - 1]);
    if (!t.empty()) g = std::max(g, end_t - t.back());
    return g;
  };
  const auto count_in = [](const std::vector<double>& t, double a, double b) {
    return std::count_if(t.begin(), t.end(), [&](double v) { return v >= a && v < b; });
  };
  EXPECT_LE(max_gap(pvt_t), 1.5) << "NAV-PVT stopped for a while";
  EXPECT_LE(max_gap(rmc_t), 1.5) << "NMEA stopped for a while";
  EXPECT_GE(count_in(pvt_t, g0, g1), 5);
  EXPECT_GE(count_in(rmc_t, g0, g1), 5);
  for (std::size_t i = 1; i < tows.size(); ++i) EXPECT_EQ(tows[i] - tows[i - 1], 1000u);
  const std::vector<UbxFrame> acks = [&] {
    std::vector<UbxFrame> a;
    for (const UbxFrame& f : pty.frames())
      if (f.id == ubx::kAckAck) a.push_back(f);
    return a;
  }();
  EXPECT_TRUE(acks.empty()) << "a corrupt CFG message was acknowledged";
  RecordProperty("garbage_bytes", static_cast<int>(garbage_bytes));
  RecordProperty("mon_ver_answer_ms", fmt::format("{:.1f}", *answered_s * 1e3));
  std::printf("faults: %zu garbage bytes in %d bursts over %.1f s; NAV-PVT max gap %.2f s, RMC max "
              "gap %.2f s; MON-VER answered after %.1f ms\n",
              garbage_bytes, bursts, g1 - g0, max_gap(pvt_t), max_gap(rmc_t), *answered_s * 1e3);
}

// ---- Time reference -------------------------------------------------------------------------

// CFG-RATE timeRef (UBX-13003221 "UBX-CFG-RATE"): the measurement epochs are whole periods of the
// reference system's time. At 700 ms, which does not divide the whole seconds between the
// systems, each reference gives its own NAV-PVT iTOW phase. The expected phases follow from the
// published offsets alone (a GPS week is 864,000 periods of 700 ms): UTC = GPS - 18 s (IERS
// Bulletin C, since 2017) gives iTOW mod 700 = 500 ms; GLONASS time = UTC + 3 h gives 100 ms;
// BDT = GPS - 14 s and GST = GPS give 0.
TEST(UbxTimeRef, EpochsFollowTheReferenceSystemsGrid) {
  TempDir dir("ubx-timeref");
  const fs::path link = dir / "gnss", log = dir / "gnss.ubx";
  const fs::path profile = write_profile(dir, "ublox-m8", "NAV-PVT: 1");
  NavemuRun nav(dir, "navemu", ubx_config(profile, link, log), 40);
  ASSERT_TRUE(nav.wait_for_pty(link, 5.0)) << nav.diagnostics();
  PtyClient pty;
  ASSERT_TRUE(pty.open(link));
  struct Case {
    std::uint16_t time_ref;
    std::uint32_t phase_ms;
  };
  for (const Case c : {Case{ubx::CfgRate::kTimeRefUtc, 500}, Case{ubx::CfgRate::kTimeRefGlonass, 100},
                       Case{ubx::CfgRate::kTimeRefGps, 0}, Case{ubx::CfgRate::kTimeRefBeidou, 0},
                       Case{ubx::CfgRate::kTimeRefUtc, 500}}) {
    std::vector<std::uint8_t> cmd;
    ubx::append(ubx::CfgRate{700, 1, c.time_ref}, cmd);
    const std::size_t from = pty.frames().size();
    ASSERT_TRUE(pty.write_all(cmd));
    bool acked = false;
    // The NAV-PVT iTOWs after the acknowledgement.
    const auto tows_after_ack = [&] {
      std::vector<std::uint32_t> tows;
      acked = false;
      for (std::size_t i = from; i < pty.frames().size(); ++i) {
        const UbxFrame& f = pty.frames()[i];
        acked = acked || f.id == ubx::kAckAck;
        ubx::NavPvt m;
        if (acked && f.id == ubx::kNavPvt && ubx::decode(f.payload, m)) tows.push_back(m.i_tow_ms);
      }
      return tows;
    };
    pty.read_until(mono_s() + 5.0, [&] { return tows_after_ack().size() >= 4; });
    const std::vector<std::uint32_t> tows = tows_after_ack();
    ASSERT_TRUE(acked) << "CFG-RATE timeRef " << c.time_ref << " acknowledged" << nav.diagnostics();
    ASSERT_GE(tows.size(), 4u) << "NAV-PVT after timeRef " << c.time_ref;
    // The first one may be the epoch that was on its way when the command came.
    for (std::size_t i = 1; i < tows.size(); ++i) {
      EXPECT_EQ(tows[i] % 700, c.phase_ms) << "timeRef " << c.time_ref << ", iTOW " << tows[i];
      if (i >= 2) {
        EXPECT_EQ(tows[i] - tows[i - 1], 700u) << "timeRef " << c.time_ref;
      }
    }
    std::printf("timeRef %u: iTOW mod 700 ms of %zu NAV-PVT: ", c.time_ref, tows.size());
    for (std::uint32_t t : tows) std::printf("%u ", t % 700);
    std::printf("\n");
  }
}

// ---- NMEA input ------------------------------------------------------------------------------

// $PUBX,41 written to the pty with in/out masks of UBX only (what an autopilot's u-blox driver
// sends to make its port UBX-only; UBX-13003221 "PUBX,41"): the NMEA stops from the next epoch
// while NAV-PVT goes on, with no reply to the sentence. (The pty has no baud: the 38400 asked
// for is the UART's and changes nothing here.)
TEST(UbxNmeaInput, PubxConfigUbxOnlyStopsNmeaOnThePty) {
  TempDir dir("ubx-pubx41");
  const fs::path link = dir / "gnss", log = dir / "gnss.ubx";
  const fs::path profile = write_profile(dir, "ublox-m8", "NAV-PVT: 1");
  NavemuRun nav(dir, "navemu", ubx_config(profile, link, log), 30);
  ASSERT_TRUE(nav.wait_for_pty(link, 5.0)) << nav.diagnostics();
  PtyClient pty;
  ASSERT_TRUE(pty.open(link));
  pty.read_until(mono_s() + 2.5);
  ASSERT_GE(pty.nmea_times("RMC").size(), 1u) << "NMEA at power-up" << nav.diagnostics();
  const std::string cmd = "$PUBX,41,1,0001,0001,38400,0*24\r\n";
  const double t_cmd = mono_s();
  ASSERT_TRUE(pty.write_all(std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(cmd.data()), cmd.size())));
  pty.read_until(t_cmd + 6.0);
  // An epoch already on its way may still carry NMEA: from 1.5 s on, none.
  const double quiet_from = t_cmd + 1.5;
  std::size_t nmea_after = 0;
  double last_nmea = t_cmd;
  for (const char* type : {"RMC", "VTG", "GGA", "GSA", "GSV", "GLL"})
    for (double t : pty.nmea_times(type)) {
      nmea_after += t >= quiet_from ? 1u : 0u;
      last_nmea = std::max(last_nmea, t);
    }
  std::size_t pvt_after = 0, acks = 0;
  for (const UbxFrame& f : pty.frames()) {
    pvt_after += f.id == ubx::kNavPvt && f.t_mono >= quiet_from ? 1u : 0u;
    acks += (f.id == ubx::kAckAck || f.id == ubx::kAckNak) && f.t_mono >= t_cmd ? 1u : 0u;
  }
  EXPECT_EQ(nmea_after, 0u) << "NMEA after $PUBX,41 with outProto UBX";
  EXPECT_GE(pvt_after, 3u) << "UBX goes on";
  EXPECT_EQ(acks, 0u) << "NMEA input is not acknowledged";
  std::printf("PUBX,41: last NMEA %.2f s after it; %zu NMEA sentences and %zu NAV-PVT from 1.5 s to 6 s after it\n",
              last_nmea - t_cmd, nmea_after, pvt_after);
}

}  // namespace
}  // namespace navemu::test::clients
