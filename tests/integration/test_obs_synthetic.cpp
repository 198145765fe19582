// `navemu obs` end to end: byte-identical files for one seed, and RTKLIB's rnx2rtkp (Debian
// package rtklib) solving the synthetic RINEX within the expected error of the truth, in
// single-frequency (broadcast corrections) and dual-frequency (iono-free) processing.

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <vector>

#include "models/geodesy.hpp"
#include "tests/test_support.hpp"

namespace navemu {
namespace {

// Station 0759's precise position and its observation hour (../shared/data/README.md).
const Vec3 kTruth(-3976219.1454, 3382371.6073, 3652511.1964);
const char* kAt = "35.160866522,139.613842697,68.3892";
const char* kStart = "1316:518400";  // 2005-04-02 00:00:00 GPS

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::filesystem::path work_dir(const std::string& name) {
  const auto d = std::filesystem::path(::testing::TempDir()) / name;
  std::filesystem::create_directories(d);
  return d;
}

int navemu_obs(const std::filesystem::path& out, const std::string& extra) {
  const auto nav = test::shared_data("gnss/rtklib_geonet_20050402/07590920.05n");
  return test::run_command(test::shell_quote(test::navemu_binary()) + " obs --nav " +
                           test::shell_quote(nav) + " --at " + kAt + " --start " + kStart +
                           " --duration 3570 --interval 30 --out " + test::shell_quote(out) +
                           " " + extra + " 2>/dev/null")
      .exit_code;
}

// rnx2rtkp -e output: ECEF positions, one per solved epoch.
std::vector<Vec3> rtklib_positions(const std::filesystem::path& obs, const std::string& conf,
                                   const std::filesystem::path& dir) {
  std::ofstream(dir / "rtk.conf") << conf;
  const auto nav = test::shared_data("gnss/rtklib_geonet_20050402/07590920.05n");
  const auto pos = dir / "out.pos";
  const auto r = test::run_command("rnx2rtkp -k " + test::shell_quote(dir / "rtk.conf") +
                                   " -e -o " + test::shell_quote(pos) + " " +
                                   test::shell_quote(obs) + " " + test::shell_quote(nav) +
                                   " 2>/dev/null");
  EXPECT_EQ(r.exit_code, 0) << "rnx2rtkp (Debian package rtklib) missing or failed";
  std::vector<Vec3> out;
  for (const test::RtklibFix& fix : test::read_rtklib_ecef_pos(pos)) out.push_back(fix.p_ecef_m);
  return out;
}

double mean_error(const std::vector<Vec3>& ps) {
  double s = 0;
  for (const Vec3& p : ps) s += (p - kTruth).norm();
  return s / static_cast<double>(ps.size());
}

TEST(ObsSynthetic, SameSeedGivesByteIdenticalFiles) {
  NAVEMU_REQUIRE_SHARED();
  const auto dir = work_dir("obs_determinism");
  ASSERT_EQ(navemu_obs(dir / "a.rnx", "--seed 5"), 0);
  ASSERT_EQ(navemu_obs(dir / "b.rnx", "--seed 5"), 0);
  ASSERT_EQ(navemu_obs(dir / "c.rnx", "--seed 6"), 0);
  const std::string a = slurp(dir / "a.rnx");
  EXPECT_GT(a.size(), 50'000u);
  EXPECT_EQ(a, slurp(dir / "b.rnx"));
  EXPECT_NE(a, slurp(dir / "c.rnx"));
}

TEST(ObsSynthetic, RtklibSolvesSingleFrequencyFileWithinExpectedError) {
  NAVEMU_REQUIRE_SHARED();
  const auto dir = work_dir("obs_rtklib_single");
  ASSERT_EQ(navemu_obs(dir / "s.rnx", "--receiver geodetic --seed 2"), 0);
  const auto ps = rtklib_positions(dir / "s.rnx",
                                   "pos1-posmode=single\npos1-elmask=15\npos1-ionoopt=brdc\n"
                                   "pos1-tropopt=saas\npos1-navsys=1\n",
                                   dir);
  ASSERT_GE(ps.size(), 114u);  // >= 95 % of the 120 epochs
  const double err = mean_error(ps);
  std::printf("rnx2rtkp on synthetic single-frequency RINEX: %zu epochs, mean 3D error %.2f m\n",
              ps.size(), err);
  // Expected: the real receiver's single-point error at this station and hour (2.6 m).
  EXPECT_LT(err, 4.0);
  EXPECT_GT(err, 0.3);  // errors are really there
}

TEST(ObsSynthetic, RtklibSolvesDualFrequencyFileIonosphereFree) {
  NAVEMU_REQUIRE_SHARED();
  const auto dir = work_dir("obs_rtklib_dual");
  ASSERT_EQ(navemu_obs(dir / "d.rnx", "--mode dual --receiver geodetic --seed 2"), 0);
  const std::string text = slurp(dir / "d.rnx");
  EXPECT_NE(text.find("C2L"), std::string::npos);
  EXPECT_NE(text.find("C5Q"), std::string::npos);
  const auto ps = rtklib_positions(dir / "d.rnx",
                                   "pos1-posmode=single\npos1-elmask=15\npos1-ionoopt=dual-freq\n"
                                   "pos1-tropopt=saas\npos1-navsys=1\npos1-frequency=l1+l2\n",
                                   dir);
  ASSERT_GE(ps.size(), 114u);
  const double err = mean_error(ps);
  std::printf("rnx2rtkp iono-free on synthetic dual-frequency RINEX: %zu epochs, mean 3D error "
              "%.2f m\n",
              ps.size(), err);
  EXPECT_LT(err, 4.0);
}

TEST(ObsSynthetic, RealVersusSyntheticTableHoldsItsGround) {
  NAVEMU_REQUIRE_SHARED();
  // tools/real-vs-synthetic compares 21 figures (3 stations x 7); 16 are within a factor 1.5.
  // Two outside are the 60-90 deg residual spread at 0759 and 3040, where the real bin holds
  // only two satellites. Three are ESBC's: its real solution carries a persistent 2.6 m
  // northward bias. It is not ionospheric (an iono-free L1/L2 solution keeps 2.4 m); with the
  // precise SP3 orbits and clocks of ../shared/data it halves to 1.2 m, so about half is that
  // day's broadcast orbit/clock error and the rest code biases or the operator-supplied marker
  // coordinate: one particular draw, which the model's median over seeds does not (and should
  // not) copy.
  // The third is ESBC's residual spread in the 30-60 deg bin.
  const auto r = test::run_command(
      "python3 " + test::shell_quote(std::filesystem::path(NAVEMU_SOURCE_DIR) / "tools" /
                                     "real-vs-synthetic") +
      " --navemu " + test::shell_quote(test::navemu_binary()) + " --shared " +
      test::shell_quote(test::shared_dir()) + " --min-in-band 16 2>&1");
  std::printf("%s\n", r.out.c_str());
  EXPECT_EQ(r.exit_code, 0);
}

}  // namespace
}  // namespace navemu
