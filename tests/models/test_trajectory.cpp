// Built-in trajectories (models/trajectory.hpp): the circle keeps its radius, cruises at its
// speed, lasts loops 2 pi R / v + v / a and stops at its start; the line's passes end at
// alternating ends; waypoints are visited in order; velocity is the time derivative of position;
// the ideal IMU on the circle senses the centripetal acceleration and the turn rate.

#include "models/trajectory.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace navemu {
namespace {

constexpr double kPiD = 3.14159265358979323846;
const GpsTime kStart = GpsTime::from_seconds(1'400'000'000.0);
const Geodetic kCenter{32.3, -90.9, 60.0};

Vec3 enu(const Geodetic& p, const Geodetic& origin) {
  return enu_from_ecef(ecef_from_geodetic(p), origin);
}

double yaw_deg(const ImuTruth& s) { return euler_rpy_from_quat(s.q_ned_from_body).z() * kRadToDeg; }

// The difference a - b of two angles in degrees, in (-180, 180].
double angle_diff_deg(double a, double b) {
  double d = std::fmod(a - b, 360.0);
  if (d > 180.0) d -= 360.0;
  if (d <= -180.0) d += 360.0;
  return d;
}

// The NED velocity from positions by the five-point central difference (fourth order, so that
// the truncation error is far below the rounding of latitude and longitude in degrees), with
// the radii of curvature at t: v_n = (R_N + h) dlat/dt, v_e = (R_E + h) cos(lat) dlon/dt,
// v_d = -dh/dt.
Vec3 velocity_by_differences(const Trajectory& traj, GpsTime t, double step_s = 0.01) {
  auto p = [&](double k) { return traj.at(t.plus_s(k * step_s)).position; };
  const Geodetic m2 = p(-2), m1 = p(-1), p1 = p(1), p2 = p(2), now = p(0);
  auto d = [&](double a2, double a1, double b1, double b2) {
    return (a2 - 8.0 * a1 + 8.0 * b1 - b2) / (12.0 * step_s);
  };
  auto dlon = [&](double lon) { return lon - now.lon_deg; };  // no antimeridian in these tests
  const double dlat_dt = d(m2.lat_deg, m1.lat_deg, p1.lat_deg, p2.lat_deg) * kDegToRad;
  const double dlon_dt =
      d(dlon(m2.lon_deg), dlon(m1.lon_deg), dlon(p1.lon_deg), dlon(p2.lon_deg)) * kDegToRad;
  const double dh_dt = d(m2.h_m, m1.h_m, p1.h_m, p2.h_m);
  return Vec3((meridian_radius_m(now.lat_deg) + now.h_m) * dlat_dt,
              (transverse_radius_m(now.lat_deg) + now.h_m) * std::cos(now.lat_deg * kDegToRad) *
                  dlon_dt,
              -dh_dt);
}

std::string error_of(auto make) {
  try {
    make();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(Trajectory, StationaryIsConstant) {
  const auto traj = make_trajectory(StationaryTrajectory{kCenter, 123.0}, kStart);
  EXPECT_EQ(traj->end(), kStart);
  for (double dt : {-10.0, 0.0, 3.5, 1e5}) {
    const ImuTruth s = traj->at(kStart.plus_s(dt));
    EXPECT_EQ(s.t, kStart.plus_s(dt));
    EXPECT_EQ(s.position.lat_deg, kCenter.lat_deg);
    EXPECT_EQ(s.position.lon_deg, kCenter.lon_deg);
    EXPECT_EQ(s.position.h_m, kCenter.h_m);
    EXPECT_EQ(s.v_ned_mps, Vec3::Zero());
    EXPECT_NEAR(yaw_deg(s), 123.0, 1e-12);
    EXPECT_FALSE(s.f_body_mps2 || s.w_ib_body_radps || s.temperature_c);
  }
}

TEST(Trajectory, CircleRadiusSpeedDurationAndEnd) {
  CircleTrajectory p;
  p.center = kCenter;
  p.radius_m = 9.144;
  p.speed_mps = 2.0;
  p.loops = 3;
  p.accel_mps2 = 0.5;
  const auto traj = make_trajectory(p, kStart);
  const double duration = p.loops * 2.0 * kPiD * p.radius_m / p.speed_mps + p.speed_mps / p.accel_mps2;
  EXPECT_NEAR(seconds_between(traj->end(), kStart), duration, 1e-9);

  const double ramp_s = p.speed_mps / p.accel_mps2;
  double max_radius_error = 0.0, max_speed_error = 0.0, max_up = 0.0;
  for (double t = -1.0; t < duration + 1.0; t += 0.01) {
    const ImuTruth s = traj->at(kStart.plus_s(t));
    const Vec3 e = enu(s.position, kCenter);
    max_radius_error = std::max(max_radius_error, std::abs(std::hypot(e.x(), e.y()) - p.radius_m));
    max_up = std::max(max_up, std::abs(e.z()));
    EXPECT_EQ(s.position.h_m, kCenter.h_m);
    EXPECT_EQ(s.v_ned_mps.z(), 0.0);
    if (t > ramp_s + 1e-6 && t < duration - ramp_s - 1e-6)
      max_speed_error = std::max(max_speed_error, std::abs(s.v_ned_mps.norm() - p.speed_mps));
    // Level, heading along the velocity when moving.
    const Vec3 rpy = euler_rpy_from_quat(s.q_ned_from_body);
    EXPECT_NEAR(rpy.x(), 0.0, 1e-12);
    EXPECT_NEAR(rpy.y(), 0.0, 1e-12);
    if (s.v_ned_mps.norm() > 1e-3) {
      EXPECT_NEAR(angle_diff_deg(yaw_deg(s), std::atan2(s.v_ned_mps.y(), s.v_ned_mps.x()) * kRadToDeg),
                  0.0, 1e-9);
    }
  }
  std::printf("circle: radius error %.3g m, cruise speed error %.3g m/s, up %.3g m\n",
              max_radius_error, max_speed_error, max_up);
  EXPECT_LT(max_radius_error, 1e-3);
  EXPECT_LT(max_speed_error, 1e-9);
  EXPECT_LT(max_up, 1e-5);  // the ellipsoid's curvature over 9 m: R^2 / (2 R_earth) ~ 7 um

  // Starts at the southern point heading east (counter-clockwise), at rest; ends there, at rest.
  for (GpsTime t : {kStart.plus_s(-5.0), kStart, traj->end(), traj->end().plus_s(60.0)}) {
    const ImuTruth s = traj->at(t);
    const Vec3 e = enu(s.position, kCenter);
    EXPECT_NEAR(e.x(), 0.0, 1e-8);
    EXPECT_NEAR(e.y(), -p.radius_m, 1e-8);
    EXPECT_LT(s.v_ned_mps.norm(), 1e-9);  // end() is rounded to the nanosecond
    EXPECT_NEAR(yaw_deg(s), 90.0, 1e-6);
  }
  const ImuTruth moving = traj->at(kStart.plus_s(0.1));
  EXPECT_GT(moving.v_ned_mps.y(), 0.0);
  EXPECT_NEAR(moving.v_ned_mps.y(), 0.05, 1e-6);  // a t
  // A quarter loop later (arc pi R / 2 after the ramp's v^2 / 2a): the eastern point, heading
  // north. (Yaw is measured from the local north, which turns from the centre's by the meridian
  // convergence, (lon - lon0) sin(lat), 5e-5 deg at 9 m east.)
  const double t_quarter = ramp_s + (kPiD * p.radius_m / 2.0 - 0.5 * p.speed_mps * ramp_s) / p.speed_mps;
  const ImuTruth q = traj->at(kStart.plus_s(t_quarter));
  EXPECT_NEAR(enu(q.position, kCenter).x(), p.radius_m, 1e-6);
  EXPECT_NEAR(enu(q.position, kCenter).y(), 0.0, 1e-6);
  EXPECT_NEAR(yaw_deg(q), 0.0, 1e-4);
}

TEST(Trajectory, CircleClockwiseStartsWestAndShortCirclesUseATriangle) {
  CircleTrajectory p;
  p.center = kCenter;
  p.radius_m = 0.1;
  p.speed_mps = 5.0;
  p.loops = 1;
  p.clockwise = true;
  p.accel_mps2 = 1.0;
  const auto traj = make_trajectory(p, kStart);
  // 2 pi R = 0.63 m < v^2 / a = 25 m: the speed peaks at sqrt(L a) in the middle.
  const double length = 2.0 * kPiD * p.radius_m;
  EXPECT_NEAR(seconds_between(traj->end(), kStart), 2.0 * std::sqrt(length / p.accel_mps2), 1e-9);
  const ImuTruth early = traj->at(kStart.plus_s(0.01));
  EXPECT_LT(early.v_ned_mps.y(), 0.0);  // west
  EXPECT_NEAR(yaw_deg(early), -90.0, 0.1);
  const ImuTruth mid = traj->at(kStart.plus_s(std::sqrt(length / p.accel_mps2)));
  EXPECT_NEAR(mid.v_ned_mps.norm(), std::sqrt(length * p.accel_mps2), 1e-9);
  EXPECT_NEAR(enu(mid.position, kCenter).y(), p.radius_m, 1e-9);  // half way: the north point
  const Vec3 end = enu(traj->at(traj->end()).position, kCenter);
  EXPECT_NEAR(end.x(), 0.0, 1e-9);
  EXPECT_NEAR(end.y(), -p.radius_m, 1e-9);
}

TEST(Trajectory, CircleForever) {
  CircleTrajectory p;
  p.center = kCenter;
  p.loops = 0;
  const auto traj = make_trajectory(p, kStart);
  EXPECT_EQ(traj->end().ns, std::numeric_limits<std::int64_t>::max());
  const ImuTruth s = traj->at(kStart.plus_s(1e6));  // ~17,000 loops later
  EXPECT_NEAR(std::hypot(enu(s.position, kCenter).x(), enu(s.position, kCenter).y()), p.radius_m,
              1e-6);
  EXPECT_NEAR(s.v_ned_mps.norm(), p.speed_mps, 1e-9);
}

TEST(Trajectory, VelocityIsTheDerivativeOfPosition) {
  CircleTrajectory c;
  c.center = kCenter;
  c.speed_mps = 2.0;
  c.loops = 2;
  LineTrajectory l;
  l.start = {-33.9, 151.2, 40.0};
  l.heading_deg = 30.0;
  l.passes = 3;
  WaypointTrajectory w;
  w.waypoints = {{47.0, 8.0, 400.0}, {47.001, 8.0, 400.0}, {47.001, 8.002, 415.0}, {47.0, 8.0, 400.0}};
  w.speed_mps = 3.0;
  const std::unique_ptr<Trajectory> trajectories[] = {
      make_trajectory(c, kStart), make_trajectory(l, kStart), make_trajectory(w, kStart)};
  for (const auto& traj : trajectories) {
    const double duration = seconds_between(traj->end(), kStart);
    double max_error = 0.0;
    int checked = 0;
    for (double t = 0.0137; t < duration; t += 0.1) {
      // Skip stencils that straddle a jump of the acceleration (start or end of a ramp or turn):
      // there the velocity's derivative, not the velocity, is discontinuous.
      const GpsTime now = kStart.plus_s(t);
      const Vec3 a_before = (traj->at(now).v_ned_mps - traj->at(now.plus_s(-0.02)).v_ned_mps) / 0.02;
      const Vec3 a_after = (traj->at(now.plus_s(0.02)).v_ned_mps - traj->at(now).v_ned_mps) / 0.02;
      if ((a_after - a_before).norm() > 1e-2) continue;
      max_error = std::max(max_error, (velocity_by_differences(*traj, now) - traj->at(now).v_ned_mps).norm());
      ++checked;
    }
    std::printf("velocity against differenced position: %.3g m/s over %d instants\n", max_error,
                checked);
    EXPECT_GT(checked, 100);
    EXPECT_LT(max_error, 1e-6);
  }
}

TEST(Trajectory, ImuOnTheCircleSensesCentripetalAccelerationAndTurnRate) {
  CircleTrajectory p;
  p.center = kCenter;
  p.radius_m = 9.144;
  p.speed_mps = 2.0;
  p.loops = 2;
  const auto traj = make_trajectory(p, kStart);
  const double v = p.speed_mps, r = p.radius_m;
  for (double t : {5.0, 12.3, 20.0, 27.7}) {  // in the cruise (ramp: the first 4 s)
    const GpsTime now = kStart.plus_s(t);
    const ImuTruth s = traj->at(now);
    const IdealImu imu =
        ideal_imu_from_kinematics(traj->at(now.plus_s(-0.01)), s, traj->at(now.plus_s(0.01)));
    // Remove what the Earth's rotation and gravity add, to get the body's rate and acceleration
    // relative to the Earth: w_eb = w_ib - C_bn w_ie, a = f - C_bn (2 w_ie x v - g)
    // ([Groves] section 5.4; the transport rate stays in: a = dv_ned/dt + w_en x v).
    const Mat3 C_bn = s.q_ned_from_body.toRotationMatrix().transpose();
    const Vec3 w_ie = earth_rate_ned_radps(s.position);
    const Vec3 w_eb = imu.w_ib_body_radps - C_bn * w_ie;
    const Vec3 a_body =
        imu.f_body_mps2 - C_bn * (2.0 * w_ie.cross(s.v_ned_mps) - gravity_ned_mps2(s.position));
    // Counter-clockwise seen from above is a left turn: the centre lies to the left, which is
    // -y in the FRD body frame (y points right), so the centripetal acceleration is -v^2/R
    // along y; the heading decreases (yaw is positive clockwise about the down axis), so the
    // yaw rate is -v/R about z. Down (+z): v^2 / (R_earth + h), ~6e-7 m/s^2, from following the
    // ellipsoid's curvature at a constant height.
    const double curvature_mps2 =
        s.v_ned_mps.x() * s.v_ned_mps.x() / (meridian_radius_m(s.position.lat_deg) + s.position.h_m) +
        s.v_ned_mps.y() * s.v_ned_mps.y() / (transverse_radius_m(s.position.lat_deg) + s.position.h_m);
    EXPECT_NEAR(a_body.x(), 0.0, 1e-7) << t;
    EXPECT_NEAR(a_body.y(), -v * v / r, 1e-7) << t;
    EXPECT_NEAR(a_body.z(), curvature_mps2, 1e-7) << t;
    // Keeping level over the curved Earth, the body turns with the local vertical: the transport
    // rate's horizontal components (v / R_earth, ~3e-7 rad/s) about x and y.
    const Vec3 w_en_body = C_bn * transport_rate_ned_radps(s.position, s.v_ned_mps);
    EXPECT_NEAR(w_eb.x(), w_en_body.x(), 1e-9) << t;
    EXPECT_NEAR(w_eb.y(), w_en_body.y(), 1e-9) << t;
    EXPECT_NEAR(w_eb.z(), -v / r, 1e-9) << t;
    // The raw outputs, with the Earth's terms (Coriolis 2 W v < 3e-4 m/s^2, Earth rate 7.3e-5
    // rad/s) inside the tolerance.
    EXPECT_NEAR(imu.f_body_mps2.y(), -v * v / r, 5e-4) << t;
    EXPECT_NEAR(imu.w_ib_body_radps.z(), -v / r, 1e-4) << t;
    EXPECT_LT(imu.f_body_mps2.z(), -9.7);
  }
}

TEST(Trajectory, LinePassesEndAtAlternatingEnds) {
  LineTrajectory p;
  p.start = kCenter;
  p.heading_deg = 30.0;
  p.length_m = 18.288;
  p.speed_mps = 1.0;
  p.passes = 3;
  p.accel_mps2 = 0.5;
  p.turn_rate_dps = 45.0;
  const auto traj = make_trajectory(p, kStart);
  const double pass_s = p.length_m / p.speed_mps + p.speed_mps / p.accel_mps2;
  const double turn_s = 180.0 / p.turn_rate_dps;
  EXPECT_NEAR(seconds_between(traj->end(), kStart), 3 * pass_s + 2 * turn_s, 1e-9);
  const Vec3 far = p.length_m * Vec3(std::sin(30.0 * kDegToRad), std::cos(30.0 * kDegToRad), 0.0);
  auto horizontal_error = [&](double t, const Vec3& want) {
    const Vec3 e = enu(traj->at(kStart.plus_s(t)).position, p.start);
    return std::hypot(e.x() - want.x(), e.y() - want.y());
  };
  EXPECT_LT(horizontal_error(0.0, Vec3::Zero()), 1e-9);
  EXPECT_LT(horizontal_error(pass_s, far), 1e-6);
  EXPECT_LT(horizontal_error(pass_s + turn_s, far), 1e-6);
  EXPECT_LT(horizontal_error(2 * pass_s + turn_s, Vec3::Zero()), 1e-6);
  EXPECT_LT(horizontal_error(2 * pass_s + 2 * turn_s, Vec3::Zero()), 1e-6);
  EXPECT_LT(horizontal_error(3 * pass_s + 2 * turn_s, far), 1e-6);
  EXPECT_LT(horizontal_error(3 * pass_s + 2 * turn_s + 100.0, far), 1e-6);
  // Half way through each pass: cruising along the line, out and back. (Yaw from the local
  // north, within the meridian convergence of the start's, 3e-5 deg at 9 m.)
  EXPECT_NEAR(yaw_deg(traj->at(kStart.plus_s(pass_s / 2))), 30.0, 1e-4);
  EXPECT_NEAR(traj->at(kStart.plus_s(pass_s / 2)).v_ned_mps.norm(), 1.0, 1e-9);
  EXPECT_NEAR(yaw_deg(traj->at(kStart.plus_s(1.5 * pass_s + turn_s))), -150.0, 1e-4);
  EXPECT_LT(horizontal_error(pass_s / 2, 0.5 * far), 1e-6);
  // Turning in place to the right at the turn rate: 45 deg after 1 s.
  const ImuTruth turning = traj->at(kStart.plus_s(pass_s + 1.0));
  EXPECT_EQ(turning.v_ned_mps.norm(), 0.0);
  EXPECT_NEAR(yaw_deg(turning), 75.0, 1e-4);
  EXPECT_NEAR(yaw_deg(traj->at(kStart.plus_s(pass_s + 1.0))) -
                  yaw_deg(traj->at(kStart.plus_s(pass_s + 0.5))),
              22.5, 1e-9);
  EXPECT_EQ(traj->at(kStart.plus_s(7.7)).position.h_m, p.start.h_m);

  // A line too short to reach the speed: a triangular profile, 2 sqrt(L / a) per pass.
  p.length_m = 0.5;
  p.speed_mps = 2.0;
  p.passes = 2;
  const auto short_line = make_trajectory(p, kStart);
  EXPECT_NEAR(seconds_between(short_line->end(), kStart), 2 * 2.0 * std::sqrt(0.5 / 0.5) + turn_s,
              1e-9);

  // Forever: the pass count keeps growing, the geometry repeats.
  p.passes = 0;
  const auto forever = make_trajectory(p, kStart);
  EXPECT_EQ(forever->end().ns, std::numeric_limits<std::int64_t>::max());
  const double period = 2.0 + turn_s;
  const Vec3 e = enu(forever->at(kStart.plus_s(1001 * period + 1.0)).position, p.start);
  EXPECT_NEAR(std::hypot(e.x(), e.y()), 0.25, 1e-6);  // pass 1001, half way back
}

// Stops: the vehicle stands still at a waypoint for stop_s, then goes on; the whole run is
// longer by the sum of the stops.
TEST(Trajectory, WaypointStopsHoldTheVehicleAtTheWaypoint) {
  WaypointTrajectory p;
  p.waypoints = {{32.3, -90.9, 60.0}, {32.3002, -90.9, 60.0}, {32.3002, -90.8997, 60.0}};
  p.speed_mps = 2.0;
  const auto plain = make_trajectory(p, kStart);
  p.stop_s = {5.0, 30.0};
  const auto stopping = make_trajectory(p, kStart);
  EXPECT_NEAR(seconds_between(stopping->end(), plain->end()), 35.0, 1e-9);
  // Standing at the first waypoint for 5 s, then at the second for 30 s.
  for (double t : {0.0, 2.5, 4.99}) {
    const ImuTruth s = stopping->at(kStart.plus_s(t));
    EXPECT_EQ(s.v_ned_mps.norm(), 0.0) << t;
    EXPECT_NEAR((ecef_from_geodetic(s.position) - ecef_from_geodetic(p.waypoints[0])).norm(), 0.0, 1e-6);
  }
  double arrive = 0.0;  // first time at the second waypoint
  for (double t = 5.0; t < 100.0 && arrive == 0.0; t += 0.01)
    if ((ecef_from_geodetic(stopping->at(kStart.plus_s(t)).position) -
         ecef_from_geodetic(p.waypoints[1])).norm() < 1e-6)
      arrive = t;
  ASSERT_GT(arrive, 5.0);
  for (double dt : {1.0, 15.0, 29.0}) {
    const ImuTruth s = stopping->at(kStart.plus_s(arrive + dt));
    EXPECT_LT(s.v_ned_mps.norm(), 1e-9) << dt;
    EXPECT_NEAR((ecef_from_geodetic(s.position) - ecef_from_geodetic(p.waypoints[1])).norm(), 0.0, 1e-6) << dt;
  }
  p.stop_s = {-1.0};
  EXPECT_THROW(make_trajectory(p, kStart), std::invalid_argument);
}

TEST(Trajectory, WaypointsAreVisitedInOrder) {
  WaypointTrajectory p;
  p.waypoints = {{32.3, -90.9, 60.0},
                 {32.3002, -90.9, 60.0},
                 {32.3002, -90.8997, 65.0},
                 {32.3, -90.8999, 62.0}};
  p.speed_mps = 2.0;
  p.accel_mps2 = 0.5;
  p.turn_rate_dps = 90.0;
  const auto traj = make_trajectory(p, kStart);
  const double duration = seconds_between(traj->end(), kStart);
  std::size_t next = 0;  // the next waypoint to reach
  std::vector<double> reached_at;
  for (double t = 0.0; t <= duration + 1.0 && next < p.waypoints.size(); t += 0.01) {
    const ImuTruth s = traj->at(kStart.plus_s(t));
    if ((ecef_from_geodetic(s.position) - ecef_from_geodetic(p.waypoints[next])).norm() < 1e-6) {
      reached_at.push_back(t);
      // Stopped there, or within 1 um of stopping: v = sqrt(2 a d) < 1e-3 m/s.
      EXPECT_LT(s.v_ned_mps.norm(), 1e-3) << next;
      ++next;
    }
  }
  ASSERT_EQ(next, p.waypoints.size());
  const ImuTruth last = traj->at(traj->end().plus_s(10.0));
  EXPECT_EQ(last.position.h_m, 62.0);
  EXPECT_NEAR(last.position.lat_deg, 32.3, 1e-12);
  EXPECT_NEAR(last.position.lon_deg, -90.8999, 1e-12);
  // Heading north to the first waypoint, then (after a right turn) east.
  EXPECT_NEAR(yaw_deg(traj->at(kStart)), 0.0, 1e-3);
  EXPECT_NEAR(yaw_deg(traj->at(kStart.plus_s((reached_at[1] + reached_at[2]) / 2))), 90.0, 0.01);
  // Climbing 5 m over the second leg: v_d < 0 while moving.
  EXPECT_LT(traj->at(kStart.plus_s((reached_at[1] + reached_at[2]) / 2)).v_ned_mps.z(), -0.01);
  // The turn at the second waypoint, from the first leg's heading to the second's (about 90 deg:
  // the chords of the origin's plane meet the local meridians at slightly different angles),
  // at a constant 90 deg/s.
  const double arrival = reached_at[1];
  const double y0 = yaw_deg(traj->at(kStart.plus_s(arrival - 1e-6)));
  const double leave = arrival + 5.0;  // well into the second leg, to get its heading
  const double y1 = yaw_deg(traj->at(kStart.plus_s(leave)));
  EXPECT_NEAR(y1 - y0, 90.0, 0.1);
  const double turn_s = (y1 - y0) / 90.0;
  const ImuTruth mid_turn = traj->at(kStart.plus_s(arrival + 0.5 * turn_s));
  EXPECT_EQ(mid_turn.v_ned_mps.norm(), 0.0);
  EXPECT_NEAR(yaw_deg(mid_turn), 0.5 * (y0 + y1), 1e-3);
}

TEST(Trajectory, BadParametersAreNamed) {
  auto circle = [](auto change) {
    CircleTrajectory p;
    p.center = kCenter;
    change(p);
    return error_of([&] { make_trajectory(p, kStart); });
  };
  EXPECT_NE(circle([](CircleTrajectory& p) { p.radius_m = 0.0; }).find("radius_m"), std::string::npos);
  EXPECT_NE(circle([](CircleTrajectory& p) { p.speed_mps = -1.0; }).find("speed_mps"), std::string::npos);
  EXPECT_NE(circle([](CircleTrajectory& p) { p.accel_mps2 = std::nan(""); }).find("accel_mps2"),
            std::string::npos);
  EXPECT_NE(circle([](CircleTrajectory& p) { p.loops = -1; }).find("loops"), std::string::npos);
  EXPECT_NE(circle([](CircleTrajectory& p) { p.center.lat_deg = 91.0; }).find("center.lat_deg"),
            std::string::npos);
  EXPECT_EQ(circle([](CircleTrajectory&) {}), "");

  LineTrajectory l;
  l.start = kCenter;
  l.turn_rate_dps = 0.0;
  EXPECT_NE(error_of([&] { make_trajectory(l, kStart); }).find("turn_rate_dps"), std::string::npos);
  l.turn_rate_dps = 45.0;
  l.passes = -3;
  EXPECT_NE(error_of([&] { make_trajectory(l, kStart); }).find("passes"), std::string::npos);
  l.passes = 1;
  l.length_m = std::numeric_limits<double>::infinity();
  EXPECT_NE(error_of([&] { make_trajectory(l, kStart); }).find("length_m"), std::string::npos);

  WaypointTrajectory w;
  w.waypoints = {kCenter};
  EXPECT_NE(error_of([&] { make_trajectory(w, kStart); }).find("waypoints"), std::string::npos);
  w.waypoints = {kCenter, kCenter};
  EXPECT_NE(error_of([&] { make_trajectory(w, kStart); }).find("waypoints[1]"), std::string::npos);
  w.waypoints = {kCenter, {32.31, -90.9, std::nan("")}};
  EXPECT_NE(error_of([&] { make_trajectory(w, kStart); }).find("waypoints[1].h_m"), std::string::npos);

  EXPECT_NE(error_of([&] { make_trajectory(StationaryTrajectory{{-95.0, 0.0, 0.0}, 0.0}, kStart); })
                .find("position.lat_deg"),
            std::string::npos);
}

}  // namespace
}  // namespace navemu
