#include "emulator/geoid_loader.hpp"

#include <proj.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string_view>
#include <vector>

namespace navemu {

namespace {

constexpr double kRadToDegExact = 180.0 / 3.14159265358979323846;

struct ContextDeleter {
  void operator()(PJ_CONTEXT* c) const { proj_context_destroy(c); }
};
struct PjDeleter {
  void operator()(PJ* p) const { proj_destroy(p); }
};

LoadedGeoid without_geoid(const std::string& why) {
  LoadedGeoid out;
  out.description = fmt::format(
      "warning: no geoid: {}; heights above mean sea level equal ellipsoidal heights (geoid "
      "separation 0, up to about 100 m off)",
      why);
  return out;
}

}  // namespace

LoadedGeoid load_geoid(const std::string& grid_name) {
  const PJ_INFO info = proj_info();
  // The grid's file and layout (PROJ's default context: PROJ_DATA or the built-in search path).
  const PJ_GRID_INFO g = proj_grid_info(grid_name.c_str());
  if (std::string_view(g.format) == "missing")
    return without_geoid(fmt::format(
        "grid {} not found in PROJ's search path {} (Debian package proj-data installs it; "
        "PROJ_DATA names other folders)",
        grid_name, info.searchpath));

  // A global grid of square cells, pole to pole and once around (PROJ gives radians).
  const double step_deg = g.cs_lat * kRadToDegExact;
  const double west_deg = g.lowerleft.lam * kRadToDegExact;
  const bool global = g.n_lat >= 2 && g.n_lon >= 1 && std::fabs(g.cs_lon - g.cs_lat) < 1e-12 &&
                      std::fabs(g.lowerleft.phi * kRadToDegExact + 90.0) < 1e-9 &&
                      std::fabs((g.n_lat - 1) * step_deg - 180.0) < 1e-6 &&
                      std::fabs(g.n_lon * step_deg - 360.0) < 1e-6;
  if (!global)
    return without_geoid(fmt::format("{} ({}) is not a global grid of square cells", grid_name,
                                     g.filename));

  // PROJ prints its errors to stderr unless told otherwise: its failure becomes this
  // function's message instead.
  const std::unique_ptr<PJ_CONTEXT, ContextDeleter> ctx(proj_context_create());
  proj_log_level(ctx.get(), PJ_LOG_NONE);
  // vgridshift adds multiplier x the grid's value to the height (PROJ documentation,
  // "Vertical grid shift"): with multiplier 1, a height of 0 becomes N.
  const std::unique_ptr<PJ, PjDeleter> shift(proj_create(
      ctx.get(), fmt::format("+proj=vgridshift +grids={} +multiplier=1", g.filename).c_str()));
  if (!shift)
    return without_geoid(fmt::format(
        "PROJ cannot read {}: {}", g.filename,
        proj_context_errno_string(ctx.get(), proj_context_errno(ctx.get()))));

  // N at every node, a row at a time. Longitude and latitude in radians, as PROJ's grid
  // extent (node c of a row at west + c * step).
  const int rows = g.n_lat, cols = g.n_lon;
  std::vector<float> n_m(static_cast<std::size_t>(rows) * static_cast<std::size_t>(cols));
  std::vector<double> lon(static_cast<std::size_t>(cols)), z(static_cast<std::size_t>(cols));
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) lon[static_cast<std::size_t>(c)] = g.lowerleft.lam + c * g.cs_lon;
    std::fill(z.begin(), z.end(), 0.0);
    double lat = g.lowerleft.phi + r * g.cs_lat;
    const std::size_t n = proj_trans_generic(shift.get(), PJ_FWD, lon.data(), sizeof(double),
                                             static_cast<std::size_t>(cols), &lat, 0, 1, z.data(),
                                             sizeof(double), static_cast<std::size_t>(cols),
                                             nullptr, 0, 0);
    for (int c = 0; c < cols; ++c) {
      const double v = z[static_cast<std::size_t>(c)];
      // PROJ returns HUGE_VAL where the grid has no value (GTX nodata); a geoid has one
      // everywhere, within about +-110 m.
      if (n != static_cast<std::size_t>(cols) || !std::isfinite(v) || std::fabs(v) > 1000.0)
        return without_geoid(fmt::format("{} has no value at latitude {} deg, longitude {} deg",
                                         g.filename, -90.0 + r * step_deg, west_deg + c * step_deg));
      n_m[static_cast<std::size_t>(r * cols + c)] = static_cast<float>(v);
    }
  }

  LoadedGeoid out;
  out.grid.emplace(grid_name, west_deg, step_deg, rows, cols, std::move(n_m));
  out.description =
      fmt::format("heights above mean sea level: geoid grid {} ({}' grid, {}, read through PROJ {})",
                  grid_name, step_deg * 60.0, g.filename, info.version);
  return out;
}

const LoadedGeoid& egm96_geoid() {
  // Function-local static: initialised once, thread-safe (C++ [stmt.dcl]/3).
  static const LoadedGeoid geoid = load_geoid(kEgm96GridName);
  return geoid;
}

}  // namespace navemu
