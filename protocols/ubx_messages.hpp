#pragma once
// Typed UBX messages: one struct per message, fields named as in the u-blox interface
// description with the wire unit in the name (lon_1e7deg is longitude in 1e-7 deg, p_dop_0p01
// is PDOP in units of 0.01, pr_res_dm is a residual in decimetres); after each struct its
// description in the payload tables further down (protocols/ubx_layout.hpp): class/ID, name and
// the payload table in wire order (wire type, field name, member, scale, repeated block). The
// description alone drives, for each struct,
//
//   void append(const X&, std::vector<std::uint8_t>& out);            // a complete frame
//   bool decode(std::span<const std::uint8_t> payload, X&);           // length-checked
//
// and the registry messages() (class, ID, name, length rule, a round-trip hook) that tables
// dispatch on and the generic tests walk. append() writes the frame straight into `out` (no
// allocation once `out` has capacity). decode() takes the payload of a frame (Parser::payload()), checks its length against the
// message's layout and returns false, leaving the struct in an unspecified state, when it does
// not fit. Fixed-layout output messages accept a payload longer than their layout (u-blox may
// append fields to a message in later protocol versions; UBX-13003221 section 32.3 "UBX
// Payload Definition Rules"); messages with repeated blocks must match their count exactly, and
// messages whose length selects their meaning (CFG polls and sets) take the exact length
// only. Reserved fields are kept, so decode() followed by append() gives the received frame
// byte for byte. Conversion to and from SI units belongs to the caller.
//
// Sources: u-blox 8 / u-blox M8 Receiver Description including Protocol Specification,
// UBX-13003221 (R25; protocol versions 15 to 23.01), chapter 32 "UBX Protocol", sections
// UBX-ACK, UBX-CFG, UBX-MON, UBX-NAV, UBX-RXM; u-blox ZED-F9P Interface Description
// UBX-18010854 (protocol version 27), section 5 "UBX protocol" and section 6 "Configuration
// interface" (configuration keys). Where the F9 (protocol 27+) layout differs it is noted at
// the field. Layouts and key IDs were cross-checked against gpsd's ubxtool and pyubx2.

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "protocols/ubx.hpp"
#include "protocols/ubx_layout.hpp"

namespace navemu::ubx {

// ---- message classes and IDs (UBX-13003221 section 32.6 "UBX Class IDs") -------------------

inline constexpr std::uint8_t kClassNav = 0x01;
inline constexpr std::uint8_t kClassRxm = 0x02;
inline constexpr std::uint8_t kClassInf = 0x04;
inline constexpr std::uint8_t kClassAck = 0x05;
inline constexpr std::uint8_t kClassCfg = 0x06;
inline constexpr std::uint8_t kClassUpd = 0x09;
inline constexpr std::uint8_t kClassMon = 0x0A;
inline constexpr std::uint8_t kClassAid = 0x0B;
inline constexpr std::uint8_t kClassTim = 0x0D;
inline constexpr std::uint8_t kClassEsf = 0x10;
inline constexpr std::uint8_t kClassMga = 0x13;
inline constexpr std::uint8_t kClassLog = 0x21;
inline constexpr std::uint8_t kClassSec = 0x27;
inline constexpr std::uint8_t kClassHnr = 0x28;
inline constexpr std::uint8_t kClassNmea = 0xF0;  // standard NMEA sentences in CFG-MSG
inline constexpr std::uint8_t kClassPubx = 0xF1;  // u-blox proprietary NMEA in CFG-MSG

inline constexpr MsgId kNavPosecef{kClassNav, 0x01};
inline constexpr MsgId kNavPosllh{kClassNav, 0x02};
inline constexpr MsgId kNavStatus{kClassNav, 0x03};
inline constexpr MsgId kNavDop{kClassNav, 0x04};
inline constexpr MsgId kNavSol{kClassNav, 0x06};
inline constexpr MsgId kNavPvt{kClassNav, 0x07};
inline constexpr MsgId kNavOdo{kClassNav, 0x09};
inline constexpr MsgId kNavResetodo{kClassNav, 0x10};
inline constexpr MsgId kNavVelecef{kClassNav, 0x11};
inline constexpr MsgId kNavVelned{kClassNav, 0x12};
inline constexpr MsgId kNavHpposecef{kClassNav, 0x13};
inline constexpr MsgId kNavHpposllh{kClassNav, 0x14};
inline constexpr MsgId kNavTimegps{kClassNav, 0x20};
inline constexpr MsgId kNavTimeutc{kClassNav, 0x21};
inline constexpr MsgId kNavClock{kClassNav, 0x22};
inline constexpr MsgId kNavTimeglo{kClassNav, 0x23};
inline constexpr MsgId kNavTimebds{kClassNav, 0x24};
inline constexpr MsgId kNavTimegal{kClassNav, 0x25};
inline constexpr MsgId kNavTimels{kClassNav, 0x26};
inline constexpr MsgId kNavSvinfo{kClassNav, 0x30};
inline constexpr MsgId kNavDgps{kClassNav, 0x31};
inline constexpr MsgId kNavSbas{kClassNav, 0x32};
inline constexpr MsgId kNavOrb{kClassNav, 0x34};
inline constexpr MsgId kNavSat{kClassNav, 0x35};
inline constexpr MsgId kNavCov{kClassNav, 0x36};
inline constexpr MsgId kNavGeofence{kClassNav, 0x39};
inline constexpr MsgId kNavSvin{kClassNav, 0x3B};
inline constexpr MsgId kNavRelposned{kClassNav, 0x3C};
inline constexpr MsgId kNavSlas{kClassNav, 0x42};
inline constexpr MsgId kNavSig{kClassNav, 0x43};
inline constexpr MsgId kNavAopstatus{kClassNav, 0x60};
inline constexpr MsgId kNavEoe{kClassNav, 0x61};

inline constexpr MsgId kRxmSfrbx{kClassRxm, 0x13};
inline constexpr MsgId kRxmMeasx{kClassRxm, 0x14};
inline constexpr MsgId kRxmRawx{kClassRxm, 0x15};
inline constexpr MsgId kRxmRtcm{kClassRxm, 0x32};
inline constexpr MsgId kRxmImes{kClassRxm, 0x61};

inline constexpr MsgId kInfError{kClassInf, 0x00};
inline constexpr MsgId kInfWarning{kClassInf, 0x01};
inline constexpr MsgId kInfNotice{kClassInf, 0x02};
inline constexpr MsgId kInfTest{kClassInf, 0x03};
inline constexpr MsgId kInfDebug{kClassInf, 0x04};

inline constexpr MsgId kAckNak{kClassAck, 0x00};
inline constexpr MsgId kAckAck{kClassAck, 0x01};

inline constexpr MsgId kCfgPrt{kClassCfg, 0x00};
inline constexpr MsgId kCfgMsg{kClassCfg, 0x01};
inline constexpr MsgId kCfgInf{kClassCfg, 0x02};
inline constexpr MsgId kCfgRst{kClassCfg, 0x04};
inline constexpr MsgId kCfgDat{kClassCfg, 0x06};
inline constexpr MsgId kCfgRate{kClassCfg, 0x08};
inline constexpr MsgId kCfgCfg{kClassCfg, 0x09};
inline constexpr MsgId kCfgRxm{kClassCfg, 0x11};
inline constexpr MsgId kCfgAnt{kClassCfg, 0x13};
inline constexpr MsgId kCfgSbas{kClassCfg, 0x16};
inline constexpr MsgId kCfgNmea{kClassCfg, 0x17};
inline constexpr MsgId kCfgUsb{kClassCfg, 0x1B};
inline constexpr MsgId kCfgOdo{kClassCfg, 0x1E};
inline constexpr MsgId kCfgNavx5{kClassCfg, 0x23};
inline constexpr MsgId kCfgNav5{kClassCfg, 0x24};
inline constexpr MsgId kCfgTp5{kClassCfg, 0x31};
inline constexpr MsgId kCfgRinv{kClassCfg, 0x34};
inline constexpr MsgId kCfgItfm{kClassCfg, 0x39};
inline constexpr MsgId kCfgPm2{kClassCfg, 0x3B};
inline constexpr MsgId kCfgGnss{kClassCfg, 0x3E};
inline constexpr MsgId kCfgLogfilter{kClassCfg, 0x47};
inline constexpr MsgId kCfgPwr{kClassCfg, 0x57};
inline constexpr MsgId kCfgGeofence{kClassCfg, 0x69};
inline constexpr MsgId kCfgDgnss{kClassCfg, 0x70};
inline constexpr MsgId kCfgTmode3{kClassCfg, 0x71};
inline constexpr MsgId kCfgPms{kClassCfg, 0x86};
inline constexpr MsgId kCfgValset{kClassCfg, 0x8A};
inline constexpr MsgId kCfgValget{kClassCfg, 0x8B};
inline constexpr MsgId kCfgValdel{kClassCfg, 0x8C};

inline constexpr MsgId kUpdSos{kClassUpd, 0x14};

inline constexpr MsgId kAidIni{kClassAid, 0x01};
inline constexpr MsgId kAidHui{kClassAid, 0x02};
inline constexpr MsgId kAidAlm{kClassAid, 0x30};
inline constexpr MsgId kAidEph{kClassAid, 0x31};
inline constexpr MsgId kAidAop{kClassAid, 0x33};

inline constexpr MsgId kMgaAck{kClassMga, 0x60};
inline constexpr MsgId kMgaDbd{kClassMga, 0x80};

inline constexpr MsgId kMonIo{kClassMon, 0x02};
inline constexpr MsgId kMonVer{kClassMon, 0x04};
inline constexpr MsgId kMonMsgpp{kClassMon, 0x06};
inline constexpr MsgId kMonRxbuf{kClassMon, 0x07};
inline constexpr MsgId kMonTxbuf{kClassMon, 0x08};
inline constexpr MsgId kMonHw{kClassMon, 0x09};
inline constexpr MsgId kMonHw2{kClassMon, 0x0B};
inline constexpr MsgId kMonPatch{kClassMon, 0x27};
inline constexpr MsgId kMonGnss{kClassMon, 0x28};
inline constexpr MsgId kMonSpan{kClassMon, 0x31};
inline constexpr MsgId kMonComms{kClassMon, 0x36};
inline constexpr MsgId kMonHw3{kClassMon, 0x37};
inline constexpr MsgId kMonRf{kClassMon, 0x38};

inline constexpr MsgId kTimTp{kClassTim, 0x01};
inline constexpr MsgId kTimTm2{kClassTim, 0x03};
inline constexpr MsgId kTimVrfy{kClassTim, 0x06};
inline constexpr MsgId kSecUniqid{kClassSec, 0x03};

// A poll request: the message's class and ID with an empty payload (UBX-13003221 section 32.5
// "UBX Message Flow", polling mechanism).
void append_poll(MsgId msg, std::vector<std::uint8_t>& out);

// ---- NAV -----------------------------------------------------------------------------------

// GNSS fix types of NAV-PVT fixType, NAV-STATUS/NAV-SOL gpsFix.
inline constexpr std::uint8_t kFixNone = 0;
inline constexpr std::uint8_t kFixDeadReckoning = 1;
inline constexpr std::uint8_t kFix2d = 2;
inline constexpr std::uint8_t kFix3d = 3;
inline constexpr std::uint8_t kFixGnssDeadReckoning = 4;
inline constexpr std::uint8_t kFixTimeOnly = 5;

// UBX-NAV-PVT (0x01 0x07), 92 bytes: navigation position velocity time solution. Protocol 27
// (F9) widened flags3 to two bytes (invalidLlh bit 0, lastCorrectionAge bits 1..4); M8 sends
// flags3 as one byte followed by reserved bytes; both are carried by flags3 + reserved1.
struct NavPvt {
  static constexpr MsgId kMsg = kNavPvt;
  static constexpr std::size_t kPayloadSize = 92;
  // valid
  static constexpr std::uint8_t kValidDate = 0x01, kValidTime = 0x02, kFullyResolved = 0x04,
                                kValidMag = 0x08;
  // flags (carrSoln in bits 6..7: 1 float, 2 fixed)
  static constexpr std::uint8_t kGnssFixOk = 0x01, kDiffSoln = 0x02, kHeadVehValid = 0x20;
  // flags2
  static constexpr std::uint8_t kConfirmedAvai = 0x20, kConfirmedDate = 0x40,
                                kConfirmedTime = 0x80;

