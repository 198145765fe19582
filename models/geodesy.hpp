#pragma once
// WGS-84 geodesy through GeographicLib: ECEF <-> geodetic, local ENU/NED frames and
// azimuth/elevation on the geodetic normal. Heights above mean sea level: models/geoid.hpp.

#include "core/vec.hpp"

namespace navemu {

// WGS-84 constants as used by GPS (IS-GPS-200 Table 20-IV).
inline constexpr double kGpsMu_m3ps2 = 3.986005e14;          // Earth's gravitational constant
inline constexpr double kOmegaEarth_radps = 7.2921151467e-5;  // Earth rotation rate
inline constexpr double kSpeedOfLight_mps = 299'792'458.0;
inline constexpr double kPi = 3.1415926535898;  // the value IS-GPS-200 prescribes for orbits
inline constexpr double kDegToRad = 3.14159265358979323846 / 180.0;
inline constexpr double kRadToDeg = 180.0 / 3.14159265358979323846;
inline constexpr double kStandardGravity_mps2 = 9.80665;  // per g (CGPM 1901, 3rd meeting)

struct Geodetic {
  double lat_deg = 0.0;
  double lon_deg = 0.0;
  double h_m = 0.0;  // height above the WGS-84 ellipsoid
};

Vec3 ecef_from_geodetic(const Geodetic& g);
Geodetic geodetic_from_ecef(const Vec3& p_ecef_m);

// Rotation taking ECEF vectors into the local East-North-Up (resp. North-East-Down) frame
// at a geodetic position.
Mat3 R_enu_from_ecef(const Geodetic& origin);
Mat3 R_ned_from_ecef(const Geodetic& origin);

Vec3 enu_from_ecef(const Vec3& p_ecef_m, const Geodetic& origin);  // position relative to origin

struct AzEl {
  double az_rad = 0.0;  // from north, clockwise, [0, 2pi)
  double el_rad = 0.0;  // above the plane normal to the ellipsoid normal
};
// Direction from a receiver to a target (e.g. a satellite), both in ECEF.
AzEl azimuth_elevation(const Vec3& p_rx_ecef_m, const Vec3& p_target_ecef_m);
AzEl azimuth_elevation(const Geodetic& rx, const Vec3& p_rx_ecef_m, const Vec3& p_target_ecef_m);
// The same with the receiver's R_enu_from_ecef computed once for many targets.
AzEl azimuth_elevation(const Mat3& R_enu_from_ecef_rx, const Vec3& p_rx_ecef_m,
                       const Vec3& p_target_ecef_m);

// A direction with the sines and cosines of its angles, read off the unit line of sight's
// east, north and up components (sin el = u, cos el = sqrt(e^2 + n^2), sin az = e / cos el,
// cos az = n / cos el; at the zenith az = 0): what the atmosphere models and the DOPs use.
struct Direction {
  AzEl az_el;
  double sin_el = 0.0, cos_el = 1.0, sin_az = 0.0, cos_az = 1.0;
};
Direction direction(const Mat3& R_enu_from_ecef_rx, const Vec3& p_rx_ecef_m, const Vec3& p_target_ecef_m);
// The same from the angles.
Direction direction(const AzEl& dir);

}  // namespace navemu
