#include "models/constellation.hpp"

#include <array>
#include <cmath>
#include <cstdint>
#include <string>

#include "models/geodesy.hpp"
#include "models/orbit.hpp"

namespace navemu {

namespace {

constexpr double kTwoPi = 2.0 * 3.14159265358979323846;

// Baseline 24-slot constellation of the GPS SPS Performance Standard: slot assignments as of
// the defined epoch, right ascension of the ascending node (RAAN) and argument of latitude,
// degrees (SPS PS Table 3.2-1 of the 4th/5th editions; Table 3-1 of the 3rd edition, 2001).
struct Slot {
  const char* name;
  double raan_deg;
  double arg_lat_deg;
};
constexpr std::array<Slot, 24> kSlots{{
    {"A1", 272.847, 268.126}, {"A2", 272.847, 161.786}, {"A3", 272.847, 11.676},
    {"A4", 272.847, 41.806},  {"B1", 332.847, 80.956},  {"B2", 332.847, 173.336},
    {"B3", 332.847, 309.976}, {"B4", 332.847, 204.376}, {"C1", 32.847, 111.876},
    {"C2", 32.847, 11.796},   {"C3", 32.847, 339.666},  {"C4", 32.847, 241.556},
    {"D1", 92.847, 135.226},  {"D2", 92.847, 265.446},  {"D3", 92.847, 35.156},
    {"D4", 92.847, 167.356},  {"E1", 152.847, 197.046}, {"E2", 152.847, 302.596},
    {"E3", 152.847, 66.066},  {"E4", 152.847, 333.686}, {"F1", 212.847, 238.886},
    {"F2", 212.847, 345.226}, {"F3", 212.847, 105.206}, {"F4", 212.847, 135.346},
}};

// Defined epoch of the table: 0000Z 1 July 1993 (UTC). GPS - UTC was 9 s from that day on, so
// in GPS time it is 1993-07-01 00:00:09, 4925 days after 1980-01-06: 425 520 009 s
// (GPS week 703, time of week 345 609 s).
constexpr std::int64_t kRefEpochGpsS = 4925LL * 86400LL + 9LL;

// Greenwich hour angle at the defined epoch: 18 h 36 m 14.4 s = 279.06 deg. The table's RAAN
// is inertial (FK5/J2000); the node's geographic longitude is RAAN - GHA.
constexpr double kGhaRefDeg = (18.0 + 36.0 / 60.0 + 14.4 / 3600.0) * 15.0;

// Reference orbit (SPS PS reference orbit parameters): semi-major axis 26 559.710 km,
// eccentricity 0, inclination 55 deg, argument of perigee 0.
constexpr double kSemiMajorAxis_m = 26'559'710.0;
constexpr double kInclinationDeg = 55.0;

// Nodal regression of the nominal orbits: -4.4874e-7 deg/s (the SPS PS nominal-constellation
// almanac, 3rd ed. Table A-2-1; the J2 rate -1.5 n J2 (Re/a)^2 cos i for this orbit).
constexpr double kRaanRate_radps = -4.4874e-7 * kDegToRad;

// The nominal slots keep their ground tracks: each satellite makes exactly two revolutions
// while the Earth turns once relative to the regressing node, so the Earth-fixed geometry
// repeats every 2 pi / (omega_e - Omega_dot) (a sidereal day less ~9 s). The argument of
// latitude rate is therefore 2 (omega_e - Omega_dot); the difference from the Keplerian mean
// motion of A goes into delta_n, as real broadcast ephemerides carry the J2 along-track rate.
constexpr double kArgLatRate_radps = 2.0 * (kOmegaEarth_radps - kRaanRate_radps);

constexpr std::int64_t kToeSpacingS = 7200;  // GPS 2-hour boundaries

double wrap_pi(double a) { return std::remainder(a, kTwoPi); }

std::int64_t floor_div(std::int64_t a, std::int64_t b) {
  std::int64_t q = a / b;
  if ((a % b != 0) && ((a < 0) != (b < 0))) --q;
  return q;
}

// A nominal orbit as a closed form of time: the node's Earth-fixed longitude and the mean
// anomaly at a reference epoch, moving at constant rates (the J2 regression of the node, the
// mean motion), so that the records of any toe describe the same orbit and a renewal is exact.
struct NominalOrbit {
  double a_m = 0.0, e = 0.0, i_rad = 0.0, omega_rad = 0.0;  // omega: argument of perigee
  double node_lon_ref_rad = 0.0, m_ref_rad = 0.0;           // at ref_gps_s
  double node_rate_radps = 0.0;                             // inertial (Omega_dot)
  double mean_motion_radps = 0.0;                           // n0 + delta_n
  std::int64_t ref_gps_s = 0;
};

// The Keplerian record of `orbit` at toe for a system's constants, with toe_tow_s in the
// system's own week (IS-GPS-200 Table 20-IV: Omega_k = Omega0 + (Omega_dot - omega_e) tk -
// omega_e toe, which at tk = 0 is the node's longitude at toe).
void set_kepler(const NominalOrbit& orbit, std::int64_t toe_gps_s, double toe_tow_s, const KeplerConstants& k,
                KeplerEphemeris& e) {
  const double dt = static_cast<double>(toe_gps_s - orbit.ref_gps_s);
  const double node_lon = wrap_pi(orbit.node_lon_ref_rad + (orbit.node_rate_radps - k.omega_earth_radps) * dt);
  e.sqrt_a_sqrtm = std::sqrt(orbit.a_m);
  e.e = orbit.e;
  e.i0_rad = orbit.i_rad;
  e.omega_rad = orbit.omega_rad;
  e.m0_rad = wrap_pi(orbit.m_ref_rad + orbit.mean_motion_radps * dt);
  e.delta_n_radps = orbit.mean_motion_radps - std::sqrt(k.mu_m3ps2 / (orbit.a_m * orbit.a_m * orbit.a_m));
  e.omega0_rad = wrap_pi(node_lon + k.omega_earth_radps * toe_tow_s);
  e.omega_dot_radps = orbit.node_rate_radps;
  e.idot_radps = 0.0;
}

// J2 regression of the node of a near-circular orbit, -1.5 n J2 (Re/a)^2 cos i / (1 - e^2)^2
// (Vallado, Fundamentals of Astrodynamics, 4th ed., eq. 9-41), with the WGS 84 J2 and radius.
double node_regression_radps(double a_m, double e, double i_rad) {
  constexpr double kJ2 = 1.08262668e-3, kRe_m = 6378137.0;
  const double n = std::sqrt(kGpsMu_m3ps2 / (a_m * a_m * a_m));
  const double p = a_m * (1.0 - e * e);
  return -1.5 * n * kJ2 * (kRe_m / p) * (kRe_m / p) * std::cos(i_rad);
}

// The reference epoch of the other systems' nominal slots: 2020-01-01 00:00:00 GPS time. Their
// positions in the slots at that instant are nominal, not those of any satellite then.
constexpr std::int64_t kNominalRefGpsS = 14609LL * 86400LL;  // days from 1980-01-06

// A Walker delta constellation T/P/F (Walker 1984): P planes with nodes 360/P apart, T/P
// satellites per plane spaced 360 P/T in argument of latitude, plane j's satellites ahead by
// j 360 F/T. Circular orbits whose ground tracks drift with the node's regression.
NominalOrbit walker_slot(double a_m, double i_deg, int t, int p, int f, int plane, int index) {
  NominalOrbit o;
  o.a_m = a_m;
  o.i_rad = i_deg * kDegToRad;
  o.node_lon_ref_rad = wrap_pi(plane * kTwoPi / p);
  o.m_ref_rad = wrap_pi(index * kTwoPi * p / t + plane * kTwoPi * f / t);
  o.node_rate_radps = node_regression_radps(a_m, 0.0, o.i_rad);
  o.mean_motion_radps = std::sqrt(kGpsMu_m3ps2 / (a_m * a_m * a_m));
  o.ref_gps_s = kNominalRefGpsS;
  return o;
}

// A geosynchronous orbit whose ground track stays put: one turn per sidereal day relative to
// its regressing node. The node's longitude at the reference epoch is `node_lon_deg`, and the
// satellite is at mean anomaly `m_deg` then.
constexpr double kGeoA_m = 42'164'170.0;  // (mu / omega_e^2)^(1/3)
NominalOrbit geosynchronous(double e, double i_deg, double omega_deg, double node_lon_deg, double m_deg) {
  NominalOrbit o;
  o.a_m = kGeoA_m;
  o.e = e;
  o.i_rad = i_deg * kDegToRad;
  o.omega_rad = omega_deg * kDegToRad;
  o.node_lon_ref_rad = wrap_pi(node_lon_deg * kDegToRad);
  o.m_ref_rad = wrap_pi(m_deg * kDegToRad);
  o.node_rate_radps = node_regression_radps(kGeoA_m, e, o.i_rad);
  o.mean_motion_radps = kOmegaEarth_radps - o.node_rate_radps;
  o.ref_gps_s = kNominalRefGpsS;
  return o;
}

// The toes of a renewal at t: on the system's 2-hour boundaries (offset_s: where its own time's
// boundaries fall in GPS time), from t - 2 h to t + 26 h, as the GPS sets.
template <class Each>
void for_each_toe(GpsTime t, std::int64_t offset_s, Each each) {
  const std::int64_t t_s = floor_div(t.ns, kNsPerS) - offset_s;
  for (std::int64_t k = floor_div(t_s, kToeSpacingS) - 1; k <= floor_div(t_s, kToeSpacingS) + 13; ++k)
    each(k, k * kToeSpacingS + offset_s);
}

// Galileo: the 24 nominal slots of the Walker 24/3/1 reference constellation at 29 599.8 km,
// 56 deg (Galileo OS SDD issue 1.1, 2.1; the almanac's reference A and i, OS SIS ICD 2.0
// 5.1.10), E01-E24 by plane and slot.
constexpr double kGalileoA_m = 29'599'800.0;
// BeiDou (BDS-SIS-ICD-B1I 3.0, 3.1): 24 MEO at 21 528 km altitude, 55 deg (Walker 24/3/1 of
// BDS-3), 3 IGSO at 35 786 km, 55 deg, 5 GEO at 58.75, 80, 110.5, 140 and 160 deg E.
constexpr double kBeidouMeoA_m = 21'528'000.0 + 6'378'137.0;
constexpr std::array<int, 24> kBeidouMeoPrns{19, 20, 21, 22, 23, 24, 25, 26, 27, 28, 29, 30,
                                             32, 33, 34, 35, 36, 37, 41, 42, 43, 44, 45, 46};
constexpr std::array<int, 3> kBeidouIgsoPrns{38, 39, 40};
struct GeoSlot {
  int prn;
  double lon_deg;
};
constexpr std::array<GeoSlot, 5> kBeidouGeo{{{1, 140.0}, {2, 80.0}, {3, 110.5}, {4, 160.0}, {5, 58.75}}};
constexpr double kBeidouIgsoNodeLonDeg = 118.0;  // where the IGSO ground tracks cross the equator

// GLONASS: 24 slots in 3 planes 120 deg apart, 8 per plane 45 deg apart, plane 2 15 deg ahead of
// plane 1 and plane 3 15 deg ahead of plane 2 (GLONASS ICD 5.1, 3.1: 64.8 deg, period 11 h 15 min
// 44 s, so a = (mu (T / 2 pi)^2)^(1/3) = 25 508 km), slots 1-8, 9-16, 17-24. Antipodal slots
// (n, n + 4 of a plane) share a frequency channel (ICD 3.3.1.1), as the IAC constellation table
// lists them.
constexpr double kGlonassA_m = 25'508'000.0;
constexpr std::array<int, 24> kGlonassChannels{1, -4, 5, 6, 1, -4, 5, 6, -2, -7, 0, -1,
                                               -2, -7, 0, -1, 4, -3, 3, 2, 4, -3, 3, 2};

// QZSS (IS-QZSS-PNT 2.2 / the QZSS orbit overview): three quasi-zenith orbits (J01-J03) of
// eccentricity 0.075, 41 deg and argument of perigee 270 deg, on one figure-of-eight ground
// track centred on 139 deg E, 8 h apart; one geostationary (J07) at 127 deg E.
constexpr double kQzoCentreLonDeg = 139.0;

// The mean anomaly at which a satellite of eccentricity e and argument of perigee omega crosses
// its ascending node (true anomaly -omega).
double mean_anomaly_at_node_deg(double e, double omega_deg) {
  const double nu = -omega_deg * kDegToRad;
  const double ecc = 2.0 * std::atan(std::sqrt((1.0 - e) / (1.0 + e)) * std::tan(nu / 2.0));
  return (ecc - e * std::sin(ecc)) / kDegToRad;
}

}  // namespace

void nominal_gps(GpsTime t, std::vector<GpsEphemeris>& out) {
  out.clear();
  for_each_toe(t, 0, [&](std::int64_t upload, std::int64_t toe_s) {
    const GpsTime toe{toe_s * kNsPerS};
    const double toe_tow = to_week_tow(toe).tow_s;
    for (const Slot& slot : kSlots) {
      // The slot's node longitude (RAAN - GHA) and argument of latitude (e = 0, omega = 0: the
      // mean anomaly) at the defined epoch.
      NominalOrbit o;
      o.a_m = kSemiMajorAxis_m;
      o.i_rad = kInclinationDeg * kDegToRad;
      o.node_lon_ref_rad = (slot.raan_deg - kGhaRefDeg) * kDegToRad;
      o.m_ref_rad = slot.arg_lat_deg * kDegToRad;
      o.node_rate_radps = kRaanRate_radps;
      o.mean_motion_radps = kArgLatRate_radps;
      o.ref_gps_s = kRefEpochGpsS;
      GpsEphemeris& e = out.emplace_back();
      set_kepler(o, toe_s, toe_tow, kepler_constants(GnssSystem::kGps), e);
      e.sat = gps_sat(static_cast<int>(&slot - kSlots.data()) + 1);
      e.toc = e.toe = toe;
      e.iode = static_cast<int>(((upload % 256) + 256) % 256);
      e.iodc = e.iode;
      e.codes_on_l2 = 1;
      e.l2p_data_flag = 0;
      e.ura_m = 2.0;
      e.health = 0;
      e.tgd_s = 0.0;
      e.transmission_tow_s = toe_tow - 7200.0;  // 2 h before toe, relative to toe's week
      e.fit_interval_h = 4.0;
      e.source = std::string("nominal slot ") + slot.name;
    }
  });
}

void nominal_galileo(GpsTime t, std::vector<GalileoEphemeris>& out) {
  out.clear();
  const KeplerConstants k = kepler_constants(GnssSystem::kGalileo);
  for_each_toe(t, 0, [&](std::int64_t upload, std::int64_t toe_s) {
    const GpsTime toe{toe_s * kNsPerS};
    const double toe_tow = to_week_tow(toe).tow_s;  // GST week and seconds = GPS's
    for (int slot = 0; slot < 24; ++slot) {
      GalileoEphemeris& e = out.emplace_back();
      set_kepler(walker_slot(kGalileoA_m, 56.0, 24, 3, 1, slot / 8, slot % 8), toe_s, toe_tow, k, e);
      e.sat = SatId(GnssSystem::kGalileo, slot + 1);
      e.toc = e.toe = toe;
      e.iod_nav = static_cast<int>(((upload % 1024) + 1024) % 1024);  // 10 bits, OS SIS ICD 5.1.9.2
      e.data_sources = (1 << 0) | (1 << 2) | (1 << 9);  // I/NAV E1-B and E5b, E5b/E1 clock (RINEX 3.05)
      e.sisa_m = 3.12;  // SISA index 107 (OS SIS ICD 5.1.12), the value of healthy satellites
      e.transmission_tow_s = toe_tow;
      e.source = "nominal slot";
    }
  });
}

void nominal_beidou(GpsTime t, std::vector<BeidouEphemeris>& out) {
  out.clear();
  const KeplerConstants k = kepler_constants(GnssSystem::kBeidou);
  for_each_toe(t, kGpsMinusBdt_s, [&](std::int64_t, std::int64_t toe_s) {
    const GpsTime toe{toe_s * kNsPerS};
    const double toe_tow = to_week_tow(toe.plus_s(-kGpsMinusBdt_s)).tow_s;  // BDT
    const auto record = [&](int prn) -> BeidouEphemeris& {
      BeidouEphemeris& e = out.emplace_back();
      e.sat = SatId(GnssSystem::kBeidou, prn);
      e.toc = e.toe = toe;
      e.aode = e.aodc = 1;  // BDS-SIS-ICD-B1I 3.0 5.2.4.9, 5.2.4.11: below 25, the age in hours
      e.ura_m = 2.0;
      e.transmission_tow_s = toe_tow;
      e.source = "nominal slot";
      return e;
    };
    for (const GeoSlot& geo : kBeidouGeo) {
      // The GEO algorithm (BDS-SIS-ICD-B1I 3.0 Table 5-11) turns the orbit by Rx(-5 deg) before
      // the Earth's rotation Rz(omega_e tk): an orbit of 5 deg with its node at 180 deg in the
      // frame of toe (Omega0 - omega_e toe = pi; no Earth rotation in the node's rate) is the
      // equator, where the satellite's longitude is its argument of latitude + 180 deg, held by
      // a mean motion of omega_e.
      BeidouEphemeris& e = record(geo.prn);
      e.sqrt_a_sqrtm = std::sqrt(kGeoA_m);
      e.i0_rad = 5.0 * kDegToRad;
      e.omega0_rad = wrap_pi(kPi + k.omega_earth_radps * toe_tow);
      e.m0_rad = wrap_pi((geo.lon_deg - 180.0) * kDegToRad);
      e.delta_n_radps = k.omega_earth_radps - std::sqrt(k.mu_m3ps2 / (kGeoA_m * kGeoA_m * kGeoA_m));
    }
    for (std::size_t i = 0; i < kBeidouIgsoPrns.size(); ++i) {
      // Three planes 120 deg apart on one ground track, each 8 h behind the one before.
      const double shift_deg = 120.0 * static_cast<double>(i);
      set_kepler(geosynchronous(0.0, 55.0, 0.0, kBeidouIgsoNodeLonDeg + shift_deg, -shift_deg), toe_s, toe_tow, k,
                 record(kBeidouIgsoPrns[i]));
    }
    for (std::size_t i = 0; i < kBeidouMeoPrns.size(); ++i) {
      const int slot = static_cast<int>(i);
      set_kepler(walker_slot(kBeidouMeoA_m, 55.0, 24, 3, 1, slot / 8, slot % 8), toe_s, toe_tow, k,
                 record(kBeidouMeoPrns[i]));
    }
  });
}

void nominal_qzss(GpsTime t, std::vector<GpsEphemeris>& out) {
  out.clear();
  const KeplerConstants k = kepler_constants(GnssSystem::kQzss);
  for_each_toe(t, 0, [&](std::int64_t upload, std::int64_t toe_s) {
    const GpsTime toe{toe_s * kNsPerS};
    const double toe_tow = to_week_tow(toe).tow_s;  // QZSST = GPST
    const auto add = [&](int prn, const NominalOrbit& o) {
      GpsEphemeris& e = out.emplace_back();
      set_kepler(o, toe_s, toe_tow, k, e);
      e.sat = SatId(GnssSystem::kQzss, prn);
      e.toc = e.toe = toe;
      e.iode = static_cast<int>(((upload % 256) + 256) % 256);
      e.iodc = e.iode;
      e.ura_m = 2.0;
      e.transmission_tow_s = toe_tow - 7200.0;
      e.fit_interval_h = 4.0;
      e.source = "nominal slot";
    };
    constexpr double kQzoE = 0.075, kQzoOmegaDeg = 270.0;
    const double m_node_deg = mean_anomaly_at_node_deg(kQzoE, kQzoOmegaDeg);
    for (int i = 0; i < 3; ++i) {
      const double shift_deg = 120.0 * i;
      add(i + 1, geosynchronous(kQzoE, 41.0, kQzoOmegaDeg, kQzoCentreLonDeg + shift_deg, m_node_deg - shift_deg));
    }
    add(7, geosynchronous(0.0, 0.0, 0.0, 0.0, 127.0));  // at the node (lon 0) + 127 deg
  });
}

void nominal_glonass(GpsTime t, std::vector<GlonassEphemeris>& out) {
  out.clear();
  // tb at 15 and 45 min past each hour of GLONASS time (ICD 4.4, P1 = 30 min): UTC(SU) + 3 h,
  // so the same minutes of UTC, + (GPS - UTC) in GPS time.
  const int leap_s = leap_seconds_at_gps(t);
  const std::int64_t spacing_s = static_cast<std::int64_t>(kGlonassUploadInterval_s);
  const std::int64_t grid_offset_s = 900 + leap_s;
  const std::int64_t t_s = floor_div(t.ns, kNsPerS) - grid_offset_s;
  const std::int64_t first_s = (floor_div(t_s, spacing_s) - 1) * spacing_s + grid_offset_s;
  const std::int64_t last_s = first_s + 26 * 3600 + 2 * spacing_s;
  const KeplerConstants k = kepler_constants(GnssSystem::kGlonass);
  for (int slot = 0; slot < 24; ++slot) {
    // The first record's state from the nominal orbit; the next ones integrate it (as the
    // control segment's uploads continue one orbit).
    KeplerEphemeris kepler;
    kepler.sat = SatId(GnssSystem::kGlonass, slot + 1);
    set_kepler(walker_slot(kGlonassA_m, 64.8, 24, 3, 1, slot / 8, slot % 8), first_s, to_week_tow(GpsTime{first_s * kNsPerS}).tow_s, k,
               kepler);
    kepler.toe = GpsTime{first_s * kNsPerS};
    const SatState s = broadcast_sat_state(kepler, kepler.toe);
    GlonassEphemeris e;
    e.sat = kepler.sat;
    e.tb = kepler.toe;
    e.p_pz90_m = s.p_ecef_m;
    e.v_pz90_mps = s.v_ecef_mps;
    e.frequency_channel = kGlonassChannels[static_cast<std::size_t>(slot)];
    e.frame_time_s = to_week_tow(e.tb.plus_s(-kGlonassUploadInterval_s / 2.0 - leap_s)).tow_s;  // UTC week
    e.source = "nominal slot";
    out.push_back(e);
    for (std::int64_t tb_s = first_s + spacing_s; tb_s <= last_s; tb_s += spacing_s)
      out.push_back(reuploaded(out.back(), GpsTime{tb_s * kNsPerS}));
  }
}

NavData nominal_constellation(GpsTime t, std::uint32_t systems) {
  NavData nav;
  nav.renews = true;
  nav.source = "nominal constellation (GPS SPS PS Table 3.2-1, epoch 1993-07-01)";
  // The broadcast ionosphere a receiver decodes from subframe 4 page 18: a real broadcast set
  // (2004-01-01, RTKLIB's default ion_default), so that the sky's ionosphere is the Klobuchar
  // model's and a receiver corrects it as a real one would.
  nav.klobuchar = KlobucharCoefficients{{0.1118e-07, -0.7451e-08, -0.5961e-07, 0.1192e-06},
                                        {0.1167e+06, -0.2294e+06, -0.1311e+06, 0.1049e+07}};
  if (systems & system_bit(GnssSystem::kGps)) nominal_gps(t, nav.gps);
  if (systems & system_bit(GnssSystem::kGalileo)) nominal_galileo(t, nav.galileo);
  if (systems & system_bit(GnssSystem::kBeidou)) nominal_beidou(t, nav.beidou);
  if (systems & system_bit(GnssSystem::kQzss)) nominal_qzss(t, nav.qzss);
  if (systems & system_bit(GnssSystem::kGlonass)) nominal_glonass(t, nav.glonass);
  return nav;
}

}  // namespace navemu
