#include "emulator/ubx_device.hpp"

#include <algorithm>
#include <cmath>

#include "core/sat_table.hpp"
#include "core/signal.hpp"
#include "models/geodesy.hpp"
#include "models/reuse.hpp"
#include "protocols/gps_lnav.hpp"

namespace navemu {

namespace {

using namespace ubx;

constexpr std::uint16_t key(MsgId id) { return static_cast<std::uint16_t>(id.cls << 8 | id.id); }

// NMEA sentences in CFG-MSG (class 0xF0) by their message ID.
constexpr std::pair<std::uint8_t, const char*> kNmeaIds[] = {
    {0x00, "GGA"}, {0x01, "GLL"}, {0x02, "GSA"}, {0x03, "GSV"},
    {0x04, "RMC"}, {0x05, "VTG"}, {0x07, "GST"}, {0x08, "ZDA"}};

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
};
Accuracy accuracy(const ReceiverFix& fix) {
  if (fix.fix == FixType::kNone) return {9999.0, 9999.0, 9999.0, 20.0};
  const double p = std::hypot(fix.sigma_h_m, fix.sigma_v_m);
  // Doppler velocity: about 5 cm/s of range-rate noise times the PDOP.
  return {fix.sigma_h_m, fix.sigma_v_m, p, 0.05 * std::max(fix.dops.pdop, 1.0)};
}

// The GPS broadcast record of a satellite as IS-GPS-200 subframes 1-3 carry it.
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


// ---- Output messages -------------------------------------------------------------------------

// What the output messages of one epoch are built from: the latest fix and measurements and
// the quantities several messages share, in wire-ready units.
struct EpochView {
  EpochView(const ReceiverFix& f, const EpochMeasurements& m, const NavData& n, ReceiverMode md,
            UbxListScratch& l)
      : fix(f), meas(m), nav(n), mode(md), lists(l) {}
  const ReceiverFix& fix;
  const EpochMeasurements& meas;
  const NavData& nav;
  ReceiverMode mode;
  UbxListScratch& lists;
  WeekTow wt = to_week_tow(fix.t);
  std::uint32_t i_tow = static_cast<std::uint32_t>(std::llround(wt.tow_s * 1000.0)) % 604'800'000u;
  bool valid = fix.fix != FixType::kNone;
  Accuracy acc = accuracy(fix);
  Vec3 v_ned = fix.v_ned_mps.value_or(Vec3::Zero());
  Vec3 v_ecef = valid ? Vec3(R_ned_from_ecef(fix.position).transpose() * v_ned) : Vec3::Zero();
  double g_speed = std::hypot(v_ned.x(), v_ned.y());
  double heading_deg = [this] {
    const double h = std::atan2(v_ned.y(), v_ned.x()) * kRadToDeg;
    return h < 0.0 ? h + 360.0 : h;
  }();
  double separation_m = fix.geoid_separation_m;  // 0 without a fix
  std::uint8_t status_flags =
      static_cast<std::uint8_t>((valid ? NavStatus::kGpsFixOk : 0) |
                                (mode == ReceiverMode::kDgps ? NavStatus::kDiffSoln : 0) |
                                NavStatus::kWknSet | NavStatus::kTowSet);
  int leap_s = leap_seconds_at_gps(fix.t, nav.leap_seconds);
};

void emit_nav_pvt(const EpochView& e, std::vector<std::uint8_t>& out) {
  const ReceiverFix& fix = e.fix;
  const CalendarTime c = utc_from_gps(fix.t);
  const double whole = std::floor(c.second);
  NavPvt m;
  m.i_tow_ms = e.i_tow;
  m.year = static_cast<std::uint16_t>(c.year);
  m.month = static_cast<std::uint8_t>(c.month);
  m.day = static_cast<std::uint8_t>(c.day);
  m.hour = static_cast<std::uint8_t>(c.hour);
  m.min = static_cast<std::uint8_t>(c.minute);
  m.sec = static_cast<std::uint8_t>(whole);
  m.nano_ns = static_cast<std::int32_t>(std::lround((c.second - whole) * 1e9));
  m.valid = NavPvt::kValidDate | NavPvt::kValidTime | NavPvt::kFullyResolved;
  m.t_acc_ns = 20;
  m.fix_type = fix_type(fix.fix);
  m.flags = static_cast<std::uint8_t>((e.valid ? NavPvt::kGnssFixOk : 0) |
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
  const double head_acc_deg =
      e.g_speed > e.acc.s_mps ? std::atan2(e.acc.s_mps, e.g_speed) * kRadToDeg : 180.0;
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
  m.gps_fix = fix_type(e.fix.fix);
  m.flags = e.status_flags;
  m.ttff_ms = 1000;
  m.msss_ms = e.i_tow;
  append(m, out);
}

void emit_nav_sol(const EpochView& e, std::vector<std::uint8_t>& out) {
  const double tow_ms = e.wt.tow_s * 1000.0;
  const EcefCm p = to_cm(e.fix.p_ecef_m);
  const EcefCm v = to_cm(e.v_ecef);
  NavSol m;
  m.i_tow_ms = e.i_tow;
  m.f_tow_ns = clamp_cast<std::int32_t>((tow_ms - std::round(tow_ms)) * 1e6);
  m.week = static_cast<std::int16_t>(e.wt.week);
  m.gps_fix = fix_type(e.fix.fix);
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
  m.week = static_cast<std::int16_t>(e.wt.week);
  m.leap_s = static_cast<std::int8_t>(e.leap_s);
  m.valid = NavTimegps::kTowValid | NavTimegps::kWeekValid | NavTimegps::kLeapSValid;
  m.t_acc_ns = 20;
  append(m, out);
}

void emit_nav_timeutc(const EpochView& e, std::vector<std::uint8_t>& out) {
  const CalendarTime c = utc_from_gps(e.fix.t);
  const double whole = std::floor(c.second);
  NavTimeutc m;
  m.i_tow_ms = e.i_tow;
  m.t_acc_ns = 20;
  m.nano_ns = static_cast<std::int32_t>(std::lround((c.second - whole) * 1e9));
  m.year = static_cast<std::uint16_t>(c.year);
  m.month = static_cast<std::uint8_t>(c.month);
  m.day = static_cast<std::uint8_t>(c.day);
  m.hour = static_cast<std::uint8_t>(c.hour);
  m.min = static_cast<std::uint8_t>(c.minute);
  m.sec = static_cast<std::uint8_t>(whole);
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
                                        NavSvinfoChannel::kOrbitAvail | NavSvinfoChannel::kOrbitEph);
    c.quality = 7;  // code and carrier locked, time synchronised
    c.cno_dbhz = clamp_cast<std::uint8_t>(s.cn0_dbhz);
    c.elev_deg = clamp_cast<std::int8_t>(s.el_deg);
    c.azim_deg = clamp_cast<std::int16_t>(s.az_deg);
    m.channels.push_back(c);
  }
  append(m, out);
}

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
    v.flags = 7u | (s.used ? NavSatSv::kSvUsed : 0u) | (1u << NavSatSv::kHealthShift) |
              (1u << NavSatSv::kOrbitSourceShift) | NavSatSv::kEphAvail;
    m.svs.push_back(v);
  }
  append(m, out);
}

