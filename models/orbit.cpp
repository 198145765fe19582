#include "models/orbit.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace navemu {

namespace {

// Relativistic correction constant F = -2 sqrt(mu) / c^2 (IS-GPS-200 20.3.3.3.3.1).
constexpr double kRelativisticF = -4.442807633e-10;  // s / sqrt(m)

// sin and cos of an angle that is usually tiny (the Earth's rotation during a signal's flight,
// < 1e-5 rad; the orbit's harmonic correction of the argument of latitude, < 1e-4 rad). Below
// 1e-4 rad their Taylor series to x^3 and x^2 are used: the first omitted terms, x^5/120 and
// x^4/24, are under 5e-18 of the value, far below the 1.1e-16 rounding of a double, so the
// series gives the rounded sin and cos (up to the last bit) without calling them.
struct SinCos {
  double sin = 0.0;
  double cos = 1.0;
};
SinCos sin_cos_small(double x_rad) {
  constexpr double kSeriesMax_rad = 1e-4;
  if (std::abs(x_rad) >= kSeriesMax_rad) return {std::sin(x_rad), std::cos(x_rad)};
  const double x2 = x_rad * x_rad;
  return {x_rad - x_rad * x2 / 6.0, 1.0 - 0.5 * x2};
}

// Kepler's equation M = E - e sin E by Newton's method; converges for every e < 1 when
// started at E = pi for high eccentricities. With sin E and cos E: when the last Newton step
// left E unchanged (e = 0, or a step below the spacing of doubles) they are the ones the
// iteration evaluated at that very argument, so they are kept rather than evaluated again.
struct EccentricAnomaly {
  double e_rad = 0.0;
  double sin_e = 0.0;
  double cos_e = 1.0;
};
EccentricAnomaly eccentric_anomaly(double mean_anomaly_rad, double e) {
  const double m = std::remainder(mean_anomaly_rad, 2.0 * kPi);
  double ecc = e < 0.8 ? m : (m < 0 ? -kPi : kPi);
  double sin_at = 0.0, cos_at = 1.0;
  double evaluated_at = std::numeric_limits<double>::quiet_NaN();  // argument of sin_at, cos_at
  for (int i = 0; i < 50; ++i) {
    sin_at = std::sin(ecc);
    cos_at = std::cos(ecc);
    evaluated_at = ecc;
    const double f = ecc - e * sin_at - m;
    const double step = f / (1.0 - e * cos_at);
    ecc -= step;
    if (std::abs(step) < 1e-15) break;
  }
  EccentricAnomaly out;
  out.e_rad = ecc + (mean_anomaly_rad - m);
  if (out.e_rad == evaluated_at) {
    out.sin_e = sin_at;
    out.cos_e = cos_at;
  } else {
    out.sin_e = std::sin(out.e_rad);
    out.cos_e = std::cos(out.e_rad);
  }
  return out;
}

}  // namespace

double gps_sat_clock_poly_s(const KeplerEphemeris& eph, GpsTime t) {
  const double dt = seconds_between(t, eph.toc);
  return eph.af0_s + eph.af1_sps * dt + eph.af2_sps2 * dt * dt;
}

GpsEphemeris reuploaded(const GpsEphemeris& eph, GpsTime toe) {
  GpsEphemeris e = eph;
  const double dt = seconds_between(toe, eph.toe);
  const double a = eph.sqrt_a_sqrtm * eph.sqrt_a_sqrtm;
  const double n = std::sqrt(kGpsMu_m3ps2 / (a * a * a)) + eph.delta_n_radps;
  const double tow_old = to_week_tow(eph.toe).tow_s, tow_new = to_week_tow(toe).tow_s;
  const double kTwoPi = 2.0 * kPi;
  e.toe = toe;
  e.toc = eph.toc.plus_s(dt);
  e.m0_rad = std::remainder(eph.m0_rad + n * dt, kTwoPi);
  // Omega_k = Omega0 + (Omega_dot - omega_e) tk - omega_e toe_tow must stay the same function
  // of time.
  e.omega0_rad = std::remainder(eph.omega0_rad + (eph.omega_dot_radps - kOmegaEarth_radps) * dt +
                                    kOmegaEarth_radps * (tow_new - tow_old),
                                kTwoPi);
  e.i0_rad = eph.i0_rad + eph.idot_radps * dt;
  e.af0_s = eph.af0_s + eph.af1_sps * dt + eph.af2_sps2 * dt * dt;
  e.af1_sps = eph.af1_sps + 2.0 * eph.af2_sps2 * dt;
  const auto uploads = static_cast<int>(std::llround(dt / kUploadInterval_s));
  e.iode = (((eph.iode + uploads) % 256) + 256) % 256;
  e.iodc = (eph.iodc & ~0xFF) | e.iode;
  e.transmission_tow_s = eph.transmission_tow_s + (tow_new - tow_old);
  return e;
}

