#pragma once
// NMEA 0183 (version 2.0, 2.3 and 4.10 field sets) sentence encoders: pure functions from
// typed fields to bytes. Each encode() appends one or more complete sentences "$...*hh\r\n" to
// `out`; with enough capacity reserved it does not allocate. Units in the field structs are SI
// or degrees; the conversion to wire units (ddmm.mmmm, knots, km/h) happens here and nowhere
// else.
//
// An unset std::optional, or a non-finite value, gives an empty field, as receivers send when
// a value is not valid.
//
// No sentence exceeds 82 characters including "$" and CR LF (NMEA 0183 section 5.3). This
// holds by construction, for every Format but one in u-blox high precision mode (which the part
// documents as violating the standard; Format::high_precision) and every field value:
//  - Format knobs are clamped to the ranges noted next to them;
//  - values are clamped to the ranges of their fields (noted at each struct; e.g. altitude to
//    [-9999, 99999] m, DOP to [0, 99.99], C/N0 to [0, 99] dB-Hz, PRN to [0, 999]);
//  - when a sentence would still be longer (GGA with a 5-digit altitude and a DGPS age in the
//    u-blox style, RMC with speed, course and magnetic variation, GSA with twelve 3-digit
//    PRNs), the decimals of its least important numbers are dropped one at a time (GGA:
//    altitude, DGPS age, geoid separation, HDOP; RMC: magnetic variation, speed, course; GSA:
//    VDOP, HDOP, PDOP) until it fits. Position and time keep their decimals.
//
// Rounding: lat/lon are rounded as a whole (59.999996' carries into the degrees), time of day
// as a whole together with the date (23:59:59.999 becomes 00:00:00.00 of the next day), a
// course that rounds to 360 is sent as 0.
//
// Field widths follow the receiver's style (Format): the defaults reproduce a u-blox receiver
// (tests/protocols: the NEO-M9N capture, NMEA 4.10), Format::garmin() a Garmin one (the 15x
// capture, NMEA 2.0 field set).

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/satellite.hpp"

namespace navemu::nmea {

// Wire style of a receiver family: decimals and zero padding of the numeric fields, and which
// optional trailing fields of newer NMEA versions are sent. Out-of-range knobs are clamped to
// the range in brackets.
struct Format {
  int time_decimals = 2;            // hhmmss.ss [0, 3]
  int latlon_minute_decimals = 5;   // ddmm.mmmmm [0, 5]
  int dop_decimals = 2;             // HDOP/PDOP/VDOP [0, 2]
  int altitude_decimals = 1;        // GGA altitude and geoid separation [0, 3]
  int speed_decimals = 3;           // knots and km/h [0, 3]
  int speed_integer_digits = 1;     // zero padded integer part ("005.3" has 3) [1, 3]
  int course_decimals = 2;          // course and magnetic variation [0, 3]
  int course_integer_digits = 1;    // [1, 3]
  int snr_digits = 2;               // GSV C/N0, zero padded ("07") [1, 2]
  int gst_significant_digits = 2;   // GST sigmas: "0.98", "2.5", "837" (never fewer than the
                                    // integer digits, at most 3 decimals) [1, 6]
  bool gga_sats_two_digits = true;  // "08" rather than "8"
  bool mode_indicator = true;       // NMEA 2.3 mode field in RMC, GLL, VTG
  bool nav_status = true;           // NMEA 4.1 navigational status field at the end of RMC
                                    // (sent only together with the mode indicator)
  bool system_signal_ids = true;    // NMEA 4.1 GNSS system ID at the end of GSA, signal ID at
                                    // the end of GSV
  // u-blox NMEA high precision mode (ZED-F9P integration manual UBX-18010802 3.1.4.5,
  // CFG-NMEA-HIGHPREC): latitude and longitude with seven decimals of the minute, altitude
  // (and geoid separation) with three, instead of the two knobs above; no decimals are dropped
  // to fit 82 characters.
  bool high_precision = false;

