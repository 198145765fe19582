#pragma once
// Geoid heights from a global grid of geoid undulations. Pure: the grid's values are given
// (emulator/geoid_loader.hpp reads them from a data file).

#include <string>
#include <vector>

namespace navemu {

// A geoid model as its undulation N, the height of the geoid above the WGS-84 ellipsoid in
// metres, at the nodes of a global latitude/longitude grid. The height above mean sea level
// (orthometric height) of a point at ellipsoidal height h is H = h - N (NGA, EGM96: h = H + N);
// N is what NMEA GGA calls the geoid separation. Between nodes N is interpolated bilinearly,
// as PROJ's vgridshift interpolates its grids (PROJ, src/transformations/vgridshift.cpp and
// grids.cpp), so that a grid read through PROJ gives PROJ's values.
class GeoidGrid {
 public:
  // `n_m` holds rows x cols node values, row by row from the south: node (r, c) lies at
  // latitude -90 + r * step_deg and longitude west_deg + c * step_deg. The grid covers the
  // globe: rows = 180 / step_deg + 1 (pole to pole) and cols = 360 / step_deg (longitude wraps
  // around); std::invalid_argument otherwise. `name` says which model it is (e.g. the file).
  GeoidGrid(std::string name, double west_deg, double step_deg, int rows, int cols,
            std::vector<float> n_m);

  // N at a position, bilinear between the four surrounding nodes. Any longitude (wrapped);
  // latitudes beyond the poles take the pole's row. NaN for a non-finite position.
  double separation_m(double lat_deg, double lon_deg) const;

  const std::string& name() const { return name_; }
  double step_deg() const { return step_deg_; }

 private:
  std::string name_;
  double west_deg_, step_deg_;
  int rows_, cols_;
  std::vector<float> n_m_;
};

}  // namespace navemu
