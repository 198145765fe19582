#pragma once
// The NMEA side of a u-blox receiver port: the NMEA input the part accepts, and the u-blox
// proprietary PUBX output sentences.
//
//  - NmeaInputReader: bytes as a host writes them to a port (in any pieces, interleaved with
//    UBX and RTCM frames and junk) -> complete NMEA sentences with a good checksum.
//  - parse_input(): a sentence -> the typed command the part takes from it (PUBX,40 message
//    rates, PUBX,41 port protocols and baud, PUBX,00/03/04 polls, standard GxQ polls), or the
//    reason it is not one.
//  - encode(): the PUBX,00 / 03 / 04 outputs from typed fields in SI units and degrees (units
//    are converted here only, unset optionals and non-finite values give empty fields, as in
//    protocols/nmea.hpp); and the input commands themselves, for tests and tools.
//
// Sources: u-blox 8 / u-blox M8 Receiver description including protocol specification
// (UBX-13003221), chapter "NMEA Protocol": "PUBX Messages" (CONFIG PUBX,41, POSITION PUBX,00,
// RATE PUBX,40, SVSTATUS PUBX,03, TIME PUBX,04) and "Standard Messages" (GPQ, GNQ, GLQ, GBQ);
// the F9 descriptions: u-blox ZED-F9P Interface Description (UBX-18010854 R04) 4.2.2 GBQ,
// 4.2.6 GLQ, 4.2.7 GNQ, 4.2.9 GPQ; u-blox F9 HPG 1.13 Interface Description (UBX-21023318
// R02) section 2.7 (standard messages), which also has GAQ (Talker ID GA) and 2.7.11 GQQ
// (Talker ID GQ), and the F9 PUBX section (PUBX,00 "The datum selection may be
// changed using the config item CFG-NAVSPG-USE_USRDAT"). Field widths follow real receiver
// output where the descriptions' examples disagree with it (see each encoder and
// tests/protocols/test_pubx.cpp).
//
// What the part does with malformed input (a bad checksum, a wrong field) the descriptions do
// not say; it gives no acknowledgement for NMEA input either way. The u-blox device ignores
// such sentences; parse_input() says why, for logs and counters.

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <variant>
#include <vector>

#include "protocols/nmea.hpp"
#include "protocols/ubx_messages.hpp"

namespace navemu::pubx {

// ---- identifiers ------------------------------------------------------------------------

// A fixed-length identifier held by value ("GP", "RMC"): commands stay trivially copyable and
// never allocate.
template <std::size_t N>
struct Id {
  std::array<char, N> chars{};