void emit_nav_eoe(const EpochView& e, std::vector<std::uint8_t>& out) {
  append(NavEoe{e.i_tow}, out);
}

void emit_rxm_rawx(const EpochView& e, std::vector<std::uint8_t>& out) {
  const WeekTow rt = to_week_tow(e.meas.t_receiver);
  RxmRawx& m = reset_keeping_storage(e.lists.rawx, &RxmRawx::meas);
  m.rcv_tow_s = rt.tow_s;
  m.week = static_cast<std::uint16_t>(rt.week);
  m.leap_s = static_cast<std::int8_t>(e.leap_s);
  m.rec_stat = RxmRawx::kLeapSec;
  for (const SatMeasurement& s : e.meas.sats) {
    if (!s.signals[0]) continue;
    const SignalObs& o = *s.signals[0];
    RxmRawxMeas r;
    r.pr_mes_m = o.pseudorange_m;
    r.cp_mes_cycles = o.carrier_cycles;
    r.do_mes_hz = static_cast<float>(o.doppler_hz);
    r.gnss_id = s.sat.ubx_gnss_id();
    r.sv_id = s.sat.ubx_sv_id();
    r.sig_id = static_cast<std::uint8_t>(ubx_sig_id(s.sat, kBandSignals[0]).value_or(0));
    r.locktime_ms = static_cast<std::uint16_t>(std::min(o.lock_time_s * 1000.0, kMaxLockTime_ms));
    r.cno_dbhz = clamp_cast<std::uint8_t>(o.cn0_dbhz);
    r.pr_stdev = 5;  // 0.01 * 2^5 = 0.32 m
    r.cp_stdev = 3;  // 0.012 cycles
    r.do_stdev = 6;  // 0.128 Hz
    r.trk_stat = RxmRawxMeas::kPrValid | RxmRawxMeas::kCpValid | RxmRawxMeas::kHalfCyc |
                 RxmRawxMeas::kSubHalfCyc;
    m.meas.push_back(r);
  }
  append(m, out);
}