  std::uint32_t i_tow_ms = 0;
  std::uint16_t year = 0;  // UTC
  std::uint8_t month = 0, day = 0, hour = 0, min = 0, sec = 0;
  std::uint8_t valid = 0;
  std::uint32_t t_acc_ns = 0;
  std::int32_t nano_ns = 0;  // fraction of the second, -1e9..1e9
  std::uint8_t fix_type = 0, flags = 0, flags2 = 0, num_sv = 0;
  std::int32_t lon_1e7deg = 0, lat_1e7deg = 0;
  std::int32_t height_mm = 0;  // above the ellipsoid
  std::int32_t h_msl_mm = 0;   // above mean sea level
  std::uint32_t h_acc_mm = 0, v_acc_mm = 0;
  std::int32_t vel_n_mmps = 0, vel_e_mmps = 0, vel_d_mmps = 0, g_speed_mmps = 0;
  std::int32_t head_mot_1e5deg = 0;
  std::uint32_t s_acc_mmps = 0, head_acc_1e5deg = 0;
  std::uint16_t p_dop_0p01 = 0;
  std::uint16_t flags3 = 0;  // F9: X2; M8: X1 + one reserved byte
  std::array<std::uint8_t, 4> reserved1{};
  std::int32_t head_veh_1e5deg = 0;
  std::int16_t mag_dec_1e2deg = 0;
  std::uint16_t mag_acc_1e2deg = 0;
};

// UBX-NAV-POSLLH (0x01 0x02), 28 bytes.
struct NavPosllh {
  static constexpr MsgId kMsg = kNavPosllh;
  static constexpr std::size_t kPayloadSize = 28;
  std::uint32_t i_tow_ms = 0;
  std::int32_t lon_1e7deg = 0, lat_1e7deg = 0, height_mm = 0, h_msl_mm = 0;
  std::uint32_t h_acc_mm = 0, v_acc_mm = 0;
};

// UBX-NAV-POSECEF (0x01 0x01), 20 bytes.
struct NavPosecef {
  static constexpr MsgId kMsg = kNavPosecef;
  static constexpr std::size_t kPayloadSize = 20;
  std::uint32_t i_tow_ms = 0;
  std::int32_t ecef_x_cm = 0, ecef_y_cm = 0, ecef_z_cm = 0;
  std::uint32_t p_acc_cm = 0;
};

// UBX-NAV-VELNED (0x01 0x12), 36 bytes.
struct NavVelned {
  static constexpr MsgId kMsg = kNavVelned;
  static constexpr std::size_t kPayloadSize = 36;
  std::uint32_t i_tow_ms = 0;
  std::int32_t vel_n_cmps = 0, vel_e_cmps = 0, vel_d_cmps = 0;
  std::uint32_t speed_cmps = 0;    // 3-D
  std::uint32_t g_speed_cmps = 0;  // ground
  std::int32_t heading_1e5deg = 0;
  std::uint32_t s_acc_cmps = 0, c_acc_1e5deg = 0;
};

// UBX-NAV-VELECEF (0x01 0x11), 20 bytes.
struct NavVelecef {
  static constexpr MsgId kMsg = kNavVelecef;
  static constexpr std::size_t kPayloadSize = 20;
  std::uint32_t i_tow_ms = 0;
  std::int32_t ecef_vx_cmps = 0, ecef_vy_cmps = 0, ecef_vz_cmps = 0;
  std::uint32_t s_acc_cmps = 0;
};

// UBX-NAV-STATUS (0x01 0x03), 16 bytes.
struct NavStatus {
  static constexpr MsgId kMsg = kNavStatus;
  static constexpr std::size_t kPayloadSize = 16;
  // flags
  static constexpr std::uint8_t kGpsFixOk = 0x01, kDiffSoln = 0x02, kWknSet = 0x04,
                                kTowSet = 0x08;
  std::uint32_t i_tow_ms = 0;
  std::uint8_t gps_fix = 0, flags = 0, fix_stat = 0, flags2 = 0;
  std::uint32_t ttff_ms = 0;
  std::uint32_t msss_ms = 0;  // milliseconds since startup or reset
};

// UBX-NAV-SOL (0x01 0x06), 52 bytes (u-blox 8; not in protocol 27+).
struct NavSol {
  static constexpr MsgId kMsg = kNavSol;
  static constexpr std::size_t kPayloadSize = 52;
  // flags
  static constexpr std::uint8_t kGpsFixOk = 0x01, kDiffSoln = 0x02, kWknSet = 0x04,
                                kTowSet = 0x08;
  std::uint32_t i_tow_ms = 0;
  std::int32_t f_tow_ns = 0;  // -500000..500000
  std::int16_t week = 0;
  std::uint8_t gps_fix = 0, flags = 0;
  std::int32_t ecef_x_cm = 0, ecef_y_cm = 0, ecef_z_cm = 0;
  std::uint32_t p_acc_cm = 0;
  std::int32_t ecef_vx_cmps = 0, ecef_vy_cmps = 0, ecef_vz_cmps = 0;
  std::uint32_t s_acc_cmps = 0;
  std::uint16_t p_dop_0p01 = 0;
  std::uint8_t reserved1 = 0, num_sv = 0;
  std::array<std::uint8_t, 4> reserved2{};
};

// UBX-NAV-SVINFO (0x01 0x30), 8 + 12 * numCh bytes (u-blox 8; replaced by NAV-SAT).
struct NavSvinfoChannel {
  // flags
  static constexpr std::uint8_t kSvUsed = 0x01, kDiffCorr = 0x02, kOrbitAvail = 0x04,
                                kOrbitEph = 0x08, kUnhealthy = 0x10, kOrbitAlm = 0x20,
                                kOrbitAop = 0x40, kSmoothed = 0x80;
  std::uint8_t chn = 0;
  std::uint8_t svid = 0;  // u-blox numbering (GPS 1-32, SBAS 120-158, GLONASS 65-96, ...)
  std::uint8_t flags = 0;
  std::uint8_t quality = 0;  // qualityInd in bits 0..3
  std::uint8_t cno_dbhz = 0;
  std::int8_t elev_deg = 0;
  std::int16_t azim_deg = 0;
  std::int32_t pr_res_cm = 0;
};
struct NavSvinfo {
  static constexpr MsgId kMsg = kNavSvinfo;
  static constexpr std::size_t kHeaderSize = 8, kBlockSize = 12;
  std::uint32_t i_tow_ms = 0;
  std::uint8_t global_flags = 0;  // chipGen in bits 0..2 (4: u-blox 8)
  std::array<std::uint8_t, 2> reserved1{};
  std::vector<NavSvinfoChannel> channels;  // numCh = channels.size() (at most 255)
};

// UBX-NAV-DOP (0x01 0x04), 18 bytes.
struct NavDop {
  static constexpr MsgId kMsg = kNavDop;
  static constexpr std::size_t kPayloadSize = 18;
  std::uint32_t i_tow_ms = 0;
  std::uint16_t g_dop_0p01 = 0, p_dop_0p01 = 0, t_dop_0p01 = 0, v_dop_0p01 = 0, h_dop_0p01 = 0;
  std::uint16_t n_dop_0p01 = 0, e_dop_0p01 = 0;
};

// UBX-NAV-SAT (0x01 0x35), 8 + 12 * numSvs bytes.
struct NavSatSv {
  // flags: qualityInd bits 0..2, svUsed bit 3, health bits 4..5, diffCorr bit 6, smoothed
  // bit 7, orbitSource bits 8..10, ephAvail bit 11, almAvail bit 12, anoAvail 13, aopAvail 14,
  // sbasCorrUsed 16, rtcmCorrUsed 17, (slasCorrUsed 18, spartnCorrUsed 19), prCorrUsed 20,
  // crCorrUsed 21, doCorrUsed 22.
  static constexpr std::uint32_t kQualityMask = 0x7, kSvUsed = 0x8, kSmoothed = 0x80, kEphAvail = 0x800,
                                 kAlmAvail = 0x1000;
  static constexpr unsigned kHealthShift = 4, kOrbitSourceShift = 8;
  std::uint8_t gnss_id = 0;  // 0 GPS, 1 SBAS, 2 Galileo, 3 BeiDou, 5 QZSS, 6 GLONASS
  std::uint8_t sv_id = 0, cno_dbhz = 0;
  std::int8_t elev_deg = 0;  // -90..90
  std::int16_t azim_deg = 0;  // 0..360
  std::int16_t pr_res_dm = 0;  // pseudorange residual, 0.1 m
  std::uint32_t flags = 0;
};
struct NavSat {
  static constexpr MsgId kMsg = kNavSat;
  static constexpr std::size_t kHeaderSize = 8, kBlockSize = 12;
  std::uint32_t i_tow_ms = 0;
  std::uint8_t version = 1;
  std::array<std::uint8_t, 2> reserved1{};
  std::vector<NavSatSv> svs;  // numSvs = svs.size() (at most 255)
};

// UBX-NAV-TIMEGPS (0x01 0x20), 16 bytes.
struct NavTimegps {
  static constexpr MsgId kMsg = kNavTimegps;
  static constexpr std::size_t kPayloadSize = 16;
  // valid
  static constexpr std::uint8_t kTowValid = 0x01, kWeekValid = 0x02, kLeapSValid = 0x04;
  std::uint32_t i_tow_ms = 0;
  std::int32_t f_tow_ns = 0;
  std::int16_t week = 0;
  std::int8_t leap_s = 0;  // GPS - UTC
  std::uint8_t valid = 0;
  std::uint32_t t_acc_ns = 0;
};

// UBX-NAV-TIMEUTC (0x01 0x21), 20 bytes.
struct NavTimeutc {
  static constexpr MsgId kMsg = kNavTimeutc;
  static constexpr std::size_t kPayloadSize = 20;
  // valid (utcStandard in bits 4..7)
  static constexpr std::uint8_t kValidTow = 0x01, kValidWkn = 0x02, kValidUtc = 0x04;
  std::uint32_t i_tow_ms = 0, t_acc_ns = 0;
  std::int32_t nano_ns = 0;
  std::uint16_t year = 0;
  std::uint8_t month = 0, day = 0, hour = 0, min = 0, sec = 0;
  std::uint8_t valid = 0;
};

// UBX-NAV-CLOCK (0x01 0x22), 20 bytes.
struct NavClock {
  static constexpr MsgId kMsg = kNavClock;
  static constexpr std::size_t kPayloadSize = 20;
  std::uint32_t i_tow_ms = 0;
  std::int32_t clk_b_ns = 0;     // clock bias
  std::int32_t clk_d_nsps = 0;   // clock drift, ns/s
  std::uint32_t t_acc_ns = 0;
  std::uint32_t f_acc_psps = 0;  // frequency accuracy, ps/s
};

// UBX-NAV-EOE (0x01 0x61), 4 bytes: end of the epoch's navigation output.
struct NavEoe {
  static constexpr MsgId kMsg = kNavEoe;
  static constexpr std::size_t kPayloadSize = 4;
  std::uint32_t i_tow_ms = 0;
};

// ---- NAV, continued: high precision, odometer, orbits, geofences, survey-in, RTK, time ------
// Sections: UBX-13003221 R20 section 32.17 "UBX-NAV"; UBX-18010854 R04 section 5.14.

// UBX-NAV-HPPOSECEF (0x01 0x13), 28 bytes (M8 32.17.8, F9 5.14.5): the ECEF position to
// 0.1 mm, ecefX + ecefXHp * 1e-2 in cm. Byte 23 is flags (invalidEcef bit 0) in UBX-13003221
// R20; UBX-18010854 R04 calls it reserved2.
struct NavHpposecef {
  static constexpr MsgId kMsg = kNavHpposecef;
  static constexpr std::size_t kPayloadSize = 28;
  static constexpr std::uint8_t kInvalidEcef = 0x01;  // flags
  std::uint8_t version = 0;
  std::array<std::uint8_t, 3> reserved1{};
  std::uint32_t i_tow_ms = 0;
  std::int32_t ecef_x_cm = 0, ecef_y_cm = 0, ecef_z_cm = 0;
  std::int8_t ecef_x_hp_0p1mm = 0, ecef_y_hp_0p1mm = 0, ecef_z_hp_0p1mm = 0;  // -99..99
  std::uint8_t flags = 0;
  std::uint32_t p_acc_0p1mm = 0;
};

// UBX-NAV-HPPOSLLH (0x01 0x14), 36 bytes (M8 32.17.9, F9 5.14.6): lon + lonHp * 1e-2 in
// 1e-7 deg, height + heightHp * 0.1 in mm. Byte 3 is flags (invalidLlh bit 0) in R20; the
// F9 R04 table has reserved1[3] there.
struct NavHpposllh {
  static constexpr MsgId kMsg = kNavHpposllh;
  static constexpr std::size_t kPayloadSize = 36;
  static constexpr std::uint8_t kInvalidLlh = 0x01;  // flags
  std::uint8_t version = 0;
  std::array<std::uint8_t, 2> reserved1{};
  std::uint8_t flags = 0;
  std::uint32_t i_tow_ms = 0;
  std::int32_t lon_1e7deg = 0, lat_1e7deg = 0;
  std::int32_t height_mm = 0, h_msl_mm = 0;
  std::int8_t lon_hp_1e9deg = 0, lat_hp_1e9deg = 0;       // -99..99
  std::int8_t height_hp_0p1mm = 0, h_msl_hp_0p1mm = 0;    // -9..9
  std::uint32_t h_acc_0p1mm = 0, v_acc_0p1mm = 0;
};

// UBX-NAV-ODO (0x01 0x09), 20 bytes (M8 32.17.11, F9 5.14.7): odometer.
struct NavOdo {
  static constexpr MsgId kMsg = kNavOdo;
  static constexpr std::size_t kPayloadSize = 20;
  std::uint8_t version = 0;
  std::array<std::uint8_t, 3> reserved1{};
  std::uint32_t i_tow_ms = 0;
  std::uint32_t distance_m = 0;        // since the last NAV-RESETODO
  std::uint32_t total_distance_m = 0;  // since the last cold start
  std::uint32_t distance_std_m = 0;
};

// UBX-NAV-RESETODO (0x01 0x10), no payload (M8 32.17.17, F9 5.14.13): a command, answered
// with ACK-ACK or ACK-NAK.
struct NavResetodo {
  static constexpr MsgId kMsg = kNavResetodo;
  static constexpr std::size_t kPayloadSize = 0;
};

// UBX-NAV-ORB (0x01 0x34), 8 + 6 * numSv bytes (M8 32.17.12, F9 5.14.8): orbit database.
struct NavOrbSv {
  // svFlag: health bits 0..1, visibility bits 2..3; eph/alm/otherOrb: usability bits 0..4,
  // source (otherOrb: type) bits 5..7.
  std::uint8_t gnss_id = 0, sv_id = 0;
  std::uint8_t sv_flag = 0, eph = 0, alm = 0, other_orb = 0;
};
struct NavOrb {
  static constexpr MsgId kMsg = kNavOrb;
  static constexpr std::size_t kHeaderSize = 8, kBlockSize = 6;
  std::uint32_t i_tow_ms = 0;
  std::uint8_t version = 1;
  std::array<std::uint8_t, 2> reserved1{};
  std::vector<NavOrbSv> svs;  // numSv = svs.size() (at most 255)
};

// UBX-NAV-GEOFENCE (0x01 0x39), 8 + 2 * numFences bytes (M8 32.17.7, F9 5.14.4). The second
// byte of a block is the geofence id in R20 and reserved1 in F9 R04.
struct NavGeofenceFence {
  std::uint8_t state = 0;  // 0 unknown, 1 inside, 2 outside
  std::uint8_t id = 0;
};
struct NavGeofence {
  static constexpr MsgId kMsg = kNavGeofence;
  static constexpr std::size_t kHeaderSize = 8, kBlockSize = 2;
  std::uint32_t i_tow_ms = 0;
  std::uint8_t version = 0;
  std::uint8_t status = 0;      // 0 not available, 1 active
  std::uint8_t comb_state = 0;  // logical OR of all fences
  std::vector<NavGeofenceFence> fences;  // numFences = fences.size() (at most 255)
};

// UBX-NAV-SVIN (0x01 0x3B), 40 bytes (M8 32.17.24, F9 5.14.17): survey-in state; the mean
// position is meanX + meanXHP * 1e-2 in cm.
struct NavSvin {
  static constexpr MsgId kMsg = kNavSvin;
  static constexpr std::size_t kPayloadSize = 40;
  std::uint8_t version = 0;
  std::array<std::uint8_t, 3> reserved1{};
  std::uint32_t i_tow_ms = 0;
  std::uint32_t dur_s = 0;
  std::int32_t mean_x_cm = 0, mean_y_cm = 0, mean_z_cm = 0;
  std::int8_t mean_x_hp_0p1mm = 0, mean_y_hp_0p1mm = 0, mean_z_hp_0p1mm = 0;
  std::uint8_t reserved2 = 0;
  std::uint32_t mean_acc_0p1mm = 0;
  std::uint32_t obs = 0;
  std::uint8_t valid = 0, active = 0;
  std::array<std::uint8_t, 2> reserved3{};
};

// UBX-NAV-RELPOSNED (0x01 0x3C): relative position of the rover to the reference station in
// its NED frame. Two versions told apart by the version byte: 0, 40 bytes (M8 protocol 20+,
// 32.17.16; also F9 R04 protocol 27.00, 5.14.12) and 1, 64 bytes with length and heading
// (F9 protocol 27.1x, the HPG 1.13 form PX4 reads). flags: gnssFixOK bit 0, diffSoln 1,
// relPosValid 2, carrSoln bits 3..4, isMoving 5, refPosMiss 6, refObsMiss 7 (version 1 adds
// relPosHeadingValid 8, relPosNormalized 9).
struct NavRelposnedV0 {
  static constexpr MsgId kMsg = kNavRelposned;
  static constexpr std::size_t kPayloadSize = 40;
  std::uint8_t version = 0, reserved1 = 0;
  std::uint16_t ref_station_id = 0;  // 0..4095
  std::uint32_t i_tow_ms = 0;
  std::int32_t rel_pos_n_cm = 0, rel_pos_e_cm = 0, rel_pos_d_cm = 0;
  std::int8_t rel_pos_hp_n_0p1mm = 0, rel_pos_hp_e_0p1mm = 0, rel_pos_hp_d_0p1mm = 0;
  std::uint8_t reserved2 = 0;
  std::uint32_t acc_n_0p1mm = 0, acc_e_0p1mm = 0, acc_d_0p1mm = 0;
  std::uint32_t flags = 0;
};
struct NavRelposned {
  static constexpr MsgId kMsg = kNavRelposned;
  static constexpr std::size_t kPayloadSize = 64;
  static constexpr std::uint32_t kGnssFixOk = 0x01, kDiffSoln = 0x02, kRelPosValid = 0x04,
                                 kIsMoving = 0x20, kRelPosHeadingValid = 0x100;
  static constexpr unsigned kCarrSolnShift = 3;
  std::uint8_t version = 1, reserved0 = 0;
  std::uint16_t ref_station_id = 0;
  std::uint32_t i_tow_ms = 0;
  std::int32_t rel_pos_n_cm = 0, rel_pos_e_cm = 0, rel_pos_d_cm = 0, rel_pos_length_cm = 0;
  std::int32_t rel_pos_heading_1e5deg = 0;
  std::array<std::uint8_t, 4> reserved1{};
  std::int8_t rel_pos_hp_n_0p1mm = 0, rel_pos_hp_e_0p1mm = 0, rel_pos_hp_d_0p1mm = 0,
              rel_pos_hp_length_0p1mm = 0;
  std::uint32_t acc_n_0p1mm = 0, acc_e_0p1mm = 0, acc_d_0p1mm = 0, acc_length_0p1mm = 0;
  std::uint32_t acc_heading_1e5deg = 0;
  std::array<std::uint8_t, 4> reserved2{};
  std::uint32_t flags = 0;
};

// UBX-NAV-COV (0x01 0x36), 64 bytes: position and velocity covariance, upper triangle of the
// NED matrices. F9 protocol 27.1x (not in UBX-18010854 R04 or in the M8); the layout is the
// one pyubx2, the ublox crate and ROS ublox_msgs agree on.
struct NavCov {
  static constexpr MsgId kMsg = kNavCov;
  static constexpr std::size_t kPayloadSize = 64;
  std::uint32_t i_tow_ms = 0;
  std::uint8_t version = 0, pos_cov_valid = 0, vel_cov_valid = 0;
  std::array<std::uint8_t, 9> reserved0{};
  float pos_cov_nn_m2 = 0, pos_cov_ne_m2 = 0, pos_cov_nd_m2 = 0, pos_cov_ee_m2 = 0,
        pos_cov_ed_m2 = 0, pos_cov_dd_m2 = 0;
  float vel_cov_nn_m2ps2 = 0, vel_cov_ne_m2ps2 = 0, vel_cov_nd_m2ps2 = 0, vel_cov_ee_m2ps2 = 0,
        vel_cov_ed_m2ps2 = 0, vel_cov_dd_m2ps2 = 0;
};

// UBX-NAV-SIG (0x01 0x43), 8 + 16 * numSigs bytes (F9 5.14.15; not in the M8): one block per
// tracked signal.
struct NavSigSignal {
  // sigFlags: health bits 0..1, prSmoothed 2, prUsed 3, crUsed 4, doUsed 5, prCorrUsed 6,
  // crCorrUsed 7, doCorrUsed 8.
  static constexpr std::uint16_t kPrSmoothed = 0x04, kPrUsed = 0x08, kCrUsed = 0x10, kDoUsed = 0x20,
                                 kPrCorrUsed = 0x40, kCrCorrUsed = 0x80;
  std::uint8_t gnss_id = 0, sv_id = 0, sig_id = 0;
  std::uint8_t freq_id = 0;    // GLONASS frequency slot + 7
  std::int16_t pr_res_dm = 0;  // pseudorange residual, 0.1 m
  std::uint8_t cno_dbhz = 0;
  std::uint8_t quality_ind = 0;  // 0..7 as NAV-SAT
  std::uint8_t corr_source = 0, iono_model = 0;
  std::uint16_t sig_flags = 0;
  std::array<std::uint8_t, 4> reserved2{};
};
struct NavSig {
  static constexpr MsgId kMsg = kNavSig;
  static constexpr std::size_t kHeaderSize = 8, kBlockSize = 16;
  std::uint32_t i_tow_ms = 0;
  std::uint8_t version = 0;
  std::array<std::uint8_t, 2> reserved1{};
  std::vector<NavSigSignal> signals;  // numSigs = signals.size() (at most 255)
};

// UBX-NAV-SBAS (0x01 0x32), 12 + 12 * cnt bytes (M8 32.17.19; not in F9 R04, but the F9P has its
// CFG-MSGOUT-UBX_NAV_SBAS items and answers it): SBAS status.
struct NavSbasSv {
  std::uint8_t svid = 0, flags = 0, udre = 0, sv_sys = 0, sv_service = 0, reserved2 = 0;
  std::int16_t prc_cm = 0;  // pseudorange correction
  std::array<std::uint8_t, 2> reserved3{};
  std::int16_t ic_cm = 0;  // ionosphere correction
};
struct NavSbas {
  static constexpr MsgId kMsg = kNavSbas;
  static constexpr std::size_t kHeaderSize = 12, kBlockSize = 12;
  std::uint32_t i_tow_ms = 0;
  std::uint8_t geo = 0;   // PRN of the GEO whose corrections are used
  std::uint8_t mode = 0;  // 0 disabled, 1 enabled integrity, 3 enabled test mode
  std::int8_t sys = -1;   // -1 unknown, 0 WAAS, 1 EGNOS, 2 MSAS, 3 GAGAN, 16 GPS
  std::uint8_t service = 0;
  std::array<std::uint8_t, 3> reserved1{};
  std::vector<NavSbasSv> svs;  // cnt = svs.size() (at most 255)
};

// UBX-NAV-SLAS (0x01 0x42), 20 + 8 * cnt bytes (u-blox 8 protocol 19.2+, F9 HPG "UBX-NAV-SLAS"):
// QZSS L1S SLAS status, the ground monitoring station and a correction per satellite.
struct NavSlasSv {
  std::uint8_t gnss_id = 0, sv_id = 0, reserved2 = 0;
  std::array<std::uint8_t, 3> reserved3{};
  std::int16_t prc_cm = 0;  // pseudorange correction
};
struct NavSlas {
  static constexpr MsgId kMsg = kNavSlas;
  static constexpr std::size_t kHeaderSize = 20, kBlockSize = 8;
  std::uint32_t i_tow_ms = 0;
  std::uint8_t version = 0;
  std::array<std::uint8_t, 3> reserved1{};
  std::int32_t gms_lon_1e3deg = 0, gms_lat_1e3deg = 0;
  std::uint8_t gms_code = 0, qzss_sv_id = 0;
  std::uint8_t service_flags = 0;  // gmsAvailable bit 0, qzssSvAvailable 1, testMode 2
  std::vector<NavSlasSv> svs;      // cnt = svs.size() (at most 255)
};

// UBX-NAV-DGPS (0x01 0x31), 16 + 12 * numCh bytes (M8 32.17.5; not on protocol 27+): the
// differential corrections the solution uses.
struct NavDgpsCh {
  std::uint8_t svid = 0;
  std::uint8_t flags = 0;  // channel bits 0..3, dgpsUsed bit 4
  std::uint16_t age_c_ms = 0;
  float prc_m = 0.0f, prrc_mps = 0.0f;
};
struct NavDgps {
  static constexpr MsgId kMsg = kNavDgps;
  static constexpr std::size_t kHeaderSize = 16, kBlockSize = 12;
  std::uint32_t i_tow_ms = 0;
  std::int32_t age_ms = 0;
  std::int16_t base_id = 0, base_health = 0;
  std::uint8_t status = 0;  // 0 none, 1 PR + PRR correction
  std::array<std::uint8_t, 2> reserved1{};
  std::vector<NavDgpsCh> channels;  // numCh = channels.size() (at most 255)
};

// UBX-NAV-AOPSTATUS (0x01 0x60), 16 bytes (M8 32.17.2): AssistNow Autonomous.
struct NavAopstatus {
  static constexpr MsgId kMsg = kNavAopstatus;
  static constexpr std::size_t kPayloadSize = 16;
  std::uint32_t i_tow_ms = 0;
  std::uint8_t aop_cfg = 0;  // useAOP bit 0
  std::uint8_t status = 0;   // 0 idle, otherwise running
  std::array<std::uint8_t, 10> reserved1{};
};

// UBX-NAV-TIMELS (0x01 0x26), 24 bytes (M8 32.17.29, F9 5.14.22): leap second event.
struct NavTimels {
  static constexpr MsgId kMsg = kNavTimels;
  static constexpr std::size_t kPayloadSize = 24;
  static constexpr std::uint8_t kValidCurrLs = 0x01, kValidTimeToLsEvent = 0x02;  // valid
  std::uint32_t i_tow_ms = 0;
  std::uint8_t version = 0;
  std::array<std::uint8_t, 3> reserved1{};
  std::uint8_t src_of_curr_ls = 0;
  std::int8_t curr_ls_s = 0;  // GPS - UTC
  std::uint8_t src_of_ls_change = 0;
  std::int8_t ls_change_s = 0;
  std::int32_t time_to_ls_event_s = 0;
  std::uint16_t date_of_ls_gps_wn = 0, date_of_ls_gps_dn = 0;
  std::array<std::uint8_t, 3> reserved2{};
  std::uint8_t valid = 0;
};

// UBX-NAV-TIMEBDS (0x01 0x24), UBX-NAV-TIMEGAL (0x01 0x25), UBX-NAV-TIMEGLO (0x01 0x23), 20
// bytes each (M8 32.17.25-27, F9 5.14.18-20): the system's time of the epoch. NAV-TIMEQZSS is
// in neither description (later F9 firmware).
struct NavTimebds {
  static constexpr MsgId kMsg = kNavTimebds;
  static constexpr std::size_t kPayloadSize = 20;
  std::uint32_t i_tow_ms = 0, sow_s = 0;
  std::int32_t f_sow_ns = 0;  // -5e8..5e8
  std::int16_t week = 0;
  std::int8_t leap_s = 0;  // BDS - UTC
  std::uint8_t valid = 0;  // sowValid bit 0, weekValid 1, leapSValid 2
  std::uint32_t t_acc_ns = 0;
};
struct NavTimegal {
  static constexpr MsgId kMsg = kNavTimegal;
  static constexpr std::size_t kPayloadSize = 20;
  std::uint32_t i_tow_ms = 0, gal_tow_s = 0;
  std::int32_t f_gal_tow_ns = 0;
  std::int16_t gal_wno = 0;
  std::int8_t leap_s = 0;  // Galileo - UTC
  std::uint8_t valid = 0;  // galTowValid bit 0, galWnoValid 1, leapSValid 2
  std::uint32_t t_acc_ns = 0;
};
struct NavTimeglo {
  static constexpr MsgId kMsg = kNavTimeglo;
  static constexpr std::size_t kPayloadSize = 20;
  std::uint32_t i_tow_ms = 0, tod_s = 0;  // GLONASS time of day
  std::int32_t f_tod_ns = 0;
  std::uint16_t nt_days = 0;  // day in the four-year interval, 1..1461
  std::uint8_t n4 = 0;        // four-year interval from 1996 (1 = 1996)
  std::uint8_t valid = 0;     // todValid bit 0, dateValid 1
  std::uint32_t t_acc_ns = 0;
};

// ---- RXM -----------------------------------------------------------------------------------

// UBX-RXM-RAWX (0x02 0x15), 16 + 32 * numMeas bytes: raw measurements. Byte 13 is the message
// version (1; the earliest M8 descriptions call it reserved, and a NEO-M8T already sends 1).
// Byte 22 of a block is sigId in protocol 27+ (F9), reserved (0) on M8.
struct RxmRawxMeas {
  // trkStat
  static constexpr std::uint8_t kPrValid = 0x01, kCpValid = 0x02, kHalfCyc = 0x04,
                                kSubHalfCyc = 0x08;
  double pr_mes_m = 0.0, cp_mes_cycles = 0.0;
  float do_mes_hz = 0.0f;
  std::uint8_t gnss_id = 0, sv_id = 0;
  std::uint8_t sig_id = 0;   // M8: reserved
  std::uint8_t freq_id = 0;  // GLONASS frequency slot + 7
  std::uint16_t locktime_ms = 0;  // carrier phase lock time, capped at 64500
  std::uint8_t cno_dbhz = 0;
  std::uint8_t pr_stdev = 0;  // bits 0..3: n, sigma = 0.01 * 2^n m
  std::uint8_t cp_stdev = 0;  // bits 0..3: n, sigma = 0.004 * n cycles (15 = invalid)
  std::uint8_t do_stdev = 0;  // bits 0..3: n, sigma = 0.002 * 2^n Hz
  std::uint8_t trk_stat = 0, reserved3 = 0;
};
// The stdev fields from a 1-sigma (F9 HPG 1.32 interface description, UBX-RXM-RAWX): the
// index whose value is nearest, on a log scale for the 2^n fields; cpStdev at least 1 (0 would
// claim a perfect phase) and 15 ("invalid") from 0.058 cycles up.
std::uint8_t rawx_pr_stdev(double sigma_m);
std::uint8_t rawx_cp_stdev(double sigma_cycles);
std::uint8_t rawx_do_stdev(double sigma_hz);
struct RxmRawx {
  static constexpr MsgId kMsg = kRxmRawx;
  static constexpr std::size_t kHeaderSize = 16, kBlockSize = 32;
  // recStat
  static constexpr std::uint8_t kLeapSec = 0x01, kClkReset = 0x02;
  double rcv_tow_s = 0.0;
  std::uint16_t week = 0;
  std::int8_t leap_s = 0;
  std::uint8_t rec_stat = 0, version = 1;
  std::array<std::uint8_t, 2> reserved1{};
  std::vector<RxmRawxMeas> meas;  // numMeas = meas.size() (at most 255)
};

// UBX-RXM-SFRBX (0x02 0x13), 8 + 4 * numWords bytes: broadcast navigation data subframe. For
// GPS L1 C/A: 10 words, each holding the 30-bit word (24 data bits, 6 parity bits) in bits
// 0..29, TLM preamble 0x8B in bits 22..29 of the first word. Protocol 27 (F9) uses byte 2 as
// sigId (M8: reserved).
struct RxmSfrbx {
  static constexpr MsgId kMsg = kRxmSfrbx;
  static constexpr std::size_t kHeaderSize = 8;
  std::uint8_t gnss_id = 0, sv_id = 0;
  std::uint8_t sig_id = 0;   // M8: reserved
  std::uint8_t freq_id = 0, chn = 0;
  std::uint8_t version = 2;  // M8 protocol 18+: 2
  std::uint8_t reserved2 = 0;
  std::vector<std::uint32_t> words;  // numWords = words.size() (at most 255)
};

// UBX-RXM-RTCM (0x02 0x32), 8 bytes, version 2 (M8 32.18.6, F9 section 5.15): one RTCM
// message received. flags: crcFailed bit 0, msgUsed bits 1..2 (2 used, 1 not used, 0 unknown).
struct RxmRtcm {
  static constexpr MsgId kMsg = kRxmRtcm;
  static constexpr std::size_t kPayloadSize = 8;
  static constexpr unsigned kMsgUsedShift = 1;
  std::uint8_t version = 2, flags = 0;
  std::uint16_t sub_type = 0;     // only for u-blox proprietary message 4072
  std::uint16_t ref_station = 0;  // DF003; 0xFFFF for messages without it
  std::uint16_t msg_type = 0;
};

// UBX-RXM-MEASX (0x02 0x14), 44 + 24 * numSV bytes (M8 32.18.2; ZED-F9P UBX-18010854 5.15.1):
// the satellite measurements of RRLP (3GPP TS 44.031, "GPS Measurement Information"): per
// satellite the code phase within the 1 ms code period and the Doppler, against the reference
// time of week of each system.
struct RxmMeasxSv {
  std::uint8_t gnss_id = 0, sv_id = 0, cno_dbhz = 0;
  std::uint8_t mpath_indic = 0;  // 0 not measured, 1 low, 2 medium, 3 high
  std::int32_t doppler_4cmps = 0;   // Doppler as a velocity, 0.04 m/s
  std::int32_t doppler_200mhz = 0;  // 0.2 Hz
  std::uint16_t whole_chips = 0;  // code phase, whole chips 0..1022
  std::uint16_t frac_chips = 0;   // and 1/1024 chips 0..1023
  std::uint32_t code_phase_2m21ms = 0;  // the same fraction of a ms, 2^-21 ms
  std::uint8_t int_code_phase_ms = 0;  // whole ms
  std::uint8_t pseu_range_rms_err = 0;  // RRLP pseudorange RMS error index
  std::array<std::uint8_t, 2> reserved5{};
};
struct RxmMeasx {
  static constexpr MsgId kMsg = kRxmMeasx;
  static constexpr std::size_t kHeaderSize = 44, kBlockSize = 24;
  static constexpr std::uint8_t kTowSetMask = 0x03;  // flags: towSet, 0 not set, 1 or 2 set
  std::uint8_t version = 1;
  std::array<std::uint8_t, 3> reserved1{};
  std::uint32_t gps_tow_ms = 0, glo_tow_ms = 0, bds_tow_ms = 0;
  std::array<std::uint8_t, 4> reserved2{};
  std::uint32_t qzss_tow_ms = 0;
  std::uint16_t gps_tow_acc_2m4ms = 0, glo_tow_acc_2m4ms = 0, bds_tow_acc_2m4ms = 0;  // 2^-4 ms
  std::array<std::uint8_t, 2> reserved3{};
  std::uint16_t qzss_tow_acc_2m4ms = 0;
  std::uint8_t flags = 0;
  std::array<std::uint8_t, 8> reserved4{};
  std::vector<RxmMeasxSv> svs;  // numSV = svs.size() (at most 255)
};

// UBX-RXM-IMES (0x02 0x61), 4 + 44 * numTx bytes (M8 32.18.1; not on protocol 27+): the Indoor
// Messaging System transmitters received.
struct RxmImesTx {
  std::uint8_t reserved2 = 0, tx_id = 0;
  std::array<std::uint8_t, 3> reserved3{};
  std::uint8_t cno_dbhz = 0;
  std::array<std::uint8_t, 2> reserved4{};
  std::int32_t doppler_2m12hz = 0;
  std::uint32_t position1_1 = 0, position1_2 = 0, position2_1 = 0;
  std::int32_t lat = 0, lon = 0;  // 180/2^23 deg (position 2)
  std::uint32_t short_id_frame = 0, medium_id_lsb = 0, medium_id_2 = 0;
};
struct RxmImes {
  static constexpr MsgId kMsg = kRxmImes;
  static constexpr std::size_t kHeaderSize = 4, kBlockSize = 44;
  std::uint8_t version = 1;
  std::array<std::uint8_t, 2> reserved1{};
  std::vector<RxmImesTx> txs;  // numTx = txs.size() (at most 255)
};

// ---- INF -----------------------------------------------------------------------------------

// UBX-INF-ERROR/WARNING/NOTICE/TEST/DEBUG (0x04 0x00..0x04), 0 + N bytes (M8 32.13, F9 5.10):
// an ASCII text of the payload's length, without a terminating NUL; every byte is kept.
template <std::uint8_t Id>
struct Inf {
  static constexpr MsgId kMsg{kClassInf, Id};
  std::string str;
};
using InfError = Inf<kInfError.id>;
using InfWarning = Inf<kInfWarning.id>;
using InfNotice = Inf<kInfNotice.id>;
using InfTest = Inf<kInfTest.id>;
using InfDebug = Inf<kInfDebug.id>;

// ---- ACK -----------------------------------------------------------------------------------

// UBX-ACK-ACK (0x05 0x01) and UBX-ACK-NAK (0x05 0x00), 2 bytes: the acknowledged message.
struct AckAck {
  static constexpr MsgId kMsg = kAckAck;
  static constexpr std::size_t kPayloadSize = 2;
  std::uint8_t cls_id = 0, msg_id = 0;
};
struct AckNak {
  static constexpr MsgId kMsg = kAckNak;
  static constexpr std::size_t kPayloadSize = 2;
  std::uint8_t cls_id = 0, msg_id = 0;
};

// ---- UPD, AID, MGA ------------------------------------------------------------------------

// UBX-UPD-SOS (0x09 0x14) (ZED-F9P UBX-18010854 5.18.1; u-blox 8 protocol 15+ on flash parts):
// the backup of the battery-backed RAM in flash. Input: the poll (empty; answered with the
// "system restored" form), create (cmd 0) and clear (cmd 1), 4 bytes. Output, 8 bytes: the
// backup creation acknowledgement (cmd 2; response 0 not acknowledged, 1 acknowledged) and
// whether the system was restored from a backup at start-up (cmd 3; response 0 unknown,
// 1 failed, 2 restored, 3 not restored: no backup).
struct UpdSosCommand {
  static constexpr MsgId kMsg = kUpdSos;
  static constexpr std::uint8_t kCreate = 0, kClear = 1;
  std::uint8_t cmd = 0;
  std::array<std::uint8_t, 3> reserved1{};
};
struct UpdSos {
  static constexpr MsgId kMsg = kUpdSos;
  static constexpr std::size_t kPayloadSize = 8;
  static constexpr std::uint8_t kCreationAck = 2, kRestored = 3;
  std::uint8_t cmd = 0;
  std::array<std::uint8_t, 3> reserved1{};
  std::uint8_t response = 0;
  std::array<std::uint8_t, 3> reserved2{};
};

// UBX-AID-INI (0x0B 0x01), 48 bytes (u-blox 8 UBX-13003221, UBX-AID-INI; not on protocol 27+):
// the aiding position, time and clock drift; a poll (empty) is answered with the receiver's own.
struct AidIni {
  static constexpr MsgId kMsg = kAidIni;
  static constexpr std::size_t kPayloadSize = 48;
  // flags
  static constexpr std::uint32_t kPos = 0x01, kTime = 0x02, kClockD = 0x04, kLla = 0x20;
  std::int32_t ecef_x_or_lat = 0, ecef_y_or_lon = 0, ecef_z_or_alt = 0;  // cm (or 1e-7 deg)
  std::uint32_t pos_acc_cm = 0;
  std::uint16_t tm_cfg = 0;
  std::uint16_t wno_or_date = 0;
  std::uint32_t tow_or_time_ms = 0;
  std::int32_t tow_ns = 0;
  std::uint32_t t_acc_ms = 0, t_acc_ns = 0;
  std::int32_t clk_d_or_freq = 0;          // ns/s (or 1e-2 Hz)
  std::uint32_t clk_d_acc_or_freq_acc = 0;  // ns/s (or ppb)
  std::uint32_t flags = 0;
};

// UBX-AID-HUI (0x0B 0x02), 72 bytes (u-blox 8, UBX-AID-HUI): GPS health, UTC and Klobuchar
// parameters as the satellites broadcast them (IS-GPS-200 20.3.3.5.1.6/7), in SI units.
struct AidHui {
  static constexpr MsgId kMsg = kAidHui;
  static constexpr std::size_t kPayloadSize = 72;
  static constexpr std::uint32_t kHealthValid = 0x01, kUtcValid = 0x02, kKlobValid = 0x04;
  std::uint32_t health = 0;  // bit n-1: SV n healthy
  double utc_a0_s = 0.0, utc_a1_sps = 0.0;
  std::int32_t utc_tow_s = 0;
  std::int16_t utc_wnt = 0, utc_ls_s = 0, utc_wnf = 0, utc_dn = 0, utc_lsf_s = 0, utc_spare = 0;
  std::array<float, 4> klob_a{}, klob_b{};  // s, s/semicircle, s/semicircle^2, s/semicircle^3
  std::uint32_t flags = 0;
};

// UBX-AID-ALM (0x0B 0x30) and UBX-AID-EPH (0x0B 0x31) (u-blox 8): a GPS satellite's almanac
// (8 or 40 bytes) and ephemeris (8 or 104 bytes). The words are those after the HOW (words
// 3..10) of the almanac page and of subframes 1-3, parity removed, the 24 data bits in bits
// 0..23. Without data only the first two fields are sent: week 0 (ALM), how 0 (EPH). A poll is
// empty (all 32 satellites) or names one satellite (1 byte, AidSvPoll).
struct AidAlm {
  static constexpr MsgId kMsg = kAidAlm;
  std::uint32_t svid = 0, week = 0;
  bool has_data = false;
  std::array<std::uint32_t, 8> dwrd{};
};
struct AidEph {
  static constexpr MsgId kMsg = kAidEph;
  std::uint32_t svid = 0, how = 0;
  bool has_data = false;
  std::array<std::uint32_t, 8> sf1d{}, sf2d{}, sf3d{};
};
template <std::uint8_t Id>
struct AidSvPoll {
  static constexpr MsgId kMsg{kClassAid, Id};
  std::uint8_t svid = 0;
};
using AidAlmPoll = AidSvPoll<kAidAlm.id>;
using AidEphPoll = AidSvPoll<kAidEph.id>;
using AidAopPoll = AidSvPoll<kAidAop.id>;

// UBX-MGA-ACK-DATA0 (0x13 0x60), 8 bytes (ZED-F9P UBX-18010854 5.12.1; u-blox 8): an assistance
// message taken (type 1) or not (type 0, infoCode why), with the first 4 bytes of its payload;
// after an MGA-DBD dump, msgPayloadStart counts the MGA-DBD messages sent.
struct MgaAck {
  static constexpr MsgId kMsg = kMgaAck;
  static constexpr std::size_t kPayloadSize = 8;
  std::uint8_t type = 1, version = 0, info_code = 0, msg_id = 0;
  std::uint32_t msg_payload_start = 0;
};

// UBX-MGA-DBD (0x13 0x80), 12 + N bytes (ZED-F9P UBX-18010854 5.12.3; u-blox 8): one entry of
// the navigation database, its data firmware-specific (only for the receiver that made it).
struct MgaDbd {
  static constexpr MsgId kMsg = kMgaDbd;
  static constexpr std::size_t kHeaderSize = 12;
  std::array<std::uint8_t, 12> reserved1{};
  std::vector<std::uint8_t> data;
};

// ---- MON -----------------------------------------------------------------------------------

// UBX-MON-VER (0x0A 0x04), 40 + 30 * N bytes: swVersion (30 chars), hwVersion (10 chars) and N
// extension strings of 30 chars (e.g. "PROTVER=18.00", "FWVER=SPG 3.01", "MOD=..."), each
// NUL-terminated and NUL-padded. append() truncates a longer string to 29 characters so the
// terminator is kept; decode() stops each string at its first NUL.
struct MonVer {
  static constexpr MsgId kMsg = kMonVer;
  static constexpr std::size_t kSwSize = 30, kHwSize = 10, kExtensionSize = 30;
  std::string sw_version, hw_version;
  std::vector<std::string> extensions;
};

// UBX-MON-HW (0x0A 0x09), 60 bytes (u-blox 7/8 layout; u-blox 6 sent 68 bytes with a longer
// VP array, so only 60 is accepted; replaced by MON-RF in protocol 27+).
struct MonHw {
  static constexpr MsgId kMsg = kMonHw;
  static constexpr std::size_t kPayloadSize = 60;
  // aStatus
  static constexpr std::uint8_t kAntInit = 0, kAntDontKnow = 1, kAntOk = 2, kAntShort = 3,
                                kAntOpen = 4;
  std::uint32_t pin_sel = 0, pin_bank = 0, pin_dir = 0, pin_val = 0;
  std::uint16_t noise_per_ms = 0;
  std::uint16_t agc_cnt = 0;  // 0..8191
  std::uint8_t a_status = 0;
  std::uint8_t a_power = 0;  // 0 off, 1 on, 2 don't know
  std::uint8_t flags = 0;    // rtcCalib bit 0, safeBoot 1, jammingState bits 2..3, xtalAbsent 4
  std::uint8_t reserved1 = 0;
  std::uint32_t used_mask = 0;
  std::array<std::uint8_t, 17> vp{};
  std::uint8_t jam_ind = 0;  // CW jamming indicator, 0..255
  std::array<std::uint8_t, 2> reserved2{};
  std::uint32_t pin_irq = 0, pull_h = 0, pull_l = 0;
};

// Sections: UBX-13003221 R20 section 32.16 "UBX-MON"; UBX-18010854 R04 section 5.13.

// UBX-MON-RF (0x0A 0x38), 4 + 24 * nBlocks bytes (F9 5.13.9; replaces MON-HW): one block per
// RF front end (L1, L2/L5).
struct MonRfBlock {
  static constexpr std::uint8_t kJammingStateMask = 0x03;  // flags: 0 unknown, 1 ok, 2 warning, 3 critical
  std::uint8_t block_id = 0, flags = 0;
  std::uint8_t ant_status = 0;  // as MON-HW aStatus: 2 OK
  std::uint8_t ant_power = 0;   // 0 off, 1 on, 2 don't know
  std::uint32_t post_status = 0;
  std::array<std::uint8_t, 4> reserved2{};
  std::uint16_t noise_per_ms = 0, agc_cnt = 0;  // agcCnt 0..8191
  std::uint8_t jam_ind = 0;                     // CW jamming indicator, 0..255
  std::int8_t ofs_i = 0;
  std::uint8_t mag_i = 0;
  std::int8_t ofs_q = 0;
  std::uint8_t mag_q = 0;
  std::array<std::uint8_t, 3> reserved3{};
};
struct MonRf {
  static constexpr MsgId kMsg = kMonRf;
  static constexpr std::size_t kHeaderSize = 4, kBlockSize = 24;
  std::uint8_t version = 0;
  std::array<std::uint8_t, 2> reserved1{};
  std::vector<MonRfBlock> blocks;  // nBlocks = blocks.size() (at most 255)
};

// UBX-MON-HW2 (0x0A 0x0B), 28 bytes (M8 32.16.3, F9 5.13.4): I/Q imbalance and POST status.
struct MonHw2 {
  static constexpr MsgId kMsg = kMonHw2;
  static constexpr std::size_t kPayloadSize = 28;
  std::int8_t ofs_i = 0;
  std::uint8_t mag_i = 0;
  std::int8_t ofs_q = 0;
  std::uint8_t mag_q = 0;
  std::uint8_t cfg_source = 0;  // 114 ROM, 111 OTP, 112 config pins, 102 flash image
  std::array<std::uint8_t, 3> reserved1{};
  std::uint32_t low_lev_cfg = 0;
  std::array<std::uint8_t, 8> reserved2{};
  std::uint32_t post_status = 0;
  std::array<std::uint8_t, 4> reserved3{};
};

// UBX-MON-HW3 (0x0A 0x37), 22 + 6 * nPins bytes (F9 5.13.5; not in the M8): I/O pin states.
struct MonHw3Pin {
  std::uint16_t pin_id = 0, pin_mask = 0;
  std::uint8_t vp = 0, reserved2 = 0;
};
struct MonHw3 {
  static constexpr MsgId kMsg = kMonHw3;
  static constexpr std::size_t kHeaderSize = 22, kBlockSize = 6;
  static constexpr std::size_t kHwVersionSize = 10;
  std::uint8_t version = 0;
  std::uint8_t flags = 0;  // rtcCalib bit 0, safeBoot 1, xtalAbsent 2
  std::string hw_version;  // CH[10], NUL-terminated as in MON-VER
  std::array<std::uint8_t, 9> reserved1{};
  std::vector<MonHw3Pin> pins;  // nPins = pins.size() (at most 255)
};

// UBX-MON-COMMS (0x0A 0x36), 8 + 40 * nPorts bytes (F9 5.13.1; not in the M8): one block per
// port in use. protIds names the protocols of the msgs counters (0 UBX, 1 NMEA, 2 RTCM2,
// 5 RTCM3; R04 writes 256 for "none", which a U1 cannot hold: 0xFF is sent).
struct MonCommsPort {
  std::uint16_t port_id = 0, tx_pending_bytes = 0;
  std::uint32_t tx_bytes = 0;
  std::uint8_t tx_usage_pct = 0, tx_peak_usage_pct = 0;
  std::uint16_t rx_pending_bytes = 0;
  std::uint32_t rx_bytes = 0;
  std::uint8_t rx_usage_pct = 0, rx_peak_usage_pct = 0;
  std::uint16_t overrun_errs = 0;  // 100 ms timeslots with overrun errors
  std::array<std::uint16_t, 4> msgs{};  // messages parsed, per protocol of protIds
  std::array<std::uint8_t, 8> reserved2{};
  std::uint32_t skipped_bytes = 0;
};
struct MonComms {
  static constexpr MsgId kMsg = kMonComms;
  static constexpr std::size_t kHeaderSize = 8, kBlockSize = 40;
  std::uint8_t version = 0;
  std::uint8_t tx_errors = 0;  // mem bit 0, alloc 1
  std::uint8_t reserved1 = 0;
  std::array<std::uint8_t, 4> prot_ids{};
  std::vector<MonCommsPort> ports;  // nPorts = ports.size() (at most 255)
};

// UBX-MON-GNSS (0x0A 0x28), 8 bytes, version 1 (M8 32.16.2, F9 5.13.2): major GNSS, bit masks
// GPS bit 0, GLONASS 1, BeiDou 2, Galileo 3.
struct MonGnss {
  static constexpr MsgId kMsg = kMonGnss;
  static constexpr std::size_t kPayloadSize = 8;
  std::uint8_t version = 1;
  std::uint8_t supported = 0, default_gnss = 0, enabled = 0;
  std::uint8_t simultaneous = 0;
  std::array<std::uint8_t, 3> reserved1{};
};

// UBX-MON-IO (0x0A 0x02), 20 * N bytes (M8 32.16.5, F9 5.13.6): one block per port (6 on
// u-blox 8).
struct MonIoPort {
  std::uint32_t rx_bytes = 0, tx_bytes = 0;
  std::uint16_t parity_errs = 0, framing_errs = 0, overrun_errs = 0, break_cond = 0;  // 100 ms slots
  std::array<std::uint8_t, 4> reserved1{};
};
struct MonIo {
  static constexpr MsgId kMsg = kMonIo;
  static constexpr std::size_t kHeaderSize = 0, kBlockSize = 20;
  std::vector<MonIoPort> ports;
};

// UBX-MON-MSGPP (0x0A 0x06), 120 bytes (M8 32.16.6, F9 5.13.7): messages parsed per protocol
// (8) on each of the 6 ports, and bytes skipped per port.
struct MonMsgpp {
  static constexpr MsgId kMsg = kMonMsgpp;
  static constexpr std::size_t kPayloadSize = 120;
  std::array<std::uint16_t, 8> msg1{}, msg2{}, msg3{}, msg4{}, msg5{}, msg6{};
  std::array<std::uint32_t, 6> skipped_bytes{};
};

// UBX-MON-PATCH (0x0A 0x27), 4 + 16 * nEntries bytes, nEntries a U2 (M8 32.16.7, F9 5.13.8).
struct MonPatchEntry {
  std::uint32_t patch_info = 0;  // activated bit 0, location bits 1..2
  std::uint32_t comparator_number = 0, patch_address = 0, patch_data = 0;
};
struct MonPatch {
  static constexpr MsgId kMsg = kMonPatch;
  static constexpr std::size_t kHeaderSize = 4, kBlockSize = 16;
  std::uint16_t version = 1;
  std::vector<MonPatchEntry> entries;  // nEntries = entries.size()
};

// UBX-MON-RXBUF (0x0A 0x07), 24 bytes, and UBX-MON-TXBUF (0x0A 0x08), 28 bytes (M8 32.16.8 and
// 32.16.11, F9 5.13.10 and 5.13.12): buffer use per port (6 targets).
struct MonRxbuf {
  static constexpr MsgId kMsg = kMonRxbuf;
  static constexpr std::size_t kPayloadSize = 24;
  std::array<std::uint16_t, 6> pending_bytes{};
  std::array<std::uint8_t, 6> usage_pct{}, peak_usage_pct{};
};
struct MonTxbuf {
  static constexpr MsgId kMsg = kMonTxbuf;
  static constexpr std::size_t kPayloadSize = 28;
  std::array<std::uint16_t, 6> pending_bytes{};
  std::array<std::uint8_t, 6> usage_pct{}, peak_usage_pct{};
  std::uint8_t t_usage_pct = 0, t_peak_usage_pct = 0;
  std::uint8_t errors = 0;  // limit bits 0..5, mem 6, alloc 7
  std::uint8_t reserved1 = 0;
};

// UBX-MON-SPAN (0x0A 0x31), 4 + 272 * numRfBlocks bytes: the RF spectrum of each front end,
// 256 points of 0.25 dB; point i lies at center + span * (i - 128) / 256. F9 protocol 27.1x
// (not in R04 or the M8); layout as pyubx2 and the ZED-F9T/RCB-F9T integration manuals give.
struct MonSpanBlock {
  std::array<std::uint8_t, 256> spectrum_0p25db{};
  std::uint32_t span_hz = 0, res_hz = 0, center_hz = 0;
  std::uint8_t pga_db = 0;
  std::array<std::uint8_t, 3> reserved1{};
};
struct MonSpan {
  static constexpr MsgId kMsg = kMonSpan;
  static constexpr std::size_t kHeaderSize = 4, kBlockSize = 272;
  std::uint8_t version = 0;
  std::array<std::uint8_t, 2> reserved0{};
  std::vector<MonSpanBlock> blocks;  // numRfBlocks = blocks.size()
};

// ---- SEC, TIM ------------------------------------------------------------------------------

// UBX-SEC-UNIQID (0x27 0x03), 9 bytes, version 1 (M8 32.19.1, F9 section 5.16): the 40-bit
// chip ID. The M10's version 2 carries 6 bytes and is not this message.
struct SecUniqid {
  static constexpr MsgId kMsg = kSecUniqid;
  static constexpr std::size_t kPayloadSize = 9;
  std::uint8_t version = 1;
  std::array<std::uint8_t, 3> reserved1{};
  std::array<std::uint8_t, 5> unique_id{};
};

// UBX-TIM-TP (0x0D 0x01), 16 bytes (M8 section 32.20, F9 5.17.2): time of the next time pulse.
struct TimTp {
  static constexpr MsgId kMsg = kTimTp;
  static constexpr std::size_t kPayloadSize = 16;
  std::uint32_t tow_ms = 0;
  std::uint32_t tow_sub_ms_2m32 = 0;  // sub-millisecond part, 2^-32 ms
  std::int32_t q_err_ps = 0;          // quantization error
  std::uint16_t week = 0;
  std::uint8_t flags = 0;     // timeBase bit 0, utc 1, raim bits 2..3, qErrInvalid 4
  std::uint8_t ref_info = 0;  // timeRefGnss bits 0..3, utcStandard bits 4..7
};

// UBX-TIM-TM2 (0x0D 0x03), 28 bytes (M8 section 32.20, F9 5.17.1): time mark on EXTINT.
struct TimTm2 {
  static constexpr MsgId kMsg = kTimTm2;
  static constexpr std::size_t kPayloadSize = 28;
  std::uint8_t ch = 0;
  std::uint8_t flags = 0;  // mode 0, run 1, newFallingEdge 2, timeBase 3..4, utc 5, time 6, newRisingEdge 7
  std::uint16_t count = 0, wn_r = 0, wn_f = 0;
  std::uint32_t tow_ms_r = 0, tow_sub_ms_r_ns = 0, tow_ms_f = 0, tow_sub_ms_f_ns = 0;
  std::uint32_t acc_est_ns = 0;
};

// UBX-TIM-VRFY (0x0D 0x06), 20 bytes (M8 32.20, F9 "UBX-TIM-VRFY"): the time last received
// from assistance data or the RTC, against the navigation time.
struct TimVrfy {
  static constexpr MsgId kMsg = kTimVrfy;
  static constexpr std::size_t kPayloadSize = 20;
  std::int32_t i_tow_ms = 0, frac_ns = 0;      // the sourced time of week
  std::int32_t delta_ms = 0, delta_ns = 0;     // sourced time - navigation time
  std::uint16_t wno = 0;
  std::uint8_t flags = 0;  // src bits 0..2: 0 no time aiding done, 2 RTC, 3 AID-INI
  std::uint8_t reserved1 = 0;
};

// ---- CFG -----------------------------------------------------------------------------------
// Every CFG message the receiver accepts is answered with ACK-ACK, or ACK-NAK when rejected; a
// poll is answered with the message followed by ACK-ACK (UBX-13003221 section 32.5).

// Port identifiers (CFG-PRT portID, CFG-MSG rate index).
inline constexpr std::uint8_t kPortDdc = 0;  // I2C
inline constexpr std::uint8_t kPortUart1 = 1;
inline constexpr std::uint8_t kPortUart2 = 2;
inline constexpr std::uint8_t kPortUsb = 3;
inline constexpr std::uint8_t kPortSpi = 4;
inline constexpr std::size_t kNumPorts = 6;  // CFG-MSG carries 6 rates (the last is reserved)

// Protocol masks of CFG-PRT inProtoMask / outProtoMask.
inline constexpr std::uint16_t kProtoUbx = 0x0001;
inline constexpr std::uint16_t kProtoNmea = 0x0002;
inline constexpr std::uint16_t kProtoRtcm = 0x0004;  // input only (RTCM 2)
inline constexpr std::uint16_t kProtoRtcm3 = 0x0020;

// UBX-CFG-PRT (0x06 0x00) poll: empty (the port the poll arrives on) or one byte (portID).
struct CfgPrtPoll {
  static constexpr MsgId kMsg = kCfgPrt;
  bool has_port_id = false;
  std::uint8_t port_id = 0;
};

// UBX-CFG-PRT (0x06 0x00), 20 bytes: port configuration (set, or the answer to a poll). For
// UART ports `mode` is the character framing (0x08C0 = 8N1) and `baud_rate` the bit rate; for
// USB both are reserved (0); for SPI/DDC `mode` holds the interface mode.
struct CfgPrt {
  static constexpr MsgId kMsg = kCfgPrt;
  static constexpr std::size_t kPayloadSize = 20;
  static constexpr std::uint32_t kMode8N1 = 0x000008C0;
  std::uint8_t port_id = 0, reserved1 = 0;
  std::uint16_t tx_ready = 0;
  std::uint32_t mode = 0, baud_rate = 0;
  std::uint16_t in_proto_mask = 0, out_proto_mask = 0;
  std::uint16_t flags = 0;  // extendedTxTimeout bit 1
  std::array<std::uint8_t, 2> reserved2{};
};

// UBX-CFG-PRT (0x06 0x00) set with several ports, 20 * N bytes, N >= 1 (UBX-13003221 R20
// 32.10.21.2: "Several configurations can be concatenated to one input message"; the answer
// to a poll is one block, CfgPrt). PX4's driver sends UART1 and USB in one 40-byte message.
struct CfgPrtPorts {
  static constexpr MsgId kMsg = kCfgPrt;
  static constexpr std::size_t kHeaderSize = 0, kBlockSize = CfgPrt::kPayloadSize;
  std::vector<CfgPrt> ports;
};

// UBX-CFG-MSG (0x06 0x01): three forms told apart by length.
//   2 bytes: poll the rates of one message (answer: the 8-byte form, then ACK-ACK);
//   3 bytes: set the rate on the port the message arrives on;
//   8 bytes: set the rates on all six ports (index = port ID).
// A rate is "output once every `rate` navigation solutions", 0 = off.
struct CfgMsgPoll {
  static constexpr MsgId kMsg = kCfgMsg;
  static constexpr std::size_t kPayloadSize = 2;
  std::uint8_t msg_class = 0, msg_id = 0;
};
struct CfgMsgCurrentPort {
  static constexpr MsgId kMsg = kCfgMsg;
  static constexpr std::size_t kPayloadSize = 3;
  std::uint8_t msg_class = 0, msg_id = 0, rate = 0;
};
struct CfgMsg {
  static constexpr MsgId kMsg = kCfgMsg;
  static constexpr std::size_t kPayloadSize = 8;
  std::uint8_t msg_class = 0, msg_id = 0;
  std::array<std::uint8_t, kNumPorts> rate{};  // indexed by port ID
};

// UBX-CFG-RATE (0x06 0x08), 6 bytes (poll: empty).
struct CfgRate {
  static constexpr MsgId kMsg = kCfgRate;
  static constexpr std::size_t kPayloadSize = 6;
  // timeRef
  static constexpr std::uint16_t kTimeRefUtc = 0, kTimeRefGps = 1, kTimeRefGlonass = 2,
                                 kTimeRefBeidou = 3, kTimeRefGalileo = 4;
  std::uint16_t meas_rate_ms = 1000;
  std::uint16_t nav_rate_cycles = 1;  // measurements per navigation solution
  std::uint16_t time_ref = kTimeRefGps;
};

// UBX-CFG-NAV5 (0x06 0x24), 36 bytes (poll: empty): navigation engine settings. Only the
// parameters whose bit is set in `mask` are applied by a set.
struct CfgNav5 {
  static constexpr MsgId kMsg = kCfgNav5;
  static constexpr std::size_t kPayloadSize = 36;
  // mask
  static constexpr std::uint16_t kMaskDyn = 0x0001, kMaskMinEl = 0x0002,
                                 kMaskPosFixMode = 0x0004, kMaskDrLim = 0x0008,
                                 kMaskPosMask = 0x0010, kMaskTimeMask = 0x0020,
                                 kMaskStaticHoldMask = 0x0040, kMaskDgpsMask = 0x0080,
                                 kMaskCnoThreshold = 0x0100, kMaskUtc = 0x0400;
  // dynModel
  static constexpr std::uint8_t kDynPortable = 0, kDynStationary = 2, kDynPedestrian = 3,
                                kDynAutomotive = 4, kDynSea = 5, kDynAirborne1g = 6,
                                kDynAirborne2g = 7, kDynAirborne4g = 8, kDynWrist = 9;
  std::uint16_t mask = 0;
  std::uint8_t dyn_model = 0;
  std::uint8_t fix_mode = 3;  // 1 2D only, 2 3D only, 3 auto
  std::int32_t fixed_alt_cm = 0;
  std::uint32_t fixed_alt_var_1e4m2 = 0;  // 0.0001 m^2
  std::int8_t min_elev_deg = 0;
  std::uint8_t dr_limit_s = 0;
  std::uint16_t p_dop_0p1 = 0, t_dop_0p1 = 0, p_acc_m = 0, t_acc_m = 0;
  std::uint8_t static_hold_thresh_cmps = 0;
  std::uint8_t dgnss_timeout_s = 0, cno_thresh_num_svs = 0, cno_thresh_dbhz = 0;
  std::array<std::uint8_t, 2> reserved1{};
  std::uint16_t static_hold_max_dist_m = 0;
  std::uint8_t utc_standard = 0;
  std::array<std::uint8_t, 5> reserved2{};
};

// UBX-CFG-GNSS (0x06 0x3E), 4 + 8 * numConfigBlocks bytes (poll: empty).
struct CfgGnssBlock {
  // flags: enable bit 0, sigCfgMask bits 16..23
  static constexpr std::uint32_t kEnable = 0x00000001;
  static constexpr unsigned kSigCfgMaskShift = 16;
  std::uint8_t gnss_id = 0, res_trk_ch = 0, max_trk_ch = 0, reserved1 = 0;
  std::uint32_t flags = 0;
};
struct CfgGnss {
  static constexpr MsgId kMsg = kCfgGnss;
  static constexpr std::size_t kHeaderSize = 4, kBlockSize = 8;
  std::uint8_t msg_ver = 0;
  std::uint8_t num_trk_ch_hw = 0;  // read only
  std::uint8_t num_trk_ch_use = 0;
  std::vector<CfgGnssBlock> blocks;  // numConfigBlocks = blocks.size() (at most 255)
};

// UBX-CFG-CFG (0x06 0x09), 12 or 13 bytes: clear, save or load configuration sections; the
// optional deviceMask selects the storage (BBR 0x01, flash 0x02, EEPROM 0x04, SPI flash 0x10).
struct CfgCfg {
  static constexpr MsgId kMsg = kCfgCfg;
  std::uint32_t clear_mask = 0, save_mask = 0, load_mask = 0;
  bool has_device_mask = false;
  std::uint8_t device_mask = 0;
};

// UBX-CFG-RST (0x06 0x04), 4 bytes: reset (not acknowledged by the receiver).
struct CfgRst {
  static constexpr MsgId kMsg = kCfgRst;
  static constexpr std::size_t kPayloadSize = 4;
  // navBbrMask special sets
  static constexpr std::uint16_t kHotStart = 0x0000, kWarmStart = 0x0001, kColdStart = 0xFFFF;
  // resetMode
  static constexpr std::uint8_t kHardwareReset = 0x00, kControlledSoftwareReset = 0x01,
                                kControlledSoftwareResetGnss = 0x02,
                                kHardwareResetAfterShutdown = 0x04, kControlledGnssStop = 0x08,
                                kControlledGnssStart = 0x09;
  std::uint16_t nav_bbr_mask = 0;
  std::uint8_t reset_mode = 0, reserved1 = 0;
};

// ---- CFG, the rest of the legacy configuration messages --------------------------------------
// Sections: UBX-13003221 R20 section 32.10 "UBX-CFG" (M8); UBX-18010854 R04 section 5.9 (F9,
// where they are deprecated in favour of CFG-VALSET but still accepted). Each is polled with
// an empty payload unless a poll form is given.

// UBX-CFG-INF (0x06 0x02), M8 32.10.11, F9 5.9.9: poll with a protocol ID (1 byte: 0 UBX,
// 1 NMEA), answered with one block; set with one or more 10-byte blocks.
struct CfgInfPoll {
  static constexpr MsgId kMsg = kCfgInf;
  static constexpr std::size_t kPayloadSize = 1;
  std::uint8_t protocol_id = 0;
};
struct CfgInfBlock {
  // infMsgMask bits: ERROR 0, WARNING 1, NOTICE 2, TEST 3, DEBUG 4
  std::uint8_t protocol_id = 0;
  std::array<std::uint8_t, 3> reserved1{};
  std::array<std::uint8_t, kNumPorts> inf_msg_mask{};  // indexed by port ID
};
struct CfgInf {
  static constexpr MsgId kMsg = kCfgInf;
  static constexpr std::size_t kHeaderSize = 0, kBlockSize = 10;
  std::vector<CfgInfBlock> blocks;  // at least one
};

// UBX-CFG-TP5 (0x06 0x31), M8 32.10.32, F9 5.9.23: poll (empty: time pulse 0; one byte: tpIdx)
// and 32-byte get/set, version 0 (M8 protocol 15) or 1 (later; same layout, other flags).
struct CfgTp5Poll {
  static constexpr MsgId kMsg = kCfgTp5;
  bool has_tp_idx = false;
  std::uint8_t tp_idx = 0;
};
struct CfgTp5 {
  static constexpr MsgId kMsg = kCfgTp5;
  static constexpr std::size_t kPayloadSize = 32;
  // flags: active bit 0, lockGnssFreq 1, lockedOtherSet 2, isFreq 3, isLength 4, alignToTow 5,
  // polarity 6, gridUtcGnss bits 7..10, syncMode bits 11..13
  std::uint8_t tp_idx = 0, version = 1;
  std::array<std::uint8_t, 2> reserved1{};
  std::int16_t ant_cable_delay_ns = 0, rf_group_delay_ns = 0;
  std::uint32_t freq_period_hz_or_us = 0, freq_period_lock_hz_or_us = 0;
  std::uint32_t pulse_len_ratio_us_or_2m32 = 0, pulse_len_ratio_lock_us_or_2m32 = 0;
  std::int32_t user_config_delay_ns = 0;
  std::uint32_t flags = 0;
};

// UBX-CFG-NMEA (0x06 0x17), M8 32.10.17, F9 5.9.15: three forms by length, each extending the
// one before: 4 bytes (deprecated), 12 bytes (version 0) and 20 bytes (version 1).
struct CfgNmea {
  static constexpr MsgId kMsg = kCfgNmea;
  static constexpr std::size_t kPayloadSize = 4;
  // flags: compat bit 0, consider 1, limit82 2, highPrec 3
  static constexpr std::uint8_t kHighPrec = 0x08;
  std::uint8_t filter = 0;
  std::uint8_t nmea_version = 0x41;  // 0x41 4.1, 0x40 4.0, 0x23 2.3, 0x21 2.1 (hex digits)
  std::uint8_t num_sv = 0;           // per talker ID, 0 unlimited
  std::uint8_t flags = 0;
  bool has_v0 = false;               // the 12-byte form's fields
  std::uint32_t gnss_to_filter = 0;  // GPS bit 0, SBAS 1, Galileo 2, QZSS 4, GLONASS 5, BeiDou 6
  std::uint8_t sv_numbering = 0, main_talker_id = 0, gsv_talker_id = 0, version = 0;
  bool has_v1 = false;  // the 20-byte form's fields
  std::array<std::uint8_t, 2> bds_talker_id{};  // CH[2], not NUL-terminated: "GB" or zeros
  std::array<std::uint8_t, 6> reserved1{};
};

// UBX-CFG-NAVX5 (0x06 0x23), M8 32.10.16, F9 5.9.14: 40 bytes, version 0 (M8 protocol 15-17;
// bytes 20..25 reserved4) or 2, or 44 bytes, version 3 (M8 protocol 19.1-19.2).
struct CfgNavx5 {
  static constexpr MsgId kMsg = kCfgNavx5;
  static constexpr std::size_t kPayloadSize = 40;
  // mask1: minMax bit 2, minCno 3, initial3dfix 6, wknRoll 9, ackAid 10, ppp 13, aop 14;
  // mask2: adr bit 6, sigAttenComp 7
  std::uint16_t version = 2, mask1 = 0;
  std::uint32_t mask2 = 0;
  std::array<std::uint8_t, 2> reserved1{};
  std::uint8_t min_svs = 0, max_svs = 0, min_cno_dbhz = 0, reserved2 = 0, ini_fix_3d = 0;
  std::array<std::uint8_t, 2> reserved3{};
  std::uint8_t ack_aiding = 0;
  std::uint16_t wkn_rollover = 0;
  std::uint8_t sig_atten_comp_mode_dbhz = 0, reserved4 = 0;
  std::array<std::uint8_t, 2> reserved5{}, reserved6{};
  std::uint8_t use_ppp = 0, aop_cfg = 0;
  std::array<std::uint8_t, 2> reserved7{};
  std::uint16_t aop_orb_max_err_m = 0;
  std::array<std::uint8_t, 4> reserved8{};
  std::array<std::uint8_t, 3> reserved9{};
  std::uint8_t use_adr = 0;
  bool has_v3 = false;  // the 44-byte form
  std::array<std::uint8_t, 2> reserved10{}, reserved11{};
};

// UBX-CFG-SBAS (0x06 0x16), 8 bytes (M8 32.10.27; not in F9 R04).
struct CfgSbas {
  static constexpr MsgId kMsg = kCfgSbas;
  static constexpr std::size_t kPayloadSize = 8;
  std::uint8_t mode = 0;       // enabled bit 0, test 1
  std::uint8_t usage = 0;      // range bit 0, diffCorr 1, integrity 2
  std::uint8_t max_sbas = 0;   // 0..3
  std::uint8_t scanmode2 = 0;  // PRN 152..158 in bits 0..6
  std::uint32_t scanmode1 = 0;  // PRN 120..151 in bits 0..31; 0: all
};

// UBX-CFG-ITFM (0x06 0x39), 8 bytes (M8 32.10.12, F9 5.9.10): jamming/interference monitor.
// config: bbThreshold bits 0..3, cwThreshold 4..8, algorithmBits 9..30, enable 31; config2:
// generalBits 0..11, antSetting 12..13, enable2 14.
struct CfgItfm {
  static constexpr MsgId kMsg = kCfgItfm;
  static constexpr std::size_t kPayloadSize = 8;
  static constexpr std::uint32_t kEnable = 0x80000000;
  std::uint32_t config = 0, config2 = 0;
};

// UBX-CFG-TMODE3 (0x06 0x71), 40 bytes (M8 32.10.31 protocol 20-20.3, F9 5.9.22): survey-in
// or fixed base. flags: mode bits 0..7 (0 disabled, 1 survey-in, 2 fixed), lla bit 8; the
// position is ECEF in cm (+ HP in 0.1 mm) or, with lla, lat/lon in 1e-7 deg (+ 1e-9 deg) and
// altitude in cm.
struct CfgTmode3 {
  static constexpr MsgId kMsg = kCfgTmode3;
  static constexpr std::size_t kPayloadSize = 40;
  static constexpr std::uint16_t kModeMask = 0x00FF, kLla = 0x0100;
  std::uint8_t version = 0, reserved1 = 0;
  std::uint16_t flags = 0;
  std::int32_t ecef_x_or_lat = 0, ecef_y_or_lon = 0, ecef_z_or_alt_cm = 0;
  std::int8_t ecef_x_or_lat_hp = 0, ecef_y_or_lon_hp = 0, ecef_z_or_alt_hp_0p1mm = 0;
  std::uint8_t reserved2 = 0;
  std::uint32_t fixed_pos_acc_0p1mm = 0, svin_min_dur_s = 0, svin_acc_limit_0p1mm = 0;
  std::array<std::uint8_t, 8> reserved3{};
};

// UBX-CFG-DGNSS (0x06 0x70), 4 bytes (M8 32.10.5 High Precision products, F9 5.9.4).
struct CfgDgnss {
  static constexpr MsgId kMsg = kCfgDgnss;
  static constexpr std::size_t kPayloadSize = 4;
  static constexpr std::uint8_t kRtkFloat = 2, kRtkFixed = 3;  // dgnssMode
  std::uint8_t dgnss_mode = kRtkFixed;
  std::array<std::uint8_t, 3> reserved1{};
};

// UBX-CFG-ODO (0x06 0x1E), 20 bytes (M8 32.10.18, F9 5.9.16). flags: useODO bit 0, useCOG 1,
// outLPVel 2, outLPCog 3; odoCfg: profile bits 0..2.
struct CfgOdo {
  static constexpr MsgId kMsg = kCfgOdo;
  static constexpr std::size_t kPayloadSize = 20;
  static constexpr std::uint8_t kUseOdo = 0x01;  // flags
  std::uint8_t version = 0;
  std::array<std::uint8_t, 3> reserved1{};
  std::uint8_t flags = 0, odo_cfg = 0;
  std::array<std::uint8_t, 6> reserved2{};
  std::uint8_t cog_max_speed_0p1mps = 0, cog_max_pos_acc_m = 0;
  std::array<std::uint8_t, 2> reserved3{};
  std::uint8_t vel_lp_gain = 0, cog_lp_gain = 0;
  std::array<std::uint8_t, 2> reserved4{};
};

// UBX-CFG-USB (0x06 0x1B), 108 bytes (M8 section 32.10, F9 5.9.24): USB descriptor settings.
struct CfgUsb {
  static constexpr MsgId kMsg = kCfgUsb;
  static constexpr std::size_t kPayloadSize = 108, kStringSize = 32;
  std::uint16_t vendor_id = 0, product_id = 0;
  std::array<std::uint8_t, 2> reserved1{}, reserved2{};
  std::uint16_t power_consumption_ma = 0;
  std::uint16_t flags = 0;  // reEnum bit 0, powerMode bit 1 (0 bus powered)
  std::string vendor_string, product_string, serial_number;  // CH[32] each
};

// UBX-CFG-ANT (0x06 0x13), 4 bytes (M8 32.10.1, F9 5.9.1): antenna supervisor. flags: svcs
// bit 0, scd 1, ocd 2, pdwnOnSCD 3, recovery 4; pins: pinSwitch bits 0..4, pinSCD 5..9,
// pinOCD 10..14, reconfig 15.
struct CfgAnt {
  static constexpr MsgId kMsg = kCfgAnt;
  static constexpr std::size_t kPayloadSize = 4;
  std::uint16_t flags = 0, pins = 0;
};

// UBX-CFG-PM2 (0x06 0x3B), M8 32.10.19 (not in F9 R04): 44 bytes (version 1) or 48 bytes
// (version 2, protocol 18+, with extintInactivityMs).
struct CfgPm2 {
  static constexpr MsgId kMsg = kCfgPm2;
  static constexpr std::size_t kPayloadSize = 44;
  std::uint8_t version = 2, reserved1 = 0, max_startup_state_dur_s = 0, reserved2 = 0;
  std::uint32_t flags = 0;
  std::uint32_t update_period_ms = 0, search_period_ms = 0, grid_offset_ms = 0;
  std::uint16_t on_time_s = 0, min_acq_time_s = 0;
  std::array<std::uint8_t, 20> reserved3{};
  bool has_extint_inactivity = false;  // the 48-byte form
  std::uint32_t extint_inactivity_ms = 0;
};

// UBX-CFG-RXM (0x06 0x11), 2 bytes (M8 32.10.26; not in F9 R04).
struct CfgRxm {
  static constexpr MsgId kMsg = kCfgRxm;
  static constexpr std::size_t kPayloadSize = 2;
  std::uint8_t reserved1 = 0;
  std::uint8_t lp_mode = 0;  // 0 or 4 continuous, 1 power save
};

// UBX-CFG-PMS (0x06 0x86), 8 bytes (M8 32.10.20; not in F9 R04): power mode setup.
struct CfgPms {
  static constexpr MsgId kMsg = kCfgPms;
  static constexpr std::size_t kPayloadSize = 8;
  std::uint8_t version = 0;
  std::uint8_t power_setup_value = 0;  // 0 full power ... 5 aggressive 4 Hz, 0xFF invalid
  std::uint16_t period_s = 0, on_time_s = 0;
  std::array<std::uint8_t, 2> reserved1{};
};

// UBX-CFG-PWR (0x06 0x57), 8 bytes (M8 32.10.22, F9 5.9.18): enter a power state.
struct CfgPwr {
  static constexpr MsgId kMsg = kCfgPwr;
  static constexpr std::size_t kPayloadSize = 8;
  static constexpr std::uint32_t kRunning = 0x52554E20, kStopped = 0x53544F50,
                                 kBackup = 0x42434B50;  // state
  std::uint8_t version = 1;
  std::array<std::uint8_t, 3> reserved1{};
  std::uint32_t state = kRunning;
};

// UBX-CFG-GEOFENCE (0x06 0x69), 8 + 12 * numFences bytes (M8 32.10.8, F9 5.9.7).
struct CfgGeofenceFence {
  std::int32_t lat_1e7deg = 0, lon_1e7deg = 0;
  std::uint32_t radius_cm = 0;
};
struct CfgGeofence {
  static constexpr MsgId kMsg = kCfgGeofence;
  static constexpr std::size_t kHeaderSize = 8, kBlockSize = 12;
  std::uint8_t version = 0;
  std::uint8_t conf_lvl = 0;  // 0 none, 1 68 %, 2 95 %, 3 99.7 %, 4 99.99 %
  std::uint8_t reserved1 = 0;
  std::uint8_t pio_enabled = 0, pin_polarity = 0, pin = 0, reserved2 = 0;
  std::vector<CfgGeofenceFence> fences;  // numFences = fences.size() (the receiver keeps 4)
};

// UBX-CFG-LOGFILTER (0x06 0x47), 12 bytes (M8 32.10.13, F9 5.9.11). flags: recordEnabled
// bit 0, psmOncePerWakupEnabled 1, applyAllFilterSettings 2.
struct CfgLogfilter {
  static constexpr MsgId kMsg = kCfgLogfilter;
  static constexpr std::size_t kPayloadSize = 12;
  std::uint8_t version = 1, flags = 0;
  std::uint16_t min_interval_s = 0, time_threshold_s = 0, speed_threshold_mps = 0;
  std::uint32_t position_threshold_m = 0;
};

// UBX-CFG-RINV (0x06 0x34), 1 + N bytes (M8 32.10.24, F9 5.9.20): remote inventory; the
// receiver keeps at most 30 data bytes and discards the rest.
struct CfgRinv {
  static constexpr MsgId kMsg = kCfgRinv;
  static constexpr std::size_t kHeaderSize = 1, kBlockSize = 1;
  std::uint8_t flags = 0;  // dump bit 0, binary 1
  std::vector<std::uint8_t> data;
};

// UBX-CFG-DAT (0x06 0x06), M8 32.10.4, F9 5.9.3: set a user datum (44 bytes); the poll is
// answered with the current datum (52 bytes: its number and name, then the same fields).
struct CfgDat {
  static constexpr MsgId kMsg = kCfgDat;
  static constexpr std::size_t kPayloadSize = 44;
  double maj_a_m = 6378137.0, flat = 298.257223563;  // semi-major axis, 1/flattening
  float d_x_m = 0, d_y_m = 0, d_z_m = 0;
  float rot_x_s = 0, rot_y_s = 0, rot_z_s = 0;  // arc seconds
  float scale_ppm = 0;
};
struct CfgDatCurrent : CfgDat {
  static constexpr std::size_t kPayloadSize = 52, kNameSize = 6;
  std::uint16_t datum_num = 0;  // 0 WGS84, 0xFFFF user-defined
  std::string datum_name;       // CH[6]: "WGS84" or "USER"
};

// ---- configuration interface (protocol 27+: CFG-VALGET / VALSET / VALDEL) ------------------
// ZED-F9P Interface Description UBX-18010854 section 6 "Configuration interface": a key ID is
// 32 bits; bits 28..30 give the value's storage size; values are little endian.

// Value size in bytes of a key from bits 28..30 of its ID: 1 one bit (stored in one byte),
// 2 one byte, 3 two bytes, 4 four bytes, 5 eight bytes; 0 for the reserved size codes.
constexpr std::size_t cfg_value_size(std::uint32_t key_id) {
  switch ((key_id >> 28) & 0x7) {
    case 1:
    case 2:
      return 1;
    case 3:
      return 2;
    case 4:
      return 4;
    case 5:
      return 8;
    default:
      return 0;
  }
}

// Configuration layers: VALSET/VALDEL take a bit mask, VALGET one layer number.
inline constexpr std::uint8_t kLayerMaskRam = 0x01;
inline constexpr std::uint8_t kLayerMaskBbr = 0x02;
inline constexpr std::uint8_t kLayerMaskFlash = 0x04;
inline constexpr std::uint8_t kLayerRam = 0;
inline constexpr std::uint8_t kLayerBbr = 1;
inline constexpr std::uint8_t kLayerFlash = 2;
inline constexpr std::uint8_t kLayerDefault = 7;

// A key and its value as raw little-endian bits (zero extended); cfg_value_size(key_id) bytes
// go on the wire. Signed and floating-point values are stored as their bit patterns.
struct CfgKeyValue {
  std::uint32_t key_id = 0;
  std::uint64_t value = 0;
  friend bool operator==(const CfgKeyValue&, const CfgKeyValue&) = default;
};

// UBX-CFG-VALGET (0x06 0x8B) request, version 0: 4 + 4 * N bytes (at most 64 keys).
struct CfgValgetRequest {
  static constexpr MsgId kMsg = kCfgValget;
  std::uint8_t version = 0, layer = kLayerRam;
  std::uint16_t position = 0;  // skip this many values of the answer
  std::vector<std::uint32_t> keys;
};
// UBX-CFG-VALGET (0x06 0x8B) answer, version 1: header + key/value pairs.
struct CfgValgetResponse {
  static constexpr MsgId kMsg = kCfgValget;
  std::uint8_t version = 1, layer = kLayerRam;
  std::uint16_t position = 0;
  std::vector<CfgKeyValue> values;
};
// UBX-CFG-VALSET (0x06 0x8A): version 0 (transactionless: bytes 2..3 reserved) or version 1
// (byte 2 = transaction: 0 none, 1 begin, 2 continue, 3 apply and end), then key/value pairs
// (at most 64).
struct CfgValset {
  static constexpr MsgId kMsg = kCfgValset;
  std::uint8_t version = 0, layers = kLayerMaskRam;
  std::uint8_t transaction = 0;  // version 0: reserved
  std::uint8_t reserved0 = 0;
  std::vector<CfgKeyValue> values;
};
// UBX-CFG-VALDEL (0x06 0x8C): as VALSET, with keys only (layers BBR and/or flash).
struct CfgValdel {
  static constexpr MsgId kMsg = kCfgValdel;
  std::uint8_t version = 0, layers = kLayerMaskBbr;
  std::uint8_t transaction = 0;  // version 0: reserved
  std::uint8_t reserved0 = 0;
  std::vector<std::uint32_t> keys;
};

// Key IDs (UBX-18010854 section 6, configuration reference; the size code in bits 28..30
// agrees with the type: L 1, U1/I1/E1 2, U2 3, U4 4).
namespace cfgkey {
// CFG-RATE
inline constexpr std::uint32_t kRateMeas = 0x30210001;     // U2, ms
inline constexpr std::uint32_t kRateNav = 0x30210002;      // U2, cycles
inline constexpr std::uint32_t kRateTimeref = 0x20210003;  // E1
// CFG-NAVSPG
inline constexpr std::uint32_t kNavspgFixmode = 0x20110011;      // E1
inline constexpr std::uint32_t kNavspgUtcstandard = 0x2011001C;  // E1
inline constexpr std::uint32_t kNavspgDynmodel = 0x20110021;     // E1
inline constexpr std::uint32_t kNavspgInfilMinelev = 0x201100A4;  // I1, deg
// CFG-NMEA
inline constexpr std::uint32_t kNmeaProtver = 0x20930001;  // E1
// CFG-UART1
inline constexpr std::uint32_t kUart1Baudrate = 0x40520001;  // U4
inline constexpr std::uint32_t kUart1Stopbits = 0x20520002;  // E1
inline constexpr std::uint32_t kUart1Databits = 0x20520003;  // E1
inline constexpr std::uint32_t kUart1Parity = 0x20520004;    // E1
inline constexpr std::uint32_t kUart1Enabled = 0x10520005;   // L
// CFG-UART1INPROT / CFG-UART1OUTPROT
inline constexpr std::uint32_t kUart1inprotUbx = 0x10730001;      // L
inline constexpr std::uint32_t kUart1inprotNmea = 0x10730002;     // L
inline constexpr std::uint32_t kUart1inprotRtcm3x = 0x10730004;   // L
inline constexpr std::uint32_t kUart1outprotUbx = 0x10740001;     // L
inline constexpr std::uint32_t kUart1outprotNmea = 0x10740002;    // L
inline constexpr std::uint32_t kUart1outprotRtcm3x = 0x10740004;  // L
// CFG-USBINPROT / CFG-USBOUTPROT
inline constexpr std::uint32_t kUsbinprotUbx = 0x10770001;    // L
inline constexpr std::uint32_t kUsbinprotNmea = 0x10770002;   // L
inline constexpr std::uint32_t kUsboutprotUbx = 0x10780001;   // L
inline constexpr std::uint32_t kUsboutprotNmea = 0x10780002;  // L
// CFG-MSGOUT (U1 rates), UART1 and USB
inline constexpr std::uint32_t kMsgoutUbxNavClockUart1 = 0x20910066;
inline constexpr std::uint32_t kMsgoutUbxNavClockUsb = 0x20910068;
inline constexpr std::uint32_t kMsgoutUbxNavDopUart1 = 0x20910039;
inline constexpr std::uint32_t kMsgoutUbxNavDopUsb = 0x2091003B;
inline constexpr std::uint32_t kMsgoutUbxNavEoeUart1 = 0x20910160;
inline constexpr std::uint32_t kMsgoutUbxNavEoeUsb = 0x20910162;
inline constexpr std::uint32_t kMsgoutUbxNavPosecefUart1 = 0x20910025;
inline constexpr std::uint32_t kMsgoutUbxNavPosecefUsb = 0x20910027;
inline constexpr std::uint32_t kMsgoutUbxNavPosllhUart1 = 0x2091002A;
inline constexpr std::uint32_t kMsgoutUbxNavPosllhUsb = 0x2091002C;
inline constexpr std::uint32_t kMsgoutUbxNavPvtUart1 = 0x20910007;
inline constexpr std::uint32_t kMsgoutUbxNavPvtUsb = 0x20910009;
inline constexpr std::uint32_t kMsgoutUbxNavSatUart1 = 0x20910016;
inline constexpr std::uint32_t kMsgoutUbxNavSatUsb = 0x20910018;
inline constexpr std::uint32_t kMsgoutUbxNavSigUart1 = 0x20910346;
inline constexpr std::uint32_t kMsgoutUbxNavSigUsb = 0x20910348;
inline constexpr std::uint32_t kMsgoutUbxNavStatusUart1 = 0x2091001B;
inline constexpr std::uint32_t kMsgoutUbxNavStatusUsb = 0x2091001D;
inline constexpr std::uint32_t kMsgoutUbxNavTimegpsUart1 = 0x20910048;
inline constexpr std::uint32_t kMsgoutUbxNavTimegpsUsb = 0x2091004A;
inline constexpr std::uint32_t kMsgoutUbxNavTimeutcUart1 = 0x2091005C;
inline constexpr std::uint32_t kMsgoutUbxNavTimeutcUsb = 0x2091005E;
inline constexpr std::uint32_t kMsgoutUbxNavVelecefUart1 = 0x2091003E;
inline constexpr std::uint32_t kMsgoutUbxNavVelecefUsb = 0x20910040;
inline constexpr std::uint32_t kMsgoutUbxNavVelnedUart1 = 0x20910043;
inline constexpr std::uint32_t kMsgoutUbxNavVelnedUsb = 0x20910045;
inline constexpr std::uint32_t kMsgoutUbxRxmRawxUart1 = 0x209102A5;
inline constexpr std::uint32_t kMsgoutUbxRxmRawxUsb = 0x209102A7;
inline constexpr std::uint32_t kMsgoutUbxRxmSfrbxUart1 = 0x20910232;
inline constexpr std::uint32_t kMsgoutUbxRxmSfrbxUsb = 0x20910234;
inline constexpr std::uint32_t kMsgoutUbxMonRfUart1 = 0x2091035A;
inline constexpr std::uint32_t kMsgoutUbxMonRfUsb = 0x2091035C;
inline constexpr std::uint32_t kMsgoutNmeaIdGbsUart1 = 0x209100DE;
inline constexpr std::uint32_t kMsgoutNmeaIdGbsUsb = 0x209100E0;
inline constexpr std::uint32_t kMsgoutNmeaIdGgaUart1 = 0x209100BB;
inline constexpr std::uint32_t kMsgoutNmeaIdGgaUsb = 0x209100BD;
inline constexpr std::uint32_t kMsgoutNmeaIdGllUart1 = 0x209100CA;
inline constexpr std::uint32_t kMsgoutNmeaIdGllUsb = 0x209100CC;
inline constexpr std::uint32_t kMsgoutNmeaIdGsaUart1 = 0x209100C0;
inline constexpr std::uint32_t kMsgoutNmeaIdGsaUsb = 0x209100C2;
inline constexpr std::uint32_t kMsgoutNmeaIdGstUart1 = 0x209100D4;
inline constexpr std::uint32_t kMsgoutNmeaIdGstUsb = 0x209100D6;
inline constexpr std::uint32_t kMsgoutNmeaIdGsvUart1 = 0x209100C5;
inline constexpr std::uint32_t kMsgoutNmeaIdGsvUsb = 0x209100C7;
inline constexpr std::uint32_t kMsgoutNmeaIdRmcUart1 = 0x209100AC;
inline constexpr std::uint32_t kMsgoutNmeaIdRmcUsb = 0x209100AE;
inline constexpr std::uint32_t kMsgoutNmeaIdVtgUart1 = 0x209100B1;
inline constexpr std::uint32_t kMsgoutNmeaIdVtgUsb = 0x209100B3;
inline constexpr std::uint32_t kMsgoutNmeaIdZdaUart1 = 0x209100D9;
inline constexpr std::uint32_t kMsgoutNmeaIdZdaUsb = 0x209100DB;
}  // namespace cfgkey

// ---- the payload tables -------------------------------------------------------------------
// One description per message struct above, in wire order (protocols/ubx_layout.hpp): class/ID,
// name, length rule, then each row's wire type, name in the interface description's table,
// member and, where the member's unit is not the quantity's, the value of one LSB (1e-7 deg,
// 1e-3 m, ...). Adding a message is its struct and one entry here.

struct Descriptions : Describing {
  // One CFG-PRT port block: the 20-byte CFG-PRT and each block of a set with several.
  static constexpr auto kCfgPrtPort = group(
      u1(&CfgPrt::port_id, "portID"), u1(&CfgPrt::reserved1, "reserved1"),
      x2(&CfgPrt::tx_ready, "txReady"), x4(&CfgPrt::mode, "mode"),
      u4(&CfgPrt::baud_rate, "baudRate"), x2(&CfgPrt::in_proto_mask, "inProtoMask"),
      x2(&CfgPrt::out_proto_mask, "outProtoMask"), x2(&CfgPrt::flags, "flags"),
      u1(&CfgPrt::reserved2, "reserved2"));
  // The datum parameters of CFG-DAT, set (44 bytes) and current datum (52 bytes).
  static constexpr auto kCfgDatum = group(
      r8(&CfgDat::maj_a_m, "majA"), r8(&CfgDat::flat, "flat"), r4(&CfgDat::d_x_m, "dX"),
      r4(&CfgDat::d_y_m, "dY"), r4(&CfgDat::d_z_m, "dZ"), r4(&CfgDat::rot_x_s, "rotX"),
      r4(&CfgDat::rot_y_s, "rotY"), r4(&CfgDat::rot_z_s, "rotZ"), r4(&CfgDat::scale_ppm, "scale"));

