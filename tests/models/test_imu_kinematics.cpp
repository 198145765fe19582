// What an ideal IMU senses (normal gravity, Earth rate, kinematics) and strapdown dead
// reckoning in NED.

#include "models/imu_kinematics.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

namespace navemu {
namespace {

const Geodetic kSite{32.3, -90.9, 60.0};  // the paper's test site, Vicksburg, MS

double angle_between(const Quat& a, const Quat& b) {
  return rotation_vector_from_quat(a.conjugate() * b).norm();
}

TEST(Gravity, NormalGravityWgs84EquatorAndPole) {
  // WGS-84 normal gravity on the ellipsoid (NIMA TR8350.2 Table 3.4): gamma_e = 9.7803253359,
  // gamma_p = 9.8321849378 m/s^2, gravitation plus centrifugal, along the normal.
  const Vec3 ge = gravity_ned_mps2({0.0, 0.0, 0.0});
  EXPECT_NEAR(ge.z(), 9.7803253359, 1e-9);
  EXPECT_NEAR(ge.x(), 0.0, 1e-12);
  EXPECT_EQ(ge.y(), 0.0);
  const Vec3 gp = gravity_ned_mps2({90.0, 0.0, 0.0});
  EXPECT_NEAR(gp.z(), 9.8321849378, 1e-9);
  EXPECT_NEAR(gravity_ned_mps2({-90.0, 10.0, 0.0}).z(), 9.8321849378, 1e-9);
  // Free-air gradient about 3.086e-6 s^-2; a small north component above the ellipsoid.
  const Vec3 g0 = gravity_ned_mps2({45.0, 0.0, 0.0});
  const Vec3 g1 = gravity_ned_mps2({45.0, 0.0, 1000.0});
  EXPECT_NEAR((g0.z() - g1.z()) / 1000.0, 3.086e-6, 0.01e-6);
  EXPECT_NE(g1.x(), 0.0);
  EXPECT_LT(std::abs(g1.x()), 1e-5);
}

TEST(Gravity, EarthAndTransportRate) {
  const double lat = kSite.lat_deg * kDegToRad;
  const Vec3 w = earth_rate_ned_radps(kSite);
  EXPECT_DOUBLE_EQ(w.x(), kOmegaEarth_radps * std::cos(lat));
  EXPECT_EQ(w.y(), 0.0);
  EXPECT_DOUBLE_EQ(w.z(), -kOmegaEarth_radps * std::sin(lat));
  // Radii: WGS-84 meridian radius 6335439.327 m at the equator, 6399593.626 m at the pole
  // (both radii equal a^2/b there).
  EXPECT_NEAR(meridian_radius_m(0.0), 6335439.327, 1e-3);
  EXPECT_NEAR(transverse_radius_m(0.0), 6378137.0, 1e-6);
  EXPECT_NEAR(meridian_radius_m(90.0), 6399593.626, 1e-3);
  EXPECT_NEAR(transverse_radius_m(90.0), 6399593.626, 1e-3);
  // Moving north at 10 m/s rotates NED about -east at v/(R_N + h); east: about north and down.
  const Vec3 wn = transport_rate_ned_radps(kSite, Vec3(10.0, 0.0, 0.0));
  EXPECT_DOUBLE_EQ(wn.y(), -10.0 / (meridian_radius_m(kSite.lat_deg) + kSite.h_m));
  EXPECT_EQ(wn.x(), 0.0);
  const Vec3 we = transport_rate_ned_radps(kSite, Vec3(0.0, 10.0, 0.0));
  const double re_h = transverse_radius_m(kSite.lat_deg) + kSite.h_m;
  EXPECT_DOUBLE_EQ(we.x(), 10.0 / re_h);
  EXPECT_DOUBLE_EQ(we.z(), -10.0 * std::tan(lat) / re_h);
}

TEST(ImuKin, LevelNorthFacingStaticImu) {
  const IdealImu imu = ideal_imu_static(kSite, Quat::Identity());
  const double g = gravity_ned_mps2(kSite).z();
  EXPECT_NEAR(g, 9.7944, 1e-3);
  EXPECT_NEAR(imu.f_body_mps2.z(), -g, 1e-12);
  EXPECT_NEAR(imu.f_body_mps2.x(), -gravity_ned_mps2(kSite).x(), 1e-15);
  EXPECT_EQ(imu.f_body_mps2.y(), 0.0);
  const double lat = kSite.lat_deg * kDegToRad;
  EXPECT_NEAR(imu.w_ib_body_radps.x(), kOmegaEarth_radps * std::cos(lat), 1e-18);
  EXPECT_NEAR(imu.w_ib_body_radps.y(), 0.0, 1e-18);
  EXPECT_NEAR(imu.w_ib_body_radps.z(), -kOmegaEarth_radps * std::sin(lat), 1e-18);
}

TEST(ImuKin, RotatedAttitudesRotateTheReadings) {
  const double g = gravity_ned_mps2(kSite).z();
  const double lat = kSite.lat_deg * kDegToRad;
  const double wc = kOmegaEarth_radps * std::cos(lat), ws = kOmegaEarth_radps * std::sin(lat);
  // Facing east: body x = east, y = south, z = down.
  const IdealImu east = ideal_imu_static(kSite, quat_from_euler_rpy({0.0, 0.0, 90.0 * kDegToRad}));
  EXPECT_NEAR(east.w_ib_body_radps.x(), 0.0, 1e-18);
  EXPECT_NEAR(east.w_ib_body_radps.y(), -wc, 1e-18);
  EXPECT_NEAR(east.w_ib_body_radps.z(), -ws, 1e-18);
  EXPECT_NEAR(east.f_body_mps2.z(), -g, 1e-12);
  // Rolled 90 deg right: body y points down, so the y accelerometer senses -g.
  const IdealImu rolled = ideal_imu_static(kSite, quat_from_euler_rpy({90.0 * kDegToRad, 0.0, 0.0}));
  EXPECT_NEAR(rolled.f_body_mps2.y(), -g, 1e-12);
  EXPECT_NEAR(rolled.f_body_mps2.z(), 0.0, 1e-5);  // only the tiny north deflection elsewhere
  EXPECT_NEAR(rolled.w_ib_body_radps.y(), -ws, 1e-18);
  // Pitched 90 deg nose up: body x points up and senses +g.
  const IdealImu up = ideal_imu_static(kSite, quat_from_euler_rpy({0.0, 90.0 * kDegToRad, 0.0}));
  EXPECT_NEAR(up.f_body_mps2.x(), g, 1e-12);
  // Any attitude: magnitudes unchanged, and C_nb f = -g.
  const Quat q = quat_from_euler_rpy({0.3, -0.7, 2.5});
  const IdealImu any = ideal_imu_static(kSite, q);
  EXPECT_LT((q * any.f_body_mps2 + gravity_ned_mps2(kSite)).norm(), 1e-14);
  EXPECT_LT((q * any.w_ib_body_radps - earth_rate_ned_radps(kSite)).norm(), 1e-19);
}

TEST(ImuKin, EulerRoundTripAndRotationVector) {
  for (const Vec3& rpy : {Vec3(0.1, -0.2, 0.3), Vec3(-3.0, 1.2, -2.9), Vec3(0.0, 0.0, 3.1)}) {
    const Vec3 back = euler_rpy_from_quat(quat_from_euler_rpy(rpy));
    EXPECT_LT((back - rpy).norm(), 1e-13) << rpy.transpose();
  }
  // Yaw 90 deg turns body x to east.
  EXPECT_LT((quat_from_euler_rpy({0, 0, kPi / 2}) * Vec3::UnitX() - Vec3::UnitY()).norm(), 1e-12);
  for (const Vec3& phi : {Vec3(1e-9, -2e-9, 3e-10), Vec3(0.5, -1.0, 2.0), Vec3::Zero().eval()}) {
    const Quat q = quat_from_rotation_vector(phi);
    EXPECT_NEAR(q.norm(), 1.0, 1e-15);
    EXPECT_LT((rotation_vector_from_quat(q) - phi).norm(), 1e-15 + 1e-14 * phi.norm());
  }
}

// A vehicle on a level circle of radius r at speed v, turning right (yaw increasing), built from
// analytic states: position on the ellipsoid from the NED offset to the centre, velocity
// v (cos psi, sin psi, 0), yaw psi = psi0 + (v/r) t.
struct Circle {
  Geodetic centre = kSite;
  double r_m = 9.144;  // the paper's 30 ft radius track
  double v_mps = 2.0;
  double psi0 = 0.4;