void emit_rxm_sfrbx(const EpochView& e, std::vector<std::uint8_t>& out) {
  // A subframe is complete every 6 s of GPS time (IS-GPS-200 20.3.2): at such an epoch, each
  // tracked satellite's subframe that just ended, regenerated from the ephemeris in use.
  const auto tow_ms = static_cast<std::int64_t>(std::llround(e.wt.tow_s * 1000.0));
  if (tow_ms % 6000 != 0) return;
  const auto tow_count_next = static_cast<std::uint32_t>(tow_ms / 6000) % lnav::kTowCountsPerWeek;
  const std::uint32_t tow_count_this = (tow_count_next + lnav::kTowCountsPerWeek - 1) % lnav::kTowCountsPerWeek;
  const int sf_id = static_cast<int>(tow_count_this % 5) + 1;
  const int page = static_cast<int>((tow_count_this / 5) % 25) + 1;
  lnav::LnavIonoUtc iono;
  if (e.nav.klobuchar) {
    iono.alpha = e.nav.klobuchar->alpha;
    iono.beta = e.nav.klobuchar->beta;
  }
  iono.dt_ls_s = e.leap_s;
  iono.dt_lsf_s = e.leap_s;
  iono.wnt = e.wt.week;
  iono.wn_lsf = e.wt.week;
  iono.dn = 1;
  std::uint8_t chn = 0;
  for (const SatMeasurement& s : e.meas.sats) {
    if (s.eph == nullptr) continue;
    RxmSfrbx& m = reset_keeping_storage(e.lists.sfrbx, &RxmSfrbx::words);
    m.gnss_id = s.sat.ubx_gnss_id();
    m.sv_id = s.sat.ubx_sv_id();
    m.sig_id = static_cast<std::uint8_t>(ubx_sig_id(s.sat, kBandSignals[0]).value_or(0));
    m.chn = chn++;
    const lnav::LnavSubframe w = lnav::lnav_subframe(sf_id, tow_count_next, to_lnav(*s.eph), iono, page);
    m.words.assign(w.begin(), w.end());
    append(m, out);
  }
}

// Every UBX output message the device can produce, in the order of one epoch's output: raw
// measurement data first (it is measured before the solution), the navigation messages, and
// NAV-EOE closing the epoch (u-blox interface description, "NAV-EOE"). Names (profiles' `ubx:
// messages`) are those of the message descriptions (ubx::find_message).
struct OutputMessage {
  MsgId id;
  std::uint32_t valset_uart1;  // CFG-MSGOUT-..._UART1 and _USB keys (protocol 27+; 0: none)
  std::uint32_t valset_usb;
  void (*emit)(const EpochView&, std::vector<std::uint8_t>&);
};
constexpr OutputMessage kOutputs[] = {
    {kRxmRawx, cfgkey::kMsgoutUbxRxmRawxUart1, cfgkey::kMsgoutUbxRxmRawxUsb, &emit_rxm_rawx},
    {kRxmSfrbx, cfgkey::kMsgoutUbxRxmSfrbxUart1, cfgkey::kMsgoutUbxRxmSfrbxUsb, &emit_rxm_sfrbx},
    {kNavPosecef, cfgkey::kMsgoutUbxNavPosecefUart1, cfgkey::kMsgoutUbxNavPosecefUsb, &emit_nav_posecef},
    {kNavPosllh, cfgkey::kMsgoutUbxNavPosllhUart1, cfgkey::kMsgoutUbxNavPosllhUsb, &emit_nav_posllh},
    {kNavStatus, cfgkey::kMsgoutUbxNavStatusUart1, cfgkey::kMsgoutUbxNavStatusUsb, &emit_nav_status},
    {kNavDop, cfgkey::kMsgoutUbxNavDopUart1, cfgkey::kMsgoutUbxNavDopUsb, &emit_nav_dop},
    {kNavSol, 0, 0, &emit_nav_sol},
    {kNavPvt, cfgkey::kMsgoutUbxNavPvtUart1, cfgkey::kMsgoutUbxNavPvtUsb, &emit_nav_pvt},
    {kNavVelecef, cfgkey::kMsgoutUbxNavVelecefUart1, cfgkey::kMsgoutUbxNavVelecefUsb, &emit_nav_velecef},
    {kNavVelned, cfgkey::kMsgoutUbxNavVelnedUart1, cfgkey::kMsgoutUbxNavVelnedUsb, &emit_nav_velned},
    {kNavTimegps, cfgkey::kMsgoutUbxNavTimegpsUart1, cfgkey::kMsgoutUbxNavTimegpsUsb, &emit_nav_timegps},
    {kNavTimeutc, cfgkey::kMsgoutUbxNavTimeutcUart1, cfgkey::kMsgoutUbxNavTimeutcUsb, &emit_nav_timeutc},
    {kNavClock, cfgkey::kMsgoutUbxNavClockUart1, cfgkey::kMsgoutUbxNavClockUsb, &emit_nav_clock},
    {kNavSvinfo, 0, 0, &emit_nav_svinfo},
    {kNavSat, cfgkey::kMsgoutUbxNavSatUart1, cfgkey::kMsgoutUbxNavSatUsb, &emit_nav_sat},
    {kNavEoe, cfgkey::kMsgoutUbxNavEoeUart1, cfgkey::kMsgoutUbxNavEoeUsb, &emit_nav_eoe},
};

