// `navemu spp` on real RINEX files: accuracy against the stations' precise coordinates, and
// epoch-by-epoch agreement with RTKLIB's rnx2rtkp (Debian package rtklib) on the same files
// and settings (single point, GPS only, 15 deg mask, broadcast Klobuchar, Saastamoinen).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

#include "models/geodesy.hpp"
#include "tests/test_support.hpp"

namespace navemu {
namespace {

struct Station {
  const char* name;
  const char* obs;
  const char* nav;
  Vec3 truth_ecef_m;
  const char* systems = "G";  // navemu spp --systems
  int rtklib_navsys = 1;      // the same for RTKLIB's pos1-navsys (bit mask)
  double max_median_m = 0.3;  // median |navemu - rnx2rtkp|
};

// Truth from ../shared/data/README.md. ESBC: the marker plus the antenna height
// (0.2160 m along the ellipsoid normal) gives the antenna reference point SPP measures.
Vec3 esbc_arp() {
  const Vec3 marker(3582105.2910, 532589.7313, 5232754.8054);
  const Mat3 r = R_enu_from_ecef(geodetic_from_ecef(marker));
  return marker + r.row(2).transpose() * 0.2160;
}

// Test names and failure messages show the station's name.
void PrintTo(const Station& s, std::ostream* os) { *os << s.name; }

std::vector<Station> stations() {
  return {
      {"0759", "gnss/rtklib_geonet_20050402/07590920.05o",
       "gnss/rtklib_geonet_20050402/07590920.05n", Vec3(-3976219.1454, 3382371.6073, 3652511.1964)},
      {"3040", "gnss/rtklib_geonet_20050402/30400920.05o",
       "gnss/rtklib_geonet_20050402/30400920.05n", Vec3(-3978241.958, 3382840.234, 3649900.853)},
      {"ESBC", "gnss/esbc_20200625/ESBC00DNK_R_20201770000_01H_30S_MO.rnx",
       "gnss/esbc_20200625/ESBC00DNK_R_20201770000_01D_MN.rnx", esbc_arp()},
      // GPS + GLONASS + Galileo + BeiDou (RTKLIB: 1 + 4 + 8 + 32), the 5 cm.
      {"ESBCMultiGnss", "gnss/esbc_20200625/ESBC00DNK_R_20201770000_01H_30S_MO.rnx",
       "gnss/esbc_20200625/ESBC00DNK_R_20201770000_01D_MN.rnx", esbc_arp(), "G,R,E,C", 45, 0.05},
  };
}

// Epoch (time of week rounded to the second) -> ECEF position. RTKLIB tags its solutions with
// the receiver-clock-corrected time, navemu with the observation epoch; both round to the
// same second at these 30 s intervals (receiver clock offsets stay below 5 ms).
using Track = std::map<long long, Vec3>;

long long key_ms(double tow_s) { return std::llround(tow_s); }

// `sigma_enu`: when given, each epoch's reported 1-sigma east, north, up.
Track parse_navemu_csv(const std::string& csv, Track* sigma_enu = nullptr) {
  Track t;
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "time,lat_deg,lon_deg,h_m,x_m,y_m,z_m,clock_m,nsat,pdop,gps_week,gps_tow_s,sigma_e_m,"
                  "sigma_n_m,sigma_u_m");
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::istringstream ls(line);
    for (std::string x; std::getline(ls, x, ',');) f.push_back(x);
    if (f.size() != 15) continue;
    const long long k = key_ms(std::stod(f[11]));
    t[k] = Vec3(std::stod(f[4]), std::stod(f[5]), std::stod(f[6]));
    if (sigma_enu) (*sigma_enu)[k] = Vec3(std::stod(f[12]), std::stod(f[13]), std::stod(f[14]));
  }
  return t;
}

