#pragma once
// Broadcast navigation data as records per system: what a navigation file or message carries,
// before any orbit is computed from it (models/orbit.hpp). GPS, QZSS, Galileo and BeiDou
// Kepler records are read (the receiver model uses GPS's); GLONASS, SBAS and NavIC records
// are parsed past (NavData::skipped_records).
//
// Times are GPS time (GpsTime): readers convert Galileo System Time (aligned to GPS time) and
// BeiDou Time (GPS time - 14 s) when they read such records.

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/satellite.hpp"
#include "core/time.hpp"
#include "core/vec.hpp"

namespace navemu {

// The clock polynomial and Keplerian orbit every CDMA system broadcasts in the GPS form:
// IS-GPS-200 Tables 20-I and 20-III (GPS LNAV; QZSS LNAV has the same layout, IS-QZSS-PNT),
// Galileo OS SIS ICD issue 2.0 section 5.1 and BDS-SIS-ICD-B1I 3.0 section 5.2. Angles in
// radians (RINEX stores them in radians already).
struct KeplerEphemeris {
  SatId sat;
  GpsTime toc;  // clock data reference time
  double af0_s = 0.0, af1_sps = 0.0, af2_sps2 = 0.0;

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

  // Where the record came from, for messages ("file.05n:123").
  std::string source;
};

// One GPS (or QZSS) LNAV ephemeris set, fields named and scaled as in IS-GPS-200 Table 20-III.
struct GpsEphemeris : KeplerEphemeris {
  int iode = 0;
  int codes_on_l2 = 0;
  int l2p_data_flag = 0;
  double ura_m = 0.0;
  int health = 0;
  double tgd_s = 0.0;
  int iodc = 0;
  double transmission_tow_s = 0.0;  // RINEX "transmission time of message"
  double fit_interval_h = 4.0;
};

// Galileo I/NAV or F/NAV ephemeris (Galileo OS SIS ICD issue 2.0 section 5.1; RINEX 3.05
// Galileo navigation data record).
struct GalileoEphemeris : KeplerEphemeris {
  int iod_nav = 0;
  int data_sources = 0;  // RINEX "data sources" bits: I/NAV E1-B, F/NAV E5a-I, ...
  double sisa_m = 0.0;
  int health = 0;        // RINEX "SV health" bits (E1-B, E5a, E5b signal and data validity)
  double bgd_e1e5a_s = 0.0;
  double bgd_e1e5b_s = 0.0;
  double transmission_tow_s = 0.0;

  // RINEX 3.05 data sources bit 9: the clock is for the E5b/E1 pair (I/NAV), else E5a/E1 (F/NAV).
  bool inav_clock() const { return (data_sources & (1 << 9)) != 0; }
  // The group delay an E1 user removes with this record's clock: BGD of its pair (OS SIS ICD
  // 2.0 5.1.5).
  double bgd_e1_s() const { return inav_clock() ? bgd_e1e5b_s : bgd_e1e5a_s; }
};

// BeiDou D1/D2 ephemeris (BDS-SIS-ICD-B1I 3.0 section 5.2; RINEX 3.05 BDS navigation data
// record).
struct BeidouEphemeris : KeplerEphemeris {
  int aode = 0;
  int aodc = 0;
  double ura_m = 0.0;
  int health = 0;  // SatH1
  double tgd1_s = 0.0;  // B1I
  double tgd2_s = 0.0;  // B2I
  double transmission_tow_s = 0.0;
};

// A GLONASS immediate-data record: the satellite's state vector in PZ-90 at tb, integrated by
// the user (GLONASS ICD edition 5.1, 4.4 and A.3.1.2; RINEX 3.05 GLONASS navigation data
// record).
struct GlonassEphemeris {
  SatId sat;
  GpsTime tb;  // reference time of the state vector
  double tau_n_s = 0.0;    // satellite clock offset from GLONASS time (the ICD's tau_n)
  double gamma_n = 0.0;    // relative frequency offset
  double frame_time_s = 0.0;  // message frame time, s of the UTC(SU) week
  Vec3 p_pz90_m = Vec3::Zero();
  Vec3 v_pz90_mps = Vec3::Zero();
  Vec3 a_pz90_mps2 = Vec3::Zero();  // lunisolar acceleration
  int health = 0;
  int frequency_channel = 0;  // k, -7..+6 (core/signal.hpp)
  double age_days = 0.0;       // age of operational information
  std::string source;
};

// Klobuchar broadcast ionosphere coefficients (IS-GPS-200 20.3.3.5.1.7, 20.3.3.5.2.5).
struct KlobucharCoefficients {
  std::array<double, 4> alpha{};  // s, s/semicircle, s/semicircle^2, s/semicircle^3
  std::array<double, 4> beta{};   // s, s/semicircle, s/semicircle^2, s/semicircle^3
};

// A broadcast offset between two time scales (RINEX 3.05 navigation header TIME SYSTEM CORR;
// RINEX 4.00 "> STO" record): offset(t) = a0 + a1 (t - t_ref) + a2 (t - t_ref)^2, seconds.
// `type` names the pair as RINEX does, the first scale minus the second: GAGP = GST - GPST
// (the Galileo GGTO, OS SIS ICD 2.0 5.1.8), GPUT = GPST - UTC(USNO), GAUT = GST - UTC,
// BDUT = BDT - UTC, QZGP = QZSST - GPST, GLUT = GLONASST - UTC(SU) (= -tau_c), leap seconds
// excluded throughout; GLGP relates GLONASS time to GPS time (its sign convention is not
// established here: read, not used).
struct TimeSystemOffset {
  std::string type;  // four letters, e.g. "GAGP"
  double a0_s = 0.0, a1_sps = 0.0, a2_sps2 = 0.0;
  GpsTime t_ref;       // reference time of the polynomial, as GPS time
  std::string source;  // "file.rnx:7"