namespace {

// The user algorithm of IS-GPS-200 Table 20-IV with the velocity equations of its later
// revisions, for a system's constants. The node's longitude is node_at_toe + node_rate tk
// (with the Earth's rotation in node_rate for an ECEF result; without it for a BeiDou GEO,
// rotated afterwards).
struct NodeModel {
  double at_toe_rad = 0.0;
  double rate_radps = 0.0;
};
SatState kepler_state(const KeplerEphemeris& eph, GpsTime t, const KeplerConstants& k,
                      const NodeModel& node_model) {
  const double a = eph.sqrt_a_sqrtm * eph.sqrt_a_sqrtm;
  const double n0 = std::sqrt(k.mu_m3ps2 / (a * a * a));
  const double tk = seconds_between(t, eph.toe);
  const double n = n0 + eph.delta_n_radps;
  const double mk = eph.m0_rad + n * tk;
  const double e = eph.e;
  const EccentricAnomaly ek = eccentric_anomaly(mk, e);
  const double sin_e = ek.sin_e;
  const double cos_e = ek.cos_e;
  const double one_minus_ecos = 1.0 - e * cos_e;
  const double sqrt_1me2 = std::sqrt(1.0 - e * e);
  // True anomaly nu and argument of latitude phi = nu + omega through their sines and
  // cosines, with no atan2 and no trigonometric call on the sums:
  //   sin nu = sqrt(1 - e^2) sin E / (1 - e cos E),  cos nu = (cos E - e) / (1 - e cos E)
  // (the Table's nu = atan2 of these numerators), then the angle sum and the double angle.
  const double sin_nu = sqrt_1me2 * sin_e / one_minus_ecos;
  const double cos_nu = (cos_e - e) / one_minus_ecos;
  const double sin_w = std::sin(eph.omega_rad), cos_w = std::cos(eph.omega_rad);
  const double sin_phi = sin_nu * cos_w + cos_nu * sin_w;
  const double cos_phi = cos_nu * cos_w - sin_nu * sin_w;
  const double s2 = 2.0 * sin_phi * cos_phi;                    // sin 2 phi
  const double c2 = (cos_phi - sin_phi) * (cos_phi + sin_phi);  // cos 2 phi

  const double du = eph.cus_rad * s2 + eph.cuc_rad * c2;
  const double dr = eph.crs_m * s2 + eph.crc_m * c2;
  const double di = eph.cis_rad * s2 + eph.cic_rad * c2;
  const double r = a * one_minus_ecos + dr;
  const double inc = eph.i0_rad + di + eph.idot_radps * tk;

  // u = phi + du by the angle sum again (du, a harmonic correction of ~1e-5 rad).
  const SinCos sc_du = sin_cos_small(du);
  const double sin_u = sin_phi * sc_du.cos + cos_phi * sc_du.sin;
  const double cos_u = cos_phi * sc_du.cos - sin_phi * sc_du.sin;
  const double xp = r * cos_u;
  const double yp = r * sin_u;
  const double omega_dot_k = node_model.rate_radps;
  const double node = node_model.at_toe_rad + omega_dot_k * tk;
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
  const double xp_dot = r_dot * cos_u - r * u_dot * sin_u;
  const double yp_dot = r_dot * sin_u + r * u_dot * cos_u;
  s.v_ecef_mps = Vec3(
      xp_dot * cn - xp * sn * omega_dot_k - yp_dot * ci * sn + yp * si * inc_dot * sn -
          yp * ci * cn * omega_dot_k,
      xp_dot * sn + xp * cn * omega_dot_k + yp_dot * ci * cn - yp * si * inc_dot * cn -
          yp * ci * sn * omega_dot_k,
      yp_dot * si + yp * ci * inc_dot);

  // Satellite clock (IS-GPS-200 20.3.3.3.3.1): polynomial plus relativistic term.
  s.relativistic_s = k.relativistic_f * e * eph.sqrt_a_sqrtm * sin_e;
  const double dtc = seconds_between(t, eph.toc);
  s.clock_bias_s = gps_sat_clock_poly_s(eph, t) + s.relativistic_s;
  s.clock_drift_sps = eph.af1_sps + 2.0 * eph.af2_sps2 * dtc +
                      k.relativistic_f * e * eph.sqrt_a_sqrtm * cos_e * ek_dot;
  return s;
}

constexpr KeplerConstants kGpsConstants{kGpsMu_m3ps2, kOmegaEarth_radps, kRelativisticF};

}  // namespace

