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
inline constexpr MsgId kNavVelecef{kClassNav, 0x11};
inline constexpr MsgId kNavVelned{kClassNav, 0x12};
inline constexpr MsgId kNavTimegps{kClassNav, 0x20};
inline constexpr MsgId kNavTimeutc{kClassNav, 0x21};
inline constexpr MsgId kNavClock{kClassNav, 0x22};
inline constexpr MsgId kNavTimels{kClassNav, 0x26};
inline constexpr MsgId kNavSvinfo{kClassNav, 0x30};
inline constexpr MsgId kNavSbas{kClassNav, 0x32};
inline constexpr MsgId kNavSat{kClassNav, 0x35};
inline constexpr MsgId kNavSig{kClassNav, 0x43};
inline constexpr MsgId kNavEoe{kClassNav, 0x61};

inline constexpr MsgId kRxmSfrbx{kClassRxm, 0x13};
inline constexpr MsgId kRxmRawx{kClassRxm, 0x15};

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
inline constexpr MsgId kCfgRate{kClassCfg, 0x08};
inline constexpr MsgId kCfgCfg{kClassCfg, 0x09};
inline constexpr MsgId kCfgSbas{kClassCfg, 0x16};
inline constexpr MsgId kCfgNmea{kClassCfg, 0x17};
inline constexpr MsgId kCfgNav5{kClassCfg, 0x24};
inline constexpr MsgId kCfgTp5{kClassCfg, 0x31};
inline constexpr MsgId kCfgGnss{kClassCfg, 0x3E};
inline constexpr MsgId kCfgValset{kClassCfg, 0x8A};
inline constexpr MsgId kCfgValget{kClassCfg, 0x8B};
inline constexpr MsgId kCfgValdel{kClassCfg, 0x8C};

inline constexpr MsgId kMonVer{kClassMon, 0x04};
inline constexpr MsgId kMonRxbuf{kClassMon, 0x07};
inline constexpr MsgId kMonTxbuf{kClassMon, 0x08};
inline constexpr MsgId kMonHw{kClassMon, 0x09};
inline constexpr MsgId kMonRf{kClassMon, 0x38};

inline constexpr MsgId kTimTp{kClassTim, 0x01};
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
  static constexpr std::uint32_t kQualityMask = 0x7, kSvUsed = 0x8, kEphAvail = 0x800,
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
  static constexpr auto kAll = std::tuple{
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
      describe<CfgPrt>(kCfgPrt, "CFG-PRT", Length::kExact,
          u1(&CfgPrt::port_id, "portID"), u1(&CfgPrt::reserved1, "reserved1"),
          x2(&CfgPrt::tx_ready, "txReady"), x4(&CfgPrt::mode, "mode"),
          u4(&CfgPrt::baud_rate, "baudRate"), x2(&CfgPrt::in_proto_mask, "inProtoMask"),
          x2(&CfgPrt::out_proto_mask, "outProtoMask"), x2(&CfgPrt::flags, "flags"),
          u1(&CfgPrt::reserved2, "reserved2")),
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
  };
};

// The description of message struct T (a compile-time error for a struct without one).
template <class T>
concept Described = layout_index<T, decltype(Descriptions::kAll)>() <
                    std::tuple_size_v<std::remove_cvref_t<decltype(Descriptions::kAll)>>;
template <Described T>
inline constexpr const auto& layout_of =
    std::get<layout_index<T, decltype(Descriptions::kAll)>()>(Descriptions::kAll);

// ---- encoders and decoders, driven by the descriptions ---------------------------------------
// Repeated blocks beyond 255 (or beyond the 16-bit length) are not sent: the count fields are
// one byte; VALGET/VALSET/VALDEL carry at most 64 keys by specification but are not truncated.
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
// again (false when the payload does not decode). Messages whose payload length selects one of
// several forms (CFG-PRT poll and set, CFG-MSG's three forms, CFG-VALGET request and answer)
// have an entry per form, in that order.
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
