#include "models/orbit.hpp"

#include <Eigen/Geometry>
#include <cmath>

namespace navemu {

namespace {

// Relativistic correction constant F = -2 sqrt(mu) / c^2 (IS-GPS-200 20.3.3.3.3.1).
constexpr double kRelativisticF = -4.442807633e-10;  // s / sqrt(m)

// Kepler's equation M = E - e sin E by Newton's method; converges for every e < 1 when
// started at E = pi for high eccentricities.
double eccentric_anomaly(double mean_anomaly_rad, double e) {
  const double m = std::remainder(mean_anomaly_rad, 2.0 * kPi);
  double ecc = e < 0.8 ? m : (m < 0 ? -kPi : kPi);
  for (int i = 0; i < 50; ++i) {
    const double f = ecc - e * std::sin(ecc) - m;
    const double step = f / (1.0 - e * std::cos(ecc));
    ecc -= step;
    if (std::abs(step) < 1e-15) break;
  }
  return ecc + (mean_anomaly_rad - m);
}

}  // namespace

double gps_sat_clock_poly_s(const GpsEphemeris& eph, GpsTime t) {
  const double dt = seconds_between(t, eph.toc);
  return eph.af0_s + eph.af1_sps * dt + eph.af2_sps2 * dt * dt;
}

// IS-GPS-200 Table 20-IV (user algorithm for ephemeris determination) with the
// velocity equations of its later revisions.
SatState gps_sat_state(const GpsEphemeris& eph, GpsTime t) {
  const double a = eph.sqrt_a_sqrtm * eph.sqrt_a_sqrtm;
  const double n0 = std::sqrt(kGpsMu_m3ps2 / (a * a * a));
  const double tk = seconds_between(t, eph.toe);
  const double n = n0 + eph.delta_n_radps;
  const double mk = eph.m0_rad + n * tk;
  const double e = eph.e;
  const double ek = eccentric_anomaly(mk, e);
  const double sin_e = std::sin(ek);
  const double cos_e = std::cos(ek);
  const double one_minus_ecos = 1.0 - e * cos_e;
  const double sqrt_1me2 = std::sqrt(1.0 - e * e);
  const double nu = std::atan2(sqrt_1me2 * sin_e, cos_e - e);
  const double phi = nu + eph.omega_rad;
  const double s2 = std::sin(2.0 * phi);
  const double c2 = std::cos(2.0 * phi);

  const double du = eph.cus_rad * s2 + eph.cuc_rad * c2;
  const double dr = eph.crs_m * s2 + eph.crc_m * c2;
  const double di = eph.cis_rad * s2 + eph.cic_rad * c2;
  const double u = phi + du;
  const double r = a * one_minus_ecos + dr;
  const double inc = eph.i0_rad + di + eph.idot_radps * tk;

  const double xp = r * std::cos(u);
  const double yp = r * std::sin(u);
  const double omega_dot_k = eph.omega_dot_radps - kOmegaEarth_radps;
  const double node = eph.omega0_rad + omega_dot_k * tk - kOmegaEarth_radps * to_week_tow(eph.toe).tow_s;
  const double cn = std::cos(node), sn = std::sin(node);
  const double ci = std::cos(inc), si = std::sin(inc);

  SatState s;
  s.p_ecef_m = Vec3(xp * cn - yp * ci * sn, xp * sn + yp * ci * cn, yp * si);

  // Rates.
  const double ek_dot = n / one_minus_ecos;
  const double nu_dot = ek_dot * sqrt_1me2 / one_minus_ecos;
  const double inc_dot = eph.idot_radps + 2.0 * nu_dot * (eph.cis_rad * c2 - eph.cic_rad * s2);
  const double u_dot = nu_dot + 2.0 * nu_dot * (eph.cus_rad * c2 - eph.cuc_rad * s2);
  const double r_dot = e * a * ek_dot * sin_e + 2.0 * nu_dot * (eph.crs_m * c2 - eph.crc_m * s2);
  const double xp_dot = r_dot * std::cos(u) - r * u_dot * std::sin(u);
  const double yp_dot = r_dot * std::sin(u) + r * u_dot * std::cos(u);
  s.v_ecef_mps = Vec3(
      xp_dot * cn - xp * sn * omega_dot_k - yp_dot * ci * sn + yp * si * inc_dot * sn -
          yp * ci * cn * omega_dot_k,
      xp_dot * sn + xp * cn * omega_dot_k + yp_dot * ci * cn - yp * si * inc_dot * cn -
          yp * ci * sn * omega_dot_k,
      yp_dot * si + yp * ci * inc_dot);

  // Satellite clock (IS-GPS-200 20.3.3.3.3.1): polynomial plus relativistic term.
  s.relativistic_s = kRelativisticF * e * eph.sqrt_a_sqrtm * sin_e;
  const double dtc = seconds_between(t, eph.toc);
  s.clock_bias_s = gps_sat_clock_poly_s(eph, t) + s.relativistic_s;
  s.clock_drift_sps = eph.af1_sps + 2.0 * eph.af2_sps2 * dtc +
                      kRelativisticF * e * eph.sqrt_a_sqrtm * cos_e * ek_dot;
  return s;
}

Vec3 rotate_earth(const Vec3& v_ecef, double dt_s) {
  const double th = kOmegaEarth_radps * dt_s;
  const double c = std::cos(th), s = std::sin(th);
  return Vec3(c * v_ecef.x() + s * v_ecef.y(), -s * v_ecef.x() + c * v_ecef.y(), v_ecef.z());
}

ReceiverPlace receiver_place(const Vec3& p_rx_ecef_m, const Vec3& v_rx_ecef_mps) {
  return {p_rx_ecef_m, v_rx_ecef_mps, R_enu_from_ecef(geodetic_from_ecef(p_rx_ecef_m))};
}

SatGeometry gps_sat_geometry(const GpsEphemeris& eph, GpsTime t_receive, const Vec3& p_rx_ecef_m,
                             const Vec3& v_rx_ecef_mps) {
  return gps_sat_geometry(eph, t_receive, receiver_place(p_rx_ecef_m, v_rx_ecef_mps));
}

SatGeometry gps_sat_geometry(const GpsEphemeris& eph, GpsTime t_receive, const ReceiverPlace& rx,
                             double tau_guess_s) {
  // Light-time equation, solved by fixed-point iteration on the flight time tau (the error
  // shrinks by |v_sat| / c ~ 1e-5 per step). Once a step changes tau by less than 1e-14 s
  // (the satellite moves 40 nm in that time) the state just evaluated is the answer.
  double tau_s = tau_guess_s;
  SatState s;
  for (int i = 0; i < 10; ++i) {
    s = gps_sat_state(eph, t_receive.plus_s(-tau_s));
    const double next = (rotate_earth(s.p_ecef_m, tau_s) - rx.p_ecef_m).norm() / kSpeedOfLight_mps;
    const bool done = std::abs(next - tau_s) < 1e-14;
    if (done) break;
    tau_s = next;
  }

  SatGeometry g;
  g.t_transmit = t_receive.plus_s(-tau_s);
  g.flight_time_s = tau_s;
  g.sat = s;
  g.sat.p_ecef_m = rotate_earth(s.p_ecef_m, tau_s);
  g.sat.v_ecef_mps = rotate_earth(s.v_ecef_mps, tau_s);
  const Vec3 los = g.sat.p_ecef_m - rx.p_ecef_m;
  g.range_m = los.norm();
  const Vec3 u = los / g.range_m;

  // Range rate in the inertial frame aligned with ECEF at reception:
  // d(rho)/dt (1 + u.v_sat/c) = u.(v_sat - v_rx), both velocities inertial.
  const Vec3 w(0.0, 0.0, kOmegaEarth_radps);
  const Vec3 v_sat_inertial = g.sat.v_ecef_mps + w.cross(g.sat.p_ecef_m);
  const Vec3 v_rx_inertial = rx.v_ecef_mps + w.cross(rx.p_ecef_m);
  g.range_rate_mps =
      u.dot(v_sat_inertial - v_rx_inertial) / (1.0 + u.dot(v_sat_inertial) / kSpeedOfLight_mps);
  g.dir = azimuth_elevation(rx.R_enu_from_ecef, rx.p_ecef_m, g.sat.p_ecef_m);
  return g;
}

}  // namespace navemu
