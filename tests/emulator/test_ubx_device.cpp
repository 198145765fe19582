// The u-blox device behaviour (emulator/ubx_device.hpp) without processes: UBX command frames
// built with protocols/ubx_messages.hpp go into UbxDevice::receive, and the replies are parsed
// back with ubx::Parser and the message decoders. What a client expects of each command
// follows the u-blox 8 Receiver Description (UBX-13003221) section 32.5 "UBX Message Flow"
// (a set is answered with ACK-ACK or ACK-NAK, a poll with the message then ACK-ACK, CFG-RST is
// not acknowledged) and the ZED-F9P interface description (UBX-18010854) for VALSET/VALGET;
// the epoch output is decoded back and compared with the receiver model's fix and raw
// measurements, as gpsd and RTKLIB read them (../shared/TESTING.md).

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <numeric>
#include <regex>
#include <set>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "emulator/ubx_device.hpp"
#include "models/constellation.hpp"
#include "models/ephemeris.hpp"
#include "models/receiver.hpp"
#include "protocols/galileo_inav.hpp"
#include "protocols/gps_lnav.hpp"
#include "protocols/nmea.hpp"
#include "protocols/ubx.hpp"
#include "protocols/ubx_messages.hpp"
#include "tests/test_support.hpp"

namespace navemu {
namespace {

// One frame of the device's output.
struct Frame {
  ubx::MsgId id;
  std::vector<std::uint8_t> payload;
};

// Every good UBX frame in a byte stream (NMEA in between is skipped by the parser). The
// device's output must hold whole, good frames only; a real capture may end inside one.
std::vector<Frame> frames_of(const std::string& bytes, bool device_output = true) {
  ubx::Parser parser(65535);
  std::vector<Frame> out;
  const auto* p = reinterpret_cast<const std::uint8_t*>(bytes.data());
  parser.feed(std::span<const std::uint8_t>(p, bytes.size()), [&](ubx::Parser::Result r) {
    EXPECT_TRUE(!device_output || r != ubx::Parser::Result::kChecksumError) << "the device sent a frame with a bad checksum";
    if (r != ubx::Parser::Result::kFrame) return;
    const auto pl = parser.payload();
    out.push_back({{parser.cls(), parser.id()}, std::vector<std::uint8_t>(pl.begin(), pl.end())});
  });
  EXPECT_TRUE(!device_output || parser.buffered() == 0u) << "the device's output ends inside a frame";
  return out;
}

std::vector<Frame> of_type(const std::vector<Frame>& frames, ubx::MsgId id) {
  std::vector<Frame> out;
  for (const Frame& f : frames)
    if (f.id == id) out.push_back(f);
  return out;
}

// Replies of the device to `bytes`.
std::string send(UbxDevice& d, const std::vector<std::uint8_t>& bytes) {
  std::string replies;
  d.receive(std::span<const std::uint8_t>(bytes.data(), bytes.size()), replies);
  return replies;
}

template <typename Msg>
std::vector<std::uint8_t> frame(const Msg& m) {
  std::vector<std::uint8_t> out;
  ubx::append(m, out);
  return out;
}

std::vector<std::uint8_t> poll(ubx::MsgId id) {
  std::vector<std::uint8_t> out;
  ubx::append_poll(id, out);
  return out;
}

std::vector<std::uint8_t> raw_frame(ubx::MsgId id, const std::vector<std::uint8_t>& payload) {
  std::vector<std::uint8_t> out;
  ubx::append_frame(id.cls, id.id, payload, out);
  return out;
}

bool is_ack(const Frame& f, ubx::MsgId acked) {
  ubx::AckAck a;
  return f.id == ubx::kAckAck && ubx::decode(f.payload, a) && a.cls_id == acked.cls && a.msg_id == acked.id;
}
bool is_nak(const Frame& f, ubx::MsgId acked) {
  ubx::AckNak a;
  return f.id == ubx::kAckNak && ubx::decode(f.payload, a) && a.cls_id == acked.cls && a.msg_id == acked.id;
}

// A reply that is exactly one ACK-ACK (or ACK-NAK) of `acked`.
::testing::AssertionResult only_ack(const std::string& replies, ubx::MsgId acked, bool nak = false) {
  const std::vector<Frame> f = frames_of(replies);
  if (f.size() != 1)
    return ::testing::AssertionFailure() << f.size() << " frames instead of one " << (nak ? "NAK" : "ACK");
  if (nak ? !is_nak(f[0], acked) : !is_ack(f[0], acked))
    return ::testing::AssertionFailure() << "frame " << int(f[0].id.cls) << "/" << int(f[0].id.id)
                                         << " is not the expected " << (nak ? "ACK-NAK" : "ACK-ACK");
  return ::testing::AssertionSuccess();
}

// The payload of a whole frame (6 header bytes, 2 checksum bytes).
std::vector<std::uint8_t> payload_of(const std::vector<std::uint8_t>& f) {
  return std::vector<std::uint8_t>(f.begin() + 6, f.end() - 2);
}

// VALGET of `keys` from the RAM layer (the values, then ACK-ACK): each key's value.
std::map<std::uint32_t, std::uint64_t> valget_items(UbxDevice& d, std::vector<std::uint32_t> keys) {
  ubx::CfgValgetRequest req;
  req.keys = std::move(keys);
  const std::vector<Frame> f = frames_of(send(d, frame(req)));
  ubx::CfgValgetResponse r;
  EXPECT_TRUE(f.size() == 2 && ubx::decode(f[0].payload, r) && is_ack(f[1], ubx::kCfgValget));
  std::map<std::uint32_t, std::uint64_t> items;
  for (const ubx::CfgKeyValue& kv : r.values) items[kv.key_id] = kv.value;
  return items;
}

const NavData& empty_nav() {
  static const NavData nav;
  return nav;
}

// A fixed 3D fix (for the tests that need some epoch, not the receiver model).
ReceiverFix a_fix(GpsTime t) {
  ReceiverFix f;
  f.t = t;
  f.fix = FixType::k3D;
  f.position = Geodetic{32.3, -90.9, 60.0};
  f.p_ecef_m = ecef_from_geodetic(f.position);
  f.v_ned_mps = Vec3::Zero();
  f.dops = Dops{2.0, 1.8, 1.1, 1.4, 0.9};
  f.num_used = 2;
  f.satellites = {{gps_sat(5), 120.0, 45.0, 44.0, true},
                  {gps_sat(12), 300.0, 10.0, 31.0, true},
                  {gps_sat(29), 30.0, 3.0, 25.0, false}};
  f.sigma_h_m = 3.3;
  f.sigma_v_m = 4.2;
  return f;
}

const GpsTime kT0 = gps_from_utc(CalendarTime{2010, 11, 17, 13, 0, 0.0});

class UbxDeviceTest : public ::testing::Test {
 protected:
  GnssProfile m8_ = load_gnss_profile("ublox-m8");
  GnssProfile f9p_ = load_gnss_profile("ublox-f9p");
};

// MON-VER poll: the profile's software and hardware versions and extension strings, among
// them PROTVER=, which gpsd needs to pick its u-blox protocol handling (TESTING.md).
TEST_F(UbxDeviceTest, MonVerCarriesTheProfileStrings) {
  for (const GnssProfile* p : {&m8_, &f9p_}) {
    SCOPED_TRACE(p->name);
    UbxDevice d(*p, ReceiverMode::kStandalone, empty_nav());
    const std::vector<Frame> f = frames_of(send(d, poll(ubx::kMonVer)));
    ASSERT_EQ(f.size(), 1u) << "MON-VER is answered with MON-VER only (no ACK: not a CFG message)";
    ASSERT_EQ(f[0].id, ubx::kMonVer);
    ubx::MonVer v;
    ASSERT_TRUE(ubx::decode(f[0].payload, v));
    EXPECT_EQ(v.sw_version, p->ubx->sw_version);
    EXPECT_EQ(v.hw_version, p->ubx->hw_version);
    EXPECT_EQ(v.extensions, p->ubx->extensions);
    const int expected = std::stoi(p->ubx->protver.substr(0, 2)) * 100 + std::stoi(p->ubx->protver.substr(3));
    EXPECT_EQ(ubx::protocol_version_x100(v), expected);
    EXPECT_EQ(d.counters().polls, 1u);
  }
}

// CFG-PRT poll (empty: the port the poll came in on; one byte: that port) gives the port's
// configuration followed by ACK-ACK; UART1 at the profile's baud with UBX+NMEA in and out.
TEST_F(UbxDeviceTest, CfgPrtPollAnswersThenAcknowledges) {
  UbxDevice d(m8_, ReceiverMode::kStandalone, empty_nav());
  for (const std::vector<std::uint8_t>& req :
       {poll(ubx::kCfgPrt), frame(ubx::CfgPrtPoll{true, ubx::kPortUart1})}) {
    const std::vector<Frame> f = frames_of(send(d, req));
    ASSERT_EQ(f.size(), 2u);
    ASSERT_EQ(f[0].id, ubx::kCfgPrt);
    ubx::CfgPrt prt;
    ASSERT_TRUE(ubx::decode(f[0].payload, prt));
    EXPECT_EQ(prt.port_id, ubx::kPortUart1);
    EXPECT_EQ(prt.baud_rate, static_cast<std::uint32_t>(m8_.baud));
    EXPECT_EQ(prt.mode, ubx::CfgPrt::kMode8N1);
    EXPECT_EQ(prt.in_proto_mask, ubx::kProtoUbx | ubx::kProtoNmea);
    EXPECT_EQ(prt.out_proto_mask, ubx::kProtoUbx | ubx::kProtoNmea);
    EXPECT_TRUE(is_ack(f[1], ubx::kCfgPrt));
  }
}

// CFG-MSG in its three forms (told apart by length): the 2-byte poll answers with the 8-byte
// form (rate on every port) then ACK-ACK; the 3-byte form sets the rate on this port (what
// gpsd's burst uses, TESTING.md); the 8-byte form sets the rates of all ports.
TEST_F(UbxDeviceTest, CfgMsgPollAndBothSetForms) {
  UbxDevice d(m8_, ReceiverMode::kStandalone, empty_nav());
  const auto poll_rate = [&](ubx::MsgId id) -> int {
    const std::vector<Frame> f = frames_of(send(d, frame(ubx::CfgMsgPoll{id.cls, id.id})));
    EXPECT_EQ(f.size(), 2u);
    if (f.size() != 2) return -1;
    EXPECT_TRUE(is_ack(f[1], ubx::kCfgMsg));
    ubx::CfgMsg m;
    EXPECT_EQ(f[0].id, ubx::kCfgMsg);
    if (!ubx::decode(f[0].payload, m)) return -1;
    EXPECT_EQ(m.msg_class, id.cls);
    EXPECT_EQ(m.msg_id, id.id);
    return m.rate[ubx::kPortUart1];
  };

  EXPECT_EQ(poll_rate(ubx::kNavPvt), 0) << "the M8 profile has UBX output off at power-up";
  EXPECT_TRUE(only_ack(send(d, frame(ubx::CfgMsgCurrentPort{0x01, 0x07, 1})), ubx::kCfgMsg));
  EXPECT_EQ(d.rate(ubx::kNavPvt), 1);
  EXPECT_EQ(poll_rate(ubx::kNavPvt), 1);

  ubx::CfgMsg all;
  all.msg_class = 0x01;
  all.msg_id = 0x07;
  all.rate = {0, 2, 0, 0, 0, 0};
  EXPECT_TRUE(only_ack(send(d, frame(all)), ubx::kCfgMsg));
  EXPECT_EQ(d.rate(ubx::kNavPvt), 2);
  EXPECT_EQ(poll_rate(ubx::kNavPvt), 2);

  // An NMEA sentence (class 0xF0): RMC off takes it out of the NMEA output.
  EXPECT_EQ(poll_rate({ubx::kClassNmea, 0x04}), 1);
  std::string before;
  d.encode_epoch(a_fix(kT0), EpochMeasurements{}, 0, before);
  EXPECT_NE(before.find("$GNRMC"), std::string::npos);
  EXPECT_TRUE(only_ack(send(d, frame(ubx::CfgMsgCurrentPort{ubx::kClassNmea, 0x04, 0})), ubx::kCfgMsg));
  std::string after;
  d.encode_epoch(a_fix(kT0), EpochMeasurements{}, 0, after);
  EXPECT_EQ(after.find("$GNRMC"), std::string::npos);
  EXPECT_NE(after.find("$GNGGA"), std::string::npos);

  // Messages of an output class that this receiver does not produce (gpsd's NAV-TIMELS, NMEA
  // GBS) are acknowledged as on the real part; an unknown class is refused.
  EXPECT_TRUE(only_ack(send(d, frame(ubx::CfgMsgCurrentPort{ubx::kClassNav, 0x26, 0xFF})), ubx::kCfgMsg));
  EXPECT_TRUE(only_ack(send(d, frame(ubx::CfgMsgCurrentPort{ubx::kClassNmea, 0x09, 0})), ubx::kCfgMsg));
  EXPECT_TRUE(only_ack(send(d, frame(ubx::CfgMsgCurrentPort{0x55, 0x01, 1})), ubx::kCfgMsg, true));
}

// CFG-RATE: a poll answers the current rate; a valid set is acknowledged and changes the
// epoch period; measRate 10 ms (above the receiver's 25 Hz) and navRate 0 are refused with
// ACK-NAK and change nothing.
TEST_F(UbxDeviceTest, CfgRateSetValidAndInvalid) {
  UbxDevice d(m8_, ReceiverMode::kStandalone, empty_nav());
  EXPECT_EQ(d.period_ns(), 1'000'000'000);
  {
    const std::vector<Frame> f = frames_of(send(d, poll(ubx::kCfgRate)));
    ASSERT_EQ(f.size(), 2u);
    ubx::CfgRate r;
    ASSERT_TRUE(ubx::decode(f[0].payload, r));
    EXPECT_EQ(r.meas_rate_ms, 1000);
    EXPECT_EQ(r.nav_rate_cycles, 1);
    EXPECT_TRUE(is_ack(f[1], ubx::kCfgRate));
  }
  EXPECT_TRUE(only_ack(send(d, frame(ubx::CfgRate{100, 1, ubx::CfgRate::kTimeRefGps})), ubx::kCfgRate));
  EXPECT_EQ(d.period_ns(), 100'000'000);

  EXPECT_TRUE(only_ack(send(d, frame(ubx::CfgRate{10, 1, ubx::CfgRate::kTimeRefGps})), ubx::kCfgRate, true));
  EXPECT_EQ(d.period_ns(), 100'000'000);
  EXPECT_TRUE(only_ack(send(d, frame(ubx::CfgRate{1000, 0, ubx::CfgRate::kTimeRefGps})), ubx::kCfgRate, true));
  EXPECT_EQ(d.period_ns(), 100'000'000);
  EXPECT_TRUE(only_ack(send(d, raw_frame(ubx::kCfgRate, {0xE8, 0x03, 0x01})), ubx::kCfgRate, true))
      << "a CFG-RATE of the wrong length";
  EXPECT_EQ(d.period_ns(), 100'000'000);

  const std::vector<Frame> f = frames_of(send(d, poll(ubx::kCfgRate)));
  ASSERT_EQ(f.size(), 2u);
  ubx::CfgRate r;
  ASSERT_TRUE(ubx::decode(f[0].payload, r));
  EXPECT_EQ(r.meas_rate_ms, 100);
  EXPECT_EQ(d.counters().naks, 3u);
}

// CFG-RATE timeRef puts the epoch grid on the reference system's whole periods: at 700 ms the
// offset from GPS time's grid is the GPS - reference difference modulo 700 ms, with the leap
// seconds of the instant (IERS Bulletin C: 17 s in 2016, 18 s from 2017).
TEST_F(UbxDeviceTest, TimeRefOffsetsTheEpochGrid) {
  UbxDevice d(m8_, ReceiverMode::kStandalone, empty_nav());
  const GpsTime t2016 = gps_from_calendar({2016, 6, 1, 0, 0, 0.0});
  const GpsTime t2024 = gps_from_calendar({2024, 6, 1, 0, 0, 0.0});
  EXPECT_EQ(d.grid_offset_ns(t2024), 0) << "GPS time at power-up";
  const auto set = [&](std::uint16_t meas_ms, std::uint16_t time_ref) {
    EXPECT_TRUE(only_ack(send(d, frame(ubx::CfgRate{meas_ms, 1, time_ref})), ubx::kCfgRate));
  };
  set(700, ubx::CfgRate::kTimeRefUtc);
  EXPECT_EQ(d.grid_offset_ns(t2016), 200'000'000);  // 17 s mod 0.7 s
  EXPECT_EQ(d.grid_offset_ns(t2024), 500'000'000);  // 18 s mod 0.7 s
  set(700, ubx::CfgRate::kTimeRefGlonass);
  EXPECT_EQ(d.grid_offset_ns(t2024), 100'000'000);  // (18 s - 3 h) mod 0.7 s
  set(700, ubx::CfgRate::kTimeRefBeidou);
  EXPECT_EQ(d.grid_offset_ns(t2024), 0);  // 14 s is 20 periods
  set(300, ubx::CfgRate::kTimeRefBeidou);
  EXPECT_EQ(d.grid_offset_ns(t2024), 200'000'000);  // 14 s mod 0.3 s
  set(700, ubx::CfgRate::kTimeRefGalileo);
  EXPECT_EQ(d.grid_offset_ns(t2024), 0);
  set(1000, ubx::CfgRate::kTimeRefUtc);
  EXPECT_EQ(d.grid_offset_ns(t2024), 0) << "whole seconds: every reference has GPS time's grid";
}

// Legacy CFG messages (UBX-13003221 32.10): one the part has is polled (the message, then
// ACK-ACK), set in its documented form and read back, and kept over a reset only after CFG-CFG
// save; a form of the wrong length and a message the part does not have (CFG-DGNSS on the
// u-blox 8 standard-precision part, CFG-SBAS on the F9P) are refused with ACK-NAK.
TEST_F(UbxDeviceTest, LegacyCfgMessagesArePolledSetAndKept) {
  UbxDevice d(m8_, ReceiverMode::kStandalone, empty_nav());
  const auto poll_tp5 = [&](std::uint8_t idx) -> std::optional<ubx::CfgTp5> {
    const std::vector<Frame> f = frames_of(send(d, raw_frame(ubx::kCfgTp5, {idx})));
    ubx::CfgTp5 m;
    if (f.size() != 2 || !is_ack(f[1], ubx::kCfgTp5) || !ubx::decode(f[0].payload, m)) return std::nullopt;
    return m;
  };
  auto tp = poll_tp5(0);
  ASSERT_TRUE(tp);
  EXPECT_EQ(tp->freq_period_hz_or_us, 1'000'000u) << "TIMEPULSE at 1 Hz after power-up";
  EXPECT_EQ(tp->ant_cable_delay_ns, 50);
  ubx::CfgTp5 set = *tp;
  set.tp_idx = 1;
  set.freq_period_hz_or_us = 10;
  EXPECT_TRUE(only_ack(send(d, frame(set)), ubx::kCfgTp5));
  EXPECT_EQ(poll_tp5(1)->freq_period_hz_or_us, 10u);
  EXPECT_EQ(poll_tp5(0)->freq_period_hz_or_us, 1'000'000u) << "TIMEPULSE unchanged";

  ubx::CfgRst hot;  // a hardware reset: what was not saved is gone
  hot.nav_bbr_mask = ubx::CfgRst::kHotStart;
  hot.reset_mode = ubx::CfgRst::kHardwareReset;
  send(d, frame(hot));
  EXPECT_EQ(poll_tp5(1)->freq_period_hz_or_us, 0u);
  EXPECT_TRUE(only_ack(send(d, frame(set)), ubx::kCfgTp5));
  ubx::CfgCfg save;
  save.save_mask = 0xFFFF;
  EXPECT_TRUE(only_ack(send(d, frame(save)), ubx::kCfgCfg));
  send(d, frame(hot));
  EXPECT_EQ(poll_tp5(1)->freq_period_hz_or_us, 10u) << "saved before the reset";

  const std::vector<std::uint8_t> short_tp5(31, 0x01);
  EXPECT_TRUE(only_ack(send(d, raw_frame(ubx::kCfgTp5, short_tp5)), ubx::kCfgTp5, true));
  EXPECT_TRUE(only_ack(send(d, poll(ubx::kCfgDgnss)), ubx::kCfgDgnss, true)) << "M8 standard precision";
  const std::vector<Frame> sbas = frames_of(send(d, poll(ubx::kCfgSbas)));
  ASSERT_EQ(sbas.size(), 2u);
  ubx::CfgSbas sb;
  ASSERT_TRUE(ubx::decode(sbas[0].payload, sb));
  EXPECT_EQ(sb.mode & 1, 1) << "SBAS on after power-up";

  UbxDevice f9p(f9p_, ReceiverMode::kStandalone, empty_nav());
  EXPECT_TRUE(only_ack(send(f9p, poll(ubx::kCfgSbas)), ubx::kCfgSbas, true)) << "no CFG-SBAS on the F9";
  EXPECT_EQ(frames_of(send(f9p, poll(ubx::kCfgTmode3))).size(), 2u) << "CFG-TMODE3 on the F9";
}

// CFG-RST is not acknowledged (UBX-13003221, CFG-RST); the receiver then searches: a cold or
// warm start has no fix for the outage, a hot start for about a second, and the epoch output
// during it reports no fix and no satellites.
TEST_F(UbxDeviceTest, CfgRstIsNotAcknowledgedAndRestarts) {
  UbxDevice d(m8_, ReceiverMode::kStandalone, empty_nav());
  EXPECT_TRUE(only_ack(send(d, frame(ubx::CfgMsgCurrentPort{0x01, 0x07, 1})), ubx::kCfgMsg));
  std::string out;
  d.encode_epoch(a_fix(kT0), EpochMeasurements{}, 0, out);
  EXPECT_FALSE(d.restarting(kT0.plus_s(1.0)));

  ubx::CfgRst cold;
  cold.nav_bbr_mask = ubx::CfgRst::kColdStart;
  cold.reset_mode = ubx::CfgRst::kControlledSoftwareResetGnss;
  EXPECT_TRUE(send(d, frame(cold)).empty()) << "CFG-RST must not be answered";
  EXPECT_EQ(d.counters().acks, 1u);
  EXPECT_EQ(d.counters().naks, 0u);
  // The outage: a cold start's time to first fix, 26 s or so on an M8 (data sheet).
  const auto outage_s = [&](GpsTime from) {
    double t = 0.0;
    while (t < 120.0 && d.restarting(from.plus_s(t))) t += 0.5;
    return t;
  };
  EXPECT_TRUE(d.restarting(kT0.plus_s(1.0)));
  const double cold_s = outage_s(kT0);
  EXPECT_GE(cold_s, 20.0);
  EXPECT_LE(cold_s, 40.0);

  out.clear();
  d.encode_epoch(a_fix(kT0.plus_s(5.0)), EpochMeasurements{}, 5, out);
  const std::vector<Frame> pvt = of_type(frames_of(out), ubx::kNavPvt);
  ASSERT_EQ(pvt.size(), 1u);
  ubx::NavPvt m;
  ASSERT_TRUE(ubx::decode(pvt[0].payload, m));
  EXPECT_EQ(m.fix_type, ubx::kFixNone);
  EXPECT_EQ(m.num_sv, 0);
  EXPECT_EQ(m.flags & ubx::NavPvt::kGnssFixOk, 0);

  // After the outage the fix is back; a hot start is short.
  out.clear();
  d.encode_epoch(a_fix(kT0.plus_s(40.0)), EpochMeasurements{}, 40, out);
  ASSERT_TRUE(ubx::decode(of_type(frames_of(out), ubx::kNavPvt).at(0).payload, m));
  EXPECT_EQ(m.fix_type, ubx::kFix3d);
  ubx::CfgRst hot;
  hot.nav_bbr_mask = ubx::CfgRst::kHotStart;
  hot.reset_mode = ubx::CfgRst::kControlledSoftwareResetGnss;
  EXPECT_TRUE(send(d, frame(hot)).empty());
  EXPECT_TRUE(d.restarting(kT0.plus_s(40.5)));
  const double hot_s = outage_s(kT0.plus_s(40.0));
  EXPECT_GT(hot_s, 0.0);
  EXPECT_LE(hot_s, 2.0);
  RecordProperty("cold_start_outage_s", std::to_string(cold_s));
  RecordProperty("hot_start_outage_s", std::to_string(hot_s));
}

// VALSET/VALGET exist from protocol 27 (ZED-F9P): a set of known keys is acknowledged and
// applied, VALGET reads it back (then ACK-ACK); a set with one unknown key is refused whole
// (nothing applied, UBX-18010854 "CFG-VALSET": all or nothing).
TEST_F(UbxDeviceTest, ValsetValgetOnProtocol27) {
  UbxDevice d(f9p_, ReceiverMode::kStandalone, empty_nav());
  const auto valget = [&](std::uint32_t key) -> std::optional<std::uint64_t> {
    ubx::CfgValgetRequest req;
    req.keys = {key};
    const std::vector<Frame> f = frames_of(send(d, frame(req)));
    if (f.size() == 1 && is_nak(f[0], ubx::kCfgValget)) return std::nullopt;
    EXPECT_EQ(f.size(), 2u);
    if (f.size() != 2) return std::nullopt;
    EXPECT_TRUE(is_ack(f[1], ubx::kCfgValget));
    ubx::CfgValgetResponse r;
    EXPECT_TRUE(ubx::decode(f[0].payload, r));
    EXPECT_EQ(r.values.size(), 1u);
    if (r.values.size() != 1) return std::nullopt;
    EXPECT_EQ(r.values[0].key_id, key);
    return r.values[0].value;
  };

  EXPECT_EQ(valget(ubx::cfgkey::kRateMeas), 1000u);
  ubx::CfgValset set;
  set.values = {{ubx::cfgkey::kRateMeas, 200}};
  EXPECT_TRUE(only_ack(send(d, frame(set)), ubx::kCfgValset));
  EXPECT_EQ(valget(ubx::cfgkey::kRateMeas), 200u);
  EXPECT_EQ(d.period_ns(), 200'000'000);

  // One key the part does not have (group 0xfe is unassigned) beside a valid one: NAK, neither
  // set.
  ubx::CfgValset mixed;
  mixed.values = {{ubx::cfgkey::kRateMeas, 500}, {0x40fe0002, 1'000'000}};
  EXPECT_TRUE(only_ack(send(d, frame(mixed)), ubx::kCfgValset, true));
  EXPECT_EQ(valget(ubx::cfgkey::kRateMeas), 200u);
  EXPECT_EQ(d.period_ns(), 200'000'000);
  EXPECT_FALSE(valget(0x40fe0002).has_value()) << "VALGET of an unknown key: ACK-NAK";

  // 20 ms is below CFG-RATE-MEAS's minimum of 25 ms (F9 HPG 1.13 description, CFG-RATE):
  // refused like CFG-RATE, not clamped after an ACK.
  ubx::CfgValset fast;
  fast.values = {{ubx::cfgkey::kRateMeas, 20}};
  EXPECT_TRUE(only_ack(send(d, frame(fast)), ubx::kCfgValset, true));
  EXPECT_EQ(valget(ubx::cfgkey::kRateMeas), 200u);

  // Message output by key, as ubxtool -z CFG-MSGOUT-UBX_NAV_PVT_UART1,1 does.
  ubx::CfgValset msg;
  msg.values = {{ubx::cfgkey::kMsgoutUbxNavPvtUart1, 1}};
  EXPECT_TRUE(only_ack(send(d, frame(msg)), ubx::kCfgValset));
  EXPECT_EQ(d.rate(ubx::kNavPvt), 1);
  EXPECT_EQ(valget(ubx::cfgkey::kMsgoutUbxNavPvtUart1), 1u);
}

// The navigation output filters (ZED-F9P integration manual UBX-18010802 3.1.7.2; F9 interface
// description 4.1.6 "GNSS fix, but user limits exceeded"): a fix beyond the PDOP or the 3D
// accuracy mask keeps its fix type but is not valid: NAV-PVT gnssFixOK and NAV-STATUS gpsFixOk
// clear, and NMEA reports no fix (GGA quality 0, RMC status V). Set by item on the F9P
// (OUTFIL_PDOP 0x301100b1 in 0.1, OUTFIL_PACC 0x301100b3 in m), by CFG-NAV5 on the M8. The fix:
// PDOP 1.8, 3D accuracy hypot(3.3, 4.2) = 5.3 m.
TEST_F(UbxDeviceTest, OutputFiltersDecideValidity) {
  const auto check = [&](UbxDevice& d, bool ok, const std::string& what) {
    SCOPED_TRACE(what);
    std::string nmea;
    d.encode_epoch(a_fix(kT0), EpochMeasurements{}, 0, nmea);
    std::vector<Frame> f = frames_of(send(d, poll(ubx::kNavPvt)));
    ubx::NavPvt pvt;
    ASSERT_TRUE(f.size() == 1 && ubx::decode(f[0].payload, pvt));
    EXPECT_EQ(pvt.fix_type, 3);
    EXPECT_EQ((pvt.flags & ubx::NavPvt::kGnssFixOk) != 0, ok);
    f = frames_of(send(d, poll(ubx::kNavStatus)));
    ubx::NavStatus st;
    ASSERT_TRUE(f.size() == 1 && ubx::decode(f[0].payload, st));
    EXPECT_EQ((st.flags & ubx::NavStatus::kGpsFixOk) != 0, ok);
    std::smatch m;
    ASSERT_TRUE(std::regex_search(nmea, m, std::regex(R"(\$G[PN]GGA,[^,]*,[^,]*,[^,]*,[^,]*,[^,]*,(\d),)"))) << nmea;
    EXPECT_EQ(m[1], ok ? "1" : "0") << "GGA quality";
    ASSERT_TRUE(std::regex_search(nmea, m, std::regex(R"(\$G[PN]RMC,[^,]*,([AV]),([^,]*),)"))) << nmea;
    EXPECT_EQ(m[1], ok ? "A" : "V") << "RMC status";
    EXPECT_EQ(m[2].length() == 0, !ok) << "no latitude for an invalid fix";
  };
  {
    UbxDevice d(f9p_, ReceiverMode::kStandalone, empty_nav());
    check(d, true, "F9P at the power-up masks (PDOP 25, 100 m)");
    const auto set = [&](std::uint32_t key, std::uint64_t value) {
      ubx::CfgValset v;
      v.values = {{key, value}};
      EXPECT_TRUE(only_ack(send(d, frame(v)), ubx::kCfgValset));
    };
    set(0x301100b3, 5);
    check(d, false, "F9P, 3D accuracy mask 5 m");
    set(0x301100b3, 6);
    check(d, true, "F9P, 3D accuracy mask 6 m");
    set(0x301100b1, 17);
    check(d, false, "F9P, PDOP mask 1.7");
    set(0x301100b1, 18);
    check(d, true, "F9P, PDOP mask 1.8");
  }
  UbxDevice d(m8_, ReceiverMode::kStandalone, empty_nav());
  ubx::CfgNav5 nav5;
  nav5.mask = ubx::CfgNav5::kMaskPosMask;
  nav5.p_dop_0p1 = 250;
  nav5.p_acc_m = 5;
  EXPECT_TRUE(only_ack(send(d, frame(nav5)), ubx::kCfgNav5));
  check(d, false, "M8, CFG-NAV5 pAcc 5 m");
  nav5.p_acc_m = 100;
  EXPECT_TRUE(only_ack(send(d, frame(nav5)), ubx::kCfgNav5));
  check(d, true, "M8, CFG-NAV5 pAcc 100 m");
}

// On the F9P, CFG-INF, CFG-ITFM and CFG-ODO are views of the CFG-INFMSG, CFG-ITFM and CFG-ODO
// items (F9 interface description, "Legacy UBX-CFG message fields reference"; item IDs from
// the description): a set is seen by VALGET, a poll gives the set back (with the reserved ITFM
// bits at their documented values, UBX-13003221 "UBX-CFG-ITFM"), and CFG-INF for a protocol
// without items is refused.
TEST_F(UbxDeviceTest, LegacyInfItfmOdoAreItemsOnTheF9) {
  UbxDevice d(f9p_, ReceiverMode::kStandalone, empty_nav());
  const auto poll_back = [&](ubx::MsgId id, const std::vector<std::uint8_t>& request) {
    const std::vector<Frame> f = frames_of(send(d, request));
    EXPECT_EQ(f.size(), 2u);
    EXPECT_TRUE(f.size() == 2 && is_ack(f[1], id));
    return f.empty() ? Frame{} : f[0];
  };

  ubx::CfgItfm itfm;
  itfm.config = 0x3 | 0xF << 4 | 0x16B156u << 9 | 0x80000000u;  // bb 3, cw 15, enabled
  itfm.config2 = 0x31E | 2u << 12;                                 // external antenna
  EXPECT_TRUE(only_ack(send(d, frame(itfm)), ubx::kCfgItfm));
  auto items = valget_items(d, {0x20410001, 0x20410002, 0x1041000d, 0x20410010, 0x10410013});
  EXPECT_EQ(items[0x20410001], 3u);
  EXPECT_EQ(items[0x20410002], 15u);
  EXPECT_EQ(items[0x1041000d], 1u);
  EXPECT_EQ(items[0x20410010], 2u);
  EXPECT_EQ(items[0x10410013], 0u);
  EXPECT_EQ(poll_back(ubx::kCfgItfm, poll(ubx::kCfgItfm)).payload, payload_of(frame(itfm)));

  ubx::CfgOdo odo;
  odo.flags = ubx::CfgOdo::kUseOdo | 0x4;  // useODO, outLPVel
  odo.odo_cfg = 2;                         // cycling
  odo.cog_max_speed_0p1mps = 12;
  odo.cog_max_pos_acc_m = 40;
  odo.vel_lp_gain = 153;
  odo.cog_lp_gain = 76;
  EXPECT_TRUE(only_ack(send(d, frame(odo)), ubx::kCfgOdo));
  items = valget_items(d, {0x10220001, 0x10220002, 0x10220003, 0x10220004, 0x20220005, 0x20220021, 0x20220022,
                  0x20220031, 0x20220032});
  EXPECT_EQ(items[0x10220001], 1u);
  EXPECT_EQ(items[0x10220002], 0u);
  EXPECT_EQ(items[0x10220003], 1u);
  EXPECT_EQ(items[0x10220004], 0u);
  EXPECT_EQ(items[0x20220005], 2u);
  EXPECT_EQ(items[0x20220021], 12u);
  EXPECT_EQ(items[0x20220022], 40u);
  EXPECT_EQ(items[0x20220031], 153u);
  EXPECT_EQ(items[0x20220032], 76u);
  EXPECT_EQ(poll_back(ubx::kCfgOdo, poll(ubx::kCfgOdo)).payload, payload_of(frame(odo)));

  ubx::CfgInf inf;
  ubx::CfgInfBlock& b = inf.blocks.emplace_back();
  b.protocol_id = 0;  // UBX
  b.inf_msg_mask[ubx::kPortUart1] = 0x1F;
  b.inf_msg_mask[ubx::kPortUsb] = 0x03;
  EXPECT_TRUE(only_ack(send(d, frame(inf)), ubx::kCfgInf));
  items = valget_items(d, {0x20920002, 0x20920004, 0x20920007});
  EXPECT_EQ(items[0x20920002], 0x1Fu) << "CFG-INFMSG-UBX_UART1";
  EXPECT_EQ(items[0x20920004], 0x03u) << "CFG-INFMSG-UBX_USB";
  EXPECT_EQ(items[0x20920007], 0x07u) << "CFG-INFMSG-NMEA_UART1 untouched (power-up 0x07)";
  EXPECT_EQ(poll_back(ubx::kCfgInf, frame(ubx::CfgInfPoll{0})).payload, payload_of(frame(inf)));
  EXPECT_TRUE(only_ack(send(d, frame(ubx::CfgInfPoll{2})), ubx::kCfgInf, true)) << "protocol 2: no items";
}

// CFG-NMEA on the F9P is a view of the CFG-NMEA-* items (F9 interface description, legacy field
// reference; IDs from the description) and acts like them: the 20-byte form sets every item, the
// 4-byte form only its own; the output follows the main talker ID (3: GN) and the version (0x23:
// NMEA 2.3, whose RMC has the mode indicator but no navigational status field).
TEST_F(UbxDeviceTest, CfgNmeaIsTheNmeaItemsOnTheF9AndActs) {
  UbxDevice d(f9p_, ReceiverMode::kStandalone, empty_nav());
  ubx::CfgNmea m;
  m.filter = 0x01;        // posFilt
  m.nmea_version = 0x23;  // 2.3
  m.num_sv = 12;
  m.flags = 0x02;  // consider
  m.has_v0 = m.has_v1 = true;
  m.gnss_to_filter = 0x21;  // GPS, GLONASS
  m.sv_numbering = 1;
  m.main_talker_id = 3;  // GN
  m.gsv_talker_id = 1;
  m.version = 1;
  m.bds_talker_id = {'G', 'B'};
  EXPECT_TRUE(only_ack(send(d, frame(m)), ubx::kCfgNmea));
  std::map<std::uint32_t, std::uint64_t> items =
      valget_items(d, {0x20930001, 0x20930002, 0x10930004, 0x20930007, 0x10930011, 0x10930016, 0x10930012,
                       0x10930021, 0x20930031, 0x20930032, 0x30930033});
  EXPECT_EQ(items[0x20930001], 23u) << "PROTVER";
  EXPECT_EQ(items[0x20930002], 12u) << "MAXSVS";
  EXPECT_EQ(items[0x10930004], 1u) << "CONSIDER";
  EXPECT_EQ(items[0x20930007], 1u) << "SVNUMBERING";
  EXPECT_EQ(items[0x10930011], 1u) << "FILT_GPS";
  EXPECT_EQ(items[0x10930016], 1u) << "FILT_GLO";
  EXPECT_EQ(items[0x10930012], 0u) << "FILT_SBAS";
  EXPECT_EQ(items[0x10930021], 1u) << "OUT_INVFIX";
  EXPECT_EQ(items[0x20930031], 3u) << "MAINTALKERID";
  EXPECT_EQ(items[0x20930032], 1u) << "GSVTALKERID";
  EXPECT_EQ(items[0x30930033], 0x4247u) << "BDSTALKERID 'G' 'B'";
  const std::vector<Frame> f = frames_of(send(d, poll(ubx::kCfgNmea)));
  ASSERT_EQ(f.size(), 2u);
  EXPECT_EQ(f[0].payload, payload_of(frame(m))) << "the poll gives the set back";

  std::string out;
  d.encode_epoch(a_fix(kT0), EpochMeasurements{}, 0, out);
  std::smatch rmc;
  ASSERT_TRUE(std::regex_search(out, rmc, std::regex(R"(\$GNRMC,[^*]*\*)"))) << out;
  const auto commas = [](const std::string& sentence) { return std::count(sentence.begin(), sentence.end(), ','); };
  EXPECT_EQ(commas(rmc.str()), 12) << "NMEA 2.3 RMC: mode, no status\n" << rmc.str();

  // The 4-byte form: version 4.1 and the flags; the talker stays GN.
  ubx::CfgNmea short_form;
  short_form.nmea_version = 0x41;
  EXPECT_TRUE(only_ack(send(d, frame(short_form)), ubx::kCfgNmea));
  out.clear();
  d.encode_epoch(a_fix(kT0), EpochMeasurements{}, 0, out);
  ASSERT_TRUE(std::regex_search(out, rmc, std::regex(R"(\$GNRMC,[^*]*\*)"))) << out;
  EXPECT_EQ(commas(rmc.str()), 13) << "NMEA 4.1 RMC: mode and status\n" << rmc.str();
}

// CFG-TP5 on the F9P is a view of the CFG-TP-*_TP1 items (F9 interface description, legacy
// field reference; IDs from the description). At power-up it reads the items' defaults: 1 s
// period, 100 ms pulse once locked, 50 ns cable delay, flags active, lockGnssFreq,
// lockedOtherSet, isLength, alignToTow, rising edge (0x77). A set in frequency and duty-ratio
// form writes FREQ and DUTY (25 % = 2^30 in 2^-32 units) and reads back; the second time pulse,
// which has no items on the part, is refused.
TEST_F(UbxDeviceTest, CfgTp5IsTheTimePulseItemsOnTheF9) {
  UbxDevice d(f9p_, ReceiverMode::kStandalone, empty_nav());
  const auto poll_tp5 = [&](std::vector<std::uint8_t> request) -> std::optional<ubx::CfgTp5> {
    const std::vector<Frame> f = frames_of(send(d, request));
    ubx::CfgTp5 m;
    if (f.size() != 2 || !is_ack(f[1], ubx::kCfgTp5) || !ubx::decode(f[0].payload, m)) return std::nullopt;
    return m;
  };
  std::optional<ubx::CfgTp5> tp = poll_tp5(poll(ubx::kCfgTp5));
  ASSERT_TRUE(tp);
  EXPECT_EQ(tp->flags, 0x77u);
  EXPECT_EQ(tp->freq_period_hz_or_us, 1'000'000u);
  EXPECT_EQ(tp->freq_period_lock_hz_or_us, 1'000'000u);
  EXPECT_EQ(tp->pulse_len_ratio_us_or_2m32, 0u);
  EXPECT_EQ(tp->pulse_len_ratio_lock_us_or_2m32, 100'000u);
  EXPECT_EQ(tp->ant_cable_delay_ns, 50);

  ubx::CfgTp5 set;
  set.flags = 0x01 | 0x02 | 0x08 | 0x20 | 0x40 | 1u << 7;  // active, lock, isFreq, align, rising, GPS grid
  set.ant_cable_delay_ns = -20;
  set.freq_period_hz_or_us = 10;
  set.freq_period_lock_hz_or_us = 1000;
  set.pulse_len_ratio_us_or_2m32 = 1u << 30;       // 25 %
  set.pulse_len_ratio_lock_us_or_2m32 = 3u << 30;  // 75 %
  set.user_config_delay_ns = -7;
  EXPECT_TRUE(only_ack(send(d, frame(set)), ubx::kCfgTp5));
  std::map<std::uint32_t, std::uint64_t> items =
      valget_items(d, {0x40050024, 0x40050025, 0x20050023, 0x20050030, 0x5005002a, 0x5005002b, 0x10050008,
                       0x10050009, 0x2005000c, 0x30050001, 0x40050006});
  EXPECT_EQ(items[0x40050024], 10u) << "FREQ_TP1";
  EXPECT_EQ(items[0x40050025], 1000u) << "FREQ_LOCK_TP1";
  EXPECT_EQ(items[0x20050023], 1u) << "PULSE_DEF frequency";
  EXPECT_EQ(items[0x20050030], 0u) << "PULSE_LENGTH_DEF ratio";
  EXPECT_EQ(std::bit_cast<double>(items[0x5005002a]), 25.0) << "DUTY_TP1 %";
  EXPECT_EQ(std::bit_cast<double>(items[0x5005002b]), 75.0) << "DUTY_LOCK_TP1 %";
  EXPECT_EQ(items[0x10050008], 1u) << "SYNC_GNSS_TP1";
  EXPECT_EQ(items[0x10050009], 0u) << "USE_LOCKED_TP1";
  EXPECT_EQ(items[0x2005000c], 1u) << "TIMEGRID_TP1 GPS";
  EXPECT_EQ(items[0x30050001], 0xFFECu) << "ANT_CABLEDELAY -20 ns";
  EXPECT_EQ(items[0x40050006], 0xFFFFFFF9u) << "USER_DELAY_TP1 -7 ns";
  tp = poll_tp5(raw_frame(ubx::kCfgTp5, {0}));
  ASSERT_TRUE(tp);
  EXPECT_EQ(frame(*tp), frame(set)) << "the poll gives the set back";

  EXPECT_TRUE(only_ack(send(d, raw_frame(ubx::kCfgTp5, {1})), ubx::kCfgTp5, true)) << "TIMEPULSE2";
  set.tp_idx = 1;
  EXPECT_TRUE(only_ack(send(d, frame(set)), ubx::kCfgTp5, true)) << "TIMEPULSE2";
}

// The F9P's time mode (F9 interface description CFG-TMODE-*, UBX-NAV-SVIN): survey-in set by
// its items (IDs from the description) reports its progress, finishes after the minimum
// duration with the mean of the 3D fixes, and starts again after a reset.
TEST_F(UbxDeviceTest, SurveyInReportsProgressAndFinishes) {
  UbxDevice d(f9p_, ReceiverMode::kStandalone, empty_nav());
  const auto svin = [&] {
    const std::vector<Frame> f = frames_of(send(d, poll(ubx::kNavSvin)));
    ubx::NavSvin m;
    EXPECT_EQ(f.size(), 1u);
    EXPECT_TRUE(!f.empty() && ubx::decode(f[0].payload, m));
    return m;
  };
  const auto feed = [&](int from_s, int to_s) {
    for (int i = from_s; i <= to_s; ++i) {
      ReceiverFix fix = a_fix(kT0.plus_s(i));
      fix.p_ecef_m.x() += i % 2 ? 1.0 : -1.0;
      d.update(fix, EpochMeasurements{}, i);
    }
  };
  const Vec3 p = a_fix(kT0).p_ecef_m;
  feed(0, 0);
  EXPECT_EQ(svin().active, 0) << "time mode off at power-up";

  ubx::CfgValset set;
  set.layers = ubx::kLayerMaskRam | ubx::kLayerMaskBbr;  // kept over the reset below
  set.values = {{0x20030001, 1}, {0x40030010, 10}, {0x40030011, 1'000'000}};  // survey-in, 10 s, 100 m
  EXPECT_TRUE(only_ack(send(d, frame(set)), ubx::kCfgValset));
  feed(1, 6);
  ubx::NavSvin m = svin();
  EXPECT_EQ(m.active, 1);
  EXPECT_EQ(m.valid, 0);
  EXPECT_EQ(m.obs, 6u);
  EXPECT_EQ(m.dur_s, 5u);
  EXPECT_NEAR(m.mean_x_cm * 1e-2 + m.mean_x_hp_0p1mm * 1e-4, p.x(), 1e-4) << "+1 -1 +1 -1 +1 -1 m";
  EXPECT_NEAR(m.mean_y_cm * 1e-2 + m.mean_y_hp_0p1mm * 1e-4, p.y(), 1e-4);
  EXPECT_NEAR(m.mean_z_cm * 1e-2 + m.mean_z_hp_0p1mm * 1e-4, p.z(), 1e-4);
  // 3D accuracy of a fix: hypot(3.3, 4.2) m; under 2 tau (120 s) the mean is no better.
  EXPECT_EQ(m.mean_acc_0p1mm, static_cast<std::uint32_t>(std::lround(std::hypot(3.3, 4.2) * 1e4)));
  feed(7, 10);
  EXPECT_EQ(svin().active, 1) << "9 s < 10 s";
  feed(11, 11);
  m = svin();
  EXPECT_EQ(m.active, 0);
  EXPECT_EQ(m.valid, 1) << "10 s and 5.3 m <= 100 m";
  EXPECT_EQ(m.obs, 11u);
  EXPECT_EQ(m.dur_s, 10u);
  feed(12, 13);
  EXPECT_EQ(svin().obs, 11u) << "finished: no more fixes taken";

  send(d, frame(ubx::CfgRst{ubx::CfgRst::kHotStart, ubx::CfgRst::kControlledSoftwareReset}));
  m = svin();
  EXPECT_EQ(m.active, 1) << "the reset starts the survey again";
  EXPECT_EQ(m.valid, 0);
  EXPECT_EQ(m.obs, 0u);

  set.values = {{0x20030001, 2}};  // fixed
  EXPECT_TRUE(only_ack(send(d, frame(set)), ubx::kCfgValset));
  EXPECT_EQ(svin().active, 0) << "fixed mode: no survey";
}

// CFG-TMODE3 on the F9P is a view of the CFG-TMODE-* items (F9 interface description, "Legacy
// UBX-CFG message fields reference"): a set in the LLH form writes the LLH items, a poll reads
// them back in the same form, VALGET sees them; the u-blox 8 standard-precision part has no
// CFG-TMODE3 and refuses it.
TEST_F(UbxDeviceTest, CfgTmode3IsTheTimeModeItemsOnTheF9) {
  ubx::CfgTmode3 llh;
  llh.flags = 2 | ubx::CfgTmode3::kLla;  // fixed, position as LLH
  llh.ecef_x_or_lat = 323'000'123;        // 1e-7 deg
  llh.ecef_y_or_lon = -909'000'456;
  llh.ecef_z_or_alt_cm = 6'012;
  llh.ecef_x_or_lat_hp = -5;  // 1e-9 deg
  llh.ecef_y_or_lon_hp = 7;
  llh.ecef_z_or_alt_hp_0p1mm = 3;
  llh.fixed_pos_acc_0p1mm = 1'000;
  llh.svin_min_dur_s = 120;
  llh.svin_acc_limit_0p1mm = 20'000;
  {
    UbxDevice m8(m8_, ReceiverMode::kStandalone, empty_nav());
    EXPECT_TRUE(only_ack(send(m8, frame(llh)), ubx::kCfgTmode3, true));
  }
  UbxDevice d(f9p_, ReceiverMode::kStandalone, empty_nav());
  EXPECT_TRUE(only_ack(send(d, frame(llh)), ubx::kCfgTmode3));
  std::map<std::uint32_t, std::uint64_t> items =
      valget_items(d, {0x20030001, 0x20030002, 0x40030009, 0x4003000a, 0x4003000b, 0x2003000c, 0x2003000d,
                       0x2003000e, 0x4003000f, 0x40030010, 0x40030011});
  EXPECT_EQ(items[0x20030001], 2u) << "MODE fixed";
  EXPECT_EQ(items[0x20030002], 1u) << "POS_TYPE LLH";
  EXPECT_EQ(items[0x40030009], 323'000'123u);
  EXPECT_EQ(items[0x4003000a], static_cast<std::uint32_t>(-909'000'456));
  EXPECT_EQ(items[0x4003000b], 6'012u);
  EXPECT_EQ(items[0x2003000c], static_cast<std::uint8_t>(-5));
  EXPECT_EQ(items[0x2003000d], 7u);
  EXPECT_EQ(items[0x2003000e], 3u);
  EXPECT_EQ(items[0x4003000f], 1'000u);
  EXPECT_EQ(items[0x40030010], 120u);
  EXPECT_EQ(items[0x40030011], 20'000u);

  std::vector<Frame> f = frames_of(send(d, poll(ubx::kCfgTmode3)));
  ASSERT_EQ(f.size(), 2u);
  EXPECT_TRUE(is_ack(f[1], ubx::kCfgTmode3));
  ubx::CfgTmode3 back;
  ASSERT_TRUE(ubx::decode(f[0].payload, back));
  EXPECT_EQ(frame(back), frame(llh)) << "the poll gives the set back";

  // An HP part beyond +-99 is out of the item's range: refused, nothing changed.
  ubx::CfgTmode3 bad = llh;
  bad.flags = 1;
  bad.ecef_x_or_lat_hp = 100;
  EXPECT_TRUE(only_ack(send(d, frame(bad)), ubx::kCfgTmode3, true));
  f = frames_of(send(d, poll(ubx::kCfgTmode3)));
  ASSERT_EQ(f.size(), 2u);
  ASSERT_TRUE(ubx::decode(f[0].payload, back));
  EXPECT_EQ(back.flags, llh.flags);
}

// A protocol 18 receiver (M8) has no configuration interface: VALSET and VALGET get ACK-NAK.
TEST_F(UbxDeviceTest, ValsetValgetNakedOnProtocol18) {
  UbxDevice d(m8_, ReceiverMode::kStandalone, empty_nav());
  ubx::CfgValset set;
  set.values = {{ubx::cfgkey::kRateMeas, 200}};
  EXPECT_TRUE(only_ack(send(d, frame(set)), ubx::kCfgValset, true));
  EXPECT_EQ(d.period_ns(), 1'000'000'000);
  ubx::CfgValgetRequest req;
  req.keys = {ubx::cfgkey::kRateMeas};
  EXPECT_TRUE(only_ack(send(d, frame(req)), ubx::kCfgValget, true));
}

// What a misbehaving client or a line glitch produces: junk (gpsd's probe strings of other
// vendors, TESTING.md), a truncated frame, a frame with a wrong checksum, a frame whose length
// exceeds what the receiver buffers, and then a valid poll. The poll is answered, nothing else
// is, and the parser's counters show the damage. Fed whole and byte by byte.
TEST_F(UbxDeviceTest, GarbageTruncatedAndBadChecksumInputStillAnswersThePoll) {
  std::vector<std::uint8_t> in;
  const auto add = [&](const std::vector<std::uint8_t>& b) { in.insert(in.end(), b.begin(), b.end()); };
  const std::string probes = "$PASHQ,RID*28\r\n@F0.3=1*67\r\n$PSRF100,0,9600,8,1,0*0C\r\n$PMTK605*31\r\n";
  add(std::vector<std::uint8_t>(probes.begin(), probes.end()));
  std::uint32_t x = 12345;  // a fixed pseudo-random junk sequence without sync bytes
  for (int i = 0; i < 300; ++i) {
    x = x * 1664525u + 1013904223u;
    const auto b = static_cast<std::uint8_t>(x >> 24);
    in.push_back(b == ubx::kSync1 ? 0x00 : b);
  }
  // Truncated: a CFG-RATE set (100 ms) cut after two payload bytes.
  std::vector<std::uint8_t> rate = frame(ubx::CfgRate{100, 1, ubx::CfgRate::kTimeRefGps});
  add({rate.begin(), rate.begin() + 8});
  // Wrong checksum: the same set with CK_B flipped.
  rate.back() ^= 0xFF;
  add(rate);
  // A length far above the receiver's buffer (0xFFFF).
  add({ubx::kSync1, ubx::kSync2, 0x06, 0x01, 0xFF, 0xFF, 0x01, 0x07, 0x01});
  add(std::vector<std::uint8_t>(40, 'x'));
  add(poll(ubx::kMonVer));

  for (bool byte_at_a_time : {false, true}) {
    SCOPED_TRACE(byte_at_a_time ? "byte at a time" : "one chunk");
    UbxDevice d(m8_, ReceiverMode::kStandalone, empty_nav());
    std::string replies;
    if (byte_at_a_time) {
      for (std::uint8_t b : in) d.receive(std::span<const std::uint8_t>(&b, 1), replies);
    } else {
      replies = send(d, in);
    }
    const std::vector<Frame> f = frames_of(replies);
    ASSERT_EQ(f.size(), 1u) << "only the MON-VER poll is answered";
    EXPECT_EQ(f[0].id, ubx::kMonVer);
    EXPECT_EQ(d.period_ns(), 1'000'000'000) << "neither the cut nor the corrupted CFG-RATE applied";
    const UbxDeviceCounters c = d.counters();
    EXPECT_EQ(c.frames, 1u);
    EXPECT_GE(c.checksum_errors, 1u);
    EXPECT_GE(c.too_long, 1u);
    EXPECT_GE(c.junk_bytes, 300u);
  }
}

// CFG-PRT with a new baud: acknowledged first (at the old baud), and the new baud is handed to
// the transport once.
TEST_F(UbxDeviceTest, CfgPrtBaudChangeIsTakenOnce) {
  UbxDevice d(m8_, ReceiverMode::kStandalone, empty_nav());
  EXPECT_FALSE(d.take_baud_change().has_value());
  ubx::CfgPrt prt;
  prt.port_id = ubx::kPortUart1;
  prt.mode = ubx::CfgPrt::kMode8N1;
  prt.baud_rate = 115200;
  prt.in_proto_mask = ubx::kProtoUbx | ubx::kProtoNmea;
  prt.out_proto_mask = ubx::kProtoUbx | ubx::kProtoNmea;
  EXPECT_TRUE(only_ack(send(d, frame(prt)), ubx::kCfgPrt));
  EXPECT_EQ(d.take_baud_change(), std::optional<int>(115200));
  EXPECT_FALSE(d.take_baud_change().has_value());
  // The same baud again changes nothing.
  EXPECT_TRUE(only_ack(send(d, frame(prt)), ubx::kCfgPrt));
  EXPECT_FALSE(d.take_baud_change().has_value());
  const std::vector<Frame> f = frames_of(send(d, poll(ubx::kCfgPrt)));
  ubx::CfgPrt now;
  ASSERT_TRUE(ubx::decode(f.at(0).payload, now));
  EXPECT_EQ(now.baud_rate, 115200u);
}

// CFG-PRT with the output mask UBX only (ubxtool -d NMEA): the epoch has no NMEA left, and
// the enabled UBX messages still go out.
TEST_F(UbxDeviceTest, OutputMaskUbxOnlyStopsNmea) {
  UbxDevice d(m8_, ReceiverMode::kStandalone, empty_nav());
  EXPECT_TRUE(only_ack(send(d, frame(ubx::CfgMsgCurrentPort{0x01, 0x07, 1})), ubx::kCfgMsg));
  std::string out;
  d.encode_epoch(a_fix(kT0), EpochMeasurements{}, 0, out);
  EXPECT_NE(out.find('$'), std::string::npos) << "NMEA is on at power-up";
  ubx::CfgPrt prt;
  prt.port_id = ubx::kPortUart1;
  prt.mode = ubx::CfgPrt::kMode8N1;
  prt.baud_rate = static_cast<std::uint32_t>(m8_.baud);
  prt.in_proto_mask = ubx::kProtoUbx | ubx::kProtoNmea;
  prt.out_proto_mask = ubx::kProtoUbx;
  EXPECT_TRUE(only_ack(send(d, frame(prt)), ubx::kCfgPrt));
  EXPECT_FALSE(d.take_baud_change().has_value());
  out.clear();
  d.encode_epoch(a_fix(kT0.plus_s(1.0)), EpochMeasurements{}, 1, out);
  EXPECT_EQ(out.find('$'), std::string::npos) << "no NMEA with outProtoMask = UBX";
  const std::vector<Frame> f = frames_of(out);
  ASSERT_EQ(f.size(), 1u);
  EXPECT_EQ(f[0].id, ubx::kNavPvt);
  ubx::NavPvt pvt;
  ASSERT_TRUE(ubx::decode(f[0].payload, pvt));
  std::size_t ubx_bytes = 0;
  for (const Frame& fr : f) ubx_bytes += fr.payload.size() + ubx::kFrameOverhead;
  EXPECT_EQ(ubx_bytes, out.size()) << "nothing but UBX frames";
}

// Satellites are named as u-blox numbers them (ZED-F9P interface description UBX-18010854 R04,
// appendix A "Satellite numbering"): NAV-SAT by gnssId:svId, NAV-SVINFO by the single UBX svId.
// An SBAS (PRN 131), a Galileo (E11) and a GLONASS (slot 5) satellite beside GPS PRN 5.
TEST_F(UbxDeviceTest, SatellitesOfEachSystemAreNumberedAsUbloxNumbersThem) {
  UbxDevice d(m8_, ReceiverMode::kStandalone, empty_nav());
  for (ubx::MsgId id : {ubx::kNavSat, ubx::kNavSvinfo})
    ASSERT_TRUE(only_ack(send(d, frame(ubx::CfgMsgCurrentPort{id.cls, id.id, 1})), ubx::kCfgMsg));
  ReceiverFix fix = a_fix(kT0);
  fix.satellites = {{gps_sat(5), 120.0, 45.0, 44.0, true},
                    {SatId(GnssSystem::kSbas, 31), 200.0, 40.0, 40.0, false},
                    {SatId(GnssSystem::kGalileo, 11), 300.0, 10.0, 31.0, true},
                    {SatId(GnssSystem::kGlonass, 5), 30.0, 3.0, 25.0, false}};
  std::string out;
  d.encode_epoch(fix, EpochMeasurements{}, 0, out);
  const std::vector<Frame> f = frames_of(out);
  ubx::NavSat sat;
  ASSERT_TRUE(ubx::decode(of_type(f, ubx::kNavSat).at(0).payload, sat));
  ubx::NavSvinfo svinfo;
  ASSERT_TRUE(ubx::decode(of_type(f, ubx::kNavSvinfo).at(0).payload, svinfo));
  const int gnss_ids[] = {0, 1, 2, 6}, sv_ids[] = {5, 131, 11, 5}, svinfo_ids[] = {5, 131, 221, 69};
  ASSERT_EQ(sat.svs.size(), 4u);
  ASSERT_EQ(svinfo.channels.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(sat.svs[i].gnss_id, gnss_ids[i]) << i;
    EXPECT_EQ(sat.svs[i].sv_id, sv_ids[i]) << i;
    EXPECT_EQ(svinfo.channels[i].svid, svinfo_ids[i]) << i;
  }
}

// The receiver model's epochs through the device with NAV-PVT, NAV-SAT, RXM-RAWX and RXM-SFRBX
// on, decoded back: NAV-PVT carries the fix (1e-7 deg on the wire), NAV-SAT the tracked
// satellites, RAWX the raw measurements exactly (R8 pseudoranges), and SFRBX, once per 6 s
// subframe (IS-GPS-200 20.3.2), words that pass the parity check gpsd applies and decode to
// the ephemeris the measurements were made with (what RTKLIB and gpsd rebuild, TESTING.md).
TEST_F(UbxDeviceTest, EpochOutputDecodesToTheReceiversFixAndMeasurements) {
  const NavData nav = nominal_constellation(kT0);
  ReceiverParams rp;
  apply_receiver_class(rp.measurement, m8_.receiver_class);
  rp.measurement.elevation_mask_deg = m8_.elevation_mask_deg;
  rp.max_channels = m8_.max_channels;
  Receiver rx(nav, rp);
  UbxDevice d(m8_, ReceiverMode::kStandalone, nav);
  for (ubx::MsgId id : {ubx::kNavPvt, ubx::kNavSat, ubx::kRxmRawx, ubx::kRxmSfrbx})
    ASSERT_TRUE(only_ack(send(d, frame(ubx::CfgMsgCurrentPort{id.cls, id.id, 1})), ubx::kCfgMsg));

  ImuTruth truth;
  truth.position = Geodetic{32.3, -90.9, 60.0};

  // Subframes per satellite in order of arrival, with the ephemeris in use at the time.
  struct Sub {
    int id;
    lnav::LnavSubframe words;
    const GpsEphemeris* eph;
  };
  std::map<int, std::vector<Sub>> subframes;
  int sfrbx_epochs = 0;

  // 48 one-second epochs: a 30 s frame repeats subframes 1, 2, 3 every 30 s, so 48 s hold one
  // complete 1-2-3 sequence whatever the start phase.
  for (int k = 0; k < 48; ++k) {
    const GpsTime t = kT0.plus_s(k);
    truth.t = t;
    const ReceiverFix fix = rx.update(t, &truth);
    const EpochMeasurements& meas = rx.measurements();
    std::string out;
    d.encode_epoch(fix, meas, t.ns / 1'000'000'000, out);
    SCOPED_TRACE("epoch " + std::to_string(k));
    EXPECT_NE(out.find('$'), std::string::npos) << "NMEA still on beside UBX";
    const std::vector<Frame> f = frames_of(out);
    const WeekTow wt = to_week_tow(t);
    const auto tow_ms = std::llround(wt.tow_s * 1000.0);

    ASSERT_EQ(fix.fix, FixType::k3D);
    const std::vector<Frame> pvt = of_type(f, ubx::kNavPvt);
    ASSERT_EQ(pvt.size(), 1u);
    ubx::NavPvt p;
    ASSERT_TRUE(ubx::decode(pvt[0].payload, p));
    EXPECT_EQ(p.i_tow_ms, static_cast<std::uint32_t>(tow_ms));
    EXPECT_EQ(p.fix_type, ubx::kFix3d);
    EXPECT_EQ(p.flags & ubx::NavPvt::kGnssFixOk, ubx::NavPvt::kGnssFixOk);
    EXPECT_EQ(p.valid & 0x03, 0x03) << "gpsd needs validDate and validTime (TESTING.md)";
    EXPECT_EQ(p.num_sv, fix.num_used);
    EXPECT_NEAR(p.lat_1e7deg * 1e-7, fix.position.lat_deg, 1e-7);
    EXPECT_NEAR(p.lon_1e7deg * 1e-7, fix.position.lon_deg, 1e-7);
    EXPECT_NEAR(p.height_mm * 1e-3, fix.position.h_m, 1e-3);
    EXPECT_NEAR(p.h_acc_mm * 1e-3, fix.sigma_h_m, 1e-3);
    EXPECT_NEAR(p.v_acc_mm * 1e-3, fix.sigma_v_m, 1e-3);

    const std::vector<Frame> sat = of_type(f, ubx::kNavSat);
    ASSERT_EQ(sat.size(), 1u);
    ubx::NavSat s;
    ASSERT_TRUE(ubx::decode(sat[0].payload, s));
    ASSERT_EQ(s.svs.size(), fix.satellites.size());
    for (std::size_t i = 0; i < s.svs.size(); ++i) {
      EXPECT_EQ(s.svs[i].gnss_id, 0);
      EXPECT_EQ(s.svs[i].sv_id, fix.satellites[i].sat.number());
      EXPECT_EQ((s.svs[i].flags & ubx::NavSatSv::kSvUsed) != 0, fix.satellites[i].used);
      EXPECT_NEAR(s.svs[i].elev_deg, fix.satellites[i].el_deg, 0.5);
    }

    const std::vector<Frame> raw = of_type(f, ubx::kRxmRawx);
    ASSERT_EQ(raw.size(), 1u);
    ubx::RxmRawx r;
    ASSERT_TRUE(ubx::decode(raw[0].payload, r));
    std::vector<const SatMeasurement*> with_l1;
    for (const SatMeasurement& m : meas.sats)
      if (m.signals[0]) with_l1.push_back(&m);
    ASSERT_EQ(r.meas.size(), with_l1.size());
    EXPECT_GT(r.meas.size(), 4u);
    EXPECT_NE(r.week, 0) << "RTKLIB drops RAWX with week 0 (TESTING.md)";
    EXPECT_NEAR(r.rcv_tow_s, to_week_tow(meas.t_receiver).tow_s, 1e-9);
    for (std::size_t i = 0; i < r.meas.size(); ++i) {
      EXPECT_EQ(r.meas[i].sv_id, with_l1[i]->sat.number());
      EXPECT_EQ(r.meas[i].pr_mes_m, with_l1[i]->signals[0]->pseudorange_m);
      EXPECT_EQ(r.meas[i].cp_mes_cycles, with_l1[i]->signals[0]->carrier_cycles);
      EXPECT_EQ(r.meas[i].trk_stat & 0x03, 0x03) << "pseudorange and phase valid";
      EXPECT_LE(r.meas[i].cp_stdev & 0x0F, 5) << "RTKLIB discards phase with cpStdev > 5";
      // Measurement quality from the loops at the signal's C/N0; the half cycle resolved once
      // the arc has lasted an LNAV subframe (6 s).
      const SignalObs& o = *with_l1[i]->signals[0];
      EXPECT_EQ(r.meas[i].pr_stdev, ubx::rawx_pr_stdev(o.sigma.code_m));
      EXPECT_EQ(r.meas[i].cp_stdev, ubx::rawx_cp_stdev(o.sigma.phase_cycles));
      EXPECT_EQ(r.meas[i].do_stdev, ubx::rawx_do_stdev(o.sigma.doppler_hz));
      EXPECT_EQ((r.meas[i].trk_stat & ubx::RxmRawxMeas::kHalfCyc) != 0, o.lock_time_s >= 6.0) << o.lock_time_s;
      EXPECT_EQ(r.meas[i].trk_stat & ubx::RxmRawxMeas::kSubHalfCyc, 0);
    }

    const std::vector<Frame> sfrbx = of_type(f, ubx::kRxmSfrbx);
    if (tow_ms % 6000 != 0) {
      EXPECT_TRUE(sfrbx.empty()) << "SFRBX only when a subframe ends (every 6 s of GPS time)";
      continue;
    }
    ++sfrbx_epochs;
    std::size_t with_eph = 0;
    for (const SatMeasurement& m : meas.sats) with_eph += m.eph != nullptr ? 1 : 0;
    EXPECT_EQ(sfrbx.size(), with_eph);
    for (const Frame& fr : sfrbx) {
      ubx::RxmSfrbx m;
      ASSERT_TRUE(ubx::decode(fr.payload, m));
      ASSERT_EQ(m.words.size(), 10u);
      lnav::LnavSubframe w{};
      std::copy(m.words.begin(), m.words.end(), w.begin());
      EXPECT_TRUE(lnav::lnav_parity_ok(w)) << "PRN " << int(m.sv_id);
      const lnav::LnavTlmHow how = lnav::decode_tlm_how(w);
      EXPECT_EQ(how.tow_count, static_cast<std::uint32_t>(tow_ms / 6000) % lnav::kTowCountsPerWeek)
          << "the HOW carries the TOW count of the next subframe's start";
      const auto it = std::find_if(meas.sats.begin(), meas.sats.end(),
                                   [&](const SatMeasurement& sm) { return sm.sat.number() == m.sv_id; });
      ASSERT_NE(it, meas.sats.end());
      subframes[m.sv_id].push_back({how.subframe_id, w, it->eph});
    }
  }
  EXPECT_GE(sfrbx_epochs, 7);

  int decoded = 0;
  for (const auto& [prn, subs] : subframes) {
    SCOPED_TRACE("PRN " + std::to_string(prn));
    for (std::size_t i = 0; i + 2 < subs.size(); ++i) {
      if (subs[i].id != 1 || subs[i + 1].id != 2 || subs[i + 2].id != 3) continue;
      const GpsEphemeris& e = *subs[i + 2].eph;
      const WeekTow toe = to_week_tow(e.toe);
      const std::optional<lnav::LnavEphemeris> l =
          lnav::decode_ephemeris(subs[i].words, subs[i + 1].words, subs[i + 2].words, toe.week);
      ASSERT_TRUE(l.has_value()) << "subframes 1-3 do not form a consistent data set";
      EXPECT_EQ(l->iode, e.iode & 0xFF);
      EXPECT_EQ(l->iodc & 0xFF, e.iode & 0xFF);
      EXPECT_NEAR(l->toe_s, toe.tow_s, 16.0) << "toe is sent in 16 s units";
      EXPECT_NEAR(l->toe_s, 16.0 * std::round(toe.tow_s / 16.0), 1e-9);
      EXPECT_EQ(l->week, toe.week);
      EXPECT_NEAR(l->sqrt_a_sqrtm, e.sqrt_a_sqrtm, std::ldexp(1.0, -19));
      EXPECT_NEAR(l->e, e.e, std::ldexp(1.0, -33));
      ++decoded;
      break;
    }
  }
  EXPECT_GE(decoded, 5) << "satellites whose subframes 1-3 came in order within 48 s";
}

// Each port keeps its own message rates and protocol masks (F9 HPG 1.13 description, CFG-MSGOUT
// items per port, CFG-USBOUTPROT; UBX-13003221 UBX-CFG-MSG "current port"): a command that
// arrives on USB changes USB, UART1 goes on as it was. At power-up every port but UART2 sends
// the profile's NMEA.
TEST_F(UbxDeviceTest, EachPortKeepsItsOwnRatesAndProtocols) {
  for (const GnssProfile* p : {&m8_, &f9p_}) {
    UbxDevice d(*p, ReceiverMode::kStandalone, empty_nav());
    const auto epoch = [&](ReceiverPort port) {
      d.update(a_fix(kT0), EpochMeasurements{}, 0);
      std::string out;
      d.encode(port, out);
      return out;
    };
    EXPECT_NE(epoch(ReceiverPort::kUsb).find("$GNGGA"), std::string::npos) << p->ubx->protver;
    EXPECT_EQ(epoch(ReceiverPort::kUart1), epoch(ReceiverPort::kUsb));

    const std::vector<std::uint8_t> on = frame(ubx::CfgMsgCurrentPort{0x01, 0x07, 1});
    std::string replies;
    d.receive(std::span<const std::uint8_t>(on.data(), on.size()), ReceiverPort::kUsb, replies);
    EXPECT_TRUE(only_ack(replies, ubx::kCfgMsg));
    EXPECT_EQ(d.rate(ubx::kNavPvt, ubx::kPortUsb), 1);
    EXPECT_EQ(d.rate(ubx::kNavPvt, ubx::kPortUart1), 0);
    EXPECT_EQ(of_type(frames_of(epoch(ReceiverPort::kUsb)), ubx::kNavPvt).size(), 1u);
    EXPECT_EQ(of_type(frames_of(epoch(ReceiverPort::kUart1)), ubx::kNavPvt).size(), 0u);
  }
  // USB output without NMEA by key, on the part that has keys.
  UbxDevice d(f9p_, ReceiverMode::kStandalone, empty_nav());
  ubx::CfgValset set;
  set.values = {{0x10780002, 0}};  // CFG-USBOUTPROT-NMEA
  EXPECT_TRUE(only_ack(send(d, frame(set)), ubx::kCfgValset));
  d.update(a_fix(kT0), EpochMeasurements{}, 0);
  std::string usb, uart1;
  d.encode(ReceiverPort::kUsb, usb);
  d.encode(ReceiverPort::kUart1, uart1);
  EXPECT_EQ(usb.find('$'), std::string::npos);
  EXPECT_NE(uart1.find("$GNGGA"), std::string::npos);

  // A baud rate is a UART's: set over USB, UART1 changes after the ACK and USB has none.
  set.values = {{0x40520001, 115200}};  // CFG-UART1-BAUDRATE
  const std::vector<std::uint8_t> baud = frame(set);
  std::string replies;
  d.receive(std::span<const std::uint8_t>(baud.data(), baud.size()), ReceiverPort::kUsb, replies);
  EXPECT_TRUE(only_ack(replies, ubx::kCfgValset));
  EXPECT_EQ(d.take_baud_change(ReceiverPort::kUsb), std::nullopt);
  EXPECT_EQ(d.take_baud_change(ReceiverPort::kUart1), 115200);
}

// NAV-HPPOSLLH (F9 HPG 1.13 description): the standard-precision part and the remainder
// (1e-9 deg, 0.1 mm) add up to the position; MON-RF has the L1 and L2 front ends with the
// antenna OK and no jamming indicated. Both by their CFG-MSGOUT items, on the F9P only.
TEST_F(UbxDeviceTest, HighPrecisionPositionAndRfMonitor) {
  UbxDevice d(f9p_, ReceiverMode::kStandalone, empty_nav());
  ubx::CfgValset set;
  set.values = {{0x20910034, 1}, {0x2091035a, 1}};  // CFG-MSGOUT-UBX_NAV_HPPOSLLH_UART1, _MON_RF_UART1
  ASSERT_TRUE(only_ack(send(d, frame(set)), ubx::kCfgValset));
  ReceiverFix fix = a_fix(kT0);
  fix.position = Geodetic{-32.123456789, 150.987654321, 61.2347};
  std::string out;
  d.encode_epoch(fix, EpochMeasurements{}, 0, out);
  const std::vector<Frame> f = frames_of(out);
  const std::vector<Frame> hp = of_type(f, ubx::kNavHpposllh);
  ASSERT_EQ(hp.size(), 1u);
  ubx::NavHpposllh m;
  ASSERT_TRUE(ubx::decode(hp[0].payload, m));
  EXPECT_NEAR(m.lat_1e7deg * 1e-7 + m.lat_hp_1e9deg * 1e-9, fix.position.lat_deg, 0.6e-9);
  EXPECT_NEAR(m.lon_1e7deg * 1e-7 + m.lon_hp_1e9deg * 1e-9, fix.position.lon_deg, 0.6e-9);
  EXPECT_NEAR(m.height_mm * 1e-3 + m.height_hp_0p1mm * 1e-4, fix.position.h_m, 0.6e-4);
  EXPECT_EQ(m.lat_1e7deg, -321234567) << "the standard part as NAV-POSLLH truncates it";
  EXPECT_TRUE(std::abs(m.lat_hp_1e9deg) <= 99 && std::abs(m.height_hp_0p1mm) <= 9);
  EXPECT_EQ(m.flags & ubx::NavHpposllh::kInvalidLlh, 0);

  const std::vector<Frame> rf = of_type(f, ubx::kMonRf);
  ASSERT_EQ(rf.size(), 1u);
  ubx::MonRf r;
  ASSERT_TRUE(ubx::decode(rf[0].payload, r));
  ASSERT_EQ(r.blocks.size(), 2u);
  for (const ubx::MonRfBlock& b : r.blocks) {
    EXPECT_EQ(b.ant_status, ubx::MonHw::kAntOk);
    EXPECT_EQ(b.flags & ubx::MonRfBlock::kJammingStateMask, 0) << "interference monitor off";
    EXPECT_GT(b.noise_per_ms, 0);
    EXPECT_LT(b.jam_ind, 25);
  }

  UbxDevice m8(m8_, ReceiverMode::kStandalone, empty_nav());
  EXPECT_TRUE(frames_of(send(m8, poll(ubx::kMonRf))).empty()) << "the u-blox 8 has no MON-RF";
  EXPECT_EQ(of_type(frames_of(send(m8, poll(ubx::kMonHw))), ubx::kMonHw).size(), 1u);
}


// ---- Output messages beyond the fix (emulator/ubx_outputs.cpp) --------------------------------

// Sets configuration items by name in the RAM layer (CFG-VALSET), expecting ACK-ACK.
void set_items(UbxDevice& d, std::initializer_list<std::pair<const char*, std::uint64_t>> items) {
  ubx::CfgValset set;
  for (const auto& [name, value] : items) {
    const ubx::CfgKey* k = ubx::find_config_key(name);
    ASSERT_NE(k, nullptr) << name;
    set.values.push_back({k->id, value});
  }
  ASSERT_TRUE(only_ack(send(d, frame(set)), ubx::kCfgValset));
}

// Whether a payload is one of the described forms of its message: it decodes, and encodes
// again (as a frame: 6 bytes of header, 2 of checksum) to the same bytes.
bool well_formed(const Frame& f) {
  for (const ubx::MessageInfo& m : ubx::messages()) {
    std::vector<std::uint8_t> again;
    if (m.id == f.id && m.reencode(f.payload, again) && again.size() == f.payload.size() + 8 &&
        std::equal(f.payload.begin(), f.payload.end(), again.begin() + 6))
      return true;
  }
  return false;
}

// Every output message of the part answers a poll with one well-formed message (UBX-13003221
// 32.2 "a message is polled by sending it with no payload"); a message of the other generation
// gets no answer, as on the part. MON-GNSS, MON-PATCH and SEC-UNIQID are answered by both,
// NAV-RESETODO is acknowledged.
// RXM-RAWX measurement quality against the real ZED-F9T of receiver_logs/nav-solutions (5 min,
// 299 epochs): the stdev fields navemu derives from its tracking loops (the geodetic class, the
// F9P's and F9T's) at each real L1 measurement's C/N0 against what the part reported, on the
// L1 signals of GPS, Galileo and BeiDou with a valid phase (the L2 ones run other loops). No
// parameter was fitted to this file.
TEST(RawxQuality, StdevFieldsFollowTheRealF9tByCn0) {
  NAVEMU_REQUIRE_SHARED();
  const std::string bytes = test::read_file(test::shared_data("receiver_logs/nav-solutions/F9T-L2-5min.ubx"));
  MeasurementConfig cfg;
  apply_receiver_class(cfg, ReceiverClass::kGeodetic);
  struct Field {
    const char* name;
    int near = 0;
    double diff = 0.0;
  };
  std::array<Field, 3> fields{{{"prStdev"}, {"cpStdev"}, {"doStdev"}}};
  int n = 0;
  for (const Frame& f : of_type(frames_of(bytes), ubx::kRxmRawx)) {
    ubx::RxmRawx r;
    ASSERT_TRUE(ubx::decode(f.payload, r));
    for (const ubx::RxmRawxMeas& m : r.meas) {
      const bool l1 = (m.gnss_id == 0 && m.sig_id == 0) || ((m.gnss_id == 2 || m.gnss_id == 3) && m.sig_id <= 1);
      if (!l1 || (m.cp_stdev & 0x0F) == 15) continue;
      const TrackingNoise s = tracking_noise(m.cno_dbhz, cfg.tracking);
      const std::array<int, 3> d{ubx::rawx_pr_stdev(s.code_m) - (m.pr_stdev & 0x0F),
                                 ubx::rawx_cp_stdev(s.phase_cycles) - (m.cp_stdev & 0x0F),
                                 ubx::rawx_do_stdev(s.doppler_hz) - (m.do_stdev & 0x0F)};
      for (std::size_t k = 0; k < 3; ++k) {
        fields[k].near += std::abs(d[k]) <= 1 ? 1 : 0;
        fields[k].diff += d[k];
      }
      ++n;
    }
  }
  ASSERT_GT(n, 5000);
  for (const Field& fd : fields) {
    const double near = static_cast<double>(fd.near) / n, mean = fd.diff / n;
    std::printf("RXM-RAWX %s against the real F9T: %.1f %% within one step, mean difference %+.2f steps (%d measurements)\n",
                fd.name, 100.0 * near, mean, n);
    EXPECT_GE(near, 0.9) << fd.name;
    EXPECT_LE(std::abs(mean), 0.6) << fd.name;
  }
}

// C/N0 tracks: per satellite, (elevation deg, C/N0 in whole dB-Hz as NAV-SAT reports it) at
// 1 Hz. Their spread across satellites (the standard deviation of each satellite's mean C/N0
// at 40-90 deg, over those with 50 s or more there) and along each track of 200 s or more
// above 30 deg (the deviation about its linear trend, and that deviation's correlation at
// 10 s).
using Cn0Tracks = std::map<std::pair<int, int>, std::vector<std::pair<double, double>>>;
struct Cn0Spread {
  double across_db = 0.0, along_db = 0.0, rho_10s = 0.0;
  int across_sats = 0, along_sats = 0;
};
Cn0Spread cn0_spread(const Cn0Tracks& tracks) {
  Cn0Spread out;
  std::vector<double> means;
  double along_sq = 0.0, lag_sum = 0.0;
  int along_n = 0;
  for (const auto& [sat, track] : tracks) {
    std::vector<double> high, above_30;
    for (const auto& [el, cn0] : track) {
      if (el >= 40.0) high.push_back(cn0);
      if (el >= 30.0) above_30.push_back(cn0);
    }
    if (high.size() >= 50) means.push_back(std::accumulate(high.begin(), high.end(), 0.0) / static_cast<double>(high.size()));
    if (above_30.size() < 200) continue;
    // Least-squares line through the track, then the residuals.
    const double n = static_cast<double>(above_30.size()), t_mean = (n - 1.0) / 2.0;
    const double y_mean = std::accumulate(above_30.begin(), above_30.end(), 0.0) / n;
    double sty = 0.0, stt = 0.0;
    for (std::size_t i = 0; i < above_30.size(); ++i) {
      sty += (static_cast<double>(i) - t_mean) * (above_30[i] - y_mean);
      stt += (static_cast<double>(i) - t_mean) * (static_cast<double>(i) - t_mean);
    }
    std::vector<double> r(above_30.size());
    for (std::size_t i = 0; i < r.size(); ++i) r[i] = above_30[i] - y_mean - sty / stt * (static_cast<double>(i) - t_mean);
    for (std::size_t i = 0; i < r.size(); ++i) {
      along_sq += r[i] * r[i];
      if (i + 10 < r.size()) lag_sum += r[i] * r[i + 10];
    }
    along_n += static_cast<int>(r.size());
    ++out.along_sats;
  }
  out.across_sats = static_cast<int>(means.size());
  if (means.size() > 1) {
    const double m = std::accumulate(means.begin(), means.end(), 0.0) / static_cast<double>(means.size());
    double v = 0.0;
    for (double x : means) v += (x - m) * (x - m);
    out.across_db = std::sqrt(v / static_cast<double>(means.size() - 1));
  }
  if (along_n > 0) {
    out.along_db = std::sqrt(along_sq / along_n);
    out.rho_10s = lag_sum / along_sq;
  }
  return out;
}

// C/N0 is not a function of elevation alone: against the real ZED-F9T of
// receiver_logs/nav-solutions (NAV-SAT, 5 min, GPS, Galileo and BeiDou), the emulated receiver
// (geodetic class, the F9P's, same systems, 5 min at 1 Hz) spreads its satellites' C/N0 alike:
// across satellites at 40-90 deg and along each arc (the sizes of
// MeasurementConfig::cn0_satellite_sigma_db, cn0_fluctuation_* and cn0_estimator_tau_s come
// from this file). The bounds allow for the few satellites on both sides: a standard
// deviation over n = 11 of them is uncertain by ~1/sqrt(2 (n - 1)) = 22 %; over seeds 1-10
// the emulated values were 1.4-2.9 dB across (mean 2.1), 0.51-0.59 dB and 0.40-0.53 along.
TEST(Cn0Spread, SatellitesDifferAndDriftLikeTheRealF9t) {
  NAVEMU_REQUIRE_SHARED();
  const std::string bytes = test::read_file(test::shared_data("receiver_logs/nav-solutions/F9T-L2-5min.ubx"));
  Cn0Tracks real;
  for (const Frame& f : of_type(frames_of(bytes), ubx::kNavSat)) {
    ubx::NavSat s;
    ASSERT_TRUE(ubx::decode(f.payload, s));
    for (const ubx::NavSatSv& sv : s.svs)
      if (sv.cno_dbhz > 0) real[{sv.gnss_id, sv.sv_id}].emplace_back(sv.elev_deg, sv.cno_dbhz);
  }
  MeasurementConfig cfg;
  apply_receiver_class(cfg, ReceiverClass::kGeodetic);
  cfg.systems = system_bit(GnssSystem::kGps) | system_bit(GnssSystem::kGalileo) | system_bit(GnssSystem::kBeidou);
  const NavData nav = nominal_constellation(kT0, cfg.systems);
  MeasurementGenerator gen(nav, cfg);
  const Vec3 p = ecef_from_geodetic(Geodetic{48.78, 9.18, 300.0});
  Cn0Tracks emulated;
  for (int k = 0; k < 300; ++k)
    for (const SatMeasurement& m : gen.generate(kT0.plus_s(k), p).sats)
      emulated[{static_cast<int>(m.sat.system()), m.sat.number()}].emplace_back(
          m.dir.el_rad * kRadToDeg, std::round(m.signals[0]->cn0_dbhz));
  const Cn0Spread r = cn0_spread(real), e = cn0_spread(emulated);
  std::printf("C/N0 across satellites at 40-90 deg: real %.2f dB (%d), emulated %.2f dB (%d); along arcs: "
              "real %.2f dB, rho(10 s) %.2f (%d), emulated %.2f dB, rho(10 s) %.2f (%d)\n",
              r.across_db, r.across_sats, e.across_db, e.across_sats, r.along_db, r.rho_10s, r.along_sats,
              e.along_db, e.rho_10s, e.along_sats);
  ASSERT_GE(r.across_sats, 10);
  ASSERT_GE(e.across_sats, 10);
  EXPECT_GT(e.across_db, 0.6 * r.across_db);
  EXPECT_LT(e.across_db, 1.6 * r.across_db);
  EXPECT_GT(e.along_db, 0.7 * r.along_db);
  EXPECT_LT(e.along_db, 1.4 * r.along_db);
  EXPECT_NEAR(e.rho_10s, r.rho_10s, 0.25);
}

// The receiver clock of the u-blox profiles, against five real u-blox logs (receiver_logs: the
// ZED-F9T of nav-solutions and of gpsd's ublox-zed-f9t-ubx_nmea_l5, gpsd's ZED-F9P, and two M8,
// ublox-glo and ublox8-uniqid-monhw). The parts' clocks run free: the frequency offset (NAV-CLOCK
// clkD, or the slope of NAV-PVT nano) is 32-297 ns/s, and the epoch falls on the millisecond
// tick nearest GPS time (F9P integration manual 3.10.2), so NAV-PVT nano is what is left of the
// bias after whole milliseconds, nano + clkB = 0 (mod 1 ms), and |nano| <= 0.5 ms. The emulated
// F9P does the same: its drift over 40 seeds has an RMS within a factor of two of the five
// parts' (180 ns/s; an RMS of five is uncertain by ~1/sqrt(10) = 32 %), and a clock whose bias
// crosses half a millisecond moves its RAWX time tag (rcvTow) by a whole millisecond while nano
// stays within 0.5 ms and the fix stays put.
struct ClockEpoch {
  std::int64_t i_tow_ms;
  std::int32_t nano_ns;
  std::optional<std::int32_t> clk_b_ns, clk_d_nsps;
  std::optional<double> rcv_tow_s;
};
std::vector<ClockEpoch> clock_epochs(const std::string& bytes, bool device_output = true) {
  std::map<std::int64_t, ClockEpoch> by_tow;
  for (const Frame& f : frames_of(bytes, device_output)) {
    if (ubx::NavPvt p; f.id == ubx::kNavPvt && ubx::decode(f.payload, p)) {
      by_tow[p.i_tow_ms].i_tow_ms = p.i_tow_ms;
      by_tow[p.i_tow_ms].nano_ns = p.nano_ns;
    } else if (ubx::NavClock c; f.id == ubx::kNavClock && ubx::decode(f.payload, c)) {
      by_tow[c.i_tow_ms].clk_b_ns = c.clk_b_ns;
      by_tow[c.i_tow_ms].clk_d_nsps = c.clk_d_nsps;
    } else if (ubx::RxmRawx r; f.id == ubx::kRxmRawx && ubx::decode(f.payload, r)) {
      by_tow[std::llround(r.rcv_tow_s) * 1000].rcv_tow_s = r.rcv_tow_s;  // by the whole second
    }
  }
  std::vector<ClockEpoch> out;
  for (const auto& [tow, e] : by_tow)
    if (e.i_tow_ms > 0) out.push_back(e);
  return out;
}
// The residue of nano + clkB after whole milliseconds, ns.
std::int64_t off_the_millisecond_ns(const ClockEpoch& e) {
  const std::int64_t sum = std::int64_t{e.nano_ns} + *e.clk_b_ns;
  return sum - std::llround(static_cast<double>(sum) / 1e6) * 1'000'000;
}

TEST_F(UbxDeviceTest, TheClockRunsFreeAndEpochsFallOnTheNearestMillisecondLikeRealParts) {
  NAVEMU_REQUIRE_SHARED();
  std::vector<double> real_drift_nsps;
  int real_clock_epochs = 0;
  for (const char* log : {"nav-solutions/F9T-L2-5min.ubx", "gpsd/ublox-zed-f9t-ubx_nmea_l5.log",
                          "gpsd/ublox-zed-f9p-sfrbx.log", "gpsd/ublox-glo.log", "gpsd/ublox8-uniqid-monhw.log"}) {
    SCOPED_TRACE(log);
    const std::vector<ClockEpoch> e =
        clock_epochs(test::read_file(test::shared_data(std::string("receiver_logs/") + log)), false);
    ASSERT_GE(e.size(), 7u);
    for (const ClockEpoch& x : e) {
      EXPECT_LE(std::abs(x.nano_ns), 500'000);
      if (x.clk_b_ns) {
        EXPECT_LE(std::abs(off_the_millisecond_ns(x)), 2);
        ++real_clock_epochs;
      }
    }
    // The drift: NAV-CLOCK's, else the slope of nano (the bias's, negated).
    const ClockEpoch& a = e.front();
    const ClockEpoch& b = e.back();
    real_drift_nsps.push_back(a.clk_d_nsps ? *a.clk_d_nsps
                                           : -static_cast<double>(b.nano_ns - a.nano_ns) * 1e3 /
                                                 static_cast<double>(b.i_tow_ms - a.i_tow_ms));
  }
  EXPECT_GT(real_clock_epochs, 300);
  const auto rms = [](const std::vector<double>& v) {
    double sq = 0.0;
    for (double x : v) sq += x * x;
    return std::sqrt(sq / static_cast<double>(v.size()));
  };

  const NavData nav = nominal_constellation(kT0, system_bit(GnssSystem::kGps));
  ImuTruth truth;
  truth.position = Geodetic{32.3, -90.9, 60.0};
  const Vec3 p_truth = ecef_from_geodetic(truth.position);
  const auto run = [&](const ReceiverParams& rp, int epochs) {
    Receiver rx(nav, rp);
    UbxDevice d(f9p_, ReceiverMode::kStandalone, nav);
    set_items(d, {{"CFG-MSGOUT-UBX_NAV_PVT_UART1", 1}, {"CFG-MSGOUT-UBX_NAV_CLOCK_UART1", 1},
                  {"CFG-MSGOUT-UBX_RXM_RAWX_UART1", 1}});
    std::string out;
    double worst_error_m = 0.0;
    for (int k = 0; k < epochs; ++k) {
      const ReceiverFix& fix = rx.update(kT0.plus_s(k), &truth);
      EXPECT_NE(fix.fix, FixType::kNone);
      worst_error_m = std::max(worst_error_m, (fix.p_ecef_m - p_truth).norm());
      d.encode_epoch(fix, rx.measurements(), k, out);
    }
    EXPECT_LT(worst_error_m, 15.0);
    return clock_epochs(out);
  };

  std::vector<double> drift_nsps;
  for (std::uint64_t seed = 1; seed <= 40; ++seed) {
    ReceiverParams rp;
    rp.measurement.seed = seed;
    rp.measurement.clock = f9p_.clock;
    const std::vector<ClockEpoch> e = run(rp, 1);
    ASSERT_EQ(e.size(), 1u);
    EXPECT_LE(std::abs(*e[0].clk_b_ns), 1'000'000);
    EXPECT_LE(std::abs(off_the_millisecond_ns(e[0])), 2);
    drift_nsps.push_back(*e[0].clk_d_nsps);
  }
  std::printf("clock drift RMS: real u-blox parts %.0f ns/s (%zu logs), emulated F9P %.0f ns/s (40 seeds)\n",
              rms(real_drift_nsps), real_drift_nsps.size(), rms(drift_nsps));
  EXPECT_GT(rms(drift_nsps), 0.5 * rms(real_drift_nsps));
  EXPECT_LT(rms(drift_nsps), 2.0 * rms(real_drift_nsps));

  // A bias that crosses +0.5 ms (0.4995 ms, 200 ns/s): the tick nearest GPS time moves a
  // millisecond later, the true time of the epoch from 0.5 ms before the second to 0.5 after.
  ReceiverParams rp;
  rp.measurement.clock.initial_bias_s = 0.4995e-3;
  rp.measurement.clock.initial_drift_sps = 200e-9;
  const std::vector<ClockEpoch> e = run(rp, 6);
  ASSERT_EQ(e.size(), 6u);
  int jumps = 0;
  for (std::size_t k = 0; k < e.size(); ++k) {
    SCOPED_TRACE(k);
    ASSERT_TRUE(e[k].rcv_tow_s && e[k].clk_b_ns);
    const double tag_ms = (*e[k].rcv_tow_s * 1e3 - static_cast<double>(e[k].i_tow_ms));
    EXPECT_NEAR(tag_ms, std::round(*e[k].clk_b_ns * 1e-6), 1e-6);  // rcvTow: the tick, whole ms
    EXPECT_LE(std::abs(e[k].nano_ns), 500'000);
    EXPECT_LE(std::abs(off_the_millisecond_ns(e[k])), 2);
    if (k > 0 && std::abs(tag_ms - (*e[k - 1].rcv_tow_s * 1e3 - static_cast<double>(e[k - 1].i_tow_ms))) > 0.5) ++jumps;
  }
  EXPECT_EQ(jumps, 1);
  EXPECT_LT(e.front().nano_ns, -499'000);
  EXPECT_GT(e.back().nano_ns, 499'000);
}

// The fractional time fields complete iTOW (NAV-SOL and NAV-TIMEGPS fTOW: to the clock tick's
// GPS time, +-0.5 ms) or the date and time rounded to 10 ms (NAV-PVT and NAV-TIMEUTC nano), also
// at an epoch between whole seconds (5 Hz: .2 s).
TEST_F(UbxDeviceTest, FractionalTimeFieldsCompleteTheirWholeParts) {
  UbxDevice d(m8_, ReceiverMode::kStandalone, empty_nav());  // the M8 has NAV-SOL
  for (const ubx::MsgId id : {ubx::kNavPvt, ubx::kNavSol, ubx::kNavTimegps, ubx::kNavTimeutc})
    ASSERT_TRUE(only_ack(send(d, frame(ubx::CfgMsgCurrentPort{id.cls, id.id, 1})), ubx::kCfgMsg));
  ReceiverFix fix = a_fix(kT0.plus_s(0.2));
  fix.time_offset_s = -123.456e-6;
  std::string out;
  d.encode_epoch(fix, EpochMeasurements{}, 0, out);
  const auto i_tow = static_cast<std::uint32_t>(std::llround(to_week_tow(kT0).tow_s * 1000.0)) + 200;
  int seen = 0;
  for (const Frame& f : frames_of(out)) {
    if (ubx::NavSol m; f.id == ubx::kNavSol && ubx::decode(f.payload, m)) {
      EXPECT_EQ(m.i_tow_ms, i_tow);
      EXPECT_EQ(m.f_tow_ns, -123456);
      ++seen;
    } else if (ubx::NavTimegps g; f.id == ubx::kNavTimegps && ubx::decode(f.payload, g)) {
      EXPECT_EQ(g.i_tow_ms, i_tow);
      EXPECT_EQ(g.f_tow_ns, -123456);
      ++seen;
    } else if (ubx::NavPvt p; f.id == ubx::kNavPvt && ubx::decode(f.payload, p)) {
      EXPECT_EQ(p.sec, 0);  // 13:00:00.2 UTC, less the offset
      EXPECT_EQ(p.nano_ns, 200'000'000 - 123'456);
      ++seen;
    } else if (ubx::NavTimeutc u; f.id == ubx::kNavTimeutc && ubx::decode(f.payload, u)) {
      EXPECT_EQ(u.sec, 0);
      EXPECT_EQ(u.nano_ns, 200'000'000 - 123'456);
      ++seen;
    }
  }
  EXPECT_EQ(seen, 4);
}

TEST_F(UbxDeviceTest, EveryOutputMessageOfThePartAnswersAPoll) {
  for (const GnssProfile* p : {&m8_, &f9p_}) {
    SCOPED_TRACE(p->name);
    const bool f9 = p == &f9p_;
    UbxDevice d(*p, ReceiverMode::kStandalone, empty_nav());
    std::string out;
    d.encode_epoch(a_fix(kT0), EpochMeasurements{}, 0, out);
    for (const UbxOutput& o : ubx_outputs()) {
      if (o.id == ubx::kRxmSfrbx) continue;  // subframes only at a subframe's end, with ephemerides
      const std::vector<Frame> f = frames_of(send(d, poll(o.id)));
      SCOPED_TRACE(ubx::find_message(o.id) ? ubx::find_message(o.id)->name : "?");
      if (f9 ? o.f9 : o.m8) {
        ASSERT_EQ(f.size(), 1u);
        EXPECT_TRUE(f[0].id == o.id);
        EXPECT_TRUE(well_formed(f[0]));
      } else {
        EXPECT_TRUE(f.empty());
      }
    }
    for (ubx::MsgId id : {ubx::kMonGnss, ubx::kMonPatch, ubx::kSecUniqid}) {
      const std::vector<Frame> f = frames_of(send(d, poll(id)));
      ASSERT_EQ(f.size(), 1u);
      EXPECT_TRUE(f[0].id == id && well_formed(f[0]));
    }
    EXPECT_TRUE(only_ack(send(d, poll(ubx::kNavResetodo)), ubx::kNavResetodo));
  }
}

// RXM-RAWX of the F9P profile (bands L1 and L2, five systems, its default signal items): every
// tracked satellite's L1 signal, and its L2-band one where the satellite sends it (GPS L2C from
// Block IIR-M on: core/signal.cpp) and the item enables it (BeiDou B2I off by default), with the
// UBX sigIds of the part (F9 interface description, "Signal identifiers").
TEST_F(UbxDeviceTest, RawxListsTheProfilesBandsOfEachSatellite) {
  const GpsTime t = gps_from_utc(CalendarTime{2024, 6, 1, 12, 0, 0.0});  // 25 GPS PRNs with L2C then
  const NavData nav = nominal_constellation(t, f9p_.systems);
  ReceiverParams rp;
  rp.measurement.systems = f9p_.systems;
  rp.measurement.bands = f9p_.bands;
  rp.max_channels = 64;
  Receiver rx(nav, rp);
  UbxDevice d(f9p_, ReceiverMode::kStandalone, nav);
  set_items(d, {{"CFG-MSGOUT-UBX_RXM_RAWX_UART1", 1}});
  rx.set_engine(*d.engine_settings());
  ImuTruth truth;
  truth.position = Geodetic{32.3, -90.9, 60.0};
  truth.t = t;
  const ReceiverFix fix = rx.update(t, &truth);
  std::string out;
  d.encode_epoch(fix, rx.measurements(), 0, out);
  const std::vector<Frame> f = of_type(frames_of(out), ubx::kRxmRawx);
  ASSERT_EQ(f.size(), 1u);
  ubx::RxmRawx m;
  ASSERT_TRUE(ubx::decode(f[0].payload, m));
  std::map<std::pair<int, int>, std::set<int>> sig_ids;  // (gnssId, svId) -> sigIds
  for (const ubx::RxmRawxMeas& r : m.meas) sig_ids[{r.gnss_id, r.sv_id}].insert(r.sig_id);
  std::map<GnssSystem, int> with_l2;
  for (const SatMeasurement& s : rx.measurements().sats) {
    SCOPED_TRACE(s.sat.rinex());
    const std::set<int>& ids = sig_ids[{s.sat.ubx_gnss_id(), s.sat.ubx_sv_id()}];
    const std::optional<int> l1 = ubx_sig_id(s.sat, band_signal(s.sat.system(), Band::kL1)->id);
    const std::optional<int> l2 = ubx_sig_id(s.sat, band_signal(s.sat.system(), Band::kL2)->id);
    const bool expect_l2 = s.sat.system() != GnssSystem::kBeidou && broadcasts(s.sat, band_signal(s.sat.system(), Band::kL2)->id, t);
    const std::set<int> expected = expect_l2 ? std::set<int>{*l1, *l2} : std::set<int>{*l1};
    EXPECT_EQ(ids, expected);
    with_l2[s.sat.system()] += expect_l2 ? 1 : 0;
  }
  EXPECT_GT(with_l2[GnssSystem::kGps], 3);  // GPS L2C sigId 3
  EXPECT_GT(with_l2[GnssSystem::kGalileo], 3);  // E5b Q sigId 6
  EXPECT_GT(with_l2[GnssSystem::kGlonass], 3);  // L2OF sigId 2
  EXPECT_EQ(with_l2[GnssSystem::kBeidou], 0);
}

// RXM-SFRBX of the F9P's Galileo satellites on both of its I/NAV signals, as the ZED-F9P capture
// in ../shared/data has them: E1-B page pairs (sigId 1) when an odd GST second ends one, E5b-I
// page pairs (sigId 5) at the even ones, each with its signal's word schedule, a valid CRC and
// E5b's "Reserved 2"; over 30 s E5b-I brings every ephemeris word.
TEST_F(UbxDeviceTest, SfrbxSendsTheGalileoPagesOfBothSignals) {
  const GpsTime t0 = gps_from_utc(CalendarTime{2024, 6, 1, 12, 0, 0.0});
  const NavData nav = nominal_constellation(t0, system_bit(GnssSystem::kGalileo));
  ReceiverParams rp;
  rp.measurement.systems = system_bit(GnssSystem::kGalileo);
  rp.measurement.bands = f9p_.bands;
  Receiver rx(nav, rp);
  UbxDevice d(f9p_, ReceiverMode::kStandalone, nav);
  set_items(d, {{"CFG-MSGOUT-UBX_RXM_SFRBX_UART1", 1}});
  rx.set_engine(*d.engine_settings());
  std::map<int, std::set<int>> e5b_words;  // svId -> word types
  int e1b = 0, e5b = 0;
  for (int k = 0; k <= 30; ++k) {
    const GpsTime t = t0.plus_s(k);
    ImuTruth truth;
    truth.position = Geodetic{48.1, 11.6, 520.0};
    truth.t = t;
    const ReceiverFix fix = rx.update(t, &truth);
    std::string out;
    d.encode_epoch(fix, rx.measurements(), 0, out);
    const double tow_s = to_week_tow(t).tow_s;
    for (const Frame& fr : of_type(frames_of(out), ubx::kRxmSfrbx)) {
      ubx::RxmSfrbx m;
      ASSERT_TRUE(ubx::decode(fr.payload, m));
      ASSERT_EQ(m.gnss_id, 2);
      const bool on_e5b = m.sig_id == 5;
      ASSERT_TRUE(on_e5b || m.sig_id == 1) << int{m.sig_id};
      EXPECT_EQ(std::fmod(tow_s, 2.0), on_e5b ? 0.0 : 1.0) << tow_s;
      const std::optional<inav::InavDecodedPage> page = inav::decode_inav_page(m.words);
      ASSERT_TRUE(page.has_value());
      const inav::InavSignal signal = on_e5b ? inav::InavSignal::kE5bI : inav::InavSignal::kE1B;
      EXPECT_EQ(page->word_type, inav::inav_word_type_for(tow_s - 2.0, signal)) << tow_s;
      if (on_e5b) {
        EXPECT_EQ(page->extras.ssp, inav::kE5bReserved2);
        e5b_words[m.sv_id].insert(page->word_type);
      }
      (on_e5b ? e5b : e1b) += 1;
    }
  }
  EXPECT_GT(e1b, 40);
  EXPECT_GT(e5b, 40);
  ASSERT_FALSE(e5b_words.empty());
  for (const auto& [sv, words] : e5b_words)
    for (int w = 1; w <= 6; ++w) EXPECT_TRUE(words.count(w)) << "E" << sv << " word " << w;
}

// NAV-SIG of a dual-frequency F9P: one block per tracked L1 C/A and L2 CL signal (sigId 0 and
// 3, as the ZED-F9T in ../shared/data numbers them); the signals of satellites the solution
// uses carry prUsed and doUsed (0x29 with health "healthy", as in that log) and the dual-frequency
// ionosphere model (8), the others health only.
TEST_F(UbxDeviceTest, NavSigListsEveryTrackedSignalAndItsUse) {
  const NavData nav = nominal_constellation(kT0);
  ReceiverParams rp;
  rp.measurement.mode = ReceiverMode::kDualFrequency;
  Receiver rx(nav, rp);
  UbxDevice d(f9p_, ReceiverMode::kDualFrequency, nav);
  set_items(d, {{"CFG-MSGOUT-UBX_NAV_SIG_UART1", 1}});
  ImuTruth truth;
  truth.position = Geodetic{32.3, -90.9, 60.0};
  truth.t = kT0;
  const ReceiverFix fix = rx.update(kT0, &truth);
  const EpochMeasurements& meas = rx.measurements();
  std::string out;
  d.encode_epoch(fix, meas, 0, out);
  const std::vector<Frame> f = of_type(frames_of(out), ubx::kNavSig);
  ASSERT_EQ(f.size(), 1u);
  ubx::NavSig m;
  ASSERT_TRUE(ubx::decode(f[0].payload, m));
  std::size_t expected = 0;
  for (const SatMeasurement& s : meas.sats) expected += (s.signals[0] ? 1u : 0u) + (s.signals[1] ? 1u : 0u);
  ASSERT_GT(expected, 8u);
  EXPECT_EQ(m.signals.size(), expected);
  int used = 0;
  for (const ubx::NavSigSignal& g : m.signals) {
    SCOPED_TRACE(::testing::Message() << "G" << int{g.sv_id} << " sig " << int{g.sig_id});
    EXPECT_EQ(g.gnss_id, 0);
    EXPECT_TRUE(g.sig_id == 0 || g.sig_id == 3);
    const auto it = std::find_if(fix.satellites.begin(), fix.satellites.end(),
                                 [&](const ReceiverSatellite& r) { return r.sat.ubx_sv_id() == g.sv_id; });
    ASSERT_NE(it, fix.satellites.end());
    EXPECT_EQ(g.sig_flags, it->used ? 0x29 : 0x01);
    EXPECT_EQ(g.iono_model, it->used ? 8 : 0);
    EXPECT_GT(g.cno_dbhz, 0);
    used += it->used ? 1 : 0;
  }
  EXPECT_EQ(used, 2 * fix.num_used) << "both bands of every used satellite";
}

// A receiver whose engine smooths its code by the carrier (the F9P profile's 100 s) says so per
// used satellite: NAV-SAT smoothed (flags bit 7) and NAV-SIG prSmoothed (sigFlags bit 2), from
// the second epoch of each carrier arc on (the first is the raw code); unused ones never.
TEST_F(UbxDeviceTest, CarrierSmoothedPseudorangesAreFlaggedInNavSatAndNavSig) {
  const NavData nav = nominal_constellation(kT0);
  ReceiverParams rp;
  rp.measurement.carrier_smoothing_s = f9p_.carrier_smoothing_s;
  ASSERT_GT(rp.measurement.carrier_smoothing_s, 0.0);
  Receiver rx(nav, rp);
  UbxDevice d(f9p_, ReceiverMode::kStandalone, nav);
  set_items(d, {{"CFG-MSGOUT-UBX_NAV_SIG_UART1", 1}, {"CFG-MSGOUT-UBX_NAV_SAT_UART1", 1}});
  ImuTruth truth;
  truth.position = Geodetic{32.3, -90.9, 60.0};
  for (int k = 0; k < 3; ++k) {
    SCOPED_TRACE("epoch " + std::to_string(k));
    truth.t = kT0.plus_s(k);
    const ReceiverFix fix = rx.update(truth.t, &truth);
    std::string out;
    d.encode_epoch(fix, rx.measurements(), k, out);
    const std::vector<Frame> f = frames_of(out);
    ubx::NavSat sat;
    ubx::NavSig sig;
    ASSERT_TRUE(ubx::decode(of_type(f, ubx::kNavSat).at(0).payload, sat));
    ASSERT_TRUE(ubx::decode(of_type(f, ubx::kNavSig).at(0).payload, sig));
    ASSERT_EQ(sat.svs.size(), fix.satellites.size());
    int smoothed = 0;
    for (std::size_t i = 0; i < sat.svs.size(); ++i) {
      const bool expected = k > 0 && fix.satellites[i].used;
      EXPECT_EQ((sat.svs[i].flags & ubx::NavSatSv::kSmoothed) != 0, expected) << i;
      smoothed += expected;
    }
    int flagged = 0;
    for (const ubx::NavSigSignal& g : sig.signals)
      if (g.sig_flags & ubx::NavSigSignal::kPrSmoothed) {
        EXPECT_TRUE(g.sig_flags & ubx::NavSigSignal::kPrUsed);
        ++flagged;
      }
    EXPECT_EQ(flagged, smoothed);
    EXPECT_EQ(smoothed, k > 0 ? fix.num_used : 0);
  }
}

// The status messages of what navemu does not model say so as the part would: NAV-SBAS with SBAS
// on and no GEO (mode 1, system -1, no blocks) on both parts; NAV-DGPS (M8) reports PR + PRR
// corrections only in DGPS mode; TIM-VRFY has no time aiding (src 0) and carries the epoch's
// GPS week and time of week, the ones NAV-TIMEGPS reports.
TEST_F(UbxDeviceTest, SbasDgpsAndTimeVerificationStatus) {
  const auto polled = [](UbxDevice& d, ubx::MsgId id) {
    const std::vector<Frame> f = frames_of(send(d, poll(id)));
    EXPECT_EQ(f.size(), 1u);
    return f.empty() ? std::vector<std::uint8_t>{} : f[0].payload;
  };
  for (const GnssProfile* p : {&m8_, &f9p_}) {
    SCOPED_TRACE(p->name);
    UbxDevice d(*p, ReceiverMode::kStandalone, empty_nav());
    std::string epoch;
    d.encode_epoch(a_fix(kT0), EpochMeasurements{}, 0, epoch);
    ubx::NavSbas sbas;
    ASSERT_TRUE(ubx::decode(polled(d, ubx::kNavSbas), sbas));
    EXPECT_EQ(sbas.mode, 1);
    EXPECT_EQ(sbas.sys, -1);
    EXPECT_TRUE(sbas.svs.empty());
    ubx::TimVrfy vrfy;
    ubx::NavTimegps tg;
    ASSERT_TRUE(ubx::decode(polled(d, ubx::kTimVrfy), vrfy));
    ASSERT_TRUE(ubx::decode(polled(d, ubx::kNavTimegps), tg));
    EXPECT_EQ(vrfy.flags & 0x07, 0);
    EXPECT_EQ(vrfy.wno, static_cast<std::uint16_t>(tg.week));
    EXPECT_EQ(static_cast<std::uint32_t>(vrfy.i_tow_ms), tg.i_tow_ms);
    EXPECT_EQ(vrfy.delta_ms, 0);
  }
  for (ReceiverMode mode : {ReceiverMode::kStandalone, ReceiverMode::kDgps}) {
    UbxDevice d(m8_, mode, empty_nav());
    std::string epoch;
    d.encode_epoch(a_fix(kT0), EpochMeasurements{}, 0, epoch);
    ubx::NavDgps dgps;
    ASSERT_TRUE(ubx::decode(polled(d, ubx::kNavDgps), dgps));
    EXPECT_EQ(dgps.status, mode == ReceiverMode::kDgps ? 1 : 0);
  }
}

// The other systems' times of NAV-TIMEBDS/GAL/GLO and NAV-TIMELS at 2010-11-17 13:00:00 UTC
// (GPS - UTC = 15 s, GPS week 1610, Wednesday), worked by hand from the system definitions:
// BDT = GPST - 14 s, BDS week = GPS week - 1356 (BDS ICD 2.0 5.2.4.5); Galileo week = GPS week -
// 1024 (Galileo OS SIS ICD 5.1.2); GLONASS time = UTC + 3 h, day 1052 of the four-year
// interval 4 that began 1 January 2008 (366 + 365 + 321). Without satellites of a system the
// time is sent, not flagged valid.
TEST_F(UbxDeviceTest, TimeMessagesOfEverySystem) {
  UbxDevice d(f9p_, ReceiverMode::kStandalone, empty_nav());
  std::string epoch;
  d.encode_epoch(a_fix(kT0), EpochMeasurements{}, 0, epoch);
  const auto polled = [&](ubx::MsgId id) {
    const std::vector<Frame> f = frames_of(send(d, poll(id)));
    EXPECT_EQ(f.size(), 1u);
    return f.empty() ? std::vector<std::uint8_t>{} : f[0].payload;
  };
  const std::uint32_t gps_tow_s = 3 * 86400 + 13 * 3600 + 15;
  ubx::NavTimebds bds;
  ASSERT_TRUE(ubx::decode(polled(ubx::kNavTimebds), bds));
  EXPECT_EQ(bds.week, 1610 - 1356);
  EXPECT_EQ(bds.sow_s, gps_tow_s - 14);
  EXPECT_EQ(bds.f_sow_ns, 0);
  EXPECT_EQ(bds.leap_s, 1);
  EXPECT_EQ(bds.valid, 0);
  ubx::NavTimegal gal;
  ASSERT_TRUE(ubx::decode(polled(ubx::kNavTimegal), gal));
  EXPECT_EQ(gal.gal_wno, 1610 - 1024);
  EXPECT_EQ(gal.gal_tow_s, gps_tow_s);
  EXPECT_EQ(gal.leap_s, 15);
  ubx::NavTimeglo glo;
  ASSERT_TRUE(ubx::decode(polled(ubx::kNavTimeglo), glo));
  EXPECT_EQ(glo.tod_s, 16u * 3600u);
  EXPECT_EQ(glo.n4, 4);
  EXPECT_EQ(glo.nt_days, 1052);
  ubx::NavTimels ls;
  ASSERT_TRUE(ubx::decode(polled(ubx::kNavTimels), ls));
  EXPECT_EQ(ls.curr_ls_s, 15);
  EXPECT_EQ(ls.src_of_curr_ls, 2) << "GPS";
  EXPECT_EQ(ls.valid & ubx::NavTimels::kValidCurrLs, ubx::NavTimels::kValidCurrLs);
  EXPECT_EQ(ls.date_of_ls_gps_wn, 1610);
  EXPECT_EQ(ls.time_to_ls_event_s, -static_cast<std::int32_t>(gps_tow_s - 86400)) << "end of day 1, passed";
}

// MON-MSGPP and MON-IO count what a port received and sent: UBX frames and NMEA sentences read,
// bytes that were part of neither, bytes of the replies.
TEST_F(UbxDeviceTest, MonitorMessagesCountEachPortsTraffic) {
  UbxDevice d(m8_, ReceiverMode::kStandalone, empty_nav());
  const std::vector<std::uint8_t> ver = poll(ubx::kMonVer);
  const std::string junk = "xyz";
  const std::string sentence = "$PUBX,00*33\r\n";
  std::vector<std::uint8_t> in = ver;
  in.insert(in.end(), junk.begin(), junk.end());
  in.insert(in.end(), sentence.begin(), sentence.end());
  const std::string replies = send(d, in);
  const std::vector<Frame> f = frames_of(send(d, poll(ubx::kMonMsgpp)));
  ASSERT_EQ(f.size(), 1u);
  ubx::MonMsgpp pp;
  ASSERT_TRUE(ubx::decode(f[0].payload, pp));
  EXPECT_EQ(pp.msg2[0], 2) << "UART1 UBX: the MON-VER poll and this one";
  EXPECT_EQ(pp.msg2[1], 1) << "UART1 NMEA";
  EXPECT_EQ(pp.skipped_bytes[1], junk.size());
  EXPECT_EQ(pp.msg4[0], 0) << "nothing on USB";

  const std::vector<std::uint8_t> io_poll = poll(ubx::kMonIo);
  const std::vector<Frame> io_f = frames_of(send(d, io_poll));
  ASSERT_EQ(io_f.size(), 1u);
  ubx::MonIo io;
  ASSERT_TRUE(ubx::decode(io_f[0].payload, io));
  ASSERT_EQ(io.ports.size(), ubx::kNumPorts);
  EXPECT_EQ(io.ports[1].rx_bytes, in.size() + 2 * ver.size());
  EXPECT_GT(io.ports[1].tx_bytes, replies.size());
  EXPECT_EQ(io.ports[3].rx_bytes, 0u);
}

// NAV-ODO: with the odometer on (CFG-ODO-USE_ODO), 10 s at 5 m/s ground speed count 50 m, a
// parked receiver's velocity noise nothing; NAV-RESETODO clears the distance, not the total.
TEST_F(UbxDeviceTest, OdometerCountsGroundDistance) {
  UbxDevice d(f9p_, ReceiverMode::kStandalone, empty_nav());
  set_items(d, {{"CFG-MSGOUT-UBX_NAV_ODO_UART1", 1}});
  const auto run = [&](int seconds, Vec3 v_ned, std::int64_t& k) {
    ubx::NavOdo m;
    for (int i = 0; i <= seconds; ++i, ++k) {
      ReceiverFix fix = a_fix(kT0.plus_s(static_cast<double>(k)));
      fix.v_ned_mps = v_ned;
      std::string out;
      d.encode_epoch(fix, EpochMeasurements{}, k, out);
      const std::vector<Frame> f = of_type(frames_of(out), ubx::kNavOdo);
      EXPECT_EQ(f.size(), 1u);
      if (!f.empty()) {
        EXPECT_TRUE(ubx::decode(f[0].payload, m));
      }
    }
    return m;
  };
  std::int64_t k = 0;
  EXPECT_EQ(run(10, Vec3(3.0, 4.0, 0.0), k).distance_m, 0u) << "the odometer is off by default";
  set_items(d, {{"CFG-ODO-USE_ODO", 1}});
  EXPECT_EQ(run(10, Vec3(3.0, 4.0, 0.0), k).distance_m, 50u);
  EXPECT_EQ(run(10, Vec3(0.03, -0.04, 0.02), k).distance_m, 50u) << "parked";
  EXPECT_TRUE(only_ack(send(d, poll(ubx::kNavResetodo)), ubx::kNavResetodo));
  const ubx::NavOdo after = run(0, Vec3::Zero(), k);
  EXPECT_EQ(after.distance_m, 0u);
  EXPECT_EQ(after.total_distance_m, 50u);
}

// The jamming state of MON-RF is "unknown or disabled" (0) with the interference monitor off,
// its default, as a ZED-F9T reports it in ../shared/data; "ok" (1) once CFG-ITFM-ENABLE is set.
// MON-GNSS reports the constellations CFG-SIGNAL enables.
TEST_F(UbxDeviceTest, MonitorsFollowTheirConfiguration) {
  UbxDevice d(f9p_, ReceiverMode::kStandalone, empty_nav());
  std::string out;
  d.encode_epoch(a_fix(kT0), EpochMeasurements{}, 0, out);
  const auto jamming = [&] {
    const std::vector<Frame> f = frames_of(send(d, poll(ubx::kMonRf)));
    ubx::MonRf r;
    EXPECT_TRUE(f.size() == 1 && ubx::decode(f[0].payload, r) && r.blocks.size() == 2);
    return r.blocks.empty() ? -1 : r.blocks[0].flags & ubx::MonRfBlock::kJammingStateMask;
  };
  EXPECT_EQ(jamming(), 0);
  set_items(d, {{"CFG-ITFM-ENABLE", 1}});
  EXPECT_EQ(jamming(), 1);

  const auto gnss = [&] {
    const std::vector<Frame> f = frames_of(send(d, poll(ubx::kMonGnss)));
    ubx::MonGnss g;
    EXPECT_TRUE(f.size() == 1 && ubx::decode(f[0].payload, g));
    return g;
  };
  EXPECT_EQ(gnss().enabled, 0x0F);
  set_items(d, {{"CFG-SIGNAL-GLO_ENA", 0}});
  EXPECT_EQ(gnss().enabled, 0x0D);
  EXPECT_EQ(gnss().supported, 0x0F);
  // The systems the receiver tracks follow: a GNSS is off with its enable or its L1 signal's.
  const auto tracked = [&](GnssSystem s) { return (d.engine_settings()->systems & system_bit(s)) != 0; };
  EXPECT_FALSE(tracked(GnssSystem::kGlonass));
  EXPECT_TRUE(tracked(GnssSystem::kGalileo));
  set_items(d, {{"CFG-SIGNAL-GAL_E1_ENA", 0}});
  EXPECT_FALSE(tracked(GnssSystem::kGalileo));
  EXPECT_EQ(gnss().enabled, 0x05);
  EXPECT_TRUE(tracked(GnssSystem::kGps));
  EXPECT_TRUE(tracked(GnssSystem::kBeidou));
  EXPECT_TRUE(tracked(GnssSystem::kQzss));
  // The second band follows its signal's item: BeiDou B2I off at power-up (the part's default),
  // switched on; GPS L2C switched off.
  const auto on_l2 = [&](GnssSystem s) { return (d.engine_settings()->l2_systems & system_bit(s)) != 0; };
  EXPECT_TRUE(on_l2(GnssSystem::kGps));
  EXPECT_FALSE(on_l2(GnssSystem::kBeidou));
  set_items(d, {{"CFG-SIGNAL-BDS_B2_ENA", 1}, {"CFG-SIGNAL-GPS_L2C_ENA", 0}});
  EXPECT_TRUE(on_l2(GnssSystem::kBeidou));
  EXPECT_FALSE(on_l2(GnssSystem::kGps));
  EXPECT_TRUE(tracked(GnssSystem::kGps));
}

// CFG-GNSS (M8 receiver description 32.10.12 "Configuration requirements"; deprecated on the F9,
// a view of its CFG-SIGNAL items): a poll lists every supported system; a valid set applies at
// once (the systems tracked follow), an invalid one is refused and changes nothing.
TEST_F(UbxDeviceTest, CfgGnssSwitchesSystemsWithTheRequirementsChecked) {
  const auto polled = [&](UbxDevice& d) {
    const std::vector<Frame> f = frames_of(send(d, poll(ubx::kCfgGnss)));
    ubx::CfgGnss g;
    EXPECT_TRUE(!f.empty() && ubx::decode(f[0].payload, g));
    std::map<int, std::uint32_t> flags;
    for (const ubx::CfgGnssBlock& b : g.blocks) flags[b.gnss_id] = b.flags;
    return flags;
  };
  const auto one_block = [](std::uint8_t gnss_id, bool on, std::uint8_t sig = 0x01) {
    ubx::CfgGnss g;
    g.num_trk_ch_use = 0xFF;
    g.blocks = {{gnss_id, 4, 8, 0, (on ? ubx::CfgGnssBlock::kEnable : 0u) | static_cast<std::uint32_t>(sig) << 16}};
    return frame(g);
  };
  const auto tracked = [](UbxDevice& d, GnssSystem s) { return (d.engine_settings()->systems & system_bit(s)) != 0; };

  UbxDevice f9(f9p_, ReceiverMode::kStandalone, empty_nav());
  std::map<int, std::uint32_t> flags = polled(f9);
  EXPECT_EQ(flags.size(), 6u);  // GPS, SBAS, Galileo, BeiDou, QZSS, GLONASS
  EXPECT_EQ(flags[0], 0x00110001u);  // GPS: L1C/A and L2C
  EXPECT_EQ(flags[2], 0x00210001u);  // Galileo: E1 and E5b
  EXPECT_TRUE(only_ack(send(f9, one_block(2, false)), ubx::kCfgGnss));
  EXPECT_FALSE(tracked(f9, GnssSystem::kGalileo));
  EXPECT_EQ(polled(f9)[2] & ubx::CfgGnssBlock::kEnable, 0u);
  const std::uint32_t gal_ena = ubx::find_config_key("CFG-SIGNAL-GAL_ENA")->id;
  EXPECT_EQ(valget_items(f9, {gal_ena})[gal_ena], 0u) << "the set is the CFG-SIGNAL items";
  EXPECT_TRUE(tracked(f9, GnssSystem::kGps));

  UbxDevice m8(m8_, ReceiverMode::kStandalone, empty_nav());
  flags = polled(m8);
  EXPECT_EQ(flags.size(), 7u);  // and IMES
  EXPECT_TRUE(tracked(m8, GnssSystem::kGlonass));
  EXPECT_FALSE(tracked(m8, GnssSystem::kGalileo));
  EXPECT_TRUE(only_ack(send(m8, one_block(2, true)), ubx::kCfgGnss));  // GPS, GLONASS, Galileo
  EXPECT_TRUE(tracked(m8, GnssSystem::kGalileo));
  EXPECT_NE(polled(m8)[2] & ubx::CfgGnssBlock::kEnable, 0u);
  // A fourth major GNSS at once is more than the u-blox 8 runs (MON-GNSS simultaneous 3).
  EXPECT_TRUE(only_ack(send(m8, one_block(3, true)), ubx::kCfgGnss, true));
  EXPECT_FALSE(tracked(m8, GnssSystem::kBeidou));
  // An enabled major GNSS without a signal, or none enabled at all, is refused too.
  EXPECT_TRUE(only_ack(send(m8, one_block(6, true, 0x00)), ubx::kCfgGnss, true));
  EXPECT_TRUE(only_ack(send(m8, one_block(0, false)), ubx::kCfgGnss));
  EXPECT_TRUE(only_ack(send(m8, one_block(2, false)), ubx::kCfgGnss));
  EXPECT_TRUE(only_ack(send(m8, one_block(6, false)), ubx::kCfgGnss, true));
  EXPECT_TRUE(tracked(m8, GnssSystem::kGlonass));
  EXPECT_FALSE(tracked(m8, GnssSystem::kGps));
}

// ---- The navigation engine's configuration (CFG-NAVSPG, CFG-NAV5) ----------------------------

// The items as the engine takes them (ZED-F9P integration manual UBX-18010802, 3.1.7): masks,
// fix mode and fixed altitude, and the dynamic platform's limits from its table ("Dynamic
// platform model details"); the airborne models give no 2D fix.
TEST_F(UbxDeviceTest, NavigationEngineSettingsFollowNavspgItems) {
  UbxDevice d(f9p_, ReceiverMode::kStandalone, empty_nav());
  const NavEngineSettings* e = d.engine_settings();
  ASSERT_NE(e, nullptr);
  EXPECT_EQ(e->elevation_mask_deg, f9p_.elevation_mask_deg) << "the profile's mask is the default";
  EXPECT_EQ(e->min_cn0_dbhz, 6.0);
  EXPECT_EQ(e->cn0_threshold_sats, 0);
  EXPECT_EQ(e->fix_mode, SolverFixMode::kAuto);
  EXPECT_EQ(e->max_height_msl_m, 12000.0) << "portable";
  EXPECT_EQ(e->max_h_speed_mps, 310.0);
  EXPECT_EQ(e->max_v_speed_mps, 50.0);
  EXPECT_FALSE(e->zero_velocity);

  set_items(d, {{"CFG-NAVSPG-INFIL_MINELEV", 0xF6},  // I1 -10
                {"CFG-NAVSPG-INFIL_MINCNO", 30},
                {"CFG-NAVSPG-INFIL_NCNOTHRS", 4},
                {"CFG-NAVSPG-INFIL_CNOTHRS", 35},
                {"CFG-NAVSPG-FIXMODE", 1},
                {"CFG-NAVSPG-CONSTR_ALT", 0xFFFFFC18},  // I4 -1000 cm
                {"CFG-NAVSPG-DYNMODEL", 2}});
  e = d.engine_settings();
  EXPECT_EQ(e->elevation_mask_deg, -10.0);
  EXPECT_EQ(e->min_cn0_dbhz, 30.0);
  EXPECT_EQ(e->cn0_threshold_sats, 4);
  EXPECT_EQ(e->cn0_threshold_dbhz, 35.0);
  EXPECT_EQ(e->fix_mode, SolverFixMode::k2DOnly);
  EXPECT_DOUBLE_EQ(e->fixed_height_msl_m, -10.0);
  EXPECT_EQ(e->max_h_speed_mps, 10.0) << "stationary";
  EXPECT_EQ(e->max_v_speed_mps, 6.0);
  EXPECT_TRUE(e->zero_velocity);

  set_items(d, {{"CFG-NAVSPG-DYNMODEL", 7}, {"CFG-NAVSPG-FIXMODE", 3}});  // airborne < 2g, auto
  EXPECT_EQ(d.engine_settings()->fix_mode, SolverFixMode::k3DOnly);
  EXPECT_EQ(d.engine_settings()->max_height_msl_m, 50000.0);
  EXPECT_TRUE(std::isinf(d.engine_settings()->max_h_speed_mps)) << "altitude checked only";
  EXPECT_FALSE(d.engine_settings()->zero_velocity);
}

// The u-blox 8's CFG-NAV5 sets the same items, each group only where its mask bit says so
// (UBX-13003221 CFG-NAV5), and the poll reads every field back.
TEST_F(UbxDeviceTest, CfgNav5SetsTheMaskedFieldsAndPollsThemAll) {
  UbxDevice d(m8_, ReceiverMode::kStandalone, empty_nav());
  const auto poll_nav5 = [&] {
    const std::vector<Frame> f = frames_of(send(d, poll(ubx::kCfgNav5)));
    ubx::CfgNav5 n;
    EXPECT_TRUE(f.size() == 2 && is_ack(f[1], ubx::kCfgNav5) && ubx::decode(f[0].payload, n));
    return n;
  };
  const ubx::CfgNav5 before = poll_nav5();
  EXPECT_EQ(before.fix_mode, 3);
  EXPECT_EQ(before.p_dop_0p1, 250);
  EXPECT_EQ(before.p_acc_m, 100);

  ubx::CfgNav5 set;
  set.mask = ubx::CfgNav5::kMaskDyn | ubx::CfgNav5::kMaskMinEl | ubx::CfgNav5::kMaskPosFixMode |
             ubx::CfgNav5::kMaskCnoThreshold;
  set.dyn_model = ubx::CfgNav5::kDynPedestrian;
  set.min_elev_deg = -5;
  set.fix_mode = 2;
  set.fixed_alt_cm = -1000;
  set.fixed_alt_var_1e4m2 = 20000;
  set.cno_thresh_num_svs = 5;
  set.cno_thresh_dbhz = 33;
  set.p_dop_0p1 = 50;  // not masked: stays
  EXPECT_TRUE(only_ack(send(d, frame(set)), ubx::kCfgNav5));
  const ubx::CfgNav5 after = poll_nav5();
  EXPECT_EQ(after.dyn_model, ubx::CfgNav5::kDynPedestrian);
  EXPECT_EQ(after.min_elev_deg, -5);
  EXPECT_EQ(after.fix_mode, 2);
  EXPECT_EQ(after.fixed_alt_cm, -1000);
  EXPECT_EQ(after.fixed_alt_var_1e4m2, 20000u);
  EXPECT_EQ(after.cno_thresh_num_svs, 5);
  EXPECT_EQ(after.cno_thresh_dbhz, 33);
  EXPECT_EQ(after.p_dop_0p1, 250);
  const NavEngineSettings& e = *d.engine_settings();
  EXPECT_EQ(e.elevation_mask_deg, -5.0);
  EXPECT_EQ(e.fix_mode, SolverFixMode::k3DOnly);
  EXPECT_EQ(e.cn0_threshold_sats, 5);
  EXPECT_EQ(e.max_h_speed_mps, 30.0) << "pedestrian";

  set.mask = ubx::CfgNav5::kMaskPosFixMode;
  set.fix_mode = 0;  // not a fix mode
  EXPECT_TRUE(only_ack(send(d, frame(set)), ubx::kCfgNav5, true));
  EXPECT_EQ(poll_nav5().fix_mode, 2);
}

// The settings acting on the receiver's fix over the nominal constellation: the masks choose the
// satellites used, too few strong satellites give no fix, 2D-only holds the fixed altitude, the
// platform's speed limit invalidates a fix, the stationary platform reports no velocity; NAV-SAT
// carries the residual of each used satellite.
TEST_F(UbxDeviceTest, NavigationEngineSettingsActOnTheFix) {
  const NavData nav = nominal_constellation(kT0);
  ReceiverParams rp;
  rp.measurement.elevation_mask_deg = f9p_.elevation_mask_deg;
  Receiver rx(nav, rp);
  UbxDevice d(f9p_, ReceiverMode::kStandalone, nav);
  set_items(d, {{"CFG-MSGOUT-UBX_NAV_SAT_UART1", 1}});
  ImuTruth truth;
  truth.position = Geodetic{32.3, -90.9, 60.0};
  double t_s = 0.0;
  const auto epoch = [&](const Vec3& v_ned_mps = Vec3::Zero()) {
    t_s += 1.0;
    truth.t = kT0.plus_s(t_s);
    truth.v_ned_mps = v_ned_mps;
    rx.set_engine(*d.engine_settings());
    return rx.update(truth.t, &truth);
  };
  const auto used_count = [](const ReceiverFix& f) {
    return std::count_if(f.satellites.begin(), f.satellites.end(), [](const ReceiverSatellite& s) { return s.used; });
  };

  ReceiverFix fix = epoch();
  ASSERT_EQ(fix.fix, FixType::k3D);
  const auto all_used = used_count(fix);
  ASSERT_GE(all_used, 6);
  double sum_sq = 0.0;
  for (const ReceiverSatellite& s : fix.satellites) {
    if (s.used) {
      EXPECT_GE(s.el_deg, f9p_.elevation_mask_deg);
      EXPECT_NE(s.residual_m, 0.0);
    }
    sum_sq += s.residual_m * s.residual_m;
  }
  EXPECT_NEAR(std::sqrt(sum_sq / static_cast<double>(all_used)), fix.range_rms_m, 1e-9);
  std::string out;
  d.encode_epoch(fix, rx.measurements(), 1, out);
  const std::vector<Frame> sat = of_type(frames_of(out), ubx::kNavSat);
  ASSERT_EQ(sat.size(), 1u);
  ubx::NavSat ns;
  ASSERT_TRUE(ubx::decode(sat[0].payload, ns));
  ASSERT_EQ(ns.svs.size(), fix.satellites.size());
  for (std::size_t i = 0; i < ns.svs.size(); ++i)
    EXPECT_EQ(ns.svs[i].pr_res_dm, std::lround(fix.satellites[i].residual_m * 10.0)) << i;

  set_items(d, {{"CFG-NAVSPG-INFIL_MINELEV", 30}});
  fix = epoch();
  ASSERT_EQ(fix.fix, FixType::k3D);
  EXPECT_LT(used_count(fix), all_used);
  for (const ReceiverSatellite& s : fix.satellites) EXPECT_EQ(s.used, s.el_deg >= 30.0) << s.el_deg;

  // A C/N0 mask that leaves the five strongest satellites (a fix needs four), whole dB-Hz.
  set_items(d, {{"CFG-NAVSPG-INFIL_MINELEV", 10}});
  fix = epoch();
  std::vector<double> cn0;
  for (const ReceiverSatellite& s : fix.satellites)
    if (s.used) cn0.push_back(s.cn0_dbhz);
  std::sort(cn0.rbegin(), cn0.rend());
  ASSERT_GE(cn0.size(), 6u);
  const auto mask_dbhz = static_cast<std::uint64_t>(std::floor(cn0[4]));
  set_items(d, {{"CFG-NAVSPG-INFIL_MINCNO", mask_dbhz}});
  fix = epoch();
  ASSERT_EQ(fix.fix, FixType::k3D);
  EXPECT_LT(used_count(fix), all_used);
  for (const ReceiverSatellite& s : fix.satellites) {
    if (s.el_deg >= 10.0) {
      EXPECT_EQ(s.used, s.cn0_dbhz >= static_cast<double>(mask_dbhz)) << s.cn0_dbhz;
    }
  }

  // More strong satellites asked for than there are: no fix attempted.
  set_items(d, {{"CFG-NAVSPG-INFIL_MINCNO", 6}, {"CFG-NAVSPG-INFIL_NCNOTHRS", 40}, {"CFG-NAVSPG-INFIL_CNOTHRS", 10}});
  EXPECT_EQ(epoch().fix, FixType::kNone);
  set_items(d, {{"CFG-NAVSPG-INFIL_NCNOTHRS", 4}});
  EXPECT_EQ(epoch().fix, FixType::k3D);

  // 2D only: the height is the fixed altitude (no geoid here: MSL = ellipsoidal).
  set_items(d, {{"CFG-NAVSPG-FIXMODE", 1}, {"CFG-NAVSPG-CONSTR_ALT", 10000}});
  fix = epoch();
  ASSERT_EQ(fix.fix, FixType::k2D);
  EXPECT_NEAR(fix.position.h_m, 100.0, 0.5) << "the truth is at 60 m";
  set_items(d, {{"CFG-NAVSPG-FIXMODE", 3}});

  // Pedestrian: 30 m/s at most (horizontal).
  set_items(d, {{"CFG-NAVSPG-DYNMODEL", 3}});
  EXPECT_EQ(epoch(Vec3(20.0, 0.0, 0.0)).fix, FixType::k3D);
  EXPECT_EQ(epoch(Vec3(40.0, 0.0, 0.0)).fix, FixType::kNone);
  EXPECT_EQ(epoch(Vec3(0.0, 0.0, -25.0)).fix, FixType::kNone) << "20 m/s vertical at most";

  // Stationary: the velocity is restricted to 0.
  set_items(d, {{"CFG-NAVSPG-DYNMODEL", 2}});
  fix = epoch(Vec3(3.0, 4.0, 0.0));
  ASSERT_EQ(fix.fix, FixType::k3D);
  ASSERT_TRUE(fix.v_ned_mps);
  EXPECT_EQ(fix.v_ned_mps->norm(), 0.0);
}

// The u-blox 8's switches are legacy messages (UBX-13003221): CFG-ITFM with config bit 31 turns
// the jamming monitor on (MON-HW jammingState 1 "ok"), CFG-ODO with flags bit 0 the odometer;
// both off at power-up, both kept over a reset only when saved.
TEST_F(UbxDeviceTest, U8MonitorsFollowLegacyCfgItfmAndOdo) {
  UbxDevice d(m8_, ReceiverMode::kStandalone, empty_nav());
  ASSERT_TRUE(only_ack(send(d, frame(ubx::CfgMsgCurrentPort{ubx::kNavOdo.cls, ubx::kNavOdo.id, 1})), ubx::kCfgMsg));
  std::int64_t k = 0;
  const auto epoch = [&] {  // 5 m/s north for one second
    ReceiverFix fix = a_fix(kT0.plus_s(static_cast<double>(k)));
    fix.v_ned_mps = Vec3(5.0, 0.0, 0.0);
    std::string out;
    d.encode_epoch(fix, EpochMeasurements{}, k++, out);
    const std::vector<Frame> f = of_type(frames_of(out), ubx::kNavOdo);
    ubx::NavOdo m;
    EXPECT_TRUE(f.size() == 1 && ubx::decode(f[0].payload, m));
    return m.distance_m;
  };
  const auto jamming = [&] {
    const std::vector<Frame> f = frames_of(send(d, poll(ubx::kMonHw)));
    ubx::MonHw m;
    EXPECT_TRUE(f.size() == 1 && ubx::decode(f[0].payload, m));
    return (m.flags >> 2) & 0x03;
  };
  epoch();
  EXPECT_EQ(jamming(), 0);
  EXPECT_EQ(epoch(), 0u);

  ubx::CfgItfm itfm;
  itfm.config = ubx::CfgItfm::kEnable | 0x16B156;  // the description's recommended thresholds
  itfm.config2 = 0x31E;
  EXPECT_TRUE(only_ack(send(d, frame(itfm)), ubx::kCfgItfm));
  EXPECT_EQ(jamming(), 1);
  ubx::CfgOdo odo;
  odo.flags = ubx::CfgOdo::kUseOdo;
  EXPECT_TRUE(only_ack(send(d, frame(odo)), ubx::kCfgOdo));
  epoch();
  EXPECT_EQ(epoch(), 5u);
  EXPECT_EQ(epoch(), 10u);

  ubx::CfgRst hot;  // not saved: gone after a hardware reset
  hot.nav_bbr_mask = ubx::CfgRst::kHotStart;
  hot.reset_mode = ubx::CfgRst::kHardwareReset;
  send(d, frame(hot));
  EXPECT_EQ(jamming(), 0);
}

// A jammer on the band moves the front end's monitors (models/interference.hpp): on the F9P's
// L1 block of MON-RF, the AGC falls and the noise level rises; the L2 block keeps its open-sky
// readings. jammingState (UBX-13003221 "UBX-MON-HW"; F9 "UBX-MON-RF") is 2 "interference
// visible but fix OK" with a fix and 3 "critical" without one, once J/N exceeds CFG-ITFM's
// broadband threshold, else 1 "ok". A CW jammer raises jamInd against the CW threshold; the
// u-blox 8 reports the same in MON-HW through its legacy CFG-ITFM.
TEST_F(UbxDeviceTest, MonitorsShowTheJammerOnTheirBand) {
  UbxDevice d(f9p_, ReceiverMode::kStandalone, empty_nav());
  set_items(d, {{"CFG-ITFM-ENABLE", 1}});
  EpochMeasurements jammed;
  jammed.interference[0].add(40.0, InterferenceKind::kWideband);  // J/N 20.4 dB
  const auto rf = [&](const ReceiverFix& fix, const EpochMeasurements& meas) {
    std::string out;
    d.encode_epoch(fix, meas, 0, out);
    const std::vector<Frame> f = frames_of(send(d, poll(ubx::kMonRf)));
    ubx::MonRf r;
    EXPECT_TRUE(f.size() == 1 && ubx::decode(f[0].payload, r) && r.blocks.size() == 2);
    return r;
  };
  const ubx::MonRf clear = rf(a_fix(kT0), EpochMeasurements{});
  const ubx::MonRf with_fix = rf(a_fix(kT0), jammed);
  EXPECT_EQ(clear.blocks[0].flags & ubx::MonRfBlock::kJammingStateMask, 1);
  EXPECT_EQ(with_fix.blocks[0].flags & ubx::MonRfBlock::kJammingStateMask, 2);
  EXPECT_EQ(with_fix.blocks[1].flags & ubx::MonRfBlock::kJammingStateMask, 1) << "no jammer on L2";
  EXPECT_LT(with_fix.blocks[0].agc_cnt + 2000, clear.blocks[0].agc_cnt);
  EXPECT_GT(with_fix.blocks[0].noise_per_ms, 50 * clear.blocks[0].noise_per_ms);
  EXPECT_EQ(with_fix.blocks[0].jam_ind, clear.blocks[0].jam_ind) << "broadband, not CW";
  EXPECT_EQ(with_fix.blocks[1].agc_cnt, clear.blocks[1].agc_cnt);
  EXPECT_EQ(with_fix.blocks[1].noise_per_ms, clear.blocks[1].noise_per_ms);
  ReceiverFix none = a_fix(kT0);
  none.fix = FixType::kNone;
  EXPECT_EQ(rf(none, jammed).blocks[0].flags & ubx::MonRfBlock::kJammingStateMask, 3);
  set_items(d, {{"CFG-ITFM-BBTHRESHOLD", 15}});  // J/N 20.4 dB still above; J/N 10.4 dB not
  EXPECT_EQ(rf(a_fix(kT0), jammed).blocks[0].flags & ubx::MonRfBlock::kJammingStateMask, 2);
  EpochMeasurements weaker;
  weaker.interference[0].add(30.0, InterferenceKind::kWideband);
  EXPECT_EQ(rf(a_fix(kT0), weaker).blocks[0].flags & ubx::MonRfBlock::kJammingStateMask, 1);
  EpochMeasurements cw;
  cw.interference[0].add(30.0, InterferenceKind::kCw);  // CW J/N 10.4 dB: below 15 dB
  const ubx::MonRf cw_rf = rf(a_fix(kT0), cw);
  EXPECT_EQ(cw_rf.blocks[0].jam_ind, clear.blocks[0].jam_ind + 52);
  EXPECT_EQ(cw_rf.blocks[0].flags & ubx::MonRfBlock::kJammingStateMask, 1);
  set_items(d, {{"CFG-ITFM-CWTHRESHOLD", 10}});
  EXPECT_EQ(rf(a_fix(kT0), cw).blocks[0].flags & ubx::MonRfBlock::kJammingStateMask, 2);

  UbxDevice m8(m8_, ReceiverMode::kStandalone, empty_nav());
  ubx::CfgItfm itfm;
  itfm.config = ubx::CfgItfm::kEnable | 3 | 15 << 4;  // bbThreshold 3 dB, cwThreshold 15 dB
  ASSERT_TRUE(only_ack(send(m8, frame(itfm)), ubx::kCfgItfm));
  std::string out;
  m8.encode_epoch(a_fix(kT0), jammed, 0, out);
  const std::vector<Frame> f = frames_of(send(m8, poll(ubx::kMonHw)));
  ubx::MonHw hw;
  ASSERT_TRUE(f.size() == 1 && ubx::decode(f[0].payload, hw));
  EXPECT_EQ((hw.flags >> 2) & 0x03, 2);
  EXPECT_EQ(hw.agc_cnt, with_fix.blocks[0].agc_cnt);
  EXPECT_EQ(hw.noise_per_ms, with_fix.blocks[0].noise_per_ms);
}

// An antenna fault of the measurements (an `events:` antenna event) is what the antenna
// supervisor reports: MON-RF antStatus / antPower and MON-HW aStatus / aPower (F9 interface
// description UBX-MON-HW: 2 OK, 3 SHORT, 4 OPEN; power 0 OFF, 1 ON), the supply off on a short.
TEST_F(UbxDeviceTest, MonitorsShowTheAntennaSupervisorsState) {
  for (const auto& [fault, status, power] :
       {std::tuple<std::optional<AntennaFault>, int, int>{std::nullopt, 2, 1}, {AntennaFault::kOpen, 4, 1},
        {AntennaFault::kShort, 3, 0}}) {
    EpochMeasurements meas;
    meas.antenna_fault = fault;
    UbxDevice f9p(f9p_, ReceiverMode::kStandalone, empty_nav());
    std::string out;
    f9p.encode_epoch(a_fix(kT0), meas, 0, out);
    const std::vector<Frame> rf = frames_of(send(f9p, poll(ubx::kMonRf)));
    ubx::MonRf r;
    ASSERT_TRUE(rf.size() == 1 && ubx::decode(rf[0].payload, r) && r.blocks.size() == 2);
    for (const ubx::MonRfBlock& b : r.blocks) {
      EXPECT_EQ(b.ant_status, status);
      EXPECT_EQ(b.ant_power, power);
    }
    UbxDevice m8(m8_, ReceiverMode::kStandalone, empty_nav());
    m8.encode_epoch(a_fix(kT0), meas, 0, out);
    const std::vector<Frame> hw = frames_of(send(m8, poll(ubx::kMonHw)));
    ubx::MonHw h;
    ASSERT_TRUE(hw.size() == 1 && ubx::decode(hw[0].payload, h));
    EXPECT_EQ(h.a_status, status);
    EXPECT_EQ(h.a_power, power);
  }
}

// ---- NMEA input (emulator/ubx_nmea_input.cpp) ------------------------------------------------
// Sentences from the u-blox 8 receiver description (UBX-13003221) "PUBX Messages" and the F9
// interface descriptions' polls ($PUBX,00*33, $PUBX,04*37, $EIGPQ,RMC*3A); others with their
// checksums computed by hand (XOR of the bytes between '$' and '*').

std::string send_nmea(UbxDevice& d, std::string_view sentence, ReceiverPort port = ReceiverPort::kUart1) {
  std::string replies;
  d.receive(std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(sentence.data()), sentence.size()),
            port, replies);
  return replies;
}

// What `port` sends at epoch k (the same fix each time).
std::string epoch_output(UbxDevice& d, std::int64_t k, ReceiverPort port = ReceiverPort::kUart1) {
  d.update(a_fix(kT0.plus_s(static_cast<double>(k))), EpochMeasurements{}, k);
  std::string out;
  d.encode(port, out);
  return out;
}

// A sentence's fields after the address, "$PUBX,04,a,b*cs\r\n" -> {"PUBX", "04", "a", "b"}.
std::vector<std::string> fields_of(const std::string& sentence) {
  std::vector<std::string> f(1);
  for (char c : sentence.substr(1, sentence.find('*') - 1)) {
    if (c == ',') f.emplace_back();
    else f.back() += c;
  }
  return f;
}

ubx::CfgPrt cfg_prt_of(UbxDevice& d, std::uint8_t port) {
  const std::vector<Frame> f = frames_of(send(d, frame(ubx::CfgPrtPoll{true, port})));
  ubx::CfgPrt prt;
  EXPECT_TRUE(!f.empty() && ubx::decode(f[0].payload, prt));
  return prt;
}

// PUBX,41 with in and out masks of UBX only on UART1 (what an autopilot's driver sends): no
// reply (NMEA input has no acknowledgement), the baud handed to the transport once, from the
// next epoch no NMEA on UART1 while UBX goes on, USB untouched; NMEA input on UART1 is off now,
// so a PUBX,41 turning NMEA back on is ignored, a CFG-PRT is not.
TEST_F(UbxDeviceTest, PubxConfigUbxOnlyStopsNmeaOnThatPort) {
  for (const GnssProfile* p : {&m8_, &f9p_}) {
    SCOPED_TRACE(p->ubx->protver);
    UbxDevice d(*p, ReceiverMode::kStandalone, empty_nav());
    EXPECT_TRUE(only_ack(send(d, frame(ubx::CfgMsgCurrentPort{0x01, 0x07, 1})), ubx::kCfgMsg));
    EXPECT_NE(epoch_output(d, 0).find("$GNGGA"), std::string::npos);
    EXPECT_EQ(send_nmea(d, "$PUBX,41,1,0001,0001,38400,0*24\r\n"), "");
    EXPECT_EQ(d.take_baud_change(ReceiverPort::kUart1), p->baud == 38400 ? std::nullopt : std::optional<int>(38400));
    EXPECT_EQ(d.take_baud_change(ReceiverPort::kUart1), std::nullopt);
    const std::string out = epoch_output(d, 1);
    EXPECT_EQ(out.find('$'), std::string::npos) << "no NMEA after PUBX,41 with outProto UBX";
    EXPECT_EQ(of_type(frames_of(out), ubx::kNavPvt).size(), 1u);
    EXPECT_NE(epoch_output(d, 2, ReceiverPort::kUsb).find("$GNGGA"), std::string::npos) << "USB keeps NMEA";
    const ubx::CfgPrt prt = cfg_prt_of(d, ubx::kPortUart1);
    EXPECT_EQ(prt.in_proto_mask, ubx::kProtoUbx);
    EXPECT_EQ(prt.out_proto_mask, ubx::kProtoUbx);
    EXPECT_EQ(prt.baud_rate, 38400u);
    EXPECT_EQ(d.counters().nmea_commands, 1u);

    EXPECT_EQ(send_nmea(d, "$PUBX,41,1,0003,0003,9600,0*14\r\n"), "");
    EXPECT_EQ(d.counters().nmea_ignored, 1u) << "NMEA is no input protocol of UART1 any more";
    EXPECT_EQ(epoch_output(d, 3).find('$'), std::string::npos);
    ubx::CfgPrt back = prt;
    back.in_proto_mask = back.out_proto_mask = ubx::kProtoUbx | ubx::kProtoNmea;
    EXPECT_TRUE(only_ack(send(d, frame(back)), ubx::kCfgPrt));
    EXPECT_NE(epoch_output(d, 4).find("$GNGGA"), std::string::npos);
  }
}

// The description's example $PUBX,41,1,0007,0003,19200,0*25 (in UBX+NMEA+RTCM, out UBX+NMEA,
// 19200 baud); sent over USB it configures UART1, and a PUBX,41 for USB sets USB's masks and
// has no baud.
TEST_F(UbxDeviceTest, PubxConfigDescriptionExampleAndOtherPorts) {
  UbxDevice d(f9p_, ReceiverMode::kStandalone, empty_nav());
  EXPECT_EQ(send_nmea(d, "$PUBX,41,1,0007,0003,19200,0*25\r\n", ReceiverPort::kUsb), "");
  EXPECT_EQ(d.take_baud_change(ReceiverPort::kUsb), std::nullopt);
  EXPECT_EQ(d.take_baud_change(ReceiverPort::kUart1), 19200);
  const ubx::CfgPrt prt = cfg_prt_of(d, ubx::kPortUart1);
  EXPECT_EQ(prt.baud_rate, 19200u);
  EXPECT_EQ(prt.out_proto_mask, ubx::kProtoUbx | ubx::kProtoNmea);
  EXPECT_EQ(prt.in_proto_mask & (ubx::kProtoUbx | ubx::kProtoNmea), ubx::kProtoUbx | ubx::kProtoNmea);
  EXPECT_EQ(d.config().get(0x40520001), 19200u);  // CFG-UART1-BAUDRATE

  EXPECT_EQ(send_nmea(d, "$PUBX,41,3,0001,0001,115200,0*1E\r\n", ReceiverPort::kUart1), "");
  EXPECT_EQ(d.config().get(0x10780002), 0u);  // CFG-USBOUTPROT-NMEA
  EXPECT_EQ(d.take_baud_change(ReceiverPort::kUsb), std::nullopt);
  EXPECT_EQ(d.take_baud_change(ReceiverPort::kUart1), std::nullopt);
  EXPECT_EQ(epoch_output(d, 0, ReceiverPort::kUsb).find('$'), std::string::npos);
  EXPECT_NE(epoch_output(d, 0, ReceiverPort::kUart1).find("$GNGGA"), std::string::npos);
}

// PUBX,40 sets one sentence's rate on each port given, like CFG-MSG: the description's example
// $PUBX,40,GLL,1,0,0,0,0,0*5D (GLL on DDC every solution, off on the UARTs, USB and SPI); the
// short form hosts send leaves SPI as it was; ZDA switched on for UART1 only.
TEST_F(UbxDeviceTest, PubxRateSetsTheSentenceRatePerPort) {
  for (const GnssProfile* p : {&m8_, &f9p_}) {
    SCOPED_TRACE(p->ubx->protver);
    UbxDevice d(*p, ReceiverMode::kStandalone, empty_nav());
    const ubx::MsgId gll{ubx::kClassNmea, 0x01}, zda{ubx::kClassNmea, 0x08};
    EXPECT_NE(epoch_output(d, 0).find("$GNGLL"), std::string::npos);
    EXPECT_EQ(send_nmea(d, "$PUBX,40,GLL,1,0,0,0,0,0*5D\r\n"), "");
    EXPECT_EQ(d.rate(gll, ubx::kPortDdc), 1);
    for (std::uint8_t q : {ubx::kPortUart1, ubx::kPortUart2, ubx::kPortUsb, ubx::kPortSpi}) EXPECT_EQ(d.rate(gll, q), 0);
    EXPECT_EQ(epoch_output(d, 1).find("$GNGLL"), std::string::npos);
    EXPECT_NE(epoch_output(d, 1).find("$GNGGA"), std::string::npos);
    EXPECT_NE(epoch_output(d, 1, ReceiverPort::kI2c).find("$GNGLL"), std::string::npos);

    EXPECT_EQ(send_nmea(d, "$PUBX,40,ZDA,0,1,0,0,0,0*45\r\n"), "");
    EXPECT_EQ(d.rate(zda, ubx::kPortUart1), 1);
    EXPECT_EQ(d.rate(zda, ubx::kPortUsb), 0);
    EXPECT_NE(epoch_output(d, 2).find("$GNZDA"), std::string::npos);
    EXPECT_EQ(epoch_output(d, 2, ReceiverPort::kUsb).find("$GNZDA"), std::string::npos);
    if (p == &f9p_) {
      EXPECT_EQ(d.config().get(0x209100d9), 1u);  // CFG-MSGOUT-NMEA_ID_ZDA_UART1
    }

    ubx::CfgMsg spi{ubx::kClassNmea, 0x01, {}};
    spi.rate[ubx::kPortSpi] = 3;
    EXPECT_TRUE(only_ack(send(d, frame(spi)), ubx::kCfgMsg));
    EXPECT_EQ(send_nmea(d, "$PUBX,40,GLL,0,0,0,0*5C\r\n"), "");
    EXPECT_EQ(d.rate(gll, ubx::kPortDdc), 0);
    EXPECT_EQ(d.rate(gll, ubx::kPortSpi), 3) << "no SPI field: SPI keeps its rate";
    EXPECT_EQ(d.counters().nmea_commands, 3u);
  }
}

// PUBX polls: answered on the port they came from with the latest epoch's sentence. The fix of
// a_fix(): 2010-11-17 13:00:00 UTC (GPS week 1610, Wednesday; GPS - UTC = 15 s), 32.3 N
// 90.9 W, 60 m, 2 satellites used of 3 tracked.
TEST_F(UbxDeviceTest, PubxPollsAnswerWithTheLatestEpoch) {
  UbxDevice d(m8_, ReceiverMode::kStandalone, empty_nav());
  epoch_output(d, 0);
  const std::string pos = send_nmea(d, "$PUBX,00*33\r\n");
  ASSERT_EQ(nmea::check(pos).status, nmea::Checked::kOk) << pos;
  EXPECT_EQ(std::count(pos.begin(), pos.end(), '\n'), 1);
  const std::vector<std::string> p = fields_of(pos);
  ASSERT_EQ(p.size(), 21u) << pos;
  EXPECT_EQ(p[1], "00");
  EXPECT_EQ(p[2], "130000.00");
  EXPECT_EQ(p[3] + p[4] + p[5] + p[6], "3218.00000N09054.00000W");
  EXPECT_EQ(p[7], "60.000");
  EXPECT_EQ(p[8], "G3");
  EXPECT_EQ(p[9] + "/" + p[10], "3.3/4.2");
  EXPECT_EQ(p[15] + "/" + p[16] + "/" + p[17], "1.10/1.40/0.90");
  EXPECT_EQ(p[18], "2");

  const std::vector<std::string> t = fields_of(send_nmea(d, "$PUBX,04*37\r\n"));
  ASSERT_GE(t.size(), 8u);
  EXPECT_EQ(t[1], "04");
  EXPECT_EQ(t[2] + " " + t[3], "130000.00 171110");
  EXPECT_EQ(t[4] + " " + t[5] + " " + t[6], "306000.00 1610 15");

  const std::string sv = send_nmea(d, "$PUBX,03*30\r\n", ReceiverPort::kUsb);
  ASSERT_EQ(nmea::check(sv).status, nmea::Checked::kOk) << sv;
  const std::vector<std::string> s = fields_of(sv);
  ASSERT_EQ(s.size(), 3u + 3 * 6) << sv;
  EXPECT_EQ(s[2], "3");
  EXPECT_EQ(s[3] + "," + s[4] + "," + s[5] + "," + s[6] + "," + s[7], "5,U,120,45,44");
  EXPECT_EQ(s[15] + "," + s[16] + "," + s[17] + "," + s[18], "29,-,030,03");
  EXPECT_EQ(d.counters().polls, 3u);
}

// Standard polls: $EIGNQ,RMC*24 (ZED-F9P description 4.2.9, "GNQ: poll a standard message
// (if the current talker ID is GN)") is answered with the RMC the port sends at that epoch; a
// sentence the port does not send (ZDA) is answered too; a poll naming another talker ID than
// the receiver's (GP: the receiver of several systems is GN) and a message the device does not
// produce (GBS) get nothing.
TEST_F(UbxDeviceTest, StandardPollsAnswerWithTheSentence) {
  UbxDevice d(f9p_, ReceiverMode::kStandalone, empty_nav());
  const std::string epoch = epoch_output(d, 0);
  const std::string rmc = send_nmea(d, "$EIGNQ,RMC*24\r\n");
  ASSERT_TRUE(rmc.starts_with("$GNRMC,130000.00,A,3218.00000,N,09054.00000,W,")) << rmc;
  EXPECT_NE(epoch.find(rmc), std::string::npos) << "the epoch's own RMC";
  EXPECT_EQ(std::count(rmc.begin(), rmc.end(), '\n'), 1);
  const std::string zda = send_nmea(d, "$EIGNQ,ZDA*27\r\n");
  EXPECT_TRUE(zda.starts_with("$GNZDA,130000.00,17,11,2010,")) << zda;
  EXPECT_EQ(nmea::check(zda).status, nmea::Checked::kOk);
  EXPECT_EQ(send_nmea(d, "$EIGPQ,RMC*3A\r\n"), "");
  EXPECT_EQ(send_nmea(d, "$EIGNQ,GBS*2E\r\n"), "");
  EXPECT_EQ(d.counters().nmea_commands, 2u);
  EXPECT_EQ(d.counters().nmea_ignored, 2u);
}

// Malformed input gets no reply and changes nothing: a wrong checksum, a bad field, an unknown
// sentence for PUBX,40, a sentence that is no input ($GPGGA), one cut by a UBX frame; each is
// counted. A UBX poll and an NMEA poll in one write are answered in the order they came.
TEST_F(UbxDeviceTest, MalformedNmeaInputIsIgnoredAndCounted) {
  UbxDevice d(m8_, ReceiverMode::kStandalone, empty_nav());
  epoch_output(d, 0);
  const std::vector<std::uint8_t> mon = poll(ubx::kMonVer);
  const std::string mon_s(mon.begin(), mon.end());
  const std::string junk = "$PUBX,41,1,0001,0001,38400,0*00\r\n"   // checksum
                           "$PUBX,41,1,00G1,0001,38400,0*53\r\n"   // not hexadecimal
                           "$PUBX,40,XYZ,0,1,0,0,0,0*41\r\n"       // no such sentence
                           "$GPGGA,,,,,,0,00,99.99,,,,,,*48\r\n"   // an output, not an input
                           "$PUBX,41,1,0001," + mon_s + ",38400,0*24\r\n";  // cut by a frame
  const std::string replies = send_nmea(d, junk);
  EXPECT_EQ(replies.find('$'), std::string::npos) << replies;
  EXPECT_EQ(of_type(frames_of(replies), ubx::kMonVer).size(), 1u);
  EXPECT_EQ(d.take_baud_change(ReceiverPort::kUart1), std::nullopt);
  EXPECT_NE(epoch_output(d, 1).find("$GNGGA"), std::string::npos);
  EXPECT_EQ(d.counters().nmea_commands, 0u);
  EXPECT_EQ(d.counters().nmea_ignored, 4u);

  const std::string both = send_nmea(d, mon_s + "$PUBX,00*33\r\n");
  ASSERT_GT(both.size(), mon.size());
  EXPECT_EQ(of_type(frames_of(both), ubx::kMonVer).size(), 1u);
  EXPECT_TRUE(both.substr(both.find('$')).starts_with("$PUBX,00,")) << "the PUBX,00 after the MON-VER";
  EXPECT_EQ(both[0], static_cast<char>(ubx::kSync1));
}

// Another maker's proprietary sentence gets the warning a u-blox 8 gives gpsd's probes
// (../shared/data/receiver_logs/gpsd/ublox8-uniqid-monhw.log: "$GNTXT,01,01,01,PMTK inv
// format*20"), as NMEA TXT with the receiver's talker on the port it came from; as UBX
// INF-WARNING where CFG-INFMSG says so; nothing where the warning bit is off.
TEST_F(UbxDeviceTest, OtherMakersSentencesGetAnInvalidFormatWarning) {
  UbxDevice m8(m8_, ReceiverMode::kStandalone, empty_nav());
  EXPECT_EQ(send_nmea(m8, "$PMTK605*31\r\n"), "$GNTXT,01,01,01,PMTK inv format*20\r\n");
  EXPECT_EQ(send_nmea(m8, "$PASHQ,RID*28\r\n"), "$GNTXT,01,01,01,PASH inv format*28\r\n");
  EXPECT_EQ(m8.counters().nmea_commands, 0u);
  EXPECT_EQ(m8.counters().polls, 0u);

  UbxDevice d(f9p_, ReceiverMode::kStandalone, empty_nav());
  set_items(d, {{"CFG-NMEA-MAINTALKERID", 3}});
  EXPECT_EQ(send_nmea(d, "$PMTK605*31\r\n"), "$GNTXT,01,01,01,PMTK inv format*20\r\n") << "the part's bytes";
  set_items(d, {{"CFG-INFMSG-NMEA_UART1", 0x05}, {"CFG-INFMSG-UBX_UART1", 0x02}});  // warnings as UBX
  const std::string r = send_nmea(d, "$PMTK605*31\r\n");
  EXPECT_EQ(r.find('$'), std::string::npos) << r;
  const std::vector<Frame> f = of_type(frames_of(r), ubx::kInfWarning);
  ASSERT_EQ(f.size(), 1u);
  EXPECT_EQ(std::string(f[0].payload.begin(), f[0].payload.end()), "PMTK inv format");
  set_items(d, {{"CFG-INFMSG-UBX_UART1", 0}});
  EXPECT_EQ(send_nmea(d, "$PMTK605*31\r\n"), "");
  EXPECT_EQ(send_nmea(d, "$PUBX,99*00\r\n"), "") << "u-blox's own, malformed: ignored";
}

// CFG-NMEA-PROTVER and -MAINTALKERID act on the next epoch's sentences (u-blox 8 receiver
// description, "NMEA protocol configuration"): RMC has 14 fields in NMEA 4.10 (mode indicator
// and navigational status), 13 in 2.3, 12 in 2.1; GSA ends with the system ID only from 4.10 on.
TEST_F(UbxDeviceTest, NmeaVersionAndTalkerFollowTheirItems) {
  UbxDevice d(f9p_, ReceiverMode::kStandalone, empty_nav());
  std::int64_t k = 0;
  const auto sentence = [&](const std::string& type) {
    const std::string out = epoch_output(d, k++);
    const std::size_t at = out.find(type + ",");
    if (at == std::string::npos || at < 3) return std::vector<std::string>{};
    return fields_of(out.substr(at - 3, out.find("\r\n", at) - (at - 3)));
  };
  std::vector<std::string> rmc = sentence("RMC");
  ASSERT_EQ(rmc.size(), 14u);
  EXPECT_EQ(rmc[0], "GNRMC") << "main talker 0 (auto): GN for several systems";
  EXPECT_EQ(sentence("GSA").size(), 19u) << "NMEA 4.10: the system ID";

  set_items(d, {{"CFG-NMEA-PROTVER", 23}, {"CFG-NMEA-MAINTALKERID", 1}});
  rmc = sentence("RMC");
  EXPECT_EQ(rmc.size(), 13u);
  EXPECT_EQ(rmc[0], "GPRMC");
  EXPECT_EQ(sentence("GSA").size(), 18u);
  set_items(d, {{"CFG-NMEA-PROTVER", 21}, {"CFG-NMEA-MAINTALKERID", 3}});
  rmc = sentence("RMC");
  EXPECT_EQ(rmc.size(), 12u);
  EXPECT_EQ(rmc[0], "GNRMC");
  EXPECT_EQ(sentence("GGA")[0], "GNGGA");
}

// The u-blox 8 applies its legacy CFG-NMEA (UBX-13003221 "UBX-CFG-NMEA"): at power-up NMEA 4.0
// (nmeaVersion 0x40), whose RMC has the mode indicator but no navigational status (13 fields)
// and whose GSA has no system ID (18), as a real u-blox 8 sends them (the gpsd capture in
// ../shared/data, when present); version 4.1 adds both, mainTalkerId 3 makes the talker GN,
// and 2.1 drops the mode indicator.
TEST_F(UbxDeviceTest, TheUblox8AppliesItsLegacyCfgNmea) {
  UbxDevice d(m8_, ReceiverMode::kStandalone, empty_nav());
  std::int64_t k = 0;
  std::string out;
  const auto sentence = [&](const std::string& type) {
    const std::size_t at = out.find(type + ",");
    if (at == std::string::npos || at < 3) return std::vector<std::string>{};
    return fields_of(out.substr(at - 3, out.find("\r\n", at) - (at - 3)));
  };
  out = epoch_output(d, k++);
  EXPECT_EQ(sentence("RMC").size(), 13u) << out;
  EXPECT_EQ(sentence("GSA").size(), 18u) << out;
  if (const std::filesystem::path capture = test::shared_data("receiver_logs/gpsd/ublox8-uniqid-monhw.log"); std::filesystem::exists(capture)) {
    const std::string real = test::read_file(capture);
    for (const char* type : {"RMC", "GSA"}) {
      const std::size_t at = real.find(std::string("$GN") + type + ",");
      ASSERT_NE(at, std::string::npos) << type;
      EXPECT_EQ(fields_of(real.substr(at, real.find("\r\n", at) - at)).size(), sentence(type).size()) << type;
    }
  }

  ubx::CfgNmea m;
  m.nmea_version = 0x41;
  m.has_v0 = m.has_v1 = true;
  m.main_talker_id = 3;  // GN
  m.version = 1;
  EXPECT_TRUE(only_ack(send(d, frame(m)), ubx::kCfgNmea));
  out = epoch_output(d, k++);
  std::vector<std::string> rmc = sentence("RMC");
  ASSERT_EQ(rmc.size(), 14u) << out;
  EXPECT_EQ(rmc[0], "GNRMC");
  EXPECT_EQ(sentence("GSA").size(), 19u) << out;
  m.nmea_version = 0x21;
  EXPECT_TRUE(only_ack(send(d, frame(m)), ubx::kCfgNmea));
  out = epoch_output(d, k++);
  EXPECT_EQ(sentence("RMC").size(), 12u) << out;
  const std::vector<Frame> f = frames_of(send(d, poll(ubx::kCfgNmea)));
  ASSERT_EQ(f.size(), 2u);
  EXPECT_EQ(f[0].payload, payload_of(frame(m))) << "the poll gives the set back";
}

// CFG-NMEA-HIGHPREC (ZED-F9P integration manual UBX-18010802 3.1.4.5): latitude and longitude
// with seven digits after the decimal point and altitude with three, unless compatibility mode
// or the 82-character limit is on, with which the mode "cannot be used".
TEST_F(UbxDeviceTest, NmeaHighPrecisionModeWidensPositionAndAltitude) {
  UbxDevice d(f9p_, ReceiverMode::kStandalone, empty_nav());
  std::int64_t k = 0;
  const auto gga = [&] {
    const std::string out = epoch_output(d, k++);
    const std::size_t at = out.find("GGA,");
    return at == std::string::npos ? std::vector<std::string>{}
                                   : fields_of(out.substr(at - 3, out.find("\r\n", at) - (at - 3)));
  };
  const auto decimals = [](const std::string& f) {
    const std::size_t dot = f.find('.');
    return dot == std::string::npos ? 0 : static_cast<int>(f.size() - dot - 1);
  };
  std::vector<std::string> g = gga();
  ASSERT_GE(g.size(), 10u);
  EXPECT_EQ(decimals(g[2]), 5);
  EXPECT_EQ(decimals(g[4]), 5);
  EXPECT_EQ(decimals(g[9]), 1);
  set_items(d, {{"CFG-NMEA-HIGHPREC", 1}});
  g = gga();
  ASSERT_GE(g.size(), 10u);
  EXPECT_EQ(g[2], "3218.0000000");
  EXPECT_EQ(g[4], "09054.0000000");
  EXPECT_EQ(g[9], "60.000");
  set_items(d, {{"CFG-NMEA-LIMIT82", 1}});
  EXPECT_EQ(decimals(gga()[2]), 5);
  set_items(d, {{"CFG-NMEA-LIMIT82", 0}, {"CFG-NMEA-COMPAT", 1}});
  EXPECT_EQ(decimals(gga()[2]), 5);
}


// One epoch of the receiver model on the nominal constellation, encoded by `d`, for the tests
// of what the device keeps between epochs (aiding data, raw measurements).
struct ModelEpoch {
  NavData nav = nominal_constellation(kT0);
  ReceiverFix fix;
  EpochMeasurements meas;
  explicit ModelEpoch(const GnssProfile& p) {
    ReceiverParams rp;
    apply_receiver_class(rp.measurement, p.receiver_class);
    rp.measurement.elevation_mask_deg = p.elevation_mask_deg;
    Receiver rx(nav, rp);
    ImuTruth truth;
    truth.position = Geodetic{32.3, -90.9, 60.0};
    truth.t = kT0;
    fix = rx.update(kT0, &truth);
    meas = rx.measurements();
  }
};

// A 24-bit field of the AID data words (words 3..10 of a subframe, parity removed, data bits
// d1..d24 in bits 23..0): `bits` bits from IS-GPS-200 bit `first` (1-based within the word).
std::uint32_t bits_of(std::uint32_t word, int first, int bits) {
  return (word >> (24 - first - bits + 1)) & ((1u << bits) - 1u);
}

// AID-EPH, AID-ALM, AID-HUI, AID-INI and AID-AOP polls of the u-blox 8 (UBX-13003221, the AID
// messages), checked field by field against the bit positions of IS-GPS-200 (Figure 20-1,
// Tables 20-I/III/VI): a tracked satellite's ephemeris (week, IODE, e, sqrt(A)), an almanac
// page's data ID, SV ID and elements, the Klobuchar and UTC values of the file, the fix.
TEST_F(UbxDeviceTest, AidPollsAnswerFromTheNavigationDataInUse) {
  const ModelEpoch e(m8_);
  ASSERT_EQ(e.fix.fix, FixType::k3D);
  UbxDevice d(m8_, ReceiverMode::kStandalone, e.nav);
  std::string epoch;
  d.encode_epoch(e.fix, e.meas, 0, epoch);
  const int week = to_week_tow(kT0).week;

  // AID-EPH: 32 answers to the poll of all; 104 bytes for each tracked satellite, 8 otherwise.
  const std::vector<Frame> eph = frames_of(send(d, poll(ubx::kAidEph)));
  ASSERT_EQ(eph.size(), 32u);
  std::size_t with_data = 0;
  for (std::size_t i = 0; i < eph.size(); ++i) {
    ubx::AidEph m;
    ASSERT_TRUE(eph[i].id == ubx::kAidEph && ubx::decode(eph[i].payload, m));
    EXPECT_EQ(m.svid, i + 1);
    const auto s = std::find_if(e.meas.sats.begin(), e.meas.sats.end(),
                                [&](const SatMeasurement& x) { return x.sat == gps_sat(static_cast<int>(i + 1)); });
    if (s == e.meas.sats.end()) {
      EXPECT_EQ(eph[i].payload.size(), 8u);
      EXPECT_EQ(m.how, 0u);
      continue;
    }
    ++with_data;
    ASSERT_EQ(eph[i].payload.size(), 104u);
    const GpsEphemeris& r = *s->eph;
    EXPECT_EQ(bits_of(m.how, 20, 3), 1u);                                          // subframe ID 1
    EXPECT_EQ(bits_of(m.sf1d[0], 1, 10), static_cast<std::uint32_t>(to_week_tow(r.toe).week % 1024));
    EXPECT_EQ(bits_of(m.sf2d[0], 1, 8), static_cast<std::uint32_t>(r.iode & 0xFF));  // word 3: IODE
    EXPECT_EQ(bits_of(m.sf3d[7], 1, 8), static_cast<std::uint32_t>(r.iode & 0xFF));  // word 10: IODE
    const double ecc = std::ldexp(static_cast<double>(bits_of(m.sf2d[3], 17, 8) << 24 | m.sf2d[4]), -33);
    const double sqrt_a = std::ldexp(static_cast<double>(bits_of(m.sf2d[5], 17, 8) << 24 | m.sf2d[6]), -19);
    EXPECT_NEAR(ecc, r.e, 0x1p-33);
    EXPECT_NEAR(sqrt_a, r.sqrt_a_sqrtm, 0x1p-19);
    for (std::uint32_t w : m.sf1d) EXPECT_EQ(w >> 24, 0u);
  }
  EXPECT_GE(with_data, 4u);
  const std::vector<Frame> one = frames_of(send(d, raw_frame(ubx::kAidEph, {eph.back().payload[0]})));
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(one[0].payload, eph.back().payload);
  EXPECT_TRUE(frames_of(send(d, raw_frame(ubx::kAidEph, {33}))).empty());

  // AID-ALM: the almanac page of each satellite with a record (subframe 5 page n for SV n <= 24,
  // subframe 4 for 25..32): data ID 01, the SV ID, e (2^-21) and sqrt(A) (2^-11).
  const std::vector<Frame> alm = frames_of(send(d, poll(ubx::kAidAlm)));
  ASSERT_EQ(alm.size(), 32u);
  for (std::size_t i = 0; i < alm.size(); ++i) {
    ubx::AidAlm m;
    ASSERT_TRUE(ubx::decode(alm[i].payload, m));
    const GpsEphemeris* r = select_ephemeris(e.nav, gps_sat(static_cast<int>(i + 1)), kT0);
    if (r == nullptr) {
      EXPECT_EQ(alm[i].payload.size(), 8u);
      EXPECT_EQ(m.week, 0u);
      continue;
    }
    ASSERT_EQ(alm[i].payload.size(), 40u);
    EXPECT_EQ(m.week, static_cast<std::uint32_t>(week));
    EXPECT_EQ(bits_of(m.dwrd[0], 1, 2), 1u);
    EXPECT_EQ(bits_of(m.dwrd[0], 3, 6), i + 1);
    EXPECT_NEAR(std::ldexp(bits_of(m.dwrd[0], 9, 16), -21), r->e, 0x1p-21);
    EXPECT_NEAR(std::ldexp(m.dwrd[3], -11), r->sqrt_a_sqrtm, 0x1p-11);
  }

  // AID-HUI: the file's Klobuchar coefficients, GPS - UTC = 15 s in 2010, every satellite of
  // the file healthy.
  const std::vector<Frame> hui = frames_of(send(d, poll(ubx::kAidHui)));
  ubx::AidHui h;
  ASSERT_EQ(hui.size(), 1u);
  ASSERT_TRUE(ubx::decode(hui[0].payload, h));
  EXPECT_EQ(h.utc_ls_s, 15);
  EXPECT_EQ(h.flags & 0x03u, 0x03u);
  for (int n = 1; n <= 32; ++n)
    EXPECT_EQ((h.health >> (n - 1)) & 1u, select_ephemeris(e.nav, gps_sat(n), kT0) ? 1u : 0u) << n;
  if (e.nav.klobuchar) {
    EXPECT_FLOAT_EQ(h.klob_a[1], static_cast<float>(e.nav.klobuchar->alpha[1]));
    EXPECT_FLOAT_EQ(h.klob_b[3], static_cast<float>(e.nav.klobuchar->beta[3]));
  }

  // AID-INI: the fix, in cm of ECEF, with its GPS week and time of week.
  const std::vector<Frame> ini = frames_of(send(d, poll(ubx::kAidIni)));
  ubx::AidIni i0;
  ASSERT_EQ(ini.size(), 1u);
  ASSERT_TRUE(ubx::decode(ini[0].payload, i0));
  EXPECT_NEAR(i0.ecef_x_or_lat * 0.01, e.fix.p_ecef_m.x(), 0.006);
  EXPECT_NEAR(i0.ecef_z_or_alt * 0.01, e.fix.p_ecef_m.z(), 0.006);
  EXPECT_EQ(i0.wno_or_date, week);
  EXPECT_EQ(i0.tow_or_time_ms, static_cast<std::uint32_t>(std::llround(to_week_tow(kT0).tow_s * 1000.0)));
  EXPECT_EQ(i0.flags & 0x27u, 0x07u);  // position, time and drift valid; ECEF

  // AID-AOP: AssistNow Autonomous off, so each satellite's poll request comes back.
  const std::vector<Frame> aop = frames_of(send(d, poll(ubx::kAidAop)));
  ASSERT_EQ(aop.size(), 32u);
  for (std::size_t i = 0; i < aop.size(); ++i) EXPECT_EQ(aop[i].payload, std::vector<std::uint8_t>{static_cast<std::uint8_t>(i + 1)});

  // The F9P has no AID messages: no answer.
  UbxDevice f9(f9p_, ReceiverMode::kStandalone, e.nav);
  f9.encode_epoch(e.fix, e.meas, 0, epoch);
  for (ubx::MsgId id : {ubx::kAidIni, ubx::kAidHui, ubx::kAidAlm, ubx::kAidEph, ubx::kAidAop})
    EXPECT_TRUE(frames_of(send(f9, poll(id))).empty());
}

// MGA-DBD (UBX-18010854 5.12.3): the dump is one entry per tracked GPS satellite, then MGA-ACK
// (type 1, msgId 0x80) whose msgPayloadStart counts the entries; UPD-SOS (5.18.1) on the F9P:
// "not restored" at power-up, "acknowledged" for a backup, "restored" after the next reset, and
// nothing on the M8 (a ROM part).
TEST_F(UbxDeviceTest, NavigationDatabaseDumpAndFlashBackup) {
  const ModelEpoch e(f9p_);
  for (const GnssProfile* p : {&m8_, &f9p_}) {
    SCOPED_TRACE(p->name);
    UbxDevice d(*p, ReceiverMode::kStandalone, e.nav);
    std::string epoch;
    d.encode_epoch(e.fix, e.meas, 0, epoch);
    const std::vector<Frame> f = frames_of(send(d, poll(ubx::kMgaDbd)));
    ASSERT_FALSE(f.empty());
    ubx::MgaAck ack;
    ASSERT_TRUE(f.back().id == ubx::kMgaAck && ubx::decode(f.back().payload, ack));
    EXPECT_EQ(ack.type, 1);
    EXPECT_EQ(ack.msg_id, 0x80);
    EXPECT_EQ(ack.msg_payload_start, f.size() - 1);
    EXPECT_EQ(f.size() - 1, e.meas.sats.size());
    for (std::size_t i = 0; i + 1 < f.size(); ++i) {
      ubx::MgaDbd dbd;
      ASSERT_TRUE(f[i].id == ubx::kMgaDbd && ubx::decode(f[i].payload, dbd));
      ASSERT_EQ(dbd.data.size(), 105u);
      EXPECT_EQ(dbd.data[0], 1);
      ubx::AidEph m;
      ASSERT_TRUE(ubx::decode(std::span(dbd.data).subspan(1), m));
      EXPECT_TRUE(m.has_data);
      EXPECT_TRUE(e.meas.sats[i].sat == gps_sat(static_cast<int>(m.svid)));
    }
  }
  UbxDevice m8(m8_, ReceiverMode::kStandalone, e.nav);
  EXPECT_TRUE(frames_of(send(m8, poll(ubx::kUpdSos))).empty());

  UbxDevice d(f9p_, ReceiverMode::kStandalone, e.nav);
  std::string epoch;
  d.encode_epoch(e.fix, e.meas, 0, epoch);
  const auto sos = [&](const std::vector<std::uint8_t>& bytes) {
    const std::vector<Frame> f = frames_of(send(d, bytes));
    ubx::UpdSos m;
    EXPECT_EQ(f.size(), 1u);
    EXPECT_TRUE(!f.empty() && ubx::decode(f[0].payload, m));
    return std::pair{int{m.cmd}, int{m.response}};
  };
  const auto reset = [&] { send(d, frame(ubx::CfgRst{ubx::CfgRst::kHotStart, ubx::CfgRst::kHardwareReset})); };
  EXPECT_EQ(sos(poll(ubx::kUpdSos)), std::pair(3, 3));  // not restored: no backup
  EXPECT_EQ(sos(raw_frame(ubx::kUpdSos, {0, 0, 0, 0})), std::pair(2, 1));  // backup acknowledged
  EXPECT_EQ(sos(poll(ubx::kUpdSos)), std::pair(3, 3));  // until the next start
  reset();
  EXPECT_EQ(sos(poll(ubx::kUpdSos)), std::pair(3, 2));  // restored from the backup
  EXPECT_TRUE(frames_of(send(d, raw_frame(ubx::kUpdSos, {1, 0, 0, 0}))).empty());  // clear: no answer
  reset();
  EXPECT_EQ(sos(poll(ubx::kUpdSos)), std::pair(3, 3));
}

// Assistance data in is acknowledged only when asked for (UBX-18010854 5.12.1 MGA-ACK-DATA0,
// "Acknowledgments are enabled by setting the ackAiding parameter"): nothing at power-up; with
// CFG-NAVSPG-ACKAIDING (the F9P) or a CFG-NAVX5 that sets ackAiding (mask1 bit 10; the u-blox
// 8) an MGA-INI-TIME_UTC gets type 1 (accepted), msgId 0x40 and its first four payload bytes,
// and each MGA-DBD entry of a dump sent back gets one with msgId 0x80. MGA-ACK itself, an
// output, gets nothing.
TEST_F(UbxDeviceTest, AssistanceIsAcknowledgedWhenAskedFor) {
  const ModelEpoch e(f9p_);
  std::vector<std::uint8_t> ini_time(24, 0);  // MGA-INI-TIME_UTC: type 0x10, version 0, ref, leapSecs
  ini_time[0] = 0x10;
  ini_time[3] = 0x80;  // leapSecs -128: unknown
  for (const GnssProfile* p : {&m8_, &f9p_}) {
    SCOPED_TRACE(p->name);
    UbxDevice d(*p, ReceiverMode::kStandalone, e.nav);
    std::string epoch;
    d.encode_epoch(e.fix, e.meas, 0, epoch);
    const ubx::MsgId ini{ubx::kClassMga, 0x40};
    EXPECT_TRUE(frames_of(send(d, raw_frame(ini, ini_time))).empty()) << "acknowledgements off";
    if (p == &f9p_) {
      set_items(d, {{"CFG-NAVSPG-ACKAIDING", 1}});
    } else {
      ubx::CfgNavx5 navx5;
      navx5.mask1 = 1u << 10;  // ackAid
      navx5.ack_aiding = 1;
      EXPECT_TRUE(only_ack(send(d, frame(navx5)), ubx::kCfgNavx5));
    }
    std::vector<Frame> f = frames_of(send(d, raw_frame(ini, ini_time)));
    ubx::MgaAck ack;
    ASSERT_EQ(f.size(), 1u);
    ASSERT_TRUE(f[0].id == ubx::kMgaAck && ubx::decode(f[0].payload, ack));
    EXPECT_EQ(ack.type, 1);
    EXPECT_EQ(ack.info_code, 0);
    EXPECT_EQ(ack.msg_id, 0x40);
    EXPECT_EQ(ack.msg_payload_start, 0x80000010u);

    const std::vector<Frame> dump = frames_of(send(d, poll(ubx::kMgaDbd)));
    ASSERT_GT(dump.size(), 1u);
    std::vector<std::uint8_t> back;
    for (std::size_t i = 0; i + 1 < dump.size(); ++i) ubx::append_frame(ubx::kMgaDbd.cls, ubx::kMgaDbd.id, dump[i].payload, back);
    f = frames_of(send(d, back));
    ASSERT_EQ(f.size(), dump.size() - 1);
    for (const Frame& a : f) EXPECT_TRUE(a.id == ubx::kMgaAck && ubx::decode(a.payload, ack) && ack.msg_id == 0x80);
    EXPECT_TRUE(frames_of(send(d, raw_frame(ubx::kMgaAck, std::vector<std::uint8_t>(8, 0)))).empty());
  }
}

// Time mode (ZED-F9P integration manual "Base station"; F9 interface description CFG-TMODE-*,
// NAV-PVT fixType 5 "time-only fix"): with a fixed position (LLH with its HP parts, then ECEF)
// or once the survey-in has finished, the receiver reports the time-only fix at that position,
// standing still, with the configured accuracy (0.1 m: hAcc = vAcc = 0.1 / sqrt(2) m) or the
// survey's; GGA carries the position; time mode off gives the 3D fix back.
TEST_F(UbxDeviceTest, TimeModeReportsTheTimeOnlyFixAtTheHeldPosition) {
  UbxDevice d(f9p_, ReceiverMode::kStandalone, empty_nav());
  std::int64_t k = 0;
  const auto epoch = [&](ReceiverFix fix) {
    d.update(fix, EpochMeasurements{}, k++);
    ubx::NavPvt pvt;
    ubx::NavStatus status;
    EXPECT_TRUE(ubx::decode(frames_of(send(d, poll(ubx::kNavPvt))).at(0).payload, pvt));
    EXPECT_TRUE(ubx::decode(frames_of(send(d, poll(ubx::kNavStatus))).at(0).payload, status));
    EXPECT_EQ(status.gps_fix, pvt.fix_type);
    return pvt;
  };
  ReceiverFix moving = a_fix(kT0);
  moving.v_ned_mps = Vec3(3.0, 4.0, 0.0);
  EXPECT_EQ(epoch(moving).fix_type, 3);

  ubx::CfgTmode3 llh;
  llh.flags = 2 | ubx::CfgTmode3::kLla;  // fixed, LLH
  llh.ecef_x_or_lat = 323'000'123;        // 32.3000123 deg - 5e-9
  llh.ecef_x_or_lat_hp = -5;
  llh.ecef_y_or_lon = -909'000'456;
  llh.ecef_z_or_alt_cm = 6'012;  // 60.12 m + 0.3 mm
  llh.ecef_z_or_alt_hp_0p1mm = 3;
  llh.fixed_pos_acc_0p1mm = 1'000;
  EXPECT_TRUE(only_ack(send(d, frame(llh)), ubx::kCfgTmode3));
  moving.t = kT0.plus_s(1);
  ubx::NavPvt pvt = epoch(moving);
  EXPECT_EQ(pvt.fix_type, 5);
  EXPECT_EQ(pvt.lat_1e7deg, 323'000'123);
  EXPECT_EQ(pvt.lon_1e7deg, -909'000'456);
  EXPECT_EQ(pvt.height_mm, 60'120);
  EXPECT_EQ(pvt.g_speed_mmps, 0);
  EXPECT_EQ(pvt.h_acc_mm, 71u);
  EXPECT_EQ(pvt.v_acc_mm, 71u);
  std::string out;
  d.encode_epoch(moving, EpochMeasurements{}, k++, out);
  EXPECT_NE(out.find("GGA,130001.00,3218.00074,N,09054.00274,W,1,"), std::string::npos) << out;

  const Vec3 p = a_fix(kT0).p_ecef_m + Vec3(10.0, -20.0, 30.0);
  std::vector<std::pair<const char*, std::int64_t>> ecef{{"CFG-TMODE-ECEF_X", 0}, {"CFG-TMODE-ECEF_Y", 0}, {"CFG-TMODE-ECEF_Z", 0}};
  for (int i = 0; i < 3; ++i) ecef[static_cast<std::size_t>(i)].second = std::llround(p[i] * 100.0);
  set_items(d, {{"CFG-TMODE-POS_TYPE", 0},
                {ecef[0].first, static_cast<std::uint32_t>(ecef[0].second)},
                {ecef[1].first, static_cast<std::uint32_t>(ecef[1].second)},
                {ecef[2].first, static_cast<std::uint32_t>(ecef[2].second)}});
  epoch(moving);
  ubx::NavPosecef pos;
  ASSERT_TRUE(ubx::decode(frames_of(send(d, poll(ubx::kNavPosecef))).at(0).payload, pos));
  EXPECT_EQ(pos.ecef_x_cm, ecef[0].second);
  EXPECT_EQ(pos.ecef_y_cm, ecef[1].second);
  EXPECT_EQ(pos.ecef_z_cm, ecef[2].second);
  EXPECT_LT((d.reported_fix().p_ecef_m - p).norm(), 0.01) << "what the run records (gnss.csv)";

  set_items(d, {{"CFG-TMODE-MODE", 1}, {"CFG-TMODE-SVIN_MIN_DUR", 2}, {"CFG-TMODE-SVIN_ACC_LIMIT", 1'000'000}});
  for (int i = 0; i < 3; ++i) {
    ReceiverFix f = a_fix(kT0.plus_s(10 + i));
    f.p_ecef_m.x() += i;  // mean: +1 m in x
    pvt = epoch(f);
    if (i < 2) {
      EXPECT_EQ(pvt.fix_type, 3) << "surveying at " << i << " s";
    }
  }
  EXPECT_EQ(pvt.fix_type, 5) << "the survey finished with the fix 2 s after its first";
  ASSERT_TRUE(ubx::decode(frames_of(send(d, poll(ubx::kNavPosecef))).at(0).payload, pos));
  EXPECT_EQ(pos.ecef_x_cm, std::llround((a_fix(kT0).p_ecef_m.x() + 1.0) * 100.0));

  set_items(d, {{"CFG-TMODE-MODE", 0}});
  EXPECT_EQ(epoch(moving).fix_type, 3);
}

// RXM-MEASX (M8 32.18.4, UBX-18010854 5.15.1): per tracked signal the code phase and Doppler of
// RRLP (3GPP TS 44.031), checked against RXM-RAWX of the same epoch: the whole ms plus the code
// phase is the pseudorange (to 2^-21 ms, 0.14 m), the chips (1023 per ms, in 1/1024) are the
// same fraction, dopplerHz is doMes in 0.2 Hz and dopplerMS the same times the L1 wavelength.
TEST_F(UbxDeviceTest, RxmMeasxIsTheRawMeasurementInRrlpUnits) {
  const ModelEpoch e(f9p_);
  UbxDevice d(f9p_, ReceiverMode::kStandalone, e.nav);
  std::string epoch;
  d.encode_epoch(e.fix, e.meas, 0, epoch);
  const std::vector<Frame> fx = frames_of(send(d, poll(ubx::kRxmMeasx)));
  const std::vector<Frame> fr = frames_of(send(d, poll(ubx::kRxmRawx)));
  ubx::RxmMeasx mx;
  ubx::RxmRawx raw;
  ASSERT_EQ(fx.size(), 1u);
  ASSERT_EQ(fr.size(), 1u);
  ASSERT_TRUE(ubx::decode(fx[0].payload, mx));
  ASSERT_TRUE(ubx::decode(fr[0].payload, raw));
  EXPECT_EQ(mx.version, 1);
  EXPECT_EQ(mx.flags & ubx::RxmMeasx::kTowSetMask, 2);
  EXPECT_EQ(mx.gps_tow_ms, static_cast<std::uint32_t>(std::llround(raw.rcv_tow_s * 1000.0)));
  EXPECT_EQ(mx.bds_tow_ms, mx.gps_tow_ms - 14'000);  // BDT = GPST - 14 s
  EXPECT_EQ(mx.glo_tow_ms, mx.gps_tow_ms + 3 * 3'600'000 - 15'000);  // UTC(SU) + 3 h, 15 s leap
  ASSERT_EQ(mx.svs.size(), raw.meas.size());
  ASSERT_GE(mx.svs.size(), 4u);
  constexpr double kC = 299'792'458.0;
  const double lambda_m = kC / 1575.42e6;
  for (std::size_t i = 0; i < mx.svs.size(); ++i) {
    const ubx::RxmMeasxSv& s = mx.svs[i];
    const ubx::RxmRawxMeas& r = raw.meas[i];
    SCOPED_TRACE(int{s.sv_id});
    EXPECT_EQ(s.gnss_id, r.gnss_id);
    EXPECT_EQ(s.sv_id, r.sv_id);
    EXPECT_EQ(s.cno_dbhz, r.cno_dbhz);
    EXPECT_LT(s.whole_chips, 1023);
    EXPECT_LT(s.frac_chips, 1024);
    const double frac_ms = std::ldexp(s.code_phase_2m21ms, -21);
    EXPECT_LT(frac_ms, 1.0);
    EXPECT_NEAR((s.int_code_phase_ms + frac_ms) * 1e-3 * kC, r.pr_mes_m, std::ldexp(1.0, -21) * 1e-3 * kC);
    EXPECT_NEAR((s.whole_chips + s.frac_chips / 1024.0) / 1023.0, frac_ms, 1.0 / 1023.0 / 1024.0);
    EXPECT_NEAR(s.doppler_200mhz * 0.2, r.do_mes_hz, 0.1);
    EXPECT_NEAR(s.doppler_4cmps * 0.04, r.do_mes_hz * lambda_m, 0.02);
    EXPECT_GE(s.mpath_indic, 1);
    EXPECT_EQ(s.pseu_range_rms_err, 0);  // 0.32 m: under 0.5 m
  }
}

}  // namespace
}  // namespace navemu
