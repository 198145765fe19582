#include "models/truth_interpolation.hpp"

#include <algorithm>
#include <cmath>

// References:
//  [Groves] P. D. Groves, Principles of GNSS, Inertial, and Multisensor Integrated Navigation
//           Systems, 2nd ed., Artech House, 2013.

namespace navemu {

namespace {

constexpr double kTwoPi = 2.0 * 3.14159265358979323846;

// Latitude (rad), longitude (rad) and height (m) of a state, and their time derivatives from
// its velocity over the Earth ([Groves] eq. (2.111)): dlat/dt = v_n / (R_N + h),
// dlon/dt = v_e / ((R_E + h) cos lat), dh/dt = -v_d.
Vec3 curvilinear(const Geodetic& g) {
  return Vec3(g.lat_deg * kDegToRad, g.lon_deg * kDegToRad, g.h_m);
}

Vec3 curvilinear_rate(const Geodetic& g, const Vec3& v_ned_mps) {
  const double lat = g.lat_deg * kDegToRad;
  return Vec3(v_ned_mps.x() / (meridian_radius_m(g.lat_deg) + g.h_m),
              v_ned_mps.y() / ((transverse_radius_m(g.lat_deg) + g.h_m) * std::cos(lat)),
              -v_ned_mps.z());
}

// Longitude in degrees, wrapped to [-180, 180).
double wrap_lon_deg(double lon_deg) {
  if (lon_deg >= -180.0 && lon_deg < 180.0) return lon_deg;
  return lon_deg - 360.0 * std::floor((lon_deg + 180.0) / 360.0);
}

Geodetic geodetic_from_curvilinear(const Vec3& p) {
  return Geodetic{p.x() * kRadToDeg, wrap_lon_deg(p.y() * kRadToDeg), p.z()};
}

}  // namespace

ImuTruth interpolate_truth(const ImuTruth& a, const ImuTruth& b, GpsTime t,
                           const std::optional<Vec3>& dv_a_ned_mps2,
                           const std::optional<Vec3>& dv_b_ned_mps2) {
  const double dt = seconds_between(b.t, a.t);
  const double s = dt > 0.0 ? std::clamp(seconds_between(t, a.t) / dt, 0.0, 1.0) : 0.0;

  // Cubic Hermite basis on [0, 1] (the derivatives scaled by the interval length).
  const double s2 = s * s, s3 = s2 * s;
  const double h00 = 2.0 * s3 - 3.0 * s2 + 1.0, h10 = s3 - 2.0 * s2 + s;
  const double h01 = -2.0 * s3 + 3.0 * s2, h11 = s3 - s2;

  // Position: Hermite on latitude, longitude (b's unwrapped to within half a turn of a's) and
  // height, the derivatives from the velocities.
  const Vec3 pa = curvilinear(a.position);
  Vec3 pb = curvilinear(b.position);
  pb.y() -= kTwoPi * std::round((pb.y() - pa.y()) / kTwoPi);
  const Vec3 dpa = curvilinear_rate(a.position, a.v_ned_mps);
  const Vec3 dpb = curvilinear_rate(b.position, b.v_ned_mps);
  const Vec3 p = h00 * pa + h10 * dt * dpa + h01 * pb + h11 * dt * dpb;

  ImuTruth out;
  out.t = t;
  out.position = geodetic_from_curvilinear(p);
  // Velocity: Hermite with the given accelerations as derivatives, else linear.
  if (dv_a_ned_mps2 && dv_b_ned_mps2)
    out.v_ned_mps = h00 * a.v_ned_mps + h10 * dt * *dv_a_ned_mps2 + h01 * b.v_ned_mps +
                    h11 * dt * *dv_b_ned_mps2;
  else
    out.v_ned_mps = (1.0 - s) * a.v_ned_mps + s * b.v_ned_mps;
  // Attitude: slerp along the shorter arc (Eigen's slerp flips the sign of one quaternion when
  // their dot product is negative); exact for a constant body rate relative to NED.
  out.q_ned_from_body = a.q_ned_from_body.slerp(s, b.q_ned_from_body).normalized();
  // f, w and temperature: linear, when both states carry them.
  if (a.f_body_mps2 && b.f_body_mps2)
    out.f_body_mps2 = Vec3((1.0 - s) * *a.f_body_mps2 + s * *b.f_body_mps2);
  if (a.w_ib_body_radps && b.w_ib_body_radps)
    out.w_ib_body_radps = Vec3((1.0 - s) * *a.w_ib_body_radps + s * *b.w_ib_body_radps);
  if (a.temperature_c && b.temperature_c)
    out.temperature_c = (1.0 - s) * *a.temperature_c + s * *b.temperature_c;

  // At the interval's ends the states themselves, unrounded (the Hermite sum is exact there, but
  // the degree/radian conversions and the quaternion normalisation are not).
  const ImuTruth* end = s == 0.0 ? &a : s == 1.0 ? &b : nullptr;
  if (end != nullptr) {
    out.position = end->position;
    out.position.lon_deg = wrap_lon_deg(end->position.lon_deg);
    out.v_ned_mps = end->v_ned_mps;
    out.q_ned_from_body = end->q_ned_from_body;
  }
  return out;
}

ImuTruth extrapolate_truth(const ImuTruth& a, GpsTime t) {
  const double dt = seconds_between(t, a.t);
  ImuTruth out = a;
  out.t = t;
  out.position.lon_deg = wrap_lon_deg(a.position.lon_deg);
  if (dt == 0.0) return out;
  // Constant velocity over the Earth: the curvilinear rates ([Groves] eq. (2.111)) by the
  // midpoint rule, so that the change of the radii and of cos(lat) along the way is followed to
  // second order (exact for motion along a parallel or the vertical).
  const Vec3 p0 = curvilinear(a.position);
  const Vec3 p_half = p0 + 0.5 * dt * curvilinear_rate(a.position, a.v_ned_mps);
  const Vec3 p = p0 + dt * curvilinear_rate(geodetic_from_curvilinear(p_half), a.v_ned_mps);
  out.position = geodetic_from_curvilinear(p);
  return out;
}

}  // namespace navemu