  // The first N characters of `s`, padded with '?' if shorter (encoders send what they hold).
  static constexpr Id of(std::string_view s) {
    Id id;
    for (std::size_t i = 0; i < N; ++i) id.chars[i] = i < s.size() ? s[i] : '?';
    return id;
  }
  std::string_view view() const { return {chars.data(), N}; }
  friend bool operator==(const Id&, const Id&) = default;
};
using Talker = Id<2>;     // NMEA talker ID, e.g. "GP", "EI"
using Formatter = Id<3>;  // NMEA sentence formatter, e.g. "GLL"

// Receiver ports as PUBX,41 (portId) and UBX-CFG-PRT (portID) number them (ubx::kPort*): 0 DDC
// (I2C), 1 UART1, 2 UART2, 3 USB, 4 SPI. PUBX,40 gives one rate per port in this order.
enum class PortId : std::uint8_t {
  kDdc = ubx::kPortDdc,
  kUart1 = ubx::kPortUart1,
  kUart2 = ubx::kPortUart2,
  kUsb = ubx::kPortUsb,
  kSpi = ubx::kPortSpi,
};
inline constexpr std::size_t kPortCount = 5;

// PUBX,41 inProto/outProto carry the protocol masks of UBX-CFG-PRT inProtoMask/outProtoMask
// (ubx::kProtoUbx, kProtoNmea, kProtoRtcm (RTCM 2, input only), kProtoRtcm3).

// ---- input commands ---------------------------------------------------------------------

// PUBX,40 (RATE), set the output rate of one NMEA message on each port:
//   $PUBX,40,msgId,rddc,rus1,rus2,rusb,rspi,reserved*cs      e.g. $PUBX,40,GLL,1,0,0,0,0,0*5D
// A rate counts navigation solutions per message (0 off, 1 every solution, 2 every other one),
// the rate of UBX-CFG-MSG (U1). Hosts also send shorter forms without the trailing fields
// ("$PUBX,40,GLL,0,0,0,0*5C": DDC, UART1, UART2 and USB, no SPI, no reserved; widely used with
// u-blox 6/7/8 parts); what the part does with absent or empty rate fields the descriptions do
// not say: they are unset here, and the device leaves those ports' rates as they are.
struct SetRate {
  Formatter msg_id;                                          // the standard message, e.g. "GLL"
  std::array<std::optional<std::uint8_t>, kPortCount> rate;  // by PortId
  friend bool operator==(const SetRate&, const SetRate&) = default;
};

// PUBX,41 (CONFIG), set the protocols and baud rate of a port:
//   $PUBX,41,portId,inProto,outProto,baudrate,autobauding*cs  e.g. $PUBX,41,1,0007,0003,19200,0*25
// inProto/outProto are hexadecimal masks (ubx::kProto*; hosts send "0007" as well as "3"),
// baudrate is in bit/s, autobauding 0 or 1.
struct SetPort {
  PortId port = PortId::kUart1;
  std::uint16_t in_proto = 0;
  std::uint16_t out_proto = 0;
  std::uint32_t baud_rate = 0;  // bit/s, > 0 (whether the part supports it is the device's call)
  bool autobauding = false;
  friend bool operator==(const SetPort&, const SetPort&) = default;
};

// A PUBX output polled: the sentence with no data fields, "$PUBX,00*33", "$PUBX,03*30",
// "$PUBX,04*37". The answer goes to the port the poll came from.
struct PollPubx {
  std::uint8_t msg_id = 0;  // 0, 3 or 4
  friend bool operator==(const PollPubx&, const PollPubx&) = default;
};

// A standard message polled: $xxGPQ,msgId*cs (also GNQ, GLQ, GBQ, GAQ and, on F9, GQQ), e.g.
// $EIGPQ,RMC*3A. xx is the talker ID of the device asking; GP/GN/GL/GB/GA/GQ (the listener)
// names the receiver by talker ID: the descriptions' "Polls a standard NMEA message if the
// current Talker ID is GP" - the part answers only the poll that names its current talker ID.
struct PollStandard {
  Talker requester;  // "EI"
  Talker listener;   // "GP", "GN", "GL", "GB", "GA" or "GQ"
  Formatter msg_id;  // "RMC"
  friend bool operator==(const PollStandard&, const PollStandard&) = default;
};

using Command = std::variant<SetRate, SetPort, PollPubx, PollStandard>;
static_assert(std::is_trivially_copyable_v<Command>, "commands must not own memory");

// Why a sentence gives no command.
enum class Reason : std::uint8_t {
  kAccepted,     // a command
  kMalformed,    // NMEA framing (nmea::check): no '$', no '*hh', a reserved character
  kBadChecksum,  // framed right, checksum wrong
  kNotInput,     // a well-formed sentence that is not one of the part's inputs ($GPGGA,
                 // $PUBX,05, a poll for an unknown talker)
  kFieldCount,   // too few or too many fields
  kBadField,     // a field of the wrong form (not a number, not hexadecimal, not three
                 // letters, empty where a value is needed)
  kOutOfRange,   // a number outside the range of its field
};
std::string_view to_string(Reason r);

struct Parsed {
  std::optional<Command> command;  // set when reason is kAccepted
  Reason reason = Reason::kMalformed;
  std::size_t field = 0;        // the offending field (0 = address), kFieldCount: the count
  std::string_view field_name;  // its name in the description ("baudrate"), else empty
};

// A received sentence "$...*hh" (CR LF or LF optional) -> its command or the reason there is
// none. No allocation.
Parsed parse_input(std::string_view sentence);

// ---- input reader -----------------------------------------------------------------------

// Incremental reader of the NMEA sentences a host writes to a receiver port, for a port that
// also carries UBX and RTCM frames and junk (each protocol's parser reads the same bytes and
// skips what is not its own).
//
// A sentence starts at '$' and ends at LF (an optional CR before it is part of the sentence):
// it is delivered when nmea::check() finds its framing and checksum right. A '$' always starts
// a new sentence (it cannot occur inside one), so a real sentence is found right after junk or
// a cut one. Bytes that cannot be in a sentence (control bytes other than CR, bytes above
// 0x7E: UBX and RTCM frames) abandon the sentence in progress. A line longer than
// max_sentence bytes (from '$' to LF inclusive; NMEA 0183 section 5.3: 82) is dropped and
// counted, and the reader skips to the next LF or '$'.
//
// The buffer is allocated at construction; feeding never allocates. A complete sentence not
// ended by LF (the descriptions' messages end with CR LF) is not delivered until its LF.
// Known limit: the reader does not know UBX framing, so a complete NMEA sentence inside a UBX
// payload would be taken (the part, parsing frames in order, would not).
class NmeaInputReader {
 public:
  static constexpr std::size_t kDefaultMaxSentence = 82;
  explicit NmeaInputReader(std::size_t max_sentence = kDefaultMaxSentence);

