// The streamed-truth buffer (emulator/truth_buffer.hpp): bad samples are rejected in the
// documented order, counted and never applied; interpolation between 10 Hz samples of a circle
// follows it to well below a centimetre at 125 Hz; extrapolation ends at the timeout; the window
// keeps memory bounded.

#include "emulator/truth_buffer.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "models/trajectory.hpp"
#include "models/truth_interpolation.hpp"

namespace navemu {
namespace {

const GpsTime kStart = GpsTime::from_seconds(1'400'000'000.0);
const Geodetic kCenter{32.3, -90.9, 60.0};
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

double distance_m(const Geodetic& a, const Geodetic& b) {
  return (ecef_from_geodetic(a) - ecef_from_geodetic(b)).norm();
}

std::unique_ptr<Trajectory> circle(int loops = 2) {
  CircleTrajectory p;
  p.center = kCenter;
  p.radius_m = 9.144;
  p.speed_mps = 2.0;
  p.loops = loops;
  return make_trajectory(p, kStart);
}

// Everything the buffer answers, compared exactly.
void expect_same(const std::optional<ImuTruth>& a, const std::optional<ImuTruth>& b) {
  ASSERT_EQ(a.has_value(), b.has_value());
  if (!a) return;
  EXPECT_EQ(a->t, b->t);
  EXPECT_EQ(a->position.lat_deg, b->position.lat_deg);
  EXPECT_EQ(a->position.lon_deg, b->position.lon_deg);
  EXPECT_EQ(a->position.h_m, b->position.h_m);
  EXPECT_EQ(a->v_ned_mps, b->v_ned_mps);
  EXPECT_EQ(a->q_ned_from_body.coeffs(), b->q_ned_from_body.coeffs());
}

TEST(TruthBuffer, RejectsBadSamplesInOrderCountsThemAndNeverAppliesThem) {
  const auto traj = circle();
  TruthBuffer buffer(1.0, 10.0);
  EXPECT_TRUE(buffer.empty());
  EXPECT_FALSE(buffer.at(kStart).has_value());
  EXPECT_FALSE(buffer.newest_time().has_value());
  for (int k = 0; k <= 10; ++k)
    ASSERT_EQ(buffer.push(traj->at(kStart.plus_s(0.1 * k + 5.0))), TruthVerdict::kAccepted);
  const GpsTime newest = kStart.plus_s(6.0);
  ASSERT_EQ(buffer.newest_time(), newest);
  const GpsTime inside = kStart.plus_s(5.55), after = kStart.plus_s(6.3);
  const std::optional<ImuTruth> before_inside = buffer.at(inside);
  const std::optional<ImuTruth> before_after = buffer.at(after);
  ASSERT_TRUE(before_inside && before_after);

  // Each bad sample a future one (7 s), except the duplicate and the backwards ones, and far
  // from the truth, so that applying it would show.
  const ImuTruth good = traj->at(kStart.plus_s(7.0));
  struct Case {
    const char* what;
    ImuTruth sample;
    TruthVerdict verdict;
  };
  std::vector<Case> cases;
  auto bad = [&](const char* what, TruthVerdict verdict, auto change) {
    ImuTruth s = good;
    s.position.lat_deg += 0.01;
    change(s);
    cases.push_back({what, s, verdict});
  };
  using V = TruthVerdict;
  bad("NaN latitude", V::kNotFinite, [](ImuTruth& s) { s.position.lat_deg = kNaN; });
  bad("infinite longitude", V::kNotFinite, [](ImuTruth& s) { s.position.lon_deg = kInf; });
  bad("NaN height", V::kNotFinite, [](ImuTruth& s) { s.position.h_m = kNaN; });
  bad("infinite velocity", V::kNotFinite, [](ImuTruth& s) { s.v_ned_mps.y() = -kInf; });
  bad("NaN quaternion", V::kNotFinite, [](ImuTruth& s) { s.q_ned_from_body.x() = kNaN; });
  bad("NaN force", V::kNotFinite, [](ImuTruth& s) { s.f_body_mps2 = Vec3(0.0, kNaN, -9.8); });
  bad("NaN rate", V::kNotFinite, [](ImuTruth& s) { s.w_ib_body_radps = Vec3(kInf, 0.0, 0.0); });
  bad("NaN temperature", V::kNotFinite, [](ImuTruth& s) { s.temperature_c = kNaN; });
  // Not finite comes first, even when the sample is also out of range or late.
  bad("NaN and out of range", V::kNotFinite, [](ImuTruth& s) {
    s.position.lat_deg = 95.0;
    s.position.h_m = kNaN;
  });
  bad("NaN and backwards", V::kNotFinite, [&](ImuTruth& s) {
    s.t = kStart;
    s.v_ned_mps.x() = kNaN;
  });
  bad("latitude 90.5", V::kOutOfRange, [](ImuTruth& s) { s.position.lat_deg = 90.5; });
  bad("latitude -91", V::kOutOfRange, [](ImuTruth& s) { s.position.lat_deg = -91.0; });
  bad("height -1001 m", V::kOutOfRange, [](ImuTruth& s) { s.position.h_m = -1001.0; });
  bad("height 100.1 km", V::kOutOfRange, [](ImuTruth& s) { s.position.h_m = 100'100.0; });
  bad("speed 2001 m/s", V::kOutOfRange, [](ImuTruth& s) { s.v_ned_mps = Vec3(0.0, 2001.0, 0.0); });
  bad("quaternion norm 1.002", V::kOutOfRange,
      [](ImuTruth& s) { s.q_ned_from_body.coeffs() *= 1.002; });
  bad("quaternion norm 0", V::kOutOfRange,
      [](ImuTruth& s) { s.q_ned_from_body.coeffs().setZero(); });
  // Out of range comes before the time checks.
  bad("out of range and duplicate", V::kOutOfRange, [&](ImuTruth& s) {
    s.t = newest;
    s.position.h_m = -5000.0;
  });
  bad("duplicate", V::kDuplicate, [&](ImuTruth& s) { s.t = newest; });
  bad("backwards by 1 ns", V::kBackwards, [&](ImuTruth& s) { s.t = GpsTime{newest.ns - 1}; });
  bad("backwards into the window", V::kBackwards, [&](ImuTruth& s) { s.t = inside; });
  bad("backwards before the oldest", V::kBackwards, [&](ImuTruth& s) { s.t = kStart; });

  for (const Case& c : cases) {
    EXPECT_EQ(buffer.push(c.sample), c.verdict) << c.what;
    EXPECT_EQ(buffer.newest_time(), newest) << c.what;
    expect_same(buffer.at(inside), before_inside);
    expect_same(buffer.at(after), before_after);
  }
  const TruthCounters& n = buffer.counters();
  EXPECT_EQ(n.accepted, 11u);
  EXPECT_EQ(n.not_finite, 10u);
  EXPECT_EQ(n.out_of_range, 8u);
  EXPECT_EQ(n.duplicate, 1u);
  EXPECT_EQ(n.backwards, 3u);
  EXPECT_EQ(n.rejected(), 22u);
  buffer.counters().bad_framing += 2;  // counted by the decoding source
  EXPECT_EQ(buffer.counters().rejected(), 24u);

  // A quaternion within 1e-3 of unit norm is accepted and normalised.
  ImuTruth slightly_off = good;
  slightly_off.q_ned_from_body.coeffs() *= 1.0009;
  EXPECT_EQ(buffer.push(slightly_off), TruthVerdict::kAccepted);
  const std::optional<ImuTruth> at_good = buffer.at(good.t);
  ASSERT_TRUE(at_good.has_value());
  EXPECT_NEAR(at_good->q_ned_from_body.norm(), 1.0, 1e-15);
  EXPECT_LT((at_good->q_ned_from_body.coeffs() - good.q_ned_from_body.coeffs()).norm(), 1e-15);

  EXPECT_STREQ(to_string(TruthVerdict::kAccepted), "accepted");
  EXPECT_STREQ(to_string(TruthVerdict::kNotFinite), "not finite");
  EXPECT_STREQ(to_string(TruthVerdict::kOutOfRange), "out of range");
  EXPECT_STREQ(to_string(TruthVerdict::kDuplicate), "duplicate");
  EXPECT_STREQ(to_string(TruthVerdict::kBackwards), "backwards");
}

TEST(TruthBuffer, InterpolatesA10HzCircleTo125Hz) {
  // The circle (9.144 m, 2 m/s, with its acceleration ramps) streamed at 10 Hz, queried at
  // 125 Hz as the sensors would be: each instant once the sample after it has arrived.
  const auto traj = circle();
  TruthBuffer buffer(1.0, 10.0);
  const double duration = seconds_between(traj->end(), kStart) + 1.0;
  const double ramp_s = 2.0 / 0.5;  // v / a at each end
  double max_pos_m = 0.0, max_vel_mps = 0.0, max_att_rad = 0.0;
  double cruise_vel_mps = 0.0, cruise_att_rad = 0.0;  // away from the ramps
  int queries = 0;
  std::int64_t next_query = 0;  // index of the next 125 Hz instant
  for (int k = 0; 0.1 * k <= duration; ++k) {
    ASSERT_EQ(buffer.push(traj->at(kStart.plus_s(0.1 * k))), TruthVerdict::kAccepted);
    const GpsTime newest = *buffer.newest_time();
    for (;; ++next_query) {
      const GpsTime t{kStart.ns + next_query * 8'000'000};  // 8 ms
      if (t > newest) break;
      const std::optional<ImuTruth> got = buffer.at(t);
      ASSERT_TRUE(got.has_value());
      EXPECT_EQ(got->t, t);
      const ImuTruth want = traj->at(t);
      const double vel_error = (got->v_ned_mps - want.v_ned_mps).norm();
      const double att_error =
          rotation_vector_from_quat(want.q_ned_from_body.conjugate() * got->q_ned_from_body).norm();
      max_pos_m = std::max(max_pos_m, distance_m(got->position, want.position));
      max_vel_mps = std::max(max_vel_mps, vel_error);
      max_att_rad = std::max(max_att_rad, att_error);
      const double since_start = seconds_between(t, kStart);
      if (since_start > ramp_s + 0.1 && since_start < duration - 1.0 - ramp_s - 0.1) {
        cruise_vel_mps = std::max(cruise_vel_mps, vel_error);
        cruise_att_rad = std::max(cruise_att_rad, att_error);
      }
      ++queries;
    }
  }
  std::printf("circle at 125 Hz from 10 Hz: position %.3g m, velocity %.3g m/s (cruise %.3g), "
              "attitude %.3g rad (cruise %.3g), %d instants\n",
              max_pos_m, max_vel_mps, cruise_vel_mps, max_att_rad, cruise_att_rad, queries);
  EXPECT_GT(queries, 7000);
  EXPECT_LT(max_pos_m, 0.01);
  EXPECT_LT(max_pos_m, 1e-3);  // in fact ~3e-5 m, at the acceleration steps of the ramps
  // Velocity is interpolated linearly: at a step of the acceleration a by up to a dt / 4
  // (0.5 m/s^2 over 0.1 s: 0.0125 m/s); in the turn the chord of the rotating velocity,
  // v (w dt)^2 / 8 ~ 1.2e-4 m/s.
  EXPECT_LT(max_vel_mps, 0.0125);
  EXPECT_LT(cruise_vel_mps, 2e-4);
  // Slerp is exact for a constant turn rate; during the ramps the rate changes at a / R, and
  // the error is (a / R) dt^2 / 8 ~ 7e-5 rad.
  EXPECT_LT(max_att_rad, 1e-4);
  EXPECT_LT(cruise_att_rad, 1e-9);
}

TEST(TruthBuffer, ExtrapolatesUpToTheTimeoutOnly) {
  LineTrajectory line;
  line.start = kCenter;
  line.heading_deg = 90.0;
  line.length_m = 100.0;
  line.speed_mps = 5.0;
  line.passes = 1;
  line.accel_mps2 = 1.0;
  const auto traj = make_trajectory(line, kStart);
  TruthBuffer buffer(0.5, 10.0);
  for (int k = 0; k <= 100; ++k) buffer.push(traj->at(kStart.plus_s(0.1 * k)));  // cruising at 10 s
  const GpsTime newest = kStart.plus_s(10.0);
  const ImuTruth last = traj->at(newest);
  ASSERT_NEAR(last.v_ned_mps.norm(), 5.0, 1e-9);

  for (double dt : {0.0, 0.1, 0.25, 0.5}) {
    const std::optional<ImuTruth> got = buffer.at(newest.plus_s(dt));
    ASSERT_TRUE(got.has_value()) << dt;
    EXPECT_EQ(got->t, newest.plus_s(dt));
    // Straight on at 5 m/s, the attitude held: along the line, as the trajectory itself.
    EXPECT_NEAR(distance_m(got->position, last.position), 5.0 * dt, 1e-6) << dt;
    EXPECT_LT(distance_m(got->position, traj->at(newest.plus_s(dt)).position), 1e-6) << dt;
    EXPECT_EQ(got->v_ned_mps, last.v_ned_mps);
    EXPECT_LT((got->q_ned_from_body.coeffs() - last.q_ned_from_body.coeffs()).norm(), 1e-15);
  }
  EXPECT_FALSE(buffer.at(GpsTime{newest.plus_s(0.5).ns + 1}).has_value());
  EXPECT_FALSE(buffer.at(newest.plus_s(3.0)).has_value());
  EXPECT_FALSE(buffer.at(GpsTime{kStart.ns - 1}).has_value());  // before the oldest sample
  // A new sample brings the truth back.
  buffer.push(traj->at(newest.plus_s(3.0)));
  EXPECT_TRUE(buffer.at(newest.plus_s(3.2)).has_value());
  EXPECT_TRUE(buffer.at(newest.plus_s(1.5)).has_value());  // interpolated across the gap

  TruthBuffer no_extrapolation(0.0);
  no_extrapolation.push(last);
  EXPECT_TRUE(no_extrapolation.at(newest).has_value());
  EXPECT_FALSE(no_extrapolation.at(GpsTime{newest.ns + 1}).has_value());
}

TEST(TruthBuffer, WindowKeepsMemoryBounded) {
  TruthBuffer buffer(1.0, 2.0);
  ImuTruth s;
  s.position = kCenter;
  s.v_ned_mps = Vec3(1.0, 0.0, 0.0);
  std::size_t max_size = 0;
  const int n = 100'000;
  for (int k = 0; k < n; ++k) {  // 100 Hz for 1000 s
    s.t = GpsTime{kStart.ns + std::int64_t{k} * 10'000'000};
    ASSERT_EQ(buffer.push(s), TruthVerdict::kAccepted);
    max_size = std::max(max_size, buffer.size());
  }
  EXPECT_EQ(buffer.counters().accepted, static_cast<std::uint64_t>(n));
  // 2 s at 100 Hz, and the sample at the window's start.
  EXPECT_LE(max_size, 202u);
  EXPECT_GE(buffer.size(), 200u);
  const GpsTime newest = *buffer.newest_time();
  EXPECT_TRUE(buffer.at(newest.plus_s(-2.0)).has_value());  // the whole window interpolable
  EXPECT_TRUE(buffer.at(newest.plus_s(-1.234)).has_value());
  EXPECT_FALSE(buffer.at(newest.plus_s(-2.02)).has_value());  // forgotten

  // Sparse samples (one per 10 s, window 2 s): the two newest stay, so the span between them
  // is still interpolable.
  TruthBuffer sparse(1.0, 2.0);
  for (int k = 0; k < 10; ++k) {
    s.t = kStart.plus_s(10.0 * k);
    sparse.push(s);
  }
  EXPECT_EQ(sparse.size(), 2u);
  EXPECT_TRUE(sparse.at(kStart.plus_s(85.0)).has_value());
}

TEST(TruthBuffer, RejectsBadSpans) {
  EXPECT_THROW(TruthBuffer(-1.0), std::invalid_argument);
  EXPECT_THROW(TruthBuffer(1.0, kNaN), std::invalid_argument);
  EXPECT_NO_THROW(TruthBuffer(0.0, 0.0));
  EXPECT_THROW(TruthBuffer(TruthStreamLimits{1.0, 10.0, -1.0, 3}), std::invalid_argument);
  EXPECT_THROW(TruthBuffer(TruthStreamLimits{1.0, 10.0, 5.0, 1}), std::invalid_argument);
}

// --- Jumps in time (emulator/truth_buffer.hpp, "Re-synchronisation").

const TruthStreamLimits kStream{1.0, 10.0, 5.0, 3};

// A stationary sample at kCenter (+ north_m) at t.
ImuTruth at_site(GpsTime t, double north_m = 0.0) {
  ImuTruth s;
  s.t = t;
  s.position = kCenter;
  s.position.lat_deg += north_m / 111'000.0;
  return s;
}

// 10 Hz for 2 s from kStart.
void push_steady(TruthBuffer& b, int samples = 21) {
  for (int k = 0; k < samples; ++k) ASSERT_EQ(b.push(at_site(kStart.plus_s(0.1 * k))), TruthVerdict::kAccepted);
}

TEST(TruthBuffer, ASingleSampleAnHourAheadIsRejectedAsFutureAndNeverApplied) {
  TruthBuffer b(kStream);
  push_steady(b);
  const GpsTime newest = kStart.plus_s(2.0);
  EXPECT_EQ(b.push(at_site(kStart.plus_s(3600.0), 1000.0)), TruthVerdict::kFuture);
  EXPECT_EQ(b.newest_time(), newest);
  // The stream goes on as if it had never come: accepted, interpolated at the site.
  for (int k = 1; k <= 10; ++k)
    EXPECT_EQ(b.push(at_site(newest.plus_s(0.1 * k))), TruthVerdict::kAccepted) << k;
  const std::optional<ImuTruth> got = b.at(newest.plus_s(0.55));
  ASSERT_TRUE(got);
  EXPECT_LT(distance_m(got->position, kCenter), 1e-6);
  EXPECT_EQ(b.counters().future, 1u);
  EXPECT_EQ(b.counters().resync, 0u);
  EXPECT_EQ(b.counters().accepted, 31u);
  // Just within the bound is a gap, not a jump.
  EXPECT_EQ(b.push(at_site(newest.plus_s(1.0 + 5.0))), TruthVerdict::kAccepted);
}

TEST(TruthBuffer, AStreamThatJumpsBackIsResynchronisedAfterThreeConsistentSamples) {
  TruthBuffer b(kStream);
  push_steady(b);
  const GpsTime newest = kStart.plus_s(2.0);
  // A simulator reset: its time starts again 100 s earlier, 10 Hz, at a place 500 m north.
  const GpsTime reset = kStart.plus_s(-100.0);
  EXPECT_EQ(b.push(at_site(reset, 500.0)), TruthVerdict::kBackwards);
  EXPECT_EQ(b.push(at_site(reset.plus_s(0.1), 500.0)), TruthVerdict::kBackwards);
  EXPECT_EQ(b.newest_time(), newest);  // nothing applied yet
  EXPECT_EQ(b.push(at_site(reset.plus_s(0.2), 500.0)), TruthVerdict::kResync);
  // The new stream goes on from the newest sample held before, one step of its own later.
  EXPECT_EQ(b.newest_time(), newest.plus_s(0.1));
  ASSERT_TRUE(b.last_resync());
  EXPECT_FALSE(b.last_resync()->against_clock);
  EXPECT_EQ(b.last_resync()->jump_ns, reset.plus_s(0.2).ns - newest.ns);
  EXPECT_EQ(b.last_resync()->offset_ns, newest.plus_s(0.1).ns - reset.plus_s(0.2).ns);
  for (int k = 3; k <= 12; ++k)
    EXPECT_EQ(b.push(at_site(reset.plus_s(0.1 * k), 500.0)), TruthVerdict::kAccepted) << k;
  // Only the new place is held: no interpolation across the jump.
  const std::optional<ImuTruth> got = b.at(newest.plus_s(0.5));
  ASSERT_TRUE(got);
  EXPECT_LT(distance_m(got->position, at_site(reset, 500.0).position), 1e-6);
  EXPECT_FALSE(b.at(newest).has_value());
  EXPECT_EQ(b.counters().backwards, 2u);
  EXPECT_EQ(b.counters().resync, 1u);
  EXPECT_EQ(b.counters().accepted, 21u + 1u + 10u);
}

TEST(TruthBuffer, AStreamThatJumpsAnHourAheadIsResynchronisedToo) {
  TruthBuffer b(kStream);
  push_steady(b);
  const GpsTime ahead = kStart.plus_s(3602.0);
  EXPECT_EQ(b.push(at_site(ahead)), TruthVerdict::kFuture);
  EXPECT_EQ(b.push(at_site(ahead.plus_s(0.1))), TruthVerdict::kFuture);
  EXPECT_EQ(b.push(at_site(ahead.plus_s(0.2))), TruthVerdict::kResync);
  EXPECT_EQ(b.newest_time(), kStart.plus_s(2.1));
  EXPECT_EQ(b.counters().future, 2u);
}

TEST(TruthBuffer, OutliersThatDoNotAgreeNeverResynchroniseAndTheTruthEndsAtTheTimeout) {
  TruthBuffer b(kStream);
  push_steady(b);
  const GpsTime newest = kStart.plus_s(2.0);
  // Datagrams keep coming, each far off and not following the one before: none is taken.
  const double offsets_s[] = {3600.0, -50.0, 7200.0, -3600.0, 600.0, 590.0, -10.0, 10'000.0, 20.0};
  for (double dt : offsets_s) {
    const TruthVerdict v = b.push(at_site(newest.plus_s(dt)));
    EXPECT_TRUE(v == TruthVerdict::kFuture || v == TruthVerdict::kBackwards) << dt;
  }
  EXPECT_EQ(b.counters().resync, 0u);
  EXPECT_EQ(b.newest_time(), newest);
  // The truth lasts until the timeout after the newest accepted sample, whatever arrives.
  EXPECT_TRUE(b.at(newest.plus_s(1.0)).has_value());
  EXPECT_FALSE(b.at(newest.plus_s(1.01)).has_value());
  // Two consistent outliers, then a good sample: the count starts again.
  EXPECT_EQ(b.push(at_site(newest.plus_s(-30.0))), TruthVerdict::kBackwards);
  EXPECT_EQ(b.push(at_site(newest.plus_s(-29.9))), TruthVerdict::kBackwards);
  EXPECT_EQ(b.push(at_site(newest.plus_s(0.1))), TruthVerdict::kAccepted);
  EXPECT_EQ(b.push(at_site(newest.plus_s(-29.8))), TruthVerdict::kBackwards);
  EXPECT_EQ(b.counters().resync, 0u);
}

TEST(TruthBuffer, AgainstTheClockStampsFarFromItAreOutliersAndResynchroniseOntoIt) {
  TruthBuffer b(kStream);
  const GpsTime clock = kStart;
  // A simulator that stamps its own time from 0 (1980), from its first datagram on.
  const GpsTime sim0{1'000'000'000};
  EXPECT_EQ(b.push(at_site(sim0), clock), TruthVerdict::kBackwards);
  EXPECT_EQ(b.push(at_site(sim0.plus_s(0.1)), clock.plus_s(0.1)), TruthVerdict::kBackwards);
  EXPECT_TRUE(b.empty());
  EXPECT_EQ(b.push(at_site(sim0.plus_s(0.2)), clock.plus_s(0.2)), TruthVerdict::kResync);
  EXPECT_EQ(b.newest_time(), clock.plus_s(0.2));  // onto the clock
  EXPECT_TRUE(b.last_resync()->against_clock);
  EXPECT_EQ(b.push(at_site(sim0.plus_s(0.3)), clock.plus_s(0.3)), TruthVerdict::kAccepted);
  EXPECT_EQ(b.newest_time(), clock.plus_s(0.3));
  // A stream that pauses and resumes with the clock is no jump, however long the pause.
  EXPECT_EQ(b.push(at_site(sim0.plus_s(60.3)), clock.plus_s(60.3)), TruthVerdict::kAccepted);
  // One stamped an hour ahead of the clock is.
  EXPECT_EQ(b.push(at_site(sim0.plus_s(3660.4)), clock.plus_s(60.4)), TruthVerdict::kFuture);
  EXPECT_EQ(b.push(at_site(sim0.plus_s(60.5)), clock.plus_s(60.5)), TruthVerdict::kAccepted);
}

TEST(TruthBuffer, WithoutAJumpLimitOnlyBackwardsTimesAreRefused) {
  TruthBuffer b(1.0, 10.0);  // max_jump_s unlimited
  push_steady(b);
  EXPECT_EQ(b.push(at_site(kStart.plus_s(3600.0))), TruthVerdict::kAccepted);
  for (int k = 0; k < 10; ++k) EXPECT_EQ(b.push(at_site(kStart.plus_s(k))), TruthVerdict::kBackwards);
  EXPECT_EQ(b.counters().resync, 0u);
  EXPECT_STREQ(to_string(TruthVerdict::kFuture), "future");
  EXPECT_STREQ(to_string(TruthVerdict::kResync), "resync");
}

}  // namespace
}  // namespace navemu