KeplerConstants kepler_constants(GnssSystem system) {
  switch (system) {
    // Galileo OS SIS ICD issue 2.0 5.1.1 (Table 59: mu, Omega_e) and 5.1.4 (F).
    case GnssSystem::kGalileo: return {3.986004418e14, 7.2921151467e-5, -4.442807309e-10};
    // BDS-SIS-ICD-B1I 3.0 5.2.4.12 (Table 5-11: CGCS2000's mu and Omega_e; F alike).
    case GnssSystem::kBeidou: return {3.986004418e14, 7.2921150e-5, -4.442807309e-10};
    // GPS, and QZSS, whose LNAV is GPS's (IS-QZSS-PNT 5.5.x refers to IS-GPS-200).
    default: return kGpsConstants;
  }
}

bool is_beidou_geo(SatId sat) {
  return sat.system() == GnssSystem::kBeidou && (sat.number() <= 5 || sat.number() >= 59);
}

SatState gps_sat_state(const GpsEphemeris& eph, GpsTime t) {
  const double toe_tow_s = to_week_tow(eph.toe).tow_s;
  return kepler_state(eph, t, kGpsConstants,
                      {eph.omega0_rad - kOmegaEarth_radps * toe_tow_s, eph.omega_dot_radps - kOmegaEarth_radps});
}

SatState broadcast_sat_state(const KeplerEphemeris& eph, GpsTime t) {
  const GnssSystem system = eph.sat.system();
  const KeplerConstants k = kepler_constants(system);
  // toe in the system's own seconds of week: BDT runs 14 s behind GPS time
  // (BDS-SIS-ICD-B1I 3.0 3.3), GST and QZSST with it.
  const double toe_tow_s =
      to_week_tow(system == GnssSystem::kBeidou ? eph.toe.plus_s(-kGpsMinusBdt_s) : eph.toe).tow_s;
  if (!is_beidou_geo(eph.sat))
    return kepler_state(eph, t, k,
                        {eph.omega0_rad - k.omega_earth_radps * toe_tow_s, eph.omega_dot_radps - k.omega_earth_radps});
  // BeiDou GEO (BDS-SIS-ICD-B1I 3.0 Table 5-11): the orbit in the inertial frame of toe
  // (node Omega0 + Omega_dot tk - Omega_e toe), tilted by Rx(-5 deg), then turned by the Earth's
  // rotation since toe, Rz(Omega_e tk): p = Rz Rx p_GK, v = Rz Rx v_GK + dRz/dt Rx p_GK.
  SatState s = kepler_state(eph, t, k, {eph.omega0_rad - k.omega_earth_radps * toe_tow_s, eph.omega_dot_radps});
  const double tk = seconds_between(t, eph.toe);
  const double tilt = -5.0 * kPi / 180.0, spin = k.omega_earth_radps * tk;
  const double ct = std::cos(tilt), st = std::sin(tilt), cs = std::cos(spin), ss = std::sin(spin);
  Mat3 rx, rz, drz;
  rx << 1.0, 0.0, 0.0, 0.0, ct, st, 0.0, -st, ct;
  rz << cs, ss, 0.0, -ss, cs, 0.0, 0.0, 0.0, 1.0;
  drz << -ss, cs, 0.0, -cs, -ss, 0.0, 0.0, 0.0, 0.0;
  const Vec3 p_gk = s.p_ecef_m, v_gk = s.v_ecef_mps;
  s.p_ecef_m = rz * (rx * p_gk);
  s.v_ecef_mps = rz * (rx * v_gk) + k.omega_earth_radps * (drz * (rx * p_gk));
  return s;
}

