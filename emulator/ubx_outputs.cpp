#include "emulator/ubx_outputs.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

#include "core/sat_table.hpp"
#include "core/signal.hpp"
#include "models/geodesy.hpp"
#include "models/reuse.hpp"
#include "protocols/beidou_nav.hpp"
#include "protocols/galileo_inav.hpp"
#include "protocols/glonass_nav.hpp"
#include "protocols/gps_lnav.hpp"

namespace navemu {

using namespace ubx;

namespace {

constexpr double kMaxLockTime_ms = 64500.0;  // RXM-RAWX locktime saturates here

template <typename T>
T clamp_cast(double v) {
  const double lo = static_cast<double>(std::numeric_limits<T>::lowest());
  const double hi = static_cast<double>(std::numeric_limits<T>::max());
  return static_cast<T>(std::clamp(std::round(v), lo, hi));
}

std::uint8_t fix_type(FixType f) {
  switch (f) {
    case FixType::kNone: return kFixNone;
    case FixType::kDeadReckoning: return kFixDeadReckoning;
    case FixType::k2D: return kFix2d;
    case FixType::k3D: return kFix3d;
  }
  return kFixNone;
}

// Accuracy estimates of the receiver (1-sigma), wire units.
struct Accuracy {
  double h_m, v_m, p_m, s_mps;
  double cross_track_mps;  // the horizontal velocity's 1-sigma across the track (heading)
};
Accuracy accuracy(const ReceiverFix& fix) {
  if (fix.fix == FixType::kNone) return {9999.0, 9999.0, 9999.0, 20.0, 20.0};
  const double p = std::hypot(fix.sigma_h_m, fix.sigma_v_m);
  // The velocity's own 1-sigma when the receiver has its covariance (across the track: one of
  // the two axes of the horizontal one); otherwise (the ideal receiver, a stationary platform's
  // held velocity) about 5 cm/s of range-rate noise times the PDOP.
  if (fix.sigma_speed_mps > 0.0)
    return {fix.sigma_h_m, fix.sigma_v_m, p, fix.sigma_speed_mps, fix.sigma_h_speed_mps / std::sqrt(2.0)};
  const double s = 0.05 * std::max(fix.dops.pdop, 1.0);
  return {fix.sigma_h_m, fix.sigma_v_m, p, s, s};
}

}  // namespace

bool within_output_filters(const ReceiverFix& fix, ReceiverMode mode, const UbxDeviceStatus& status) {
  if (fix.fix == FixType::kNone) return false;
  if (mode == ReceiverMode::kRtkFixed) return true;
  return fix.dops.pdop <= status.outfil_pdop && accuracy(fix).p_m <= status.outfil_pacc_m;
}

lnav::LnavEphemeris to_lnav(const GpsEphemeris& e) {
  lnav::LnavEphemeris l;
  l.sv_id = e.sat.number();
  l.week = to_week_tow(e.toe).week;
  l.codes_on_l2 = e.codes_on_l2 ? e.codes_on_l2 : 1;
  l.ura_index = lnav::lnav_ura_index(e.ura_m);
  l.health = e.health;
  // IODE must equal the 8 LSBs of IODC (IS-GPS-200 20.3.4.4).
  l.iodc = (e.iodc & ~0xFF) | (e.iode & 0xFF);
  l.iode = e.iode & 0xFF;
  l.l2p_data_flag = e.l2p_data_flag;
  l.tgd_s = e.tgd_s;
  l.toc_s = to_week_tow(e.toc).tow_s;
  l.af0_s = e.af0_s;
  l.af1_sps = e.af1_sps;
  l.af2_sps2 = e.af2_sps2;
  l.crs_m = e.crs_m;
  l.delta_n_radps = e.delta_n_radps;
  l.m0_rad = e.m0_rad;
  l.cuc_rad = e.cuc_rad;
  l.e = e.e;
  l.cus_rad = e.cus_rad;
  l.sqrt_a_sqrtm = e.sqrt_a_sqrtm;
  l.toe_s = to_week_tow(e.toe).tow_s;
  l.fit_interval_flag = e.fit_interval_h > 4.0 ? 1 : 0;
  l.cic_rad = e.cic_rad;
  l.omega0_rad = e.omega0_rad;
  l.cis_rad = e.cis_rad;
  l.i0_rad = e.i0_rad;
  l.crc_m = e.crc_m;
  l.omega_rad = e.omega_rad;
  l.omega_dot_radps = e.omega_dot_radps;
  l.idot_radps = e.idot_radps;
  return l;
}

lnav::LnavIonoUtc broadcast_iono_utc(const NavData& nav, int week, int leap_s) {
  lnav::LnavIonoUtc iono;
  if (nav.klobuchar) {
    iono.alpha = nav.klobuchar->alpha;
    iono.beta = nav.klobuchar->beta;
  }
  iono.dt_ls_s = leap_s;
  iono.dt_lsf_s = leap_s;
  iono.wnt = week;
  iono.wn_lsf = week;
  iono.dn = 1;
  return iono;
}

// What the output messages of one epoch are built from: the latest fix and measurements and
// the quantities several messages share, in wire-ready units.
struct EpochView {
  EpochView(const ReceiverFix& f, const EpochMeasurements& m, const NavData& n, ReceiverMode md,
            const UbxDeviceStatus& st, UbxListScratch& l)
      : fix(f), meas(m), nav(n), mode(md), status(st), lists(l) {}
  const ReceiverFix& fix;
  const EpochMeasurements& meas;
  const NavData& nav;
  ReceiverMode mode;
  const UbxDeviceStatus& status;
  UbxListScratch& lists;
  WeekTow wt = to_week_tow(fix.t);
  // The GPS time of the clock tick that took the epoch (within 0.5 ms of fix.t, iTOW's whole
  // milliseconds): what the fractional fields (NAV-PVT nano, NAV-SOL fTOW, ...) complete.
  GpsTime t_nav = fix.t.plus_s(fix.time_offset_s);
  std::uint32_t i_tow = static_cast<std::uint32_t>(std::llround(wt.tow_s * 1000.0)) % 604'800'000u;
  // NAV-SOL / NAV-TIMEGPS fTOW: t_nav minus iTOW, ns (+-500000).
  std::int32_t f_tow_ns =
      clamp_cast<std::int32_t>((wt.tow_s * 1000.0 - std::round(wt.tow_s * 1000.0)) * 1e6 + fix.time_offset_s * 1e9);
  bool valid = fix.fix != FixType::kNone;
  // NAV-PVT fixType, NAV-STATUS / NAV-SOL gpsFix: 5 "time only fix" in time mode.
  std::uint8_t gps_fix = status.time_only && valid ? kFixTimeOnly : fix_type(fix.fix);
  Accuracy acc = accuracy(fix);
  bool fix_ok = within_output_filters(fix, mode, status);
  Vec3 v_ned = fix.v_ned_mps.value_or(Vec3::Zero());
  Vec3 v_ecef = valid ? Vec3(R_ned_from_ecef(fix.position).transpose() * v_ned) : Vec3::Zero();
  double g_speed = std::hypot(v_ned.x(), v_ned.y());
  double heading_deg = [this] {
    const double h = std::atan2(v_ned.y(), v_ned.x()) * kRadToDeg;
    return h < 0.0 ? h + 360.0 : h;
  }();
  double separation_m = fix.geoid_separation_m;  // 0 without a fix
  std::uint8_t status_flags =
      static_cast<std::uint8_t>((fix_ok ? NavStatus::kGpsFixOk : 0) |
                                (mode == ReceiverMode::kDgps ? NavStatus::kDiffSoln : 0) |
                                NavStatus::kWknSet | NavStatus::kTowSet);
  int leap_s = leap_seconds_at_gps(fix.t, nav.leap_seconds);
};

namespace {

// ---- Output messages -------------------------------------------------------------------------

// A system time as whole seconds of week (rounded) and the remainder in ns (-5e8..5e8).
struct SystemTow {
  int week;
  std::uint32_t tow_s;
  std::int32_t f_tow_ns;
};
// Seconds into a period (a week, a day) as whole seconds, rounded, the remainder in ns
// (-5e8..5e8), and the carry into the next period when they round up to its end.
struct RoundedSeconds {
  int carry;
  std::uint32_t whole_s;
  std::int32_t frac_ns;
};
RoundedSeconds round_in_period(double t_s, std::int64_t period_s) {
  double whole = std::round(t_s);
  const auto frac_ns = clamp_cast<std::int32_t>((t_s - whole) * 1e9);
  const bool carry = whole >= static_cast<double>(period_s);
  if (carry) whole -= static_cast<double>(period_s);
  return {carry ? 1 : 0, static_cast<std::uint32_t>(whole), frac_ns};
}

SystemTow system_tow(GpsTime t, int week_offset) {
  const WeekTow wt = to_week_tow(t);
  const RoundedSeconds r = round_in_period(wt.tow_s, kSecondsPerWeek);
  return {wt.week - week_offset + r.carry, r.whole_s, r.frac_ns};
}

// UTC date and time fields with `nano` completing them (NAV-PVT, NAV-TIMEUTC): the fields are
// the time rounded to the nearest hundredth of a second, so nano runs from -5 ms to +995 ms
// (u-blox integration manuals, "UTC representation", e.g. MAX-M10S 2.8.6).
struct UtcFields {
  CalendarTime c;  // second: whole
  std::int32_t nano_ns;
};
UtcFields utc_fields(GpsTime t) {
  constexpr std::int64_t kHundredth_ns = 10'000'000;
  const GpsTime rounded{(t.ns + kHundredth_ns / 2) / kHundredth_ns * kHundredth_ns};
  CalendarTime c = utc_from_gps(rounded);
  const double whole = std::floor(c.second + 1e-9);
  const double frac_s = c.second - whole;
  c.second = whole;
  return {c, static_cast<std::int32_t>(std::lround(frac_s * 1e9)) + static_cast<std::int32_t>(t.ns - rounded.ns)};
}

void emit_nav_pvt(const EpochView& e, std::vector<std::uint8_t>& out) {
  const ReceiverFix& fix = e.fix;
  const auto [c, nano_ns] = utc_fields(e.t_nav);
  NavPvt m;
  m.i_tow_ms = e.i_tow;
  m.year = static_cast<std::uint16_t>(c.year);
  m.month = static_cast<std::uint8_t>(c.month);
  m.day = static_cast<std::uint8_t>(c.day);
  m.hour = static_cast<std::uint8_t>(c.hour);
  m.min = static_cast<std::uint8_t>(c.minute);
  m.sec = static_cast<std::uint8_t>(c.second);
  m.nano_ns = nano_ns;
  m.valid = NavPvt::kValidDate | NavPvt::kValidTime | NavPvt::kFullyResolved;
  m.t_acc_ns = 20;
  m.fix_type = e.gps_fix;
  m.flags = static_cast<std::uint8_t>((e.fix_ok ? NavPvt::kGnssFixOk : 0) |
                                      (e.mode == ReceiverMode::kDgps ? NavPvt::kDiffSoln : 0) |
                                      (e.mode == ReceiverMode::kRtkFixed && e.valid ? 0x80 : 0));
  m.flags2 = NavPvt::kConfirmedAvai | NavPvt::kConfirmedDate | NavPvt::kConfirmedTime;
  m.num_sv = static_cast<std::uint8_t>(fix.num_used);
  if (e.valid) {
    m.lon_1e7deg = clamp_cast<std::int32_t>(fix.position.lon_deg * 1e7);
    m.lat_1e7deg = clamp_cast<std::int32_t>(fix.position.lat_deg * 1e7);
    m.height_mm = clamp_cast<std::int32_t>(fix.position.h_m * 1e3);
    m.h_msl_mm = clamp_cast<std::int32_t>((fix.position.h_m - e.separation_m) * 1e3);
  } else {
    m.flags3 = 0x01;  // invalidLlh
  }
  m.h_acc_mm = clamp_cast<std::uint32_t>(e.acc.h_m * 1e3);
  m.v_acc_mm = clamp_cast<std::uint32_t>(e.acc.v_m * 1e3);
  m.vel_n_mmps = clamp_cast<std::int32_t>(e.v_ned.x() * 1e3);
  m.vel_e_mmps = clamp_cast<std::int32_t>(e.v_ned.y() * 1e3);
  m.vel_d_mmps = clamp_cast<std::int32_t>(e.v_ned.z() * 1e3);
  m.g_speed_mmps = clamp_cast<std::int32_t>(e.g_speed * 1e3);
  m.head_mot_1e5deg = clamp_cast<std::int32_t>(e.heading_deg * 1e5);
  m.s_acc_mmps = clamp_cast<std::uint32_t>(e.acc.s_mps * 1e3);
  // The heading of motion's 1-sigma: the velocity's across the track over the ground speed.
  const double head_acc_deg =
      e.g_speed > e.acc.cross_track_mps ? std::atan2(e.acc.cross_track_mps, e.g_speed) * kRadToDeg : 180.0;
  m.head_acc_1e5deg = clamp_cast<std::uint32_t>(head_acc_deg * 1e5);
  m.p_dop_0p01 = clamp_cast<std::uint16_t>(e.valid ? fix.dops.pdop * 100.0 : 9999.0);
  append(m, out);
}

void emit_nav_posllh(const EpochView& e, std::vector<std::uint8_t>& out) {
  const Geodetic& p = e.fix.position;
  NavPosllh m;
  m.i_tow_ms = e.i_tow;
  m.lon_1e7deg = clamp_cast<std::int32_t>(p.lon_deg * 1e7);
  m.lat_1e7deg = clamp_cast<std::int32_t>(p.lat_deg * 1e7);
  m.height_mm = clamp_cast<std::int32_t>(p.h_m * 1e3);
  m.h_msl_mm = clamp_cast<std::int32_t>((p.h_m - e.separation_m) * 1e3);
  m.h_acc_mm = clamp_cast<std::uint32_t>(e.acc.h_m * 1e3);
  m.v_acc_mm = clamp_cast<std::uint32_t>(e.acc.v_m * 1e3);
  append(m, out);
}

// ECEF position and velocity in cm and cm/s, as NAV-POSECEF, NAV-VELECEF and NAV-SOL carry them.
struct EcefCm {
  std::int32_t x, y, z;
};
EcefCm to_cm(const Vec3& v) {
  return {clamp_cast<std::int32_t>(v.x() * 100.0), clamp_cast<std::int32_t>(v.y() * 100.0),
          clamp_cast<std::int32_t>(v.z() * 100.0)};
}

void emit_nav_posecef(const EpochView& e, std::vector<std::uint8_t>& out) {
  const EcefCm p = to_cm(e.fix.p_ecef_m);
  append(NavPosecef{e.i_tow, p.x, p.y, p.z, clamp_cast<std::uint32_t>(e.acc.p_m * 100.0)}, out);
}

void emit_nav_velned(const EpochView& e, std::vector<std::uint8_t>& out) {
  const EcefCm v = to_cm(e.v_ned);  // north, east, down
  NavVelned m{e.i_tow, v.x, v.y, v.z};
  m.speed_cmps = clamp_cast<std::uint32_t>(e.v_ned.norm() * 100.0);
  m.g_speed_cmps = clamp_cast<std::uint32_t>(e.g_speed * 100.0);
  m.heading_1e5deg = clamp_cast<std::int32_t>(e.heading_deg * 1e5);
  m.s_acc_cmps = clamp_cast<std::uint32_t>(e.acc.s_mps * 100.0);
  m.c_acc_1e5deg = clamp_cast<std::uint32_t>(180.0 * 1e5);
  append(m, out);
}

void emit_nav_velecef(const EpochView& e, std::vector<std::uint8_t>& out) {
  const EcefCm v = to_cm(e.v_ecef);
  append(NavVelecef{e.i_tow, v.x, v.y, v.z, clamp_cast<std::uint32_t>(e.acc.s_mps * 100.0)}, out);
}

void emit_nav_status(const EpochView& e, std::vector<std::uint8_t>& out) {
  NavStatus m;
  m.i_tow_ms = e.i_tow;
  m.gps_fix = e.gps_fix;
  m.flags = e.status_flags;
  // flags2 spoofDetState (bits 3-4, UBX-13003221 32.17.x NAV-STATUS; the F9 descriptions
  // alike): 1 no spoofing indicated, 2 spoofing indicated (models/measurement.hpp SpoofingEvent).
  m.flags2 = static_cast<std::uint8_t>((e.meas.spoofing_indicated ? 2 : 1) << 3);
  m.ttff_ms = 1000;
  m.msss_ms = e.i_tow;
  append(m, out);
}

void emit_nav_sol(const EpochView& e, std::vector<std::uint8_t>& out) {
  const EcefCm p = to_cm(e.fix.p_ecef_m);
  const EcefCm v = to_cm(e.v_ecef);
  NavSol m;
  m.i_tow_ms = e.i_tow;
  m.f_tow_ns = e.f_tow_ns;
  m.week = static_cast<std::int16_t>(e.wt.week);
  m.gps_fix = e.gps_fix;
  m.flags = e.status_flags;
  m.ecef_x_cm = p.x;
  m.ecef_y_cm = p.y;
  m.ecef_z_cm = p.z;
  m.p_acc_cm = clamp_cast<std::uint32_t>(e.acc.p_m * 100.0);
  m.ecef_vx_cmps = v.x;
  m.ecef_vy_cmps = v.y;
  m.ecef_vz_cmps = v.z;
  m.s_acc_cmps = clamp_cast<std::uint32_t>(e.acc.s_mps * 100.0);
  m.p_dop_0p01 = clamp_cast<std::uint16_t>(e.valid ? e.fix.dops.pdop * 100.0 : 9999.0);
  m.num_sv = static_cast<std::uint8_t>(e.fix.num_used);
  append(m, out);
}

void emit_nav_dop(const EpochView& e, std::vector<std::uint8_t>& out) {
  // Without a fix every DOP is 99.99.
  const auto dop = [&](double d) { return clamp_cast<std::uint16_t>(e.valid ? d * 100.0 : 9999.0); };
  const Dops& d = e.fix.dops;
  NavDop m{e.i_tow, dop(d.gdop), dop(d.pdop), dop(d.tdop), dop(d.vdop), dop(d.hdop)};
  // Without the full covariance, north and east share the horizontal DOP equally.
  m.n_dop_0p01 = dop(d.hdop / std::sqrt(2.0));
  m.e_dop_0p01 = m.n_dop_0p01;
  append(m, out);
}

void emit_nav_timegps(const EpochView& e, std::vector<std::uint8_t>& out) {
  NavTimegps m;
  m.i_tow_ms = e.i_tow;
  m.f_tow_ns = e.f_tow_ns;
  m.week = static_cast<std::int16_t>(e.wt.week);
  m.leap_s = static_cast<std::int8_t>(e.leap_s);
  m.valid = NavTimegps::kTowValid | NavTimegps::kWeekValid | NavTimegps::kLeapSValid;
  m.t_acc_ns = 20;
  append(m, out);
}

void emit_nav_timeutc(const EpochView& e, std::vector<std::uint8_t>& out) {
  const auto [c, nano_ns] = utc_fields(e.t_nav);
  NavTimeutc m;
  m.i_tow_ms = e.i_tow;
  m.t_acc_ns = 20;
  m.nano_ns = nano_ns;
  m.year = static_cast<std::uint16_t>(c.year);
  m.month = static_cast<std::uint8_t>(c.month);
  m.day = static_cast<std::uint8_t>(c.day);
  m.hour = static_cast<std::uint8_t>(c.hour);
  m.min = static_cast<std::uint8_t>(c.minute);
  m.sec = static_cast<std::uint8_t>(c.second);
  m.valid = NavTimeutc::kValidTow | NavTimeutc::kValidWkn | NavTimeutc::kValidUtc | (3 << 4);
  append(m, out);
}

void emit_nav_clock(const EpochView& e, std::vector<std::uint8_t>& out) {
  append(NavClock{e.i_tow, clamp_cast<std::int32_t>(e.meas.rx_clock_bias_s * 1e9),
                  clamp_cast<std::int32_t>(e.meas.rx_clock_drift_sps * 1e9), 20, 500},
         out);
}

void emit_nav_svinfo(const EpochView& e, std::vector<std::uint8_t>& out) {
  NavSvinfo& m = reset_keeping_storage(e.lists.svinfo, &NavSvinfo::channels);
  m.i_tow_ms = e.i_tow;
  m.global_flags = 4;  // u-blox 8 generation
  std::uint8_t chn = 0;
  for (const ReceiverSatellite& s : e.fix.satellites) {
    NavSvinfoChannel c;
    c.chn = chn++;
    c.svid = static_cast<std::uint8_t>(s.sat.ubx_legacy_sv_id().value_or(0));
    c.flags = static_cast<std::uint8_t>((s.used ? NavSvinfoChannel::kSvUsed : 0) |
                                        (s.unhealthy ? NavSvinfoChannel::kUnhealthy : 0) |
                                        NavSvinfoChannel::kOrbitAvail | NavSvinfoChannel::kOrbitEph);
    c.quality = 7;  // code and carrier locked, time synchronised
    c.cno_dbhz = clamp_cast<std::uint8_t>(s.cn0_dbhz);
    c.elev_deg = clamp_cast<std::int8_t>(s.el_deg);
    c.azim_deg = clamp_cast<std::int16_t>(s.az_deg);
    c.pr_res_cm = clamp_cast<std::int32_t>(s.residual_m * 100.0);
    m.channels.push_back(c);
  }
  append(m, out);
}

// NAV-SAT (interface description, UBX-NAV-SAT flags): health (bits 4..5: 1 healthy, 2 unhealthy) as the
// broadcast data say; an unhealthy satellite is tracked and not used. smoothed (bit 7) on a used
// satellite whose pseudorange the engine smoothed by its carrier (NAV-SIG prSmoothed alike).
void emit_nav_sat(const EpochView& e, std::vector<std::uint8_t>& out) {
  NavSat& m = reset_keeping_storage(e.lists.sat, &NavSat::svs);
  m.i_tow_ms = e.i_tow;
  for (const ReceiverSatellite& s : e.fix.satellites) {
    NavSatSv v;
    v.gnss_id = s.sat.ubx_gnss_id();
    v.sv_id = s.sat.ubx_sv_id();
    v.cno_dbhz = clamp_cast<std::uint8_t>(s.cn0_dbhz);
    v.elev_deg = clamp_cast<std::int8_t>(s.el_deg);
    v.azim_deg = clamp_cast<std::int16_t>(s.az_deg);
    v.pr_res_dm = clamp_cast<std::int16_t>(s.residual_m * 10.0);
    v.flags = 7u | (s.used ? NavSatSv::kSvUsed : 0u) | (s.smoothed ? NavSatSv::kSmoothed : 0u) |
              ((s.unhealthy ? 2u : 1u) << NavSatSv::kHealthShift) | (1u << NavSatSv::kOrbitSourceShift) |
              NavSatSv::kEphAvail;
    m.svs.push_back(v);
  }
  append(m, out);
}

void emit_nav_eoe(const EpochView& e, std::vector<std::uint8_t>& out) {
  append(NavEoe{e.i_tow}, out);
}

// RXM-RAWX trkStat (F9 HPG 1.32 interface description): the pseudorange is valid while the
// signal is tracked; the phase while cpStdev is not 15 ("invalid"; the real ZED-F9T of
// receiver_logs/nav-solutions clears cpValid exactly then); the half-cycle ambiguity of the
// Costas loop is resolved by the navigation data's synchronisation pattern, so once the arc has
// lasted one subframe (GPS LNAV and QZSS 6 s, IS-GPS-200 20.3.2; BeiDou D1 6 s, BDS-SIS-ICD-B1I
// 5.2.1) or one string or page (GLONASS 2 s, ICD 3.3.2.2; Galileo I/NAV 2 s, OS SIS ICD 4.3.2).
// navemu's carrier phase carries no half cycle, so none is subtracted (bit 3 stays clear).
std::uint8_t rawx_tracking_status(GnssSystem system, const SignalObs& o, std::uint8_t cp_stdev) {
  const double resolve_s = system == GnssSystem::kGalileo || system == GnssSystem::kGlonass ? 2.0 : 6.0;
  std::uint8_t st = RxmRawxMeas::kPrValid;
  if (cp_stdev != 15) st |= RxmRawxMeas::kCpValid;
  if (cp_stdev != 15 && o.lock_time_s >= resolve_s) st |= RxmRawxMeas::kHalfCyc;
  return st;
}

void emit_rxm_rawx(const EpochView& e, std::vector<std::uint8_t>& out) {
  const WeekTow rt = to_week_tow(e.meas.t_receiver);
  RxmRawx& m = reset_keeping_storage(e.lists.rawx, &RxmRawx::meas);
  m.rcv_tow_s = rt.tow_s;
  m.week = static_cast<std::uint16_t>(rt.week);
  m.leap_s = static_cast<std::int8_t>(e.leap_s);
  m.rec_stat = RxmRawx::kLeapSec;
  for (const SatMeasurement& s : e.meas.sats)
    for (std::size_t b = 0; b < s.signals.size(); ++b) {
      // The part's bands; numMeas is a U1.
      if (!s.signals[b] || !(e.status.bands & band_bit(static_cast<Band>(b))) || m.meas.size() == 255) continue;
      const SignalObs& o = *s.signals[b];
      RxmRawxMeas r;
      r.pr_mes_m = o.pseudorange_m;
      r.cp_mes_cycles = o.carrier_cycles;
      r.do_mes_hz = static_cast<float>(o.doppler_hz);
      r.gnss_id = s.sat.ubx_gnss_id();
      r.sv_id = s.sat.ubx_sv_id();
      r.sig_id = static_cast<std::uint8_t>(ubx_sig_id(s.sat, o.signal).value_or(0));
      if (s.sat.system() == GnssSystem::kGlonass) r.freq_id = static_cast<std::uint8_t>(ubx_freq_id(s.glonass_channel));
      r.locktime_ms = static_cast<std::uint16_t>(std::min(o.lock_time_s * 1000.0, kMaxLockTime_ms));
      r.cno_dbhz = clamp_cast<std::uint8_t>(o.cn0_dbhz);
      r.pr_stdev = ubx::rawx_pr_stdev(o.sigma.code_m);
      r.cp_stdev = ubx::rawx_cp_stdev(o.sigma.phase_cycles);
      r.do_stdev = ubx::rawx_do_stdev(o.sigma.doppler_hz);
      r.trk_stat = rawx_tracking_status(s.sat.system(), o, r.cp_stdev);
      m.meas.push_back(r);
    }
  append(m, out);
}

// What the Galileo pages carry besides the satellite's ephemeris (Galileo OS SIS ICD 2.0 5.1.6-
// 5.1.8: words 5, 6, 10): the file's NeQuick G coefficients, GST - UTC from its GAUT (else
// the whole leap seconds), the GGTO from its GAGP; no leap second announced (as LNAV's).
inav::InavSystemData galileo_system_data(const NavData& nav, GpsTime t, int leap_s) {
  inav::InavSystemData d;
  if (nav.nequick_g) {
    d.ai0_sfu = (*nav.nequick_g)[0];
    d.ai1_sfu_per_deg = (*nav.nequick_g)[1];
    d.ai2_sfu_per_deg2 = (*nav.nequick_g)[2];
  }
  const int gst_week = to_week_tow(t).week - kGstWeek0InGpsWeeks;
  d.dt_ls_s = d.dt_lsf_s = leap_s;
  d.wnot = d.wn_lsf = gst_week;
  d.dn = 1;
  if (const TimeSystemOffset* o = nav.time_offset("GAUT", t)) {
    const WeekTow ref = to_week_tow(o->t_ref);
    d.a0_s = o->a0_s;
    d.a1_sps = o->a1_sps;
    d.tot_s = ref.tow_s;
    d.wnot = ref.week - kGstWeek0InGpsWeeks;
  }
  if (const TimeSystemOffset* o = nav.time_offset("GAGP", t)) {
    const WeekTow ref = to_week_tow(o->t_ref);
    d.a0g_s = o->a0_s;
    d.a1g_sps = o->a1_sps;
    d.t0g_s = ref.tow_s;
    d.wn0g = ref.week - kGstWeek0InGpsWeeks;
  }
  return d;
}

// What GLONASS string 5 carries (GLONASS ICD 5.1, 4.5): the day of the almanac (today), the
// four-year interval, tau_c = -(the file's GLUT) (3.3.3); tau_GPS 0.
gnav::GnavSystemData glonass_system_data(const NavData& nav, GpsTime t, int leap_s) {
  gnav::GnavSystemData d;
  const gnav::GnavDay day = gnav::glonass_day(t, leap_s);
  d.n_a = day.day;
  d.n4 = day.n4;
  if (const TimeSystemOffset* o = nav.time_offset("GLUT", t)) d.tau_c_s = -o->at_s(t);
  return d;
}

// What the BeiDou subframes carry besides the satellite's ephemeris (BDS-SIS-ICD-B1I 3.0
// 5.2.4): the file's Klobuchar set (navemu's data have GPS's), BDT - UTC from its BDUT, leap
// seconds BDT's (GPS's - 14 s), no leap second announced, no almanac.
bdnav::BdsBroadcast beidou_broadcast(const NavData& nav, GpsTime t, int leap_s) {
  bdnav::BdsBroadcast b;
  if (nav.klobuchar) b.iono = *nav.klobuchar;
  b.utc.dt_ls_s = b.utc.dt_lsf_s = leap_s - kGpsMinusBdt_s;
  b.utc.wn_lsf = bdnav::bdt_from_gps(t).week;
  if (const TimeSystemOffset* o = nav.time_offset("BDUT", t)) {
    b.utc.a0_utc_s = o->a0_s;
    b.utc.a1_utc_sps = o->a1_sps;
  }
  return b;
}

// RXM-SFRBX: each tracked satellite's navigation message unit that has just been received,
// regenerated from the ephemeris in use, on the whole seconds of GPS time at which one ends
// (epochs between whole seconds send none):
//   GPS, QZSS  LNAV subframes of 6 s from the start of the GPS week (IS-GPS-200 20.3.2);
//   Galileo    E1-B page pairs of 2 s starting at odd GST seconds (OS SIS ICD 2.0 4.3.2), in
//              9 words as the ZED-F9P sends them (the 9th undocumented, 0 here; RTKLIB's
//              decoder requires it) on sigId 1, E1-B; with the E5b band, E5b-I page pairs
//              starting at even seconds on sigId 5, as the ZED-F9P capture has both;
//   GLONASS    strings of 2 s from the start of the GLONASS day (ICD 5.1, 4.3);
//   BeiDou     D1 subframes of 6 s from the start of the BDT week; D2 (GEO) subframes of
//              0.6 s, those that ended within the last second (BDS-SIS-ICD-B1I 3.0 5.2.2, 5.3.1).
// The channel is the satellite's place among the tracked ones.
void emit_rxm_sfrbx(const EpochView& e, std::vector<std::uint8_t>& out) {
  const auto tow_ms = static_cast<std::int64_t>(std::llround(e.wt.tow_s * 1000.0));
  if (tow_ms % 1000 != 0) return;
  const std::int64_t tow_s = tow_ms / 1000;
  const GpsTime t = from_week_tow(e.wt.week, static_cast<double>(tow_s));
  const auto ends_on = [&](std::int64_t period_s, std::int64_t offset_s) {
    return ((tow_s - offset_s) % period_s + period_s) % period_s == 0;
  };
  const bool lnav_due = ends_on(6, 0), inav_due = ends_on(2, 1), e5b_due = ends_on(2, 0),
             gnav_due = ends_on(2, e.leap_s), d1_due = ends_on(6, kGpsMinusBdt_s);
  const auto send = [&](const SatMeasurement& s, std::uint8_t sig_id, std::uint8_t chn,
                        std::span<const std::uint32_t> words) {
    RxmSfrbx& m = reset_keeping_storage(e.lists.sfrbx, &RxmSfrbx::words);
    m.gnss_id = s.sat.ubx_gnss_id();
    m.sv_id = s.sat.ubx_sv_id();
    m.sig_id = sig_id;
    m.freq_id = s.sat.system() == GnssSystem::kGlonass ? static_cast<std::uint8_t>(ubx_freq_id(s.glonass_channel)) : 0;
    m.chn = chn;
    m.words.assign(words.begin(), words.end());
    append(m, out);
  };
  std::optional<lnav::LnavIonoUtc> iono;
  std::optional<inav::InavSystemData> galileo;
  std::optional<gnav::GnavSystemData> glonass;
  std::optional<bdnav::BdsBroadcast> beidou;
  std::uint8_t chn = 0;
  for (const SatMeasurement& s : e.meas.sats) {
    const std::uint8_t ch = chn++;
    const auto sig = static_cast<std::uint8_t>(s.signals[0] ? ubx_sig_id(s.sat, s.signals[0]->signal).value_or(0) : 0);
    if (s.eph != nullptr && lnav_due) {
      const auto count_next = static_cast<std::uint32_t>(tow_s / 6) % lnav::kTowCountsPerWeek;
      const std::uint32_t count_this = (count_next + lnav::kTowCountsPerWeek - 1) % lnav::kTowCountsPerWeek;
      if (!iono) iono = broadcast_iono_utc(e.nav, e.wt.week, e.leap_s);
      send(s, sig, ch,
           lnav::lnav_subframe(static_cast<int>(count_this % 5) + 1, count_next, to_lnav(*s.eph), *iono,
                               static_cast<int>((count_this / 5) % 25) + 1));
    } else if (const auto* gal = std::get_if<const GalileoEphemeris*>(&s.record); gal != nullptr) {
      const bool e5b = e5b_due && s.signals[1] && (e.status.bands & band_bit(Band::kL2));
      if (!inav_due && !e5b) continue;
      if (!galileo) galileo = galileo_system_data(e.nav, t, e.leap_s);
      const WeekTow start = to_week_tow(t.plus_s(-2.0));
      const inav::InavSignal signal = e5b ? inav::InavSignal::kE5bI : inav::InavSignal::kE1B;
      inav::InavPageExtras extras;
      if (e5b) extras.ssp = inav::kE5bReserved2;
      send(s, e5b ? 5 : 1, ch,
           inav::inav_page(inav::inav_word_type_for(start.tow_s, signal), start.week - kGstWeek0InGpsWeeks,
                           start.tow_s, **gal, *galileo, extras));
    } else if (const auto* glo = std::get_if<const GlonassEphemeris*>(&s.record); glo != nullptr && gnav_due) {
      if (!glonass) glonass = glonass_system_data(e.nav, t, e.leap_s);
      const gnav::GnavSlot slot = gnav::glonass_slot(t.plus_s(-gnav::kString_s), e.leap_s);
      gnav::GnavImmediateFlags flags;
      flags.frame_time_s = slot.frame_time_s;
      flags.l_n = (*glo)->health != 0 ? 1 : 0;
      send(s, sig, ch, gnav::glonass_string(slot.frame, slot.string, **glo, flags, e.leap_s, *glonass, {}, slot.superframe));
    } else if (const auto* bds = std::get_if<const BeidouEphemeris*>(&s.record); bds != nullptr) {
      // A subframe that started `ago_s` before t, at its BDT week and second.
      const auto send_bds = [&](double ago_s, bool d1) {
        const WeekTow start = to_week_tow(t.plus_s(-ago_s - kGpsMinusBdt_s));
        const bdnav::BdsSlot slot = d1 ? bdnav::d1_slot_at(start.tow_s) : bdnav::d2_slot_at(start.tow_s);
        const bdnav::BdtWeekSow at{start.week - kBdtWeek0InGpsWeeks, slot.sow_s};
        if (!beidou) beidou = beidou_broadcast(e.nav, t, e.leap_s);
        send(s, sig, ch,
             d1 ? bdnav::d1_subframe(slot.fra_id, slot.page, at, **bds, *beidou)
                : bdnav::d2_subframe(slot.fra_id, slot.page, at, **bds, *beidou));
      };
      if (bdnav::nav_type_for_prn(s.sat.number()) == bdnav::NavType::kD1) {
        if (d1_due) send_bds(6.0, true);
      } else {
        // D2 subframes of 0.6 s on a grid from the week's start (6 048 000 tenths of a second
        // hold whole subframes): those ending in (t - 1 s, t], oldest first.
        const std::int64_t now_ds = ((tow_s - kGpsMinusBdt_s) * 10 % 6'048'000 + 6'048'000) % 6'048'000;
        const std::int64_t last_end_ds = now_ds - now_ds % 6;
        for (std::int64_t end_ds = last_end_ds - 6; end_ds <= last_end_ds; end_ds += 6)
          if (end_ds > now_ds - 10) send_bds(static_cast<double>(now_ds - end_ds + 6) / 10.0, false);
      }
    }
  }
}

// High-precision geodetic position (F9 HPG 1.13 description, UBX-NAV-HPPOSLLH): the 1e-7 deg
// and mm parts as NAV-POSLLH has them, the remainders in 1e-9 deg (-99..99) and 0.1 mm (-9..9),
// accuracies in 0.1 mm.
// A value counted in high-precision units as the standard field, whole multiples of
// `hp_per_unit` truncated toward zero, and the high-precision remainder, which has the value's
// sign (NAV-HPPOSLLH, NAV-HPPOSECEF: value = field + hp / hp_per_unit).
void split_high_precision(double hp_units, double hp_per_unit, std::int32_t& whole, std::int8_t& hp) {
  const double rounded = std::round(hp_units);
  whole = clamp_cast<std::int32_t>(std::trunc(rounded / hp_per_unit));
  hp = static_cast<std::int8_t>(rounded - static_cast<double>(whole) * hp_per_unit);
}

void emit_nav_hpposllh(const EpochView& e, std::vector<std::uint8_t>& out) {
  const Geodetic& p = e.fix.position;
  NavHpposllh m;
  m.flags = e.valid ? 0 : NavHpposllh::kInvalidLlh;
  m.i_tow_ms = e.i_tow;
  split_high_precision(p.lon_deg * 1e9, 100.0, m.lon_1e7deg, m.lon_hp_1e9deg);
  split_high_precision(p.lat_deg * 1e9, 100.0, m.lat_1e7deg, m.lat_hp_1e9deg);
  split_high_precision(p.h_m * 1e4, 10.0, m.height_mm, m.height_hp_0p1mm);
  split_high_precision((p.h_m - e.separation_m) * 1e4, 10.0, m.h_msl_mm, m.h_msl_hp_0p1mm);
  m.h_acc_0p1mm = clamp_cast<std::uint32_t>(e.acc.h_m * 1e4);
  m.v_acc_0p1mm = clamp_cast<std::uint32_t>(e.acc.v_m * 1e4);
  append(m, out);
}

// The RF front end as MON-HW (u-blox 8, UBX-13003221 "UBX-MON-HW") and MON-RF (F9, one block per
// band) report it: the open-sky readings of an active antenna, per band as a ZED-F9T reports
// them in ../shared/data (receiver_logs/nav-solutions/F9T-L2-5min.ubx, MON-RF): antenna OK and
// powered, CW jamming indicator near 10 of 255, noise and AGC mid-range; moved by the jammers
// on the band (models/interference.hpp).
struct FrontEndBlock {
  FrontEndReading open_sky;
  Band band;
  std::int8_t ofs_i;
  std::uint8_t mag_i;
  std::int8_t ofs_q;
  std::uint8_t mag_q;
};
constexpr FrontEndBlock kFrontEnd[2] = {{{81, 5265, 11}, Band::kL1, 11, 171, 1, 167},
                                        {{54, 4914, 9}, Band::kL2, 8, 154, 7, 154}};

FrontEndMonitor monitor_of(const FrontEndBlock& b, const EpochView& e) {
  const auto i = static_cast<std::size_t>(b.band);
  return front_end_monitor(b.open_sky, e.meas.interference[i], kBandChipRate_Hz[i]);
}

// The antenna supervisor's status and the antenna supply (MON-HW aStatus / aPower, MON-RF
// antStatus / antPower; F9 interface description UBX-MON-HW aStatus 0=INIT 1=DONTKNOW 2=OK
// 3=SHORT 4=OPEN, aPower 0=OFF 1=ON): OK and on; OPEN with the supply on; SHORT with the supply
// off, the supervisor's power-down on a short (CFG-HW-ANT_CFG_PWRDOWN).
std::pair<std::uint8_t, std::uint8_t> antenna_status(const EpochView& e) {
  if (!e.meas.antenna_fault) return {MonHw::kAntOk, 1};
  return *e.meas.antenna_fault == AntennaFault::kOpen ? std::pair<std::uint8_t, std::uint8_t>{MonHw::kAntOpen, 1}
                                                      : std::pair<std::uint8_t, std::uint8_t>{MonHw::kAntShort, 0};
}

// jammingState (MON-HW flags bits 2..3, MON-RF flags bits 0..1; UBX-13003221 "UBX-MON-HW"):
// 0 "unknown or feature disabled" unless the jamming/interference monitor is on
// (CFG-ITFM-ENABLE); then 1 "ok", 2 "warning - interference visible but fix OK", 3 "critical -
// interference visible and no fix". Visible: broadband J/N above bbThreshold or CW J/N above
// cwThreshold (CFG-ITFM).
std::uint8_t jamming_state(const EpochView& e, const FrontEndMonitor& m) {
  if (!e.status.jamming_monitor) return 0;
  const bool visible = m.broadband_j_over_n_db > e.status.itfm_bb_threshold_db ||
                       m.cw_j_over_n_db > e.status.itfm_cw_threshold_db;
  if (!visible) return 1;
  return e.fix.fix >= FixType::k2D ? 2 : 3;
}

void emit_mon_hw(const EpochView& e, std::vector<std::uint8_t>& out) {
  const FrontEndMonitor fe = monitor_of(kFrontEnd[0], e);
  MonHw m;
  std::tie(m.a_status, m.a_power) = antenna_status(e);
  m.noise_per_ms = fe.reading.noise_per_ms;
  m.agc_cnt = fe.reading.agc_cnt;
  m.jam_ind = fe.reading.jam_ind;
  m.flags = static_cast<std::uint8_t>(jamming_state(e, fe) << 2);
  append(m, out);
}

void emit_mon_rf(const EpochView& e, std::vector<std::uint8_t>& out) {
  MonRf& m = e.lists.rf;
  m.blocks.resize(2);  // L1 and L2 front ends of the ZED-F9P
  for (std::uint8_t b = 0; b < 2; ++b) {
    MonRfBlock& k = m.blocks[b];
    const FrontEndBlock& r = kFrontEnd[b];
    const FrontEndMonitor fe = monitor_of(r, e);
    k.block_id = b;
    k.flags = jamming_state(e, fe);
    std::tie(k.ant_status, k.ant_power) = antenna_status(e);
    k.noise_per_ms = fe.reading.noise_per_ms;
    k.agc_cnt = fe.reading.agc_cnt;
    k.jam_ind = fe.reading.jam_ind;
    k.ofs_i = r.ofs_i;
    k.mag_i = r.mag_i;
    k.ofs_q = r.ofs_q;
    k.mag_q = r.mag_q;
  }
  append(m, out);
}

// MON-HW2 (M8 32.16.3, F9 5.13.4): the L1 front end's I/Q offsets and magnitudes as MON-RF's
// first block, configuration from ROM (u-blox 8 "ROM CORE" firmware) or the flash image (F9
// firmware runs from flash), power-on self test passed.
void emit_mon_hw2(const EpochView& e, std::vector<std::uint8_t>& out) {
  MonHw2 m;
  m.ofs_i = kFrontEnd[0].ofs_i;
  m.mag_i = kFrontEnd[0].mag_i;
  m.ofs_q = kFrontEnd[0].ofs_q;
  m.mag_q = kFrontEnd[0].mag_q;
  m.cfg_source = e.status.hw_version.starts_with("0008") ? 114 : 102;
  append(m, out);
}

// MON-HW3 (F9 5.13.5): the hardware version as MON-VER's, RTC calibrated; no pins reported.
void emit_mon_hw3(const EpochView& e, std::vector<std::uint8_t>& out) {
  MonHw3 m;
  m.flags = 0x01;  // rtcCalib
  m.hw_version = std::string(e.status.hw_version);
  append(m, out);
}

// MON-IO (M8 32.16.5, F9 5.13.6): bytes received and sent per port, 6 blocks as on u-blox 8;
// no UART errors on a pty.
void emit_mon_io(const EpochView& e, std::vector<std::uint8_t>& out) {
  MonIo& m = e.lists.io;
  m.ports.resize(kNumPorts);
  for (std::size_t p = 0; p < kNumPorts; ++p)
    m.ports[p] = MonIoPort{e.status.ports[p].rx_bytes, e.status.ports[p].tx_bytes};
  append(m, out);
}

// MON-MSGPP (M8 32.16.6, F9 5.13.7): messages read per protocol and bytes skipped (received
// but part of no message read) per port.
void emit_mon_msgpp(const EpochView& e, std::vector<std::uint8_t>& out) {
  MonMsgpp m;
  std::array<std::uint16_t, 8>* msgs[kNumPorts] = {&m.msg1, &m.msg2, &m.msg3, &m.msg4, &m.msg5, &m.msg6};
  for (std::size_t p = 0; p < kNumPorts; ++p) {
    const UbxPortTraffic& t = e.status.ports[p];
    *msgs[p] = t.msgs;
    m.skipped_bytes[p] = t.rx_bytes - std::min(t.parsed_bytes, t.rx_bytes);
  }
  append(m, out);
}

// MON-RXBUF and MON-TXBUF (M8 32.16.8/32.16.11, F9 5.13.10/5.13.12): navemu hands every byte to
// the port at once, so nothing is pending in a receiver buffer.
void emit_mon_rxbuf(const EpochView&, std::vector<std::uint8_t>& out) { append(MonRxbuf{}, out); }
void emit_mon_txbuf(const EpochView&, std::vector<std::uint8_t>& out) { append(MonTxbuf{}, out); }

// MON-COMMS (F9 5.13.1): one block per port of the ZED-F9P with D_SEL open (I2C, UART1, UART2,
// USB; SPI replaces UART1 and I2C only with D_SEL low: ZED-F9P integration manual, "Interfaces").
// portId as the description numbers them (port type in the high byte, instance in the low).
void emit_mon_comms(const EpochView& e, std::vector<std::uint8_t>& out) {
  constexpr std::pair<std::uint8_t, std::uint16_t> kPorts[] = {
      {kPortDdc, 0x0000}, {kPortUart1, 0x0100}, {kPortUart2, 0x0201}, {kPortUsb, 0x0300}};
  constexpr std::uint8_t kProtocols[4] = {0, 1, 5, 0xFF};  // UBX, NMEA, RTCM3, none
  MonComms& m = e.lists.comms;
  m.prot_ids = {kProtocols[0], kProtocols[1], kProtocols[2], kProtocols[3]};
  m.ports.resize(std::size(kPorts));
  for (std::size_t i = 0; i < std::size(kPorts); ++i) {
    const UbxPortTraffic& t = e.status.ports[kPorts[i].first];
    MonCommsPort& c = m.ports[i];
    c = MonCommsPort{};
    c.port_id = kPorts[i].second;
    c.tx_bytes = t.tx_bytes;
    c.rx_bytes = t.rx_bytes;
    for (std::size_t k = 0; k < 3; ++k) c.msgs[k] = t.msgs[kProtocols[k]];
    c.skipped_bytes = t.rx_bytes - std::min(t.parsed_bytes, t.rx_bytes);
  }
  append(m, out);
}

// NAV-HPPOSECEF (M8 32.17.8, F9 5.14.5): the ECEF position in cm and the remainder in 0.1 mm.
void emit_nav_hpposecef(const EpochView& e, std::vector<std::uint8_t>& out) {
  NavHpposecef m;
  m.i_tow_ms = e.i_tow;
  m.flags = e.valid ? 0 : NavHpposecef::kInvalidEcef;
  split_high_precision(e.fix.p_ecef_m.x() * 1e4, 100.0, m.ecef_x_cm, m.ecef_x_hp_0p1mm);
  split_high_precision(e.fix.p_ecef_m.y() * 1e4, 100.0, m.ecef_y_cm, m.ecef_y_hp_0p1mm);
  split_high_precision(e.fix.p_ecef_m.z() * 1e4, 100.0, m.ecef_z_cm, m.ecef_z_hp_0p1mm);
  m.p_acc_0p1mm = clamp_cast<std::uint32_t>(e.acc.p_m * 1e4);
  append(m, out);
}

// NAV-COV (F9 protocol 27.1x): the solution's north, east and down position variances and the
// speed accuracy as velocity variances; without the solver's full covariance the off-diagonal
// terms are 0.
void emit_nav_cov(const EpochView& e, std::vector<std::uint8_t>& out) {
  NavCov m;
  m.i_tow_ms = e.i_tow;
  m.pos_cov_valid = m.vel_cov_valid = e.valid ? 1 : 0;
  m.pos_cov_nn_m2 = static_cast<float>(e.fix.sigma_n_m * e.fix.sigma_n_m);
  m.pos_cov_ee_m2 = static_cast<float>(e.fix.sigma_e_m * e.fix.sigma_e_m);
  m.pos_cov_dd_m2 = static_cast<float>(e.acc.v_m * e.acc.v_m);
  const auto s2 = static_cast<float>(e.acc.s_mps * e.acc.s_mps);
  m.vel_cov_nn_m2ps2 = m.vel_cov_ee_m2ps2 = m.vel_cov_dd_m2ps2 = s2;
  append(m, out);
}

// NAV-SIG (F9 5.14.15): one block per tracked signal of the profile's bands (ZED-F9P: L1, L2). Flags as
// a ZED-F9T reports them in ../shared/data (F9T-L2-5min.ubx): health 1 (healthy); a signal the
// solution uses has prUsed and doUsed, and its ionosphere model (1 Klobuchar, 8 dual
// frequency); differential corrections (DGPS, RTK: RTCM 3 OSR, corrSource 4) add prCorrUsed,
// and carrier-phase solutions crUsed. A used signal carries its satellite's pseudorange
// residual in the fix (the engine's, of the combination it used).
void emit_nav_sig(const EpochView& e, std::vector<std::uint8_t>& out) {
  NavSig& m = reset_keeping_storage(e.lists.sig, &NavSig::signals);
  m.i_tow_ms = e.i_tow;
  const bool corrected = e.mode == ReceiverMode::kDgps || e.mode == ReceiverMode::kRtkFixed;
  for (const SatMeasurement& s : e.meas.sats) {
    const auto it = std::find_if(e.fix.satellites.begin(), e.fix.satellites.end(),
                                 [&](const ReceiverSatellite& r) { return r.sat == s.sat; });
    const bool sat_used = it != e.fix.satellites.end() && it->used;
    const double residual_m = sat_used ? it->residual_m : 0.0;
    for (std::size_t b = 0; b < s.signals.size() && m.signals.size() < 255; ++b) {
      if (!s.signals[b] || !(e.status.bands & band_bit(static_cast<Band>(b)))) continue;
      const std::optional<int> sig = ubx_sig_id(s.sat, s.signals[b]->signal);
      if (!sig) continue;
      // The single-frequency solution uses L1; the dual-frequency one both bands.
      const bool used = sat_used && (b == 0 || e.mode == ReceiverMode::kDualFrequency);
      NavSigSignal g;
      g.gnss_id = s.sat.ubx_gnss_id();
      g.sv_id = s.sat.ubx_sv_id();
      g.sig_id = static_cast<std::uint8_t>(*sig);
      if (s.sat.system() == GnssSystem::kGlonass) g.freq_id = static_cast<std::uint8_t>(ubx_freq_id(s.glonass_channel));
      g.cno_dbhz = clamp_cast<std::uint8_t>(s.signals[b]->cn0_dbhz);
      g.quality_ind = 7;  // code and carrier locked, as NAV-SAT
      unsigned flags = s.unhealthy ? 2 : 1;  // health: 1 healthy, 2 unhealthy
      if (used) {
        g.pr_res_dm = clamp_cast<std::int16_t>(residual_m * 10.0);
        flags |= NavSigSignal::kPrUsed | NavSigSignal::kDoUsed;
        if (it->smoothed) flags |= NavSigSignal::kPrSmoothed;
        if (e.mode == ReceiverMode::kRtkFixed) flags |= NavSigSignal::kCrUsed | NavSigSignal::kCrCorrUsed;
        if (corrected) {
          flags |= NavSigSignal::kPrCorrUsed;
          g.corr_source = 4;  // RTCM 3 OSR
        } else {
          g.iono_model = e.mode == ReceiverMode::kDualFrequency ? 8 : 1;
        }
      }
      g.sig_flags = static_cast<std::uint16_t>(flags);
      m.signals.push_back(g);
    }
  }
  append(m, out);
}

// NAV-TIMELS (M8 32.17.29, F9 5.14.22): the leap second from GPS (source 2), and the leap second
// event that the GPS navigation message the receiver sends (RXM-SFRBX, subframe 4 page 18)
// announces: no change, at the end of day 1 of the current week.
void emit_nav_timels(const EpochView& e, std::vector<std::uint8_t>& out) {
  NavTimels m;
  m.i_tow_ms = e.i_tow;
  m.src_of_curr_ls = 2;
  m.curr_ls_s = static_cast<std::int8_t>(e.leap_s);
  m.src_of_ls_change = 2;
  m.ls_change_s = 0;
  const GpsTime event = from_week_tow(e.wt.week, 1.0 * kSecondsPerDay);
  m.time_to_ls_event_s = clamp_cast<std::int32_t>(std::floor(seconds_between(event, e.fix.t)));
  m.date_of_ls_gps_wn = static_cast<std::uint16_t>(e.wt.week);
  m.date_of_ls_gps_dn = 1;
  m.valid = NavTimels::kValidCurrLs | NavTimels::kValidTimeToLsEvent;
  append(m, out);
}

// Whether the receiver tracks a satellite of a system (UBX gnssId): the time of a system is
// known from its own signals.
bool tracks(const EpochView& e, std::uint8_t gnss_id) {
  return std::any_of(e.meas.sats.begin(), e.meas.sats.end(),
                     [&](const SatMeasurement& s) { return s.sat.ubx_gnss_id() == gnss_id; });
}

// NAV-TIMEBDS (M8 32.17.25, F9 5.14.18): BDT = GPST - 14 s, BDS week 0 = GPS week 1356 (BDS
// ICD 2.0, 4.3.2 and 5.2.4.5); BDS - UTC = (GPS - UTC) - 14 s.
void emit_nav_timebds(const EpochView& e, std::vector<std::uint8_t>& out) {
  const SystemTow st = system_tow(e.t_nav.plus_s(-kGpsMinusBdt_s), kBdtWeek0InGpsWeeks);
  NavTimebds m;
  m.i_tow_ms = e.i_tow;
  m.sow_s = st.tow_s;
  m.f_sow_ns = st.f_tow_ns;
  m.week = static_cast<std::int16_t>(st.week);
  m.leap_s = static_cast<std::int8_t>(e.leap_s - 14);
  m.valid = tracks(e, 3) ? 0x07 : 0;
  m.t_acc_ns = 20;
  append(m, out);
}

// NAV-TIMEGAL (M8 32.17.26, F9 5.14.19): GST = GPST + the GGTO (GAGP) when the navigation data
// give it (Galileo OS SIS ICD 2.0 5.1.8), Galileo week 0 = GPS week 1024 (5.1.2); Galileo - UTC =
// GPS - UTC in whole seconds.
void emit_nav_timegal(const EpochView& e, std::vector<std::uint8_t>& out) {
  const SystemTow st = system_tow(e.t_nav.plus_s(e.nav.time_offset_s("GAGP", e.t_nav)), kGstWeek0InGpsWeeks);
  NavTimegal m;
  m.i_tow_ms = e.i_tow;
  m.gal_tow_s = st.tow_s;
  m.f_gal_tow_ns = st.f_tow_ns;
  m.gal_wno = static_cast<std::int16_t>(st.week);
  m.leap_s = static_cast<std::int8_t>(e.leap_s);
  m.valid = tracks(e, 2) ? 0x07 : 0;
  m.t_acc_ns = 20;
  append(m, out);
}

// NAV-TIMEGLO (M8 32.17.27, F9 5.14.20): GLONASS time = UTC(SU) + 3 h (GLONASS ICD 5.1, 3.3.3),
// as time of day, day in the four-year interval (1..1461) and the interval from 1996 (1).
void emit_nav_timeglo(const EpochView& e, std::vector<std::uint8_t>& out) {
  const GpsTime moscow = e.t_nav.plus_s(3.0 * 3600.0 - e.leap_s);  // read as a calendar time
  const double since_1996_s = seconds_between(moscow, gps_from_calendar({1996, 1, 1, 0, 0, 0.0}));
  const auto day = static_cast<std::int64_t>(std::floor(since_1996_s / kSecondsPerDay));
  const double tod_s = since_1996_s - static_cast<double>(day * kSecondsPerDay);
  const RoundedSeconds r = round_in_period(tod_s, kSecondsPerDay);
  NavTimeglo m;
  m.i_tow_ms = e.i_tow;
  m.f_tod_ns = r.frac_ns;
  m.tod_s = r.whole_s;
  const std::int64_t d = day + r.carry;
  m.nt_days = static_cast<std::uint16_t>(d % 1461 + 1);
  m.n4 = static_cast<std::uint8_t>(d / 1461 + 1);
  m.valid = tracks(e, 6) ? 0x03 : 0;
  m.t_acc_ns = 20;
  append(m, out);
}

// NAV-ORB (M8 32.17.12, F9 5.14.8): the orbit database, one block per satellite navemu has
// broadcast data for. svFlag: health (bits 0..1: 1 healthy, 2 unhealthy), visibility (bits
// 2..3: 3 above the elevation mask, i.e. tracked; 0 unknown otherwise). eph: usability (bits
// 0..4: 0 unusable, n in 1..29 usable (n-1)*15 to n*15 more minutes, 30 more than 450
// minutes) and source (bits 5..7: 1 GNSS transmission), for the record a tracked satellite
// broadcasts (until toe + half its fit interval); no almanac.
void emit_nav_orb(const EpochView& e, std::vector<std::uint8_t>& out) {
  NavOrb& m = reset_keeping_storage(e.lists.orb, &NavOrb::svs);
  m.i_tow_ms = e.i_tow;
  for (const GpsEphemeris& r : e.nav.gps) {
    const SatId sat = r.sat;
    const bool listed = std::any_of(m.svs.begin(), m.svs.end(), [&](const NavOrbSv& v) {
      return v.gnss_id == sat.ubx_gnss_id() && v.sv_id == sat.ubx_sv_id();
    });
    if (listed || m.svs.size() == 255) continue;
    NavOrbSv v;
    v.gnss_id = sat.ubx_gnss_id();
    v.sv_id = sat.ubx_sv_id();
    const auto meas = std::find_if(e.meas.sats.begin(), e.meas.sats.end(),
                                   [&](const SatMeasurement& s) { return s.sat == sat; });
    const GpsEphemeris* eph = meas != e.meas.sats.end() ? meas->eph : nullptr;
    v.sv_flag = static_cast<std::uint8_t>(eph ? ((eph->health == 0 && !meas->unhealthy ? 1 : 2) | 3 << 2) : 0);
    if (eph) {
      const double left_min =
          seconds_between(eph->toe.plus_s(eph->fit_interval_h * 1800.0), e.fix.t) / 60.0;
      const int n = left_min <= 0.0 ? 0 : std::min(30, static_cast<int>(left_min / 15.0) + 1);
      v.eph = static_cast<std::uint8_t>(n | 1 << 5);
    }
    m.svs.push_back(v);
  }
  append(m, out);
}

// NAV-ODO (M8 32.17.11, F9 5.14.7): the odometer's ground distance (CFG-ODO-USE_ODO); its
// 1-sigma accuracy taken as 1 % of the distance.
void emit_nav_odo(const EpochView& e, std::vector<std::uint8_t>& out) {
  NavOdo m;
  m.i_tow_ms = e.i_tow;
  m.distance_m = clamp_cast<std::uint32_t>(e.status.odo_distance_m);
  m.total_distance_m = clamp_cast<std::uint32_t>(e.status.odo_total_m);
  m.distance_std_m = clamp_cast<std::uint32_t>(0.01 * e.status.odo_distance_m);
  append(m, out);
}

// NAV-RELPOSNED (F9 5.14.12, version 1 from protocol 27.1x): a rover without a reference
// station's corrections: gnssFixOK as the fix, no relative position.
void emit_nav_relposned(const EpochView& e, std::vector<std::uint8_t>& out) {
  NavRelposned m;
  m.i_tow_ms = e.i_tow;
  m.flags = e.fix_ok ? NavRelposned::kGnssFixOk : 0;
  append(m, out);
}

// NAV-SVIN (M8 32.17.24, F9 5.14.17): the survey-in's progress (models/survey_in.hpp); all 0
// while the time mode is off or fixed.
void emit_nav_svin(const EpochView& e, std::vector<std::uint8_t>& out) {
  const SurveyInState& s = e.status.svin;
  NavSvin m;
  m.i_tow_ms = e.i_tow;
  m.dur_s = static_cast<std::uint32_t>(s.duration_s);
  split_high_precision(s.mean_ecef_m.x() * 1e4, 100.0, m.mean_x_cm, m.mean_x_hp_0p1mm);
  split_high_precision(s.mean_ecef_m.y() * 1e4, 100.0, m.mean_y_cm, m.mean_y_hp_0p1mm);
  split_high_precision(s.mean_ecef_m.z() * 1e4, 100.0, m.mean_z_cm, m.mean_z_hp_0p1mm);
  m.mean_acc_0p1mm = clamp_cast<std::uint32_t>(s.mean_acc_m * 1e4);
  m.obs = s.obs;
  m.valid = s.valid ? 1 : 0;
  m.active = s.active ? 1 : 0;
  append(m, out);
}

// A status message of something navemu does not model: every field but iTOW (where the message
// has one) keeps its "nothing to report" value (what each one reports is beside its row in
// kOutputs).
template <class M>
void emit_status(const EpochView& e, std::vector<std::uint8_t>& out) {
  M m;
  if constexpr (requires { m.i_tow_ms; }) m.i_tow_ms = e.i_tow;
  append(m, out);
}

// NAV-SBAS (M8 32.17.19; the F9P's CFG-MSGOUT-UBX_NAV_SBAS): SBAS on, as both parts are at
// power-up, and no SBAS satellite tracked (navemu has none): no GEO, system unknown, no blocks.
void emit_nav_sbas(const EpochView& e, std::vector<std::uint8_t>& out) {
  NavSbas m;
  m.i_tow_ms = e.i_tow;
  m.mode = 1;  // enabled integrity
  append(m, out);
}

// NAV-DGPS (M8 32.17.5): PR + PRR corrections in DGPS mode, none otherwise. The corrections
// themselves are not modelled (ReceiverMode::kDgps removes the errors they would), so no
// per-satellite blocks.
void emit_nav_dgps(const EpochView& e, std::vector<std::uint8_t>& out) {
  NavDgps m;
  m.i_tow_ms = e.i_tow;
  m.status = e.mode == ReceiverMode::kDgps ? 1 : 0;
  append(m, out);
}

// RXM-MEASX (M8 32.18.2, F9 UBX-18010854 5.15.1): each tracked signal's pseudorange as RRLP
// reports it (3GPP TS 44.031 A.3.2.6, "GPS Measurement Information"): the code phase is the
// pseudorange modulo the 1 ms C/A code period, in chips (1023 per ms) with 1/1024 fractions and
// again in 2^-21 ms; intCodePhase the whole milliseconds; the Doppler in 0.2 Hz and, times the
// wavelength, in 0.04 m/s. RRLP's multipath indicator: low under 5 m of multipath error, medium
// to 43 m, high above; its pseudorange RMS error index: 0.5 (1 + x/8) 2^y m (x the index's low
// 3 bits, y the high 3), of the 0.32 m RXM-RAWX reports. The reference times of week are the
// receiver's, in each system's time scale (GLONASS: UTC(SU) + 3 h; BeiDou: GPS - 14 s).
std::uint8_t rrlp_multipath(double error_m) {
  const double a = std::abs(error_m);
  return a < 5.0 ? 1 : a < 43.0 ? 2 : 3;
}
std::uint8_t rrlp_rms_error_index(double sigma_m) {
  for (int i = 0; i < 63; ++i)
    if (sigma_m <= 0.5 * (1.0 + (i & 7) / 8.0) * std::ldexp(1.0, i >> 3)) return static_cast<std::uint8_t>(i);
  return 63;
}
void emit_rxm_measx(const EpochView& e, std::vector<std::uint8_t>& out) {
  constexpr std::uint32_t kWeek_ms = 604'800'000u;
  constexpr double kPrSigma_m = 0.32;  // RXM-RAWX prStdev 5
  const WeekTow rt = to_week_tow(e.meas.t_receiver);
  const auto tow_ms = static_cast<std::uint32_t>(std::llround(rt.tow_s * 1000.0)) % kWeek_ms;
  const auto shifted = [&](std::int64_t offset_ms) {
    return static_cast<std::uint32_t>((tow_ms + offset_ms + kWeek_ms) % kWeek_ms);
  };
  RxmMeasx& m = reset_keeping_storage(e.lists.measx, &RxmMeasx::svs);
  m.gps_tow_ms = m.qzss_tow_ms = tow_ms;
  m.glo_tow_ms = shifted(3 * 3'600'000 - 1000 * static_cast<std::int64_t>(e.leap_s));
  m.bds_tow_ms = shifted(-14'000);
  const std::uint16_t acc = e.valid ? 1 : 0;  // the 20 ns of tAcc, rounded up to 2^-4 ms
  m.gps_tow_acc_2m4ms = m.glo_tow_acc_2m4ms = m.bds_tow_acc_2m4ms = m.qzss_tow_acc_2m4ms = acc;
  m.flags = e.valid ? 2 : 0;  // towSet
  for (const SatMeasurement& s : e.meas.sats) {
    if (!s.signals[0]) continue;
    const SignalObs& o = *s.signals[0];
    const double pr_ms = o.pseudorange_m / kSpeedOfLight_mps * 1e3;
    const double whole_ms = std::floor(pr_ms);
    const double frac_ms = pr_ms - whole_ms;
    const auto frac_1024chips = static_cast<std::uint32_t>(std::floor(frac_ms * 1023.0 * 1024.0));
    RxmMeasxSv v;
    v.gnss_id = s.sat.ubx_gnss_id();
    v.sv_id = s.sat.ubx_sv_id();
    v.cno_dbhz = clamp_cast<std::uint8_t>(o.cn0_dbhz);
    v.mpath_indic = rrlp_multipath(s.multipath_m);
    v.doppler_200mhz = clamp_cast<std::int32_t>(o.doppler_hz / 0.2);
    v.doppler_4cmps = clamp_cast<std::int32_t>(o.doppler_hz * kSpeedOfLight_mps / o.carrier_hz / 0.04);
    v.whole_chips = static_cast<std::uint16_t>(frac_1024chips / 1024);
    v.frac_chips = static_cast<std::uint16_t>(frac_1024chips % 1024);
    v.code_phase_2m21ms = static_cast<std::uint32_t>(std::floor(std::ldexp(frac_ms, 21)));
    v.int_code_phase_ms = static_cast<std::uint8_t>(static_cast<std::int64_t>(whole_ms) & 0xFF);
    v.pseu_range_rms_err = rrlp_rms_error_index(kPrSigma_m);
    m.svs.push_back(v);
  }
  append(m, out);
}

// TIM-VRFY (M8 32.20, F9 "UBX-TIM-VRFY"): navemu takes no time aiding (src 0), so the sourced
// time is the navigation time of this epoch and the difference 0.
void emit_tim_vrfy(const EpochView& e, std::vector<std::uint8_t>& out) {
  TimVrfy m;
  m.i_tow_ms = static_cast<std::int32_t>(e.i_tow);
  m.wno = static_cast<std::uint16_t>(e.wt.week);
  append(m, out);
}

// TIM-TP (M8 32.20, F9 5.17.2): the time pulse at the next whole GPS second (time base GNSS,
// time reference GPS, UTC available; utcStandard 3, USNO as GPS disseminates it).
void emit_tim_tp(const EpochView& e, std::vector<std::uint8_t>& out) {
  const WeekTow next = to_week_tow(from_week_tow(e.wt.week, std::floor(e.wt.tow_s) + 1.0));
  TimTp m;
  m.tow_ms = static_cast<std::uint32_t>(std::llround(next.tow_s * 1000.0));
  m.week = static_cast<std::uint16_t>(next.week);
  m.flags = 0x02;  // timeBase GNSS, utc available
  m.ref_info = 3 << 4;
  append(m, out);
}

// TIM-TM2 (M8 32.20, F9 5.17.1): navemu has no EXTINT input: no time mark, count 0.
void emit_tim_tm2(const EpochView&, std::vector<std::uint8_t>& out) {
  TimTm2 m;
  m.flags = 1 << 3 | 1 << 5;  // timeBase GNSS, UTC available
  append(m, out);
}

}  // namespace

namespace {

// Every UBX output message the device can produce, in the order of one epoch's output: raw
// measurement data first (it is measured before the solution), the navigation and timing
// messages, the monitor messages, and NAV-EOE closing the epoch (u-blox interface description,
// "NAV-EOE"). Which generation has a message: the message lists of UBX-13003221 (the
// standard-precision u-blox 8, protocol 18: no high-precision, RTK or survey-in messages) and
// of the F9 HPG descriptions (CFG-MSGOUT items).
// Names (profiles' `ubx: messages`) are those of the message descriptions (ubx::find_message).
constexpr UbxOutput kOutputs[] = {
    {kRxmRawx, "UBX_RXM_RAWX", true, true, &emit_rxm_rawx},
    {kRxmSfrbx, "UBX_RXM_SFRBX", true, true, &emit_rxm_sfrbx},
    {kRxmMeasx, "UBX_RXM_MEASX", true, true, &emit_rxm_measx},
    // RXM-IMES (M8 32.18.1): no IMES transmitter received.
    {kRxmImes, "", true, false, &emit_status<RxmImes>},
    {kNavPosecef, "UBX_NAV_POSECEF", true, true, &emit_nav_posecef},
    {kNavPosllh, "UBX_NAV_POSLLH", true, true, &emit_nav_posllh},
    {kNavStatus, "UBX_NAV_STATUS", true, true, &emit_nav_status},
    {kNavDop, "UBX_NAV_DOP", true, true, &emit_nav_dop},
    {kNavSol, "", true, false, &emit_nav_sol},
    {kNavPvt, "UBX_NAV_PVT", true, true, &emit_nav_pvt},
    {kNavVelecef, "UBX_NAV_VELECEF", true, true, &emit_nav_velecef},
    {kNavVelned, "UBX_NAV_VELNED", true, true, &emit_nav_velned},
    {kNavTimegps, "UBX_NAV_TIMEGPS", true, true, &emit_nav_timegps},
    {kNavTimeutc, "UBX_NAV_TIMEUTC", true, true, &emit_nav_timeutc},
    {kNavClock, "UBX_NAV_CLOCK", true, true, &emit_nav_clock},
    {kNavSvinfo, "", true, false, &emit_nav_svinfo},
    {kNavSat, "UBX_NAV_SAT", true, true, &emit_nav_sat},
    {kNavSig, "UBX_NAV_SIG", false, true, &emit_nav_sig},
    {kNavSbas, "UBX_NAV_SBAS", true, true, &emit_nav_sbas},
    // NAV-SLAS (F9 HPG "UBX-NAV-SLAS"): no QZSS L1S signal tracked, so no ground monitoring
    // station and no corrections.
    {kNavSlas, "UBX_NAV_SLAS", false, true, &emit_status<NavSlas>},
    {kNavDgps, "", true, false, &emit_nav_dgps},
    // NAV-AOPSTATUS (M8 32.17.2): AssistNow Autonomous off (CFG-NAVX5 aopCfg's power-up value), idle.
    {kNavAopstatus, "", true, false, &emit_status<NavAopstatus>},
    {kNavHpposecef, "UBX_NAV_HPPOSECEF", false, true, &emit_nav_hpposecef},
    {kNavHpposllh, "UBX_NAV_HPPOSLLH", false, true, &emit_nav_hpposllh},
    {kNavCov, "UBX_NAV_COV", false, true, &emit_nav_cov},
    {kNavRelposned, "UBX_NAV_RELPOSNED", false, true, &emit_nav_relposned},
    {kNavSvin, "UBX_NAV_SVIN", false, true, &emit_nav_svin},
    {kNavTimels, "UBX_NAV_TIMELS", true, true, &emit_nav_timels},
    {kNavTimebds, "UBX_NAV_TIMEBDS", true, true, &emit_nav_timebds},
    {kNavTimegal, "UBX_NAV_TIMEGAL", true, true, &emit_nav_timegal},
    {kNavTimeglo, "UBX_NAV_TIMEGLO", true, true, &emit_nav_timeglo},
    {kNavOrb, "UBX_NAV_ORB", true, true, &emit_nav_orb},
    {kNavOdo, "UBX_NAV_ODO", true, true, &emit_nav_odo},
    // NAV-GEOFENCE (M8 32.17.7, F9 5.14.4): no geofence configured: status 0 "not available".
    {kNavGeofence, "UBX_NAV_GEOFENCE", true, true, &emit_status<NavGeofence>},
    {kTimTp, "UBX_TIM_TP", true, true, &emit_tim_tp},
    {kTimTm2, "UBX_TIM_TM2", true, true, &emit_tim_tm2},
    {kTimVrfy, "UBX_TIM_VRFY", true, true, &emit_tim_vrfy},
    {kMonHw, "UBX_MON_HW", true, true, &emit_mon_hw},
    {kMonHw2, "UBX_MON_HW2", true, true, &emit_mon_hw2},
    {kMonHw3, "UBX_MON_HW3", false, true, &emit_mon_hw3},
    {kMonRf, "UBX_MON_RF", false, true, &emit_mon_rf},
    {kMonComms, "UBX_MON_COMMS", false, true, &emit_mon_comms},
    {kMonIo, "UBX_MON_IO", true, true, &emit_mon_io},
    {kMonMsgpp, "UBX_MON_MSGPP", true, true, &emit_mon_msgpp},
    {kMonRxbuf, "UBX_MON_RXBUF", true, true, &emit_mon_rxbuf},
    {kMonTxbuf, "UBX_MON_TXBUF", true, true, &emit_mon_txbuf},
    {kNavEoe, "UBX_NAV_EOE", true, true, &emit_nav_eoe},
};

}  // namespace

std::span<const UbxOutput> ubx_outputs() { return kOutputs; }

const UbxOutput* find_ubx_output(MsgId id) {
  for (const UbxOutput& m : kOutputs)
    if (m.id == id) return &m;
  return nullptr;
}

void emit_ubx_outputs(std::uint64_t due, const ReceiverFix& fix, const EpochMeasurements& meas,
                      const NavData& nav, ReceiverMode mode, const UbxDeviceStatus& status,
                      UbxListScratch& lists, std::vector<std::uint8_t>& out) {
  static_assert(std::size(kOutputs) <= kMaxUbxOutputs, "one bit per output message");
  const EpochView view(fix, meas, nav, mode, status, lists);
  for (std::size_t i = 0; i < std::size(kOutputs); ++i)
    if (due >> i & 1u) kOutputs[i].emit(view, out);
}

}  // namespace navemu
