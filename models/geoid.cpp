#include "models/geoid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

namespace navemu {

GeoidGrid::GeoidGrid(std::string name, double west_deg, double step_deg, int rows, int cols,
                     std::vector<float> n_m)
    : name_(std::move(name)), west_deg_(west_deg), step_deg_(step_deg), rows_(rows), cols_(cols),
      n_m_(std::move(n_m)) {
  const auto bad = [&](const char* what) {
    return std::invalid_argument("geoid grid " + name_ + ": " + what);
  };
  if (!(step_deg > 0.0) || !std::isfinite(west_deg)) throw bad("needs a positive step and a finite west edge");
  if (std::fabs(static_cast<double>(rows - 1) * step_deg - 180.0) > 1e-9 * 180.0)
    throw bad("rows must run from pole to pole (rows = 180 / step + 1)");
  if (std::fabs(static_cast<double>(cols) * step_deg - 360.0) > 1e-9 * 360.0)
    throw bad("columns must go once around the globe (cols = 360 / step)");
  if (n_m_.size() != static_cast<std::size_t>(rows) * static_cast<std::size_t>(cols))
    throw bad("needs rows x cols values");
}

double GeoidGrid::separation_m(double lat_deg, double lon_deg) const {
  if (!std::isfinite(lat_deg) || !std::isfinite(lon_deg)) return std::numeric_limits<double>::quiet_NaN();
  // Grid coordinates: y rows north of the south pole, x columns east of the west edge, the
  // longitude reduced to [west, west + 360).
  const double y = std::clamp((lat_deg + 90.0) / step_deg_, 0.0, static_cast<double>(rows_ - 1));
  double lon = std::fmod(lon_deg - west_deg_, 360.0);
  if (lon < 0.0) lon += 360.0;
  const double x = lon / step_deg_;
  const int r = std::min(static_cast<int>(y), rows_ - 2);  // the north pole: the last cell, fy = 1
  const int c = std::min(static_cast<int>(x), cols_ - 1);
  const int c1 = c + 1 == cols_ ? 0 : c + 1;  // across the grid's seam
  const double fy = y - r, fx = x - c;
  const auto n = [&](int row, int col) {
    return static_cast<double>(n_m_[static_cast<std::size_t>(row) * static_cast<std::size_t>(cols_) +
                                    static_cast<std::size_t>(col)]);
  };
  return (1.0 - fy) * ((1.0 - fx) * n(r, c) + fx * n(r, c1)) +
         fy * ((1.0 - fx) * n(r + 1, c) + fx * n(r + 1, c1));
}

}  // namespace navemu