const OutputMessage* output_of(MsgId id) {
  for (const OutputMessage& m : kOutputs)
    if (m.id == id) return &m;
  return nullptr;
}

// The message and port a CFG-MSGOUT key configures, if it is one.
std::optional<std::pair<MsgId, std::uint8_t>> msgout_key(std::uint32_t k) {
  for (const OutputMessage& m : kOutputs) {
    if (m.valset_uart1 && k == m.valset_uart1) return std::pair{m.id, kPortUart1};
    if (m.valset_usb && k == m.valset_usb) return std::pair{m.id, kPortUsb};
  }
  return std::nullopt;
}

}  // namespace

UbxDevice::UbxDevice(const GnssProfile& profile, ReceiverMode mode, const NavData& nav)
    : profile_(profile), mode_(mode), nav_(nav) {
  // Room for every satellite: copying and refilling the epoch's lists never allocates.
  last_fix_.satellites.reserve(kDefinedSatellites);
  last_meas_.sats.reserve(kDefinedSatellites);
  lists_.svinfo.channels.reserve(kDefinedSatellites);
  lists_.sat.svs.reserve(kDefinedSatellites);
  lists_.rawx.meas.reserve(kDefinedSatellites);
  const UbxSettings& u = *profile_.ubx;
  baud_ = profile_.baud;
  out_proto_ = static_cast<std::uint16_t>(kProtoUbx | (u.nmea_out ? kProtoNmea : 0));
  meas_rate_ms_ = static_cast<std::uint16_t>(std::lround(1000.0 / profile_.rate_hz));
  for (const auto& [name, rate] : u.messages)
    if (const MessageInfo* m = find_message(name); m != nullptr && output_of(m->id) != nullptr)
      set_rate(m->id, port_id_, rate);
  for (const auto& [name, rate] : profile_.sentences)
    for (const auto& [id, n] : kNmeaIds)
      if (name == n) set_rate({kClassNmea, id}, port_id_, rate);
  nav5_.dyn_model = CfgNav5::kDynPortable;
  nav5_.fix_mode = 3;
  nav5_.min_elev_deg = static_cast<std::int8_t>(std::lround(profile_.elevation_mask_deg));
  gnss_.msg_ver = 0;
  gnss_.num_trk_ch_hw = static_cast<std::uint8_t>(std::min(profile_.max_channels, 255));
  gnss_.num_trk_ch_use = gnss_.num_trk_ch_hw;
  gnss_.blocks.push_back({0, 8, 16, 0, CfgGnssBlock::kEnable | (1u << 16)});  // GPS L1C/A
  rebuild_nmea();
  scratch_.reserve(8192);
}

void UbxDevice::rebuild_nmea() {
  GnssProfile p = profile_;
  p.sentences.clear();
  // Keep the profile's order of sentences, then any other one a client switched on.
  for (const auto& [id, n] : kNmeaIds) {
    if (const int r = rate({kClassNmea, id}); r > 0) p.sentences.emplace_back(n, r);
  }
  std::stable_sort(p.sentences.begin(), p.sentences.end(), [&](const auto& a, const auto& b) {
    const auto rank = [&](const std::string& s) {
      for (std::size_t i = 0; i < profile_.sentences.size(); ++i)
        if (profile_.sentences[i].first == s) return i;
      return profile_.sentences.size();
    };
    return rank(a.first) < rank(b.first);
  });
  nmea_ = std::make_unique<NmeaOutput>(p, mode_);
}

std::int64_t UbxDevice::period_ns() const {
  return static_cast<std::int64_t>(meas_rate_ms_) * nav_rate_ * 1'000'000;
}

std::optional<int> UbxDevice::take_baud_change() {
  std::optional<int> b = pending_baud_;
  pending_baud_.reset();
  return b;
}

int UbxDevice::rate(MsgId id, std::uint8_t port) const {
  const auto it = rates_.find(key(id));
  return it == rates_.end() || port >= kNumPorts ? 0 : it->second[port];
}

void UbxDevice::set_rate(MsgId id, std::uint8_t port, int r) {
  if (port < kNumPorts) rates_[key(id)][port] = static_cast<std::uint8_t>(std::clamp(r, 0, 255));
}

UbxDeviceCounters UbxDevice::counters() const {
  UbxDeviceCounters c = counters_;
  c.checksum_errors = parser_.counters().checksum_errors;
  c.too_long = parser_.counters().too_long;
  c.junk_bytes = parser_.counters().junk_bytes;
  return c;
}