  // Appends `byte`; returns the sentence it completed, "$...*hh" plus the CR LF or LF as
  // received. Valid until the next call of feed() or reset().
  std::optional<std::string_view> feed(std::uint8_t byte);

  // Feeds `bytes`, calling on_sentence(std::string_view) for every sentence they complete.
  template <typename OnSentence>
  void feed(std::span<const std::uint8_t> bytes, OnSentence&& on_sentence) {
    for (const std::uint8_t b : bytes) {
      if (const auto s = feed(b)) on_sentence(*s);
    }
  }

  // Forgets the sentence in progress (counters are kept).
  void reset();

  struct Counters {
    std::uint64_t sentences = 0;        // delivered
    std::uint64_t checksum_errors = 0;  // ended lines framed right with a wrong checksum
    std::uint64_t malformed = 0;        // ended lines with wrong framing (no '*hh', ...)
    std::uint64_t overlong = 0;         // lines longer than max_sentence, dropped
    std::uint64_t abandoned = 0;        // '$' lines cut by a byte that cannot be in a sentence
                                        // or by the next '$' (binary frames, junk, cut writes)
  };
  const Counters& counters() const { return counters_; }
  std::size_t max_sentence() const { return buf_.size(); }

 private:
  enum class State { kIdle, kLine, kSkip };
  void start();

