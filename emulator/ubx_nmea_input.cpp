// The NMEA input of a u-blox receiver port (UbxDevice::receive_nmea): what the part does with
// the sentences protocols/pubx.hpp reads out of the host's bytes.
//
// Sources: u-blox 8 / u-blox M8 Receiver description (UBX-13003221), "PUBX Messages": RATE
// (PUBX,40) "Set NMEA message output rate" on each port like UBX-CFG-MSG; CONFIG (PUBX,41)
// "Set protocols and baudrate" of a port like UBX-CFG-PRT; POSITION (PUBX,00), SVSTATUS
// (PUBX,03) and TIME (PUBX,04) polled by the sentence without data fields; and "Standard
// Messages" GPQ/GNQ/GLQ/GBQ "Polls a standard NMEA message if the current Talker ID is ..";
// the F9 interface descriptions (UBX-18010854 4.2 and UBX-21023318 2.7) say the same of the
// standard polls and the PUBX polls. The part reads NMEA input only on a port whose input
// protocols include NMEA (CFG-PRT inProtoMask, CFG-<port>INPROT-NMEA).
//
// NMEA input is never acknowledged (it has no ACK), so a PUBX,41 baud change applies at once
// after the sentence, through the same pending change as CFG-PRT's (after its ACK there). A
// poll is answered on the port it came from with the sentence of the latest epoch. Malformed
// sentences and ones the part does not take get no reply, but for other makers' proprietary
// sentences, which get an "inv format" warning (INF, see receive_nmea); all are counted
// (UbxDeviceCounters::nmea_ignored).

#include <algorithm>
#include <cmath>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "emulator/ubx_device.hpp"