// ---- Input: configuration and polls ------------------------------------------------------

void UbxDevice::receive(std::span<const std::uint8_t> bytes, std::string& replies) {
  scratch_.clear();
  parser_.feed(bytes, [&](Parser::Result r) {
    if (r != Parser::Result::kFrame) return;
    ++counters_.frames;
    if (in_proto_ & kProtoUbx) handle(parser_.cls(), parser_.id(), parser_.payload(), scratch_);
  });
  replies.append(reinterpret_cast<const char*>(scratch_.data()), scratch_.size());
}

void UbxDevice::ack(MsgId msg, std::vector<std::uint8_t>& out) {
  ++counters_.acks;
  append(AckAck{msg.cls, msg.id}, out);
}

void UbxDevice::nak(MsgId msg, std::vector<std::uint8_t>& out) {
  ++counters_.naks;
  append(AckNak{msg.cls, msg.id}, out);
}

// The commands the receiver takes: a poll (empty payload) answered by `poll`, anything else
// (and polls of messages without `poll`) handled by `set`, which acknowledges itself.
struct UbxDevice::Command {
  MsgId id;
  bool protocol27;  // protocol 27+ only (configuration interface, UBX-18010854 section 6)
  void (UbxDevice::*poll)(std::vector<std::uint8_t>& out);
  void (UbxDevice::*set)(std::span<const std::uint8_t> payload, std::vector<std::uint8_t>& out);
};

const UbxDevice::Command UbxDevice::kCommands[] = {
    {kMonVer, false, &UbxDevice::poll_mon_ver, nullptr},
    {kMonHw, false, &UbxDevice::poll_mon_hw, nullptr},
    {kCfgPrt, false, nullptr, &UbxDevice::handle_cfg_prt},
    {kCfgMsg, false, nullptr, &UbxDevice::handle_cfg_msg},
    {kCfgRate, false, &UbxDevice::poll_cfg_rate, &UbxDevice::handle_cfg_rate},
    {kCfgNav5, false, &UbxDevice::poll_cfg_nav5, &UbxDevice::handle_cfg_nav5},
    {kCfgGnss, false, &UbxDevice::poll_cfg_gnss, &UbxDevice::handle_cfg_gnss},
    {kCfgCfg, false, nullptr, &UbxDevice::handle_cfg_cfg},
    {kCfgRst, false, nullptr, &UbxDevice::handle_cfg_rst},
    {kCfgValset, true, nullptr, &UbxDevice::handle_valset},
    {kCfgValget, true, nullptr, &UbxDevice::handle_valget},
    {kCfgValdel, true, nullptr, &UbxDevice::handle_valdel},
};

void UbxDevice::handle(std::uint8_t cls, std::uint8_t id, std::span<const std::uint8_t> p,
                       std::vector<std::uint8_t>& out) {
  const MsgId msg{cls, id};
  const bool protocol27 = profile_.ubx->protver >= "27";
  for (const Command& c : kCommands) {
    if (!(c.id == msg) || (c.protocol27 && !protocol27)) continue;
    if (p.empty() && c.poll) {
      ++counters_.polls;
      return (this->*c.poll)(out);
    }
    if (c.set) return (this->*c.set)(p, out);
    break;
  }
  if (cls != kClassCfg) {
    // A poll of an output message is answered with the latest epoch's message.
    if (p.empty() && output_message(msg, out)) ++counters_.polls;
    return;
  }
  nak(msg, out);  // a configuration message this receiver does not know
}

void UbxDevice::poll_mon_ver(std::vector<std::uint8_t>& out) {
  const UbxSettings& u = *profile_.ubx;
  append(MonVer{u.sw_version, u.hw_version, u.extensions}, out);
}

void UbxDevice::poll_mon_hw(std::vector<std::uint8_t>& out) {
  MonHw hw;
  hw.a_status = MonHw::kAntOk;
  hw.a_power = 1;
  hw.noise_per_ms = 85;
  hw.agc_cnt = 5000;
  append(hw, out);
}

void UbxDevice::handle_cfg_prt(std::span<const std::uint8_t> p, std::vector<std::uint8_t>& out) {
  CfgPrtPoll poll;
  CfgPrt set;
  if (decode(p, poll)) {
    ++counters_.polls;
    CfgPrt r;
    r.port_id = poll.has_port_id ? poll.port_id : port_id_;
    r.mode = CfgPrt::kMode8N1;
    r.baud_rate = static_cast<std::uint32_t>(baud_);
    r.in_proto_mask = in_proto_;
    r.out_proto_mask = out_proto_;
    append(r, out);
    return ack(kCfgPrt, out);
  }
  if (!decode(p, set) || (set.port_id != port_id_ && set.port_id != kPortUsb))
    return nak(kCfgPrt, out);
  in_proto_ = set.in_proto_mask;
  out_proto_ = set.out_proto_mask;
  if (set.baud_rate != 0 && static_cast<int>(set.baud_rate) != baud_) {
    baud_ = static_cast<int>(set.baud_rate);
    pending_baud_ = baud_;  // after the acknowledgement, as on the hardware
  }
  ack(kCfgPrt, out);
}

