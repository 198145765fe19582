#include "emulator/nmea_output.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "models/geodesy.hpp"
#include "models/reuse.hpp"

namespace navemu {

namespace {
// Systems in the order of their NMEA system IDs (GSA and GSV groups are sent in it).
constexpr std::array<GnssSystem, 5> kNmeaSystemOrder{GnssSystem::kGps, GnssSystem::kGlonass,
                                                     GnssSystem::kGalileo, GnssSystem::kBeidou,
                                                     GnssSystem::kQzss};
// The GSA a satellite is listed in: SBAS with GPS (NMEA system ID 1).
GnssSystem gsa_system(GnssSystem s) { return s == GnssSystem::kSbas ? GnssSystem::kGps : s; }
}  // namespace

// The GSV group a satellite is listed in: SBAS with GPS, QZSS too with the NMEA 4.10 numbering.
GnssSystem NmeaOutput::gsv_system(GnssSystem s) const {
  if (s == GnssSystem::kSbas || (s == GnssSystem::kQzss && numbering_ != NmeaNumbering::kV411))
    return GnssSystem::kGps;
  return s;
}

NmeaOutput::NmeaOutput(const GnssProfile& profile, ReceiverMode mode, std::optional<int> nmea_version,
                       bool high_precision)
    : profile_(profile),
      format_(profile.style == "garmin" ? nmea::Format::garmin() : nmea::Format::ublox()) {
  // GGA quality and the mode indicator by receiver mode (NMEA 0183 4.10, GGA and RMC).
  switch (mode) {
    case ReceiverMode::kStandalone:
    case ReceiverMode::kDualFrequency: quality_ = 1; mode_ = 'A'; break;
    case ReceiverMode::kDgps: quality_ = 2; mode_ = 'D'; break;
    case ReceiverMode::kRtkFixed: quality_ = 4; mode_ = 'R'; break;
  }
  if (profile.time_decimals) format_.time_decimals = *profile.time_decimals;
  // The fields each version has (u-blox 8 receiver description UBX-13003221, "NMEA protocol
  // configuration"): the mode indicator from 2.3 on; the navigational status of RMC and the
  // system and signal IDs of GSA and GSV from 4.10 on.
  if (nmea_version) {
    format_.mode_indicator = *nmea_version >= 23;
    format_.nav_status = format_.system_signal_ids = *nmea_version >= 41;
  }
  format_.high_precision = high_precision;
  numbering_ = format_.system_signal_ids ? NmeaNumbering::kV411 : NmeaNumbering::kV410Extended;
  gsv_.reserve(64);
  gsa_.sat_ids.reserve(64);
}

void NmeaOutput::encode(const ReceiverFix& fix, std::int64_t epoch_index, std::string& out) {
  const CalendarTime c = utc_from_gps(fix.t);
  const nmea::UtcTime utc{c.year, c.month, c.day, c.hour, c.minute, c.second};
  const bool valid = fix.fix != FixType::kNone;
  std::optional<nmea::LatLon> pos;
  std::optional<double> alt_msl_m, separation_m, speed_mps, course_deg;
  if (valid) {
    pos = nmea::LatLon{fix.position.lat_deg, fix.position.lon_deg};
    // Height above the geoid and the geoid's separation, so that a client adding them gets
    // the ellipsoidal height back (0 separation when the receiver has no geoid model).
    separation_m = fix.geoid_separation_m;
    alt_msl_m = fix.position.h_m - *separation_m;
    if (fix.v_ned_mps) {
      const Vec3& v = *fix.v_ned_mps;
      speed_mps = std::hypot(v.x(), v.y());
      double course = std::atan2(v.y(), v.x()) * kRadToDeg;
      if (course < 0.0) course += 360.0;
      course_deg = course;
    }
  }
  const char mode = valid ? mode_ : 'N';
  const std::string_view talker = profile_.talker;

  for (const auto& [name, divisor] : profile_.sentences) {
    if (epoch_index % divisor != 0) continue;
    if (name == "RMC") {
      nmea::encode(nmea::RmcFields{talker, utc, valid, pos, speed_mps, course_deg, {}, mode,
                                   'V'},  // u-blox sends V (no navigational status) always
                   format_, out);
    } else if (name == "GGA") {
      nmea::GgaFields f;
      f.talker = talker;
      f.utc = utc;
      f.position = pos;
      f.quality = valid ? quality_ : 0;
      f.num_sats = std::min(fix.num_used, 12);  // "00-12" (NMEA 0183 4.10 GGA; u-blox alike)
      if (valid) f.hdop = fix.dops.hdop;
      f.alt_msl_m = alt_msl_m;
      f.geoid_separation_m = separation_m;
      nmea::encode(f, format_, out);
    } else if (name == "GSA") {
      // One GSA per system tracked, each with its used satellites and, from NMEA 4.10 on, its
      // system ID (NMEA 0183 4.10 GSA; u-blox sends one per enabled GNSS); SBAS counts as GPS.
      for (const GnssSystem system : kNmeaSystemOrder) {
        if (!(profile_.systems & system_bit(system))) continue;
        nmea::GsaFields& f = reset_keeping_storage(gsa_, &nmea::GsaFields::sat_ids);
        for (const ReceiverSatellite& s : fix.satellites)
          if (const std::optional<int> id = s.sat.nmea_id(numbering_);
              s.used && id && gsa_system(s.sat.system()) == system)
            f.sat_ids.push_back(*id);
        f.talker = talker;
        f.system_id = system_info(system).nmea_system_id;
        f.fix = fix.fix == FixType::k3D ? 3 : fix.fix == FixType::k2D ? 2 : 1;
        if (valid) {
          f.pdop = fix.dops.pdop;
          f.hdop = fix.dops.hdop;
          f.vdop = fix.dops.vdop;
        }
        nmea::encode(f, format_, out);
      }
    } else if (name == "GSV") {
      // One GSV group per system tracked, under the system's talker (u-blox CFG-NMEA
      // gsvTalkerId 0, its default) and with its L1 signal's ID (NMEA 0183 4.11); with the NMEA
      // 4.10 numbering QZSS goes with GPS, whose IDs 193-202 it has there. Where the sentences
      // carry signal IDs, each further band of the profile has its own group after it, of the
      // satellites tracked on it (as a ZED-F9T sends its L1 and L5 groups per system,
      // receiver_logs/gpsd/ublox-zed-f9t-ubx_nmea_l5.log).
      for (const GnssSystem system : kNmeaSystemOrder) {
        if (!(profile_.systems & system_bit(system)) || gsv_system(system) != system) continue;
        for (const Band band : {Band::kL1, Band::kL2, Band::kL5}) {
          const std::optional<BandSignal> signal = band_signal(system, band);
          const SignalInfo* info = signal ? signal_info(signal->id) : nullptr;
          const std::size_t b = static_cast<std::size_t>(band);
          if (band != Band::kL1 && (!(profile_.bands & band_bit(band)) || !format_.system_signal_ids ||
                                    info == nullptr || info->nmea_signal_id == 0))
            continue;
          gsv_.clear();
          for (const ReceiverSatellite& s : fix.satellites) {
            if (gsv_system(s.sat.system()) != system || (band != Band::kL1 && s.band_cn0_dbhz[b] <= 0.0)) continue;
            if (const std::optional<int> id = s.sat.nmea_id(numbering_))
              gsv_.push_back({*id, static_cast<int>(std::lround(std::max(s.el_deg, 0.0))),
                              static_cast<int>(std::lround(s.az_deg)) % 360,
                              static_cast<int>(std::lround(band == Band::kL1 ? s.cn0_dbhz : s.band_cn0_dbhz[b]))});
          }
          if (band != Band::kL1 && gsv_.empty()) continue;
          nmea::GsvFields f{nmea::system_talker(system), gsv_};
          f.signal_id = info ? info->nmea_signal_id : 1;
          nmea::encode(f, format_, out);
        }
      }
    } else if (name == "VTG") {
      nmea::encode(nmea::VtgFields{talker, course_deg, {}, speed_mps, mode}, format_, out);
    } else if (name == "GLL") {
      nmea::encode(nmea::GllFields{talker, pos, utc, valid, mode}, format_, out);
    } else if (name == "GST") {
      nmea::GstFields f;
      f.talker = talker;
      f.utc = utc;
      if (valid) {
        // The error ellipse is given by its north and east axes (the covariance's
        // north-east correlation is not carried).
        f.range_rms_m = fix.range_rms_m;
        f.major_m = std::max(fix.sigma_n_m, fix.sigma_e_m);
        f.minor_m = std::min(fix.sigma_n_m, fix.sigma_e_m);
        f.orientation_deg = fix.sigma_n_m >= fix.sigma_e_m ? 0.0 : 90.0;
        f.lat_sigma_m = fix.sigma_n_m;
        f.lon_sigma_m = fix.sigma_e_m;
        f.alt_sigma_m = fix.sigma_v_m;
      }
      nmea::encode(f, format_, out);
    } else if (name == "ZDA") {
      nmea::encode(nmea::ZdaFields{talker, utc, 0, 0}, format_, out);
    } else if (name == "PGRME") {
      // Garmin's estimated position errors, taken as 2-sigma (95 %) figures.
      nmea::PgrmeFields f;
      if (valid) {
        f.hpe_m = 2.0 * fix.sigma_h_m;
        f.vpe_m = 2.0 * fix.sigma_v_m;
        f.epe_m = 2.0 * std::hypot(fix.sigma_h_m, fix.sigma_v_m);
      }
      nmea::encode(f, format_, out);
    }
  }
}

}  // namespace navemu
