// Truth impairments (emulator/truth_source.hpp ImpairedTruth) against the same source without
// them: a straight line east at 10 m/s, faults from 10 s.

#include "emulator/truth_source.hpp"

#include <gtest/gtest.h>

#include "models/geodesy.hpp"

namespace navemu {
namespace {

const GpsTime kStart = from_week_tow(2244, 36000.0);

TruthSpec line_east() {
  TruthSpec spec;
  spec.kind = TruthSourceKind::kLine;
  spec.line.start = Geodetic{32.3, -90.9, 60.0};
  spec.line.heading_deg = 90.0;
  spec.line.length_m = 10'000.0;
  spec.line.speed_mps = 10.0;
  spec.line.passes = 1;
  spec.line.accel_mps2 = 5.0;
  return spec;
}

std::unique_ptr<TruthSource> with(std::vector<TruthFault> faults) {
  auto t = std::make_unique<ImpairedTruth>(make_truth_source(line_east(), kStart, GpsTime{0}));
  t->set_faults(std::move(faults), kStart);
  return t;
}

// Each fault acts exactly over its window and nowhere else; the state carries the query's time.
TEST(ImpairedTruth, FreezeTeleportAndTimeJumpActOverTheirWindows) {
  EXPECT_EQ(with({})->describe(), make_truth_source(line_east(), kStart, GpsTime{0})->describe());
  auto clean = make_truth_source(line_east(), kStart, GpsTime{0});
  auto frozen = with({TruthFault{EventWindow{10.0, 5.0}, TruthFaultKind::kFreeze}});
  auto teleported = with({TruthFault{EventWindow{10.0, 5.0}, TruthFaultKind::kTeleport, Vec3(0.0, 200.0, -3.0)}});
  auto jumped = with({TruthFault{EventWindow{10.0, 5.0}, TruthFaultKind::kTimeJump, Vec3::Zero(), 4.0}});
  const std::optional<ImuTruth> at_10 = clean->at(kStart.plus_s(10.0));
  ASSERT_TRUE(at_10);
  for (double t = 0.0; t <= 20.0; t += 0.25) {
    const GpsTime when = kStart.plus_s(t);
    const bool on = t >= 10.0 && t < 15.0;
    const ImuTruth c = *clean->at(when), f = *frozen->at(when), p = *teleported->at(when), j = *jumped->at(when);
    for (const ImuTruth* s : {&f, &p, &j}) EXPECT_EQ(s->t, when) << t;
    // Freeze: the state of 10 s.
    const ImuTruth& want_f = on ? *at_10 : c;
    EXPECT_LT((ecef_from_geodetic(f.position) - ecef_from_geodetic(want_f.position)).norm(), 1e-6) << t;
    EXPECT_EQ(f.v_ned_mps, want_f.v_ned_mps) << t;
    // Teleport: 200 m north and 3 m down, nothing else.
    const Vec3 d_enu = enu_from_ecef(ecef_from_geodetic(p.position), c.position);
    EXPECT_LT((d_enu - (on ? Vec3(0.0, 200.0, -3.0) : Vec3::Zero())).norm(), 1e-3) << t;
    EXPECT_EQ(p.v_ned_mps, c.v_ned_mps) << t;
    // Time jump: the state of 4 s later, 40 m further east at 10 m/s.
    const double east_m = enu_from_ecef(ecef_from_geodetic(j.position), c.position).x();
    EXPECT_NEAR(east_m, on ? 40.0 : 0.0, 1e-3) << t;
  }
}

}  // namespace
}  // namespace navemu