  static Format ublox() { return {}; }  // u-blox M9 with NMEA 4.10 (its default)
  static Format garmin();               // the Garmin 15x/18x style
};

// UTC; the second may carry a fraction (a leap second 60.x is sent as 00.x of the next minute).
// The date is sent by RMC (ddmmyy) and ZDA; year [0, 9999].
struct UtcTime {
  int year = 2000, month = 1, day = 1;
  int hour = 0, minute = 0;
  double second = 0.0;
};

// Degrees, north and east positive. Latitude is clamped to [-90, 90], longitude to
// [-180, 180]; a non-finite coordinate gives empty position fields.
struct LatLon {
  double lat_deg = 0.0;
  double lon_deg = 0.0;
};

// Talker IDs are two characters ("GP", "GN", ...); a longer one is cut to two.

// GGA, global positioning system fix data (NMEA 0183 4.10). Position-fix quality:
// 0 invalid, 1 GPS, 2 DGPS, 4 RTK fixed, 5 RTK float, 6 dead reckoning, 8 simulation.
// The unit fields "M" are empty when their value is, as u-blox sends them without a fix:
//   $GPGGA,185253.00,,,,,0,00,99.99,,,,,,*6E
struct GgaFields {
  std::string_view talker = "GP";
  UtcTime utc;
  std::optional<LatLon> position;
  int quality = 0;                           // [0, 9]
  int num_sats = 0;                          // satellites used [0, 99]
  std::optional<double> hdop;                // [0, 99.99]
  std::optional<double> alt_msl_m;           // [-9999, 99999]
  std::optional<double> geoid_separation_m;  // ellipsoid height minus MSL height [-999, 999]
  std::optional<double> dgps_age_s;          // one decimal [0, 99.9]
  std::optional<int> dgps_station;           // four digits "0000" [0, 1023]
};

// RMC, recommended minimum specific GNSS data (NMEA 0183 4.10).
// Mode indicator of NMEA 2.3: 'A' autonomous, 'D' differential, 'E' dead reckoning,
// 'R' RTK fixed, 'F' RTK float, 'N' not valid. Navigational status of NMEA 4.1: 'S' safe,
// 'C' caution, 'U' unsafe, 'V' not valid. A character other than an upper-case letter is sent
// as 'N' (mode) or 'V' (status).
struct RmcFields {
  std::string_view talker = "GP";
  UtcTime utc;
  bool valid = false;  // status A / V
  std::optional<LatLon> position;
  std::optional<double> speed_mps;       // over ground, sent in knots [0, 9999.999 kn]
  std::optional<double> course_deg;      // true, [0, 360)
  std::optional<double> magvar_deg;      // east positive [-180, 180]
  char mode = 'N';
  char nav_status = 'V';                 // NMEA 4.1 (only with Format::nav_status)
};

// The talker ID of a system's own sentences (GSV), as u-blox receivers send them (u-blox F9
// interface description UBX-18010854, "NMEA talker ID"): GP GPS (and SBAS), GL GLONASS,
// GA Galileo, GB BeiDou, GQ QZSS, GI NavIC; and the main talker (GGA, RMC, GSA, ...) of a
// receiver tracking `systems` (a system_bit mask): the one system's, GN for several.
std::string_view system_talker(GnssSystem s);
std::string_view main_talker(std::uint32_t systems);

// GSA, GNSS DOP and active satellites (NMEA 0183 4.10).
struct GsaFields {
  std::string_view talker = "GP";
  char selection = 'A';  // A automatic, M manual
  int fix = 1;           // 1 none, 2 2D, 3 3D
  // NMEA satellite IDs of the used satellites (SatId::nmea_id) [0, 999], the first 12 are
  // sent, two digits at least.
  std::vector<int> sat_ids;
  std::optional<double> pdop, hdop, vdop;  // [0, 99.99]
  int system_id = 1;  // NMEA 4.1 GNSS system ID (1 GPS, 2 GLONASS, 3 Galileo, 4 BeiDou)
                      // [0, 15], only with Format::system_signal_ids
};

struct GsvSatellite {
  int sat_id = 0;                    // NMEA satellite ID [0, 999], two digits at least
  std::optional<int> elevation_deg;  // [0, 90], two digits
  std::optional<int> azimuth_deg;    // [0, 359] (taken modulo 360), three digits
  std::optional<int> snr_dbhz;       // C/N0 [0, 99]; empty when not tracked
};

// GSV, GNSS satellites in view (NMEA 0183 4.10): ceil(n / 4) sentences of at most
// four satellites each (the last one not padded), each with the number of sentences, its own
// number and the total count n; one sentence "1,1,00" when none. At most 99 satellites are
// sent (so both counters stay within two digits).
struct GsvFields {
  std::string_view talker = "GP";
  std::span<const GsvSatellite> satellites;
  int signal_id = 1;  // NMEA 4.1 signal ID (1 GPS L1 C/A) [0, 15], only with
                      // Format::system_signal_ids; 0 ("all signals") is sent when there are
                      // no satellites, as u-blox does: $GPGSV,1,1,00,0*65
};

// VTG, course over ground and ground speed (NMEA 0183 4.10). The unit letters
// T, M, N, K are empty only when all three values are, as u-blox sends it without a fix:
//   $GNVTG,,,,,,,,,N*2E
struct VtgFields {
  std::string_view talker = "GP";
  std::optional<double> course_true_deg;      // [0, 360)
  std::optional<double> course_magnetic_deg;  // [0, 360)
  std::optional<double> speed_mps;            // sent in knots and km/h [0, 9999.999 kn]
  char mode = 'N';
};

// GLL, geographic position (NMEA 0183 4.10).
struct GllFields {
  std::string_view talker = "GP";
  std::optional<LatLon> position;
  UtcTime utc;
  bool valid = false;
  char mode = 'N';
};

// GST, GNSS pseudorange error statistics (NMEA 0183 4.10): 1-sigma errors in
// metres [0, 999999], orientation of the semi-major axis in degrees from true north [0, 180].
struct GstFields {
  std::string_view talker = "GP";
  UtcTime utc;
  std::optional<double> range_rms_m;
  std::optional<double> major_m, minor_m, orientation_deg;  // error ellipse
  std::optional<double> lat_sigma_m, lon_sigma_m, alt_sigma_m;
};

// ZDA, time and date (NMEA 0183 4.10).
struct ZdaFields {
  std::string_view talker = "GP";
  UtcTime utc;
  int local_zone_hours = 0, local_zone_minutes = 0;  // [-13, 13], [0, 59]
};

// TXT, text transmission (NMEA 0183 4.10): the number of sentences and this one's number
// [1, 99], the text identifier [0, 99] (u-blox: 00 error, 01 warning, 02 notice, 07 user) and the
// text, cut to the 61 characters that fit in 82; a character the standard reserves or does not
// allow in text ($ * , ! \ ^ ~, control characters) is sent as a space.
struct TxtFields {
  std::string_view talker = "GP";
  int total = 1, number = 1, text_id = 2;
  std::string_view text;
};

// Garmin proprietary PGRME, estimated position error (horizontal, vertical, spherical), metres
// with one decimal [0, 99999.9].
struct PgrmeFields {
  std::optional<double> hpe_m, vpe_m, epe_m;
};

void encode(const GgaFields& f, const Format& fmt, std::string& out);
void encode(const RmcFields& f, const Format& fmt, std::string& out);
void encode(const GsaFields& f, const Format& fmt, std::string& out);
void encode(const GsvFields& f, const Format& fmt, std::string& out);
void encode(const VtgFields& f, const Format& fmt, std::string& out);
void encode(const GllFields& f, const Format& fmt, std::string& out);
void encode(const GstFields& f, const Format& fmt, std::string& out);
void encode(const ZdaFields& f, const Format& fmt, std::string& out);
void encode(const PgrmeFields& f, const Format& fmt, std::string& out);
void encode(const TxtFields& f, const Format& fmt, std::string& out);

// The checksum of a sentence body (the characters between '$' and '*'): XOR of the bytes.
std::uint8_t checksum(std::string_view body);

// The framing and checksum of a received sentence "$...*hh" (CR LF or LF optional), without
// splitting or allocating. kMalformed: no leading '$', no address field, a character outside
// printable ASCII or a reserved one ('$', '*', '!', '\\', '~') in the body, or no '*' followed
// by exactly two hex digits (either case). kBadChecksum: framed right, checksum mismatch. The
// body (between '$' and '*') is set unless malformed. The length is not checked (real
// receivers exceed 82 characters now and then).
struct Checked {
  enum Status { kOk, kMalformed, kBadChecksum } status = kMalformed;
  std::string_view body;
};
Checked check(std::string_view sentence);

// A received sentence split into fields, for tests and tools: "$GPGGA,...*hh" (CR LF or LF
// optional) -> {"GPGGA", ...}. Empty unless check() finds it kOk.
std::optional<std::vector<std::string>> parse(std::string_view sentence);

}  // namespace navemu::nmea