// rnx2rtkp -e output, keyed like navemu's.
Track parse_rtklib_pos(const std::filesystem::path& file) {
  Track t;
  for (const test::RtklibFix& fix : test::read_rtklib_ecef_pos(file))
    t[key_ms(fix.gps_tow_s)] = fix.p_ecef_m;
  return t;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

class SppRealData : public ::testing::TestWithParam<Station> {};

TEST_P(SppRealData, AccurateAndAgreesWithRtklib) {
  NAVEMU_REQUIRE_SHARED();
  const Station& st = GetParam();
  const auto obs = test::shared_data(st.obs);
  const auto nav = test::shared_data(st.nav);

  const auto ours = test::run_command(
      test::shell_quote(test::navemu_binary().string()) + " spp " + test::shell_quote(obs) + " " +
      test::shell_quote(nav) + " --mask 15 --iono klobuchar --tropo saastamoinen --systems " +
      st.systems + " 2>/dev/null");
  ASSERT_EQ(ours.exit_code, 0);
  Track sigma;
  const Track mine = parse_navemu_csv(ours.out, &sigma);
  ASSERT_GE(mine.size(), 100u) << st.name;

  // Accuracy against the precise station position; each component's error against the sigma
  // the fix reports (no fix more than 10 sigma off).
  const Geodetic truth_geo = geodetic_from_ecef(st.truth_ecef_m);
  double sum3d = 0.0, worst_ratio = 0.0;
  Vec3 sum_enu = Vec3::Zero();
  for (const auto& [k, p] : mine) {
    sum3d += (p - st.truth_ecef_m).norm();
    const Vec3 enu = enu_from_ecef(p, truth_geo);
    sum_enu += enu;
    worst_ratio = std::max(worst_ratio, enu.cwiseAbs().cwiseQuotient(sigma.at(k)).maxCoeff());
  }
  std::printf("%s: largest error / reported sigma of a component %.2f\n", st.name, worst_ratio);
  EXPECT_LE(worst_ratio, 10.0) << st.name;
  const double mean3d = sum3d / static_cast<double>(mine.size());
  const Vec3 mean_enu = sum_enu / static_cast<double>(mine.size());

  // RTKLIB on the same files and settings.
  const auto dir = std::filesystem::path(::testing::TempDir()) / (std::string("spp_") + st.name);
  std::filesystem::create_directories(dir);
  {
    std::ofstream conf(dir / "spp.conf");
    conf << "pos1-posmode=single\npos1-elmask=15\npos1-ionoopt=brdc\npos1-tropopt=saas\n"
            "pos1-navsys="
         << st.rtklib_navsys << "\n";
  }
  const auto pos = dir / "rtklib.pos";
  const auto rtk = test::run_command("rnx2rtkp -k " + test::shell_quote(dir / "spp.conf") +
                                     " -e -o " + test::shell_quote(pos) + " " +
                                     test::shell_quote(obs) + " " + test::shell_quote(nav) +
                                     " 2>/dev/null");
  ASSERT_EQ(rtk.exit_code, 0) << "rnx2rtkp (Debian package rtklib) missing or failed; "
                                 "tools/install-deps installs it";
  const Track theirs = parse_rtklib_pos(pos);
  ASSERT_GE(theirs.size(), 100u);

  std::vector<double> diffs;
  for (const auto& [k, p] : mine) {
    const auto it = theirs.find(k);
    if (it != theirs.end()) diffs.push_back((p - it->second).norm());
  }
  ASSERT_GE(diffs.size(), 100u);
  const double med = median(diffs);
  std::printf("%s: %zu epochs solved (RTKLIB %zu, common %zu); mean 3D error %.3f m, "
              "mean ENU (%.2f, %.2f, %.2f) m; median |navemu - rnx2rtkp| %.3f m, max %.3f m\n",
              st.name, mine.size(), theirs.size(), diffs.size(), mean3d, mean_enu.x(),
              mean_enu.y(), mean_enu.z(), med, *std::max_element(diffs.begin(), diffs.end()));
  EXPECT_LE(mean3d, 3.0);
  EXPECT_LE(med, st.max_median_m);
}

// Four systems solve better than GPS alone: 26 satellites instead of 7 (ESBC, 15 deg mask).
TEST(SppRealDataMultiGnss, BeatsGpsOnlyAtEsbc) {
  NAVEMU_REQUIRE_SHARED();
  const auto obs = test::shared_data("gnss/esbc_20200625/ESBC00DNK_R_20201770000_01H_30S_MO.rnx");
  const auto nav = test::shared_data("gnss/esbc_20200625/ESBC00DNK_R_20201770000_01D_MN.rnx");
  const Vec3 truth = esbc_arp();
  const auto log = std::filesystem::path(::testing::TempDir()) / "spp_multi_gnss.err";
  // The start-up line (stderr) and the mean 3D error of the solutions.
  const auto run = [&](const std::string& systems) {
    const auto r = test::run_command(test::shell_quote(test::navemu_binary().string()) + " spp " +
                                     test::shell_quote(obs) + " " + test::shell_quote(nav) +
                                     " --systems " + systems + " 2>" + test::shell_quote(log));
    EXPECT_EQ(r.exit_code, 0);
    std::ifstream err(log);
    std::string line;
    std::getline(err, line);
    const Track t = parse_navemu_csv(r.out);
    EXPECT_EQ(t.size(), 120u) << systems;
    double sum = 0.0;
    for (const auto& [k, p] : t) sum += (p - truth).norm();
    const double mean_m = sum / static_cast<double>(t.size());
    std::printf("--systems %s: %s; mean 3D error %.3f m\n", systems.c_str(), line.c_str(), mean_m);
    return std::make_pair(line, mean_m);
  };
  const auto [gps_line, gps_m] = run("G");
  const auto [all_line, all_m] = run("G,R,E,C,J");
  EXPECT_EQ(gps_line, "navemu spp: solving with GPS C1C");
  // QZSS types are declared in the header, but no QZSS satellite is in view in this hour.
  EXPECT_EQ(all_line,
            "navemu spp: solving with GPS C1C, GLONASS C1C, Galileo C1C, BeiDou C2I, QZSS C1C");
  EXPECT_LT(all_m, 0.75 * gps_m);
}

INSTANTIATE_TEST_SUITE_P(Stations, SppRealData, ::testing::ValuesIn(stations()),
                         [](const auto& param_info) { return std::string("Station") + param_info.param.name; });

}  // namespace
}  // namespace navemu
