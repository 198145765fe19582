// Geoid heights from a grid (models/geoid.hpp): bilinear interpolation between nodes, the
// longitude wrapping around the globe, the poles, and grids that do not cover the globe. The
// expected values are worked out by hand from the node values of small synthetic grids; the
// EGM96 grid itself is tested against NGA's published values in
// tests/emulator/test_geoid_loader.cpp.

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "models/geoid.hpp"

namespace navemu {
namespace {

// A 90-degree grid: rows at -90, 0, 90 and columns at -180, -90, 0, 90 (4 columns once around).
// Node (r, c) holds 10 r + c, so each value says where it sits.
GeoidGrid coarse_grid() {
  std::vector<float> n;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) n.push_back(static_cast<float>(10 * r + c));
  return GeoidGrid("coarse", -180.0, 90.0, 3, 4, n);
}

TEST(GeoidGrid, NodesGiveTheirValues) {
  const GeoidGrid g = coarse_grid();
  EXPECT_DOUBLE_EQ(g.separation_m(-90.0, -180.0), 0.0);
  EXPECT_DOUBLE_EQ(g.separation_m(0.0, -90.0), 11.0);
  EXPECT_DOUBLE_EQ(g.separation_m(0.0, 0.0), 12.0);
  EXPECT_DOUBLE_EQ(g.separation_m(0.0, 90.0), 13.0);
  EXPECT_DOUBLE_EQ(g.separation_m(90.0, 90.0), 23.0);
}

TEST(GeoidGrid, BetweenNodesIsBilinear) {
  const GeoidGrid g = coarse_grid();
  // The middle of the cell with corners 11, 12, 21, 22.
  EXPECT_DOUBLE_EQ(g.separation_m(45.0, -45.0), (11.0 + 12.0 + 21.0 + 22.0) / 4.0);
  // A quarter of the way east and three quarters north of the corner 11:
  // (1 - 3/4) (3/4 * 11 + 1/4 * 12) + 3/4 (3/4 * 21 + 1/4 * 22) = 18.75.
  EXPECT_NEAR(g.separation_m(67.5, -67.5), 18.75, 1e-12);
  // Along a row only the longitude weights: a third of the way from 12 to 13.
  EXPECT_NEAR(g.separation_m(0.0, 30.0), 12.0 + 1.0 / 3.0, 1e-12);
}

TEST(GeoidGrid, LongitudeWrapsAroundTheGlobe) {
  const GeoidGrid g = coarse_grid();
  // Between the last column (90 E, value 13) and the first one again (180 = -180, value 10).
  EXPECT_DOUBLE_EQ(g.separation_m(0.0, 135.0), (13.0 + 10.0) / 2.0);
  EXPECT_DOUBLE_EQ(g.separation_m(0.0, 180.0), 10.0);
  EXPECT_DOUBLE_EQ(g.separation_m(0.0, -180.0), 10.0);
  // Longitudes outside [-180, 180) (e.g. 0-360 as NGA's test files give them) name the same place.
  EXPECT_NEAR(g.separation_m(45.0, 315.0), g.separation_m(45.0, -45.0), 1e-12);
  EXPECT_NEAR(g.separation_m(45.0, -405.0), g.separation_m(45.0, -45.0), 1e-12);
  EXPECT_NEAR(g.separation_m(10.0, 359.999999), g.separation_m(10.0, -0.000001), 1e-9);
}

TEST(GeoidGrid, PolesTakeTheLastRow) {
  const GeoidGrid g = coarse_grid();
  EXPECT_DOUBLE_EQ(g.separation_m(90.0, -45.0), (22.0 + 21.0) / 2.0);
  EXPECT_DOUBLE_EQ(g.separation_m(-90.0, -45.0), (1.0 + 2.0) / 2.0);
  EXPECT_DOUBLE_EQ(g.separation_m(91.0, -45.0), g.separation_m(90.0, -45.0));
  EXPECT_TRUE(std::isnan(g.separation_m(std::nan(""), 0.0)));
  EXPECT_TRUE(std::isnan(g.separation_m(0.0, INFINITY)));
}

TEST(GeoidGrid, OnlyGlobalGridsAreAccepted) {
  const std::vector<float> twelve(12, 0.0f);
  EXPECT_NO_THROW(GeoidGrid("ok", -180.0, 90.0, 3, 4, twelve));
  EXPECT_THROW(GeoidGrid("short of a pole", -180.0, 90.0, 2, 4, std::vector<float>(8)),
               std::invalid_argument);
  EXPECT_THROW(GeoidGrid("not once around", -180.0, 90.0, 3, 3, std::vector<float>(9)),
               std::invalid_argument);
  EXPECT_THROW(GeoidGrid("values missing", -180.0, 90.0, 3, 4, std::vector<float>(11)),
               std::invalid_argument);
  EXPECT_THROW(GeoidGrid("no step", -180.0, 0.0, 3, 4, twelve), std::invalid_argument);
}

}  // namespace
}  // namespace navemu
