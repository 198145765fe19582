#include "emulator/ubx_outputs.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/sat_table.hpp"
#include "core/signal.hpp"
#include "models/geodesy.hpp"
#include "models/reuse.hpp"
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

}  // namespace

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

namespace {

// ---- Output messages -------------------------------------------------------------------------

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

// High-precision geodetic position (F9 HPG 1.13 description, UBX-NAV-HPPOSLLH): the 1e-7 deg
// and mm parts as NAV-POSLLH has them, the remainders in 1e-9 deg (-99..99) and 0.1 mm (-9..9),
// accuracies in 0.1 mm.
void emit_nav_hpposllh(const EpochView& e, std::vector<std::uint8_t>& out) {
  const Geodetic& p = e.fix.position;
  NavHpposllh m;
  m.flags = e.valid ? 0 : NavHpposllh::kInvalidLlh;
  m.i_tow_ms = e.i_tow;
  const auto split = [](double v, double unit_per_hp, auto& whole, auto& hp) {
    const double hp_units = std::round(v);
    whole = clamp_cast<std::int32_t>(std::trunc(hp_units / unit_per_hp));
    hp = static_cast<std::int8_t>(hp_units - static_cast<double>(whole) * unit_per_hp);
  };
  split(p.lon_deg * 1e9, 100.0, m.lon_1e7deg, m.lon_hp_1e9deg);
  split(p.lat_deg * 1e9, 100.0, m.lat_1e7deg, m.lat_hp_1e9deg);
  split(p.h_m * 1e4, 10.0, m.height_mm, m.height_hp_0p1mm);
  split((p.h_m - e.separation_m) * 1e4, 10.0, m.h_msl_mm, m.h_msl_hp_0p1mm);
  m.h_acc_0p1mm = clamp_cast<std::uint32_t>(e.acc.h_m * 1e4);
  m.v_acc_0p1mm = clamp_cast<std::uint32_t>(e.acc.v_m * 1e4);
  append(m, out);
}

// The RF front end as MON-HW (u-blox 8, UBX-13003221 "UBX-MON-HW") and MON-RF (F9, one block per
// band) report it. navemu models no RF interference yet, so these are an active antenna's
// quiet-sky readings: antenna OK and powered, no CW jamming indicated (jamInd well below the
// level the M8 description's "Jamming/interference indicator" section treats as interference),
// jamming state "ok", noise and AGC mid-range as real receivers in open sky report them.
struct QuietFrontEnd {
  std::uint16_t noise_per_ms = 88;
  std::uint16_t agc_cnt = 5200;  // of 8191
  std::uint8_t jam_ind = 6;      // of 255
};
constexpr QuietFrontEnd kFrontEnd;

void emit_mon_hw(const EpochView&, std::vector<std::uint8_t>& out) {
  MonHw m;
  m.a_status = MonHw::kAntOk;
  m.a_power = 1;
  m.noise_per_ms = kFrontEnd.noise_per_ms;
  m.agc_cnt = kFrontEnd.agc_cnt;
  m.jam_ind = kFrontEnd.jam_ind;
  m.flags = 1 << 2;  // jammingState 1: ok, no significant jamming
  append(m, out);
}

void emit_mon_rf(const EpochView& e, std::vector<std::uint8_t>& out) {
  MonRf& m = e.lists.rf;
  m.blocks.resize(2);  // L1 and L2 front ends of the ZED-F9P
  for (std::uint8_t b = 0; b < 2; ++b) {
    MonRfBlock& k = m.blocks[b];
    k.block_id = b;
    k.flags = 1;  // jammingState ok
    k.ant_status = MonHw::kAntOk;
    k.ant_power = 1;
    k.noise_per_ms = kFrontEnd.noise_per_ms;
    k.agc_cnt = kFrontEnd.agc_cnt;
    k.jam_ind = kFrontEnd.jam_ind;
  }
  append(m, out);
}

}  // namespace

namespace {

// Every UBX output message the device can produce, in the order of one epoch's output: raw
// measurement data first (it is measured before the solution), the navigation messages, the
// monitor messages, and NAV-EOE closing the epoch (u-blox interface description, "NAV-EOE").
// Names (profiles' `ubx: messages`) are those of the message descriptions (ubx::find_message).
constexpr UbxOutput kOutputs[] = {
    {kRxmRawx, "UBX_RXM_RAWX", true, true, &emit_rxm_rawx},
    {kRxmSfrbx, "UBX_RXM_SFRBX", true, true, &emit_rxm_sfrbx},
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
    {kNavHpposllh, "UBX_NAV_HPPOSLLH", false, true, &emit_nav_hpposllh},
    {kMonHw, "UBX_MON_HW", true, true, &emit_mon_hw},
    {kMonRf, "UBX_MON_RF", false, true, &emit_mon_rf},
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
                      const NavData& nav, ReceiverMode mode, UbxListScratch& lists,
                      std::vector<std::uint8_t>& out) {
  static_assert(std::size(kOutputs) <= 64, "one bit per output message");
  const EpochView view(fix, meas, nav, mode, lists);
  for (std::size_t i = 0; i < std::size(kOutputs); ++i)
    if (due >> i & 1u) kOutputs[i].emit(view, out);
}

}  // namespace navemu
