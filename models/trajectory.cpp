#include "models/trajectory.hpp"

#include <GeographicLib/LocalCartesian.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

// References:
//  [Groves] P. D. Groves, Principles of GNSS, Inertial, and Multisensor Integrated Navigation
//           Systems, 2nd ed., Artech House, 2013.
//  [GeographicLib] C. F. F. Karney, GeographicLib, LocalCartesian class documentation.

namespace navemu {

namespace {

constexpr double kTwoPiExact = 2.0 * 3.14159265358979323846;
constexpr double kPiExact = 3.14159265358979323846;
constexpr GpsTime kForever{std::numeric_limits<std::int64_t>::max()};

// ---- parameter checks ------------------------------------------------------------------------

[[noreturn]] void bad(const std::string& what, const std::string& param, const std::string& problem,
                      double value) {
  throw std::invalid_argument(
      fmt::format("{} trajectory: {} {} (got {})", what, param, problem, value));
}

void check_positive(const char* what, const char* param, double value) {
  if (!(std::isfinite(value) && value > 0.0)) bad(what, param, "must be positive and finite", value);
}

void check_finite(const char* what, const std::string& param, double value) {
  if (!std::isfinite(value)) bad(what, param, "must be finite", value);
}

void check_count(const char* what, const char* param, int value) {
  if (value < 0) bad(what, param, "must be 0 (forever) or positive", value);
}

void check_position(const char* what, const std::string& param, const Geodetic& g) {
  if (!(std::isfinite(g.lat_deg) && std::abs(g.lat_deg) <= 90.0))
    bad(what, param + ".lat_deg", "must lie in [-90, 90]", g.lat_deg);
  check_finite(what, param + ".lon_deg", g.lon_deg);
  check_finite(what, param + ".h_m", g.h_m);
}

// ---- speed profile ---------------------------------------------------------------------------

// Distance along a path of `length_m` from rest to rest: accelerate at `accel` to `speed`,
// cruise, decelerate at `accel` to a stop at the end (the trapezoidal speed profile); a triangle
// reaching sqrt(length * accel) when the path is shorter than speed^2 / accel. An infinite
// length accelerates and then cruises forever.
class SpeedProfile {
 public:
  SpeedProfile(double length_m, double speed_mps, double accel_mps2)
      : length_m_(length_m), accel_(accel_mps2) {
    if (std::isinf(length_m)) {
      peak_mps_ = speed_mps;
      t_accel_s_ = speed_mps / accel_mps2;
      s_accel_m_ = 0.5 * speed_mps * t_accel_s_;
      t_cruise_s_ = std::numeric_limits<double>::infinity();
    } else if (length_m >= speed_mps * speed_mps / accel_mps2) {
      peak_mps_ = speed_mps;
      t_accel_s_ = speed_mps / accel_mps2;
      s_accel_m_ = 0.5 * speed_mps * t_accel_s_;
      t_cruise_s_ = (length_m - 2.0 * s_accel_m_) / speed_mps;
    } else {
      peak_mps_ = std::sqrt(length_m * accel_mps2);
      t_accel_s_ = peak_mps_ / accel_mps2;
      s_accel_m_ = 0.5 * length_m;
      t_cruise_s_ = 0.0;
    }
    duration_s_ = 2.0 * t_accel_s_ + t_cruise_s_;
  }

  double duration_s() const { return duration_s_; }

  // Distance s (m) and speed ds/dt (m/s) at `tau_s` after the start.
  void at(double tau_s, double& s_m, double& sdot_mps) const {
    if (tau_s <= 0.0) {
      s_m = 0.0;
      sdot_mps = 0.0;
    } else if (tau_s < t_accel_s_) {
      s_m = 0.5 * accel_ * tau_s * tau_s;
      sdot_mps = accel_ * tau_s;
    } else if (tau_s < t_accel_s_ + t_cruise_s_) {
      s_m = s_accel_m_ + peak_mps_ * (tau_s - t_accel_s_);
      sdot_mps = peak_mps_;
    } else if (tau_s < duration_s_) {
      const double r = duration_s_ - tau_s;  // time left to the stop
      s_m = length_m_ - 0.5 * accel_ * r * r;
      sdot_mps = accel_ * r;
    } else {
      s_m = length_m_;
      sdot_mps = 0.0;
    }
  }

