#include "emulator/ubx_aiding.hpp"

#include <algorithm>
#include <cmath>
#include <span>

#include "emulator/ubx_outputs.hpp"
#include "models/ephemeris.hpp"
#include "protocols/gps_lnav.hpp"
#include "protocols/ubx_messages.hpp"

namespace navemu {

using namespace ubx;

namespace {

// A subframe's words 3..10 as AID-ALM/AID-EPH carry them: parity removed, the 24 data bits
// (bits 29..6 of the RXM-SFRBX form, protocols/gps_lnav.hpp) in bits 0..23.
std::array<std::uint32_t, 8> data_words(const lnav::LnavSubframe& w) {
  std::array<std::uint32_t, 8> d{};
  for (std::size_t i = 0; i < d.size(); ++i) d[i] = (w[i + 2] >> 6) & 0xFFFFFFu;
  return d;
}

AidEph aid_eph(int svid, const EpochMeasurements& meas) {
  AidEph m;
  m.svid = static_cast<std::uint32_t>(svid);
  const SatId sat(GnssSystem::kGps, svid);
  const auto s = std::find_if(meas.sats.begin(), meas.sats.end(),
                              [&](const SatMeasurement& x) { return x.sat == sat && x.eph != nullptr; });
  if (s == meas.sats.end()) return m;
  // Subframes 1-3 of the record in use; the TOW count of the HOW "is not valid" (UBX-AID-EPH).
  const lnav::LnavEphemeris eph = to_lnav(*s->eph);
  const auto subframe = [&](int id) { return lnav::lnav_subframe(id, 0, eph, {}, 1); };
  const lnav::LnavSubframe sf1 = subframe(1);
  m.how = (sf1[1] >> 6) & 0xFFFFFFu;
  m.has_data = true;
  m.sf1d = data_words(sf1);
  m.sf2d = data_words(subframe(2));
  m.sf3d = data_words(subframe(3));
  return m;
}

}  // namespace

void append_aid_ini(const ReceiverFix& fix, const EpochMeasurements& meas, std::vector<std::uint8_t>& out) {
  AidIni m;
  if (fix.fix != FixType::kNone) {
    m.ecef_x_or_lat = static_cast<std::int32_t>(std::llround(fix.p_ecef_m.x() * 100.0));
    m.ecef_y_or_lon = static_cast<std::int32_t>(std::llround(fix.p_ecef_m.y() * 100.0));
    m.ecef_z_or_alt = static_cast<std::int32_t>(std::llround(fix.p_ecef_m.z() * 100.0));
    m.pos_acc_cm = static_cast<std::uint32_t>(std::llround(std::hypot(fix.sigma_h_m, fix.sigma_v_m) * 100.0));
    const WeekTow wt = to_week_tow(fix.t);
    const double ms = std::floor(wt.tow_s * 1000.0);
    m.wno_or_date = static_cast<std::uint16_t>(wt.week);
    m.tow_or_time_ms = static_cast<std::uint32_t>(ms);
    m.tow_ns = static_cast<std::int32_t>(std::llround((wt.tow_s * 1000.0 - ms) * 1e6));
    m.t_acc_ns = 20;  // as NAV-PVT tAcc
    m.clk_d_or_freq = static_cast<std::int32_t>(std::llround(meas.rx_clock_drift_sps * 1e9));
    m.clk_d_acc_or_freq_acc = 1;  // NAV-CLOCK fAcc 0.5 ns/s, rounded up
    m.flags = AidIni::kPos | AidIni::kTime | AidIni::kClockD;
  }
  append(m, out);
}

void append_aid_hui(const NavData& nav, GpsTime t, std::vector<std::uint8_t>& out) {
  AidHui m;
  for (int n = 1; n <= kAidSatellites; ++n)
    if (select_ephemeris(nav, SatId(GnssSystem::kGps, n), t) != nullptr) m.health |= 1u << (n - 1);
  const WeekTow wt = to_week_tow(t);
  const lnav::LnavIonoUtc u = broadcast_iono_utc(nav, wt.week, leap_seconds_at_gps(t, nav.leap_seconds));
  m.utc_a0_s = u.a0_s;
  m.utc_a1_sps = u.a1_sps;
  m.utc_tow_s = static_cast<std::int32_t>(u.tot_s);
  m.utc_wnt = static_cast<std::int16_t>(u.wnt);
  m.utc_ls_s = static_cast<std::int16_t>(u.dt_ls_s);
  m.utc_wnf = static_cast<std::int16_t>(u.wn_lsf);
  m.utc_dn = static_cast<std::int16_t>(u.dn);
  m.utc_lsf_s = static_cast<std::int16_t>(u.dt_lsf_s);
  for (std::size_t i = 0; i < 4; ++i) {
    m.klob_a[i] = static_cast<float>(u.alpha[i]);
    m.klob_b[i] = static_cast<float>(u.beta[i]);
  }
  m.flags = (m.health != 0 ? AidHui::kHealthValid : 0) | AidHui::kUtcValid |
            (nav.klobuchar ? AidHui::kKlobValid : 0);
  append(m, out);
}

void append_aid_alm(int svid, const NavData& nav, GpsTime t, std::vector<std::uint8_t>& out) {
  AidAlm m;
  m.svid = static_cast<std::uint32_t>(svid);
  if (const GpsEphemeris* e = select_ephemeris(nav, SatId(GnssSystem::kGps, svid), t)) {
    const WeekTow wt = to_week_tow(t);
    const double toa_s = std::floor(wt.tow_s / 4096.0) * 4096.0;
    const lnav::LnavEphemeris eph = to_lnav(*e);
    const lnav::LnavAlmanacEntry entry = lnav::lnav_almanac_from_ephemeris(eph, toa_s, wt.week);
    // Where the satellite's almanac is broadcast (IS-GPS-200 Table 20-V): subframe 5 pages
    // 1-24 for SV 1-24, subframe 4 pages 2-5 and 7-10 for SV 25-32.
    const int subframe = svid <= 24 ? 5 : 4;
    const int page = svid <= 24 ? svid : svid <= 28 ? svid - 23 : svid - 22;
    lnav::LnavAlmanac alm;
    alm.entries = std::span(&entry, 1);
    alm.toa_s = toa_s;
    alm.week = wt.week;
    m.week = static_cast<std::uint32_t>(wt.week);
    m.has_data = true;
    m.dwrd = data_words(lnav::lnav_subframe(subframe, 0, eph, {}, page, alm));
  }
  append(m, out);
}

void append_aid_eph(int svid, const EpochMeasurements& meas, std::vector<std::uint8_t>& out) {
  append(aid_eph(svid, meas), out);
}

void append_mga_dbd_dump(const EpochMeasurements& meas, std::vector<std::uint8_t>& out) {
  std::uint32_t sent = 0;
  std::vector<std::uint8_t> eph;
  for (const SatMeasurement& s : meas.sats) {
    if (s.sat.system() != GnssSystem::kGps || s.eph == nullptr) continue;
    eph.clear();
    append(aid_eph(s.sat.number(), meas), eph);
    MgaDbd d;
    d.data.push_back(1);  // GPS LNAV ephemeris
    // The AID-EPH frame's payload: after the 6-byte header, before the 2-byte checksum.
    d.data.insert(d.data.end(), eph.begin() + 6, eph.end() - 2);
    append(d, out);
    ++sent;
  }
  MgaAck ack;
  ack.msg_id = kMgaDbd.id;
  ack.msg_payload_start = sent;
  append(ack, out);
}

}  // namespace navemu