namespace {

// GLONASS ICD edition 5.1 A.3.1.2 (PZ-90.11 constants as the ICD gives them): the equations of
// motion in the rotating PZ-90 frame, with the Earth's central field, its J2 term and the
// lunisolar accelerations of the message taken as constant over the interval.
constexpr double kGloMu_m3ps2 = 3.9860044e14;
constexpr double kGloAe_m = 6378136.0;
constexpr double kGloJ2 = 1.0826257e-3;
constexpr double kGloOmega_radps = 7.292115e-5;

struct GloState {
  Vec3 p = Vec3::Zero(), v = Vec3::Zero();
};

GloState glonass_derivative(const GloState& s, const Vec3& a_ls) {
  const double r2 = s.p.squaredNorm(), r = std::sqrt(r2), r3 = r2 * r;
  const double mu_r3 = kGloMu_m3ps2 / r3;
  const double j2 = 1.5 * kGloJ2 * kGloMu_m3ps2 * kGloAe_m * kGloAe_m / (r3 * r2);
  const double z2_r2 = s.p.z() * s.p.z() / r2;
  const double w2 = kGloOmega_radps * kGloOmega_radps;
  GloState d;
  d.p = s.v;
  d.v.x() = -mu_r3 * s.p.x() - j2 * s.p.x() * (1.0 - 5.0 * z2_r2) + w2 * s.p.x() + 2.0 * kGloOmega_radps * s.v.y() + a_ls.x();
  d.v.y() = -mu_r3 * s.p.y() - j2 * s.p.y() * (1.0 - 5.0 * z2_r2) + w2 * s.p.y() - 2.0 * kGloOmega_radps * s.v.x() + a_ls.y();
  d.v.z() = -mu_r3 * s.p.z() - j2 * s.p.z() * (3.0 - 5.0 * z2_r2) + a_ls.z();
  return d;
}

}  // namespace

double glonass_sat_clock_s(const GlonassEphemeris& eph, GpsTime t) {
  return -eph.tau_n_s + eph.gamma_n * seconds_between(t, eph.tb);
}

namespace {
// One fourth-order Runge-Kutta step of h seconds (A.3.1.2).
GloState glonass_step(const GloState& s, const Vec3& a_ls, double h) {
  const auto add = [](const GloState& a, const GloState& d, double k) { return GloState{a.p + k * d.p, a.v + k * d.v}; };
  const GloState k1 = glonass_derivative(s, a_ls);
  const GloState k2 = glonass_derivative(add(s, k1, h / 2.0), a_ls);
  const GloState k3 = glonass_derivative(add(s, k2, h / 2.0), a_ls);
  const GloState k4 = glonass_derivative(add(s, k3, h), a_ls);
  return {s.p + h / 6.0 * (k1.p + 2.0 * k2.p + 2.0 * k3.p + k4.p), s.v + h / 6.0 * (k1.v + 2.0 * k2.v + 2.0 * k3.v + k4.v)};
}
SatState glonass_output(const GlonassEphemeris& eph, const GloState& s, GpsTime t) {
  SatState out;
  out.p_ecef_m = s.p;
  out.v_ecef_mps = s.v;
  // Satellite clock (ICD 3.3.3.x, "tau_n(tb) - gamma_n (t - tb)" is GLONASS time minus the
  // satellite's): the offset of the satellite's time from GLONASS time, relativity included.
  out.clock_bias_s = glonass_sat_clock_s(eph, t);
  out.clock_drift_sps = eph.gamma_n;
  return out;
}
}  // namespace

SatState glonass_sat_state(const GlonassEphemeris& eph, GpsTime t) {
  // Fourth-order Runge-Kutta from tb to t (A.3.1.2) in steps of at most 60 s.
  constexpr double kMaxStep_s = 60.0;
  const double span_s = seconds_between(t, eph.tb);
  const int steps = std::max(1, static_cast<int>(std::ceil(std::abs(span_s) / kMaxStep_s)));
  const double h = span_s / steps;
  GloState s{eph.p_pz90_m, eph.v_pz90_mps};
  for (int i = 0; i < steps; ++i) s = glonass_step(s, eph.a_pz90_mps2, h);
  return glonass_output(eph, s, t);
}

GlonassArc::GlonassArc(const GlonassEphemeris& eph) : eph_(&eph), tb_(eph.tb), a_ls_(eph.a_pz90_mps2) {
  p_[kHalfNodes] = eph.p_pz90_m;
  v_[kHalfNodes] = eph.v_pz90_mps;
  for (const double dir : {1.0, -1.0}) {
    GloState s{eph.p_pz90_m, eph.v_pz90_mps};
    for (int k = 1; k <= kHalfNodes; ++k) {
      s = glonass_step(s, eph.a_pz90_mps2, dir * kNodeStep_s);
      const auto i = static_cast<std::size_t>(kHalfNodes + static_cast<int>(dir) * k);
      p_[i] = s.p;
      v_[i] = s.v;
    }
  }
}

