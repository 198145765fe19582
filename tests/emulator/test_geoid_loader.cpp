// The EGM96 geoid read through PROJ (emulator/geoid_loader.hpp): its undulations against the
// values NGA publishes with the model, its interpolation against PROJ's own, and what happens
// when the grid file is missing or damaged.

#include <gtest/gtest.h>
#include <proj.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <vector>

#include "emulator/geoid_loader.hpp"
#include "tests/nga_egm96.hpp"

namespace navemu {
namespace {

namespace fs = std::filesystem;

using test::kEgm96BilinearTolerance_m;
using test::kNgaEgm96TestPoints;

// proj-data, a dependency of libproj (tools/install-deps), installs the grid: its absence is
// a failure here.
TEST(GeoidLoader, Egm96MatchesNgaTestValues) {
  const LoadedGeoid& geoid = egm96_geoid();
  ASSERT_TRUE(geoid.grid) << geoid.description;
  const GeoidGrid& g = *geoid.grid;
  EXPECT_EQ(g.name(), kEgm96GridName);
  EXPECT_DOUBLE_EQ(g.step_deg(), 0.25);
  for (const test::NgaEgm96Point& p : kNgaEgm96TestPoints) {
    const double n = g.separation_m(p.lat_deg, p.lon_deg);
    std::printf("%12.7f %12.7f  NGA %8.3f m  grid %8.3f m  difference %+.3f m\n", p.lat_deg,
                p.lon_deg, p.n_m, n, n - p.n_m);
    EXPECT_NEAR(n, p.n_m, kEgm96BilinearTolerance_m) << p.lat_deg << ", " << p.lon_deg;
    // The same place with its longitude in [-180, 180).
    EXPECT_NEAR(g.separation_m(p.lat_deg, p.lon_deg - 360.0), p.n_m, kEgm96BilinearTolerance_m);
  }
  EXPECT_NE(geoid.description.find("/usr/share/proj/egm96_15.gtx"), std::string::npos)
      << geoid.description;
}

// Between the nodes the grid in memory gives what PROJ's vgridshift gives reading the file:
// random places over the globe, the grid's seam at 180 deg and the poles.
TEST(GeoidLoader, InterpolatesAsProjDoes) {
  const LoadedGeoid& geoid = egm96_geoid();
  ASSERT_TRUE(geoid.grid) << geoid.description;
  const GeoidGrid& g = *geoid.grid;
  PJ_CONTEXT* ctx = proj_context_create();
  PJ* shift = proj_create(ctx, "+proj=vgridshift +grids=egm96_15.gtx +multiplier=1");
  ASSERT_NE(shift, nullptr);
  std::mt19937_64 rng(19);
  std::uniform_real_distribution<double> lat(-90.0, 90.0), lon(-180.0, 180.0);
  std::vector<std::pair<double, double>> places = {{0.0, 179.9}, {0.0, -179.9}, {12.3, 179.99},
                                                   {90.0, 17.0}, {-90.0, -17.0}, {89.9, 0.1}};
  for (int i = 0; i < 20'000; ++i) places.emplace_back(lat(rng), lon(rng));
  double worst = 0.0;
  for (const auto& [la, lo] : places) {
    const PJ_COORD c = proj_trans(shift, PJ_FWD, proj_coord(lo * M_PI / 180.0, la * M_PI / 180.0, 0.0, 0.0));
    worst = std::max(worst, std::fabs(g.separation_m(la, lo) - c.xyz.z));
  }
  std::printf("grid in memory vs PROJ at %zu places: worst difference %.2e m\n", places.size(), worst);
  EXPECT_LT(worst, 1e-6);
  proj_destroy(shift);
  proj_context_destroy(ctx);
}

// A missing grid is not an error: the receiver reports separation 0 (MSL height = ellipsoidal
// height, still consistent: altitude + separation = h) and the start-up line says so, why,
// and how to install the grid.
TEST(GeoidLoader, MissingGridSaysWhatIsMissingAndTheConsequence) {
  const LoadedGeoid g = load_geoid("no_such_geoid.gtx");
  EXPECT_FALSE(g.grid);
  for (const char* part : {"warning: no geoid", "no_such_geoid.gtx not found in PROJ's search path",
                           "/usr/share/proj", "proj-data", "PROJ_DATA",
                           "heights above mean sea level equal ellipsoidal heights",
                           "separation 0"})
    EXPECT_NE(g.description.find(part), std::string::npos) << part << " in: " << g.description;
}

// A grid file cut short (a damaged download): its header promises 721 x 1440 nodes, the values
// end after three rows. PROJ reads the header; the loader names the first node without a value.
TEST(GeoidLoader, TruncatedGridIsRefusedNamingTheFirstMissingNode) {
  const fs::path cut = fs::temp_directory_path() / "navemu_truncated_egm96_15.gtx";
  {
    std::ifstream in("/usr/share/proj/egm96_15.gtx", std::ios::binary);
    std::vector<char> bytes(40 + 4 * 1440 * 3);  // header and three rows
    in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    ASSERT_TRUE(in) << "egm96_15.gtx (proj-data) not readable";
    std::ofstream(cut, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  }
  const LoadedGeoid g = load_geoid(cut.string());
  EXPECT_FALSE(g.grid);
  // The first node whose cell reaches past the end of the file: -89.5 or -89.25 deg
  // depending on how PROJ rounds a node's grid coordinate.
  EXPECT_NE(g.description.find(cut.string() + " has no value at latitude -89."), std::string::npos)
      << g.description;
  EXPECT_NE(g.description.find("separation 0"), std::string::npos);
  fs::remove(cut);
}

// Loading takes a fraction of a second (once per process, before the loop).
TEST(GeoidLoader, LoadsInUnderTwoSeconds) {
  const auto t0 = std::chrono::steady_clock::now();
  const LoadedGeoid g = load_geoid(kEgm96GridName);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("egm96_15.gtx loaded in %.3f s\n", s);
  EXPECT_TRUE(g.grid);
  EXPECT_LT(s, 2.0);  // loose: a shared, busy machine (about 0.15 s when idle)
}

}  // namespace
}  // namespace navemu
