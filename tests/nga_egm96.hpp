#pragma once
// The test points NGA publishes with EGM96 (readme.txt of the EGM96 distribution,
// earth-info.nga.mil/GandG/wgs84/gravitymod/egm96/): latitude, longitude east in [0, 360) as
// NGA gives it, and the geoid height N in metres as NGA's programs compute it from the model.

namespace navemu::test {

struct NgaEgm96Point {
  double lat_deg, lon_deg, n_m;
};

inline constexpr NgaEgm96Point kNgaEgm96TestPoints[] = {
    {38.6281550, 269.7791550, -31.628}, {-14.6212170, 305.0211140, -2.969},
    {46.8743190, 102.4487290, -43.575}, {-23.6174460, 133.8747120, 15.871},
    {38.6254730, 359.9995000, 50.066},  {-0.4667440, 0.0023000, 17.329},
};

// What bilinear interpolation in the 15' grid (PROJ's egm96_15.gtx) may miss these by: its
// error is 0.040 m RMS and 1.15 m at worst, in high mountains (GeographicLib, GeoidEval
// documentation, egm96-15); the six points lie in smooth terrain, so 3 x the RMS. A wrong sign
// or a missing geoid is off by 3 to 100 m.
inline constexpr double kEgm96BilinearTolerance_m = 0.12;

}  // namespace navemu::test