  State state_ = State::kIdle;
  std::vector<char> buf_;  // max_sentence bytes
  std::size_t n_ = 0;
  Counters counters_;
};

// ---- PUBX outputs -----------------------------------------------------------------------

// Navigation status of PUBX,00 (navStat).
enum class NavStatus : std::uint8_t {
  kNoFix,              // NF
  kDeadReckoning,      // DR: dead reckoning only solution
  kStandalone2D,       // G2
  kStandalone3D,       // G3
  kDifferential2D,     // D2
  kDifferential3D,     // D3
  kGnssDeadReckoning,  // RK: combined GNSS + dead reckoning solution
  kTimeOnly,           // TT
};

// PUBX,00 (POSITION), lat/long position data:
//   $PUBX,00,time,lat,NS,long,EW,altRef,navStat,hAcc,vAcc,SOG,COG,vVel,diffAge,HDOP,VDOP,TDOP,
//   numSvs,reserved,DR*cs
// Wire units: altRef m, hAcc/vAcc m, SOG km/h, COG degrees, vVel m/s positive downwards,
// diffAge s. Widths as a u-blox M8 sends them (tests: captures): time hhmmss.ss, lat/long
// (d)ddmm.mmmmm (Format::latlon_minute_decimals; the descriptions' example has six decimals,
// an older firmware's), altRef 3 decimals, hAcc/vAcc 2 significant digits ("1.2", "27",
// "5303316"), SOG 3 decimals, COG 2, vVel 3, diffAge 1, DOPs 2, numSvs plain, reserved "0",
// DR 0/1. Without a fix the part sends zeros, "NF", its large accuracies and DOPs of 99.99
// rather than empty fields; the device fills the fields that way.
struct PositionFields {
  nmea::UtcTime utc;                          // the date is not sent
  std::optional<nmea::LatLon> position;       // user datum (WGS84 by default)
  std::optional<double> height_user_datum_m;  // altRef, above the user datum ellipsoid
                                              // [-99999.999, 999999.999]
  NavStatus nav_status = NavStatus::kNoFix;
  std::optional<double> h_acc_m, v_acc_m;   // [0, 9999999]
  std::optional<double> speed_mps;          // over ground, sent in km/h [0, 99999.999 km/h]
  std::optional<double> course_deg;         // over ground, [0, 360)
  std::optional<double> velocity_down_mps;  // vVel [-9999.999, 9999.999]
  std::optional<double> diff_age_s;         // age of the differential corrections [0, 999.9]
  std::optional<double> hdop, vdop, tdop;   // [0, 99.99]
  int num_svs = 0;                          // satellites used [0, 255]
  bool dead_reckoning_used = false;         // DR
};

// Use of a satellite in PUBX,03 (status).
enum class SvUse : std::uint8_t {
  kNotUsed,           // '-'
  kUsed,              // 'U': used in the navigation solution
  kEphemerisNotUsed,  // 'e': ephemeris available, but not used for navigation
};

struct SvStatus {
  int sv_id = 0;  // NMEA satellite number [0, 999], sent without padding
  SvUse use = SvUse::kNotUsed;
  std::optional<int> azimuth_deg;    // [0, 359] (taken modulo 360), three digits
  std::optional<int> elevation_deg;  // [-90, 90], two digits ("-2", "06")
  std::optional<int> cno_dbhz;       // [0, 99], two digits; unset when not tracked
  double carrier_lock_s = 0.0;       // carrier lock time; 0 code lock only; sent in whole
                                     // seconds, three digits, at most 64 ("lock for 64 s or
                                     // more": the M8 captures never exceed "064")
};

// PUBX,03 (SVSTATUS), satellite status, one sentence for all satellites (real receivers send
// it longer than 82 characters: 32 satellites make ~620):
//   $PUBX,03,GT{,sv,s,az,el,cno,lck}*cs
struct SvStatusFields {
  std::span<const SvStatus> satellites;
};

// PUBX,04 (TIME), time of day and clock information:
//   $PUBX,04,time,date,utcTow,utcWk,leapSec,clkBias,clkDrift,tpGran*cs
// Wire units: utcTow s (2 decimals), utcWk weeks (continues beyond 1023), leapSec s with a
// trailing 'D' when it is the firmware default rather than received from the satellites,
// clkBias integer ns, clkDrift ns/s (3 decimals), tpGran ns (two digits). The M8, u-blox 7 and
// F9 captures end with tpGran; the descriptions' example has one more, empty field.
struct TimeFields {
  nmea::UtcTime utc;                   // time and date (ddmmyy)
  std::optional<double> utc_tow_s;     // UTC time of week [0, 604800]
  std::optional<int> utc_week;         // [0, 99999]
  std::optional<int> leap_seconds;     // [-99, 99]
  bool leap_seconds_default = false;   // 'D'
  std::optional<double> clock_bias_s;  // receiver clock bias, sent in ns [-999.999, 999.999] s
  std::optional<double> clock_drift_s_per_s;       // sent in ns/s [-1e-3, 1e-3] s/s
  std::optional<double> time_pulse_granularity_s;  // sent in ns [0, 999e-9] s
};

void encode(const PositionFields& f, const nmea::Format& fmt, std::string& out);  // PUBX,00
void encode(const SvStatusFields& f, std::string& out);                           // PUBX,03
void encode(const TimeFields& f, const nmea::Format& fmt, std::string& out);      // PUBX,04

// The input commands as a host sends them (tests, tools): parse_input() of the result gives
// the command back. SetRate sends its rates up to the last set one, empty fields for unset ones
// before it, and the reserved field when all five are set.
void encode(const Command& c, std::string& out);

}  // namespace navemu::pubx
