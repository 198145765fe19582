// Scene ray tracing (models/scene.hpp) against closed-form geometry: image-method excess paths
// and reflection points for walls and the ground, blocking by buildings, foliage chords, the
// street canyon's double reflection, face grouping and mesh validation.

#include "models/scene.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <thread>
#include <vector>

namespace navemu {
namespace {

constexpr double kMm = 1e-3;

// Unit vector towards a satellite at azimuth az (from north, clockwise) and elevation el, in
// east-north-up: (cos el sin az, cos el cos az, sin el).
Vec3 sat_dir(double az_deg, double el_deg) {
  const double az = az_deg * kDegToRad, el = el_deg * kDegToRad;
  return {std::cos(el) * std::sin(az), std::cos(el) * std::cos(az), std::sin(el)};
}

// Horizontal unit normal pointing towards azimuth az.
Vec3 horizontal_dir(double az_deg) {
  const double az = az_deg * kDegToRad;
  return {std::sin(az), std::cos(az), 0.0};
}

// Mirror image of point x in the plane through q with unit normal n.
Vec3 image(const Vec3& x, const Vec3& q, const Vec3& n) { return x - 2.0 * n.dot(x - q) * n; }

struct MeshBuilder {
  SceneMesh mesh;

  std::uint32_t material(const std::string& name, double foliage_db_per_m = 0.0) {
    SceneMaterial m;
    m.name = name;
    m.foliage_db_per_m = foliage_db_per_m;
    mesh.materials.push_back(m);
    return static_cast<std::uint32_t>(mesh.materials.size() - 1);
  }
  std::uint32_t vertex(const Vec3& v) {
    mesh.vertices_enu_m.push_back(v);
    return static_cast<std::uint32_t>(mesh.vertices_enu_m.size() - 1);
  }
  void triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t mat) {
    mesh.triangles.push_back({a, b, c});
    mesh.triangle_material.push_back(mat);
  }
  // Quad a b c d (in order around it) as two triangles sharing the diagonal a c.
  void quad(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, std::uint32_t mat,
            bool flip_second = false) {
    const std::uint32_t ia = vertex(a), ib = vertex(b), ic = vertex(c), id = vertex(d);
    triangle(ia, ib, ic, mat);
    if (flip_second) {
      triangle(ia, id, ic, mat);
    } else {
      triangle(ia, ic, id, mat);
    }
  }
  // A vertical rectangle: centre of its bottom edge `base`, horizontal direction `along`,
  // half length, height.
  void wall(const Vec3& base, const Vec3& along, double half_length_m, double height_m,
            std::uint32_t mat, bool flip_second = false) {
    const Vec3 up = Vec3::UnitZ() * height_m;
    const Vec3 a = base - along * half_length_m, b = base + along * half_length_m;
    quad(a, b, b + up, a + up, mat, flip_second);
  }
  // Horizontal square centred at c.
  void ground(const Vec3& c, double half_m, std::uint32_t mat) {
    quad(c + Vec3(-half_m, -half_m, 0), c + Vec3(half_m, -half_m, 0), c + Vec3(half_m, half_m, 0),
         c + Vec3(-half_m, half_m, 0), mat);
  }
  // Axis-aligned closed box, 12 triangles on 8 shared vertices.
  void box(const Vec3& lo, const Vec3& hi, std::uint32_t mat) {
    std::uint32_t v[8];
    for (int i = 0; i < 8; ++i) {
      v[i] = vertex({(i & 1) ? hi.x() : lo.x(), (i & 2) ? hi.y() : lo.y(),
                     (i & 4) ? hi.z() : lo.z()});
    }
    const int q[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                         {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& f : q) {
      triangle(v[f[0]], v[f[1]], v[f[2]], mat);
      triangle(v[f[0]], v[f[2]], v[f[3]], mat);
    }
  }
};

// Length of the ray o + t d (t >= 0) inside the axis-aligned box [lo, hi], by the slab method.
double chord_in_box(const Vec3& o, const Vec3& d, const Vec3& lo, const Vec3& hi) {
  double t0 = 0.0, t1 = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    if (d[k] == 0.0) {
      if (o[k] < lo[k] || o[k] > hi[k]) return 0.0;
      continue;
    }
    double a = (lo[k] - o[k]) / d[k], b = (hi[k] - o[k]) / d[k];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
  }
  return std::max(0.0, t1 - t0);
}

std::vector<ReflectedPath> reflect(const Scene& s, const Vec3& p, const Vec3& u, int order = 1,
                                   double range_m = 2000.0) {
  ScenePathOptions opt;
  opt.max_order = order;
  opt.max_range_m = range_m;
  std::vector<ReflectedPath> out;
  s.reflections(p, u, opt, out);
  return out;
}

// ---- First order: vertical wall ------------------------------------------------------------
// Image method: a wall through q with unit normal n towards the antenna p, at distance
// d = n.(p - q). The reflected signal reaches p as if coming straight from the image
// p' = p - 2 d n; with the satellite at infinity in direction u the wavefronts are planes
// normal to u, so the path difference to the direct signal is u.(p - p') = 2 d (u.n). For a
// vertical wall with normal azimuth az_n and a satellite at (az, el):
//   u.n = cos(el) sin(az) sin(az_n) + cos(el) cos(az) cos(az_n) = cos(el) cos(az - az_n),
//   excess = 2 d cos(el) cos(az - az_n)
// (cos(el), not sin(el): sin(el) is the ground plane's u.n). The reflection point is where the
// line from p' towards the satellite crosses the wall: r = p' + s u, s = d / (u.n).
TEST(SceneFirstOrder, VerticalWallMatchesImageMethod) {
  const Vec3 p(0.3, -2.1, 0.0);
  int checked = 0;
  for (const double wall_az_deg : {90.0, 30.0, 217.0}) {
    const Vec3 n = horizontal_dir(wall_az_deg);  // towards the antenna
    const Vec3 along(n.y(), -n.x(), 0.0);
    for (const double d : {3.0, 12.5, 47.3}) {
      for (const bool flip : {false, true}) {
        MeshBuilder mb;
        const std::uint32_t concrete = mb.material("concrete");
        // 10 km x 10 km, centred on the antenna's foot: effectively infinite.
        mb.wall(p - d * n - Vec3(0, 0, 5000.0), along, 5000.0, 10000.0, concrete, flip);
        const Scene scene(mb.mesh);
        EXPECT_EQ(scene.stats().faces, 1u);
        for (const double h : {1.5, 20.0}) {
          const Vec3 ant = p + Vec3(0, 0, h);
          for (const double daz : {0.0, -50.0, 35.0, 80.0}) {
            for (const double el : {5.0, 30.0, 60.0, 80.0}) {
              const Vec3 u = sat_dir(wall_az_deg + daz, el);
              const auto paths = reflect(scene, ant, u);
              SCOPED_TRACE(::testing::Message() << "wall az " << wall_az_deg << " d " << d
                                                << " h " << h << " daz " << daz << " el " << el);
              ASSERT_EQ(paths.size(), 1u);
              const ReflectedPath& r = paths[0];
              EXPECT_EQ(r.order, 1);
              EXPECT_EQ(r.material[0], concrete);
              const double expected = 2.0 * d * std::cos(el * kDegToRad) * std::cos(daz * kDegToRad);
              EXPECT_NEAR(r.excess_m, expected, kMm);
              const Vec3 img = ant - 2.0 * d * n;
              const Vec3 r_img = img + (d / u.dot(n)) * u;
              EXPECT_NEAR((r.points_enu_m[0] - r_img).norm(), 0.0, kMm);
              EXPECT_NEAR(n.dot(r.points_enu_m[0] - (p - d * n)), 0.0, kMm);  // on the wall
              // The general definition agrees: |r - p| - (r - p).u.
              const Vec3 rp = r.points_enu_m[0] - ant;
              EXPECT_NEAR(rp.norm() - rp.dot(u), expected, kMm);
              EXPECT_NEAR(r.grazing_rad[0], std::asin(u.dot(n)), 1e-9);
              EXPECT_NEAR((r.arrival_enu - rp.normalized()).norm(), 0.0, 1e-9);
              EXPECT_FALSE(scene.direct(ant, u).blocked);
              ++checked;
            }
          }
        }
      }
    }
  }
  EXPECT_EQ(checked, 3 * 3 * 2 * 2 * 4 * 4);
}

TEST(SceneFirstOrder, ReflectionBeyondRangeIsIgnored) {
  MeshBuilder mb;
  mb.wall({-40.0, 0.0, -5000.0}, Vec3::UnitY(), 5000.0, 10000.0, mb.material("concrete"));
  const Scene scene(mb.mesh);
  const Vec3 u = sat_dir(90.0, 60.0);  // t = 40 / cos(60) = 80 m
  EXPECT_EQ(reflect(scene, Vec3::Zero(), u, 1, 81.0).size(), 1u);
  EXPECT_TRUE(reflect(scene, Vec3::Zero(), u, 1, 79.0).empty());
  EXPECT_TRUE(reflect(scene, Vec3::Zero(), u, 0, 1000.0).empty());
}

// A satellite behind the wall (relative to the antenna) has no specular reflection from it.
TEST(SceneFirstOrder, WallBehindAntennaGivesNothing) {
  MeshBuilder mb;
  mb.wall({-10.0, 0.0, -5000.0}, Vec3::UnitY(), 5000.0, 10000.0, mb.material("concrete"));
  const Scene scene(mb.mesh);
  const Vec3 p(0, 0, 1.5);
  for (const double az : {190.0, 225.0, 270.0, 315.0, 350.0}) {
    for (const double el : {5.0, 45.0, 85.0}) {
      EXPECT_TRUE(reflect(scene, p, sat_dir(az, el)).empty()) << az << " " << el;
      EXPECT_TRUE(scene.direct(p, sat_dir(az, el)).blocked);  // the wall is in the way
    }
  }
}

// ---- First order: ground ---------------------------------------------------------------------
// Horizontal plane at height h below the antenna: n = up, u.n = sin(el), excess 2 h sin(el);
// r = p + t m with m = (u_e, u_n, -u_u), t = h / sin(el).
TEST(SceneFirstOrder, GroundPlaneMatchesImageMethod) {
  MeshBuilder mb;
  const std::uint32_t soil = mb.material("soil");
  mb.ground({0, 0, 0}, 5000.0, soil);
  const Scene scene(mb.mesh);
  for (const double h : {0.5, 1.5, 10.0, 35.0}) {
    for (const double az : {0.0, 77.0, 190.0, 301.0}) {
      for (const double el : {5.0, 15.0, 45.0, 85.0}) {
        const Vec3 p(1.7, -3.2, h);
        const Vec3 u = sat_dir(az, el);
        const auto paths = reflect(scene, p, u);
        SCOPED_TRACE(::testing::Message() << "h " << h << " az " << az << " el " << el);
        ASSERT_EQ(paths.size(), 1u);
        EXPECT_NEAR(paths[0].excess_m, 2.0 * h * std::sin(el * kDegToRad), kMm);
        const Vec3 r_expected(p.x() + h * u.x() / u.z(), p.y() + h * u.y() / u.z(), 0.0);
        EXPECT_NEAR((paths[0].points_enu_m[0] - r_expected).norm(), 0.0, kMm);
        EXPECT_NEAR(paths[0].grazing_rad[0], el * kDegToRad, 1e-9);
        EXPECT_EQ(paths[0].material[0], soil);
      }
    }
  }
}

// ---- Blocking ------------------------------------------------------------------------------
TEST(SceneDirect, BuildingBlocksSatellitesBehindIt) {
  MeshBuilder mb;
  mb.box({10, -10, 0}, {30, 10, 20}, mb.material("concrete"));
  const Scene scene(mb.mesh);
  const Vec3 p(0, 0, 1.5);
  // East at 20 deg: the ray reaches x = 10 at z = 1.5 + 10 tan 20 = 5.1 m < 20 m.
  EXPECT_TRUE(scene.direct(p, sat_dir(90, 20)).blocked);
  // East at 60 deg: z = 1.5 + 10 tan 60 = 18.8 m at the wall: still blocked.
  EXPECT_TRUE(scene.direct(p, sat_dir(90, 60)).blocked);
  // East at 70 deg: z = 1.5 + 10 tan 70 = 29 m: over the roof.
  EXPECT_FALSE(scene.direct(p, sat_dir(90, 70)).blocked);
  // In front of the antenna (west), and north past the building's side (y = 10 at x < 10).
  EXPECT_FALSE(scene.direct(p, sat_dir(270, 20)).blocked);
  EXPECT_FALSE(scene.direct(p, sat_dir(0, 10)).blocked);
  EXPECT_EQ(scene.direct(p, sat_dir(90, 20)).foliage_loss_db, 0.0);
}

// A wall reflection whose leg from the wall towards the satellite passes through another
// building is not returned; the direct path, which misses that building, stays clear.
TEST(SceneFirstOrder, ReflectionWithBlockedSatelliteLegIsDropped) {
  // Wall x = -8 facing east; satellite az 60, el 30: u = (0.75, 0.433, 0.5). The image of
  // p = (0, 0, 1.5) is (-16, 0, 1.5); the leg from the wall runs along -16 e + s u. At s = 30 it
  // is at (6.5, 12.99, 16.5): a tower [3.5, 9.5] x [10, 16] x [0, 40] around that point blocks
  // it. The direct line (s u) crosses y in [10, 16] at x in [17, 27.7]: it misses the tower.
  const Vec3 p(0, 0, 1.5);
  const Vec3 u = sat_dir(60, 30);
  const auto make = [&](bool with_tower) {
    MeshBuilder mb;
    const std::uint32_t concrete = mb.material("concrete");
    mb.wall({-8.0, 0.0, -5000.0}, Vec3::UnitY(), 5000.0, 10000.0, concrete);
    if (with_tower) mb.box({3.5, 10, 0}, {9.5, 16, 40}, concrete);
    return Scene(mb.mesh);
  };
  const auto on_wall = [](const std::vector<ReflectedPath>& paths) {
    return std::count_if(paths.begin(), paths.end(), [](const ReflectedPath& r) {
      return std::abs(r.points_enu_m[0].x() + 8.0) < kMm;
    });
  };
  const Scene open = make(false);
  const Scene blocked = make(true);
  EXPECT_EQ(on_wall(reflect(open, p, u)), 1);
  EXPECT_NEAR(reflect(open, p, u)[0].excess_m, 2 * 8 * 0.75, kMm);
  EXPECT_EQ(on_wall(reflect(blocked, p, u)), 0);
  EXPECT_FALSE(blocked.direct(p, u).blocked);
}

// ---- Foliage -------------------------------------------------------------------------------
TEST(SceneFoliage, LossIsAttenuationTimesChordAndDoesNotBlock) {
  constexpr double kDbPerM = 1.3;
  const Vec3 lo(5, -5, 0), hi(15, 5, 12);
  MeshBuilder mb;
  mb.box(lo, hi, mb.material("tree", kDbPerM));
  const Scene scene(mb.mesh);
  const Vec3 p(0, 0, 1.5);
  // el 20: in through x = 5, out through x = 15 (chord 10 / cos 20); el 45: out through the
  // top; az 70: out through the side y = 5; az 270: misses.
  for (const auto& [az, el] : std::vector<std::pair<double, double>>{
           {90, 20}, {90, 45}, {70, 10}, {100, 30}, {270, 20}, {0, 5}}) {
    const Vec3 u = sat_dir(az, el);
    const double chord = chord_in_box(p, u, lo, hi);
    const DirectPath d = scene.direct(p, u);
    EXPECT_FALSE(d.blocked);
    EXPECT_NEAR(d.foliage_loss_db, kDbPerM * chord, 1e-6 * kDbPerM * chord) << az << " " << el;
    if (az == 90 && el == 20) {
      EXPECT_NEAR(chord, 10.0 / std::cos(20 * kDegToRad), 1e-12);
    }
    if (az == 270) {
      EXPECT_EQ(d.foliage_loss_db, 0.0);
    }
  }
  // Foliage does not reflect.
  for (const double az : {0.0, 90.0, 180.0, 270.0}) {
    EXPECT_TRUE(reflect(scene, p, sat_dir(az, 30)).empty());
  }
}

TEST(SceneFoliage, AntennaInsideFoliageCountsFromTheAntenna) {
  constexpr double kDbPerM = 0.8;
  const Vec3 lo(-3, -4, 0), hi(5, 2, 9);
  MeshBuilder mb;
  mb.box(lo, hi, mb.material("hedge", kDbPerM));
  // A second, disjoint crown further along the same ray adds its own chord.
  const Vec3 lo2(20, -6, 0), hi2(30, 6, 30);
  mb.box(lo2, hi2, mb.material("crown", 2.0 * kDbPerM));
  const Scene scene(mb.mesh);
  const Vec3 p(0.4, 0.3, 1.5);
  const Vec3 u = sat_dir(83, 25);
  const double c1 = chord_in_box(p, u, lo, hi), c2 = chord_in_box(p, u, lo2, hi2);
  ASSERT_GT(c1, 0.0);
  ASSERT_GT(c2, 0.0);
  const double expected = kDbPerM * c1 + 2.0 * kDbPerM * c2;
  EXPECT_NEAR(scene.direct(p, u).foliage_loss_db, expected, 1e-6 * expected);
}

// A reflected path collects the foliage on each leg: a hedge around the antenna costs the
// chord along the arrival direction (to the wall), none on the leg from the wall.
TEST(SceneFoliage, ReflectedLegsAccumulateFoliage) {
  constexpr double kDbPerM = 0.5;
  const Vec3 lo(-2, -2, 0), hi(2, 2, 3);
  MeshBuilder mb;
  mb.wall({-8.0, 0.0, -5000.0}, Vec3::UnitY(), 5000.0, 10000.0, mb.material("concrete"));
  mb.box(lo, hi, mb.material("hedge", kDbPerM));
  const Scene scene(mb.mesh);
  const Vec3 p(0, 0, 1.5);
  const Vec3 u = sat_dir(90, 10);
  const auto paths = reflect(scene, p, u);
  ASSERT_EQ(paths.size(), 1u);
  const Vec3 m(-u.x(), u.y(), u.z());
  const Vec3 r = paths[0].points_enu_m[0];
  const double expected = kDbPerM * (chord_in_box(p, m, lo, hi) + chord_in_box(r, u, lo, hi));
  EXPECT_GT(expected, 0.0);
  EXPECT_NEAR(paths[0].foliage_loss_db, expected, 1e-6 * expected);
  EXPECT_NEAR(scene.direct(p, u).foliage_loss_db, kDbPerM * chord_in_box(p, u, lo, hi), 1e-9);
}

// ---- Second order: street canyon -------------------------------------------------------------
// Walls W at x = -6 (40 m tall, facing east) and E at x = +9 (20 m, facing west), 10 km long,
// on a ground plane; antenna at (0, 0, 1.5); satellite to the east behind E. The signal comes
// over E, reflects on W, then on E, then reaches p. Image of image: p' = image of p in E,
// p'' = image of p' in W; excess = u.(p - p'') = 2 (a + b) u_e with a + b = 15 m the street
// width. Every other path is blocked by E (numbers in the comments of each case).
TEST(SceneSecondOrder, StreetCanyonMatchesImageOfImage) {
  MeshBuilder mb;
  const std::uint32_t west = mb.material("west");
  const std::uint32_t east = mb.material("east");
  mb.ground({0, 0, 0}, 5000.0, mb.material("asphalt"));
  mb.wall({-6.0, 0.0, 0.0}, Vec3::UnitY(), 5000.0, 40.0, west);
  mb.wall({9.0, 0.0, 0.0}, Vec3::UnitY(), 5000.0, 20.0, east);
  const Scene scene(mb.mesh);
  const Vec3 p(0, 0, 1.5);
  const Vec3 qW(-6, 0, 0), qE(9, 0, 0), nx = Vec3::UnitX();
  // az 90: u = (0.866, 0, 0.5): r1 = (9, 0, 6.70) on E, r2 = (-6, 0, 15.36) on W, the last leg
  // passes x = 9 at z = 24.0 > 20. First order on W: leg at x = 9 at z = 13.6 < 20, blocked.
  // az 60: u = (0.75, 0.433, 0.5): r1 z = 7.5, r2 z = 17.5, last leg over E at 27.5 m.
  for (const double az : {90.0, 60.0}) {
    const Vec3 u = sat_dir(az, 30);
    SCOPED_TRACE(az);
    EXPECT_TRUE(scene.direct(p, u).blocked);
    EXPECT_TRUE(reflect(scene, p, u, 1).empty());
    const auto paths = reflect(scene, p, u, 2);
    ASSERT_EQ(paths.size(), 1u);
    const ReflectedPath& r = paths[0];
    EXPECT_EQ(r.order, 2);
    const Vec3 p2 = image(image(p, qE, nx), qW, nx);
    EXPECT_NEAR(r.excess_m, u.dot(p - p2), kMm);
    EXPECT_NEAR(r.excess_m, 2.0 * 15.0 * u.x(), kMm);
    EXPECT_EQ(r.material[0], east);
    EXPECT_EQ(r.material[1], west);
    // r1 where the line from p towards the satellite meets E; r2 on W along u mirrored in x.
    const Vec3 r1 = p + (9.0 / u.x()) * u;
    const Vec3 r2 = r1 + (15.0 / u.x()) * Vec3(-u.x(), u.y(), u.z());
    EXPECT_NEAR((r.points_enu_m[0] - r1).norm(), 0.0, kMm);
    EXPECT_NEAR((r.points_enu_m[1] - r2).norm(), 0.0, kMm);
    // The general definition: |r1 - p| + |r2 - r1| - (r2 - p).u.
    const double len = (r1 - p).norm() + (r2 - r1).norm() - (r2 - p).dot(u);
    EXPECT_NEAR(r.excess_m, len, kMm);
    EXPECT_NEAR((r.arrival_enu - u).norm(), 0.0, 1e-12);  // mirrored twice in parallel planes
  }
  // Satellite in the west at 60 deg, u = (-0.5, 0, 0.866): the first order on E exists
  // (r at x = 9, z = 1.5 + 18 * 0.866 = 17.1 < 20; its leg passes x = -6 at 43.1 m > 40) with
  // excess 2 * 9 * cos(60) = 9 m; the output is sorted by excess.
  const auto west_paths = reflect(scene, p, sat_dir(270, 60), 2);
  ASSERT_FALSE(west_paths.empty());
  EXPECT_EQ(std::count_if(west_paths.begin(), west_paths.end(),
                          [](const ReflectedPath& r) {
                            return r.order == 1 && std::abs(r.excess_m - 9.0) < kMm &&
                                   std::abs(r.points_enu_m[0].x() - 9.0) < kMm;
                          }),
            1);
  EXPECT_TRUE(std::is_sorted(west_paths.begin(), west_paths.end(),
                             [](const auto& a, const auto& b) { return a.excess_m < b.excess_m; }));
}

// ---- Faces and bookkeeping -------------------------------------------------------------------
TEST(SceneFaces, CoplanarEdgeConnectedTrianglesFormOneFace) {
  MeshBuilder mb;
  const std::uint32_t c = mb.material("concrete");
  mb.box({0, 0, 0}, {10, 10, 10}, c);                          // 12 triangles, 6 faces
  mb.wall({30, 0, 0}, Vec3::UnitY(), 5.0, 10.0, c, true);      // mixed windings: 1 face
  mb.wall({30, 20, 0}, Vec3::UnitY(), 5.0, 10.0, c);           // coplanar, disjoint: 1 face
  mb.box({50, 0, 0}, {52, 2, 2}, mb.material("bush", 1.0));    // foliage: no faces
  // A box whose faces repeat their vertices (no shared indices): welded, 6 faces.
  const Vec3 lo(70, 0, 0), hi(75, 5, 5);
  mb.quad({lo.x(), lo.y(), lo.z()}, {hi.x(), lo.y(), lo.z()}, {hi.x(), hi.y(), lo.z()},
          {lo.x(), hi.y(), lo.z()}, c);
  mb.quad({lo.x(), lo.y(), hi.z()}, {hi.x(), lo.y(), hi.z()}, {hi.x(), hi.y(), hi.z()},
          {lo.x(), hi.y(), hi.z()}, c);
  mb.quad({lo.x(), lo.y(), lo.z()}, {hi.x(), lo.y(), lo.z()}, {hi.x(), lo.y(), hi.z()},
          {lo.x(), lo.y(), hi.z()}, c);
  mb.quad({lo.x(), hi.y(), lo.z()}, {hi.x(), hi.y(), lo.z()}, {hi.x(), hi.y(), hi.z()},
          {lo.x(), hi.y(), hi.z()}, c);
  mb.quad({lo.x(), lo.y(), lo.z()}, {lo.x(), hi.y(), lo.z()}, {lo.x(), hi.y(), hi.z()},
          {lo.x(), lo.y(), hi.z()}, c);
  mb.quad({hi.x(), lo.y(), lo.z()}, {hi.x(), hi.y(), lo.z()}, {hi.x(), hi.y(), hi.z()},
          {hi.x(), lo.y(), hi.z()}, c);
  const Scene scene(mb.mesh);
  const SceneStats st = scene.stats();
  EXPECT_EQ(st.triangles, 12u + 2u + 2u + 12u + 12u);
  EXPECT_EQ(st.faces, 6u + 1u + 1u + 6u);
  EXPECT_GT(st.memory_bytes, 0u);
  EXPECT_EQ(scene.material(c).name, "concrete");
  EXPECT_THROW(scene.material(9), std::out_of_range);
}

TEST(SceneQueries, CountRaysAndAgreeAcrossThreads) {
  MeshBuilder mb;
  const std::uint32_t c = mb.material("concrete");
  mb.ground({0, 0, 0}, 2000.0, c);
  for (int i = 0; i < 8; ++i) {
    for (int j = 0; j < 8; ++j) {
      mb.box({i * 40.0 - 160.0, j * 40.0 - 160.0, 0.0},
             {i * 40.0 - 130.0, j * 40.0 - 130.0, 10.0 + 5.0 * ((i * 7 + j * 3) % 6)}, c);
    }
  }
  const Scene scene(mb.mesh);
  const Vec3 p(-5.0, 2.0, 1.5);  // in a street
  const auto run = [&](std::vector<double>& excess) {
    for (int k = 0; k < 24; ++k) {
      const auto paths = reflect(scene, p, sat_dir(15.0 * k, 10.0 + 3.0 * k), 2, 300.0);
      for (const auto& r : paths) excess.push_back(r.excess_m);
      excess.push_back(scene.direct(p, sat_dir(15.0 * k, 10.0 + 3.0 * k)).blocked ? -1.0 : -2.0);
    }
  };
  const std::uint64_t before = scene.rays_cast();
  std::vector<double> serial;
  run(serial);
  EXPECT_GT(scene.rays_cast(), before);
  EXPECT_GT(serial.size(), 24u + 12u);  // 24 direct markers and some reflections
  std::vector<double> a, b;
  std::thread ta([&] { run(a); });
  std::thread tb([&] { run(b); });
  ta.join();
  tb.join();
  EXPECT_EQ(a, serial);
  EXPECT_EQ(b, serial);
}

// ---- Validation --------------------------------------------------------------------------------
std::string error_of(SceneMesh mesh) {
  try {
    const Scene scene(std::move(mesh));
  } catch (const InvalidScene& e) {
    return e.what();
  }
  return "(no error)";
}

SceneMesh twenty_walls() {
  MeshBuilder mb;
  const std::uint32_t c = mb.material("concrete");
  for (int i = 0; i < 10; ++i) mb.wall({i * 10.0, 0, 0}, Vec3::UnitY(), 2.0, 3.0, c);
  return mb.mesh;  // triangles 0..19, vertices 0..39
}

TEST(SceneValidation, InvalidMeshesThrowNamingTheIndex) {
  EXPECT_EQ(error_of(SceneMesh{}), "scene: no triangles");
  {
    SceneMesh m = twenty_walls();
    const std::uint32_t v = m.triangles[17][2];  // not shared with triangle 16
    m.vertices_enu_m[v].y() = std::numeric_limits<double>::quiet_NaN();
    EXPECT_EQ(error_of(m), "scene: triangle 17 has a non-finite vertex " + std::to_string(v));
  }
  {
    SceneMesh m = twenty_walls();
    m.triangles[3][2] = 99;
    EXPECT_EQ(error_of(m), "scene: triangle 3 has vertex index 99 out of range (40 vertices)");
  }
  {
    SceneMesh m = twenty_walls();
    m.triangles[5][1] = m.triangles[5][0];
    EXPECT_NE(error_of(m).find("scene: triangle 5 is degenerate"), std::string::npos);
  }
  {
    SceneMesh m = twenty_walls();  // collinear vertices
    m.vertices_enu_m.push_back({0, 0, 0});
    m.vertices_enu_m.push_back({1, 1, 1});
    m.vertices_enu_m.push_back({2, 2, 2});
    m.triangles[8] = {40, 41, 42};
    EXPECT_NE(error_of(m).find("scene: triangle 8 is degenerate"), std::string::npos);
  }
  {
    SceneMesh m = twenty_walls();
    m.triangle_material[11] = 7;
    EXPECT_EQ(error_of(m), "scene: triangle 11 has material 7 out of range (1 materials)");
  }
  {
    SceneMesh m = twenty_walls();
    m.triangle_material.pop_back();
    EXPECT_EQ(error_of(m), "scene: 19 triangle materials for 20 triangles");
  }
  {
    SceneMesh m = twenty_walls();
    m.vertices_enu_m.push_back({std::numeric_limits<double>::infinity(), 0, 0});
    EXPECT_EQ(error_of(m), "scene: vertex 40 is not finite");
  }
  {
    SceneMesh m = twenty_walls();
    m.materials[0].foliage_db_per_m = -1.0;
    EXPECT_NE(error_of(m).find("scene: material 0 (\"concrete\")"), std::string::npos);
  }
  EXPECT_EQ(error_of(twenty_walls()), "(no error)");
}

}  // namespace
}  // namespace navemu