void UbxDevice::handle_cfg_msg(std::span<const std::uint8_t> p, std::vector<std::uint8_t>& out) {
  CfgMsgPoll poll;
  CfgMsgCurrentPort cur;
  CfgMsg all;
  if (decode(p, poll)) {
    ++counters_.polls;
    CfgMsg r;
    r.msg_class = poll.msg_class;
    r.msg_id = poll.msg_id;
    for (std::uint8_t port = 0; port < kNumPorts; ++port)
      r.rate[port] = static_cast<std::uint8_t>(rate({poll.msg_class, poll.msg_id}, port));
    append(r, out);
    return ack(kCfgMsg, out);
  }
  // The 3-byte form sets the rate on the port the command came in on, the 8-byte form on all.
  std::optional<MsgId> change;
  if (decode(p, cur)) change = MsgId{cur.msg_class, cur.msg_id};
  else if (decode(p, all)) change = MsgId{all.msg_class, all.msg_id};
  if (!change) return nak(kCfgMsg, out);
  const MsgId target = *change;
  // The receiver takes a rate for any message of its output classes (gpsd also sets e.g.
  // NAV-TIMELS and NMEA GBS); it sends those it produces. Other classes are refused.
  constexpr std::uint8_t kOutputClasses[] = {kClassNav, kClassRxm, kClassInf, kClassMon,
                                             kClassTim, kClassEsf, kClassHnr, kClassSec,
                                             kClassNmea, kClassPubx};
  if (std::find(std::begin(kOutputClasses), std::end(kOutputClasses), target.cls) ==
      std::end(kOutputClasses))
    return nak(kCfgMsg, out);
  if (p.size() == CfgMsgCurrentPort::kPayloadSize)
    set_rate(target, port_id_, cur.rate);
  else
    for (std::uint8_t port = 0; port < kNumPorts; ++port) set_rate(target, port, all.rate[port]);
  if (target.cls == kClassNmea) rebuild_nmea();
  ack(kCfgMsg, out);
}

void UbxDevice::poll_cfg_rate(std::vector<std::uint8_t>& out) {
  append(CfgRate{meas_rate_ms_, nav_rate_, time_ref_}, out);
  ack(kCfgRate, out);
}

void UbxDevice::handle_cfg_rate(std::span<const std::uint8_t> p, std::vector<std::uint8_t>& out) {
  CfgRate r;
  // Measurement rate 25 Hz at most (40 ms), navigation rate at least one measurement.
  if (!decode(p, r) || r.meas_rate_ms < 40 || r.nav_rate_cycles < 1 || r.nav_rate_cycles > 127 ||
      r.time_ref > CfgRate::kTimeRefGalileo)
    return nak(kCfgRate, out);
  meas_rate_ms_ = r.meas_rate_ms;
  nav_rate_ = r.nav_rate_cycles;
  time_ref_ = r.time_ref;
  ack(kCfgRate, out);
}

void UbxDevice::poll_cfg_nav5(std::vector<std::uint8_t>& out) {
  append(nav5_, out);
  ack(kCfgNav5, out);
}

void UbxDevice::handle_cfg_nav5(std::span<const std::uint8_t> p, std::vector<std::uint8_t>& out) {
  CfgNav5 n;
  if (!decode(p, n)) return nak(kCfgNav5, out);
  if (n.mask & CfgNav5::kMaskDyn) nav5_.dyn_model = n.dyn_model;
  if (n.mask & CfgNav5::kMaskMinEl) nav5_.min_elev_deg = n.min_elev_deg;
  if (n.mask & CfgNav5::kMaskPosFixMode) nav5_.fix_mode = n.fix_mode;
  ack(kCfgNav5, out);
}

void UbxDevice::poll_cfg_gnss(std::vector<std::uint8_t>& out) {
  append(gnss_, out);
  ack(kCfgGnss, out);
}

// CFG-GNSS, CFG-CFG and (protocol 27+) CFG-VALDEL are acknowledged when well formed: the
// emulated receiver tracks GPS L1 C/A whatever is enabled, and keeps nothing beyond its running
// (RAM) configuration, so clearing, saving, loading or deleting stored layers changes nothing.
template <class Msg>
void UbxDevice::accept_well_formed(std::span<const std::uint8_t> p, std::vector<std::uint8_t>& out) {
  Msg m;
  decode(p, m) ? ack(Msg::kMsg, out) : nak(Msg::kMsg, out);
}

