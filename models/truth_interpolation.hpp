#pragma once
// Interpolation of vehicle truth between two states (shared by the CSV track and the streamed
// truth buffer):
//   position  cubic Hermite on latitude, longitude (unwrapped) and height, with the states'
//             velocities as derivatives: dlat/dt = v_n / (R_N + h), dlon/dt = v_e / ((R_E + h)
//             cos lat), dh/dt = -v_d (R_N, R_E the WGS-84 radii of curvature);
//   velocity  cubic Hermite when accelerations (dv/dt at a and b) are both given, else linear;
//   attitude  slerp of the quaternions (the shorter arc; exact for a constant body rate);
//   f, w, temperature  linear when both states carry them.
// At t = a.t (b.t) the result is a's (b's) position, velocity and attitude unchanged, the
// longitude wrapped to [-180, 180) as every result's is.

#include <optional>

#include "models/imu_kinematics.hpp"

namespace navemu {

// The state at t, a.t <= t <= b.t, a.t < b.t (t outside is clamped to the interval for the
// values; the result's t is t).
ImuTruth interpolate_truth(const ImuTruth& a, const ImuTruth& b, GpsTime t,
                           const std::optional<Vec3>& dv_a_ned_mps2 = {},
                           const std::optional<Vec3>& dv_b_ned_mps2 = {});

// Constant-velocity extrapolation from `a` to t >= a.t (attitude, f, w, temperature held):
// latitude, longitude and height advanced at the rates of the velocity over the Earth, by the
// midpoint rule (exact along a parallel or the vertical; ~1e-9 relative error over a second).
ImuTruth extrapolate_truth(const ImuTruth& a, GpsTime t);

}  // namespace navemu
