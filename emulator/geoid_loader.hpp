#pragma once
// The geoid of the receiver's heights above mean sea level, read from a grid file through PROJ
// (libproj) into memory once, before any real-time loop: evaluating it (models/geoid.hpp)
// then reads no file and allocates nothing.

#include <optional>
#include <string>

#include "models/geoid.hpp"

namespace navemu {

// EGM96 on NGA's 15' grid (WW15MGH.GRD) as PROJ's data ships it: Debian package proj-data,
// /usr/share/proj/egm96_15.gtx.
inline constexpr const char* kEgm96GridName = "egm96_15.gtx";

struct LoadedGeoid {
  std::optional<GeoidGrid> grid;  // none: the grid file is missing or unusable
  // One line for the start-up messages: the grid and the file it came from; without a grid a
  // warning saying why, how to install it, and that MSL heights then equal ellipsoidal ones.
  std::string description;
};

// Reads a global geoid grid (values N, MSL height = h - N) by path or by file name in PROJ's
// search path (~/.local/share/proj, then the folders of PROJ_DATA or else /usr/share/proj).
// PROJ reads the file, and its own vgridshift gives the value at every node.
LoadedGeoid load_geoid(const std::string& grid_name);

// EGM96 (kEgm96GridName), loaded on the first call and shared by every later one.
const LoadedGeoid& egm96_geoid();

}  // namespace navemu
