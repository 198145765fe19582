// Heights above mean sea level end to end: the engine's receiver at the places NGA publishes
// EGM96 geoid heights for, its UBX NAV-PVT and NAV-POSLLH hMSL and its NMEA GGA altitude and
// geoid separation; and a run without the geoid grid.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

#include "emulator/engine.hpp"
#include "emulator/run_config.hpp"
#include "core/time.hpp"
#include "protocols/nmea.hpp"
#include "protocols/ubx.hpp"
#include "protocols/ubx_messages.hpp"
#include "tests/nga_egm96.hpp"
#include "tests/test_support.hpp"

namespace navemu {
namespace {

namespace fs = std::filesystem;

fs::path temp_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("navemu_geoid_" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// The GGA sentences of a byte stream (NMEA alone, or mixed with UBX frames).
std::vector<std::vector<std::string>> gga_sentences(const std::string& bytes) {
  std::vector<std::vector<std::string>> out;
  for (std::size_t i = bytes.find('$'); i != std::string::npos; i = bytes.find('$', i + 1)) {
    const std::size_t end = bytes.find('\n', i);
    if (end == std::string::npos) break;
    const auto f = nmea::parse(bytes.substr(i, end + 1 - i));
    if (f && (*f)[0].size() == 5 && (*f)[0].substr(2) == "GGA") out.push_back(*f);
  }
  return out;
}

using test::kEgm96BilinearTolerance_m;
using test::kNgaEgm96TestPoints;

// A u-blox F9P standing at each of NGA's EGM96 test points for 5 s, sending NAV-PVT, NAV-POSLLH and its NMEA.
// ellipsoidal height - hMSL is the geoid height there (the fix is within metres of the point;
// EGM96 changes by millimetres over that); GGA's altitude + separation is the ellipsoidal
// height, its separation the geoid height to GGA's 0.1 m.
TEST(GeoidHeights, UbxAndNmeaReportEgm96AtNgaTestPoints) {
  RunConfig cfg = load_run_config(fs::path(NAVEMU_SOURCE_DIR) / "configs" / "ublox-f9p.yaml");
  ASSERT_TRUE(cfg.gnss.ubx);
  cfg.gnss.ubx->messages = {{"NAV-PVT", 1}, {"NAV-POSLLH", 1}};
  cfg.imu_enabled = false;
  cfg.truth.kind = TruthSourceKind::kStationary;
  for (const test::NgaEgm96Point& p : kNgaEgm96TestPoints) {
    SCOPED_TRACE(testing::Message() << p.lat_deg << ", " << p.lon_deg);
    cfg.truth.position = Geodetic{p.lat_deg, p.lon_deg > 180.0 ? p.lon_deg - 360.0 : p.lon_deg, 100.0};
    const fs::path d = temp_dir("nga");
    EngineOptions opt;
    opt.realtime = false;
    opt.duration_s = 5.0;
    opt.out_dir = d;
    std::ostringstream log;
    const EngineSummary s = run_engine(cfg, parse_time("2010-11-17T13:00:00Z"), opt, log);
    ASSERT_GT(s.gnss_epochs, 0) << log.str();
    EXPECT_NE(log.str().find("heights above mean sea level: geoid grid egm96_15.gtx"), std::string::npos)
        << log.str();

    const std::string bytes = slurp(d / "ubx.bin");
    std::map<int, double> height_by_tow;  // NAV-PVT ellipsoidal height by iTOW, m
    int pvt = 0, posllh = 0;
    ubx::Parser parser;
    parser.feed(std::span(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()),
                [&](ubx::Parser::Result r) {
                  if (r != ubx::Parser::Result::kFrame) return;
                  const ubx::MsgId id{parser.cls(), parser.id()};
                  if (id == ubx::kNavPvt) {
                    ubx::NavPvt m;
                    ASSERT_TRUE(ubx::decode(parser.payload(), m));
                    if (!(m.flags & ubx::NavPvt::kGnssFixOk)) return;
                    ++pvt;
                    EXPECT_NEAR((m.height_mm - m.h_msl_mm) * 1e-3, p.n_m, kEgm96BilinearTolerance_m);
                    height_by_tow[static_cast<int>(m.i_tow_ms)] = m.height_mm * 1e-3;
                  } else if (id == ubx::kNavPosllh) {
                    ubx::NavPosllh m;
                    ASSERT_TRUE(ubx::decode(parser.payload(), m));
                    ++posllh;
                    EXPECT_NEAR((m.height_mm - m.h_msl_mm) * 1e-3, p.n_m, kEgm96BilinearTolerance_m);
                  }
                });
    EXPECT_GE(pvt, 4);
    EXPECT_GE(posllh, 4);

    const auto gga = gga_sentences(bytes);
    EXPECT_GE(gga.size(), 4u);
    for (const auto& f : gga) {
      ASSERT_EQ(f[6], "1") << "a fix";
      EXPECT_NEAR(std::stod(f[11]), p.n_m, kEgm96BilinearTolerance_m + 0.05);  // printed to 0.1 m
      EXPECT_GT(std::stod(f[9]) + std::stod(f[11]), 90.0);  // h = H + N: about 100 m again
      EXPECT_LT(std::stod(f[9]) + std::stod(f[11]), 110.0);
    }
    fs::remove_all(d);
  }
}

// Without the grid (PROJ finds no egm96_15.gtx: PROJ_DATA names an empty folder, and so does
// XDG_DATA_HOME, where PROJ's user folder lies) the run goes on, the start-up lines say what
// is missing and what it means, and GGA reports separation 0 and the ellipsoidal height.
TEST(GeoidHeights, WithoutTheGridMslHeightIsEllipsoidalAndTheStartUpSaysSo) {
  const fs::path d = temp_dir("missing");
  fs::create_directories(d / "empty");
  const std::string empty = test::shell_quote((d / "empty").string());
  const auto r = test::run_command(
      "PROJ_DATA=" + empty + " XDG_DATA_HOME=" + empty + " " +
      test::shell_quote(test::navemu_binary().string()) + " simulate " +
      test::shell_quote((fs::path(NAVEMU_SOURCE_DIR) / "configs" / "default.yaml").string()) +
      " --start 2010-11-17T13:00:00Z --duration 3 --out " + test::shell_quote((d / "out").string()) +
      " 2>&1");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("navemu: warning: no geoid: grid egm96_15.gtx not found in PROJ's search path"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("proj-data"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("heights above mean sea level equal ellipsoidal heights (geoid separation 0"),
            std::string::npos)
      << r.out;
  const auto gga = gga_sentences(slurp(d / "out" / "nmea.log"));
  ASSERT_EQ(gga.size(), 15u);  // 3 s at 5 Hz
  for (const auto& f : gga) {
    EXPECT_EQ(f[11], "0.0");
    // The default site's ellipsoidal height is 60 m; a standalone fix is within metres.
    EXPECT_NEAR(std::stod(f[9]), 60.0, 25.0);
  }
  fs::remove_all(d);
}

}  // namespace
}  // namespace navemu
