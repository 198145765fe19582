#include "models/geodesy.hpp"

#include <GeographicLib/Geocentric.hpp>

#include <cmath>

namespace navemu {

namespace {

constexpr double kTwoPi = 2.0 * 3.14159265358979323846;

}  // namespace

Vec3 ecef_from_geodetic(const Geodetic& g) {
  Vec3 p;
  GeographicLib::Geocentric::WGS84().Forward(g.lat_deg, g.lon_deg, g.h_m, p.x(), p.y(), p.z());
  return p;
}

Geodetic geodetic_from_ecef(const Vec3& p_ecef_m) {
  Geodetic g;
  GeographicLib::Geocentric::WGS84().Reverse(p_ecef_m.x(), p_ecef_m.y(), p_ecef_m.z(), g.lat_deg,
                                             g.lon_deg, g.h_m);
  return g;
}

// Rows are the local east, north and up unit vectors expressed in ECEF, the up vector being
// the ellipsoid normal at the geodetic latitude (the transpose of the matrix M that
// GeographicLib::Geocentric returns). Built directly so that no allocation takes place.
Mat3 R_enu_from_ecef(const Geodetic& origin) {
  const double lat = origin.lat_deg * kDegToRad;
  const double lon = origin.lon_deg * kDegToRad;
  const double sphi = std::sin(lat), cphi = std::cos(lat);
  const double slam = std::sin(lon), clam = std::cos(lon);
  Mat3 R;
  R << -slam, clam, 0.0,                    //
      -sphi * clam, -sphi * slam, cphi,     //
      cphi * clam, cphi * slam, sphi;
  return R;
}

Mat3 R_ned_from_ecef(const Geodetic& origin) {
  const Mat3 enu = R_enu_from_ecef(origin);
  Mat3 R;
  R.row(0) = enu.row(1);
  R.row(1) = enu.row(0);
  R.row(2) = -enu.row(2);
  return R;
}

Vec3 enu_from_ecef(const Vec3& p_ecef_m, const Geodetic& origin) {
  return R_enu_from_ecef(origin) * (p_ecef_m - ecef_from_geodetic(origin));
}

AzEl azimuth_elevation(const Vec3& p_rx_ecef_m, const Vec3& p_target_ecef_m) {
  return azimuth_elevation(geodetic_from_ecef(p_rx_ecef_m), p_rx_ecef_m, p_target_ecef_m);
}

AzEl azimuth_elevation(const Geodetic& rx, const Vec3& p_rx_ecef_m, const Vec3& p_target_ecef_m) {
  return azimuth_elevation(R_enu_from_ecef(rx), p_rx_ecef_m, p_target_ecef_m);
}

AzEl azimuth_elevation(const Mat3& R_enu_from_ecef_rx, const Vec3& p_rx_ecef_m,
                       const Vec3& p_target_ecef_m) {
  return direction(R_enu_from_ecef_rx, p_rx_ecef_m, p_target_ecef_m).az_el;
}

Direction direction(const Mat3& R_enu_from_ecef_rx, const Vec3& p_rx_ecef_m, const Vec3& p_target_ecef_m) {
  const Vec3 enu = R_enu_from_ecef_rx * (p_target_ecef_m - p_rx_ecef_m);
  const double horizontal = std::sqrt(enu.x() * enu.x() + enu.y() * enu.y());
  const double range = std::sqrt(horizontal * horizontal + enu.z() * enu.z());
  Direction d;
  d.az_el.el_rad = std::atan2(enu.z(), horizontal);
  double az = std::atan2(enu.x(), enu.y());
  if (az < 0.0) az += kTwoPi;
  if (az >= kTwoPi) az = 0.0;  // a tiny negative angle rounded up to 2*pi
  d.az_el.az_rad = az;
  if (range > 0.0) {
    d.sin_el = enu.z() / range;
    d.cos_el = horizontal / range;
  }
  if (horizontal > 0.0) {
    d.sin_az = enu.x() / horizontal;
    d.cos_az = enu.y() / horizontal;
  }
  return d;
}

Direction direction(const AzEl& dir) {
  return {dir, std::sin(dir.el_rad), std::cos(dir.el_rad), std::sin(dir.az_rad), std::cos(dir.az_rad)};
}

}  // namespace navemu