SatState GlonassArc::state(GpsTime t) const {
  const double span_s = seconds_between(t, eph_->tb);
  const double node = std::round(span_s / kNodeStep_s);
  if (std::abs(node) > kHalfNodes) return glonass_sat_state(*eph_, t);
  const auto i = static_cast<std::size_t>(kHalfNodes + static_cast<int>(node));
  const double h = span_s - node * kNodeStep_s;
  const GloState at_node{p_[i], v_[i]};
  return glonass_output(*eph_, h == 0.0 ? at_node : glonass_step(at_node, eph_->a_pz90_mps2, h), t);
}

GlonassEphemeris reuploaded(const GlonassEphemeris& eph, GpsTime tb) {
  const SatState s = glonass_sat_state(eph, tb);
  GlonassEphemeris e = eph;
  e.tb = tb;
  e.p_pz90_m = s.p_ecef_m;
  e.v_pz90_mps = s.v_ecef_mps;
  e.tau_n_s = -s.clock_bias_s;  // -tau_n + gamma_n (tb - tb_old) continued
  e.frame_time_s = eph.frame_time_s + seconds_between(tb, eph.tb);
  if (e.frame_time_s >= 604800.0) e.frame_time_s -= 604800.0;
  return e;
}

Vec3 rotate_earth(const Vec3& v_ecef, double dt_s) {
  const SinCos th = sin_cos_small(kOmegaEarth_radps * dt_s);
  const double c = th.cos, s = th.sin;
  return Vec3(c * v_ecef.x() + s * v_ecef.y(), -s * v_ecef.x() + c * v_ecef.y(), v_ecef.z());
}

ReceiverPlace receiver_place(const Vec3& p_rx_ecef_m, const Vec3& v_rx_ecef_mps) {
  return {p_rx_ecef_m, v_rx_ecef_mps, R_enu_from_ecef(geodetic_from_ecef(p_rx_ecef_m))};
}

SatGeometry gps_sat_geometry(const GpsEphemeris& eph, GpsTime t_receive, const Vec3& p_rx_ecef_m,
                             const Vec3& v_rx_ecef_mps) {
  return gps_sat_geometry(eph, t_receive, receiver_place(p_rx_ecef_m, v_rx_ecef_mps));
}

SatState record_sat_state(const BroadcastRecord& r, GpsTime t) {
  if (const auto* glo = std::get_if<const GlonassEphemeris*>(&r)) return glonass_sat_state(**glo, t);
  if (const auto* gal = std::get_if<const GalileoEphemeris*>(&r)) return broadcast_sat_state(**gal, t);
  if (const auto* bds = std::get_if<const BeidouEphemeris*>(&r)) return broadcast_sat_state(**bds, t);
  return broadcast_sat_state(*std::get<const GpsEphemeris*>(r), t);
}

SatGeometry gps_sat_geometry(const GpsEphemeris& eph, GpsTime t_receive, const ReceiverPlace& rx,
                             double tau_guess_s) {
  return sat_geometry(BroadcastRecord(&eph), t_receive, rx, tau_guess_s);
}

SatGeometry sat_geometry(const BroadcastRecord& r, GpsTime t_receive, const ReceiverPlace& rx,
                         double tau_guess_s, const GlonassArc* arc) {
  // Light-time equation, solved by fixed-point iteration on the flight time tau (the error
  // shrinks by |v_sat| / c ~ 1e-5 per step). Once a step changes tau by less than 1e-14 s
  // (the satellite moves 40 nm in that time) the state just evaluated is the answer.
  //
  // The orbit is evaluated at whole nanoseconds (GpsTime), so a step that leaves the transmit
  // time on the same nanosecond (the usual second step from a good guess) would evaluate the
  // same state again: it is kept instead (keyed exactly by the transmit time; the record is
  // the same throughout).
  double tau_s = tau_guess_s;
  SatState s;
  std::optional<GpsTime> evaluated_at;
  for (int i = 0; i < 10; ++i) {
    const GpsTime t_tx = t_receive.plus_s(-tau_s);
    if (t_tx != evaluated_at) {
      s = arc != nullptr ? arc->state(t_tx) : record_sat_state(r, t_tx);
      evaluated_at = t_tx;
    }
    const double next = (rotate_earth(s.p_ecef_m, tau_s) - rx.p_ecef_m).norm() / kSpeedOfLight_mps;
    const bool done = std::abs(next - tau_s) < 1e-14;
    if (done) break;
    tau_s = next;
  }

  SatGeometry g;
  g.t_transmit = t_receive.plus_s(-tau_s);
  g.flight_time_s = tau_s;
  g.sat = g.sat_transmit = s;
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
  g.direction = direction(rx.R_enu_from_ecef, rx.p_ecef_m, g.sat.p_ecef_m);
  g.dir = g.direction.az_el;
  return g;
}

}  // namespace navemu
