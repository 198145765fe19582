// The output messages and legacy CFG forms of protocols/ubx_messages.hpp against the lengths
// their interface descriptions document (UBX-13003221 R20 chapter 32, UBX-18010854 R04
// chapter 5) and against an independent decoder: gpsd's ubxtool (python3-gps), which reads
// the frames the descriptions encode and must find the same value in every field both name.
#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <algorithm>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <type_traits>
#include <unistd.h>
#include <vector>

#include "protocols/ubx.hpp"
#include "protocols/ubx_messages.hpp"

namespace navemu::ubx {
namespace {

using Bytes = std::vector<std::uint8_t>;

template <Described T>
Bytes payload_of(const T& m) {
  Bytes frame;
  append(m, frame);
  return Bytes(frame.begin() + 6, frame.end() - 2);
}

template <Described T>
std::size_t length_of(const T& m) {
  return payload_of(m).size();
}

// ---- documented lengths ----------------------------------------------------------------------

// Each message's payload length as its table gives it (fixed messages), and the length of the
// fixed part and of one repeated block (messages with blocks).
TEST(UbxOutputMessages, PayloadLengthsAreTheDocumentedOnes) {
  // UBX-18010854 R04 section 5.14 / UBX-13003221 R20 section 32.17.
  EXPECT_EQ(length_of(NavHpposecef{}), 28u);
  EXPECT_EQ(length_of(NavHpposllh{}), 36u);
  EXPECT_EQ(length_of(NavOdo{}), 20u);
  EXPECT_EQ(length_of(NavResetodo{}), 0u);
  EXPECT_EQ(length_of(NavSvin{}), 40u);
  EXPECT_EQ(length_of(NavRelposnedV0{}), 40u);
  EXPECT_EQ(length_of(NavRelposned{}), 64u);
  EXPECT_EQ(length_of(NavTimels{}), 24u);
  EXPECT_EQ(length_of(NavTimegal{}), 20u);
  EXPECT_EQ(length_of(NavTimeglo{}), 20u);
  EXPECT_EQ(length_of(NavTimebds{}), 20u);
  NavOrb orb;
  orb.svs.resize(3);
  EXPECT_EQ(length_of(orb), 8u + 6u * 3);
  NavGeofence geofence;
  geofence.fences.resize(4);
  EXPECT_EQ(length_of(geofence), 8u + 2u * 4);
  NavSig sig;
  sig.signals.resize(5);
  EXPECT_EQ(length_of(sig), 8u + 16u * 5);
  // Section 5.13 / 32.16.
  MonRf rf;
  rf.blocks.resize(2);
  EXPECT_EQ(length_of(rf), 4u + 24u * 2);
  MonComms comms;
  comms.ports.resize(3);
  EXPECT_EQ(length_of(comms), 8u + 40u * 3);
  EXPECT_EQ(length_of(MonGnss{}), 8u);
  EXPECT_EQ(length_of(MonHw{}), 60u);
  EXPECT_EQ(length_of(MonHw2{}), 28u);
  MonHw3 hw3;
  hw3.pins.resize(2);
  EXPECT_EQ(length_of(hw3), 22u + 6u * 2);
  MonIo io;
  io.ports.resize(6);
  EXPECT_EQ(length_of(io), 20u * 6);
  EXPECT_EQ(length_of(MonMsgpp{}), 120u);
  EXPECT_EQ(length_of(MonRxbuf{}), 24u);
  EXPECT_EQ(length_of(MonTxbuf{}), 28u);
  MonPatch patch;
  patch.entries.resize(2);
  EXPECT_EQ(length_of(patch), 4u + 16u * 2);
  // Sections 5.16, 5.17 / 32.19, 32.20.
  EXPECT_EQ(length_of(SecUniqid{}), 9u);
  EXPECT_EQ(length_of(TimTp{}), 16u);
  EXPECT_EQ(length_of(TimTm2{}), 28u);
  // INF (5.10 / 32.13): the text's length, no terminator.
  EXPECT_EQ(length_of(InfNotice{"fix"}), 3u);
}

TEST(UbxLegacyCfg, PayloadLengthsOfEveryDocumentedForm) {
  // UBX-13003221 R20 section 32.10 / UBX-18010854 R04 section 5.9.
  EXPECT_EQ(length_of(CfgPrtPoll{}), 0u);
  EXPECT_EQ(length_of(CfgPrtPoll{true, kPortUsb}), 1u);
  EXPECT_EQ(length_of(CfgPrt{}), 20u);
  CfgPrtPorts ports;
  ports.ports.resize(2);
  EXPECT_EQ(length_of(ports), 40u);
  EXPECT_EQ(length_of(CfgMsgPoll{}), 2u);
  EXPECT_EQ(length_of(CfgMsgCurrentPort{}), 3u);
  EXPECT_EQ(length_of(CfgMsg{}), 8u);
  EXPECT_EQ(length_of(CfgInfPoll{}), 1u);
  CfgInf inf;
  inf.blocks.resize(2);
  EXPECT_EQ(length_of(inf), 20u);
  CfgGnss gnss;
  gnss.blocks.resize(7);
  EXPECT_EQ(length_of(gnss), 4u + 8u * 7);
  EXPECT_EQ(length_of(CfgTp5Poll{}), 0u);
  EXPECT_EQ(length_of(CfgTp5Poll{true, 1}), 1u);
  EXPECT_EQ(length_of(CfgTp5{}), 32u);
  CfgNmea nmea;
  EXPECT_EQ(length_of(nmea), 4u);
  nmea.has_v0 = true;
  EXPECT_EQ(length_of(nmea), 12u);
  nmea.has_v1 = true;
  EXPECT_EQ(length_of(nmea), 20u);
  CfgNavx5 navx5;
  EXPECT_EQ(length_of(navx5), 40u);
  navx5.has_v3 = true;
  EXPECT_EQ(length_of(navx5), 44u);
  EXPECT_EQ(length_of(CfgSbas{}), 8u);
  EXPECT_EQ(length_of(CfgItfm{}), 8u);
  EXPECT_EQ(length_of(CfgTmode3{}), 40u);
  EXPECT_EQ(length_of(CfgDgnss{}), 4u);
  EXPECT_EQ(length_of(CfgOdo{}), 20u);
  EXPECT_EQ(length_of(CfgUsb{}), 108u);
  EXPECT_EQ(length_of(CfgAnt{}), 4u);
  CfgPm2 pm2;
  EXPECT_EQ(length_of(pm2), 44u);
  pm2.has_extint_inactivity = true;
  EXPECT_EQ(length_of(pm2), 48u);
  EXPECT_EQ(length_of(CfgRxm{}), 2u);
  EXPECT_EQ(length_of(CfgPms{}), 8u);
  EXPECT_EQ(length_of(CfgPwr{}), 8u);
  CfgGeofence geofence;
  geofence.fences.resize(4);
  EXPECT_EQ(length_of(geofence), 8u + 12u * 4);
  EXPECT_EQ(length_of(CfgLogfilter{}), 12u);
  EXPECT_EQ(length_of(CfgDat{}), 44u);
  EXPECT_EQ(length_of(CfgDatCurrent{}), 52u);
}

// ---- the multi-block and multi-length forms by hand ----------------------------------------

// PX4's driver (PX4-GPSDrivers src/ubx.cpp, configure()) sends UART1 and USB in one CFG-PRT:
// 8N1, 115200 Bd, UBX in and out (+ RTCM3 in). Both ports decode, in order; the same payload
// is no single-port CFG-PRT.
TEST(UbxLegacyCfg, CfgPrtWithTwoPortBlocks) {
  Bytes p;
  Writer w(p);
  for (std::uint8_t port : {kPortUart1, kPortUsb}) {
    w.u1(port);
    w.u1(0);
    w.u2(0);
    w.u4(CfgPrt::kMode8N1);
    w.u4(115200);
    w.u2(kProtoUbx | kProtoRtcm3);
    w.u2(kProtoUbx);
    w.u2(0);
    w.u2(0);
  }
  ASSERT_EQ(p.size(), 40u);
  CfgPrtPorts m;
  ASSERT_TRUE(decode(p, m));
  ASSERT_EQ(m.ports.size(), 2u);
  EXPECT_EQ(m.ports[0].port_id, kPortUart1);
  EXPECT_EQ(m.ports[1].port_id, kPortUsb);
  EXPECT_EQ(m.ports[1].baud_rate, 115200u);
  EXPECT_EQ(m.ports[1].in_proto_mask, kProtoUbx | kProtoRtcm3);
  EXPECT_EQ(payload_of(m), p);
  CfgPrt one;
  EXPECT_FALSE(decode(p, one));
  // No port at all is the poll, not a set.
  EXPECT_FALSE(decode(Bytes{}, m));
  CfgPrtPoll poll;
  ASSERT_TRUE(decode(Bytes{kPortUsb}, poll));
  EXPECT_TRUE(poll.has_port_id);
  EXPECT_EQ(poll.port_id, kPortUsb);
  ASSERT_TRUE(decode(Bytes{}, poll));
  EXPECT_FALSE(poll.has_port_id);
  EXPECT_FALSE(decode(Bytes(2), poll));
}

// CFG-NMEA: 4, 12 and 20 bytes decode, each with the fields of its form; other lengths do not.
TEST(UbxLegacyCfg, CfgNmeaThreeLengths) {
  // ubxtool -p CFG-NMEA style 20-byte form: NMEA 4.10, highPrec, GPS talker, BeiDou "GB".
  const Bytes v1{0x00, 0x41, 0x00, CfgNmea::kHighPrec, 0, 0, 0, 0, 1, 1, 0, 1, 'G', 'B', 0, 0, 0, 0, 0, 0};
  CfgNmea m;
  ASSERT_TRUE(decode(v1, m));
  EXPECT_TRUE(m.has_v0);
  EXPECT_TRUE(m.has_v1);
  EXPECT_EQ(m.nmea_version, 0x41);
  EXPECT_EQ(m.main_talker_id, 1);
  EXPECT_EQ(m.version, 1);
  EXPECT_EQ(m.bds_talker_id[0], 'G');
  EXPECT_EQ(payload_of(m), v1);
  const Bytes v0(v1.begin(), v1.begin() + 12);
  ASSERT_TRUE(decode(v0, m));
  EXPECT_TRUE(m.has_v0);
  EXPECT_FALSE(m.has_v1);
  EXPECT_EQ(m.bds_talker_id[0], 0);
  EXPECT_EQ(payload_of(m), v0);
  const Bytes old(v1.begin(), v1.begin() + 4);
  ASSERT_TRUE(decode(old, m));
  EXPECT_FALSE(m.has_v0);
  EXPECT_EQ(m.main_talker_id, 0);
  EXPECT_EQ(payload_of(m), old);
  for (std::size_t n : {0u, 3u, 5u, 11u, 13u, 16u, 19u, 21u})
    EXPECT_FALSE(decode(Bytes(n), m)) << n << " bytes";
}

// CFG-INF: the one-byte poll and a set with a UBX and an NMEA block; CFG-GNSS with its count.
TEST(UbxLegacyCfg, CfgInfAndGnssBlocks) {
  CfgInfPoll poll;
  ASSERT_TRUE(decode(Bytes{1}, poll));
  EXPECT_EQ(poll.protocol_id, 1);
  CfgInf inf;
  inf.blocks.resize(2);
  inf.blocks[0].inf_msg_mask[kPortUart1] = 0x07;  // ERROR, WARNING, NOTICE
  inf.blocks[1].protocol_id = 1;
  inf.blocks[1].inf_msg_mask[kPortUsb] = 0x1F;
  const Bytes p = payload_of(inf);
  ASSERT_EQ(p.size(), 20u);
  EXPECT_EQ(p[4 + kPortUart1], 0x07);
  EXPECT_EQ(p[10], 1);
  EXPECT_EQ(p[10 + 4 + kPortUsb], 0x1F);
  CfgInf back;
  ASSERT_TRUE(decode(p, back));
  ASSERT_EQ(back.blocks.size(), 2u);
  EXPECT_EQ(back.blocks[1].inf_msg_mask[kPortUsb], 0x1F);
  EXPECT_FALSE(decode(Bytes{}, back)) << "a set carries at least one block";
  EXPECT_FALSE(decode(Bytes(15), back));

  CfgGnss gnss;
  gnss.msg_ver = 0;
  gnss.num_trk_ch_hw = 32;
  gnss.num_trk_ch_use = 32;
  gnss.blocks = {{0, 8, 16, 0, CfgGnssBlock::kEnable | 0x010000}, {6, 8, 14, 0, CfgGnssBlock::kEnable | 0x010000}};
  const Bytes g = payload_of(gnss);
  ASSERT_EQ(g.size(), 20u);
  EXPECT_EQ(g[3], 2) << "numConfigBlocks";
  Bytes bad = g;
  bad[3] = 3;
  EXPECT_FALSE(decode(bad, gnss)) << "the count disagrees with the length";
}

// MON-PATCH counts its entries with a U2 (UBX-13003221 32.16.7).
TEST(UbxOutputMessages, MonPatchTwoByteCount) {
  MonPatch m;
  m.entries.resize(300);
  m.entries[299].patch_data = 0xDEADBEEF;
  const Bytes p = payload_of(m);
  ASSERT_EQ(p.size(), 4u + 16u * 300);
  EXPECT_EQ(p[2] | p[3] << 8, 300);
  MonPatch back;
  ASSERT_TRUE(decode(p, back));
  ASSERT_EQ(back.entries.size(), 300u);
  EXPECT_EQ(back.entries[299].patch_data, 0xDEADBEEFu);
}

// INF messages carry every byte of the text, NULs and all.
TEST(UbxOutputMessages, InfTextKeepsEveryByte) {
  const Bytes p{'a', 0, 'b', '\r'};
  InfWarning m;
  ASSERT_TRUE(decode(p, m));
  EXPECT_EQ(m.str, std::string("a\0b\r", 4));
  EXPECT_EQ(payload_of(m), p);
  InfDebug empty;
  ASSERT_TRUE(decode(Bytes{}, empty));
  EXPECT_TRUE(empty.str.empty());
}

// ---- ubxtool as an independent decoder ---------------------------------------------------------

struct Sections {
  std::vector<std::string> names;  // "NAV-TIMELS"
  std::vector<std::string> texts;
};

// ubxtool's output split at its "UBX-XXX-YYY:" headers.
Sections split_sections(const std::string& out) {
  Sections s;
  std::stringstream ss(out);
  for (std::string line; std::getline(ss, line);) {
    if (line.rfind("UBX-", 0) == 0 && !line.empty() && line.back() == ':') {
      s.names.push_back(line.substr(4, line.size() - 5));
      s.texts.emplace_back();
    } else if (!s.texts.empty()) {
      s.texts.back() += line + "\n";
    }
  }
  return s;
}

// The first "name value" pair of each name in ubxtool's text (hex as 0x.. or x..).
std::map<std::string, double> values_in(const std::string& text) {
  std::string t = text;
  for (char& c : t)
    if (c == ':' || c == ',' || c == '[' || c == ']' || c == '(' || c == ')') c = ' ';
  std::stringstream ss(t);
  std::vector<std::string> tok;
  for (std::string x; ss >> x;) tok.push_back(x);
  std::map<std::string, double> v;
  for (std::size_t i = 0; i + 1 < tok.size(); ++i) {
    if (!std::isalpha(static_cast<unsigned char>(tok[i][0])) || v.count(tok[i]) != 0) continue;
    const std::string& s = tok[i + 1];
    char* end = nullptr;
    double x = 0;
    if (s.rfind("0x", 0) == 0) x = static_cast<double>(std::strtoull(s.c_str() + 2, &end, 16));
    else if (s.rfind("x-", 0) == 0)  // a field ubxtool unpacks signed ('b'), in hex: x-5b
      x = static_cast<double>(std::strtoll(s.c_str() + 1, &end, 16));
    else if (s.rfind("x", 0) == 0 && s.size() > 1) x = static_cast<double>(std::strtoull(s.c_str() + 1, &end, 16));
    else x = std::strtod(s.c_str(), &end);
    if (end != nullptr && *end == '\0') v[tok[i]] = x;
  }
  return v;
}

// A payload of message form `m` with random contents: the fixed part, two blocks (at least
// the least number), every optional group and, with `text`, a few characters after an empty
// fixed part (INF messages; NAV-RESETODO has no payload at all).
Bytes random_payload(const MessageInfo& m, std::mt19937& rng, bool text) {
  const auto byte = [&] {
    const auto r = static_cast<std::uint32_t>(rng());
    return static_cast<std::uint8_t>(r % 4 == 0 ? (r >> 8) % 2 : r >> 16);
  };
  Bytes p(m.header_size);
  for (std::uint8_t& b : p) b = byte();
  if (m.block_size > 0) {
    const std::size_t n = std::max<std::size_t>(2, m.min_blocks);
    if (m.count_offset < m.header_size) {
      p[m.count_offset] = static_cast<std::uint8_t>(n);
      if (m.count_size == 2) p[m.count_offset + 1] = 0;
    }
    for (std::size_t i = 0; i < n * m.block_size; ++i) p.push_back(byte());
  }
  for (std::size_t i = 0; i < m.optional_size; ++i) p.push_back(byte());
  if (text && m.header_size == 0 && m.block_size == 0 && m.optional_size == 0 && !m.key_values)
    for (char c : std::string("text")) p.push_back(static_cast<std::uint8_t>(c));
  return p;
}

// One scalar field's raw wire value, its size and whether it is a float (R4, R8).
struct RawField {
  double value = 0;
  std::size_t bytes = 0;
  bool real = false;
};

// The raw wire value of every scalar field, by its name in the table: the fixed part, then
// the first repeated block (the first of a name wins, as in values_in()).
template <class Rows, class S>
void add_raw_values(const Rows& rows, const S& m, std::map<std::string, RawField>& v) {
  rows.apply(
      [&](const auto&... row) {
        const auto one = [&](const auto& r) {
          if constexpr (requires { r.scale; r.member; }) {
            using M = std::remove_cvref_t<decltype(m.*r.member)>;
            if constexpr (std::is_arithmetic_v<M>)
              v.emplace(r.name, RawField{static_cast<double>(m.*r.member), sizeof(M),
                                         std::is_floating_point_v<M>});
          }
        };
        (void)one;  // NAV-RESETODO has no rows
        (one(row), ...);
        const auto block = [&](const auto& r) {
          if constexpr (layout::IsBlock<std::remove_cvref_t<decltype(r)>>::value) {
            using E = typename std::remove_cvref_t<decltype(m.*r.member)>::value_type;
            if constexpr (std::is_class_v<E>)
              if (!(m.*r.member).empty()) add_raw_values(r.rows, (m.*r.member)[0], v);
          }
        };
        (void)block;
        (block(row), ...);
      });
}

template <class L, class S>
std::map<std::string, RawField> raw_values(const L& l, const S& m) {
  std::map<std::string, RawField> v;
  add_raw_values(l.rows, m, v);
  return v;
}

// The same bits: integers compared modulo 2^(8 * size), since ubxtool unpacks some unsigned
// fields as signed (NAV-DOP, NAV-TIMEGLO Nt, CFG-NAV5 cnoThresh: 'h', 'b'); floats as ubxtool
// prints them (CFG-DAT with one decimal).
bool same_value(const RawField& ours, double theirs) {
  if (ours.real) return std::abs(ours.value - theirs) <= std::max(std::abs(ours.value) * 1e-6, 0.05);
  const long double mod = std::ldexp(1.0L, static_cast<int>(8 * ours.bytes));
  long double d = std::fmod(static_cast<long double>(ours.value) - theirs, mod);
  if (d < 0) d += mod;
  return d == 0;
}

// Every described message form, encoded from random field values, decoded by ubxtool: each
// field ubxtool names as the description does holds the same value (raw, in wire units).
// Fields are compared only where both name them; reserved fields and text are not compared.
TEST(UbxReference, UbxtoolDecodesTheSameFieldValues) {
  const char* ubxtool = "/usr/bin/ubxtool";
  if (access(ubxtool, X_OK) != 0) GTEST_SKIP() << ubxtool << " not installed (python3-gps): skipped";
  std::mt19937 rng(21);
  Bytes stream;
  std::vector<std::string> names;
  std::vector<std::map<std::string, RawField>> ours;
  const auto infos = messages();
  std::size_t index = 0;
  Descriptions::kAll.apply(
      [&](const auto&... layout) {
        const auto one = [&](const auto& l) {
          const MessageInfo& info = infos[index++];
          using S = typename std::remove_cvref_t<decltype(l)>::Struct;
          if (info.key_values) return;  // VALGET/VALSET: ubxtool prints key names
          // Not comparable with ubxtool 3.22 (gps/ubx.py), whose decoder stops the run: it
          // unpacks 32 bytes at offset 20 of a 40-byte version 0 NAV-RELPOSNED (struct.error),
          // and its CFG-DGNSS and CFG-PWR format strings are broken (TypeError; both read the
          // layout described here: '<BBBB' and '<BBBBL'). Its NAV-SLAS loop counts blocks with
          // qzssSvId (u[8]) instead of cnt (u[10]) and reads past the end (struct.error). NAV-COV
          // and MON-SPAN it does not know.
          if constexpr (std::is_same_v<S, NavRelposnedV0> || std::is_same_v<S, CfgDgnss> ||
                        std::is_same_v<S, CfgPwr> || std::is_same_v<S, NavCov> ||
                        std::is_same_v<S, MonSpan> || std::is_same_v<S, NavSlas>)
            return;
          S m{};
          bool decoded = false;
          for (int tries = 0; tries < 1000 && !decoded; ++tries) decoded = l.decode(random_payload(info, rng, tries % 2 == 0), m);
          EXPECT_TRUE(decoded) << info.name;
          std::map<std::string, RawField> v = raw_values(l, m);
          l.append(m, stream);
          names.push_back(info.name);
          ours.push_back(std::move(v));
        };
        (one(layout), ...);
      });

  const std::filesystem::path file =
      std::filesystem::temp_directory_path() / ("navemu-ubxtool-" + std::to_string(::getpid()) + ".ubx");
  {
    std::ofstream out(file, std::ios::binary);
    out.write(reinterpret_cast<const char*>(stream.data()), static_cast<std::streamsize>(stream.size()));
  }
  std::string out;
  {
    const std::string cmd = std::string("/usr/bin/python3 ") + ubxtool + " -f '" + file.string() + "' -v 2 -P 27 2>&1";
    FILE* pipe = ::popen(cmd.c_str(), "r");
    ASSERT_NE(pipe, nullptr);
    char buf[4096];
    for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, pipe)) > 0;) out.append(buf, n);
    ::pclose(pipe);
  }
  std::filesystem::remove(file);

  const Sections s = split_sections(out);
  ASSERT_EQ(s.names.size(), names.size()) << out;
  std::size_t compared = 0;
  std::string report;
  for (std::size_t i = 0; i < names.size(); ++i) {
    SCOPED_TRACE(names[i]);
    EXPECT_EQ(s.names[i], names[i]);
    const std::map<std::string, double> theirs = values_in(s.texts[i]);
    std::size_t n = 0;
    for (const auto& [name, field] : ours[i]) {
      if (name.rfind("reserved", 0) == 0) continue;
      // ubxtool 3.22 unpacks NAV-PVT's headVeh, magDec and magAcc at offset 81 ('<lhH');
      // UBX-13003221 32.17.15 and UBX-18010854 5.14.11 place headVeh at 84.
      if (names[i] == "NAV-PVT" && (name == "headVeh" || name == "magDec" || name == "magAcc")) continue;
      // Its CFG-GEOFENCE prints only the last fence (it assigns each fence's line to s).
      if (names[i] == "CFG-GEOFENCE" && (name == "lat" || name == "lon" || name == "radius")) continue;
      const auto it = theirs.find(name);
      if (it == theirs.end()) continue;
      ++n;
      EXPECT_TRUE(same_value(field, it->second))
          << name << ": ours " << field.value << ", ubxtool " << it->second << "\n" << s.texts[i];
    }
    compared += n;
    report += " " + names[i] + ":" + std::to_string(n);
  }
  std::printf("ubxtool: %zu fields compared in %zu frames;%s\n", compared, names.size(), report.c_str());
  EXPECT_GE(compared, 300u);
}

}  // namespace
}  // namespace navemu::ubx
