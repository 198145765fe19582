// The scene in the receiver: a street canyon built here box by box. Checked by hand geometry:
// which satellites are blocked, the excess path of a reflection off a wall (image method), and
// that the receiver in the canyon tracks fewer satellites with a worse HDOP than in open sky
// at the same instant.

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "models/constellation.hpp"
#include "models/receiver.hpp"
#include "models/signal_environment.hpp"

namespace navemu {
namespace {

constexpr double kDeg = M_PI / 180.0;
const Geodetic kOrigin{32.3, -90.9, 60.0};

// An axis-aligned closed box [lo, hi] (12 triangles, outward normals) of material `mat`.
void add_box(SceneMesh& m, const Vec3& lo, const Vec3& hi, std::uint32_t mat) {
  const auto base = static_cast<std::uint32_t>(m.vertices_enu_m.size());
  for (int i = 0; i < 8; ++i)
    m.vertices_enu_m.emplace_back((i & 1) ? hi.x() : lo.x(), (i & 2) ? hi.y() : lo.y(),
                                  (i & 4) ? hi.z() : lo.z());
  static const std::uint32_t kFaces[12][3] = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6},
                                              {0, 1, 4}, {1, 5, 4}, {2, 6, 3}, {3, 6, 7},
                                              {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  for (const auto& f : kFaces) {
    m.triangles.push_back({base + f[0], base + f[1], base + f[2]});
    m.triangle_material.push_back(mat);
  }
}

// A street along north, 20 m wide (walls at east = +-10 m), 30 m high buildings 1 km long.
std::shared_ptr<const Scene> canyon() {
  SceneMesh m;
  m.materials.push_back({"metal", 1.0, 0.0, -1.0, 0.0, true});
  add_box(m, Vec3(10, -500, 0), Vec3(30, 500, 30), 0);
  add_box(m, Vec3(-30, -500, 0), Vec3(-10, 500, 30), 0);
  return std::make_shared<const Scene>(std::move(m));
}

Vec3 u_ecef_of(double az_deg, double el_deg) {
  const Vec3 u_enu(std::sin(az_deg * kDeg) * std::cos(el_deg * kDeg),
                   std::cos(az_deg * kDeg) * std::cos(el_deg * kDeg), std::sin(el_deg * kDeg));
  return R_enu_from_ecef(kOrigin).transpose() * u_enu;
}

Vec3 antenna_ecef() {
  Geodetic g = kOrigin;
  g.h_m += 1.5;
  return ecef_from_geodetic(g);
}

TEST(SignalEnvironment, NlosThroughOneWallIsBiasedByTheImageMethodExcess) {
  // Satellite due east at 50 deg: the east wall blocks the direct path (at 10 m it rises only
  // 11.9 m); the west wall (normal east, 10 m away) reflects it over the east wall: the
  // reflection point is 1.5 + 10 tan 50 = 13.4 m up, and from there the ray rises 23.8 m over
  // the 20 m to the east wall. Image method: excess = 2 d (u . n) = 2 * 10 * cos 50 = 12.856 m.
  // A single path is tracked where it is, by either response.
  for (MultipathResponse r : {MultipathResponse::kDiscriminator, MultipathResponse::kPaperRule}) {
    SceneEnvironmentParams p;
    p.origin = kOrigin;
    p.response = r;
    const SceneEnvironment env(canyon(), p);
    const SignalEnvironment e = env.evaluate(antenna_ecef(), u_ecef_of(90.0, 50.0));
    EXPECT_TRUE(e.received);
    EXPECT_TRUE(e.nlos);
    EXPECT_NEAR(e.code_error_m, 2.0 * 10.0 * std::cos(50.0 * kDeg), 1e-3);
    // Metal: all power goes into the cross-polar part, received through the antenna's LHCP
    // rejection: weaker than the direct signal by at least that.
    EXPECT_LT(e.power_db, -10.0);
  }
}

TEST(SignalEnvironment, LineOfSightUpTheStreetIsUnbiasedByThePaperRule) {
  // Due north at 20 deg: straight up the street, visible; the walls' reflections arrive later.
  SceneEnvironmentParams p;
  p.origin = kOrigin;
  p.response = MultipathResponse::kPaperRule;
  const SceneEnvironment env(canyon(), p);
  const SignalEnvironment e = env.evaluate(antenna_ecef(), u_ecef_of(0.0, 20.0));
  EXPECT_TRUE(e.received);
  EXPECT_FALSE(e.nlos);
  EXPECT_EQ(e.code_error_m, 0.0);
  // Blocked completely: due east at 20 deg has neither a direct path nor a reflection over
  // the east wall (the west wall's reflection point is 5.1 m up and rises only 7.3 m more).
  const SignalEnvironment blocked = env.evaluate(antenna_ecef(), u_ecef_of(90.0, 20.0));
  EXPECT_FALSE(blocked.received);
}

TEST(SignalEnvironment, CanyonTracksFewerSatellitesWithLargerHdopThanOpenSky) {
  const GpsTime t = gps_from_calendar({2010, 11, 17, 13, 0, 0.0});
  const NavData nav = nominal_constellation(t);
  ImuTruth truth;
  truth.t = t;
  truth.position = kOrigin;
  truth.position.h_m += 1.5;
  ReceiverParams open;
  open.measurement.seed = 7;
  ReceiverParams street = open;
  SceneEnvironmentParams p;
  p.origin = kOrigin;
  street.measurement.environment = std::make_shared<SceneEnvironment>(canyon(), p);
  Receiver a(nav, open), b(nav, street);
  const ReceiverFix fa = a.update(t, &truth);
  const ReceiverFix fb = b.update(t, &truth);
  ASSERT_NE(fa.fix, FixType::kNone);
  EXPECT_LT(fb.satellites.size(), fa.satellites.size());
  if (fb.fix != FixType::kNone) {
    EXPECT_GT(fb.dops.hdop, fa.dops.hdop);
  }
  int nlos = 0;
  for (const SatMeasurement& m : b.measurements().sats) nlos += m.nlos ? 1 : 0;
  std::printf("open sky: %zu satellites, HDOP %.2f; canyon: %zu satellites (%d NLOS), HDOP %.2f\n",
              fa.satellites.size(), fa.dops.hdop, fb.satellites.size(), nlos, fb.dops.hdop);

  // Same seed and scene: identical measurements.
  Receiver c(nav, street);
  const ReceiverFix fc = c.update(t, &truth);
  ASSERT_EQ(fc.satellites.size(), fb.satellites.size());
  for (std::size_t i = 0; i < b.measurements().sats.size(); ++i)
    EXPECT_EQ(c.measurements().sats[i].engine_pseudorange_m, b.measurements().sats[i].engine_pseudorange_m);
}

}  // namespace
}  // namespace navemu
