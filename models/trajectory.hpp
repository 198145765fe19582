#pragma once
// Built-in truth generators: vehicle trajectories as pure functions of time, for runs without
// a simulator. Each gives position, velocity over the Earth (NED) and attitude (level, the FRD
// body's x axis along the direction of travel) at any GPS time, and every motion is smooth
// enough for the IMU's kinematic derivation (models/imu_kinematics.hpp): speeds ramp with a
// bounded acceleration (trapezoidal speed profiles, a triangle when a path is too short to
// reach the speed) and headings turn in place at a constant yaw rate. Geometry is laid out in
// the local east-north-up plane of the origin (GeographicLib::LocalCartesian: the circle's
// centre, the line's start, the first waypoint) and mapped to latitude and longitude; heights
// are constant (waypoints: changing in proportion to the distance along each leg). Velocity
// over the Earth is the exact time derivative of the position; yaw is measured from the local
// north, so a straight line of the plane turns by the meridian convergence ((lon - lon0)
// sin(lat), 5e-5 deg at 9 m east at 32 deg latitude).
// Before the start time the vehicle waits at its first point; after the last loop or pass it
// stays at its last point.

#include <memory>
#include <vector>

#include "models/geodesy.hpp"
#include "models/imu_kinematics.hpp"
#include "core/time.hpp"

namespace navemu {

class Trajectory {
 public:
  virtual ~Trajectory() = default;
  // The truth at t (t.t set; f/w and temperature unset).
  virtual ImuTruth at(GpsTime t) const = 0;
  // When the motion ends (the vehicle stands still after it); the start for a stationary one;
  // GpsTime{INT64_MAX} for one that goes on forever (loops or passes 0).
  virtual GpsTime end() const = 0;
};

struct StationaryTrajectory {
  Geodetic position;
  double yaw_deg = 0.0;
};

// The paper's circle track (section 3: 30 ft radius, 8 loops). Starts at the circle's southern
// point heading east (counter-clockwise seen from above) or west (clockwise); accelerates to
// speed along the circle, runs the loops, decelerates to a stop at the start point: the
// `loops` 2 pi R of arc include both ramps, so the motion lasts loops 2 pi R / v + v / a.
// Counter-clockwise is a left turn: centripetal acceleration -v^2/R along the FRD body's y,
// yaw rate -v/R about z.
struct CircleTrajectory {
  Geodetic center;
  double radius_m = 9.144;
  double speed_mps = 1.0;
  int loops = 8;  // 0: forever
  bool clockwise = false;
  double accel_mps2 = 0.5;
};

// The paper's linear track (60 ft, 10 passes): from `start` along `heading_deg`, `length_m`
// per pass; stops at each end, turns in place through 180 deg at `turn_rate_dps` (always to the
// right, yaw increasing), goes back. Lasts passes (L/v + v/a) + (passes - 1) 180 / rate.
struct LineTrajectory {
  Geodetic start;
  double heading_deg = 0.0;
  double length_m = 18.288;
  double speed_mps = 1.0;
  int passes = 10;  // 0: forever
  double accel_mps2 = 0.5;
  double turn_rate_dps = 45.0;
};

// Through the waypoints in order at a constant cruise speed: starts from rest, stops at each
// waypoint, turns in place toward the next by the smaller angle (as a skid-steer robot does),
// stops at the last. Each leg is straight in the first waypoint's ENU frame; its length (and
// the speed) counts the change of height. Consecutive waypoints must lie at least 1 mm apart
// horizontally.
struct WaypointTrajectory {
  std::vector<Geodetic> waypoints;  // at least 2
  // Seconds standing still on arrival at each waypoint (before turning to the next leg); may
  // be shorter than waypoints (missing entries: 0). A stop at the first delays the departure.
  std::vector<double> stop_s;
  double speed_mps = 1.0;
  double accel_mps2 = 0.5;
  double turn_rate_dps = 45.0;
};

// Trajectories starting their motion at `start`. Parameters are checked: std::invalid_argument
// naming the parameter when one is out of range (non-positive radius, speed, acceleration;
// fewer than two waypoints; ...).
std::unique_ptr<Trajectory> make_trajectory(const StationaryTrajectory& p, GpsTime start);
std::unique_ptr<Trajectory> make_trajectory(const CircleTrajectory& p, GpsTime start);
std::unique_ptr<Trajectory> make_trajectory(const LineTrajectory& p, GpsTime start);
std::unique_ptr<Trajectory> make_trajectory(const WaypointTrajectory& p, GpsTime start);

}  // namespace navemu