void UbxDevice::handle_cfg_gnss(std::span<const std::uint8_t> p, std::vector<std::uint8_t>& out) {
  accept_well_formed<CfgGnss>(p, out);
}

void UbxDevice::handle_cfg_cfg(std::span<const std::uint8_t> p, std::vector<std::uint8_t>& out) {
  accept_well_formed<CfgCfg>(p, out);
}

void UbxDevice::handle_valdel(std::span<const std::uint8_t> p, std::vector<std::uint8_t>& out) {
  accept_well_formed<CfgValdel>(p, out);
}

void UbxDevice::handle_cfg_rst(std::span<const std::uint8_t> p, std::vector<std::uint8_t>& out) {
  // Not acknowledged (interface description, CFG-RST). The fix returns after the part's
  // time to first fix (u-blox M8 data sheet: hot start 1 s, cold start 26 s; a warm start
  // still has to collect the ephemerides, about as long).
  CfgRst r;
  if (!decode(p, r)) return nak(kCfgRst, out);
  const double outage_s = r.nav_bbr_mask == CfgRst::kHotStart    ? 1.0
                          : r.nav_bbr_mask == CfgRst::kWarmStart ? 25.0
                                                                 : 26.0;
  restart_until_ = last_fix_.t.plus_s(outage_s);
}

void UbxDevice::handle_valset(std::span<const std::uint8_t> p, std::vector<std::uint8_t>& out) {
  CfgValset v;
  const auto nak = [&] { UbxDevice::nak(kCfgValset, out); };
  if (!decode(p, v)) return nak();
  // All or nothing: every key must be known and its value valid before any is applied.
  for (const CfgKeyValue& kv : v.values) {
    bool known = kv.key_id == cfgkey::kRateMeas || kv.key_id == cfgkey::kRateNav ||
                 kv.key_id == cfgkey::kRateTimeref || kv.key_id == cfgkey::kUart1Baudrate ||
                 kv.key_id == cfgkey::kUart1outprotNmea || kv.key_id == cfgkey::kUart1outprotUbx ||
                 kv.key_id == cfgkey::kUart1inprotNmea || kv.key_id == cfgkey::kUart1inprotUbx ||
                 kv.key_id == cfgkey::kNavspgDynmodel;
    known = known || msgout_key(kv.key_id).has_value() || kv.key_id == cfgkey::kUsbinprotUbx ||
            kv.key_id == cfgkey::kUsbinprotNmea || kv.key_id == cfgkey::kUsboutprotUbx ||
            kv.key_id == cfgkey::kUsboutprotNmea;
    if (!known) return nak();
    if (kv.key_id == cfgkey::kRateMeas && kv.value < 40) return nak();  // 25 Hz at most, as CFG-RATE
    if (kv.key_id == cfgkey::kRateNav && (kv.value < 1 || kv.value > 127)) return nak();
  }
  for (const CfgKeyValue& kv : v.values) {
    const auto flag = [&](std::uint16_t& mask, std::uint16_t bit) {
      mask = static_cast<std::uint16_t>(kv.value ? (mask | bit) : (mask & ~bit));
    };
    if (kv.key_id == cfgkey::kRateMeas) meas_rate_ms_ = static_cast<std::uint16_t>(kv.value);
    if (kv.key_id == cfgkey::kRateNav) nav_rate_ = static_cast<std::uint16_t>(kv.value);
    if (kv.key_id == cfgkey::kRateTimeref) time_ref_ = static_cast<std::uint16_t>(kv.value);
    if (kv.key_id == cfgkey::kNavspgDynmodel) nav5_.dyn_model = static_cast<std::uint8_t>(kv.value);
    if (kv.key_id == cfgkey::kUart1outprotNmea) flag(out_proto_, kProtoNmea);
    if (kv.key_id == cfgkey::kUart1outprotUbx) flag(out_proto_, kProtoUbx);
    if (kv.key_id == cfgkey::kUart1inprotNmea) flag(in_proto_, kProtoNmea);
    if (kv.key_id == cfgkey::kUart1inprotUbx) flag(in_proto_, kProtoUbx);
    if (kv.key_id == cfgkey::kUart1Baudrate && static_cast<int>(kv.value) != baud_) {
      baud_ = static_cast<int>(kv.value);
      pending_baud_ = baud_;
    }
    if (const auto mk = msgout_key(kv.key_id)) set_rate(mk->first, mk->second, static_cast<int>(kv.value));
    // The USB port is not emulated: its protocol masks are kept for VALGET only.
    if ((kv.key_id >> 16) == 0x1077 || (kv.key_id >> 16) == 0x1078) usb_proto_keys_[kv.key_id] = kv.value;
  }
  ack(kCfgValset, out);
}

