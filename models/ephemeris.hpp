#pragma once
// Choosing among broadcast ephemeris records (core/nav_data.hpp): which record holds for a
// satellite at a time, their fit intervals, and when a set of records supports a fix.

#include <cstdint>
#include <span>
#include <variant>
#include <vector>

#include "core/nav_data.hpp"
#include "core/satellite.hpp"
#include "core/time.hpp"

namespace navemu {

// The spacing of the built-in constellation's uploads: regular GPS data sets are each sent for
// 2 h (IS-GPS-200 20.3.4.4), their toes on even GPS hours, as in real broadcast files.
inline constexpr double kUploadInterval_s = 7200.0;
// GLONASS immediate data: a state vector every 30 min, tb at 15 and 45 min past the hour
// (GLONASS ICD 5.1, 4.4: P1 = 30 min).
inline constexpr double kGlonassUploadInterval_s = 1800.0;

// How far from its toe a broadcast ephemeris is still used: twice the half-width of the
// nominal 4 h curve-fit interval (IS-GPS-200 20.3.4.4), lenient for sparse files.
inline constexpr double kMaxEphemerisAge_s = 4.0 * 3600.0;

// The ephemeris to use for satellite `sat` at time `t`: among healthy records, the one whose toe
// is nearest to t (IS-GPS-200 20.3.4.5 curve fit interval centred on toe); when t precedes
// every toe, the first one. Ties go to the later transmitted record. nullptr when the file has
// none. GPS records from NavData::gps, QZSS's from NavData::qzss.
const GpsEphemeris* select_ephemeris(const NavData& nav, SatId sat, GpsTime t);
// The same among one satellite's records, indexed once (nav.gps scanned per satellite and epoch
// would cost as much as the orbit).
const GpsEphemeris* select_ephemeris(std::span<const GpsEphemeris* const> records_of_one_sat,
                                     GpsTime t);

// The records of the other systems a single-frequency user takes at time t, nullptr when there
// is none (each rule as RTKLIB 2.4.3's seleph applies it, so that `navemu spp` and rnx2rtkp use
// the same data):
// - Galileo: a record whose toe is not after t (Galileo OS SIS ICD 2.0 5.1.9: data are valid
//   from toe on), the nearest such, at most kMaxEphemerisAge_s old; I/NAV (data sources bit 9,
//   the clock for E1/E5b, what an E1 user decodes) preferred to F/NAV; the E1-B signal health
//   and data validity (health bits 0-2, OS SIS ICD 2.0 5.1.9.3) must be zero.
// - BeiDou: the healthy record (SatH1 = 0, BDS-SIS-ICD-B1I 3.0 5.2.4.6) nearest in toe, within
//   kMaxEphemerisAge_s.
// - GLONASS: the healthy record (Bn = 0, GLONASS ICD 5.1 4.4) nearest in tb, within 15 min: the
//   immediate data are updated every 30 min (ICD 4.4, tb).
// - QZSS: as GPS, from NavData::qzss (select_ephemeris).
const GalileoEphemeris* select_galileo_ephemeris(const NavData& nav, SatId sat, GpsTime t);
const BeidouEphemeris* select_beidou_ephemeris(const NavData& nav, SatId sat, GpsTime t);
const GlonassEphemeris* select_glonass_ephemeris(const NavData& nav, SatId sat, GpsTime t);
inline constexpr double kMaxGlonassAge_s = 15.0 * 60.0;
// The same among one satellite's records, indexed once (the receiver model's form: no
// allocation, no scan of the other satellites' records).
const GalileoEphemeris* select_galileo_ephemeris(std::span<const GalileoEphemeris* const> records_of_one_sat,
                                                 GpsTime t);
const BeidouEphemeris* select_beidou_ephemeris(std::span<const BeidouEphemeris* const> records_of_one_sat,
                                               GpsTime t);
const GlonassEphemeris* select_glonass_ephemeris(std::span<const GlonassEphemeris* const> records_of_one_sat,
                                                 GpsTime t);

// A broadcast record of any system (GPS and QZSS LNAV records are GpsEphemeris); the
// monostate when there is none.
using BroadcastRecord = std::variant<std::monostate, const GpsEphemeris*, const GalileoEphemeris*,
                                     const BeidouEphemeris*, const GlonassEphemeris*>;
// A record's reference time: toe, or tb for GLONASS.
inline GpsTime reference_time(const KeplerEphemeris& e) { return e.toe; }
inline GpsTime reference_time(const GlonassEphemeris& e) { return e.tb; }
GpsTime reference_time(const BroadcastRecord& r);
// The record a single-frequency user takes for a satellite of any system at t: GPS and QZSS by
// select_ephemeris within kMaxEphemerisAge_s, the others by their rules above; the monostate
// when there is none.
BroadcastRecord select_record(const NavData& nav, SatId sat, GpsTime t);

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
EphemerisSelection select_ephemeris_span(std::span<const GpsEphemeris* const> records_of_one_sat,
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

// The spans of time over which `nav` has data for a fix: at least `min_satellites` satellites
// each with a healthy record (SV health 0) inside its fit interval. Sorted and disjoint; empty
// when never. Data that renew (NavData::renews) cover all time: one span from the earliest to
// the latest representable GpsTime.
std::vector<TimeSpan> covered_spans(const NavData& nav, int min_satellites = kSatellitesForFix);

}  // namespace navemu
