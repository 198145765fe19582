// A receiver epoch as a profile's NMEA sentences: fields carry the fix, loss of fix is reported
// the way clients (gpsd) expect it: GGA quality 0, RMC status V, GSA fix 1.

#include <gtest/gtest.h>

#include "emulator/nmea_output.hpp"
#include "protocols/nmea.hpp"

namespace navemu {
namespace {

std::vector<std::vector<std::string>> sentences(const std::string& text) {
  std::vector<std::vector<std::string>> out;
  std::size_t pos = 0;
  while (pos < text.size()) {
    const std::size_t eol = text.find("\r\n", pos);
    EXPECT_NE(eol, std::string::npos);
    if (eol == std::string::npos) break;
    const auto f = nmea::parse(text.substr(pos, eol + 2 - pos));
    EXPECT_TRUE(f.has_value()) << text.substr(pos, eol - pos);
    if (f) out.push_back(*f);
    pos = eol + 2;
  }
  return out;
}

ReceiverFix a_fix() {
  ReceiverFix f;
  f.t = gps_from_utc(CalendarTime{2010, 11, 17, 13, 0, 1.2});
  f.fix = FixType::k3D;
  f.position = Geodetic{32.3, -90.9, 60.0};
  f.v_ned_mps = Vec3(0.0, 1.0, 0.0);  // east at 1 m/s
  f.dops = Dops{2.0, 1.8, 1.1, 1.4, 0.9};
  f.num_used = 2;
  f.satellites = {{gps_sat(5), 120.0, 45.0, 44.0, true},
                  {gps_sat(12), 300.0, 10.0, 31.0, true},
                  {gps_sat(29), 30.0, 3.0, 25.0, false}};
  f.sigma_h_m = 3.3;
  f.sigma_v_m = 4.2;
  return f;
}

TEST(NmeaOutput, GarminProfileSendsItsSentencesWithTheFix) {
  const GnssProfile p = load_gnss_profile("garmin-18x-5hz");
  NmeaOutput out(p, ReceiverMode::kStandalone);
  std::string text;
  out.encode(a_fix(), 0, text);  // epoch 0: every sentence, GSV and PGRME included
  const auto s = sentences(text);
  ASSERT_EQ(s.size(), 5u);
  EXPECT_EQ(s[0][0], "GPRMC");
  EXPECT_EQ(s[0][2], "A");
  EXPECT_EQ(s[0][9], "171110");  // date ddmmyy, UTC
  EXPECT_EQ(s[0][1].substr(0, 6), "130001");
  EXPECT_NEAR(std::stod(s[0][7]), 1.0 / 0.514444, 0.05);  // knots
  EXPECT_NEAR(std::stod(s[0][8]), 90.0, 0.05);            // course east
  EXPECT_EQ(s[1][0], "GPGGA");
  EXPECT_EQ(s[1][6], "1");
  EXPECT_NEAR(std::stod(s[1][2].substr(0, 2)) + std::stod(s[1][2].substr(2)) / 60.0, 32.3, 1e-5);
  EXPECT_EQ(s[1][3], "N");
  EXPECT_EQ(s[1][5], "W");
  // Altitude plus geoid separation gives the ellipsoidal height back.
  EXPECT_NEAR(std::stod(s[1][9]) + std::stod(s[1][11]), 60.0, 0.11);
  EXPECT_EQ(s[2][0], "GPGSA");
  EXPECT_EQ(s[2][2], "3");
  EXPECT_EQ(s[2][3], "05");
  EXPECT_EQ(s[2][4], "12");
  EXPECT_EQ(s[2][5], "");
  EXPECT_EQ(s[3][0], "GPGSV");
  EXPECT_EQ(s[3][3], "03");  // satellites in view (tracked)
  EXPECT_EQ(s[4][0], "PGRME");
  EXPECT_NEAR(std::stod(s[4][1]), 6.6, 0.05);  // 2-sigma horizontal

  // Epoch 1 (0.2 s later): GSV and PGRME are sent once a second only.
  text.clear();
  out.encode(a_fix(), 1, text);
  EXPECT_EQ(sentences(text).size(), 3u);
}

TEST(NmeaOutput, LossOfFixIsQualityZeroStatusVoidFixOne) {
  const GnssProfile p = load_gnss_profile("ublox-nmea-5hz");
  NmeaOutput out(p, ReceiverMode::kStandalone);
  ReceiverFix none;
  none.t = a_fix().t;
  std::string text;
  out.encode(none, 0, text);
  bool saw_gga = false, saw_rmc = false, saw_gsa = false;
  for (const auto& s : sentences(text)) {
    if (s[0] == "GPGGA") {
      saw_gga = true;
      EXPECT_EQ(s[6], "0");
      EXPECT_EQ(s[2], "");
    }
    if (s[0] == "GPRMC") {
      saw_rmc = true;
      EXPECT_EQ(s[2], "V");
      EXPECT_EQ(s[3], "");
    }
    if (s[0] == "GPGSA") {
      saw_gsa = true;
      EXPECT_EQ(s[2], "1");
    }
  }
  EXPECT_TRUE(saw_gga && saw_rmc && saw_gsa);
}

TEST(NmeaOutput, DgpsAndRtkModesReportTheirQuality) {
  const GnssProfile p = load_gnss_profile("ublox-nmea-5hz");
  for (auto [mode, quality] : {std::pair{ReceiverMode::kDgps, "2"}, std::pair{ReceiverMode::kRtkFixed, "4"}}) {
    NmeaOutput out(p, mode);
    std::string text;
    out.encode(a_fix(), 0, text);
    for (const auto& s : sentences(text)) {
      if (s[0] == "GPGGA") {
        EXPECT_EQ(s[6], quality);
      }
    }
  }
}

// Several systems (u-blox F9 interface description UBX-18010854, "NMEA protocol"): the main
// sentences under GN, one GSA per system with its system ID, one GSV group per system under the
// system's talker with its L1 signal ID (Galileo E1: 7).
TEST(NmeaOutput, MultiGnssSentencesPerSystem) {
  GnssProfile p = load_gnss_profile("ublox-f9p");
  p.systems = system_bit(GnssSystem::kGps) | system_bit(GnssSystem::kGlonass) |
              system_bit(GnssSystem::kGalileo) | system_bit(GnssSystem::kBeidou);
  p.talker = std::string(nmea::main_talker(p.systems));
  p.sentences = {{"GGA", 1}, {"GSA", 1}, {"GSV", 1}};
  NmeaOutput out(p, ReceiverMode::kStandalone, 41);  // NMEA 4.11
  ReceiverFix f = a_fix();
  f.satellites = {{gps_sat(5), 120.0, 45.0, 44.0, true},
                  {SatId(GnssSystem::kGalileo, 11), 200.0, 60.0, 46.0, true},
                  {SatId(GnssSystem::kBeidou, 20), 10.0, 20.0, 38.0, false},
                  {SatId(GnssSystem::kGlonass, 3), 300.0, 30.0, 41.0, true}};
  std::string text;
  out.encode(f, 0, text);
  const auto s = sentences(text);
  ASSERT_EQ(s.size(), 9u) << text;
  EXPECT_EQ(s[0][0], "GNGGA");
  for (int k = 0; k < 4; ++k) {
    const auto& gsa = s[static_cast<std::size_t>(1 + k)];
    EXPECT_EQ(gsa[0], "GNGSA");
    EXPECT_EQ(gsa.back(), std::to_string(k + 1));  // system IDs 1 GPS, 2 GLONASS, 3 Galileo, 4 BeiDou
  }
  EXPECT_EQ(s[1][3], "05");
  EXPECT_EQ(s[2][3], "67");  // GLONASS slot 3: NMEA ID 67
  EXPECT_EQ(s[3][3], "11");
  EXPECT_EQ(s[4][3], "");    // the BeiDou satellite is tracked, not used
  EXPECT_EQ(s[5][0], "GPGSV");
  EXPECT_EQ(s[6][0], "GLGSV");
  EXPECT_EQ(s[6][4], "67");
  EXPECT_EQ(s[7][0], "GAGSV");
  EXPECT_EQ(s[7][4], "11");
  EXPECT_EQ(s[7].back(), "7");  // E1
  EXPECT_EQ(s[8][0], "GBGSV");
  EXPECT_EQ(s[8].back(), "1");  // B1I
}

// The profile's second band (the ZED-F9P's L2): after each system's L1 group, a group of the
// satellites tracked on its L2-band signal with that signal's ID and C/N0 (NMEA 4.11 signal IDs
// as u-blox gives them: GPS L2 CL 6, Galileo E5b 2), as the ZED-F9T sends its L1 and L5 groups
// (receiver_logs/gpsd/ublox-zed-f9t-ubx_nmea_l5.log); none where a system has no satellite on
// it, and none without signal IDs (before NMEA 4.10).
TEST(NmeaOutput, SecondBandGsvGroupsFollowEachSystemsL1Group) {
  GnssProfile p = load_gnss_profile("ublox-f9p");
  ASSERT_EQ(p.bands, band_bit(Band::kL1) | band_bit(Band::kL2));
  p.systems = system_bit(GnssSystem::kGps) | system_bit(GnssSystem::kGlonass) | system_bit(GnssSystem::kGalileo);
  p.talker = "GN";
  p.sentences = {{"GSV", 1}};
  ReceiverFix f = a_fix();
  f.satellites = {{gps_sat(5), 120.0, 45.0, 44.0, true, false, 0.0, {44.0, 38.0, 0.0}},
                  {gps_sat(13), 60.0, 30.0, 40.0, true, false, 0.0, {40.0, 0.0, 0.0}},
                  {SatId(GnssSystem::kGalileo, 11), 200.0, 60.0, 46.0, true, false, 0.0, {46.0, 41.0, 0.0}},
                  {SatId(GnssSystem::kGlonass, 3), 300.0, 30.0, 41.0, true, false, 0.0, {41.0, 0.0, 0.0}}};
  std::string text;
  NmeaOutput(p, ReceiverMode::kStandalone, 41).encode(f, 0, text);
  const auto s = sentences(text);
  ASSERT_EQ(s.size(), 5u) << text;
  EXPECT_EQ(s[0][0], "GPGSV");
  EXPECT_EQ(s[0][3], "02");
  EXPECT_EQ(s[0].back(), "1");
  EXPECT_EQ(s[1][0], "GPGSV");
  EXPECT_EQ(s[1][3], "01");  // only the L2C satellite
  EXPECT_EQ(s[1][4], "05");
  EXPECT_EQ(s[1][7], "38");
  EXPECT_EQ(s[1].back(), "6");
  EXPECT_EQ(s[2][0], "GLGSV");  // no GLONASS satellite on L2
  EXPECT_EQ(s[3][0], "GAGSV");
  EXPECT_EQ(s[3].back(), "7");
  EXPECT_EQ(s[4][0], "GAGSV");
  EXPECT_EQ(s[4][7], "41");
  EXPECT_EQ(s[4].back(), "2");

  text.clear();
  NmeaOutput(p, ReceiverMode::kStandalone, 40).encode(f, 0, text);  // NMEA 4.0: no signal IDs
  EXPECT_EQ(sentences(text).size(), 3u) << text;
}

}  // namespace
}  // namespace navemu