  static constexpr auto kAll = layout::list(
      describe<NavPvt>(kNavPvt, "NAV-PVT", Length::kAtLeast,
          u4(&NavPvt::i_tow_ms, "iTOW", 1e-3), u2(&NavPvt::year, "year"),
          u1(&NavPvt::month, "month"), u1(&NavPvt::day, "day"), u1(&NavPvt::hour, "hour"),
          u1(&NavPvt::min, "min"), u1(&NavPvt::sec, "sec"), x1(&NavPvt::valid, "valid"),
          u4(&NavPvt::t_acc_ns, "tAcc", 1e-9), i4(&NavPvt::nano_ns, "nano", 1e-9),
          u1(&NavPvt::fix_type, "fixType"), x1(&NavPvt::flags, "flags"),
          x1(&NavPvt::flags2, "flags2"), u1(&NavPvt::num_sv, "numSV"),
          i4(&NavPvt::lon_1e7deg, "lon", 1e-7), i4(&NavPvt::lat_1e7deg, "lat", 1e-7),
          i4(&NavPvt::height_mm, "height", 1e-3), i4(&NavPvt::h_msl_mm, "hMSL", 1e-3),
          u4(&NavPvt::h_acc_mm, "hAcc", 1e-3), u4(&NavPvt::v_acc_mm, "vAcc", 1e-3),
          i4(&NavPvt::vel_n_mmps, "velN", 1e-3), i4(&NavPvt::vel_e_mmps, "velE", 1e-3),
          i4(&NavPvt::vel_d_mmps, "velD", 1e-3), i4(&NavPvt::g_speed_mmps, "gSpeed", 1e-3),
          i4(&NavPvt::head_mot_1e5deg, "headMot", 1e-5), u4(&NavPvt::s_acc_mmps, "sAcc", 1e-3),
          u4(&NavPvt::head_acc_1e5deg, "headAcc", 1e-5), u2(&NavPvt::p_dop_0p01, "pDOP", 0.01),
          x2(&NavPvt::flags3, "flags3"), u1(&NavPvt::reserved1, "reserved1"),
          i4(&NavPvt::head_veh_1e5deg, "headVeh", 1e-5), i2(&NavPvt::mag_dec_1e2deg, "magDec", 1e-2),
          u2(&NavPvt::mag_acc_1e2deg, "magAcc", 1e-2)),
      describe<NavPosllh>(kNavPosllh, "NAV-POSLLH", Length::kAtLeast,
          u4(&NavPosllh::i_tow_ms, "iTOW", 1e-3), i4(&NavPosllh::lon_1e7deg, "lon", 1e-7),
          i4(&NavPosllh::lat_1e7deg, "lat", 1e-7), i4(&NavPosllh::height_mm, "height", 1e-3),
          i4(&NavPosllh::h_msl_mm, "hMSL", 1e-3), u4(&NavPosllh::h_acc_mm, "hAcc", 1e-3),
          u4(&NavPosllh::v_acc_mm, "vAcc", 1e-3)),
      describe<NavPosecef>(kNavPosecef, "NAV-POSECEF", Length::kAtLeast,
          u4(&NavPosecef::i_tow_ms, "iTOW", 1e-3), i4(&NavPosecef::ecef_x_cm, "ecefX", 1e-2),
          i4(&NavPosecef::ecef_y_cm, "ecefY", 1e-2), i4(&NavPosecef::ecef_z_cm, "ecefZ", 1e-2),
          u4(&NavPosecef::p_acc_cm, "pAcc", 1e-2)),
      describe<NavVelned>(kNavVelned, "NAV-VELNED", Length::kAtLeast,
          u4(&NavVelned::i_tow_ms, "iTOW", 1e-3), i4(&NavVelned::vel_n_cmps, "velN", 1e-2),
          i4(&NavVelned::vel_e_cmps, "velE", 1e-2), i4(&NavVelned::vel_d_cmps, "velD", 1e-2),
          u4(&NavVelned::speed_cmps, "speed", 1e-2), u4(&NavVelned::g_speed_cmps, "gSpeed", 1e-2),
          i4(&NavVelned::heading_1e5deg, "heading", 1e-5), u4(&NavVelned::s_acc_cmps, "sAcc", 1e-2),
          u4(&NavVelned::c_acc_1e5deg, "cAcc", 1e-5)),
      describe<NavVelecef>(kNavVelecef, "NAV-VELECEF", Length::kAtLeast,
          u4(&NavVelecef::i_tow_ms, "iTOW", 1e-3), i4(&NavVelecef::ecef_vx_cmps, "ecefVX", 1e-2),
          i4(&NavVelecef::ecef_vy_cmps, "ecefVY", 1e-2), i4(&NavVelecef::ecef_vz_cmps, "ecefVZ", 1e-2),
          u4(&NavVelecef::s_acc_cmps, "sAcc", 1e-2)),
      describe<NavStatus>(kNavStatus, "NAV-STATUS", Length::kAtLeast,
          u4(&NavStatus::i_tow_ms, "iTOW", 1e-3), u1(&NavStatus::gps_fix, "gpsFix"),
          x1(&NavStatus::flags, "flags"), x1(&NavStatus::fix_stat, "fixStat"),
          x1(&NavStatus::flags2, "flags2"), u4(&NavStatus::ttff_ms, "ttff", 1e-3),
          u4(&NavStatus::msss_ms, "msss", 1e-3)),
      describe<NavSol>(kNavSol, "NAV-SOL", Length::kAtLeast,
          u4(&NavSol::i_tow_ms, "iTOW", 1e-3), i4(&NavSol::f_tow_ns, "fTOW", 1e-9),
          i2(&NavSol::week, "week"), u1(&NavSol::gps_fix, "gpsFix"), x1(&NavSol::flags, "flags"),
          i4(&NavSol::ecef_x_cm, "ecefX", 1e-2), i4(&NavSol::ecef_y_cm, "ecefY", 1e-2),
          i4(&NavSol::ecef_z_cm, "ecefZ", 1e-2), u4(&NavSol::p_acc_cm, "pAcc", 1e-2),
          i4(&NavSol::ecef_vx_cmps, "ecefVX", 1e-2), i4(&NavSol::ecef_vy_cmps, "ecefVY", 1e-2),
          i4(&NavSol::ecef_vz_cmps, "ecefVZ", 1e-2), u4(&NavSol::s_acc_cmps, "sAcc", 1e-2),
          u2(&NavSol::p_dop_0p01, "pDOP", 0.01), u1(&NavSol::reserved1, "reserved1"),
          u1(&NavSol::num_sv, "numSV"), u1(&NavSol::reserved2, "reserved2")),
      describe<NavSvinfo>(kNavSvinfo, "NAV-SVINFO", Length::kExact,
          u4(&NavSvinfo::i_tow_ms, "iTOW", 1e-3), count("numCh"),
          x1(&NavSvinfo::global_flags, "globalFlags"), u1(&NavSvinfo::reserved1, "reserved1"),
          block(&NavSvinfo::channels, u1(&NavSvinfoChannel::chn, "chn"),
                u1(&NavSvinfoChannel::svid, "svid"), x1(&NavSvinfoChannel::flags, "flags"),
                x1(&NavSvinfoChannel::quality, "quality"), u1(&NavSvinfoChannel::cno_dbhz, "cno"),
                i1(&NavSvinfoChannel::elev_deg, "elev"), i2(&NavSvinfoChannel::azim_deg, "azim"),
                i4(&NavSvinfoChannel::pr_res_cm, "prRes", 1e-2))),
      describe<NavDop>(kNavDop, "NAV-DOP", Length::kAtLeast,
          u4(&NavDop::i_tow_ms, "iTOW", 1e-3), u2(&NavDop::g_dop_0p01, "gDOP", 0.01),
          u2(&NavDop::p_dop_0p01, "pDOP", 0.01), u2(&NavDop::t_dop_0p01, "tDOP", 0.01),
          u2(&NavDop::v_dop_0p01, "vDOP", 0.01), u2(&NavDop::h_dop_0p01, "hDOP", 0.01),
          u2(&NavDop::n_dop_0p01, "nDOP", 0.01), u2(&NavDop::e_dop_0p01, "eDOP", 0.01)),
      describe<NavSat>(kNavSat, "NAV-SAT", Length::kExact,
          u4(&NavSat::i_tow_ms, "iTOW", 1e-3), u1(&NavSat::version, "version"), count("numSvs"),
          u1(&NavSat::reserved1, "reserved1"),
          block(&NavSat::svs, u1(&NavSatSv::gnss_id, "gnssId"), u1(&NavSatSv::sv_id, "svId"),
                u1(&NavSatSv::cno_dbhz, "cno"), i1(&NavSatSv::elev_deg, "elev"),
                i2(&NavSatSv::azim_deg, "azim"), i2(&NavSatSv::pr_res_dm, "prRes", 0.1),
                x4(&NavSatSv::flags, "flags"))),
      describe<NavTimegps>(kNavTimegps, "NAV-TIMEGPS", Length::kAtLeast,
          u4(&NavTimegps::i_tow_ms, "iTOW", 1e-3), i4(&NavTimegps::f_tow_ns, "fTOW", 1e-9),
          i2(&NavTimegps::week, "week"), i1(&NavTimegps::leap_s, "leapS"),
          x1(&NavTimegps::valid, "valid"), u4(&NavTimegps::t_acc_ns, "tAcc", 1e-9)),
      describe<NavTimeutc>(kNavTimeutc, "NAV-TIMEUTC", Length::kAtLeast,
          u4(&NavTimeutc::i_tow_ms, "iTOW", 1e-3), u4(&NavTimeutc::t_acc_ns, "tAcc", 1e-9),
          i4(&NavTimeutc::nano_ns, "nano", 1e-9), u2(&NavTimeutc::year, "year"),
          u1(&NavTimeutc::month, "month"), u1(&NavTimeutc::day, "day"), u1(&NavTimeutc::hour, "hour"),
          u1(&NavTimeutc::min, "min"), u1(&NavTimeutc::sec, "sec"), x1(&NavTimeutc::valid, "valid")),
      describe<NavClock>(kNavClock, "NAV-CLOCK", Length::kAtLeast,
          u4(&NavClock::i_tow_ms, "iTOW", 1e-3), i4(&NavClock::clk_b_ns, "clkB", 1e-9),
          i4(&NavClock::clk_d_nsps, "clkD", 1e-9), u4(&NavClock::t_acc_ns, "tAcc", 1e-9),
          u4(&NavClock::f_acc_psps, "fAcc", 1e-12)),
      describe<NavEoe>(kNavEoe, "NAV-EOE", Length::kAtLeast,
          u4(&NavEoe::i_tow_ms, "iTOW", 1e-3)),
      describe<RxmRawx>(kRxmRawx, "RXM-RAWX", Length::kExact,
          r8(&RxmRawx::rcv_tow_s, "rcvTow"), u2(&RxmRawx::week, "week"),
          i1(&RxmRawx::leap_s, "leapS"), count("numMeas"), x1(&RxmRawx::rec_stat, "recStat"),
          u1(&RxmRawx::version, "version"), u1(&RxmRawx::reserved1, "reserved1"),
          block(&RxmRawx::meas, r8(&RxmRawxMeas::pr_mes_m, "prMes"),
                r8(&RxmRawxMeas::cp_mes_cycles, "cpMes"), r4(&RxmRawxMeas::do_mes_hz, "doMes"),
                u1(&RxmRawxMeas::gnss_id, "gnssId"), u1(&RxmRawxMeas::sv_id, "svId"),
                u1(&RxmRawxMeas::sig_id, "sigId"), u1(&RxmRawxMeas::freq_id, "freqId"),
                u2(&RxmRawxMeas::locktime_ms, "locktime", 1e-3), u1(&RxmRawxMeas::cno_dbhz, "cno"),
                x1(&RxmRawxMeas::pr_stdev, "prStdev"), x1(&RxmRawxMeas::cp_stdev, "cpStdev"),
                x1(&RxmRawxMeas::do_stdev, "doStdev"), x1(&RxmRawxMeas::trk_stat, "trkStat"),
                u1(&RxmRawxMeas::reserved3, "reserved3"))),
      describe<RxmSfrbx>(kRxmSfrbx, "RXM-SFRBX", Length::kExact,
          u1(&RxmSfrbx::gnss_id, "gnssId"), u1(&RxmSfrbx::sv_id, "svId"),
          u1(&RxmSfrbx::sig_id, "sigId"), u1(&RxmSfrbx::freq_id, "freqId"), count("numWords"),
          u1(&RxmSfrbx::chn, "chn"), u1(&RxmSfrbx::version, "version"),
          u1(&RxmSfrbx::reserved2, "reserved2"),
          block(&RxmSfrbx::words, self<Wire::kU4, std::uint32_t>("dwrd"))),
      describe<RxmMeasx>(kRxmMeasx, "RXM-MEASX", Length::kExact,
          u1(&RxmMeasx::version, "version"), u1(&RxmMeasx::reserved1, "reserved1"),
          u4(&RxmMeasx::gps_tow_ms, "gpsTOW", 1e-3), u4(&RxmMeasx::glo_tow_ms, "gloTOW", 1e-3),
          u4(&RxmMeasx::bds_tow_ms, "bdsTOW", 1e-3), u1(&RxmMeasx::reserved2, "reserved2"),
          u4(&RxmMeasx::qzss_tow_ms, "qzssTOW", 1e-3),
          u2(&RxmMeasx::gps_tow_acc_2m4ms, "gpsTOWacc", 0x1p-4 * 1e-3),
          u2(&RxmMeasx::glo_tow_acc_2m4ms, "gloTOWacc", 0x1p-4 * 1e-3),
          u2(&RxmMeasx::bds_tow_acc_2m4ms, "bdsTOWacc", 0x1p-4 * 1e-3), u1(&RxmMeasx::reserved3, "reserved3"),
          u2(&RxmMeasx::qzss_tow_acc_2m4ms, "qzssTOWacc", 0x1p-4 * 1e-3), count("numSV"),
          x1(&RxmMeasx::flags, "flags"), u1(&RxmMeasx::reserved4, "reserved4"),
          block(&RxmMeasx::svs, u1(&RxmMeasxSv::gnss_id, "gnssId"), u1(&RxmMeasxSv::sv_id, "svId"),
                u1(&RxmMeasxSv::cno_dbhz, "cNo"), u1(&RxmMeasxSv::mpath_indic, "mpathIndic"),
                i4(&RxmMeasxSv::doppler_4cmps, "dopplerMS", 0.04),
                i4(&RxmMeasxSv::doppler_200mhz, "dopplerHz", 0.2),
                u2(&RxmMeasxSv::whole_chips, "wholeChips"), u2(&RxmMeasxSv::frac_chips, "fracChips"),
                u4(&RxmMeasxSv::code_phase_2m21ms, "codePhase", 0x1p-21 * 1e-3),
                u1(&RxmMeasxSv::int_code_phase_ms, "intCodePhase", 1e-3),
                u1(&RxmMeasxSv::pseu_range_rms_err, "pseuRangeRMSErr"),
                u1(&RxmMeasxSv::reserved5, "reserved5"))),
      describe<RxmImes>(kRxmImes, "RXM-IMES", Length::kExact,
          count("numTx"), u1(&RxmImes::version, "version"), u1(&RxmImes::reserved1, "reserved1"),
          block(&RxmImes::txs, u1(&RxmImesTx::reserved2, "reserved2"), u1(&RxmImesTx::tx_id, "txId"),
                u1(&RxmImesTx::reserved3, "reserved3"), u1(&RxmImesTx::cno_dbhz, "cno"),
                u1(&RxmImesTx::reserved4, "reserved4"), i4(&RxmImesTx::doppler_2m12hz, "doppler", 0x1p-12),
                x4(&RxmImesTx::position1_1, "position1_1"), x4(&RxmImesTx::position1_2, "position1_2"),
                x4(&RxmImesTx::position2_1, "position2_1"), i4(&RxmImesTx::lat, "lat"),
                i4(&RxmImesTx::lon, "lon"), x4(&RxmImesTx::short_id_frame, "shortIdFrame"),
                u4(&RxmImesTx::medium_id_lsb, "mediumIdLSB"), x4(&RxmImesTx::medium_id_2, "mediumId_2"))),
      describe<UpdSosCommand>(kUpdSos, "UPD-SOS", Length::kExact,
          u1(&UpdSosCommand::cmd, "cmd"), u1(&UpdSosCommand::reserved1, "reserved1")),
      describe<UpdSos>(kUpdSos, "UPD-SOS", Length::kExact,
          u1(&UpdSos::cmd, "cmd"), u1(&UpdSos::reserved1, "reserved1"),
          u1(&UpdSos::response, "response"), u1(&UpdSos::reserved2, "reserved2")),
      describe<AidIni>(kAidIni, "AID-INI", Length::kExact,
          i4(&AidIni::ecef_x_or_lat, "ecefXOrLat"), i4(&AidIni::ecef_y_or_lon, "ecefYOrLon"),
          i4(&AidIni::ecef_z_or_alt, "ecefZOrAlt"), u4(&AidIni::pos_acc_cm, "posAcc", 1e-2),
          x2(&AidIni::tm_cfg, "tmCfg"), u2(&AidIni::wno_or_date, "wnoOrDate"),
          u4(&AidIni::tow_or_time_ms, "towOrTime", 1e-3), i4(&AidIni::tow_ns, "towNs", 1e-9),
          u4(&AidIni::t_acc_ms, "tAccMs", 1e-3), u4(&AidIni::t_acc_ns, "tAccNs", 1e-9),
          i4(&AidIni::clk_d_or_freq, "clkDOrFreq"), u4(&AidIni::clk_d_acc_or_freq_acc, "clkDAccOrFreqAcc"),
          x4(&AidIni::flags, "flags")),
      describe<AidHui>(kAidHui, "AID-HUI", Length::kExact,
          x4(&AidHui::health, "health"), r8(&AidHui::utc_a0_s, "utcA0"), r8(&AidHui::utc_a1_sps, "utcA1"),
          i4(&AidHui::utc_tow_s, "utcTOW"), i2(&AidHui::utc_wnt, "utcWNT"), i2(&AidHui::utc_ls_s, "utcLS"),
          i2(&AidHui::utc_wnf, "utcWNF"), i2(&AidHui::utc_dn, "utcDN"), i2(&AidHui::utc_lsf_s, "utcLSF"),
          i2(&AidHui::utc_spare, "utcSpare"), r4(&AidHui::klob_a, "klobA"), r4(&AidHui::klob_b, "klobB"),
          x4(&AidHui::flags, "flags")),
      describe<AidAlmPoll>(kAidAlm, "AID-ALM", Length::kExact, u1(&AidAlmPoll::svid, "svid")),
      describe<AidAlm>(kAidAlm, "AID-ALM", Length::kExact,
          u4(&AidAlm::svid, "svid"), u4(&AidAlm::week, "week"),
          optional(&AidAlm::has_data, u4(&AidAlm::dwrd, "dwrd"))),
      describe<AidEphPoll>(kAidEph, "AID-EPH", Length::kExact, u1(&AidEphPoll::svid, "svid")),
      describe<AidEph>(kAidEph, "AID-EPH", Length::kExact,
          u4(&AidEph::svid, "svid"), x4(&AidEph::how, "how"),
          optional(&AidEph::has_data, u4(&AidEph::sf1d, "sf1d"), u4(&AidEph::sf2d, "sf2d"),
                   u4(&AidEph::sf3d, "sf3d"))),
      describe<AidAopPoll>(kAidAop, "AID-AOP", Length::kExact, u1(&AidAopPoll::svid, "svid")),
      describe<MgaAck>(kMgaAck, "MGA-ACK", Length::kExact,
          u1(&MgaAck::type, "type"), u1(&MgaAck::version, "version"), u1(&MgaAck::info_code, "infoCode"),
          u1(&MgaAck::msg_id, "msgId"), u4(&MgaAck::msg_payload_start, "msgPayloadStart")),
      describe<MgaDbd>(kMgaDbd, "MGA-DBD", Length::kExact,
          u1(&MgaDbd::reserved1, "reserved1"),
          block_to_end<Repeat::kAll>(&MgaDbd::data, self<Wire::kU1, std::uint8_t>("data"))),
      describe<AckAck>(kAckAck, "ACK-ACK", Length::kExact,
          u1(&AckAck::cls_id, "clsID"), u1(&AckAck::msg_id, "msgID")),
      describe<AckNak>(kAckNak, "ACK-NAK", Length::kExact,
          u1(&AckNak::cls_id, "clsID"), u1(&AckNak::msg_id, "msgID")),
      describe<MonVer>(kMonVer, "MON-VER", Length::kExact,
          ch<MonVer::kSwSize>(&MonVer::sw_version, "swVersion"),
          ch<MonVer::kHwSize>(&MonVer::hw_version, "hwVersion"),
          block_to_end<Repeat::kFitLength>(
              &MonVer::extensions, self<Wire::kCh, std::string, MonVer::kExtensionSize>("extension"))),
      describe<MonHw>(kMonHw, "MON-HW", Length::kExact,
          x4(&MonHw::pin_sel, "pinSel"), x4(&MonHw::pin_bank, "pinBank"),
          x4(&MonHw::pin_dir, "pinDir"), x4(&MonHw::pin_val, "pinVal"),
          u2(&MonHw::noise_per_ms, "noisePerMS"), u2(&MonHw::agc_cnt, "agcCnt"),
          u1(&MonHw::a_status, "aStatus"), u1(&MonHw::a_power, "aPower"), x1(&MonHw::flags, "flags"),
          u1(&MonHw::reserved1, "reserved1"), x4(&MonHw::used_mask, "usedMask"),
          u1(&MonHw::vp, "VP"), u1(&MonHw::jam_ind, "jamInd"), u1(&MonHw::reserved2, "reserved2"),
          x4(&MonHw::pin_irq, "pinIrq"), x4(&MonHw::pull_h, "pullH"), x4(&MonHw::pull_l, "pullL")),
      describe<CfgPrtPoll>(kCfgPrt, "CFG-PRT", Length::kExact,
          optional(&CfgPrtPoll::has_port_id, u1(&CfgPrtPoll::port_id, "portID"))),
      describe<CfgPrt>(kCfgPrt, "CFG-PRT", Length::kExact, kCfgPrtPort),
      describe<CfgPrtPorts>(kCfgPrt, "CFG-PRT", Length::kExact,
          block_to_end<Repeat::kAll>(&CfgPrtPorts::ports, kCfgPrtPort).at_least(1)),
      describe<CfgMsgPoll>(kCfgMsg, "CFG-MSG", Length::kExact,
          u1(&CfgMsgPoll::msg_class, "msgClass"), u1(&CfgMsgPoll::msg_id, "msgID")),
      describe<CfgMsgCurrentPort>(kCfgMsg, "CFG-MSG", Length::kExact,
          u1(&CfgMsgCurrentPort::msg_class, "msgClass"), u1(&CfgMsgCurrentPort::msg_id, "msgID"),
          u1(&CfgMsgCurrentPort::rate, "rate")),
      describe<CfgMsg>(kCfgMsg, "CFG-MSG", Length::kExact,
          u1(&CfgMsg::msg_class, "msgClass"), u1(&CfgMsg::msg_id, "msgID"),
          u1(&CfgMsg::rate, "rate")),
      describe<CfgRate>(kCfgRate, "CFG-RATE", Length::kExact,
          u2(&CfgRate::meas_rate_ms, "measRate", 1e-3), u2(&CfgRate::nav_rate_cycles, "navRate"),
          u2(&CfgRate::time_ref, "timeRef")),
      describe<CfgNav5>(kCfgNav5, "CFG-NAV5", Length::kExact,
          x2(&CfgNav5::mask, "mask"), u1(&CfgNav5::dyn_model, "dynModel"),
          u1(&CfgNav5::fix_mode, "fixMode"), i4(&CfgNav5::fixed_alt_cm, "fixedAlt", 1e-2),
          u4(&CfgNav5::fixed_alt_var_1e4m2, "fixedAltVar", 1e-4),
          i1(&CfgNav5::min_elev_deg, "minElev"), u1(&CfgNav5::dr_limit_s, "drLimit"),
          u2(&CfgNav5::p_dop_0p1, "pDop", 0.1), u2(&CfgNav5::t_dop_0p1, "tDop", 0.1),
          u2(&CfgNav5::p_acc_m, "pAcc"), u2(&CfgNav5::t_acc_m, "tAcc"),
          u1(&CfgNav5::static_hold_thresh_cmps, "staticHoldThresh", 1e-2),
          u1(&CfgNav5::dgnss_timeout_s, "dgnssTimeout"),
          u1(&CfgNav5::cno_thresh_num_svs, "cnoThreshNumSVs"),
          u1(&CfgNav5::cno_thresh_dbhz, "cnoThresh"), u1(&CfgNav5::reserved1, "reserved1"),
          u2(&CfgNav5::static_hold_max_dist_m, "staticHoldMaxDist"),
          u1(&CfgNav5::utc_standard, "utcStandard"), u1(&CfgNav5::reserved2, "reserved2")),
      describe<CfgGnss>(kCfgGnss, "CFG-GNSS", Length::kExact,
          u1(&CfgGnss::msg_ver, "msgVer"), u1(&CfgGnss::num_trk_ch_hw, "numTrkChHw"),
          u1(&CfgGnss::num_trk_ch_use, "numTrkChUse"), count("numConfigBlocks"),
          block(&CfgGnss::blocks, u1(&CfgGnssBlock::gnss_id, "gnssId"),
                u1(&CfgGnssBlock::res_trk_ch, "resTrkCh"), u1(&CfgGnssBlock::max_trk_ch, "maxTrkCh"),
                u1(&CfgGnssBlock::reserved1, "reserved1"), x4(&CfgGnssBlock::flags, "flags"))),
      describe<CfgCfg>(kCfgCfg, "CFG-CFG", Length::kExact,
          x4(&CfgCfg::clear_mask, "clearMask"), x4(&CfgCfg::save_mask, "saveMask"),
          x4(&CfgCfg::load_mask, "loadMask"),
          optional(&CfgCfg::has_device_mask, x1(&CfgCfg::device_mask, "deviceMask"))),
      describe<CfgRst>(kCfgRst, "CFG-RST", Length::kExact,
          x2(&CfgRst::nav_bbr_mask, "navBbrMask"), u1(&CfgRst::reset_mode, "resetMode"),
          u1(&CfgRst::reserved1, "reserved1")),
      describe<CfgValgetRequest>(kCfgValget, "CFG-VALGET", Length::kExact,
          u1(&CfgValgetRequest::version, "version").only(0, 0),
          u1(&CfgValgetRequest::layer, "layer"), u2(&CfgValgetRequest::position, "position"),
          block_to_end<Repeat::kAll>(&CfgValgetRequest::keys, self<Wire::kU4, std::uint32_t>("keys"))),
      describe<CfgValgetResponse>(kCfgValget, "CFG-VALGET", Length::kExact,
          u1(&CfgValgetResponse::version, "version").only(1, 1),
          u1(&CfgValgetResponse::layer, "layer"), u2(&CfgValgetResponse::position, "position"),
          key_values(&CfgValgetResponse::values, &cfg_value_size)),
      describe<CfgValset>(kCfgValset, "CFG-VALSET", Length::kExact,
          u1(&CfgValset::version, "version").only(0, 1), x1(&CfgValset::layers, "layers"),
          u1(&CfgValset::transaction, "transaction"), u1(&CfgValset::reserved0, "reserved0"),
          key_values(&CfgValset::values, &cfg_value_size)),
      describe<CfgValdel>(kCfgValdel, "CFG-VALDEL", Length::kExact,
          u1(&CfgValdel::version, "version").only(0, 1), x1(&CfgValdel::layers, "layers"),
          u1(&CfgValdel::transaction, "transaction"), u1(&CfgValdel::reserved0, "reserved0"),
          block_to_end<Repeat::kAll>(&CfgValdel::keys, self<Wire::kU4, std::uint32_t>("keys"))),
      // ---- NAV, continued ----
      describe<NavHpposecef>(kNavHpposecef, "NAV-HPPOSECEF", Length::kAtLeast,
          u1(&NavHpposecef::version, "version"), u1(&NavHpposecef::reserved1, "reserved1"),
          u4(&NavHpposecef::i_tow_ms, "iTOW", 1e-3), i4(&NavHpposecef::ecef_x_cm, "ecefX", 1e-2),
          i4(&NavHpposecef::ecef_y_cm, "ecefY", 1e-2), i4(&NavHpposecef::ecef_z_cm, "ecefZ", 1e-2),
          i1(&NavHpposecef::ecef_x_hp_0p1mm, "ecefXHp", 1e-4),
          i1(&NavHpposecef::ecef_y_hp_0p1mm, "ecefYHp", 1e-4),
          i1(&NavHpposecef::ecef_z_hp_0p1mm, "ecefZHp", 1e-4), x1(&NavHpposecef::flags, "flags"),
          u4(&NavHpposecef::p_acc_0p1mm, "pAcc", 1e-4)),
      describe<NavHpposllh>(kNavHpposllh, "NAV-HPPOSLLH", Length::kAtLeast,
          u1(&NavHpposllh::version, "version"), u1(&NavHpposllh::reserved1, "reserved1"),
          x1(&NavHpposllh::flags, "flags"), u4(&NavHpposllh::i_tow_ms, "iTOW", 1e-3),
          i4(&NavHpposllh::lon_1e7deg, "lon", 1e-7), i4(&NavHpposllh::lat_1e7deg, "lat", 1e-7),
          i4(&NavHpposllh::height_mm, "height", 1e-3), i4(&NavHpposllh::h_msl_mm, "hMSL", 1e-3),
          i1(&NavHpposllh::lon_hp_1e9deg, "lonHp", 1e-9), i1(&NavHpposllh::lat_hp_1e9deg, "latHp", 1e-9),
          i1(&NavHpposllh::height_hp_0p1mm, "heightHp", 1e-4),
          i1(&NavHpposllh::h_msl_hp_0p1mm, "hMSLHp", 1e-4),
          u4(&NavHpposllh::h_acc_0p1mm, "hAcc", 1e-4), u4(&NavHpposllh::v_acc_0p1mm, "vAcc", 1e-4)),
      describe<NavOdo>(kNavOdo, "NAV-ODO", Length::kAtLeast,
          u1(&NavOdo::version, "version"), u1(&NavOdo::reserved1, "reserved1"),
          u4(&NavOdo::i_tow_ms, "iTOW", 1e-3), u4(&NavOdo::distance_m, "distance"),
          u4(&NavOdo::total_distance_m, "totalDistance"), u4(&NavOdo::distance_std_m, "distanceStd")),
      describe<NavResetodo>(kNavResetodo, "NAV-RESETODO", Length::kExact),
      describe<NavOrb>(kNavOrb, "NAV-ORB", Length::kExact,
          u4(&NavOrb::i_tow_ms, "iTOW", 1e-3), u1(&NavOrb::version, "version"), count("numSv"),
          u1(&NavOrb::reserved1, "reserved1"),
          block(&NavOrb::svs, u1(&NavOrbSv::gnss_id, "gnssId"), u1(&NavOrbSv::sv_id, "svId"),
                x1(&NavOrbSv::sv_flag, "svFlag"), x1(&NavOrbSv::eph, "eph"), x1(&NavOrbSv::alm, "alm"),
                x1(&NavOrbSv::other_orb, "otherOrb"))),
      describe<NavGeofence>(kNavGeofence, "NAV-GEOFENCE", Length::kExact,
          u4(&NavGeofence::i_tow_ms, "iTOW", 1e-3), u1(&NavGeofence::version, "version"),
          u1(&NavGeofence::status, "status"), count("numFences"),
          u1(&NavGeofence::comb_state, "combState"),
          block(&NavGeofence::fences, u1(&NavGeofenceFence::state, "state"),
                u1(&NavGeofenceFence::id, "id"))),
      describe<NavSvin>(kNavSvin, "NAV-SVIN", Length::kAtLeast,
          u1(&NavSvin::version, "version"), u1(&NavSvin::reserved1, "reserved1"),
          u4(&NavSvin::i_tow_ms, "iTOW", 1e-3), u4(&NavSvin::dur_s, "dur"),
          i4(&NavSvin::mean_x_cm, "meanX", 1e-2), i4(&NavSvin::mean_y_cm, "meanY", 1e-2),
          i4(&NavSvin::mean_z_cm, "meanZ", 1e-2), i1(&NavSvin::mean_x_hp_0p1mm, "meanXHP", 1e-4),
          i1(&NavSvin::mean_y_hp_0p1mm, "meanYHP", 1e-4), i1(&NavSvin::mean_z_hp_0p1mm, "meanZHP", 1e-4),
          u1(&NavSvin::reserved2, "reserved2"), u4(&NavSvin::mean_acc_0p1mm, "meanAcc", 1e-4),
          u4(&NavSvin::obs, "obs"), u1(&NavSvin::valid, "valid"), u1(&NavSvin::active, "active"),
          u1(&NavSvin::reserved3, "reserved3")),
      describe<NavRelposnedV0>(kNavRelposned, "NAV-RELPOSNED", Length::kAtLeast,
          u1(&NavRelposnedV0::version, "version").only(0, 0), u1(&NavRelposnedV0::reserved1, "reserved1"),
          u2(&NavRelposnedV0::ref_station_id, "refStationId"),
          u4(&NavRelposnedV0::i_tow_ms, "iTOW", 1e-3),
          i4(&NavRelposnedV0::rel_pos_n_cm, "relPosN", 1e-2),
          i4(&NavRelposnedV0::rel_pos_e_cm, "relPosE", 1e-2),
          i4(&NavRelposnedV0::rel_pos_d_cm, "relPosD", 1e-2),
          i1(&NavRelposnedV0::rel_pos_hp_n_0p1mm, "relPosHPN", 1e-4),
          i1(&NavRelposnedV0::rel_pos_hp_e_0p1mm, "relPosHPE", 1e-4),
          i1(&NavRelposnedV0::rel_pos_hp_d_0p1mm, "relPosHPD", 1e-4),
          u1(&NavRelposnedV0::reserved2, "reserved2"),
          u4(&NavRelposnedV0::acc_n_0p1mm, "accN", 1e-4), u4(&NavRelposnedV0::acc_e_0p1mm, "accE", 1e-4),
          u4(&NavRelposnedV0::acc_d_0p1mm, "accD", 1e-4), x4(&NavRelposnedV0::flags, "flags")),
      describe<NavRelposned>(kNavRelposned, "NAV-RELPOSNED", Length::kAtLeast,
          u1(&NavRelposned::version, "version").only(1, 1), u1(&NavRelposned::reserved0, "reserved0"),
          u2(&NavRelposned::ref_station_id, "refStationId"), u4(&NavRelposned::i_tow_ms, "iTOW", 1e-3),
          i4(&NavRelposned::rel_pos_n_cm, "relPosN", 1e-2), i4(&NavRelposned::rel_pos_e_cm, "relPosE", 1e-2),
          i4(&NavRelposned::rel_pos_d_cm, "relPosD", 1e-2),
          i4(&NavRelposned::rel_pos_length_cm, "relPosLength", 1e-2),
          i4(&NavRelposned::rel_pos_heading_1e5deg, "relPosHeading", 1e-5),
          u1(&NavRelposned::reserved1, "reserved1"),
          i1(&NavRelposned::rel_pos_hp_n_0p1mm, "relPosHPN", 1e-4),
          i1(&NavRelposned::rel_pos_hp_e_0p1mm, "relPosHPE", 1e-4),
          i1(&NavRelposned::rel_pos_hp_d_0p1mm, "relPosHPD", 1e-4),
          i1(&NavRelposned::rel_pos_hp_length_0p1mm, "relPosHPLength", 1e-4),
          u4(&NavRelposned::acc_n_0p1mm, "accN", 1e-4), u4(&NavRelposned::acc_e_0p1mm, "accE", 1e-4),
          u4(&NavRelposned::acc_d_0p1mm, "accD", 1e-4),
          u4(&NavRelposned::acc_length_0p1mm, "accLength", 1e-4),
          u4(&NavRelposned::acc_heading_1e5deg, "accHeading", 1e-5),
          u1(&NavRelposned::reserved2, "reserved2"), x4(&NavRelposned::flags, "flags")),
      describe<NavCov>(kNavCov, "NAV-COV", Length::kAtLeast,
          u4(&NavCov::i_tow_ms, "iTOW", 1e-3), u1(&NavCov::version, "version"),
          u1(&NavCov::pos_cov_valid, "posCovValid"), u1(&NavCov::vel_cov_valid, "velCovValid"),
          u1(&NavCov::reserved0, "reserved0"), r4(&NavCov::pos_cov_nn_m2, "posCovNN"),
          r4(&NavCov::pos_cov_ne_m2, "posCovNE"), r4(&NavCov::pos_cov_nd_m2, "posCovND"),
          r4(&NavCov::pos_cov_ee_m2, "posCovEE"), r4(&NavCov::pos_cov_ed_m2, "posCovED"),
          r4(&NavCov::pos_cov_dd_m2, "posCovDD"), r4(&NavCov::vel_cov_nn_m2ps2, "velCovNN"),
          r4(&NavCov::vel_cov_ne_m2ps2, "velCovNE"), r4(&NavCov::vel_cov_nd_m2ps2, "velCovND"),
          r4(&NavCov::vel_cov_ee_m2ps2, "velCovEE"), r4(&NavCov::vel_cov_ed_m2ps2, "velCovED"),
          r4(&NavCov::vel_cov_dd_m2ps2, "velCovDD")),
      describe<NavSig>(kNavSig, "NAV-SIG", Length::kExact,
          u4(&NavSig::i_tow_ms, "iTOW", 1e-3), u1(&NavSig::version, "version"), count("numSigs"),
          u1(&NavSig::reserved1, "reserved1"),
          block(&NavSig::signals, u1(&NavSigSignal::gnss_id, "gnssId"), u1(&NavSigSignal::sv_id, "svId"),
                u1(&NavSigSignal::sig_id, "sigId"), u1(&NavSigSignal::freq_id, "freqId"),
                i2(&NavSigSignal::pr_res_dm, "prRes", 0.1), u1(&NavSigSignal::cno_dbhz, "cno"),
                u1(&NavSigSignal::quality_ind, "qualityInd"), u1(&NavSigSignal::corr_source, "corrSource"),
                u1(&NavSigSignal::iono_model, "ionoModel"), x2(&NavSigSignal::sig_flags, "sigFlags"),
                u1(&NavSigSignal::reserved2, "reserved2"))),
      describe<NavSbas>(kNavSbas, "NAV-SBAS", Length::kExact,
          u4(&NavSbas::i_tow_ms, "iTOW", 1e-3), u1(&NavSbas::geo, "geo"), u1(&NavSbas::mode, "mode"),
          i1(&NavSbas::sys, "sys"), x1(&NavSbas::service, "service"), count("cnt"),
          u1(&NavSbas::reserved1, "reserved1"),
          block(&NavSbas::svs, u1(&NavSbasSv::svid, "svid"), u1(&NavSbasSv::flags, "flags"),
                u1(&NavSbasSv::udre, "udre"), u1(&NavSbasSv::sv_sys, "svSys"),
                u1(&NavSbasSv::sv_service, "svService"), u1(&NavSbasSv::reserved2, "reserved2"),
                i2(&NavSbasSv::prc_cm, "prc", 1e-2), u1(&NavSbasSv::reserved3, "reserved3"),
                i2(&NavSbasSv::ic_cm, "ic", 1e-2))),
      describe<NavSlas>(kNavSlas, "NAV-SLAS", Length::kExact,
          u4(&NavSlas::i_tow_ms, "iTOW", 1e-3), u1(&NavSlas::version, "version"),
          u1(&NavSlas::reserved1, "reserved1"), i4(&NavSlas::gms_lon_1e3deg, "gmsLon", 1e-3),
          i4(&NavSlas::gms_lat_1e3deg, "gmsLat", 1e-3), u1(&NavSlas::gms_code, "gmsCode"),
          u1(&NavSlas::qzss_sv_id, "qzssSvId"), x1(&NavSlas::service_flags, "serviceFlags"), count("cnt"),
          block(&NavSlas::svs, u1(&NavSlasSv::gnss_id, "gnssId"), u1(&NavSlasSv::sv_id, "svId"),
                u1(&NavSlasSv::reserved2, "reserved2"), u1(&NavSlasSv::reserved3, "reserved3"),
                i2(&NavSlasSv::prc_cm, "prc", 1e-2))),
      describe<NavDgps>(kNavDgps, "NAV-DGPS", Length::kExact,
          u4(&NavDgps::i_tow_ms, "iTOW", 1e-3), i4(&NavDgps::age_ms, "age", 1e-3),
          i2(&NavDgps::base_id, "baseId"), i2(&NavDgps::base_health, "baseHealth"), count("numCh"),
          u1(&NavDgps::status, "status"), u1(&NavDgps::reserved1, "reserved1"),
          block(&NavDgps::channels, u1(&NavDgpsCh::svid, "svid"), x1(&NavDgpsCh::flags, "flags"),
                u2(&NavDgpsCh::age_c_ms, "ageC", 1e-3), r4(&NavDgpsCh::prc_m, "prc"),
                r4(&NavDgpsCh::prrc_mps, "prrc"))),
      describe<NavAopstatus>(kNavAopstatus, "NAV-AOPSTATUS", Length::kAtLeast,
          u4(&NavAopstatus::i_tow_ms, "iTOW", 1e-3), x1(&NavAopstatus::aop_cfg, "aopCfg"),
          u1(&NavAopstatus::status, "status"), u1(&NavAopstatus::reserved1, "reserved1")),
      describe<NavTimels>(kNavTimels, "NAV-TIMELS", Length::kAtLeast,
          u4(&NavTimels::i_tow_ms, "iTOW", 1e-3), u1(&NavTimels::version, "version"),
          u1(&NavTimels::reserved1, "reserved1"), u1(&NavTimels::src_of_curr_ls, "srcOfCurrLs"),
          i1(&NavTimels::curr_ls_s, "currLs"), u1(&NavTimels::src_of_ls_change, "srcOfLsChange"),
          i1(&NavTimels::ls_change_s, "lsChange"), i4(&NavTimels::time_to_ls_event_s, "timeToLsEvent"),
          u2(&NavTimels::date_of_ls_gps_wn, "dateOfLsGpsWn"),
          u2(&NavTimels::date_of_ls_gps_dn, "dateOfLsGpsDn"), u1(&NavTimels::reserved2, "reserved2"),
          x1(&NavTimels::valid, "valid")),
      describe<NavTimebds>(kNavTimebds, "NAV-TIMEBDS", Length::kAtLeast,
          u4(&NavTimebds::i_tow_ms, "iTOW", 1e-3), u4(&NavTimebds::sow_s, "SOW"),
          i4(&NavTimebds::f_sow_ns, "fSOW", 1e-9), i2(&NavTimebds::week, "week"),
          i1(&NavTimebds::leap_s, "leapS"), x1(&NavTimebds::valid, "valid"),
          u4(&NavTimebds::t_acc_ns, "tAcc", 1e-9)),
      describe<NavTimegal>(kNavTimegal, "NAV-TIMEGAL", Length::kAtLeast,
          u4(&NavTimegal::i_tow_ms, "iTOW", 1e-3), u4(&NavTimegal::gal_tow_s, "galTow"),
          i4(&NavTimegal::f_gal_tow_ns, "fGalTow", 1e-9), i2(&NavTimegal::gal_wno, "galWno"),
          i1(&NavTimegal::leap_s, "leapS"), x1(&NavTimegal::valid, "valid"),
          u4(&NavTimegal::t_acc_ns, "tAcc", 1e-9)),
      describe<NavTimeglo>(kNavTimeglo, "NAV-TIMEGLO", Length::kAtLeast,
          u4(&NavTimeglo::i_tow_ms, "iTOW", 1e-3), u4(&NavTimeglo::tod_s, "TOD"),
          i4(&NavTimeglo::f_tod_ns, "fTOD", 1e-9), u2(&NavTimeglo::nt_days, "Nt"),
          u1(&NavTimeglo::n4, "N4"), x1(&NavTimeglo::valid, "valid"),
          u4(&NavTimeglo::t_acc_ns, "tAcc", 1e-9)),
      // ---- RXM, INF ----
      describe<RxmRtcm>(kRxmRtcm, "RXM-RTCM", Length::kAtLeast,
          u1(&RxmRtcm::version, "version"), x1(&RxmRtcm::flags, "flags"),
          u2(&RxmRtcm::sub_type, "subType"), u2(&RxmRtcm::ref_station, "refStation"),
          u2(&RxmRtcm::msg_type, "msgType")),
      describe<InfError>(kInfError, "INF-ERROR", Length::kExact, text(&InfError::str, "str")),
      describe<InfWarning>(kInfWarning, "INF-WARNING", Length::kExact, text(&InfWarning::str, "str")),
      describe<InfNotice>(kInfNotice, "INF-NOTICE", Length::kExact, text(&InfNotice::str, "str")),
      describe<InfTest>(kInfTest, "INF-TEST", Length::kExact, text(&InfTest::str, "str")),
      describe<InfDebug>(kInfDebug, "INF-DEBUG", Length::kExact, text(&InfDebug::str, "str")),
      // ---- MON, SEC, TIM ----
      describe<MonRf>(kMonRf, "MON-RF", Length::kExact,
          u1(&MonRf::version, "version"), count("nBlocks"), u1(&MonRf::reserved1, "reserved1"),
          block(&MonRf::blocks, u1(&MonRfBlock::block_id, "blockId"), x1(&MonRfBlock::flags, "flags"),
                u1(&MonRfBlock::ant_status, "antStatus"), u1(&MonRfBlock::ant_power, "antPower"),
                x4(&MonRfBlock::post_status, "postStatus"), u1(&MonRfBlock::reserved2, "reserved2"),
                u2(&MonRfBlock::noise_per_ms, "noisePerMS"), u2(&MonRfBlock::agc_cnt, "agcCnt"),
                u1(&MonRfBlock::jam_ind, "jamInd"), i1(&MonRfBlock::ofs_i, "ofsI"),
                u1(&MonRfBlock::mag_i, "magI"), i1(&MonRfBlock::ofs_q, "ofsQ"),
                u1(&MonRfBlock::mag_q, "magQ"), u1(&MonRfBlock::reserved3, "reserved3"))),
      describe<MonHw2>(kMonHw2, "MON-HW2", Length::kAtLeast,
          i1(&MonHw2::ofs_i, "ofsI"), u1(&MonHw2::mag_i, "magI"), i1(&MonHw2::ofs_q, "ofsQ"),
          u1(&MonHw2::mag_q, "magQ"), u1(&MonHw2::cfg_source, "cfgSource"),
          u1(&MonHw2::reserved1, "reserved1"), x4(&MonHw2::low_lev_cfg, "lowLevCfg"),
          u1(&MonHw2::reserved2, "reserved2"), x4(&MonHw2::post_status, "postStatus"),
          u1(&MonHw2::reserved3, "reserved3")),
      describe<MonHw3>(kMonHw3, "MON-HW3", Length::kExact,
          u1(&MonHw3::version, "version"), count("nPins"), x1(&MonHw3::flags, "flags"),
          ch<MonHw3::kHwVersionSize>(&MonHw3::hw_version, "hwVersion"),
          u1(&MonHw3::reserved1, "reserved1"),
          block(&MonHw3::pins, u2(&MonHw3Pin::pin_id, "pinId"), x2(&MonHw3Pin::pin_mask, "pinMask"),
                u1(&MonHw3Pin::vp, "VP"), u1(&MonHw3Pin::reserved2, "reserved2"))),
      describe<MonComms>(kMonComms, "MON-COMMS", Length::kExact,
          u1(&MonComms::version, "version"), count("nPorts"), x1(&MonComms::tx_errors, "txErrors"),
          u1(&MonComms::reserved1, "reserved1"), u1(&MonComms::prot_ids, "protIds"),
          block(&MonComms::ports, u2(&MonCommsPort::port_id, "portId"),
                u2(&MonCommsPort::tx_pending_bytes, "txPending"), u4(&MonCommsPort::tx_bytes, "txBytes"),
                u1(&MonCommsPort::tx_usage_pct, "txUsage"),
                u1(&MonCommsPort::tx_peak_usage_pct, "txPeakUsage"),
                u2(&MonCommsPort::rx_pending_bytes, "rxPending"), u4(&MonCommsPort::rx_bytes, "rxBytes"),
                u1(&MonCommsPort::rx_usage_pct, "rxUsage"),
                u1(&MonCommsPort::rx_peak_usage_pct, "rxPeakUsage"),
                u2(&MonCommsPort::overrun_errs, "overrunErrs"), u2(&MonCommsPort::msgs, "msgs"),
                u1(&MonCommsPort::reserved2, "reserved2"), u4(&MonCommsPort::skipped_bytes, "skipped"))),
      describe<MonGnss>(kMonGnss, "MON-GNSS", Length::kAtLeast,
          u1(&MonGnss::version, "version"), x1(&MonGnss::supported, "supported"),
          x1(&MonGnss::default_gnss, "defaultGnss"), x1(&MonGnss::enabled, "enabled"),
          u1(&MonGnss::simultaneous, "simultaneous"), u1(&MonGnss::reserved1, "reserved1")),
      describe<MonIo>(kMonIo, "MON-IO", Length::kExact,
          block_to_end<Repeat::kFitLength>(&MonIo::ports, u4(&MonIoPort::rx_bytes, "rxBytes"),
              u4(&MonIoPort::tx_bytes, "txBytes"), u2(&MonIoPort::parity_errs, "parityErrs"),
              u2(&MonIoPort::framing_errs, "framingErrs"), u2(&MonIoPort::overrun_errs, "overrunErrs"),
              u2(&MonIoPort::break_cond, "breakCond"), u1(&MonIoPort::reserved1, "reserved1"))),
      describe<MonMsgpp>(kMonMsgpp, "MON-MSGPP", Length::kAtLeast,
          u2(&MonMsgpp::msg1, "msg1"), u2(&MonMsgpp::msg2, "msg2"), u2(&MonMsgpp::msg3, "msg3"),
          u2(&MonMsgpp::msg4, "msg4"), u2(&MonMsgpp::msg5, "msg5"), u2(&MonMsgpp::msg6, "msg6"),
          u4(&MonMsgpp::skipped_bytes, "skipped")),
      describe<MonPatch>(kMonPatch, "MON-PATCH", Length::kExact,
          u2(&MonPatch::version, "version"), count_u2("nEntries"),
          block(&MonPatch::entries, x4(&MonPatchEntry::patch_info, "patchInfo"),
                u4(&MonPatchEntry::comparator_number, "comparatorNumber"),
                u4(&MonPatchEntry::patch_address, "patchAddress"),
                u4(&MonPatchEntry::patch_data, "patchData"))),
      describe<MonRxbuf>(kMonRxbuf, "MON-RXBUF", Length::kAtLeast,
          u2(&MonRxbuf::pending_bytes, "pending"), u1(&MonRxbuf::usage_pct, "usage"),
          u1(&MonRxbuf::peak_usage_pct, "peakUsage")),
      describe<MonTxbuf>(kMonTxbuf, "MON-TXBUF", Length::kAtLeast,
          u2(&MonTxbuf::pending_bytes, "pending"), u1(&MonTxbuf::usage_pct, "usage"),
          u1(&MonTxbuf::peak_usage_pct, "peakUsage"), u1(&MonTxbuf::t_usage_pct, "tUsage"),
          u1(&MonTxbuf::t_peak_usage_pct, "tPeakusage"), x1(&MonTxbuf::errors, "errors"),
          u1(&MonTxbuf::reserved1, "reserved1")),
      describe<MonSpan>(kMonSpan, "MON-SPAN", Length::kExact,
          u1(&MonSpan::version, "version"), count("numRfBlocks"), u1(&MonSpan::reserved0, "reserved0"),
          block(&MonSpan::blocks, u1(&MonSpanBlock::spectrum_0p25db, "spectrum"),
                u4(&MonSpanBlock::span_hz, "span"), u4(&MonSpanBlock::res_hz, "res"),
                u4(&MonSpanBlock::center_hz, "center"), u1(&MonSpanBlock::pga_db, "pga"),
                u1(&MonSpanBlock::reserved1, "reserved1"))),
      describe<SecUniqid>(kSecUniqid, "SEC-UNIQID", Length::kAtLeast,
          u1(&SecUniqid::version, "version").only(1, 1), u1(&SecUniqid::reserved1, "reserved1"),
          u1(&SecUniqid::unique_id, "uniqueId")),
      describe<TimTp>(kTimTp, "TIM-TP", Length::kAtLeast,
          u4(&TimTp::tow_ms, "towMS", 1e-3), u4(&TimTp::tow_sub_ms_2m32, "towSubMS", 0x1p-32 * 1e-3),
          i4(&TimTp::q_err_ps, "qErr", 1e-12), u2(&TimTp::week, "week"), x1(&TimTp::flags, "flags"),
          x1(&TimTp::ref_info, "refInfo")),
      describe<TimTm2>(kTimTm2, "TIM-TM2", Length::kAtLeast,
          u1(&TimTm2::ch, "ch"), x1(&TimTm2::flags, "flags"), u2(&TimTm2::count, "count"),
          u2(&TimTm2::wn_r, "wnR"), u2(&TimTm2::wn_f, "wnF"), u4(&TimTm2::tow_ms_r, "towMsR", 1e-3),
          u4(&TimTm2::tow_sub_ms_r_ns, "towSubMsR", 1e-9), u4(&TimTm2::tow_ms_f, "towMsF", 1e-3),
          u4(&TimTm2::tow_sub_ms_f_ns, "towSubMsF", 1e-9), u4(&TimTm2::acc_est_ns, "accEst", 1e-9)),
      describe<TimVrfy>(kTimVrfy, "TIM-VRFY", Length::kAtLeast,
          i4(&TimVrfy::i_tow_ms, "itow", 1e-3), i4(&TimVrfy::frac_ns, "frac", 1e-9),
          i4(&TimVrfy::delta_ms, "deltaMs", 1e-3), i4(&TimVrfy::delta_ns, "deltaNs", 1e-9),
          u2(&TimVrfy::wno, "wno"), x1(&TimVrfy::flags, "flags"), u1(&TimVrfy::reserved1, "reserved1")),
      // ---- CFG, the rest of the legacy messages ----
      describe<CfgInfPoll>(kCfgInf, "CFG-INF", Length::kExact,
          u1(&CfgInfPoll::protocol_id, "protocolID")),
      describe<CfgInf>(kCfgInf, "CFG-INF", Length::kExact,
          block_to_end<Repeat::kAll>(&CfgInf::blocks, u1(&CfgInfBlock::protocol_id, "protocolID"),
              u1(&CfgInfBlock::reserved1, "reserved1"), x1(&CfgInfBlock::inf_msg_mask, "infMsgMask"))
              .at_least(1)),
      describe<CfgTp5Poll>(kCfgTp5, "CFG-TP5", Length::kExact,
          optional(&CfgTp5Poll::has_tp_idx, u1(&CfgTp5Poll::tp_idx, "tpIdx"))),
      describe<CfgTp5>(kCfgTp5, "CFG-TP5", Length::kExact,
          u1(&CfgTp5::tp_idx, "tpIdx"), u1(&CfgTp5::version, "version"),
          u1(&CfgTp5::reserved1, "reserved1"), i2(&CfgTp5::ant_cable_delay_ns, "antCableDelay", 1e-9),
          i2(&CfgTp5::rf_group_delay_ns, "rfGroupDelay", 1e-9),
          u4(&CfgTp5::freq_period_hz_or_us, "freqPeriod"),
          u4(&CfgTp5::freq_period_lock_hz_or_us, "freqPeriodLock"),
          u4(&CfgTp5::pulse_len_ratio_us_or_2m32, "pulseLenRatio"),
          u4(&CfgTp5::pulse_len_ratio_lock_us_or_2m32, "pulseLenRatioLock"),
          i4(&CfgTp5::user_config_delay_ns, "userConfigDelay", 1e-9), x4(&CfgTp5::flags, "flags")),
      describe<CfgNmea>(kCfgNmea, "CFG-NMEA", Length::kExact,
          x1(&CfgNmea::filter, "filter"), u1(&CfgNmea::nmea_version, "nmeaVersion"),
          u1(&CfgNmea::num_sv, "numSV"), x1(&CfgNmea::flags, "flags"),
          optional(&CfgNmea::has_v0, x4(&CfgNmea::gnss_to_filter, "gnssToFilter"),
                   u1(&CfgNmea::sv_numbering, "svNumbering"), u1(&CfgNmea::main_talker_id, "mainTalkerId"),
                   u1(&CfgNmea::gsv_talker_id, "gsvTalkerId"), u1(&CfgNmea::version, "version")),
          optional(&CfgNmea::has_v1, u1(&CfgNmea::bds_talker_id, "bdsTalkerId"),
                   u1(&CfgNmea::reserved1, "reserved1"))),
      describe<CfgNavx5>(kCfgNavx5, "CFG-NAVX5", Length::kExact,
          u2(&CfgNavx5::version, "version"), x2(&CfgNavx5::mask1, "mask1"), x4(&CfgNavx5::mask2, "mask2"),
          u1(&CfgNavx5::reserved1, "reserved1"), u1(&CfgNavx5::min_svs, "minSVs"),
          u1(&CfgNavx5::max_svs, "maxSVs"), u1(&CfgNavx5::min_cno_dbhz, "minCNO"),
          u1(&CfgNavx5::reserved2, "reserved2"), u1(&CfgNavx5::ini_fix_3d, "iniFix3D"),
          u1(&CfgNavx5::reserved3, "reserved3"), u1(&CfgNavx5::ack_aiding, "ackAiding"),
          u2(&CfgNavx5::wkn_rollover, "wknRollover"),
          u1(&CfgNavx5::sig_atten_comp_mode_dbhz, "sigAttenCompMode"),
          u1(&CfgNavx5::reserved4, "reserved4"), u1(&CfgNavx5::reserved5, "reserved5"),
          u1(&CfgNavx5::reserved6, "reserved6"), u1(&CfgNavx5::use_ppp, "usePPP"),
          u1(&CfgNavx5::aop_cfg, "aopCfg"), u1(&CfgNavx5::reserved7, "reserved7"),
          u2(&CfgNavx5::aop_orb_max_err_m, "aopOrbMaxErr"), u1(&CfgNavx5::reserved8, "reserved8"),
          u1(&CfgNavx5::reserved9, "reserved9"), u1(&CfgNavx5::use_adr, "useAdr"),
          optional(&CfgNavx5::has_v3, u1(&CfgNavx5::reserved10, "reserved10"),
                   u1(&CfgNavx5::reserved11, "reserved11"))),
      describe<CfgSbas>(kCfgSbas, "CFG-SBAS", Length::kExact,
          x1(&CfgSbas::mode, "mode"), x1(&CfgSbas::usage, "usage"), u1(&CfgSbas::max_sbas, "maxSBAS"),
          x1(&CfgSbas::scanmode2, "scanmode2"), x4(&CfgSbas::scanmode1, "scanmode1")),
      describe<CfgItfm>(kCfgItfm, "CFG-ITFM", Length::kExact,
          x4(&CfgItfm::config, "config"), x4(&CfgItfm::config2, "config2")),
      describe<CfgTmode3>(kCfgTmode3, "CFG-TMODE3", Length::kExact,
          u1(&CfgTmode3::version, "version"), u1(&CfgTmode3::reserved1, "reserved1"),
          x2(&CfgTmode3::flags, "flags"), i4(&CfgTmode3::ecef_x_or_lat, "ecefXOrLat"),
          i4(&CfgTmode3::ecef_y_or_lon, "ecefYOrLon"), i4(&CfgTmode3::ecef_z_or_alt_cm, "ecefZOrAlt", 1e-2),
          i1(&CfgTmode3::ecef_x_or_lat_hp, "ecefXOrLatHP"), i1(&CfgTmode3::ecef_y_or_lon_hp, "ecefYOrLonHP"),
          i1(&CfgTmode3::ecef_z_or_alt_hp_0p1mm, "ecefZOrAltHP", 1e-4),
          u1(&CfgTmode3::reserved2, "reserved2"),
          u4(&CfgTmode3::fixed_pos_acc_0p1mm, "fixedPosAcc", 1e-4),
          u4(&CfgTmode3::svin_min_dur_s, "svinMinDur"),
          u4(&CfgTmode3::svin_acc_limit_0p1mm, "svinAccLimit", 1e-4),
          u1(&CfgTmode3::reserved3, "reserved3")),
      describe<CfgDgnss>(kCfgDgnss, "CFG-DGNSS", Length::kExact,
          u1(&CfgDgnss::dgnss_mode, "dgnssMode"), u1(&CfgDgnss::reserved1, "reserved1")),
      describe<CfgOdo>(kCfgOdo, "CFG-ODO", Length::kExact,
          u1(&CfgOdo::version, "version"), u1(&CfgOdo::reserved1, "reserved1"),
          x1(&CfgOdo::flags, "flags"), x1(&CfgOdo::odo_cfg, "odoCfg"), u1(&CfgOdo::reserved2, "reserved2"),
          u1(&CfgOdo::cog_max_speed_0p1mps, "cogMaxSpeed", 0.1),
          u1(&CfgOdo::cog_max_pos_acc_m, "cogMaxPosAcc"), u1(&CfgOdo::reserved3, "reserved3"),
          u1(&CfgOdo::vel_lp_gain, "velLpGain"), u1(&CfgOdo::cog_lp_gain, "cogLpGain"),
          u1(&CfgOdo::reserved4, "reserved4")),
      describe<CfgUsb>(kCfgUsb, "CFG-USB", Length::kExact,
          u2(&CfgUsb::vendor_id, "vendorID"), u2(&CfgUsb::product_id, "productID"),
          u1(&CfgUsb::reserved1, "reserved1"), u1(&CfgUsb::reserved2, "reserved2"),
          u2(&CfgUsb::power_consumption_ma, "powerConsumption"), x2(&CfgUsb::flags, "flags"),
          ch<CfgUsb::kStringSize>(&CfgUsb::vendor_string, "vendorString"),
          ch<CfgUsb::kStringSize>(&CfgUsb::product_string, "productString"),
          ch<CfgUsb::kStringSize>(&CfgUsb::serial_number, "serialNumber")),
      describe<CfgAnt>(kCfgAnt, "CFG-ANT", Length::kExact,
          x2(&CfgAnt::flags, "flags"), x2(&CfgAnt::pins, "pins")),
      describe<CfgPm2>(kCfgPm2, "CFG-PM2", Length::kExact,
          u1(&CfgPm2::version, "version"), u1(&CfgPm2::reserved1, "reserved1"),
          u1(&CfgPm2::max_startup_state_dur_s, "maxStartupStateDur"), u1(&CfgPm2::reserved2, "reserved2"),
          x4(&CfgPm2::flags, "flags"), u4(&CfgPm2::update_period_ms, "updatePeriod", 1e-3),
          u4(&CfgPm2::search_period_ms, "searchPeriod", 1e-3),
          u4(&CfgPm2::grid_offset_ms, "gridOffset", 1e-3), u2(&CfgPm2::on_time_s, "onTime"),
          u2(&CfgPm2::min_acq_time_s, "minAcqTime"), u1(&CfgPm2::reserved3, "reserved3"),
          optional(&CfgPm2::has_extint_inactivity,
                   u4(&CfgPm2::extint_inactivity_ms, "extintInactivityMs", 1e-3))),
      describe<CfgRxm>(kCfgRxm, "CFG-RXM", Length::kExact,
          u1(&CfgRxm::reserved1, "reserved1"), u1(&CfgRxm::lp_mode, "lpMode")),
      describe<CfgPms>(kCfgPms, "CFG-PMS", Length::kExact,
          u1(&CfgPms::version, "version"), u1(&CfgPms::power_setup_value, "powerSetupValue"),
          u2(&CfgPms::period_s, "period"), u2(&CfgPms::on_time_s, "onTime"),
          u1(&CfgPms::reserved1, "reserved1")),
      describe<CfgPwr>(kCfgPwr, "CFG-PWR", Length::kExact,
          u1(&CfgPwr::version, "version"), u1(&CfgPwr::reserved1, "reserved1"),
          u4(&CfgPwr::state, "state")),
      describe<CfgGeofence>(kCfgGeofence, "CFG-GEOFENCE", Length::kExact,
          u1(&CfgGeofence::version, "version"), count("numFences"), u1(&CfgGeofence::conf_lvl, "confLvl"),
          u1(&CfgGeofence::reserved1, "reserved1"), u1(&CfgGeofence::pio_enabled, "pioEnabled"),
          u1(&CfgGeofence::pin_polarity, "pinPolarity"), u1(&CfgGeofence::pin, "pin"),
          u1(&CfgGeofence::reserved2, "reserved2"),
          block(&CfgGeofence::fences, i4(&CfgGeofenceFence::lat_1e7deg, "lat", 1e-7),
                i4(&CfgGeofenceFence::lon_1e7deg, "lon", 1e-7),
                u4(&CfgGeofenceFence::radius_cm, "radius", 1e-2))),
      describe<CfgLogfilter>(kCfgLogfilter, "CFG-LOGFILTER", Length::kExact,
          u1(&CfgLogfilter::version, "version"), x1(&CfgLogfilter::flags, "flags"),
          u2(&CfgLogfilter::min_interval_s, "minInterval"),
          u2(&CfgLogfilter::time_threshold_s, "timeThreshold"),
          u2(&CfgLogfilter::speed_threshold_mps, "speedThreshold"),
          u4(&CfgLogfilter::position_threshold_m, "positionThreshold")),
      describe<CfgRinv>(kCfgRinv, "CFG-RINV", Length::kExact,
          x1(&CfgRinv::flags, "flags"),
          block_to_end<Repeat::kAll>(&CfgRinv::data, self<Wire::kU1, std::uint8_t>("data"))),
      describe<CfgDat>(kCfgDat, "CFG-DAT", Length::kExact, kCfgDatum),
      describe<CfgDatCurrent>(kCfgDat, "CFG-DAT", Length::kExact,
          u2(&CfgDatCurrent::datum_num, "datumNum"),
          ch<CfgDatCurrent::kNameSize>(&CfgDatCurrent::datum_name, "datumName"), kCfgDatum));
};

// The description of message struct T (a compile-time error for a struct without one).
template <class T>
concept Described = requires { layout_in<T>(Descriptions::kAll); };
template <Described T>
inline constexpr const auto& layout_of = layout_in<T>(Descriptions::kAll);

// ---- encoders and decoders, driven by the descriptions ---------------------------------------
// Repeated blocks beyond the count field's range (255; 65535 for MON-PATCH's U2) or beyond the
// 16-bit length are not sent; VALGET/VALSET/VALDEL carry at most 64 keys by specification but
// are not truncated.
// A decoder checks the payload's length against the description (see the top of this file):
// at least the fixed part for output messages, exactly for the others, exactly the count's
// blocks for messages with a counted block, whole blocks for blocks to the end (MON-VER,
// VALGET keys); CFG-VALGET's request (version 0) and answer (version 1) each reject the other.

template <Described T>
void append(const T& m, std::vector<std::uint8_t>& out) {
  layout_of<T>.append(m, out);
}

template <Described T>
bool decode(std::span<const std::uint8_t> payload, T& m) {
  return layout_of<T>.decode(payload, m);
}

// ---- the registry of described messages ----------------------------------------------------

// One described message, type-erased, for table dispatch and generic tests: its class/ID, name
// and length rule, and a hook that decodes a payload as this message and appends the frame
// again (false when the payload does not decode). Messages with several forms, told apart by
// their length or version byte (CFG-PRT poll, one port and several ports; CFG-MSG's three
// forms; CFG-INF and CFG-TP5 poll and set; CFG-DAT set and current datum; NAV-RELPOSNED
// versions 0 and 1; CFG-VALGET request and answer) have an entry per form, in that order.
struct MessageInfo {
  MsgId id;
  const char* name;
  Length length;
  std::size_t header_size;    // the fixed part (the whole payload without a block)
  std::size_t block_size;     // one repeated block; 0: none, or of variable size
  std::size_t count_offset;   // the count of the blocks; header_size: not counted
  std::size_t count_size;     // bytes of that count (1, or 2 for MON-PATCH)
  std::size_t min_blocks;     // blocks a payload has at least
  std::size_t optional_size;  // bytes of all optional last groups (0: none)
  bool key_values;            // key/value pairs to the end (CFG-VALGET answer, CFG-VALSET)
  bool text;                  // NUL-padded strings: what follows a NUL is not kept
  bool (*reencode)(std::span<const std::uint8_t> payload, std::vector<std::uint8_t>& out);
};

// Every described message, in the order of the descriptions above.
std::span<const MessageInfo> messages();
// The first described message (form) with this class and ID, or with this name; null if none.
const MessageInfo* find_message(MsgId id);
const MessageInfo* find_message(std::string_view name);

// The PROTVER extension of a MON-VER ("PROTVER=18.00", or "PROTVER 16.00" on older
// firmware) as protocol version x 100 (1800); 0 when absent or malformed.
int protocol_version_x100(const MonVer& m);

}  // namespace navemu::ubx