  double at_s(GpsTime t) const {
    const double dt_s = seconds_between(t, t_ref);
    return a0_s + (a1_sps + a2_sps2 * dt_s) * dt_s;
  }
};

struct NavData {
  double rinex_version = 0.0;
  // The records per system, every one in file order (several may share an issue of data).
  std::vector<GpsEphemeris> gps;
  std::vector<GpsEphemeris> qzss;
  std::vector<GalileoEphemeris> galileo;
  std::vector<BeidouEphemeris> beidou;
  std::vector<GlonassEphemeris> glonass;
  std::optional<KlobucharCoefficients> klobuchar;
  // Galileo NeQuick G effective ionisation level coefficients ai0 (sfu), ai1 (sfu/deg), ai2
  // (sfu/deg^2) (Galileo OS SIS ICD 2.0 5.1.6; RINEX 3.05 IONOSPHERIC CORR "GAL").
  std::optional<std::array<double, 3>> nequick_g;
  std::optional<int> leap_seconds;  // GPS - UTC from the header, if given
  // System time offsets in file order (a type may recur with newer reference times).
  std::vector<TimeSystemOffset> time_offsets;
  // The offset of `type` that applies at t: the latest reference time not after t, else the
  // earliest one given; null when the file has none of that type.
  const TimeSystemOffset* time_offset(std::string_view type, GpsTime t) const {
    const TimeSystemOffset* best = nullptr;
    for (const TimeSystemOffset& o : time_offsets) {
      if (o.type != type) continue;
      const bool applies = o.t_ref <= t, best_applies = best != nullptr && best->t_ref <= t;
      if (best == nullptr || (applies && (!best_applies || o.t_ref > best->t_ref)) ||
          (!applies && !best_applies && o.t_ref < best->t_ref))
        best = &o;
    }
    return best;
  }
  // That offset's value at t, seconds; 0 when the file has none of that type.
  double time_offset_s(std::string_view type, GpsTime t) const {
    const TimeSystemOffset* o = time_offset(type, t);
    return o != nullptr ? o->at_s(t) : 0.0;
  }
  int skipped_records = 0;          // records of the systems not read (parsed past)
  std::string source;               // file name
  // Navigation data that never run out: the built-in constellation's satellites get a new data
  // set every 2 h for ever, as the GPS control segment uploads them (models/constellation.hpp).
  // `gps` holds the sets around one time (edited or not); a user running past them continues
  // each satellite's latest set with reuploaded() (models/orbit.hpp), as
  // models/measurement.cpp does. False for a file, whose records are all there are.
  bool renews = false;
};

}  // namespace navemu