 private:
  double length_m_;
  double accel_;
  double peak_mps_ = 0.0;
  double t_accel_s_ = 0.0;
  double s_accel_m_ = 0.0;
  double t_cruise_s_ = 0.0;
  double duration_s_ = 0.0;
};

// ---- the local plane -------------------------------------------------------------------------

// Geometry laid out in the east-north-up frame of an origin (GeographicLib::LocalCartesian), the
// vehicle given its own height. A point P(t) of that frame maps to latitude and longitude by
// LocalCartesian::Reverse; its velocity dP/dt, rotated into the local ENU frame at the point
// (R_enu_from_ecef(point) R_enu_from_ecef(origin)^T, the transpose of the matrix M of
// LocalCartesian::Reverse), gives the rates of latitude and longitude ([Groves] eq. (2.111)):
//   dlat/dt = v_n,P / (R_N + h_P),   dlon/dt = v_e,P / ((R_E + h_P) cos lat)
// with h_P the point's own height. The vehicle, at the same latitude and longitude but at the
// height h, moves over the Earth with
//   v_n = (R_N + h) dlat/dt,   v_e = (R_E + h) cos(lat) dlon/dt,   v_d = -dh/dt,
// the exact time derivative of its position.
class LocalPlane {
 public:
  explicit LocalPlane(const Geodetic& origin)
      : cartesian_(origin.lat_deg, origin.lon_deg, origin.h_m),
        R_ecef_from_enu0_(R_enu_from_ecef(origin).transpose()) {}

  Vec3 enu(const Geodetic& g) const {
    Vec3 p;
    cartesian_.Forward(g.lat_deg, g.lon_deg, g.h_m, p.x(), p.y(), p.z());
    return p;
  }

  // The truth at t for the frame point p_enu moving with v_enu, the vehicle at height h_m
  // changing at dh_mps; level, its x axis along the horizontal direction that dir_enu (a vector
  // of the origin's frame) has at the point.
  ImuTruth state(GpsTime t, const Vec3& p_enu, const Vec3& v_enu, double h_m, double dh_mps,
                 const Vec3& dir_enu) const {
    double lat_deg = 0.0, lon_deg = 0.0, h_point_m = 0.0;
    cartesian_.Reverse(p_enu.x(), p_enu.y(), p_enu.z(), lat_deg, lon_deg, h_point_m);
    const Geodetic where{lat_deg, lon_deg, h_m};
    const Mat3 R_enu_from_enu0 = R_enu_from_ecef(where) * R_ecef_from_enu0_;
    const Vec3 v_point = R_enu_from_enu0 * v_enu;
    const Vec3 d_point = R_enu_from_enu0 * dir_enu;
    const double r_n = meridian_radius_m(lat_deg), r_e = transverse_radius_m(lat_deg);
    const double k_n = (r_n + h_m) / (r_n + h_point_m);
    const double k_e = (r_e + h_m) / (r_e + h_point_m);

    ImuTruth out;
    out.t = t;
    out.position = where;
    out.v_ned_mps = Vec3(k_n * v_point.y(), k_e * v_point.x(), -dh_mps);
    // Yaw: the direction in the local north/east plane, measured from north toward east.
    const double yaw = std::atan2(k_e * d_point.x(), k_n * d_point.y());
    out.q_ned_from_body = Quat(Eigen::AngleAxisd(yaw, Vec3::UnitZ()));  // level: yaw only
    return out;
  }

 private:
  GeographicLib::LocalCartesian cartesian_;
  Mat3 R_ecef_from_enu0_;
};

// A horizontal unit vector of the origin's frame at a heading (rad from north toward east).
Vec3 horizontal(double heading_rad) {
  return Vec3(std::sin(heading_rad), std::cos(heading_rad), 0.0);
}

// ---- stationary ------------------------------------------------------------------------------

class Stationary final : public Trajectory {
 public:
  Stationary(const StationaryTrajectory& p, GpsTime start) : start_(start) {
    check_position("stationary", "position", p.position);
    check_finite("stationary", "yaw_deg", p.yaw_deg);
    state_.position = p.position;
    state_.q_ned_from_body = quat_from_euler_rpy(Vec3(0.0, 0.0, p.yaw_deg * kDegToRad));
  }
  ImuTruth at(GpsTime t) const override {
    ImuTruth out = state_;
    out.t = t;
    return out;
  }
  GpsTime end() const override { return start_; }

