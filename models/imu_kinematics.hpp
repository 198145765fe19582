#pragma once
// What an ideal strapdown IMU senses, and strapdown dead reckoning.
//
// Frames: navigation frame NED (north, east, down) at the vehicle; body frame FRD (x forward,
// y right, z down). Attitude is q_ned_from_body (rotates body vectors into NED). A level,
// stationary IMU therefore senses specific force f_body = (0, 0, -g) and angular rate
// w_ib_body = Earth rotation projected on its axes: (W cos(lat), 0, -W sin(lat)) when facing
// north.

#include <Eigen/Geometry>
#include <optional>

#include "models/geodesy.hpp"
#include "core/time.hpp"

namespace navemu {

using Quat = Eigen::Quaterniond;

// The vehicle's true state at one instant.
struct ImuTruth {
  GpsTime t;
  Geodetic position;
  Vec3 v_ned_mps = Vec3::Zero();
  Quat q_ned_from_body = Quat::Identity();
  // When the simulator provides them, used as they are; otherwise derived from the kinematics.
  std::optional<Vec3> f_body_mps2;
  std::optional<Vec3> w_ib_body_radps;
  std::optional<double> temperature_c;
};

// Ideal (error-free) IMU output.
struct IdealImu {
  Vec3 f_body_mps2 = Vec3::Zero();     // specific force a - g
  Vec3 w_ib_body_radps = Vec3::Zero();  // angular rate relative to inertial space
};

// Normal gravity (WGS-84, GeographicLib::NormalGravity) in NED at a position: gravitation plus
// centrifugal, (0, 0, ~9.8) m/s^2 with a small north component.
Vec3 gravity_ned_mps2(const Geodetic& where);
// Earth rotation in NED, and the transport rate of a vehicle moving with v_ned.
Vec3 earth_rate_ned_radps(const Geodetic& where);
Vec3 transport_rate_ned_radps(const Geodetic& where, const Vec3& v_ned_mps);

// A stationary IMU at `where` with attitude q_ned_from_body.
IdealImu ideal_imu_static(const Geodetic& where, const Quat& q_ned_from_body);

// The ideal output at `now` from three consecutive truth states (before, now, after):
// w_ib = w_nb + C_bn (w_ie + w_en), f = C_bn (dv/dt + (2 w_ie + w_en) x v - g), with dv/dt and
// w_nb by central differences. Provided f/w in `now` take precedence.
// (w_nb: rotation vector of q_before^-1 q_after over the span; dv/dt = C_nb (dv_body/dt +
// w_nb x v_body) with the body-frame velocity differenced; exact for constant body rate and
// velocity, e.g. circles at constant speed. Details in imu_kinematics.cpp.)
IdealImu ideal_imu_from_kinematics(const ImuTruth& before, const ImuTruth& now,
                                   const ImuTruth& after);

// Strapdown integration in NED (attitude by the rotation-vector quaternion update, velocity with
// gravity and Coriolis, position on the ellipsoid); samples in, state out.
struct StrapdownState {
  GpsTime t;
  Geodetic position;
  Vec3 v_ned_mps = Vec3::Zero();
  Quat q_ned_from_body = Quat::Identity();
};

class Strapdown {
 public:
  explicit Strapdown(const StrapdownState& initial);
  // Integrates one sample held over dt_s.
  void step(const Vec3& f_body_mps2, const Vec3& w_ib_body_radps, double dt_s);
  const StrapdownState& state() const { return s_; }

 private:
  StrapdownState s_;
};

// Roll, pitch, yaw (rad, ZYX Euler) of q_ned_from_body, and back.
Vec3 euler_rpy_from_quat(const Quat& q_ned_from_body);
Quat quat_from_euler_rpy(const Vec3& rpy_rad);

// WGS-84 radii of curvature (m) at a geodetic latitude (deg): meridian (north-south) and
// transverse (prime vertical, east-west).
double meridian_radius_m(double lat_deg);
double transverse_radius_m(double lat_deg);

// The unit quaternion of a rotation vector (axis times angle, rad), and back (angle in [0, pi]).
Quat quat_from_rotation_vector(const Vec3& phi_rad);
Vec3 rotation_vector_from_quat(const Quat& q);

}  // namespace navemu