namespace navemu {

namespace {

using namespace ubx;

// The standard NMEA messages a rate can be set for, by their UBX-CFG-MSG ID in class 0xF0
// (UBX-13003221 "NMEA Messages Overview"; RLM: F9 HPG 1.13 UBX-21023318 "NMEA-Standard-RLM").
constexpr std::pair<std::string_view, std::uint8_t> kStandardMessages[] = {
    {"GGA", 0x00}, {"GLL", 0x01}, {"GSA", 0x02}, {"GSV", 0x03}, {"RMC", 0x04},
    {"VTG", 0x05}, {"GRS", 0x06}, {"GST", 0x07}, {"ZDA", 0x08}, {"GBS", 0x09},
    {"DTM", 0x0A}, {"RLM", 0x0B}, {"GNS", 0x0D}, {"THS", 0x0E}, {"VLW", 0x0F},
    {"TXT", 0x41}};

std::optional<MsgId> standard_message(pubx::Formatter f) {
  for (const auto& [name, id] : kStandardMessages)
    if (name == f.view()) return MsgId{kClassNmea, id};
  return std::nullopt;
}

nmea::Format format_of(const GnssProfile& p) {
  nmea::Format f = nmea::Format::ublox();
  if (p.time_decimals) f.time_decimals = *p.time_decimals;
  return f;
}

nmea::UtcTime utc_of(GpsTime t, const NavData& nav) {
  const CalendarTime c = utc_from_gps(t, nav.leap_seconds);
  return {c.year, c.month, c.day, c.hour, c.minute, c.second};
}

// PUBX,00 of a fix. Without a fix the part sends zeros, NF and large accuracies and DOPs of
// 99.99 (protocols/pubx.hpp); the accuracies are NAV-PVT's (emulator/ubx_outputs.cpp).
pubx::PositionFields position_fields(const ReceiverFix& fix, ReceiverMode mode, const NavData& nav) {
  pubx::PositionFields f;
  f.utc = utc_of(fix.t, nav);
  const bool valid = fix.fix != FixType::kNone;
  const Vec3 v = fix.v_ned_mps.value_or(Vec3::Zero());
  f.position = valid ? nmea::LatLon{fix.position.lat_deg, fix.position.lon_deg} : nmea::LatLon{0.0, 0.0};
  f.height_user_datum_m = valid ? fix.position.h_m : 0.0;
  const bool diff = mode != ReceiverMode::kStandalone && mode != ReceiverMode::kDualFrequency;
  f.nav_status = !valid                   ? pubx::NavStatus::kNoFix
                 : fix.fix == FixType::k2D ? (diff ? pubx::NavStatus::kDifferential2D : pubx::NavStatus::kStandalone2D)
                                           : (diff ? pubx::NavStatus::kDifferential3D : pubx::NavStatus::kStandalone3D);
  f.h_acc_m = valid ? fix.sigma_h_m : 9999.0;
  f.v_acc_m = valid ? fix.sigma_v_m : 9999.0;
  f.speed_mps = std::hypot(v.x(), v.y());
  const double course = std::atan2(v.y(), v.x()) * kRadToDeg;
  f.course_deg = course < 0.0 ? course + 360.0 : course;
  f.velocity_down_mps = v.z();
  f.hdop = valid ? fix.dops.hdop : 99.99;
  f.vdop = valid ? fix.dops.vdop : 99.99;
  f.tdop = valid ? fix.dops.tdop : 99.99;
  f.num_svs = fix.num_used;
  return f;
}

// PUBX,03's satellites (NMEA numbering with the extended ranges: the sentence has no system
// field), the carrier lock time from the L1 measurement.
void sv_status(const ReceiverFix& fix, const EpochMeasurements& meas, std::vector<pubx::SvStatus>& out) {
  out.clear();
  for (const ReceiverSatellite& s : fix.satellites) {
    const std::optional<int> id = s.sat.nmea_id(NmeaNumbering::kV410Extended);
    if (!id) continue;
    pubx::SvStatus sv;
    sv.sv_id = *id;
    sv.use = s.used ? pubx::SvUse::kUsed : pubx::SvUse::kNotUsed;
    sv.azimuth_deg = static_cast<int>(std::lround(s.az_deg));
    sv.elevation_deg = static_cast<int>(std::lround(s.el_deg));
    sv.cno_dbhz = static_cast<int>(std::lround(s.cn0_dbhz));
    const auto m = std::find_if(meas.sats.begin(), meas.sats.end(), [&](const SatMeasurement& x) { return x.sat == s.sat; });
    if (m != meas.sats.end() && m->signals[0]) sv.carrier_lock_s = m->signals[0]->lock_time_s;
    out.push_back(sv);
  }
}

// PUBX,04: UTC time of week and week (GPS week numbering, shifted by the leap seconds), the
// receiver clock (NAV-CLOCK's). The leap seconds are known (NAV-TIMEGPS says them valid).
pubx::TimeFields time_fields(const ReceiverFix& fix, const EpochMeasurements& meas, const NavData& nav) {
  pubx::TimeFields f;
  f.utc = utc_of(fix.t, nav);
  const int leap_s = leap_seconds_at_gps(fix.t, nav.leap_seconds);
  const WeekTow utc = to_week_tow(fix.t.plus_s(-leap_s));
  f.utc_tow_s = utc.tow_s;
  f.utc_week = utc.week;
  f.leap_seconds = leap_s;
  f.clock_bias_s = meas.rx_clock_bias_s;
  f.clock_drift_s_per_s = meas.rx_clock_drift_sps;
  return f;
}

}  // namespace

void UbxDevice::receive_nmea(std::string_view sentence, std::uint8_t port, Bytes& out) {
  const pubx::Parsed parsed = pubx::parse_input(sentence);
  std::string reply;
  bool taken = false;
  if (parsed.command && ports_[port].in_nmea) {
    const pubx::Command& c = *parsed.command;
    if (const auto* r = std::get_if<pubx::SetRate>(&c)) {
      if (const std::optional<MsgId> id = standard_message(r->msg_id)) {
        for (std::uint8_t q = 0; q < pubx::kPortCount; ++q)
          if (r->rate[q]) set_rate(*id, q, *r->rate[q]);
        taken = true;
      }
    } else if (const auto* p = std::get_if<pubx::SetPort>(&c)) {
      std::vector<CfgKeyValue> values;
      port_values(static_cast<std::uint8_t>(p->port), p->in_proto, p->out_proto, p->baud_rate, values);
      taken = config_.set_ram(values);
    } else if (const auto* q = std::get_if<pubx::PollPubx>(&c)) {
      taken = true;
      if (q->msg_id == 0) {
        pubx::encode(position_fields(last_fix_, mode_, nav_), format_of(profile_), reply);
      } else if (q->msg_id == 3) {
        std::vector<pubx::SvStatus> svs;
        sv_status(last_fix_, last_meas_, svs);
        pubx::encode(pubx::SvStatusFields{svs}, reply);
      } else {
        pubx::encode(time_fields(last_fix_, last_meas_, nav_), format_of(profile_), reply);
      }
    } else if (const auto* s = std::get_if<pubx::PollStandard>(&c); s && s->listener.view() == talker_) {
      // The sentence as the port's output would have it, whatever its rate.
      GnssProfile one = profile_;
      one.talker = talker_;
      one.sentences = {{std::string(s->msg_id.view()), 1}};
      NmeaOutput(one, mode_, nmea_version_).encode(last_fix_, 0, reply);
      taken = !reply.empty();  // a message the device does not send
    }
  } else if (parsed.reason == pubx::Reason::kNotInput && ports_[port].in_nmea && sentence.size() > 5 &&
             sentence[1] == 'P' && !sentence.starts_with("$PUBX")) {
    // Another maker's proprietary sentence (gpsd probes with $PMTK605, $PASHQ,RID ...): a
    // warning "<first four characters of the address> inv format", as the u-blox 8 parts of
    // ../shared/data/receiver_logs/gpsd answer ($GNTXT,01,01,01,PMTK inv format*20).
    const std::string text = std::string(sentence.substr(1, 4)) + " inv format";
    Bytes warning;
    inform(port, 1, text, warning);
    reply.assign(warning.begin(), warning.end());
  }
  ++(taken ? counters_.nmea_commands : counters_.nmea_ignored);
  if (taken && !reply.empty()) ++counters_.polls;
  out.insert(out.end(), reply.begin(), reply.end());
  refresh();
}

}  // namespace navemu
