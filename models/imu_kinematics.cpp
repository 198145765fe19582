#include "models/imu_kinematics.hpp"

#include <GeographicLib/Constants.hpp>
#include <GeographicLib/NormalGravity.hpp>

#include <algorithm>
#include <cmath>

// References:
//  [Groves] P. D. Groves, Principles of GNSS, Inertial, and Multisensor Integrated Navigation
//           Systems, 2nd ed., Artech House, 2013.
//  [T&W]    D. H. Titterton, J. L. Weston, Strapdown Inertial Navigation Technology, 2nd ed.,
//           IET, 2004.

namespace navemu {

namespace {

// WGS-84 ellipsoid (NIMA TR8350.2), through GeographicLib so that every module agrees.
const double kA_m = GeographicLib::Constants::WGS84_a();
const double kF = GeographicLib::Constants::WGS84_f();
const double kE2 = kF * (2.0 - kF);  // first eccentricity squared

// Geodetic position from latitude and longitude in radians.
Geodetic geodetic_rad(double lat_rad, double lon_rad, double h_m) {
  double lon_deg = lon_rad * kRadToDeg;
  // Keep longitude in [-180, 180) after crossing the antimeridian.
  if (lon_deg >= 180.0) lon_deg -= 360.0;
  if (lon_deg < -180.0) lon_deg += 360.0;
  return Geodetic{lat_rad * kRadToDeg, lon_deg, h_m};
}

}  // namespace

double meridian_radius_m(double lat_deg) {
  // [Groves] eq. (2.105): R_N = a (1 - e^2) / (1 - e^2 sin^2 L)^(3/2).
  const double s = std::sin(lat_deg * kDegToRad);
  const double d = 1.0 - kE2 * s * s;
  return kA_m * (1.0 - kE2) / (d * std::sqrt(d));
}

double transverse_radius_m(double lat_deg) {
  // [Groves] eq. (2.106): R_E = a / sqrt(1 - e^2 sin^2 L).
  const double s = std::sin(lat_deg * kDegToRad);
  return kA_m / std::sqrt(1.0 - kE2 * s * s);
}

Quat quat_from_rotation_vector(const Vec3& phi_rad) {
  // [T&W] section 11.2.5, [Groves] section 5.5.1: the exact quaternion of a rotation vector,
  // q = (cos(|phi|/2), sin(|phi|/2) phi/|phi|). Series form for tiny angles.
  const double theta = phi_rad.norm();
  double w, k;  // k = sin(theta/2) / theta
  if (theta < 1e-6) {
    const double t2 = theta * theta;
    w = 1.0 - t2 / 8.0 + t2 * t2 / 384.0;
    k = 0.5 - t2 / 48.0 + t2 * t2 / 3840.0;
  } else {
    w = std::cos(0.5 * theta);
    k = std::sin(0.5 * theta) / theta;
  }
  return Quat(w, k * phi_rad.x(), k * phi_rad.y(), k * phi_rad.z());
}

Vec3 rotation_vector_from_quat(const Quat& q_in) {
  // The shorter of the two equivalent rotations (w >= 0).
  Quat q = q_in.normalized();
  if (q.w() < 0.0) q.coeffs() = -q.coeffs();
  const Vec3 v = q.vec();
  const double s = v.norm();
  if (s < 1e-12) return 2.0 * v / q.w();  // sin(theta/2) ~ theta/2, w ~ 1
  return 2.0 * std::atan2(s, q.w()) / s * v;
}

Vec3 gravity_ned_mps2(const Geodetic& where) {
  // GeographicLib::NormalGravity::Gravity gives gravitation plus centrifugal acceleration of
  // the WGS-84 normal field in the local east-north-up frame; the east component vanishes by
  // symmetry. NED: (north, east, -up).
  double g_north = 0.0, g_up = 0.0;
  GeographicLib::NormalGravity::WGS84().Gravity(where.lat_deg, where.h_m, g_north, g_up);
  return Vec3(g_north, 0.0, -g_up);
}

Vec3 earth_rate_ned_radps(const Geodetic& where) {
  // [Groves] eq. (2.123) resolved in NED (section 5.4.1): w_ie^n = W (cos L, 0, -sin L).
  const double lat = where.lat_deg * kDegToRad;
  return Vec3(kOmegaEarth_radps * std::cos(lat), 0.0, -kOmegaEarth_radps * std::sin(lat));
}

Vec3 transport_rate_ned_radps(const Geodetic& where, const Vec3& v_ned_mps) {
  // [Groves] eq. (5.44): w_en^n = (v_E/(R_E+h), -v_N/(R_N+h), -v_E tan L/(R_E+h)), R_N the
  // meridian and R_E the transverse radius of curvature.
  const double lat = where.lat_deg * kDegToRad;
  const double re_h = transverse_radius_m(where.lat_deg) + where.h_m;
  const double rn_h = meridian_radius_m(where.lat_deg) + where.h_m;
  return Vec3(v_ned_mps.y() / re_h, -v_ned_mps.x() / rn_h, -v_ned_mps.y() * std::tan(lat) / re_h);
}

IdealImu ideal_imu_static(const Geodetic& where, const Quat& q_ned_from_body) {
  // At rest a = 0, so f = -g and w_ib = w_ie, both resolved in the body frame
  // ([Groves] section 5.4, velocity and attitude equations with v = 0 and w_nb = 0).
  const Mat3 C_bn = q_ned_from_body.toRotationMatrix().transpose();
  IdealImu out;
  out.f_body_mps2 = -(C_bn * gravity_ned_mps2(where));
  out.w_ib_body_radps = C_bn * earth_rate_ned_radps(where);
  return out;
}

// Method, for truth states without rates and accelerations:
//  - Body rate relative to NED: the rotation vector of q_before^-1 q_after divided by the time
//    between them. For a constant body rate w_nb, C_nb(t + T) = C_nb(t) exp([w_nb x] T), so this
//    is exact for constant rates however large the step.
//  - Acceleration over the Earth dv_ned/dt: v_ned = C_nb v_body, so
//    dv_ned/dt = C_nb (dv_body/dt + w_nb x v_body), with dv_body/dt by the central difference
//    of the body-frame velocity. Exact for constant body velocity and rate (straight lines and
//    circles at constant speed, the built-in generators) and for constant acceleration at a
//    fixed attitude; second order in the step otherwise.
//  - Then w_ib = w_nb + C_bn (w_ie + w_en) and f = C_bn (dv/dt + (2 w_ie + w_en) x v - g)
//    ([Groves] section 5.4, the attitude and velocity equations solved for the sensed
//    quantities), at `now`.
IdealImu ideal_imu_from_kinematics(const ImuTruth& before, const ImuTruth& now,
                                   const ImuTruth& after) {
  const Mat3 C_nb = now.q_ned_from_body.normalized().toRotationMatrix();
  const Mat3 C_bn = C_nb.transpose();
  const double span_s = seconds_between(after.t, before.t);

  Vec3 w_nb_body = Vec3::Zero();
  Vec3 a_ned = Vec3::Zero();
  if (span_s > 0.0) {
    const Quat q_before = before.q_ned_from_body.normalized();
    const Quat q_after = after.q_ned_from_body.normalized();
    w_nb_body = rotation_vector_from_quat(q_before.conjugate() * q_after) / span_s;
    const Vec3 v_body_before = q_before.conjugate() * before.v_ned_mps;
    const Vec3 v_body_after = q_after.conjugate() * after.v_ned_mps;
    const Vec3 v_body_now = C_bn * now.v_ned_mps;
    const Vec3 dv_body = (v_body_after - v_body_before) / span_s;
    a_ned = C_nb * (dv_body + w_nb_body.cross(v_body_now));
  }

  const Vec3 w_ie = earth_rate_ned_radps(now.position);
  const Vec3 w_en = transport_rate_ned_radps(now.position, now.v_ned_mps);
  IdealImu out;
  out.w_ib_body_radps = now.w_ib_body_radps ? *now.w_ib_body_radps
                                            : Vec3(w_nb_body + C_bn * (w_ie + w_en));
  out.f_body_mps2 =
      now.f_body_mps2
          ? *now.f_body_mps2
          : Vec3(C_bn * (a_ned + (2.0 * w_ie + w_en).cross(now.v_ned_mps) -
                         gravity_ned_mps2(now.position)));
  return out;
}

Strapdown::Strapdown(const StrapdownState& initial) : s_(initial) {
  s_.q_ned_from_body.normalize();
}

// Local-navigation-frame mechanization, [Groves] section 5.4 (eqs. 5.44-5.56) with the
// precision refinements of section 5.5, and [T&W] section 3.5:
//  attitude  C_nb+ = exp(-[w_in x] dt) C_nb exp([w_ib x] dt), both factors as exact
//            rotation-vector quaternions, w_in = w_ie + w_en;
//  velocity  v+ = v + (C_nb(mid) f + g - (2 w_ie + w_en) x v) dt, the specific force resolved
//            with the attitude at the middle of the interval;
//  position  h, latitude, longitude by the trapezoidal rule on the old and new velocity with
//            the radii of curvature ([Groves] eq. (5.56)).
void Strapdown::step(const Vec3& f_body_mps2, const Vec3& w_ib_body_radps, double dt_s) {
  const Geodetic p0 = s_.position;
  const Vec3 v0 = s_.v_ned_mps;
  const Quat q0 = s_.q_ned_from_body;

  const Vec3 w_ie = earth_rate_ned_radps(p0);
  const Vec3 w_en = transport_rate_ned_radps(p0, v0);
  const Vec3 w_in = w_ie + w_en;

  // Attitude, and the attitude half way through the interval.
  const Quat q_mid = (quat_from_rotation_vector(-0.5 * dt_s * w_in) * q0 *
                      quat_from_rotation_vector(0.5 * dt_s * w_ib_body_radps))
                         .normalized();
  const Quat q1 = (quat_from_rotation_vector(-dt_s * w_in) * q0 *
                   quat_from_rotation_vector(dt_s * w_ib_body_radps))
                      .normalized();

  // Velocity ([Groves] eq. (5.54)).
  const Vec3 f_ned = q_mid * f_body_mps2;
  const Vec3 v1 = v0 + (f_ned + gravity_ned_mps2(p0) - (2.0 * w_ie + w_en).cross(v0)) * dt_s;

  // Position ([Groves] eq. (5.56)).
  const double lat0 = p0.lat_deg * kDegToRad;
  const double lon0 = p0.lon_deg * kDegToRad;
  const double h1 = p0.h_m - 0.5 * dt_s * (v0.z() + v1.z());
  const double rn = meridian_radius_m(p0.lat_deg);
  const double lat1 = lat0 + 0.5 * dt_s * (v0.x() / (rn + p0.h_m) + v1.x() / (rn + h1));
  const double re0 = transverse_radius_m(p0.lat_deg);
  const double re1 = transverse_radius_m(lat1 * kRadToDeg);
  const double lon1 = lon0 + 0.5 * dt_s *
                                 (v0.y() / ((re0 + p0.h_m) * std::cos(lat0)) +
                                  v1.y() / ((re1 + h1) * std::cos(lat1)));

  s_.t = s_.t.plus_s(dt_s);
  s_.position = geodetic_rad(lat1, lon1, h1);
  s_.v_ned_mps = v1;
  s_.q_ned_from_body = q1;
}

Vec3 euler_rpy_from_quat(const Quat& q_ned_from_body) {
  // ZYX (yaw, pitch, roll) Euler angles of C_nb ([Groves] section 2.2.2, [T&W] section 3.6.3).
  const Mat3 C = q_ned_from_body.normalized().toRotationMatrix();
  const double roll = std::atan2(C(2, 1), C(2, 2));
  const double pitch = -std::asin(std::clamp(C(2, 0), -1.0, 1.0));
  const double yaw = std::atan2(C(1, 0), C(0, 0));
  return Vec3(roll, pitch, yaw);
}

Quat quat_from_euler_rpy(const Vec3& rpy_rad) {
  // C_nb = R_z(yaw) R_y(pitch) R_x(roll) ([Groves] section 2.2.2).
  return (Eigen::AngleAxisd(rpy_rad.z(), Vec3::UnitZ()) *
          Eigen::AngleAxisd(rpy_rad.y(), Vec3::UnitY()) *
          Eigen::AngleAxisd(rpy_rad.x(), Vec3::UnitX()))
      .normalized();
}

}  // namespace navemu
