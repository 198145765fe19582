#include "models/constellation.hpp"

#include <array>
#include <cmath>
#include <cstdint>
#include <string>

#include "models/geodesy.hpp"

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

}  // namespace

NavData nominal_constellation(GpsTime t) {
  NavData nav;
  nav.renews = true;
  nav.source = "nominal constellation (GPS SPS PS Table 3.2-1, epoch 1993-07-01)";
  // The broadcast ionosphere a receiver decodes from subframe 4 page 18: a real broadcast set
  // (2004-01-01, RTKLIB's default ion_default), so that the sky's ionosphere is the Klobuchar
  // model's and a receiver corrects it as a real one would.
  nav.klobuchar = KlobucharCoefficients{{0.1118e-07, -0.7451e-08, -0.5961e-07, 0.1192e-06},
                                        {0.1167e+06, -0.2294e+06, -0.1311e+06, 0.1049e+07}};

  const double a = kSemiMajorAxis_m;
  const double n0 = std::sqrt(kGpsMu_m3ps2 / (a * a * a));
  const double delta_n = kArgLatRate_radps - n0;

  // toe at the 2-hour boundaries from (t - 2 h) to (t + 26 h), rounded down to boundaries.
  const std::int64_t t_s = floor_div(t.ns, kNsPerS);
  const std::int64_t k_first = floor_div(t_s, kToeSpacingS) - 1;
  const std::int64_t k_last = floor_div(t_s, kToeSpacingS) + 13;

  for (std::int64_t k = k_first; k <= k_last; ++k) {
    const std::int64_t toe_s = k * kToeSpacingS;
    const GpsTime toe{toe_s * kNsPerS};
    const double dt = static_cast<double>(toe_s - kRefEpochGpsS);
    const double toe_tow = to_week_tow(toe).tow_s;
    const int iode = static_cast<int>(((k % 256) + 256) % 256);

    for (std::size_t i = 0; i < kSlots.size(); ++i) {
      const Slot& slot = kSlots[i];
      // Geographic longitude of the node and argument of latitude at toe.
      const double node_lon_ref = (slot.raan_deg - kGhaRefDeg) * kDegToRad;
      const double node_lon =
          wrap_pi(node_lon_ref + (kRaanRate_radps - kOmegaEarth_radps) * dt);
      const double arg_lat = wrap_pi(slot.arg_lat_deg * kDegToRad + kArgLatRate_radps * dt);

      GpsEphemeris e;
      e.sat = gps_sat(static_cast<int>(i) + 1);
      e.toc = toe;
      e.toe = toe;
      e.iode = iode;
      e.iodc = iode;
      e.sqrt_a_sqrtm = std::sqrt(a);
      e.e = 0.0;
      e.i0_rad = kInclinationDeg * kDegToRad;
      e.omega_rad = 0.0;
      // e = 0, omega = 0: the mean anomaly is the argument of latitude.
      e.m0_rad = arg_lat;
      e.delta_n_radps = delta_n;
      // IS-GPS-200 Table 20-IV: Omega_k = Omega0 + (Omega_dot - omega_e) t_k - omega_e toe,
      // which at t_k = 0 must equal the node's geographic longitude at toe.
      e.omega0_rad = wrap_pi(node_lon + kOmegaEarth_radps * toe_tow);
      e.omega_dot_radps = kRaanRate_radps;
      e.idot_radps = 0.0;
      e.codes_on_l2 = 1;
      e.l2p_data_flag = 0;
      e.ura_m = 2.0;
      e.health = 0;
      e.tgd_s = 0.0;
      e.transmission_tow_s = toe_tow - 7200.0;  // 2 h before toe, relative to toe's week
      e.fit_interval_h = 4.0;
      e.source = std::string("nominal slot ") + slot.name;
      nav.gps.push_back(e);
    }
  }
  return nav;
}

}  // namespace navemu
