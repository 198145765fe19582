// WGS-84 geodesy: ECEF <-> geodetic against published station coordinates, round trips at
// awkward places, local frames and azimuth/elevation.

#include <gtest/gtest.h>

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "models/geodesy.hpp"
#include "tests/test_support.hpp"

namespace navemu {
namespace {

constexpr double kMm = 1e-3;
// One millimetre on the ground, in degrees of latitude (about 9e-9 deg).
constexpr double kMmDeg = 1e-3 / 111'000.0;

// Unit vectors of the local frame at a geodetic position, written out in the test so as not
// to depend on the implementation (e.g. Hofmann-Wellenhof et al., GNSS, eq. 10.14).
Vec3 up_ecef(double lat_deg, double lon_deg) {
  const double p = lat_deg * kDegToRad, l = lon_deg * kDegToRad;
  return {std::cos(p) * std::cos(l), std::cos(p) * std::sin(l), std::sin(p)};
}
Vec3 north_ecef(double lat_deg, double lon_deg) {
  const double p = lat_deg * kDegToRad, l = lon_deg * kDegToRad;
  return {-std::sin(p) * std::cos(l), -std::sin(p) * std::sin(l), std::cos(p)};
}
Vec3 east_ecef(double lon_deg) {
  const double l = lon_deg * kDegToRad;
  return {-std::sin(l), std::cos(l), 0.0};
}

// GEONET 0759 (../shared/data/README.md, RTKLIB data/stations.pos, 2009/1/1 F3 solution).
TEST(GeodesyEcef, Geonet0759) {
  const Geodetic g{35.160866522, 139.613842697, 68.3892};
  const Vec3 ref{-3976219.1454, 3382371.6073, 3652511.1964};
  const Vec3 p = ecef_from_geodetic(g);
  EXPECT_NEAR(p.x(), ref.x(), kMm);
  EXPECT_NEAR(p.y(), ref.y(), kMm);
  EXPECT_NEAR(p.z(), ref.z(), kMm);
  const Geodetic back = geodetic_from_ecef(ref);
  EXPECT_NEAR(back.lat_deg, g.lat_deg, kMmDeg);
  EXPECT_NEAR(back.lon_deg, g.lon_deg, kMmDeg);
  EXPECT_NEAR(back.h_m, g.h_m, kMm);
}

// GEONET 3040, base position of RTKLIB's rnx2rtkp tests; geodetic values given to 1e-9 deg
// and 1 mm in ../shared/data/README.md.
TEST(GeodesyEcef, Geonet3040) {
  const Geodetic back = geodetic_from_ecef({-3978241.958, 3382840.234, 3649900.853});
  EXPECT_NEAR(back.lat_deg, 35.132057068, 2 * kMmDeg);
  EXPECT_NEAR(back.lon_deg, 139.624306577, 2 * kMmDeg);
  EXPECT_NEAR(back.h_m, 73.908, 2 * kMm);
}

// Spirent SimGEN static antenna, a simulator input (exact).
TEST(GeodesyEcef, SpirentStatic) {
  const Vec3 ref{-481819.31349724, 5507219.95375401, 3170373.73538364};
  const Vec3 p = ecef_from_geodetic({30.0, 95.0, 0.0});
  EXPECT_NEAR((p - ref).norm(), 0.0, 1e-6);
  const Geodetic g = geodetic_from_ecef(ref);
  EXPECT_NEAR(g.lat_deg, 30.0, 1e-11);
  EXPECT_NEAR(g.lon_deg, 95.0, 1e-11);
  EXPECT_NEAR(g.h_m, 0.0, 1e-6);
}

// WGS-84 semi-axes: a = 6378137 m, b = a (1 - f), f = 1/298.257223563.
TEST(GeodesyEcef, EquatorAndPoles) {
  const double a = 6378137.0, b = a * (1.0 - 1.0 / 298.257223563);
  EXPECT_NEAR((ecef_from_geodetic({0, 0, 0}) - Vec3(a, 0, 0)).norm(), 0.0, 1e-6);
  EXPECT_NEAR((ecef_from_geodetic({90, 0, 0}) - Vec3(0, 0, b)).norm(), 0.0, 1e-6);
  EXPECT_NEAR((ecef_from_geodetic({-90, 0, 100}) - Vec3(0, 0, -b - 100)).norm(), 0.0, 1e-6);
  const Geodetic np = geodetic_from_ecef({0, 0, b + 1000});
  EXPECT_NEAR(np.lat_deg, 90.0, 1e-12);
  EXPECT_NEAR(np.h_m, 1000.0, 1e-6);
  const Geodetic sp = geodetic_from_ecef({0, 0, -b});
  EXPECT_NEAR(sp.lat_deg, -90.0, 1e-12);
  EXPECT_NEAR(sp.h_m, 0.0, 1e-6);
}

TEST(GeodesyEcef, RoundTrips) {
  for (const Geodetic g : {Geodetic{89.9999999, 12.0, 10.0}, Geodetic{-89.999, -170.0, 0.0},
                           Geodetic{0.0, 180.0, 0.0}, Geodetic{10.0, -179.9999999, 500.0},
                           Geodetic{45.0, 179.9999999, -100.0}, Geodetic{-33.9, 18.4, 26'000'000.0},
                           Geodetic{55.49, 8.46, 20'200'000.0}, Geodetic{-1.0, -1.0, -400.0}}) {
    SCOPED_TRACE(testing::Message() << g.lat_deg << " " << g.lon_deg << " " << g.h_m);
    const Vec3 p = ecef_from_geodetic(g);
    const Geodetic back = geodetic_from_ecef(p);
    EXPECT_NEAR(back.lat_deg, g.lat_deg, 1e-10);
    // Longitudes compare modulo 360 (180 and -180 are the same meridian).
    EXPECT_NEAR(std::remainder(back.lon_deg - g.lon_deg, 360.0), 0.0, 1e-10);
    EXPECT_NEAR(back.h_m, g.h_m, 1e-6 * std::max(1.0, std::abs(g.h_m) / 1e6));
    EXPECT_NEAR((ecef_from_geodetic(back) - p).norm(), 0.0, 1e-6 * std::max(1.0, g.h_m / 1e6));
  }
}

// ---- local frames --------------------------------------------------------------------------

TEST(GeodesyFrames, RotationsOrthonormalAndConsistent) {
  for (const Geodetic g : {Geodetic{35.16, 139.61, 68}, Geodetic{90, 0, 0}, Geodetic{-90, 45, 0},
                           Geodetic{0, 180, 0}, Geodetic{-33.9, -70.6, 500}}) {
    const Mat3 enu = R_enu_from_ecef(g);
    const Mat3 ned = R_ned_from_ecef(g);
    EXPECT_NEAR((enu * enu.transpose() - Mat3::Identity()).norm(), 0.0, 1e-14);
    EXPECT_NEAR((ned * ned.transpose() - Mat3::Identity()).norm(), 0.0, 1e-14);
    EXPECT_NEAR(enu.determinant(), 1.0, 1e-14);
    EXPECT_NEAR(ned.determinant(), 1.0, 1e-14);
    EXPECT_NEAR((enu.row(0).transpose() - east_ecef(g.lon_deg)).norm(), 0.0, 1e-15);
    EXPECT_NEAR((enu.row(1).transpose() - north_ecef(g.lat_deg, g.lon_deg)).norm(), 0.0, 1e-15);
    EXPECT_NEAR((enu.row(2).transpose() - up_ecef(g.lat_deg, g.lon_deg)).norm(), 0.0, 1e-15);
    EXPECT_NEAR((ned.row(0) - enu.row(1)).norm(), 0.0, 0.0);
    EXPECT_NEAR((ned.row(1) - enu.row(0)).norm(), 0.0, 0.0);
    EXPECT_NEAR((ned.row(2) + enu.row(2)).norm(), 0.0, 0.0);
  }
}

TEST(GeodesyFrames, EnuOfOffsets) {
  const Geodetic o{35.160866522, 139.613842697, 68.3892};
  const Vec3 p0 = ecef_from_geodetic(o);
  EXPECT_NEAR(enu_from_ecef(p0, o).norm(), 0.0, 1e-6);
  const Vec3 enu = enu_from_ecef(p0 + 3.0 * east_ecef(o.lon_deg) + 4.0 * north_ecef(o.lat_deg, o.lon_deg) +
                                     5.0 * up_ecef(o.lat_deg, o.lon_deg),
                                 o);
  EXPECT_NEAR((enu - Vec3(3, 4, 5)).norm(), 0.0, 1e-6);
  // The 0759 -> 3040 baseline: 3040 is 3.33 km away and lies to the south-east.
  const Vec3 b = enu_from_ecef({-3978241.958, 3382840.234, 3649900.853}, o);
  EXPECT_NEAR(b.norm(), 3330.0, 10.0);
  EXPECT_GT(b.x(), 0.0);
  EXPECT_LT(b.y(), 0.0);
}

// ---- azimuth / elevation -------------------------------------------------------------------

TEST(GeodesyAzEl, CardinalDirections) {
  const Geodetic o{35.160866522, 139.613842697, 68.3892};
  const Vec3 rx = ecef_from_geodetic(o);
  const Vec3 up = up_ecef(o.lat_deg, o.lon_deg), n = north_ecef(o.lat_deg, o.lon_deg),
             e = east_ecef(o.lon_deg);
  const double d = 20'000'000.0;

  const AzEl zen = azimuth_elevation(rx, rx + d * up);
  EXPECT_NEAR(zen.el_rad * kRadToDeg, 90.0, 1e-9);
  const AzEl north = azimuth_elevation(rx, rx + d * n);
  EXPECT_NEAR(north.az_rad, 0.0, 1e-12);
  EXPECT_NEAR(north.el_rad, 0.0, 1e-12);
  const AzEl east = azimuth_elevation(o, rx, rx + d * e);
  EXPECT_NEAR(east.az_rad * kRadToDeg, 90.0, 1e-9);
  EXPECT_NEAR(east.el_rad, 0.0, 1e-12);
  EXPECT_NEAR(azimuth_elevation(rx, rx - d * n).az_rad * kRadToDeg, 180.0, 1e-9);
  EXPECT_NEAR(azimuth_elevation(rx, rx - d * e).az_rad * kRadToDeg, 270.0, 1e-9);
  const AzEl nw = azimuth_elevation(rx, rx + d * n - 1.0 * e);
  EXPECT_GE(nw.az_rad, 0.0);
  EXPECT_LT(nw.az_rad, 2.0 * std::numbers::pi);
  EXPECT_NEAR(nw.az_rad, 2.0 * std::numbers::pi, 1e-6);
  const AzEl nadir = azimuth_elevation(rx, rx - d * up);
  EXPECT_NEAR(nadir.el_rad * kRadToDeg, -90.0, 1e-9);
  const AzEl ne45 = azimuth_elevation(rx, rx + 100.0 * (n + e) + 100.0 * std::sqrt(2.0) * up);
  EXPECT_NEAR(ne45.az_rad * kRadToDeg, 45.0, 1e-9);
  EXPECT_NEAR(ne45.el_rad * kRadToDeg, 45.0, 1e-9);
}

// Azimuth/elevation written by Spirent SimGEN for its static antenna at 30 N 95 E 0 m
// (sat_data_V1A1.csv, Time_ms 60000, GPS rows; values rounded to 1e-4 rad, azimuth in
// (-pi, pi]). The simulator's satellite positions and look angles come from its own models,
// so agreement to the printed precision is expected.
TEST(GeodesyAzEl, SpirentLookAngles) {
  const Vec3 rx{-481819.31349724, 5507219.95375401, 3170373.73538364};
  struct Row {
    Vec3 sat;
    double az, el;
  };
  const Row rows[] = {
      {{-13946912.0663, 22372291.9642, -819544.0049}, 2.3766, 0.6667},   // PRN 1
      {{-2786000.9885, 22614766.9572, 13652520.6980}, 1.0549, 1.5250},   // PRN 7
      {{15483892.8337, -426898.6723, 21422541.6450}, -0.6691, 0.1125},   // PRN 13
      {{12737582.5591, 22958857.0640, -3224234.4148}, -2.3197, 0.4963},  // PRN 17
      {{5889919.0627, 24174936.0220, -9304057.0507}, -2.7591, 0.4139},   // PRN 9
      {{-16727416.0989, 18110931.1843, 9335373.9703}, 1.6795, 0.7856},   // PRN 21
      {{-12356897.5190, 8935416.2948, 21677616.3165}, 0.6960, 0.6298},   // PRN 8
  };
  for (const Row& r : rows) {
    const AzEl ae = azimuth_elevation(rx, r.sat);
    EXPECT_NEAR(std::remainder(ae.az_rad - r.az, 2.0 * std::numbers::pi), 0.0, 2e-4);
    EXPECT_NEAR(ae.el_rad, r.el, 2e-4);
  }
}

}  // namespace
}  // namespace navemu