 private:
  GpsTime start_;
  ImuTruth state_;
};

// ---- circle ----------------------------------------------------------------------------------

// Arc length s from the southern point, angle theta = s / R about the centre:
//   counter-clockwise  e = R sin(theta),  n = -R cos(theta)   (south, east, north, west)
//   clockwise          e = -R sin(theta), n = -R cos(theta)   (south, west, north, east)
// and the velocity ds/dt times the unit tangent (+-cos(theta), sin(theta)).
class Circle final : public Trajectory {
 public:
  Circle(const CircleTrajectory& p, GpsTime start)
      : p_(checked(p)),
        start_(start),
        plane_(p.center),
        profile_(p.loops == 0 ? std::numeric_limits<double>::infinity()
                              : p.loops * kTwoPiExact * p.radius_m,
                 p.speed_mps, p.accel_mps2),
        sense_(p.clockwise ? -1.0 : 1.0) {}

  ImuTruth at(GpsTime t) const override {
    double s = 0.0, sdot = 0.0;
    profile_.at(seconds_between(t, start_), s, sdot);
    const double theta = std::fmod(s, kTwoPiExact * p_.radius_m) / p_.radius_m;
    const double c = std::cos(theta), sn = std::sin(theta);
    const Vec3 tangent(sense_ * c, sn, 0.0);
    const Vec3 p_enu(sense_ * p_.radius_m * sn, -p_.radius_m * c, 0.0);
    return plane_.state(t, p_enu, sdot * tangent, p_.center.h_m, 0.0, tangent);
  }
  GpsTime end() const override {
    return p_.loops == 0 ? kForever : start_.plus_s(profile_.duration_s());
  }

 private:
  static const CircleTrajectory& checked(const CircleTrajectory& p) {
    check_position("circle", "center", p.center);
    check_positive("circle", "radius_m", p.radius_m);
    check_positive("circle", "speed_mps", p.speed_mps);
    check_count("circle", "loops", p.loops);
    check_positive("circle", "accel_mps2", p.accel_mps2);
    return p;
  }

  CircleTrajectory p_;
  GpsTime start_;
  LocalPlane plane_;
  SpeedProfile profile_;
  double sense_;
};

// ---- line ------------------------------------------------------------------------------------

// Pass k (from 0) runs forward (from the start) when k is even, back when odd, over
// [k T, k T + T_pass], T = T_pass + T_turn; the turn after it rotates the heading by +180 deg
// (to the right, yaw increasing) at the turn rate, T_turn = 180 / rate.
class Line final : public Trajectory {
 public:
  Line(const LineTrajectory& p, GpsTime start)
      : p_(checked(p)),
        start_(start),
        plane_(p.start),
        profile_(p.length_m, p.speed_mps, p.accel_mps2),
        heading_rad_(p.heading_deg * kDegToRad),
        turn_rate_radps_(p.turn_rate_dps * kDegToRad),
        turn_s_(kPiExact / turn_rate_radps_),
        period_s_(profile_.duration_s() + turn_s_) {}

  ImuTruth at(GpsTime t) const override {
    const double tau = seconds_between(t, start_);
    std::int64_t k = 0;
    double r = 0.0;  // time into period k
    if (p_.passes > 0 && tau >= end_s()) {
      k = p_.passes - 1;
      r = profile_.duration_s();
    } else if (tau > 0.0) {
      k = static_cast<std::int64_t>(std::floor(tau / period_s_));
      r = tau - static_cast<double>(k) * period_s_;
    }
    const bool forward = k % 2 == 0;
    const double heading = heading_rad_ + (forward ? 0.0 : kPiExact);
    const Vec3 u = horizontal(heading_rad_);
    if (r <= profile_.duration_s()) {
      double s = 0.0, sdot = 0.0;
      profile_.at(r, s, sdot);
      const Vec3 p_enu = forward ? Vec3(s * u) : Vec3((p_.length_m - s) * u);
      const Vec3 v_enu = forward ? Vec3(sdot * u) : Vec3(-sdot * u);
      return plane_.state(t, p_enu, v_enu, p_.start.h_m, 0.0, horizontal(heading));
    }
    // Turning in place at the end of pass k.
    const Vec3 p_enu = forward ? Vec3(p_.length_m * u) : Vec3::Zero();
    const double yaw = heading + turn_rate_radps_ * (r - profile_.duration_s());
    return plane_.state(t, p_enu, Vec3::Zero(), p_.start.h_m, 0.0, horizontal(yaw));
  }
  GpsTime end() const override { return p_.passes == 0 ? kForever : start_.plus_s(end_s()); }