std::optional<std::uint64_t> UbxDevice::value_of(std::uint32_t k) const {
  if (k == cfgkey::kRateMeas) return meas_rate_ms_;
  if (k == cfgkey::kRateNav) return nav_rate_;
  if (k == cfgkey::kRateTimeref) return time_ref_;
  if (k == cfgkey::kNavspgDynmodel) return nav5_.dyn_model;
  if (k == cfgkey::kUart1Baudrate) return static_cast<std::uint64_t>(baud_);
  if (k == cfgkey::kUart1outprotNmea) return (out_proto_ & kProtoNmea) ? 1 : 0;
  if (k == cfgkey::kUart1outprotUbx) return (out_proto_ & kProtoUbx) ? 1 : 0;
  if (k == cfgkey::kUart1inprotNmea) return (in_proto_ & kProtoNmea) ? 1 : 0;
  if (k == cfgkey::kUart1inprotUbx) return (in_proto_ & kProtoUbx) ? 1 : 0;
  if (const auto mk = msgout_key(k)) return static_cast<std::uint64_t>(rate(mk->first, mk->second));
  if ((k >> 16) == 0x1077 || (k >> 16) == 0x1078) {
    const auto it = usb_proto_keys_.find(k);
    return it != usb_proto_keys_.end() ? it->second : 1;  // USB takes UBX and NMEA by default
  }
  return std::nullopt;
}

void UbxDevice::handle_valget(std::span<const std::uint8_t> p, std::vector<std::uint8_t>& out) {
  CfgValgetRequest req;
  const auto nak = [&] { UbxDevice::nak(kCfgValget, out); };
  if (!decode(p, req)) return nak();
  // The default layer answers the power-up configuration; RAM, BBR and flash the running one
  // (nothing here is saved apart from it).
  std::unique_ptr<UbxDevice> defaults;
  if (req.layer == kLayerDefault) defaults = std::make_unique<UbxDevice>(profile_, mode_, nav_);
  const UbxDevice& from = defaults ? *defaults : *this;
  CfgValgetResponse r;
  r.layer = req.layer;
  r.position = req.position;
  for (std::uint32_t k : req.keys) {
    const std::optional<std::uint64_t> v = from.value_of(k);
    if (!v) return nak();
    r.values.push_back({k, *v});
  }
  ++counters_.polls;
  append(r, out);
  ack(kCfgValget, out);
}

// ---- Output --------------------------------------------------------------------------------

bool UbxDevice::output_message(MsgId id, std::vector<std::uint8_t>& out) const {
  const OutputMessage* m = output_of(id);
  if (m == nullptr) return false;
  m->emit(EpochView(last_fix_, last_meas_, nav_, mode_, lists_), out);
  return true;
}
void UbxDevice::encode_epoch(const ReceiverFix& fix_in, const EpochMeasurements& meas,
                             std::int64_t epoch_index, std::string& out) {
  last_fix_ = fix_in;
  last_meas_ = meas;
  if (restarting(fix_in.t)) {  // after CFG-RST: searching, no fix and no satellites yet
    reset_keeping_storage(last_fix_, &ReceiverFix::satellites).t = fix_in.t;
    last_meas_.sats.clear();
  }
  if (out_proto_ & kProtoUbx) {
    scratch_.clear();
    const EpochView view(last_fix_, last_meas_, nav_, mode_, lists_);
    for (const OutputMessage& m : kOutputs) {
      const int r = rate(m.id);
      if (r > 0 && epoch_index % r == 0) m.emit(view, scratch_);
    }
    out.append(reinterpret_cast<const char*>(scratch_.data()), scratch_.size());
  }
  if (out_proto_ & kProtoNmea) nmea_->encode(last_fix_, epoch_index, out);
}

// ---- The device of a profile ----------------------------------------------------------------

namespace {
class NmeaDevice final : public GnssDevice {
 public:
  NmeaDevice(const GnssProfile& p, ReceiverMode mode)
      : out_(p, mode), period_ns_(std::llround(1e9 / p.rate_hz)) {}
  void encode_epoch(const ReceiverFix& fix, const EpochMeasurements&, std::int64_t epoch_index,
                    std::string& out) override {
    out_.encode(fix, epoch_index, out);
  }
  std::int64_t period_ns() const override { return period_ns_; }

 private:
  NmeaOutput out_;
  std::int64_t period_ns_;
};
}  // namespace

std::unique_ptr<GnssDevice> make_gnss_device(const GnssProfile& profile, ReceiverMode mode,
                                             const NavData& nav) {
  if (profile.ubx) return std::make_unique<UbxDevice>(profile, mode, nav);
  return std::make_unique<NmeaDevice>(profile, mode);
}

}  // namespace navemu
