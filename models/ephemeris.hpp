#pragma once
// GPS LNAV broadcast ephemeris records and the navigation data a RINEX nav file carries.

#include <array>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "models/time.hpp"

namespace navemu {

// One broadcast ephemeris set, fields named and scaled as in IS-GPS-200 Table 20-III
// (angles in radians; RINEX stores them in radians already).
struct GpsEphemeris {
  int prn = 0;
  GpsTime toc;  // clock data reference time
  double af0_s = 0.0, af1_sps = 0.0, af2_sps2 = 0.0;

  int iode = 0;
  double crs_m = 0.0;
  double delta_n_radps = 0.0;
  double m0_rad = 0.0;
  double cuc_rad = 0.0;
  double e = 0.0;
  double cus_rad = 0.0;
  double sqrt_a_sqrtm = 0.0;
  GpsTime toe;  // ephemeris reference time (full week resolved)
  double cic_rad = 0.0;
  double omega0_rad = 0.0;  // longitude of ascending node of orbit plane at weekly epoch
  double cis_rad = 0.0;
  double i0_rad = 0.0;
  double crc_m = 0.0;
  double omega_rad = 0.0;  // argument of perigee
  double omega_dot_radps = 0.0;
  double idot_radps = 0.0;

  int codes_on_l2 = 0;
  int l2p_data_flag = 0;
  double ura_m = 0.0;
  int health = 0;
  double tgd_s = 0.0;
  int iodc = 0;
  double transmission_tow_s = 0.0;  // RINEX "transmission time of message"
  double fit_interval_h = 4.0;

  // Where the record came from, for messages ("file.05n:123").
  std::string source;
};

// Klobuchar broadcast ionosphere coefficients (IS-GPS-200 20.3.3.5.1.7, 20.3.3.5.2.5).
struct KlobucharCoefficients {
  std::array<double, 4> alpha{};  // s, s/semicircle, s/semicircle^2, s/semicircle^3
  std::array<double, 4> beta{};   // s, s/semicircle, s/semicircle^2, s/semicircle^3
};

struct NavData {
  double rinex_version = 0.0;
  std::vector<GpsEphemeris> gps;  // every record, file order (several may share an IODE)
  std::optional<KlobucharCoefficients> klobuchar;
  std::optional<int> leap_seconds;  // GPS - UTC from the header, if given
  int skipped_records = 0;          // records of other systems (parsed past, not used)
  std::string source;               // file name
  // Navigation data that never run out: the built-in constellation's satellites get a new data
  // set every 2 h for ever, as the GPS control segment uploads them (models/constellation.hpp).
  // `gps` holds the sets around one time (edited or not); a user running past them continues
  // each satellite's latest set with reuploaded() (models/orbit.hpp), as
  // models/measurement.cpp does. False for a file, whose records are all there are.
  bool renews = false;
};

// The spacing of the built-in constellation's uploads: regular GPS data sets are each sent for
// 2 h (IS-GPS-200 20.3.4.4), their toes on even GPS hours, as in real broadcast files.
inline constexpr double kUploadInterval_s = 7200.0;

// How far from its toe a broadcast ephemeris is still used: twice the half-width of the
// nominal 4 h curve-fit interval (IS-GPS-200 20.3.4.4), lenient for sparse files.
inline constexpr double kMaxEphemerisAge_s = 4.0 * 3600.0;

// The ephemeris to use for `prn` at time `t`: among healthy records, the one whose toe is
// nearest to t (IS-GPS-200 20.3.4.5 curve fit interval centred on toe); when t precedes every
// toe, the first one. Ties go to the later transmitted record. nullptr when the file has none.
const GpsEphemeris* select_ephemeris(const NavData& nav, int prn, GpsTime t);
// The same among one PRN's records, indexed once (nav.gps scanned per satellite and epoch
// would cost as much as the orbit).
const GpsEphemeris* select_ephemeris(std::span<const GpsEphemeris* const> records_of_one_prn,
                                     GpsTime t);

// The record select_ephemeris gives at a time, with the open span of times around it over which
// it gives the same record: the choice changes only where t passes midway between the toe of
// the chosen record and another healthy one's (records sharing the chosen toe tie at every t
// and are decided by their transmission times alone). Bounds in doubled nanoseconds, since
// midpoints may fall on half a nanosecond.
struct EphemerisSelection {
  const GpsEphemeris* eph = nullptr;
  std::int64_t after_2ns = 0;   // exclusive: 2 t.ns must exceed it
  std::int64_t before_2ns = 0;  // exclusive: 2 t.ns must stay below it
  bool covers(GpsTime t) const { return after_2ns < 2 * t.ns && 2 * t.ns < before_2ns; }
};
EphemerisSelection select_ephemeris_span(std::span<const GpsEphemeris* const> records_of_one_prn,
                                         GpsTime t);

// A closed span of GPS time.
struct TimeSpan {
  GpsTime from, to;
  bool contains(GpsTime t) const { return from <= t && t <= to; }
};

// Satellites a fix needs: three coordinates and the receiver clock offset are four unknowns, so
// with fewer than four satellites' data no receiver anywhere can solve for its position.
inline constexpr int kSatellitesForFix = 4;

// The curve-fit interval of a record, over which its orbit and clock fit is specified. It starts
// when the set's transmission starts (IS-GPS-200 20.3.4.4) and a regular set is transmitted for
// the 2 h before its toe, so its 4 h fit interval (fit interval flag 0, 20.3.3.4.3.1) is
// toe +- 2 h; longer fits (flag 1, Table 20-XII) are taken centred on toe alike, as RTKLIB's
// MAXDTOE check does. The fit interval is never shorter than 4 h: a RINEX file that holds the
// flag (0 or 1) in its hours field counts as 4 h.
TimeSpan fit_interval(const GpsEphemeris& e);

// The spans of time over which `nav` has data for a fix: at least `min_satellites` PRNs each
// with a healthy record (SV health 0) inside its fit interval. Sorted and disjoint; empty when
// never. Data that renew (NavData::renews) cover all time: one span from the earliest to the
// latest representable GpsTime.
std::vector<TimeSpan> covered_spans(const NavData& nav, int min_satellites = kSatellitesForFix);

}  // namespace navemu