 private:
  static const LineTrajectory& checked(const LineTrajectory& p) {
    check_position("line", "start", p.start);
    check_finite("line", "heading_deg", p.heading_deg);
    check_positive("line", "length_m", p.length_m);
    check_positive("line", "speed_mps", p.speed_mps);
    check_count("line", "passes", p.passes);
    check_positive("line", "accel_mps2", p.accel_mps2);
    check_positive("line", "turn_rate_dps", p.turn_rate_dps);
    return p;
  }
  // The end of the last pass: passes T_pass + (passes - 1) T_turn.
  double end_s() const { return static_cast<double>(p_.passes - 1) * period_s_ + profile_.duration_s(); }

  LineTrajectory p_;
  GpsTime start_;
  LocalPlane plane_;
  SpeedProfile profile_;
  double heading_rad_;
  double turn_rate_radps_;
  double turn_s_;
  double period_s_;
};

// ---- waypoints -------------------------------------------------------------------------------

// Leg i runs in a straight line of the origin's (the first waypoint's) frame from waypoint i to
// i + 1, the height changing in proportion to the distance covered; its length is the
// three-dimensional distance sqrt(horizontal^2 + (h_i+1 - h_i)^2). At each inner waypoint the
// vehicle turns in place by the smaller angle to the next leg's heading.
class Waypoints final : public Trajectory {
 public:
  Waypoints(const WaypointTrajectory& p, GpsTime start)
      : p_(checked(p)), start_(start), plane_(p.waypoints.front()) {
    const std::size_t n = p.waypoints.size();
    for (std::size_t i = 0; i + 1 < n; ++i) {
      Leg leg;
      leg.from_enu = plane_.enu(p.waypoints[i]);
      leg.delta_enu = plane_.enu(p.waypoints[i + 1]) - leg.from_enu;
      leg.h_from_m = p.waypoints[i].h_m;
      leg.dh_m = p.waypoints[i + 1].h_m - p.waypoints[i].h_m;
      const double horizontal_m = std::hypot(leg.delta_enu.x(), leg.delta_enu.y());
      if (!(horizontal_m >= 1e-3))
        throw std::invalid_argument(fmt::format(
            "waypoint trajectory: waypoints[{}] lies within 1 mm horizontally of waypoints[{}]",
            i + 1, i));
      leg.length_m = std::hypot(horizontal_m, leg.dh_m);
      leg.heading_rad = std::atan2(leg.delta_enu.x(), leg.delta_enu.y());
      legs_.push_back(leg);
      profiles_.emplace_back(leg.length_m, p.speed_mps, p.accel_mps2);
    }
    const double rate_radps = p.turn_rate_dps * kDegToRad;
    double t0 = 0.0;
    for (std::size_t i = 0; i < legs_.size(); ++i) {
      if (i < p.stop_s.size() && p.stop_s[i] > 0.0) {
        segments_.push_back(Segment{t0, p.stop_s[i], Segment::kStop, i});
        t0 += p.stop_s[i];
      }
      if (i > 0) {
        // The turn at waypoint i, from leg i-1's heading to leg i's by the smaller angle.
        double turn = legs_[i].heading_rad - legs_[i - 1].heading_rad;
        turn -= kTwoPiExact * std::round(turn / kTwoPiExact);
        legs_[i].turn_before_rad = turn;
        const double duration = std::abs(turn) / rate_radps;
        segments_.push_back(Segment{t0, duration, Segment::kTurn, i});
        t0 += duration;
      }
      segments_.push_back(Segment{t0, profiles_[i].duration_s(), Segment::kMove, i});
      t0 += profiles_[i].duration_s();
    }
    end_s_ = t0;
  }

