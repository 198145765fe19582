// RINEX navigation and observation readers (the choice among their records:
// tests/models/test_ephemeris.cpp).
// Reference values are copied from the text of the files in ../shared/data/gnss.

#include <gtest/gtest.h>

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <functional>
#include <iostream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "core/time.hpp"
#include "protocols/rinex.hpp"
#include "tests/rinex_data.hpp"
#include "tests/test_support.hpp"

namespace navemu {
namespace {

using test::expect_input_error;
using test::shared_data;

// A header line: content in columns 1-60, label from column 61.
std::string hdr(std::string content, const std::string& label) {
  content.resize(60, ' ');
  return content + label + "\n";
}

NavData nav_from(const std::string& text, const std::string& name = "mem.nav") {
  std::istringstream in(text);
  return parse_rinex_nav(in, name);
}

ObsData obs_from(const std::string& text, const std::string& name = "mem.obs") {
  std::istringstream in(text);
  return parse_rinex_obs(in, name);
}

GpsTime gps(int y, int mo, int d, int h, int mi, double s) {
  return gps_from_calendar(CalendarTime{y, mo, d, h, mi, s});
}

// ---------------------------------------------------------------------------------------------
// Navigation files: reference data

TEST(RinexNav, Geonet0759Rinex210) {
  NAVEMU_REQUIRE_SHARED();
  const auto file = shared_data("gnss/rtklib_geonet_20050402/07590920.05n");
  const NavData nav = test::rinex_nav_file(file);
  EXPECT_DOUBLE_EQ(nav.rinex_version, 2.10);
  EXPECT_EQ(nav.source, file.string());
  ASSERT_EQ(nav.gps.size(), 162u);
  EXPECT_EQ(nav.skipped_records, 0);
  // DELTA-UTC gives W = 1061 in GPS week 1316: the broadcast 8 bits (37) of week 1317.
  ASSERT_EQ(nav.time_offsets.size(), 1u);
  EXPECT_EQ(nav.time_offsets[0].type, "GPUT");
  EXPECT_DOUBLE_EQ(nav.time_offsets[0].a0_s, -2.793967723850E-09);
  EXPECT_EQ(nav.time_offsets[0].t_ref, from_week_tow(1317, 61440.0));
  ASSERT_TRUE(nav.leap_seconds.has_value());
  EXPECT_EQ(*nav.leap_seconds, 13);

  ASSERT_TRUE(nav.klobuchar.has_value());
  const std::array<double, 4> alpha{1.1180e-08, 1.4900e-08, -5.9600e-08, -5.9600e-08};
  const std::array<double, 4> beta{8.8060e+04, 1.6380e+04, -1.9660e+05, -1.3110e+05};
  for (std::size_t k = 0; k < 4; ++k) {
    EXPECT_DOUBLE_EQ(nav.klobuchar->alpha[k], alpha[k]);
    EXPECT_DOUBLE_EQ(nav.klobuchar->beta[k], beta[k]);
  }

  // " 1 05  4  2  2  0  0.0 3.966595977540D-04 1.705302565820D-12 0.000000000000D+00"
  const GpsEphemeris& e = nav.gps.front();
  EXPECT_EQ(e.sat.number(), 1);
  EXPECT_EQ(e.toc, gps(2005, 4, 2, 2, 0, 0.0));
  EXPECT_DOUBLE_EQ(e.af0_s, 3.966595977540e-04);
  EXPECT_DOUBLE_EQ(e.af1_sps, 1.705302565820e-12);
  EXPECT_DOUBLE_EQ(e.af2_sps2, 0.0);
  EXPECT_EQ(e.iode, 140);
  EXPECT_DOUBLE_EQ(e.crs_m, -5.218750000000e+01);
  EXPECT_DOUBLE_EQ(e.delta_n_radps, 4.026596389650e-09);
  EXPECT_DOUBLE_EQ(e.m0_rad, 2.871534990340e+00);
  EXPECT_DOUBLE_EQ(e.cuc_rad, -2.676621079440e-06);
  EXPECT_DOUBLE_EQ(e.e, 5.957618006510e-03);
  EXPECT_DOUBLE_EQ(e.cus_rad, 4.174187779430e-06);
  EXPECT_DOUBLE_EQ(e.sqrt_a_sqrtm, 5.153636478420e+03);
  EXPECT_EQ(e.toe, from_week_tow(1316, 5.256e5));
  EXPECT_EQ(to_week_tow(e.toe).week, 1316);
  EXPECT_DOUBLE_EQ(to_week_tow(e.toe).tow_s, 525600.0);
  EXPECT_DOUBLE_EQ(e.cic_rad, 1.061707735060e-07);
  EXPECT_DOUBLE_EQ(e.omega0_rad, -2.493184817740e+00);
  EXPECT_DOUBLE_EQ(e.cis_rad, -9.313225746150e-08);
  EXPECT_DOUBLE_EQ(e.i0_rad, 9.833919144490e-01);
  EXPECT_DOUBLE_EQ(e.crc_m, 3.093750000000e+02);
  EXPECT_DOUBLE_EQ(e.omega_rad, -1.650496813270e+00);
  EXPECT_DOUBLE_EQ(e.omega_dot_radps, -7.889971342930e-09);
  EXPECT_DOUBLE_EQ(e.idot_radps, -8.571785642400e-12);
  EXPECT_EQ(e.codes_on_l2, 1);
  EXPECT_EQ(e.l2p_data_flag, 0);
  EXPECT_DOUBLE_EQ(e.ura_m, 1.0);
  EXPECT_EQ(e.health, 0);
  EXPECT_DOUBLE_EQ(e.tgd_s, -3.259629011150e-09);
  EXPECT_EQ(e.iodc, 396);
  EXPECT_DOUBLE_EQ(e.transmission_tow_s, 5.195760000000e+05);
  EXPECT_DOUBLE_EQ(e.fit_interval_h, 4.0);  // blank in the file
  EXPECT_EQ(e.source, file.string() + ":13");

  // Second and third records: PRN 3 at 00:00 and 02:00 (file order kept).
  EXPECT_EQ(nav.gps[1].sat.number(), 3);
  EXPECT_EQ(nav.gps[1].toc, gps(2005, 4, 2, 0, 0, 0.0));
  EXPECT_EQ(nav.gps[2].sat.number(), 3);
  EXPECT_EQ(nav.gps[2].iode, 84);
  EXPECT_EQ(nav.gps[2].source, file.string() + ":29");
}

TEST(RinexNav, Geonet3040Rinex210) {
  NAVEMU_REQUIRE_SHARED();
  const NavData nav = test::rinex_nav_file(shared_data("gnss/rtklib_geonet_20050402/30400920.05n"));
  EXPECT_EQ(nav.gps.size(), 164u);
  EXPECT_EQ(nav.leap_seconds, 13);
  EXPECT_TRUE(nav.klobuchar.has_value());
  for (const auto& e : nav.gps) {
    EXPECT_GE(e.sat.number(), 1);
    EXPECT_LE(e.sat.number(), 32);
    EXPECT_NEAR(e.sqrt_a_sqrtm, 5153.6, 1.0);
    EXPECT_LT(std::fabs(seconds_between(e.toe, e.toc)), 7200.0 + 1.0);
  }
}

TEST(RinexNav, EsbcMixedRinex305) {
  NAVEMU_REQUIRE_SHARED();
  const auto file = shared_data("gnss/esbc_20200625/ESBC00DNK_R_20201770000_01D_MN.rnx");
  const NavData nav = test::rinex_nav_file(file);
  EXPECT_DOUBLE_EQ(nav.rinex_version, 3.05);
  ASSERT_EQ(nav.gps.size(), 257u);
  ASSERT_EQ(nav.galileo.size(), 1602u);
  ASSERT_EQ(nav.beidou.size(), 357u);
  ASSERT_EQ(nav.qzss.size(), 15u);
  ASSERT_EQ(nav.glonass.size(), 510u);
  EXPECT_EQ(nav.skipped_records, 2130);  // SBAS
  // The header's NeQuick G coefficients and its GAGP, GAUT and GPUT.
  ASSERT_TRUE(nav.nequick_g.has_value());
  EXPECT_DOUBLE_EQ((*nav.nequick_g)[0], 2.8250e+01);
  EXPECT_DOUBLE_EQ((*nav.nequick_g)[2], 1.0071e-02);
  ASSERT_EQ(nav.time_offsets.size(), 3u);
  const TimeSystemOffset* ggto = nav.time_offset("GAGP", from_week_tow(2111, 345600.0));
  ASSERT_NE(ggto, nullptr);
  EXPECT_DOUBLE_EQ(ggto->a0_s, 2.3574102670E-09);
  EXPECT_DOUBLE_EQ(ggto->a1_sps, 3.996802889E-15);
  EXPECT_EQ(ggto->t_ref, from_week_tow(2111, 345600.0));
  EXPECT_EQ(nav.leap_seconds, 18);
  ASSERT_TRUE(nav.klobuchar.has_value());
  EXPECT_DOUBLE_EQ(nav.klobuchar->alpha[0], 4.6566e-09);
  EXPECT_DOUBLE_EQ(nav.klobuchar->alpha[3], -1.1921e-07);
  EXPECT_DOUBLE_EQ(nav.klobuchar->beta[0], 8.1920e+04);
  EXPECT_DOUBLE_EQ(nav.klobuchar->beta[3], -5.2429e+05);

  // "G01 2020 06 25 04 00 00 1.604342833161e-05 7.048583938740e-12 0.000000000000e+00"
  const GpsEphemeris& e = nav.gps.front();
  EXPECT_EQ(e.sat.number(), 1);
  EXPECT_EQ(e.toc, gps(2020, 6, 25, 4, 0, 0.0));
  EXPECT_DOUBLE_EQ(e.af0_s, 1.604342833161e-05);
  EXPECT_EQ(e.iode, 58);
  EXPECT_DOUBLE_EQ(e.e, 1.000394229777e-02);
  EXPECT_DOUBLE_EQ(e.sqrt_a_sqrtm, 5.153707128525e+03);
  EXPECT_EQ(to_week_tow(e.toe).week, 2111);
  EXPECT_DOUBLE_EQ(to_week_tow(e.toe).tow_s, 360000.0);
  EXPECT_EQ(e.iodc, 58);
  EXPECT_DOUBLE_EQ(e.transmission_tow_s, 356106.0);
  EXPECT_DOUBLE_EQ(e.fit_interval_h, 4.0);
  EXPECT_EQ(e.source, file.string() + ":15880");

  std::set<int> prns;
  for (const auto& g : nav.gps) prns.insert(g.sat.number());
  EXPECT_GE(prns.size(), 30u);

  // The file's first Galileo record (line 3064), in GST, which RINEX gives on GPS's weeks:
  // "E01 2020 06 24 23 30 00-8.846927667037e-04-7.972289495228e-12 0.000000000000e+00".
  const GalileoEphemeris& gal = nav.galileo.front();
  EXPECT_TRUE(gal.sat == SatId(GnssSystem::kGalileo, 1));
  EXPECT_EQ(gal.toc, gps(2020, 6, 24, 23, 30, 0.0));
  EXPECT_DOUBLE_EQ(gal.af0_s, -8.846927667037e-04);
  EXPECT_EQ(gal.iod_nav, 61);
  EXPECT_EQ(gal.toe, from_week_tow(2111, 343800.0));
  EXPECT_EQ(gal.data_sources, 258);  // F/NAV E5a-I, E5a clock
  EXPECT_DOUBLE_EQ(gal.sisa_m, 3.12);
  EXPECT_DOUBLE_EQ(gal.bgd_e1e5a_s, -1.862645149231e-09);
  EXPECT_DOUBLE_EQ(gal.transmission_tow_s, 344540.0);
  EXPECT_EQ(gal.source, file.string() + ":3064");
  // The first BeiDou record (line 208), a GEO: epoch and toe in BDT (GPS time - 14 s) on BDT's
  // weeks (week 0 = GPS week 1356): "C05 2020 06 24 22 00 00", toe 338400 s of BDT week 755.
  const BeidouEphemeris& bds = nav.beidou.front();
  EXPECT_TRUE(bds.sat == SatId(GnssSystem::kBeidou, 5));
  EXPECT_EQ(bds.toc, gps(2020, 6, 24, 22, 0, 14.0));
  EXPECT_EQ(bds.toe, from_week_tow(2111, 338414.0));
  EXPECT_EQ(bds.aode, 1);
  EXPECT_EQ(bds.aodc, 0);
  EXPECT_DOUBLE_EQ(bds.ura_m, 2.0);
  EXPECT_DOUBLE_EQ(bds.tgd1_s, 1.0e-10);
  EXPECT_DOUBLE_EQ(bds.tgd2_s, -9.3e-09);
  // The first QZSS record (line 17936): "J01 2020 06 25 11 00 00", IODC 969, fit flag 0 (2 h).
  const GpsEphemeris& qzs = nav.qzss.front();
  EXPECT_TRUE(qzs.sat == SatId(GnssSystem::kQzss, 1));
  EXPECT_EQ(qzs.toc, gps(2020, 6, 25, 11, 0, 0.0));
  EXPECT_EQ(qzs.toe, from_week_tow(2111, 385200.0));
  EXPECT_EQ(qzs.iodc, 969);
  EXPECT_EQ(qzs.codes_on_l2, 2);
  EXPECT_DOUBLE_EQ(qzs.fit_interval_h, 2.0);
  // The first GLONASS record (line 18056), tb in UTC (GPS time - 18 s), km and km/s:
  // "R01 2020 06 24 23 15 00 6.355904042721e-05 0.000000000000e+00 3.420000000000e+05".
  const GlonassEphemeris& glo = nav.glonass.front();
  EXPECT_TRUE(glo.sat == SatId(GnssSystem::kGlonass, 1));
  EXPECT_EQ(glo.tb, gps(2020, 6, 24, 23, 15, 18.0));
  EXPECT_DOUBLE_EQ(glo.tau_n_s, -6.355904042721e-05);
  EXPECT_DOUBLE_EQ(glo.frame_time_s, 342000.0);
  EXPECT_DOUBLE_EQ(glo.p_pz90_m.x(), 1.090894238281e+07);
  EXPECT_DOUBLE_EQ(glo.v_pz90_mps.y(), 2.795855522156e+03);
  EXPECT_DOUBLE_EQ(glo.a_pz90_mps2.z(), -2.793967723846e-06);
  EXPECT_EQ(glo.health, 0);
  EXPECT_EQ(glo.frequency_channel, 1);
  EXPECT_EQ(glo.source, file.string() + ":18056");
}

TEST(RinexNav, SpirentRinex304) {
  NAVEMU_REQUIRE_SHARED();
  const NavData nav = test::rinex_nav_file(shared_data("gnss/spirent_simgen_static_20230108/Spirent_RINEX_GN.23N"));
  EXPECT_DOUBLE_EQ(nav.rinex_version, 3.04);
  EXPECT_EQ(nav.gps.size(), 93u);
  EXPECT_EQ(nav.skipped_records, 0);
  EXPECT_EQ(nav.leap_seconds, 18);
  ASSERT_TRUE(nav.klobuchar.has_value());
  const std::array<double, 4> alpha{2.4214e-08, 7.4506e-09, -1.1921e-07, 5.9605e-08};
  const std::array<double, 4> beta{1.4746e+05, -1.9661e+05, 0.0, 2.6214e+05};
  for (std::size_t k = 0; k < 4; ++k) {
    EXPECT_DOUBLE_EQ(nav.klobuchar->alpha[k], alpha[k]);
    EXPECT_DOUBLE_EQ(nav.klobuchar->beta[k], beta[k]);
  }
  const GpsEphemeris& e = nav.gps.front();
  EXPECT_EQ(e.sat.number(), 1);
  EXPECT_EQ(e.toc, gps(2023, 1, 8, 10, 0, 0.0));
  EXPECT_DOUBLE_EQ(e.af0_s, 2.270801778650e-04);
  EXPECT_DOUBLE_EQ(e.af1_sps, -4.774847184308e-12);
  EXPECT_DOUBLE_EQ(e.sqrt_a_sqrtm, 5.153651281357e+03);
  EXPECT_DOUBLE_EQ(e.e, 1.217794988770e-02);
  EXPECT_EQ(e.toe, from_week_tow(2244, 36000.0));
  EXPECT_DOUBLE_EQ(e.ura_m, 1.2);
  EXPECT_DOUBLE_EQ(e.fit_interval_h, 4.0);
}

TEST(RinexNav, ParsesLargeFilesQuickly) {
  NAVEMU_REQUIRE_SHARED();
  using clock = std::chrono::steady_clock;
  auto t0 = clock::now();
  const NavData nav = test::rinex_nav_file(shared_data("gnss/esbc_20200625/ESBC00DNK_R_20201770000_01D_MN.rnx"));
  auto t1 = clock::now();
  const ObsData obs =
      test::rinex_obs_file(shared_data("gnss/esbc_20200625/ESBC00DNK_R_20201770000_01H_30S_MO.rnx"));
  auto t2 = clock::now();
  const double nav_ms = std::chrono::duration<double, std::milli>(t1 - t0).count();
  const double obs_ms = std::chrono::duration<double, std::milli>(t2 - t1).count();
  std::cout << fmt::format("[ timing   ] ESBC nav (2.3 MB): {:.1f} ms, ESBC obs (1.3 MB): {:.1f} ms\n",
                           nav_ms, obs_ms);
  EXPECT_EQ(nav.gps.size(), 257u);
  EXPECT_EQ(obs.epochs.size(), 120u);
  // Generous bound so that Debug and sanitizer builds pass; Release is far below.
  EXPECT_LT(nav_ms + obs_ms, 10000.0);
}

// ---------------------------------------------------------------------------------------------
// Navigation files: inline snippets

// RINEX 2.10 header and the first record of 07590920.05n (lines 6-13).
std::string nav_v2_header() {
  return hdr("     2.10           N: GPS NAV DATA", "RINEX VERSION / TYPE") +
         hdr("    1.1180D-08  1.4900D-08 -5.9600D-08 -5.9600D-08", "ION ALPHA") +
         hdr("    8.8060D+04  1.6380D+04 -1.9660D+05 -1.3110D+05", "ION BETA") +
         hdr("    13", "LEAP SECONDS") + hdr("", "END OF HEADER");
}

const char* const kNavV2Record =
    " 1 05  4  2  2  0  0.0 3.966595977540D-04 1.705302565820D-12 0.000000000000D+00\n"
    "    1.400000000000D+02-5.218750000000D+01 4.026596389650D-09 2.871534990340D+00\n"
    "   -2.676621079440D-06 5.957618006510D-03 4.174187779430D-06 5.153636478420D+03\n"
    "    5.256000000000D+05 1.061707735060D-07-2.493184817740D+00-9.313225746150D-08\n"
    "    9.833919144490D-01 3.093750000000D+02-1.650496813270D+00-7.889971342930D-09\n"
    "   -8.571785642400D-12 1.000000000000D+00 1.316000000000D+03 0.000000000000D+00\n"
    "    1.000000000000D+00 0.000000000000D+00-3.259629011150D-09 3.960000000000D+02\n"
    "    5.195760000000D+05\n";

std::string replace(std::string s, const std::string& from, const std::string& to) {
  const auto pos = s.find(from);
  EXPECT_NE(pos, std::string::npos) << from;
  if (pos != std::string::npos) s.replace(pos, from.size(), to);
  return s;
}

// The G01 record of Spirent_RINEX_GN.23N in RINEX 3/4 layout.
const char* const kNavV3G01 =
    "G01 2023 01 08 10 00 00 2.270801778650E-04-4.774847184308E-12 0.000000000000E+00\n"
    "     4.800000000000E+01 4.684375000000E+01 4.114099940205E-09-9.548443013955E-01\n"
    "     2.561137080193E-06 1.217794988770E-02 1.572072505951E-06 5.153651281357E+03\n"
    "     3.600000000000E+04 9.685754776001E-08-1.509330417236E+00 2.831220626831E-07\n"
    "     9.889932931861E-01 3.624375000000E+02 9.377089341753E-01-8.193912737927E-09\n"
    "     2.285809498855E-11 1.000000000000E+00 2.244000000000E+03 0.000000000000E+00\n"
    "     1.200000000000E+00 0.000000000000E+00 4.656612873077E-09 4.800000000000E+01\n"
    "     3.600000000000E+04 4.000000000000E+00\n";

TEST(RinexNav, Rinex210SnippetParses) {
  const NavData nav = nav_from(nav_v2_header() + kNavV2Record, "snippet.05n");
  ASSERT_EQ(nav.gps.size(), 1u);
  EXPECT_EQ(nav.gps[0].source, "snippet.05n:6");
  EXPECT_DOUBLE_EQ(nav.gps[0].sqrt_a_sqrtm, 5.153636478420e+03);
}

TEST(RinexNav, CrLfLineEndings) {
  std::string text = nav_v2_header() + kNavV2Record;
  std::string crlf;
  for (const char c : text) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  const NavData nav = nav_from(crlf);
  ASSERT_EQ(nav.gps.size(), 1u);
  EXPECT_DOUBLE_EQ(nav.gps[0].transmission_tow_s, 519576.0);
  EXPECT_EQ(nav.leap_seconds, 13);
}

TEST(RinexNav, KeepsRecordsSharingAnIode) {
  const std::string again = replace(kNavV2Record, "5.195760000000D+05", "5.199360000000D+05");
  const NavData nav = nav_from(nav_v2_header() + kNavV2Record + again);
  ASSERT_EQ(nav.gps.size(), 2u);
  EXPECT_EQ(nav.gps[0].iode, nav.gps[1].iode);
  EXPECT_EQ(nav.gps[1].source, "mem.nav:14");
  EXPECT_DOUBLE_EQ(nav.gps[1].transmission_tow_s, 519936.0);
}

TEST(RinexNav, ModuloWeekIsResolvedAgainstToc) {
  // Week 292 = 1316 - 1024 (a writer that ignored the continuous-week rule).
  const NavData nav =
      nav_from(nav_v2_header() + replace(kNavV2Record, "1.316000000000D+03", "2.920000000000D+02"));
  ASSERT_EQ(nav.gps.size(), 1u);
  EXPECT_EQ(nav.gps[0].toe, from_week_tow(1316, 525600.0));
}

TEST(RinexNav, Rinex3GpsFileWithFitInterval) {
  const std::string text = hdr("     3.04           N: GNSS NAV DATA    G: GPS", "RINEX VERSION / TYPE") +
                           hdr("GPSA   2.4214D-08  7.4506D-09 -1.1921D-07  5.9605D-08", "IONOSPHERIC CORR") +
                           hdr("", "END OF HEADER") + kNavV3G01;
  const NavData nav = nav_from(text);
  ASSERT_EQ(nav.gps.size(), 1u);
  EXPECT_FALSE(nav.klobuchar.has_value());  // GPSB missing: no usable set
  EXPECT_DOUBLE_EQ(nav.gps[0].m0_rad, -9.548443013955E-01);
  EXPECT_EQ(nav.gps[0].source, "mem.nav:4");
}

TEST(RinexNav, Rinex4SnippetParses) {
  const std::string g02 = replace(kNavV3G01, "G01 2023", "G02 2023");
  const std::string text =
      hdr("     4.00           NAVIGATION DATA     M: MIXED", "RINEX VERSION / TYPE") +
      hdr("    18    18  2185     7", "LEAP SECONDS") + hdr("", "END OF HEADER") +
      "> EPH G01 LNAV\n" + kNavV3G01 +
      "> EPH E11 INAV\n"
      "E11 2023 01 08 10 00 00-6.069173011929E-04-7.915925436828E-12 0.000000000000E+00\n"
      "     1.200000000000E+01 1.046875000000E+01 3.039055206883E-09 6.651563429348E-01\n"
      "     4.600733518600E-07 1.537999557331E-04 3.682449460030E-06 5.440617427826E+03\n"
      "     3.600000000000E+04 1.862645149231E-08-1.455893218330E+00-2.235174179077E-08\n"
      "     9.795183446102E-01 2.758125000000E+02-4.209044012085E-01-5.754166531633E-09\n"
      "    -1.414344916519E-10 5.170000000000E+02 2.244000000000E+03\n"
      "     3.120000000000E+00 0.000000000000E+00-1.396983861923E-09-1.629814505577E-09\n"
      "     3.670400000000E+04\n"
      "> STO G01 LNAV\n"
      "    2023 01 08 09 59 42 GPUT        UTC(USNO)\n"
      "     3.600000000000E+04 5.587935447693E-09 0.000000000000E+00 0.000000000000E+00\n"
      "> ION G01 LNAV\n"
      "    2023 01 08 09 59 42 2.421438694000E-08 7.450580596924E-09-1.192092895508E-07\n"
      "     5.960464477539E-08 1.474560000000E+05-1.966080000000E+05 0.000000000000E+00\n"
      "     2.621440000000E+05\n"
      "> EPH G03 CNAV\n"
      "G03 2023 01 08 10 00 00-3.733077537617E-04 1.932676241267E-12 0.000000000000E+00\n"
      "     0.000000000000E+00 0.000000000000E+00 0.000000000000E+00 0.000000000000E+00\n"
      "> EPH G02 LNAV\n" +
      g02;
  const NavData nav = nav_from(text, "v4.rnx");
  EXPECT_DOUBLE_EQ(nav.rinex_version, 4.00);
  EXPECT_EQ(nav.leap_seconds, 18);
  ASSERT_EQ(nav.gps.size(), 2u);
  EXPECT_EQ(nav.gps[0].sat.number(), 1);
  EXPECT_EQ(nav.gps[0].source, "v4.rnx:4");  // the "> EPH G01 LNAV" line
  EXPECT_DOUBLE_EQ(nav.gps[0].sqrt_a_sqrtm, 5.153651281357E+03);
  EXPECT_EQ(nav.gps[0].toe, from_week_tow(2244, 36000.0));
  EXPECT_EQ(nav.gps[1].sat.number(), 2);
  ASSERT_EQ(nav.galileo.size(), 1u);  // E11 INAV, in the RINEX 3 layout
  EXPECT_EQ(nav.galileo[0].source, "v4.rnx:13");  // its "> EPH E11 INAV" line
  EXPECT_EQ(nav.galileo[0].iod_nav, 12);
  EXPECT_EQ(nav.galileo[0].data_sources, 517);
  EXPECT_EQ(nav.skipped_records, 2);  // ION, G03 CNAV
  // The STO record: GPS - UTC(USNO) referred to its epoch (GPS time for a GPS satellite).
  ASSERT_EQ(nav.time_offsets.size(), 1u);
  const TimeSystemOffset& sto = nav.time_offsets[0];
  EXPECT_EQ(sto.type, "GPUT");
  EXPECT_DOUBLE_EQ(sto.a0_s, 5.587935447693E-09);
  EXPECT_EQ(sto.t_ref, gps(2023, 1, 8, 9, 59, 42.0));
  EXPECT_EQ(nav.time_offset("GPUT", sto.t_ref), &sto);
  EXPECT_EQ(nav.time_offset("GAGP", sto.t_ref), nullptr);
  // The GPS LNAV ION record carries the Klobuchar coefficients.
  ASSERT_TRUE(nav.klobuchar.has_value());
  EXPECT_DOUBLE_EQ(nav.klobuchar->alpha[0], 2.421438694000E-08);
  EXPECT_DOUBLE_EQ(nav.klobuchar->alpha[2], -1.192092895508E-07);
  EXPECT_DOUBLE_EQ(nav.klobuchar->alpha[3], 5.960464477539E-08);
  EXPECT_DOUBLE_EQ(nav.klobuchar->beta[0], 1.474560000000E+05);
  EXPECT_DOUBLE_EQ(nav.klobuchar->beta[2], 0.0);
  EXPECT_DOUBLE_EQ(nav.klobuchar->beta[3], 2.621440000000E+05);
}

// A RINEX 2.11 GLONASS navigation file (Tables A10, A11): the ESBC file's first R01 record in
// the RINEX 2 layout reads as the RINEX 3 record does (tb in UTC with the header's leap
// seconds, km to m, -TauN, frequency number).
TEST(RinexNav, Rinex211GlonassFile) {
  const std::string v2 = hdr("     2.11           G: GLONASS NAV DATA", "RINEX VERSION / TYPE") +
                         hdr("  2020     6    24   -1.862645149231D-09", "CORR TO SYSTEM TIME") +
                         hdr("    18", "LEAP SECONDS") + hdr("", "END OF HEADER") +
                         " 1 20  6 24 23 15  0.0 6.355904042721D-05 0.000000000000D+00 3.420000000000D+05\n"
                         "    1.090894238281D+04 1.407806396484D+00-1.862645149231D-09 0.000000000000D+00\n"
                         "   -2.885726074219D+03 2.795855522156D+00-0.000000000000D+00 1.000000000000D+00\n"
                         "    2.288353955078D+04-3.169984817505D-01-2.793967723846D-09 0.000000000000D+00\n";
  const std::string v3 = hdr("     3.05           N: GNSS NAV DATA    R: GLONASS", "RINEX VERSION / TYPE") +
                         hdr("    18", "LEAP SECONDS") + hdr("", "END OF HEADER") +
                         "R01 2020 06 24 23 15 00 6.355904042721e-05 0.000000000000e+00 3.420000000000e+05\n"
                         "     1.090894238281e+04 1.407806396484e+00-1.862645149231e-09 0.000000000000e+00\n"
                         "    -2.885726074219e+03 2.795855522156e+00-0.000000000000e+00 1.000000000000e+00\n"
                         "     2.288353955078e+04-3.169984817505e-01-2.793967723846e-09 0.000000000000e+00\n"
                         "                         .999999999999e+09 1.500000000000e+01\n";
  const NavData a = nav_from(v2, "esbc.20g"), b = nav_from(v3, "esbc.rnx");
  ASSERT_EQ(a.glonass.size(), 1u);
  ASSERT_EQ(b.glonass.size(), 1u);
  // CORR TO SYSTEM TIME: -TauC, i.e. GLONASST - UTC(SU), from the reference date.
  ASSERT_EQ(a.time_offsets.size(), 1u);
  EXPECT_EQ(a.time_offsets[0].type, "GLUT");
  EXPECT_DOUBLE_EQ(a.time_offsets[0].a0_s, -1.862645149231E-09);
  EXPECT_EQ(a.time_offsets[0].t_ref, gps(2020, 6, 24, 0, 0, 0.0));
  const GlonassEphemeris &x = a.glonass[0], &y = b.glonass[0];
  EXPECT_TRUE(x.sat == y.sat);
  EXPECT_EQ(x.tb, gps(2020, 6, 24, 23, 15, 18.0));
  EXPECT_EQ(x.tb, y.tb);
  EXPECT_DOUBLE_EQ(x.tau_n_s, y.tau_n_s);
  EXPECT_DOUBLE_EQ(x.frame_time_s, y.frame_time_s);
  EXPECT_EQ(x.p_pz90_m, y.p_pz90_m);
  EXPECT_EQ(x.v_pz90_mps, y.v_pz90_mps);
  EXPECT_EQ(x.a_pz90_mps2, y.a_pz90_mps2);
  EXPECT_EQ(x.frequency_channel, 1);
  EXPECT_EQ(x.source, "esbc.20g:5");
}

// ---------------------------------------------------------------------------------------------
// Navigation files: bad input

TEST(RinexNavErrors, EmptyAndNotRinex) {
  expect_input_error([] { (void)nav_from(""); }, 1, "RINEX VERSION / TYPE");
  expect_input_error([] { (void)nav_from("hello world\n"); }, 1, "RINEX VERSION / TYPE");
}

TEST(RinexNavErrors, UnsupportedVersionOrType) {
  expect_input_error([] { (void)nav_from(hdr("     5.00           N", "RINEX VERSION / TYPE")); }, 1,
                     "version");
  expect_input_error([] { (void)nav_from(hdr("     1.00           N", "RINEX VERSION / TYPE")); }, 1,
                     "version");
  expect_input_error([] { (void)nav_from(hdr("     x.10           N", "RINEX VERSION / TYPE")); }, 1,
                     "version");
  expect_input_error(
      [] { (void)nav_from(hdr("     2.10           H: GEO NAV MSG DATA", "RINEX VERSION / TYPE")); }, 1,
      "file type");
  expect_input_error(
      [] { (void)nav_from(hdr("     3.05           OBSERVATION DATA    M", "RINEX VERSION / TYPE")); },
      1, "file type");
}

TEST(RinexNavErrors, MissingEndOfHeader) {
  expect_input_error(
      [] {
        (void)nav_from(hdr("     2.10           N: GPS NAV DATA", "RINEX VERSION / TYPE") +
                       hdr("    13", "LEAP SECONDS"));
      },
      2, "END OF HEADER");
}

// RINEX 2.11 Table A3, DELTA-UTC: A0,A1,T,W (3X,2D19.12,2I9): T a second of the week, W a week
// the nanosecond count holds.
TEST(RinexNavErrors, DeltaUtcReferenceTime) {
  const auto with = [](const std::string& t_w) {
    return hdr("     2.10           N: GPS NAV DATA", "RINEX VERSION / TYPE") +
           hdr("    .133179128170D-06  .107469588780D-12" + t_w, "DELTA-UTC: A0,A1,T,W") + hdr("", "END OF HEADER");
  };
  (void)nav_from(with("   552960     1316"));
  expect_input_error([&] { (void)nav_from(with("   604800     1316")); }, 2, "DELTA-UTC T");
  expect_input_error([&] { (void)nav_from(with("   552960      -13")); }, 2, "DELTA-UTC W");
  expect_input_error([&] { (void)nav_from(with("   552960 99999999")); }, 2, "DELTA-UTC W");
}

TEST(RinexNavErrors, NonNumericField) {
  const std::string bad = replace(kNavV2Record, " 5.153636478420D+03", "        5.15x3D+03");
  const std::string msg = expect_input_error([&] { (void)nav_from(nav_v2_header() + bad, "x.05n"); },
                                             8, "sqrtA");
  EXPECT_NE(msg.find("x.05n:8: sqrtA:"), std::string::npos) << msg;
}

TEST(RinexNavErrors, NanAndInfinity) {
  expect_input_error(
      [&] {
        (void)nav_from(nav_v2_header() +
                       replace(kNavV2Record, " 5.957618006510D-03", "                NaN"));
      },
      8, "e");
  expect_input_error(
      [&] {
        (void)nav_from(nav_v2_header() +
                       replace(kNavV2Record, " 1.705302565820D-12", "                inf"));
      },
      6, "af1");
  // Overflows a double.
  expect_input_error(
      [&] {
        (void)nav_from(nav_v2_header() +
                       replace(kNavV2Record, " 1.705302565820D-12", " 1.00000000000D+999"));
      },
      6, "af1");
}

TEST(RinexNavErrors, BadPrnAndEpoch) {
  expect_input_error(
      [&] { (void)nav_from(nav_v2_header() + replace(kNavV2Record, " 1 05  4", " x 05  4")); }, 6,
      "PRN");
  expect_input_error(
      [&] { (void)nav_from(nav_v2_header() + replace(kNavV2Record, " 1 05  4  2", " 1 05 13  2")); },
      6, "epoch");
  expect_input_error(
      [&] { (void)nav_from(nav_v2_header() + replace(kNavV2Record, " 1 05  4", "99 05  4")); }, 6,
      "PRN");
}

TEST(RinexNavErrors, TruncatedRecord) {
  // End of file instead of BROADCAST ORBIT - 7.
  std::string rec = kNavV2Record;
  rec = rec.substr(0, rec.rfind("    5.195760000000D+05"));
  expect_input_error([&] { (void)nav_from(nav_v2_header() + rec); }, 13, "transmission time");

  // BROADCAST ORBIT - 7 missing: the next record starts where it was expected.
  expect_input_error([&] { (void)nav_from(nav_v2_header() + rec + kNavV2Record); }, 13,
                     "transmission time");

  // A file cut in the middle of the last number.
  expect_input_error(
      [&] { (void)nav_from(nav_v2_header() + rec + "    5.1957"); }, 13, "transmission time");

  // A field missing from a full line.
  expect_input_error(
      [&] {
        (void)nav_from(nav_v2_header() + replace(kNavV2Record, " 3.960000000000D+02\n", "\n"));
      },
      12, "IODC");
}

TEST(RinexNavErrors, ImplausibleOrbit) {
  expect_input_error(
      [&] {
        (void)nav_from(nav_v2_header() +
                       replace(kNavV2Record, " 5.153636478420D+03", "-5.153636478420D+03"));
      },
      8, "sqrtA");
  expect_input_error(
      [&] {
        (void)nav_from(nav_v2_header() +
                       replace(kNavV2Record, " 1.400000000000D+02", " 1.405000000000D+02"));
      },
      7, "IODE");
  // A week so far out that toe in nanoseconds would overflow (found by tools/fuzz).
  expect_input_error(
      [&] {
        (void)nav_from(nav_v2_header() +
                       replace(kNavV2Record, " 1.316000000000D+03", " 2.244000000000D+07"));
      },
      11, "GPS week");
}

TEST(RinexNavErrors, Rinex3OtherSystemTruncated) {
  const std::string text = hdr("     3.05           N: GNSS NAV DATA    M: MIXED", "RINEX VERSION / TYPE") +
                           hdr("", "END OF HEADER") +
                           "S23 2020 06 25 00 00 16 0.000000000000e+00 0.000000000000e+00 3.456300000000e+05\n"
                           "     3.594460000000e+04 0.000000000000e+00 0.000000000000e+00 6.300000000000e+01\n" +
                           kNavV3G01;
  expect_input_error([&] { (void)nav_from(text); }, 5, "BROADCAST ORBIT");
}

// A Galileo record with a satellite number Galileo does not have, and a BeiDou record cut
// short: file, line and field, as for GPS.
TEST(RinexNavErrors, GalileoAndBeidouRecords) {
  const std::string head = hdr("     3.05           N: GNSS NAV DATA    M: MIXED", "RINEX VERSION / TYPE") +
                           hdr("", "END OF HEADER");
  const std::string e11 =
      "E11 2023 01 08 10 00 00-6.069173011929E-04-7.915925436828E-12 0.000000000000E+00\n"
      "     1.200000000000E+01 1.046875000000E+01 3.039055206883E-09 6.651563429348E-01\n"
      "     4.600733518600E-07 1.537999557331E-04 3.682449460030E-06 5.440617427826E+03\n"
      "     3.600000000000E+04 1.862645149231E-08-1.455893218330E+00-2.235174179077E-08\n"
      "     9.795183446102E-01 2.758125000000E+02-4.209044012085E-01-5.754166531633E-09\n"
      "    -1.414344916519E-10 5.170000000000E+02 2.244000000000E+03\n"
      "     3.120000000000E+00 0.000000000000E+00-1.396983861923E-09-1.629814505577E-09\n"
      "     3.670400000000E+04\n";
  EXPECT_EQ(nav_from(head + e11).galileo.size(), 1u);
  const std::string why = expect_input_error([&] { (void)nav_from(head + replace(e11, "E11 2023", "E37 2023")); }, 3, "PRN");
  EXPECT_NE(why.find("Galileo PRN 37 out of range 1-36"), std::string::npos) << why;
  // A BDS record whose SatH1 line is missing: the next record starts where it was expected.
  std::string c06 = replace(e11, "E11 2023", "C06 2023");
  c06 = c06.substr(0, c06.find("     3.120000000000E+00"));
  expect_input_error([&] { (void)nav_from(head + c06 + e11); }, 9, "SV accuracy");
}

TEST(RinexNavErrors, Rinex4Problems) {
  const std::string head = hdr("     4.00           NAVIGATION DATA     M: MIXED", "RINEX VERSION / TYPE") +
                           hdr("", "END OF HEADER");
  // Marker names another satellite than the record.
  expect_input_error([&] { (void)nav_from(head + "> EPH G05 LNAV\n" + kNavV3G01); }, 4, "PRN");
  // A record line with no '>' line before it.
  expect_input_error([&] { (void)nav_from(head + kNavV3G01); }, 3, "record type");
  // Truncated LNAV record followed by the next '>' line.
  std::string rec = kNavV3G01;
  rec = rec.substr(0, rec.rfind("     3.600000000000E+04 4.0"));
  expect_input_error([&] { (void)nav_from(head + "> EPH G01 LNAV\n" + rec + "> EPH G01 LNAV\n" + kNavV3G01); },
                     11, "transmission time");
  // A GPS ION record cut after its first line, and one with a non-numeric beta.
  expect_input_error(
      [&] {
        (void)nav_from(head + "> ION G01 LNAV\n"
                              "    2023 01 08 09 59 42 2.421438694000E-08 7.450580596924E-09-1.192092895508E-07\n" +
                       "> EPH G01 LNAV\n" + kNavV3G01);
      },
      5, "alpha3");  // line 5 is where the second ION line should have been
  expect_input_error(
      [&] {
        (void)nav_from(head + "> ION G01 LNAV\n"
                              "    2023 01 08 09 59 42 2.421438694000E-08 7.450580596924E-09-1.192092895508E-07\n"
                              "     5.960464477539E-08 1.474560000000E+05-1.96608000000xE+05 0.000000000000E+00\n"
                              "     2.621440000000E+05\n");
      },
      5, "beta1");
  // An STO record cut after its epoch line, and one with a non-numeric a0.
  expect_input_error([&] { (void)nav_from(head + "> STO G01 LNAV\n    2023 01 08 09 59 42 GPUT        UTC(USNO)\n"); },
                     4, "STO");
  expect_input_error(
      [&] {
        (void)nav_from(head + "> STO G01 LNAV\n    2023 01 08 09 59 42 GPUT        UTC(USNO)\n"
                              "     3.600000000000E+04 5.58793544769xE-09 0.000000000000E+00 0.000000000000E+00\n");
      },
      5, "STO a0");
}

// System time offsets of the navigation header (RINEX 3.05 TIME SYSTEM CORR), with their
// reference times in GPS time: BDS weeks and seconds are BDT's.
TEST(RinexNav, TimeSystemCorrections) {
  const std::string text = hdr("     3.05           N: GNSS NAV DATA    M: MIXED", "RINEX VERSION / TYPE") +
                           hdr("GAGP  2.3574102670E-09 3.996802889E-15 345600 2111", "TIME SYSTEM CORR") +
                           hdr("BDUT -2.7939677238E-09 0.000000000E+00     14  755", "TIME SYSTEM CORR") +
                           hdr("GLUT  1.8626451492E-09 0.000000000E+00      0    0", "TIME SYSTEM CORR") +
                           hdr("", "END OF HEADER");
  const NavData nav = nav_from(text, "h.rnx");
  ASSERT_EQ(nav.time_offsets.size(), 3u);
  const TimeSystemOffset& gagp = nav.time_offsets[0];
  EXPECT_EQ(gagp.type, "GAGP");
  EXPECT_EQ(gagp.source, "h.rnx:2");
  EXPECT_EQ(gagp.t_ref, from_week_tow(2111, 345600.0));
  EXPECT_DOUBLE_EQ(gagp.at_s(gagp.t_ref.plus_s(1000.0)), 2.3574102670E-09 + 1000.0 * 3.996802889E-15);
  EXPECT_EQ(nav.time_offsets[1].t_ref, from_week_tow(755 + 1356, 28.0));  // BDT 14 s = GPST 28 s
  EXPECT_EQ(nav.time_offsets[2].t_ref, GpsTime{});
  // The latest reference time not after t applies, else the earliest.
  NavData two = nav;
  two.time_offsets.push_back(gagp);
  two.time_offsets.back().t_ref = gagp.t_ref.plus_s(86400.0);
  EXPECT_EQ(two.time_offset("GAGP", gagp.t_ref.plus_s(-1.0)), &two.time_offsets[0]);
  EXPECT_EQ(two.time_offset("GAGP", gagp.t_ref.plus_s(86399.0)), &two.time_offsets[0]);
  EXPECT_EQ(two.time_offset("GAGP", gagp.t_ref.plus_s(86400.0)), &two.time_offsets[3]);

  const auto with = [](const std::string& corr) {
    return hdr("     3.05           N: GNSS NAV DATA    M: MIXED", "RINEX VERSION / TYPE") + hdr(corr, "TIME SYSTEM CORR") +
           hdr("", "END OF HEADER");
  };
  expect_input_error([&] { (void)nav_from(with("GA    2.3574102670E-09 3.996802889E-15 345600 2111")); }, 2, "TIME SYSTEM CORR type");
  expect_input_error([&] { (void)nav_from(with("GAGP  2.35741026x0E-09 3.996802889E-15 345600 2111")); }, 2, "TIME SYSTEM CORR a0");
  expect_input_error([&] { (void)nav_from(with("GAGP  2.3574102670E-09 3.996802889E-15 604800 2111")); }, 2, "TIME SYSTEM CORR T");
  // A week beyond 10000 (year 2171; the columns read 60121) would overflow the nanosecond count.
  expect_input_error([&] { (void)nav_from(with("GAGP  2.3574102670E-09 3.996802889E-15  3456060121")); }, 2, "TIME SYSTEM CORR W");
}

// ---------------------------------------------------------------------------------------------
// Observation files: reference data

TEST(RinexObs, Geonet0759Rinex210) {
  NAVEMU_REQUIRE_SHARED();
  const ObsData obs = test::rinex_obs_file(shared_data("gnss/rtklib_geonet_20050402/07590920.05o"));
  const ObsHeader& h = obs.header;
  EXPECT_DOUBLE_EQ(h.version, 2.10);
  EXPECT_EQ(h.file_system, 'G');
  EXPECT_EQ(h.marker_name, "0759");
  EXPECT_DOUBLE_EQ(h.approx_position_ecef_m.x(), -3976219.5082);
  EXPECT_DOUBLE_EQ(h.approx_position_ecef_m.y(), 3382372.5671);
  EXPECT_DOUBLE_EQ(h.approx_position_ecef_m.z(), 3652512.9849);
  EXPECT_DOUBLE_EQ(h.antenna_delta_hen_m.norm(), 0.0);
  EXPECT_DOUBLE_EQ(h.interval_s, 30.0);
  EXPECT_EQ(h.time_system, 'G');
  EXPECT_FALSE(h.leap_seconds.has_value());
  ASSERT_EQ(h.types.count('G'), 1u);
  EXPECT_EQ(h.types.at('G'), (std::vector<std::string>{"L1", "C1", "L2", "P2"}));
  EXPECT_EQ(h.index_of('G', "C1"), 1);
  EXPECT_EQ(h.index_of('G', "P2"), 3);
  EXPECT_EQ(h.index_of('G', "C2"), -1);
  EXPECT_EQ(h.index_of('R', "C1"), -1);

  ASSERT_EQ(obs.epochs.size(), 120u);
  EXPECT_EQ(obs.event_records, 3);  // event flag 4 "RINEX FILE SPLICE" inserts
  EXPECT_EQ(obs.cycle_slip_records, 0);

  const ObsEpoch& e0 = obs.epochs.front();
  EXPECT_EQ(e0.time, gps(2005, 4, 2, 0, 0, 0.0));
  EXPECT_EQ(to_week_tow(e0.time).week, 1316);
  EXPECT_EQ(e0.flag, 0);
  ASSERT_EQ(e0.sats.size(), 8u);
  const std::vector<int> prns{3, 7, 8, 11, 19, 20, 24, 28};
  for (std::size_t k = 0; k < prns.size(); ++k) {
    EXPECT_EQ(e0.sats[k].system, 'G');
    EXPECT_EQ(e0.sats[k].number, prns[k]);
  }
  // "  55923622.160    24767686.375    43647388.2424   24767684.8224"
  const SatObs& g3 = e0.sats[0];
  ASSERT_EQ(g3.values.size(), 4u);
  EXPECT_DOUBLE_EQ(g3.values[0], 55923622.160);
  EXPECT_DOUBLE_EQ(g3.values[1], 24767686.375);
  EXPECT_DOUBLE_EQ(g3.values[2], 43647388.242);
  EXPECT_DOUBLE_EQ(g3.values[3], 24767684.822);
  EXPECT_EQ(g3.lli, (std::vector<int>{0, 0, 4, 4}));
  EXPECT_EQ(g3.ssi, (std::vector<int>{0, 0, 0, 0}));

  for (const auto& e : obs.epochs) {
    EXPECT_GE(e.sats.size(), 7u);
    EXPECT_LE(e.sats.size(), 11u);
  }
  // Epochs around the splice at 00:48 are all there, 30 s apart.
  for (std::size_t k = 1; k < obs.epochs.size(); ++k)
    EXPECT_NEAR(seconds_between(obs.epochs[k].time, obs.epochs[k - 1].time), 30.0, 0.01);
  EXPECT_EQ(obs.epochs.back().time, gps(2005, 4, 2, 0, 59, 30.005));
}

TEST(RinexObs, Geonet3040Rinex210) {
  NAVEMU_REQUIRE_SHARED();
  const ObsData obs = test::rinex_obs_file(shared_data("gnss/rtklib_geonet_20050402/30400920.05o"));
  EXPECT_EQ(obs.header.marker_name, "3040");
  EXPECT_EQ(obs.epochs.size(), 120u);
  EXPECT_GE(obs.event_records, 1);
  EXPECT_EQ(obs.epochs.front().sats.size(), 9u);
  EXPECT_DOUBLE_EQ(obs.epochs.front().sats[0].values[0], -41706426.668);
}

TEST(RinexObs, EsbcMixedRinex305) {
  NAVEMU_REQUIRE_SHARED();
  const ObsData obs =
      test::rinex_obs_file(shared_data("gnss/esbc_20200625/ESBC00DNK_R_20201770000_01H_30S_MO.rnx"));
  const ObsHeader& h = obs.header;
  EXPECT_DOUBLE_EQ(h.version, 3.05);
  EXPECT_EQ(h.file_system, 'M');
  EXPECT_EQ(h.marker_name, "ESBC00DNK");
  EXPECT_DOUBLE_EQ(h.approx_position_ecef_m.x(), 3582105.2910);
  EXPECT_DOUBLE_EQ(h.antenna_delta_hen_m.x(), 0.2160);
  EXPECT_DOUBLE_EQ(h.interval_s, 30.0);
  EXPECT_EQ(h.time_system, 'G');
  for (const char s : std::string("CEGJRS")) EXPECT_EQ(h.types.count(s), 1u) << s;
  ASSERT_EQ(h.types.at('G').size(), 18u);
  EXPECT_EQ(h.types.at('G').front(), "C1C");
  EXPECT_EQ(h.types.at('G').back(), "S5Q");  // from the continuation line
  EXPECT_EQ(h.types.at('R').size(), 20u);
  EXPECT_EQ(h.index_of('G', "C1C"), 0);
  EXPECT_EQ(h.index_of('G', "L1C"), 9);

  ASSERT_EQ(obs.epochs.size(), 120u);
  EXPECT_EQ(obs.event_records, 0);
  EXPECT_TRUE(obs.warnings.empty());
  std::set<char> systems;
  for (const auto& e : obs.epochs) {
    EXPECT_GE(e.sats.size(), 42u);  // 42 in 18 epochs (data/README.md says 43-46)
    EXPECT_LE(e.sats.size(), 46u);
    for (const auto& s : e.sats) {
      systems.insert(s.system);
      EXPECT_EQ(s.values.size(), h.types.at(s.system).size());
    }
  }
  EXPECT_EQ(systems, (std::set<char>{'C', 'E', 'G', 'R', 'S'}));

  const ObsEpoch& e0 = obs.epochs.front();
  EXPECT_EQ(e0.time, gps(2020, 6, 25, 0, 0, 0.0));
  EXPECT_EQ(to_week_tow(e0.time).week, 2111);
  EXPECT_DOUBLE_EQ(to_week_tow(e0.time).tow_s, 345600.0);
  ASSERT_EQ(e0.sats.size(), 43u);
  // "C05  40715949.461 5                  40715946.882 6        -2.196 5 ..."
  const SatObs& c05 = e0.sats[0];
  EXPECT_EQ(c05.system, 'C');
  EXPECT_EQ(c05.number, 5);
  EXPECT_DOUBLE_EQ(c05.values[0], 40715949.461);  // C2I
  EXPECT_EQ(c05.ssi[0], 5);
  EXPECT_EQ(c05.lli[0], 0);
  EXPECT_TRUE(std::isnan(c05.values[1]));  // C6I blank
  EXPECT_EQ(c05.ssi[1], 0);
  EXPECT_DOUBLE_EQ(c05.values[2], 40715946.882);  // C7I
  EXPECT_DOUBLE_EQ(c05.values[3], -2.196);        // D2I
  EXPECT_DOUBLE_EQ(c05.values[11], 38.000);       // S7I, last field of the line
  EXPECT_EQ(obs.epochs.back().time, gps(2020, 6, 25, 0, 59, 30.0));
}

TEST(RinexObs, SpirentRinex304) {
  NAVEMU_REQUIRE_SHARED();
  const ObsData obs = test::rinex_obs_file(
      shared_data("gnss/spirent_simgen_static_20230108/klobuchar_saastamoinen/Spirent_RINEX_MO.obs"));
  EXPECT_DOUBLE_EQ(obs.header.version, 3.04);
  EXPECT_EQ(obs.header.types.at('G').size(), 28u);
  EXPECT_EQ(obs.header.types.at('E').size(), 48u);
  ASSERT_EQ(obs.epochs.size(), 49u);
  const ObsEpoch& e0 = obs.epochs.front();
  EXPECT_EQ(e0.time, gps(2023, 1, 8, 10, 0, 0.0));
  EXPECT_DOUBLE_EQ(e0.receiver_clock_offset_s, 0.0);
  // This simulator announces two satellites more than it lists in 6 of the 49 epochs (43 for
  // 41 lines here): the epochs are kept and the discrepancy reported.
  ASSERT_EQ(e0.sats.size(), 41u);
  ASSERT_EQ(obs.warnings.size(), 6u);
  EXPECT_NE(obs.warnings[0].find("Spirent_RINEX_MO.obs:78: satellite count:"), std::string::npos)
      << obs.warnings[0];
  // "G01  21878660.530 9 114973009.794 9      2660.069 9        55.376 9   ..."
  const auto at = [&](const std::string& code) {
    const int i = obs.header.index_of('G', code);
    EXPECT_GE(i, 0) << code;
    return e0.sats[0].values.at(static_cast<std::size_t>(i));
  };
  EXPECT_EQ(e0.sats[0].number, 1);
  EXPECT_DOUBLE_EQ(at("C1C"), 21878660.530);
  EXPECT_DOUBLE_EQ(at("L1C"), 114973009.794);
  EXPECT_EQ(e0.sats[0].ssi[0], 9);
  EXPECT_TRUE(std::isnan(at("C1X")));
  EXPECT_EQ(obs.epochs.back().time, gps(2023, 1, 8, 14, 0, 0.0));
  // QZSS written with the letter Q by this simulator: kept like any declared system.
  bool has_q = false;
  for (const auto& s : e0.sats) has_q = has_q || s.system == 'Q';
  EXPECT_TRUE(has_q);
}

// ---------------------------------------------------------------------------------------------
// Observation files: inline snippets

std::string obs16(double v, int lli = 0, int ssi = 0) {
  if (std::isnan(v)) return std::string(16, ' ');
  return fmt::format("{:14.3f}{}{}", v, lli ? static_cast<char>('0' + lli) : ' ',
                     ssi ? static_cast<char>('0' + ssi) : ' ');
}

// RINEX 2.11 mixed file with 10 observation types (a continuation line in the header, two
// lines per satellite) and 13 satellites in an epoch (a continuation line of satellites).
std::string obs_v2_header() {
  return hdr("     2.11           OBSERVATION DATA    M (MIXED)", "RINEX VERSION / TYPE") +
         hdr("TEST", "MARKER NAME") +
         hdr(" -3976219.5082  3382372.5671  3652512.9849", "APPROX POSITION XYZ") +
         hdr("        1.2500        0.0000        0.0000", "ANTENNA: DELTA H/E/N") +
         hdr("    10    L1    L2    C1    P1    P2    D1    D2    S1    S2", "# / TYPES OF OBSERV") +
         hdr("          C5", "# / TYPES OF OBSERV") +  //
         hdr("     1.000", "INTERVAL") +
         hdr("  2005     4     2     0     0    0.0000000     GPS", "TIME OF FIRST OBS") +
         hdr("", "END OF HEADER");  // line 9
}

std::string v2_sat_lines(double base) {
  std::string a, b;
  for (int k = 0; k < 5; ++k) a += obs16(base + k, k == 0 ? 1 : 0, 7);
  for (int k = 5; k < 10; ++k) b += obs16(k == 7 ? kMissing : base + k);
  // Trailing blanks removed, as RINEX 2.11 section 6.3 allows.
  while (!b.empty() && b.back() == ' ') b.pop_back();
  return a + "\n" + b + "\n";
}

TEST(RinexObs, Rinex2SnippetWithContinuations) {
  std::string text = obs_v2_header();
  // Epoch 1: 13 satellites, ids with blank system (GPS), G, R, S and E.
  text += " 05  4  2  0  0  0.0000000  0 13  1  2G03G04R01R02S20E11  9 10 11 12 0.000123456\n";
  text += std::string(32, ' ') + "G13\n";  // line 11
  for (int s = 0; s < 13; ++s) text += v2_sat_lines(1000.0 * (s + 1));
  // Epoch 2: event flag 2 (start moving antenna) without special records, then flag 4 with a
  // comment and the same types list again, then a flag 6 cycle-slip record, then data.
  text += std::string(28, ' ') + "2  0\n";
  text += std::string(28, ' ') + "4  3\n";
  text += hdr("SPLICE", "COMMENT");
  text += hdr("    10    L1    L2    C1    P1    P2    D1    D2    S1    S2", "# / TYPES OF OBSERV");
  text += hdr("          C5", "# / TYPES OF OBSERV");
  text += " 05  4  2  0  0  1.0000000  6  1G03\n" + v2_sat_lines(5.0);
  text += " 05  4  2  0  0  1.0000000  0  1G03\n" + v2_sat_lines(7.0);

  const ObsData obs = obs_from(text);
  EXPECT_EQ(obs.header.marker_name, "TEST");
  EXPECT_DOUBLE_EQ(obs.header.antenna_delta_hen_m.x(), 1.25);
  EXPECT_DOUBLE_EQ(obs.header.interval_s, 1.0);
  for (const char s : std::string("GRES")) {
    ASSERT_EQ(obs.header.types.count(s), 1u) << s;
    EXPECT_EQ(obs.header.types.at(s).size(), 10u);
    EXPECT_EQ(obs.header.index_of(s, "C5"), 9);
  }
  EXPECT_EQ(obs.event_records, 2);
  EXPECT_EQ(obs.cycle_slip_records, 1);
  ASSERT_EQ(obs.epochs.size(), 2u);
  const ObsEpoch& e = obs.epochs[0];
  EXPECT_EQ(e.time, gps(2005, 4, 2, 0, 0, 0.0));
  EXPECT_DOUBLE_EQ(e.receiver_clock_offset_s, 0.000123456);
  ASSERT_EQ(e.sats.size(), 13u);
  const std::vector<std::pair<char, int>> ids{{'G', 1}, {'G', 2},  {'G', 3},  {'G', 4},  {'R', 1},
                                              {'R', 2}, {'S', 20}, {'E', 11}, {'G', 9},  {'G', 10},
                                              {'G', 11}, {'G', 12}, {'G', 13}};
  for (std::size_t k = 0; k < ids.size(); ++k) {
    EXPECT_EQ(e.sats[k].system, ids[k].first) << k;
    EXPECT_EQ(e.sats[k].number, ids[k].second) << k;
    EXPECT_DOUBLE_EQ(e.sats[k].values[0], 1000.0 * static_cast<double>(k + 1));
    EXPECT_DOUBLE_EQ(e.sats[k].values[9], 1000.0 * static_cast<double>(k + 1) + 9.0);
  }
  EXPECT_EQ(e.sats[4].lli[0], 1);
  EXPECT_EQ(e.sats[4].ssi[0], 7);
  EXPECT_EQ(e.sats[4].ssi[5], 0);
  EXPECT_TRUE(std::isnan(e.sats[4].values[7]));  // blank D2
  EXPECT_EQ(obs.epochs[1].time, gps(2005, 4, 2, 0, 0, 1.0));
  EXPECT_DOUBLE_EQ(obs.epochs[1].sats[0].values[0], 7.0);
}

std::string obs_v3_header(const std::string& time_system = "GPS") {
  return hdr("     3.05           OBSERVATION DATA    M: MIXED", "RINEX VERSION / TYPE") +
         hdr("G    4 C1C L1C D1C S1C", "SYS / # / OBS TYPES") +
         hdr("E    2 C1C L1C", "SYS / # / OBS TYPES") +
         hdr("  2020     6    25     0     0    0.0000000     " + time_system, "TIME OF FIRST OBS") +
         hdr("", "END OF HEADER");  // line 5
}

const char* const kObsV3Body =
    "> 2020 06 25 00 00  0.0000000  0  3       0.000000001000\n"  // line 6
    "G01  21878660.530 9 114973009.794 9\n"
    "G07  20116762.409 9 105714215.725 9       377.005 9        56.099 9\n"
    "E05  23456789.123 7\n"
    "> 2020 06 25 00 00 30.0000000  0  1\n"  // line 10
    "G01  21878661.530 9\n";

TEST(RinexObs, Rinex3SnippetWithShortLines) {
  const ObsData obs = obs_from(obs_v3_header() + kObsV3Body);
  ASSERT_EQ(obs.epochs.size(), 2u);
  const ObsEpoch& e = obs.epochs[0];
  EXPECT_DOUBLE_EQ(e.receiver_clock_offset_s, 1e-9);
  ASSERT_EQ(e.sats.size(), 3u);
  EXPECT_DOUBLE_EQ(e.sats[0].values[1], 114973009.794);
  EXPECT_TRUE(std::isnan(e.sats[0].values[2]));
  EXPECT_TRUE(std::isnan(e.sats[0].values[3]));
  EXPECT_DOUBLE_EQ(e.sats[1].values[3], 56.099);
  EXPECT_EQ(e.sats[2].system, 'E');
  EXPECT_EQ(e.sats[2].values.size(), 2u);
  EXPECT_EQ(e.sats[2].ssi[0], 7);
  EXPECT_TRUE(std::isnan(e.sats[2].values[1]));
  EXPECT_EQ(obs.epochs[1].time, gps(2020, 6, 25, 0, 0, 30.0));
}

TEST(RinexObs, EpochsInOtherTimeSystemsBecomeGpsTime) {
  const ObsData bdt = obs_from(obs_v3_header("BDT") + kObsV3Body);
  EXPECT_EQ(bdt.header.time_system, 'C');
  EXPECT_EQ(bdt.epochs[0].time, gps(2020, 6, 25, 0, 0, 14.0));  // BDT = GPST - 14 s
  const ObsData gal = obs_from(obs_v3_header("GAL") + kObsV3Body);
  EXPECT_EQ(gal.header.time_system, 'E');
  EXPECT_EQ(gal.epochs[0].time, gps(2020, 6, 25, 0, 0, 0.0));
  const ObsData blank = obs_from(obs_v3_header("   ") + kObsV3Body);
  EXPECT_EQ(blank.header.time_system, 'G');
  expect_input_error([] { (void)obs_from(obs_v3_header("XYZ") + kObsV3Body); }, 4,
                     "TIME OF FIRST OBS");
}

TEST(RinexObs, Rinex3EventsAreConsumed) {
  const std::string text = obs_v3_header() + kObsV3Body +
                           "> 2020 06 25 00 00 45.0000000  5  0\n"
                           ">" + std::string(30, ' ') + "4  2\n" +
                           hdr("ANOTHER COMMENT", "COMMENT") + hdr("NEW", "MARKER NAME") +
                           "> 2020 06 25 00 01 00.0000000  6  1\n"
                           "G01  21878661.530 9\n"
                           "> 2020 06 25 00 01 00.0000000  1  1\n"
                           "G01  21878662.530 9\n";
  const ObsData obs = obs_from(text);
  EXPECT_EQ(obs.event_records, 2);
  EXPECT_EQ(obs.cycle_slip_records, 1);
  ASSERT_EQ(obs.epochs.size(), 3u);
  EXPECT_EQ(obs.epochs[2].flag, 1);
  EXPECT_DOUBLE_EQ(obs.epochs[2].sats[0].values[0], 21878662.530);
}

// ---------------------------------------------------------------------------------------------
// Observation files: bad input

// A missing file: tests/emulator/test_rinex_files.cpp.
TEST(RinexObsErrors, WrongType) {
  expect_input_error(
      [] { (void)obs_from(hdr("     2.10           N: GPS NAV DATA", "RINEX VERSION / TYPE")); }, 1,
      "file type");
  expect_input_error(
      [] { (void)obs_from(hdr("     4.01           OBSERVATION DATA    M", "RINEX VERSION / TYPE")); },
      1, "version");
  expect_input_error([] { (void)obs_from(hdr("1.0                 COMPACT RINEX FORMAT", "CRINEX VERS   / TYPE")); },
                     1, "RINEX VERSION / TYPE");
}

TEST(RinexObsErrors, HeaderProblems) {
  // Fewer types listed than declared.
  expect_input_error(
      [] {
        (void)obs_from(hdr("     3.05           OBSERVATION DATA    M", "RINEX VERSION / TYPE") +
                       hdr("G    5 C1C L1C D1C S1C", "SYS / # / OBS TYPES") + hdr("", "END OF HEADER"));
      },
      3, "SYS / # / OBS TYPES");
  // No types at all.
  expect_input_error(
      [] {
        (void)obs_from(hdr("     3.05           OBSERVATION DATA    M", "RINEX VERSION / TYPE") +
                       hdr("", "END OF HEADER"));
      },
      2, "SYS / # / OBS TYPES");
  // Non-numeric approximate position.
  expect_input_error(
      [] {
        (void)obs_from(hdr("     2.11           OBSERVATION DATA    G", "RINEX VERSION / TYPE") +
                       hdr(" -3976219.5082  3382372.56x1  3652512.9849", "APPROX POSITION XYZ"));
      },
      2, "APPROX POSITION XYZ");
  // End of file in the header.
  expect_input_error(
      [] { (void)obs_from(hdr("     2.11           OBSERVATION DATA    G", "RINEX VERSION / TYPE")); },
      1, "END OF HEADER");
}

TEST(RinexObsErrors, Rinex3SatelliteCountTooHigh) {
  // Followed by the next epoch line: the listed satellites are kept, with a warning.
  const std::string body = replace(kObsV3Body, "  0  3       0.0", "  0  4       0.0");
  const ObsData obs = obs_from(obs_v3_header() + body, "a.rnx");
  ASSERT_EQ(obs.epochs.size(), 2u);
  EXPECT_EQ(obs.epochs[0].sats.size(), 3u);
  ASSERT_EQ(obs.warnings.size(), 1u);
  EXPECT_EQ(obs.warnings[0],
            "a.rnx:6: satellite count: epoch announced 4 satellites, 3 satellite lines follow");
  // ... at the end of the file: truncated, an error.
  const std::string last = replace(kObsV3Body, "30.0000000  0  1", "30.0000000  0  2");
  expect_input_error([&] { (void)obs_from(obs_v3_header() + last); }, 12, "satellite count");
}

TEST(RinexObsErrors, Rinex3SatelliteCountTooLow) {
  const std::string body = replace(kObsV3Body, "  0  3       0.0", "  0  2       0.0");
  expect_input_error([&] { (void)obs_from(obs_v3_header() + body); }, 9, "satellite count");
}

TEST(RinexObsErrors, Rinex3BadValues) {
  // A line cut in the middle of a number.
  expect_input_error(
      [&] { (void)obs_from(obs_v3_header() + replace(kObsV3Body, "G01  21878661.530 9\n", "G01  218786")); },
      11, "C1C");
  expect_input_error(
      [&] { (void)obs_from(obs_v3_header() + replace(kObsV3Body, "21878660.530", "2187x660.530")); },
      7, "C1C");
  expect_input_error(
      [&] { (void)obs_from(obs_v3_header() + replace(kObsV3Body, "      377.005", "          nan")); },
      8, "D1C");
  expect_input_error(
      [&] { (void)obs_from(obs_v3_header() + replace(kObsV3Body, "114973009.794 9", "114973009.794x9")); },
      7, "L1C LLI");
  expect_input_error(
      [&] { (void)obs_from(obs_v3_header() + replace(kObsV3Body, "E05  23456789.123 7", "R05  23456789.123 7")); },
      9, "satellite");
  expect_input_error(
      [&] { (void)obs_from(obs_v3_header() + replace(kObsV3Body, "> 2020 06 25 00 00  0", "> 2020 13 25 00 00  0")); },
      6, "epoch");
  expect_input_error(
      [&] { (void)obs_from(obs_v3_header() + replace(kObsV3Body, "E05  23456789.123 7", "E05  23456789.123 7  23456789.123 7  1.000")); },
      9, "observations");
}

TEST(RinexObsErrors, Rinex2SatelliteCountInconsistent) {
  const std::string epoch1 = " 05  4  2  0  0  0.0000000  0  2G01G02\n";
  const std::string epoch2 = " 05  4  2  0  0  1.0000000  0  1G01\n";
  // Three satellites announced, two listed.
  expect_input_error(
      [&] {
        (void)obs_from(obs_v2_header() + " 05  4  2  0  0  0.0000000  0  3G01G02\n" + v2_sat_lines(1.0) +
                       v2_sat_lines(2.0) + v2_sat_lines(3.0));
      },
      10, "satellite count");
  // Announced satellites match the list, but one satellite's lines are missing: the next epoch
  // line is met inside the observations.
  expect_input_error(
      [&] { (void)obs_from(obs_v2_header() + epoch1 + v2_sat_lines(1.0) + epoch2 + v2_sat_lines(1.0)); },
      13, "satellite count");
  // More observation lines than announced.
  expect_input_error(
      [&] {
        (void)obs_from(obs_v2_header() + epoch2 + v2_sat_lines(1.0) + v2_sat_lines(2.0) + epoch2 +
                       v2_sat_lines(1.0));
      },
      13, "epoch");
  // Truncated at the end of the file.
  expect_input_error([&] { (void)obs_from(obs_v2_header() + epoch1 + v2_sat_lines(1.0)); }, 13, "L1");
}

TEST(RinexObsErrors, Rinex2EventProblems) {
  // The event announces more records than the file has.
  expect_input_error(
      [&] { (void)obs_from(obs_v2_header() + std::string(28, ' ') + "4  2\n" + hdr("X", "COMMENT")); },
      12, "event");
  // The types change in an event: not supported.
  expect_input_error(
      [&] {
        (void)obs_from(obs_v2_header() + std::string(28, ' ') + "4  1\n" +
                       hdr("     2    L1    C1", "# / TYPES OF OBSERV"));
      },
      10, "event");
  expect_input_error(
      [&] { (void)obs_from(obs_v2_header() + " 05  4  2  0  0  0.0000000  9  1G01\n" + v2_sat_lines(1.0)); },
      10, "epoch flag");
}

}  // namespace
}  // namespace navemu