  double w() const { return v_mps / r_m; }
  // Times on the integer-nanosecond grid of GpsTime, so that the states are exactly those of
  // the instants the kinematics sees.
  static GpsTime time_of(double t_s) { return GpsTime::from_seconds(t_s); }
  ImuTruth at(double t_request_s) const {
    const GpsTime t = time_of(t_request_s);
    const double t_s = t.seconds();
    const double psi = psi0 + w() * t_s;
    const Vec3 p_ned(r_m * std::sin(psi), -r_m * std::cos(psi), 0.0);
    ImuTruth s;
    s.t = t;
    s.position = geodetic_from_ecef(ecef_from_geodetic(centre) +
                                    R_ned_from_ecef(centre).transpose() * p_ned);
    s.v_ned_mps = v_mps * Vec3(std::cos(psi), std::sin(psi), 0.0);
    s.q_ned_from_body = quat_from_euler_rpy({0.0, 0.0, psi});
    return s;
  }
  // The exact output: dv/dt = v w (-sin psi, cos psi, 0), w_nb = (0, 0, w).
  IdealImu exact(double t_request_s) const {
    const ImuTruth s = at(t_request_s);
    const double t_s = s.t.seconds();
    const double psi = psi0 + w() * t_s;
    const Mat3 C_bn = s.q_ned_from_body.toRotationMatrix().transpose();
    const Vec3 a = v_mps * w() * Vec3(-std::sin(psi), std::cos(psi), 0.0);
    const Vec3 w_ie = earth_rate_ned_radps(s.position);
    const Vec3 w_en = transport_rate_ned_radps(s.position, s.v_ned_mps);
    IdealImu out;
    out.f_body_mps2 = C_bn * (a + (2.0 * w_ie + w_en).cross(s.v_ned_mps) - gravity_ned_mps2(s.position));
    out.w_ib_body_radps = Vec3(0.0, 0.0, w()) + C_bn * (w_ie + w_en);
    return out;
  }
};

TEST(ImuKin, KinematicsExactOnACircle) {
  const Circle c;
  for (double h : {0.008, 0.1, 1.0}) {
    for (double t : {0.0, 3.3, 17.0}) {
      const IdealImu d = ideal_imu_from_kinematics(c.at(t - h), c.at(t), c.at(t + h));
      const IdealImu e = c.exact(t);
      EXPECT_LT((d.f_body_mps2 - e.f_body_mps2).norm(), 1e-11) << "h " << h << " t " << t;
      EXPECT_LT((d.w_ib_body_radps - e.w_ib_body_radps).norm(), 1e-14) << "h " << h << " t " << t;
      // Centripetal acceleration v^2/r towards the centre, on the right (body +y); yaw rate
      // v/r about body z (Earth rate and Coriolis are below 1e-3 of these).
      EXPECT_NEAR(d.f_body_mps2.y(), c.v_mps * c.v_mps / c.r_m, 1e-3);
      EXPECT_NEAR(d.w_ib_body_radps.z(), c.w(), 1e-4);
    }
  }
}

TEST(ImuKin, KinematicsStraightLineAndPrecedence) {
  // Constant acceleration north at a fixed attitude: exact.
  const Quat q = quat_from_euler_rpy({0.05, -0.1, 1.0});
  auto state = [&](double t) {
    ImuTruth s;
    s.t = GpsTime::from_seconds(1000.0 + t);
    s.position = kSite;
    s.v_ned_mps = Vec3(0.5 * t, 0.0, 0.0);
    s.q_ned_from_body = q;
    return s;
  };
  const IdealImu d = ideal_imu_from_kinematics(state(1.9), state(2.0), state(2.1));
  const Vec3 w_ie = earth_rate_ned_radps(kSite);
  const Vec3 v(1.0, 0.0, 0.0);
  const Vec3 w_en = transport_rate_ned_radps(kSite, v);
  const Vec3 f_expect = q.conjugate() * (Vec3(0.5, 0, 0) + (2.0 * w_ie + w_en).cross(v) -
                                         gravity_ned_mps2(kSite));
  EXPECT_LT((d.f_body_mps2 - f_expect).norm(), 1e-12);
  EXPECT_LT((d.w_ib_body_radps - q.conjugate() * (w_ie + w_en)).norm(), 1e-18);
  // A truth that carries f and w is used as it is.
  ImuTruth now = state(2.0);
  now.f_body_mps2 = Vec3(1, 2, 3);
  now.w_ib_body_radps = Vec3(4, 5, 6);
  const IdealImu p = ideal_imu_from_kinematics(state(1.9), now, state(2.1));
  EXPECT_EQ(p.f_body_mps2, Vec3(1, 2, 3));
  EXPECT_EQ(p.w_ib_body_radps, Vec3(4, 5, 6));
}

TEST(Strapdown, PerfectStationaryImuTenMinutesAt125Hz) {
  for (const Vec3& rpy_deg : {Vec3(0, 0, 0), Vec3(1.5, -2.0, 123.0)}) {
    const Quat q0 = quat_from_euler_rpy(rpy_deg * kDegToRad);
    const IdealImu imu = ideal_imu_static(kSite, q0);
    StrapdownState s0;
    s0.t = GpsTime::from_seconds(1e9);
    s0.position = kSite;
    s0.q_ned_from_body = q0;
    Strapdown sd(s0);
    const double dt = 1.0 / 125.0;
    double max_v_at_1min = 0.0;
    for (int k = 1; k <= 75'000; ++k) {
      sd.step(imu.f_body_mps2, imu.w_ib_body_radps, dt);
      if (k == 7'500) max_v_at_1min = sd.state().v_ned_mps.norm();
    }
    const StrapdownState& s = sd.state();
    const double dp = (ecef_from_geodetic(s.position) - ecef_from_geodetic(kSite)).norm();
    const double dv = s.v_ned_mps.norm();
    const double da = angle_between(q0, s.q_ned_from_body);
    std::cout << "[ measured ] 10 min stationary, rpy " << rpy_deg.transpose()
              << " deg: position " << dp << " m, velocity " << dv << " m/s (after 1 min "
              << max_v_at_1min << "), attitude " << da << " rad\n";
    EXPECT_LT(dp, 1e-3);
    EXPECT_LT(max_v_at_1min, 1e-6);
    EXPECT_LT(dv, 1e-5);
    EXPECT_LT(da, 1e-8);
    EXPECT_NEAR(seconds_between(s.t, s0.t), 600.0, 1e-6);
  }
}

TEST(Strapdown, ConstantYawRateIntegratesToTheRightHeading) {
  // Level, turning at 10 deg/s about body z for 60 s: yaw 600 deg = -120 deg (mod 360). Each
  // sample is the mean rate over its interval (Earth rate projected at the middle of it).
  const double r = 10.0 * kDegToRad, dt = 1.0 / 125.0;
  const double psi0 = 0.2;
  StrapdownState s0;
  s0.position = kSite;
  s0.q_ned_from_body = quat_from_euler_rpy({0.0, 0.0, psi0});
  Strapdown sd(s0);
  for (int k = 1; k <= 7'500; ++k) {
    const Quat q_mid = quat_from_euler_rpy({0.0, 0.0, psi0 + r * (k - 0.5) * dt});
    const IdealImu still = ideal_imu_static(kSite, q_mid);
    sd.step(still.f_body_mps2, still.w_ib_body_radps + Vec3(0.0, 0.0, r), dt);
  }
  const Vec3 rpy = euler_rpy_from_quat(sd.state().q_ned_from_body);
  double yaw_err = std::remainder(rpy.z() - (psi0 + r * 60.0), 2.0 * kPi);
  std::cout << "[ measured ] 60 s at 10 deg/s: yaw error " << yaw_err << " rad, roll "
            << rpy.x() << ", pitch " << rpy.y() << ", position "
            << (ecef_from_geodetic(sd.state().position) - ecef_from_geodetic(kSite)).norm()
            << " m\n";
  EXPECT_LT(std::abs(yaw_err), 1e-8);
  EXPECT_LT(std::abs(rpy.x()), 1e-8);
  EXPECT_LT(std::abs(rpy.y()), 1e-8);
  EXPECT_NEAR(std::remainder(rpy.z(), 2.0 * kPi), std::remainder(psi0 - 120.0 * kDegToRad, 2.0 * kPi), 1e-8);
}

TEST(Strapdown, FollowsTheCircleFromItsIdealImuOutput) {
  // Round trip: the ideal output of the circle (each sample the output at the middle of its
  // interval) integrated for one lap comes back to the circle.
  const Circle c;
  const double dt = 1.0 / 125.0;
  const double lap_s = 2.0 * kPi / c.w();
  const int n = static_cast<int>(std::lround(lap_s / dt));
  const ImuTruth start = c.at(0.0);
  StrapdownState s0;
  s0.t = start.t;
  s0.position = start.position;
  s0.v_ned_mps = start.v_ned_mps;
  s0.q_ned_from_body = start.q_ned_from_body;
  Strapdown sd(s0);
  const double h = 1e-3;
  for (int k = 1; k <= n; ++k) {
    const double tm = (k - 0.5) * dt;
    const IdealImu imu = ideal_imu_from_kinematics(c.at(tm - h), c.at(tm), c.at(tm + h));
    sd.step(imu.f_body_mps2, imu.w_ib_body_radps, dt);
  }
  const ImuTruth end = c.at(n * dt);
  const double dp = (ecef_from_geodetic(sd.state().position) - ecef_from_geodetic(end.position)).norm();
  const double dv = (sd.state().v_ned_mps - end.v_ned_mps).norm();
  const double da = angle_between(sd.state().q_ned_from_body, end.q_ned_from_body);
  std::cout << "[ measured ] one lap of the 9.144 m circle at 2 m/s, 125 Hz: position " << dp
            << " m, velocity " << dv << " m/s, attitude " << da << " rad\n";
  EXPECT_LT(dp, 1e-3);
  EXPECT_LT(dv, 1e-5);
  EXPECT_LT(da, 1e-8);
}

}  // namespace
}  // namespace navemu