  ImuTruth at(GpsTime t) const override {
    const double tau = seconds_between(t, start_);
    if (tau <= 0.0) return move(t, 0, 0.0);
    if (tau >= end_s_) return move(t, legs_.size() - 1, profiles_.back().duration_s());
    // The last segment starting at or before tau.
    const auto it = std::upper_bound(segments_.begin(), segments_.end(), tau,
                                     [](double x, const Segment& s) { return x < s.t0_s; });
    const Segment& seg = *(it - 1);
    const double r = tau - seg.t0_s;
    if (seg.kind == Segment::kMove) return move(t, seg.leg, r);
    // Standing at waypoint `seg.leg`: where the previous leg ended (or where the first starts).
    if (seg.kind == Segment::kStop)
      return seg.leg == 0 ? move(t, 0, 0.0) : move(t, seg.leg - 1, profiles_[seg.leg - 1].duration_s());
    // Turning in place at the start of leg `seg.leg`: heading, horizontal and vertical parts of
    // the direction blended from the previous leg's to this one's.
    const Leg& prev = legs_[seg.leg - 1];
    const Leg& next = legs_[seg.leg];
    const double f = seg.duration_s > 0.0 ? std::clamp(r / seg.duration_s, 0.0, 1.0) : 1.0;
    const double yaw = prev.heading_rad + f * next.turn_before_rad;
    const Vec3 dp = direction(prev), dn = direction(next);
    const double horiz = (1.0 - f) * std::hypot(dp.x(), dp.y()) + f * std::hypot(dn.x(), dn.y());
    Vec3 dir = horiz * horizontal(yaw);
    dir.z() = (1.0 - f) * dp.z() + f * dn.z();
    return plane_.state(t, next.from_enu, Vec3::Zero(), next.h_from_m, 0.0, dir);
  }
  GpsTime end() const override { return start_.plus_s(end_s_); }

 private:
  struct Leg {
    Vec3 from_enu = Vec3::Zero();
    Vec3 delta_enu = Vec3::Zero();
    double h_from_m = 0.0;
    double dh_m = 0.0;
    double length_m = 0.0;
    double heading_rad = 0.0;
    double turn_before_rad = 0.0;
  };
  struct Segment {
    enum Kind { kMove, kTurn, kStop };
    double t0_s;
    double duration_s;
    Kind kind;
    std::size_t leg;  // the leg it moves along, or starts (turn, stop)
  };

  static Vec3 direction(const Leg& leg) { return leg.delta_enu / leg.length_m; }

  // On leg i, r seconds after it started moving.
  ImuTruth move(GpsTime t, std::size_t i, double r) const {
    const Leg& leg = legs_[i];
    double s = 0.0, sdot = 0.0;
    profiles_[i].at(r, s, sdot);
    const double f = s / leg.length_m;
    const Vec3 dir = direction(leg);
    return plane_.state(t, leg.from_enu + f * leg.delta_enu, sdot * dir,
                        leg.h_from_m + f * leg.dh_m, sdot * leg.dh_m / leg.length_m, dir);
  }

  static const WaypointTrajectory& checked(const WaypointTrajectory& p) {
    if (p.waypoints.size() < 2)
      bad("waypoint", "waypoints", "must hold at least 2 positions",
          static_cast<double>(p.waypoints.size()));
    for (std::size_t i = 0; i < p.waypoints.size(); ++i)
      check_position("waypoint", fmt::format("waypoints[{}]", i), p.waypoints[i]);
    for (std::size_t i = 0; i < p.stop_s.size(); ++i)
      if (!(p.stop_s[i] >= 0.0 && std::isfinite(p.stop_s[i])))
        bad("waypoint", fmt::format("stop_s[{}]", i), "must be finite and >= 0", p.stop_s[i]);
    check_positive("waypoint", "speed_mps", p.speed_mps);
    check_positive("waypoint", "accel_mps2", p.accel_mps2);
    check_positive("waypoint", "turn_rate_dps", p.turn_rate_dps);
    return p;
  }

  WaypointTrajectory p_;
  GpsTime start_;
  LocalPlane plane_;
  std::vector<Leg> legs_;
  std::vector<SpeedProfile> profiles_;
  std::vector<Segment> segments_;
  double end_s_ = 0.0;
};

}  // namespace

std::unique_ptr<Trajectory> make_trajectory(const StationaryTrajectory& p, GpsTime start) {
  return std::make_unique<Stationary>(p, start);
}
std::unique_ptr<Trajectory> make_trajectory(const CircleTrajectory& p, GpsTime start) {
  return std::make_unique<Circle>(p, start);
}
std::unique_ptr<Trajectory> make_trajectory(const LineTrajectory& p, GpsTime start) {
  return std::make_unique<Line>(p, start);
}
std::unique_ptr<Trajectory> make_trajectory(const WaypointTrajectory& p, GpsTime start) {
  return std::make_unique<Waypoints>(p, start);
}

}  // namespace navemu
