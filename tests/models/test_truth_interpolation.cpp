// Truth interpolation (models/truth_interpolation.hpp): exact for motion at a constant velocity
// along a parallel, the states themselves at the interval's ends, slerp of a constant-rate yaw,
// longitude across the antimeridian, Hermite velocity with accelerations, and constant-velocity
// extrapolation.

#include "models/truth_interpolation.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace navemu {
namespace {

constexpr double kPiD = 3.14159265358979323846;
const GpsTime kT0 = GpsTime::from_seconds(1'400'000'000.0);

ImuTruth state(GpsTime t, Geodetic p, Vec3 v, double yaw_deg = 0.0) {
  ImuTruth s;
  s.t = t;
  s.position = p;
  s.v_ned_mps = v;
  s.q_ned_from_body = quat_from_euler_rpy(Vec3(0.0, 0.0, yaw_deg * kDegToRad));
  return s;
}

// Distance between two positions, m.
double distance_m(const Geodetic& a, const Geodetic& b) {
  return (ecef_from_geodetic(a) - ecef_from_geodetic(b)).norm();
}

double angle_rad(const Quat& a, const Quat& b) {
  return rotation_vector_from_quat(a.conjugate() * b).norm();
}

TEST(TruthInterpolation, ExactForConstantVelocityAlongAParallel) {
  // East at 20 m/s along 45 N: latitude and height constant, longitude linear in time, so the
  // cubic Hermite reproduces it; the extrapolation is exact too (constant rates).
  const ImuTruth a = state(kT0, {45.0, 10.0, 100.0}, Vec3(0.0, 20.0, 0.0), 90.0);
  const ImuTruth b = extrapolate_truth(a, kT0.plus_s(1.0));
  EXPECT_EQ(b.position.lat_deg, 45.0);
  EXPECT_EQ(b.position.h_m, 100.0);
  const double lon_rate_deg = 20.0 / ((transverse_radius_m(45.0) + 100.0) * std::cos(kPiD / 4.0)) *
                              kRadToDeg;
  EXPECT_NEAR(b.position.lon_deg, 10.0 + lon_rate_deg, 1e-13);
  for (double f : {0.1, 0.25, 0.5, 0.9}) {
    const GpsTime t = kT0.plus_s(f);
    const ImuTruth got = interpolate_truth(a, b, t);
    EXPECT_EQ(got.t, t);
    EXPECT_NEAR(got.position.lat_deg, 45.0, 1e-13) << f;
    EXPECT_NEAR(got.position.lon_deg, 10.0 + f * lon_rate_deg, 1e-13) << f;
    EXPECT_NEAR(got.position.h_m, 100.0, 1e-12) << f;
    EXPECT_LT((got.v_ned_mps - a.v_ned_mps).norm(), 1e-12) << f;
    EXPECT_LT(angle_rad(got.q_ned_from_body, a.q_ned_from_body), 1e-12) << f;
    EXPECT_LT(distance_m(got.position, extrapolate_truth(a, t).position), 1e-8) << f;
  }
}

TEST(TruthInterpolation, ConstantVelocityInAnyDirectionWithinMicrometres) {
  // North-east and climbing at ~100 m/s: the radii and cos(lat) change along the way, so the
  // curvilinear rates are not quite constant; both the Hermite and the midpoint-rule
  // extrapolation follow them to well below a millimetre over one second.
  const Vec3 v(60.0, 80.0, -5.0);
  const ImuTruth a = state(kT0, {60.0, -20.0, 500.0}, v, 53.13);
  const ImuTruth b = extrapolate_truth(a, kT0.plus_s(1.0));
  EXPECT_NEAR(distance_m(a.position, b.position), v.norm(), 1e-3);
  const ImuTruth mid = interpolate_truth(a, b, kT0.plus_s(0.5));
  EXPECT_LT(distance_m(mid.position, extrapolate_truth(a, kT0.plus_s(0.5)).position), 1e-6);
  EXPECT_NEAR(mid.position.h_m, 502.5, 1e-9);
}

TEST(TruthInterpolation, EndpointsAreTheStatesThemselves) {
  ImuTruth a = state(kT0, {32.3, -90.9, 60.0}, Vec3(1.1, -2.2, 0.3));
  a.q_ned_from_body = quat_from_euler_rpy(Vec3(0.1, -0.2, 2.9));
  a.f_body_mps2 = Vec3(0.1, 0.2, -9.8);
  a.w_ib_body_radps = Vec3(0.01, 0.02, 0.03);
  a.temperature_c = 21.5;
  ImuTruth b = state(kT0.plus_s(0.02), {32.3000002, -90.9000003, 60.01}, Vec3(1.2, -2.1, 0.2));
  b.q_ned_from_body = quat_from_euler_rpy(Vec3(0.11, -0.19, -3.1));
  b.f_body_mps2 = Vec3(0.3, 0.1, -9.7);
  b.w_ib_body_radps = Vec3(0.02, 0.01, 0.05);
  b.temperature_c = 21.7;
  for (const ImuTruth* want : {&a, &b}) {
    const ImuTruth got = interpolate_truth(a, b, want->t, Vec3(1.0, 2.0, 3.0), Vec3(3.0, 2.0, 1.0));
    EXPECT_EQ(got.t, want->t);
    EXPECT_EQ(got.position.lat_deg, want->position.lat_deg);
    EXPECT_EQ(got.position.lon_deg, want->position.lon_deg);
    EXPECT_EQ(got.position.h_m, want->position.h_m);
    EXPECT_EQ(got.v_ned_mps, want->v_ned_mps);
    EXPECT_EQ(got.q_ned_from_body.coeffs(), want->q_ned_from_body.coeffs());
    ASSERT_TRUE(got.f_body_mps2 && got.w_ib_body_radps && got.temperature_c);
    EXPECT_EQ(*got.f_body_mps2, *want->f_body_mps2);
    EXPECT_EQ(*got.w_ib_body_radps, *want->w_ib_body_radps);
    EXPECT_EQ(*got.temperature_c, *want->temperature_c);
  }
}

TEST(TruthInterpolation, SlerpsAConstantRateYaw) {
  // 60 deg/s about the down axis; slerp is exact for a constant body rate.
  const ImuTruth a = state(kT0, {32.3, -90.9, 60.0}, Vec3::Zero(), 10.0);
  const ImuTruth b = state(kT0.plus_s(1.0), {32.3, -90.9, 60.0}, Vec3::Zero(), 70.0);
  for (double f : {0.25, 0.5, 0.75}) {
    const ImuTruth got = interpolate_truth(a, b, kT0.plus_s(f));
    const Vec3 rpy = euler_rpy_from_quat(got.q_ned_from_body);
    EXPECT_NEAR(rpy.z() * kRadToDeg, 10.0 + 60.0 * f, 1e-12) << f;
    EXPECT_NEAR(rpy.x(), 0.0, 1e-15);
    EXPECT_NEAR(rpy.y(), 0.0, 1e-15);
  }
  // Through north-south: 170 deg to -170 deg takes the short way, through 180.
  const ImuTruth c = state(kT0, {32.3, -90.9, 60.0}, Vec3::Zero(), 170.0);
  const ImuTruth d = state(kT0.plus_s(1.0), {32.3, -90.9, 60.0}, Vec3::Zero(), -170.0);
  const ImuTruth mid = interpolate_truth(c, d, kT0.plus_s(0.5));
  EXPECT_LT(angle_rad(mid.q_ned_from_body, quat_from_euler_rpy(Vec3(0.0, 0.0, kPiD))), 1e-12);
  // A combined roll/pitch/yaw rotation at a constant rate: the midpoint halves the rotation.
  const Quat q0 = quat_from_euler_rpy(Vec3(0.2, -0.1, 1.0));
  const Vec3 w_body(0.3, -0.4, 0.5);  // rad/s over 1 s
  ImuTruth e = c, g = d;
  e.q_ned_from_body = q0;
  g.q_ned_from_body = q0 * quat_from_rotation_vector(w_body);
  const ImuTruth half = interpolate_truth(e, g, kT0.plus_s(0.5));
  EXPECT_LT(angle_rad(half.q_ned_from_body, q0 * quat_from_rotation_vector(0.5 * w_body)), 1e-12);
}

TEST(TruthInterpolation, LongitudeAcrossTheAntimeridian) {
  // East along the equator from 179.9999 E: 0.0002 deg of longitude is ~22.3 m.
  const double v_e = 0.0002 * kDegToRad * transverse_radius_m(0.0);
  const ImuTruth a = state(kT0, {0.0, 179.9999, 0.0}, Vec3(0.0, v_e, 0.0), 90.0);
  const ImuTruth b = extrapolate_truth(a, kT0.plus_s(1.0));
  EXPECT_NEAR(b.position.lon_deg, -179.9999, 1e-10);
  const ImuTruth mid = interpolate_truth(a, b, kT0.plus_s(0.5));
  // At the antimeridian itself; [-180, 180) writes it as -180.
  EXPECT_NEAR(mid.position.lon_deg, -180.0, 1e-10);
  EXPECT_GE(mid.position.lon_deg, -180.0);
  const ImuTruth quarter = interpolate_truth(a, b, kT0.plus_s(0.25));
  EXPECT_NEAR(quarter.position.lon_deg, 179.99995, 1e-10);
  const ImuTruth three_quarters = interpolate_truth(a, b, kT0.plus_s(0.75));
  EXPECT_NEAR(three_quarters.position.lon_deg, -179.99995, 1e-10);
  // The same with b written as 180.0001 (unwrapped): the same results.
  ImuTruth b_unwrapped = b;
  b_unwrapped.position.lon_deg = 180.0001;
  EXPECT_NEAR(interpolate_truth(a, b_unwrapped, kT0.plus_s(0.75)).position.lon_deg, -179.99995,
              1e-10);
}

TEST(TruthInterpolation, VelocityHermiteWithAccelerationsElseLinear) {
  // v(t) = v0 + a0 t + j t^2 / 2 over [0, 2] s: cubic Hermite with dv/dt at both ends is exact.
  const Vec3 v0(1.0, -2.0, 0.5), a0(0.3, 0.1, -0.2), j(0.4, -0.6, 0.2);
  auto v = [&](double t) { return Vec3(v0 + a0 * t + 0.5 * j * t * t); };
  auto dv = [&](double t) { return Vec3(a0 + j * t); };
  const ImuTruth a = state(kT0, {10.0, 20.0, 30.0}, v(0.0));
  const ImuTruth b = state(kT0.plus_s(2.0), {10.00001, 20.00001, 29.0}, v(2.0));
  for (double t : {0.3, 1.0, 1.7}) {
    const ImuTruth got = interpolate_truth(a, b, kT0.plus_s(t), dv(0.0), dv(2.0));
    EXPECT_LT((got.v_ned_mps - v(t)).norm(), 1e-13) << t;
    const ImuTruth lin = interpolate_truth(a, b, kT0.plus_s(t));
    EXPECT_LT((lin.v_ned_mps - (v(0.0) + t / 2.0 * (v(2.0) - v(0.0)))).norm(), 1e-13) << t;
    // Only one acceleration given: linear.
    EXPECT_EQ(interpolate_truth(a, b, kT0.plus_s(t), dv(0.0)).v_ned_mps, lin.v_ned_mps);
  }
}

TEST(TruthInterpolation, RatesAndTemperatureOnlyWhenBothCarryThem) {
  ImuTruth a = state(kT0, {10.0, 20.0, 30.0}, Vec3::Zero());
  ImuTruth b = state(kT0.plus_s(1.0), {10.0, 20.0, 30.0}, Vec3::Zero());
  a.f_body_mps2 = Vec3(1.0, 2.0, 3.0);
  b.f_body_mps2 = Vec3(3.0, 2.0, 1.0);
  a.w_ib_body_radps = Vec3(0.1, 0.2, 0.3);
  a.temperature_c = 20.0;
  b.temperature_c = 30.0;
  const ImuTruth got = interpolate_truth(a, b, kT0.plus_s(0.25));
  ASSERT_TRUE(got.f_body_mps2.has_value());
  EXPECT_LT((*got.f_body_mps2 - Vec3(1.5, 2.0, 2.5)).norm(), 1e-15);
  EXPECT_FALSE(got.w_ib_body_radps.has_value());
  EXPECT_NEAR(got.temperature_c.value_or(0.0), 22.5, 1e-12);
}

TEST(TruthInterpolation, ExtrapolationHoldsAttitudeRatesAndTemperature) {
  ImuTruth a = state(kT0, {-33.9, 151.2, 40.0}, Vec3(100.0, 0.0, 0.0), 5.0);
  a.f_body_mps2 = Vec3(0.1, 0.0, -9.8);
  a.w_ib_body_radps = Vec3(0.0, 0.0, 0.01);
  a.temperature_c = 25.0;
  const ImuTruth same = extrapolate_truth(a, kT0);
  EXPECT_EQ(same.position.lat_deg, a.position.lat_deg);
  EXPECT_EQ(same.position.lon_deg, a.position.lon_deg);
  const ImuTruth later = extrapolate_truth(a, kT0.plus_s(1.0));
  EXPECT_EQ(later.t, kT0.plus_s(1.0));
  // 100 m north along the meridian (the chord differs from the arc by ~1e-9 m).
  EXPECT_NEAR(distance_m(a.position, later.position), 100.0, 1e-6);
  EXPECT_NEAR(later.position.lon_deg, 151.2, 1e-12);
  EXPECT_GT(later.position.lat_deg, a.position.lat_deg);
  EXPECT_EQ(later.v_ned_mps, a.v_ned_mps);
  EXPECT_EQ(later.q_ned_from_body.coeffs(), a.q_ned_from_body.coeffs());
  EXPECT_EQ(later.f_body_mps2, a.f_body_mps2);
  EXPECT_EQ(later.w_ib_body_radps, a.w_ib_body_radps);
  EXPECT_EQ(later.temperature_c, a.temperature_c);
}

}  // namespace
}  // namespace navemu
