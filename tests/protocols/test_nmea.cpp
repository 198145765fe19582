// NMEA encoders against real receiver output: sentences of a u-blox NEO-M9N and a Garmin 15x
// (gpsd's regression logs in ../shared/data/receiver_logs/gpsd) are parsed, converted to the
// SI fields the encoders take, and encoded again with the matching Format; the bytes must be
// the original ones, checksum included. Then the edge cases: rounding carries, empty fields,
// GSV splitting and the 82-character limit.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "protocols/nmea.hpp"
#include "tests/protocols/nmea_test_fields.hpp"

namespace navemu::nmea {
namespace {

constexpr double kKnot_mps = 1852.0 / 3600.0;

// ---- reference data ------------------------------------------------------------------------
// tests/test_support.hpp pulls in the models (Eigen), which this test executable does not link,
// so the lookup of ../shared is repeated here with the same rule: $NAVEMU_SHARED, else the
// directory next to the repository.
std::filesystem::path gpsd_log(const std::string& name) {
  const char* env = std::getenv("NAVEMU_SHARED");
  const std::filesystem::path shared = env != nullptr ? env : NAVEMU_SHARED_DEFAULT;
  return shared / "data" / "receiver_logs" / "gpsd" / name;
}

#define REQUIRE_GPSD_LOG(name)                                                     \
  do {                                                                             \
    if (!std::filesystem::is_regular_file(gpsd_log(name)))                         \
      GTEST_SKIP() << gpsd_log(name) << " not found (set NAVEMU_SHARED): skipped"; \
  } while (0)

// The sentences of a gpsd test log ('#' lines are comments).
std::vector<std::string> read_log(const std::string& name) {
  std::vector<std::string> lines;
  std::ifstream in(gpsd_log(name));
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (!line.empty() && line[0] == '$') lines.push_back(line);
  }
  return lines;
}

std::string type_of(const std::string& sentence) { return sentence.substr(3, 3); }

// ---- fields of a parsed sentence -> SI ---------------------------------------------------------

using namespace navemu::nmea::test_fields;

std::string_view talker_of(const Fields& f) { return std::string_view(f[0]).substr(0, 2); }

std::string encoded(const auto& fields, const Format& fmt) {
  std::string out;
  encode(fields, fmt, out);
  return out;
}

GgaFields gga_of(const Fields& f) {
  GgaFields g;
  g.talker = talker_of(f);
  g.utc = time_of(f[1]);
  g.position = position_of(f, 2);
  g.quality = std::stoi(f[6]);
  g.num_sats = std::stoi(f[7]);
  g.hdop = num(f[8]);
  g.alt_msl_m = num(f[9]);
  g.geoid_separation_m = num(f[11]);
  g.dgps_age_s = num(f[13]);
  g.dgps_station = inum(f[14]);
  return g;
}

RmcFields rmc_of(const Fields& f) {
  RmcFields r;
  r.talker = talker_of(f);
  r.utc = time_of(f[1], f[9]);
  r.valid = f[2] == "A";
  r.position = position_of(f, 3);
  if (const auto kn = num(f[7])) r.speed_mps = *kn * kKnot_mps;
  r.course_deg = num(f[8]);
  if (const auto mv = num(f[10])) r.magvar_deg = f[11] == "W" ? -*mv : *mv;
  if (f.size() > 12) r.mode = f[12][0];
  if (f.size() > 13) r.nav_status = f[13][0];
  return r;
}

GsaFields gsa_of(const Fields& f) {
  GsaFields g;
  g.talker = talker_of(f);
  g.selection = f[1][0];
  g.fix = std::stoi(f[2]);
  for (std::size_t i = 3; i < 15; ++i)
    if (!f[i].empty()) g.sat_ids.push_back(std::stoi(f[i]));
  g.pdop = num(f[15]);
  g.hdop = num(f[16]);
  g.vdop = num(f[17]);
  if (f.size() > 18) g.system_id = std::stoi(f[18]);
  return g;
}

// A speed that gives both printed values (knots and km/h, each rounded to `decimals` from
// the receiver's unrounded speed): the middle of the intersection of their rounding intervals.
std::optional<double> speed_of_vtg(const std::string& knots, const std::string& kmh) {
  if (knots.empty()) return std::nullopt;
  const auto half_ulp = [](const std::string& s) {
    const auto dot = s.find('.');
    return dot == std::string::npos
               ? 0.5
               : 0.5 * std::pow(10.0, -static_cast<double>(s.size() - dot - 1));
  };
  const double k = std::stod(knots), h = std::stod(kmh);
  const double lo = std::max((k - half_ulp(knots)) * kKnot_mps, (h - half_ulp(kmh)) / 3.6);
  const double hi = std::min((k + half_ulp(knots)) * kKnot_mps, (h + half_ulp(kmh)) / 3.6);
  EXPECT_LT(lo, hi) << "knots " << knots << " and km/h " << kmh << " disagree";
  return 0.5 * (lo + hi);
}

VtgFields vtg_of(const Fields& f) {
  VtgFields v;
  v.talker = talker_of(f);
  v.course_true_deg = num(f[1]);
  v.course_magnetic_deg = num(f[3]);
  v.speed_mps = speed_of_vtg(f[5], f[7]);
  if (f.size() > 9) v.mode = f[9][0];
  return v;
}

GllFields gll_of(const Fields& f) {
  GllFields g;
  g.talker = talker_of(f);
  g.position = position_of(f, 1);
  g.utc = time_of(f[5]);
  g.valid = f[6] == "A";
  if (f.size() > 7) g.mode = f[7][0];
  return g;
}

GstFields gst_of(const Fields& f) {
  GstFields g;
  g.talker = talker_of(f);
  g.utc = time_of(f[1]);
  g.range_rms_m = num(f[2]);
  g.major_m = num(f[3]);
  g.minor_m = num(f[4]);
  g.orientation_deg = num(f[5]);
  g.lat_sigma_m = num(f[6]);
  g.lon_sigma_m = num(f[7]);
  g.alt_sigma_m = num(f[8]);
  return g;
}

ZdaFields zda_of(const Fields& f) {
  ZdaFields z;
  z.talker = talker_of(f);
  z.utc = time_of(f[1]);
  z.utc.day = std::stoi(f[2]);
  z.utc.month = std::stoi(f[3]);
  z.utc.year = std::stoi(f[4]);
  z.local_zone_hours = std::stoi(f[5]);
  z.local_zone_minutes = std::stoi(f[6]);
  return z;
}

PgrmeFields pgrme_of(const Fields& f) { return {num(f[1]), num(f[3]), num(f[5])}; }

// The satellites of consecutive GSV sentences of one talker (1 of n .. n of n), with the
// signal ID of NMEA 4.1 when present (a field count of 4 + 4k + 1).
struct GsvGroup {
  std::string talker;
  std::vector<GsvSatellite> satellites;
  int signal_id = 1;
  std::string original;  // the sentences, CR LF terminated
};

std::vector<GsvGroup> gsv_groups(const std::vector<std::string>& lines) {
  std::vector<GsvGroup> groups;
  for (const std::string& line : lines) {
    if (type_of(line) != "GSV") continue;
    const Fields f = must_parse(line);
    if (f[2] == "1") groups.push_back({f[0].substr(0, 2), {}, 1, {}});
    if (groups.empty()) continue;  // the log starts in the middle of a group
    GsvGroup& g = groups.back();
    const std::size_t n_sat_fields = (f.size() - 4) / 4 * 4;
    for (std::size_t i = 4; i < 4 + n_sat_fields; i += 4)
      g.satellites.push_back({std::stoi(f[i]), inum(f[i + 1]), inum(f[i + 2]), inum(f[i + 3])});
    if (f.size() - 4 > n_sat_fields) g.signal_id = std::stoi(f.back());
    g.original += line + "\r\n";
  }
  return groups;
}

std::string encoded_gsv(const GsvGroup& g, const Format& fmt) {
  GsvFields f;
  f.talker = g.talker;
  f.satellites = g.satellites;
  f.signal_id = g.signal_id;
  return encoded(f, fmt);
}

// Re-encodes one sentence of a supported type; empty for types the encoders do not model.
std::string reencode(const std::string& line, const Format& fmt) {
  const Fields f = must_parse(line);
  if (f.empty()) return {};
  const std::string t = type_of(line);
  if (line.starts_with("$PGRME")) return encoded(pgrme_of(f), fmt);
  if (t == "GGA") return encoded(gga_of(f), fmt);
  if (t == "RMC") return encoded(rmc_of(f), fmt);
  if (t == "GSA") return encoded(gsa_of(f), fmt);
  if (t == "VTG") return encoded(vtg_of(f), fmt);
  if (t == "GLL") return encoded(gll_of(f), fmt);
  if (t == "GST") return encoded(gst_of(f), fmt);
  if (t == "ZDA") return encoded(zda_of(f), fmt);
  return {};
}

// ---- golden sentences (copied from the logs, so they run without ../shared) -------------------

TEST(NmeaGolden, UbloxNeoM9nSentences) {
  const Format fmt = Format::ublox();
  for (const char* s : {
           "$GNRMC,223745.00,A,3806.62964,N,12237.61382,W,0.040,,110720,,,D,V*0E",
           "$GNRMC,223747.00,A,3806.62968,N,12237.61386,W,0.084,,110720,,,D,V*0C",
           "$GNVTG,,T,,M,0.040,N,0.075,K,D*3E",
           "$GNVTG,,T,,M,0.061,N,0.114,K,D*3B",
           "$GNGGA,223745.00,3806.62964,N,12237.61382,W,2,12,0.54,83.1,M,-29.5,M,,0000*44",
           "$GNGGA,223746.00,3806.62966,N,12237.61384,W,2,12,0.56,83.0,M,-29.5,M,,0000*40",
           "$GNGSA,A,3,29,20,18,16,51,13,44,26,,,,,0.99,0.54,0.83,1*0E",
           "$GNGSA,A,3,82,73,74,67,81,83,68,,,,,,0.99,0.54,0.83,2*08",
           "$GNGSA,A,3,32,28,30,33,27,,,,,,,,1.04,0.56,0.88,4*0F",
           "$GNGLL,3806.62964,N,12237.61382,W,223745.00,A,D*6C",
           "$GNGST,223745.00,228650,2.5,2.4,126,0.98,1.0,3.1*41",
           "$GNGST,223746.00,837,2.5,2.4,127,0.98,1.0,3.0*75",
           "$GNZDA,223745.00,11,07,2020,00,00*7A",
       }) {
    EXPECT_EQ(reencode(s, fmt), std::string(s) + "\r\n");
  }
}

TEST(NmeaGolden, Garmin15xSentences) {
  const Format fmt = Format::garmin();
  for (const char* s : {
           "$GPRMC,113258,A,3238.9148,N,10822.4466,W,005.3,247.1,181022,009.3,E*6B",
           "$GPRMC,113300,A,3238.9141,N,10822.4498,W,005.0,245.0,181022,009.3,E*6F",
           "$GPGGA,113258,3238.9148,N,10822.4466,W,2,08,1.1,1577.4,M,-24.6,M,,*4D",
           "$GPGGA,113302,3238.9133,N,10822.4528,W,2,08,1.1,1579.0,M,-24.6,M,,*4E",
           "$GPGSA,A,3,02,05,11,12,18,20,25,29,,,,,1.4,1.1,0.9*3D",
           "$PGRME,7.6,M,41.7,M,42.4,M*2F",
           "$PGRME,7.7,M,43.0,M,43.7,M*29",
       }) {
    EXPECT_EQ(reencode(s, fmt), std::string(s) + "\r\n");
  }
}

TEST(NmeaGolden, GsvGroupsOfBothReceivers) {
  const std::vector<std::string> ublox{
      "$GPGSV,4,1,16,05,01,047,,10,29,224,,13,22,062,23,15,40,094,,1*65",
      "$GPGSV,4,2,16,16,25,306,30,18,68,358,39,20,63,235,37,21,35,292,,1*6B",
      "$GPGSV,4,3,16,23,58,225,,25,00,179,,26,33,265,35,27,07,316,,1*60",
      "$GPGSV,4,4,16,29,46,133,43,44,45,171,45,46,45,191,43,51,43,156,43,1*60",
      "$GLGSV,3,1,10,66,09,027,,67,56,054,40,68,55,168,44,69,08,194,21,1*79",
      "$GLGSV,3,2,10,73,13,282,27,74,10,318,13,81,09,110,16,82,51,077,39,1*7A",
      "$GLGSV,3,3,10,83,52,346,29,84,05,307,,1*72",
      "$GAGSV,3,1,10,03,44,149,40,05,42,071,39,08,08,190,,09,06,034,,7*74",
      "$GAGSV,3,2,10,13,11,292,,15,56,322,39,21,10,318,,27,24,268,26,7*75",
      "$GAGSV,3,3,10,30,14,215,16,36,08,098,,7*79",  // Galileo E1: signal ID 7
  };
  const std::vector<std::string> garmin{
      "$GPGSV,3,1,11,02,60,319,36,05,77,132,38,11,29,052,29,12,46,186,46*74",
      "$GPGSV,3,2,11,18,19,264,16,20,48,049,35,25,58,245,39,29,45,323,38*7B",
      "$GPGSV,3,3,11,06,01,064,00,13,09,132,00,15,10,164,00*41",
  };
  const auto u = gsv_groups(ublox);
  ASSERT_EQ(u.size(), 3u);
  EXPECT_EQ(u[2].signal_id, 7);
  for (const GsvGroup& g : u) EXPECT_EQ(encoded_gsv(g, Format::ublox()), g.original);
  const auto g = gsv_groups(garmin);
  ASSERT_EQ(g.size(), 1u);
  EXPECT_EQ(g[0].satellites.size(), 11u);
  EXPECT_EQ(encoded_gsv(g[0], Format::garmin()), g[0].original);
}

// ---- whole files -----------------------------------------------------------------------------

// Every sentence of a modelled type in the file is reproduced byte for byte; returns how many
// sentences of each type were checked.
std::map<std::string, int> check_whole_log(const std::string& name, const Format& fmt) {
  std::map<std::string, int> checked;
  const auto lines = read_log(name);
  for (const std::string& line : lines) {
    const std::string t = line.starts_with("$P") ? line.substr(1, 5) : type_of(line);
    const std::string again = reencode(line, fmt);
    if (again.empty()) continue;  // GSV below; GBS, PGRMV, PGRMT are not modelled
    EXPECT_EQ(again, line + "\r\n");
    ++checked[t];
  }
  for (const GsvGroup& g : gsv_groups(lines)) {
    EXPECT_EQ(encoded_gsv(g, fmt), g.original);
    ++checked["GSV groups"];
  }
  return checked;
}

TEST(NmeaGolden, WholeUbloxNeoM9nLog) {
  REQUIRE_GPSD_LOG("ublox-neo-m9n-nmea.log");
  const auto n = check_whole_log("ublox-neo-m9n-nmea.log", Format::ublox());
  // 61 epochs: one RMC, VTG, GGA, GLL, GST, ZDA, four GNGSA and four GSV groups each.
  for (const char* t : {"RMC", "VTG", "GGA", "GLL", "GST", "ZDA"}) EXPECT_EQ(n.at(t), 61) << t;
  EXPECT_EQ(n.at("GSA"), 244);
  EXPECT_EQ(n.at("GSV groups"), 244);
}

TEST(NmeaGolden, WholeGarmin15xLog) {
  REQUIRE_GPSD_LOG("garmin15x.log");
  const auto n = check_whole_log("garmin15x.log", Format::garmin());
  for (const char* t : {"RMC", "GGA", "GSA", "PGRME"}) EXPECT_EQ(n.at(t), 7) << t;
  EXPECT_EQ(n.at("GSV groups"), 7);
}

// ---- checksum and parsing --------------------------------------------------------------------

TEST(Nmea, ChecksumOfTheTextbookGga) {
  // The GGA example of NMEA 0183 primers: *47.
  EXPECT_EQ(checksum("GPGGA,123519,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,"), 0x47);
  EXPECT_EQ(checksum(""), 0);
}

TEST(Nmea, ParseSplitsFields) {
  const auto f = parse("$GPGGA,123519,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,*47\r\n");
  ASSERT_TRUE(f);
  ASSERT_EQ(f->size(), 15u);
  EXPECT_EQ((*f)[0], "GPGGA");
  EXPECT_EQ((*f)[2], "4807.038");
  EXPECT_EQ((*f)[14], "");
  EXPECT_TRUE(parse("$GPGGA,123519,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,*47"));
  EXPECT_TRUE(parse("$PGRME,7.6,M,41.7,M,42.4,M*2f")) << "lower-case hex is accepted";
}

TEST(Nmea, ParseRejectsBadChecksumAndFraming) {
  const std::string good = "$GPGSA,A,3,02,05,11,12,18,20,25,29,,,,,1.4,1.1,0.9*3D";
  ASSERT_TRUE(parse(good));
  EXPECT_FALSE(parse("$GPGSA,A,3,02,05,11,12,18,20,25,29,,,,,1.4,1.1,0.9*3E"));  // checksum
  EXPECT_FALSE(parse("$GPGSA,A,3,02,05,11,12,18,20,25,29,,,,,1.4,1.1,0.8*3D"));  // a bit flipped
  EXPECT_FALSE(parse(good.substr(1)));                                           // no '$'
  EXPECT_FALSE(parse(good.substr(0, good.size() - 3)));                          // no checksum
  EXPECT_FALSE(parse(good.substr(0, good.size() - 1)));                          // one hex digit
  EXPECT_FALSE(parse(good + "0"));                                               // three
  EXPECT_FALSE(parse(good + "\r\n\r\n"));
  EXPECT_FALSE(parse("$GPGSA,A,3,02,05,11,12,18,20,25,29,,,,,1.4,1.1,0.9*G1"));
  EXPECT_FALSE(parse("$GPG$A,A*00"));
  EXPECT_FALSE(parse("$GPGSA,A\r,3*00"));
  EXPECT_FALSE(parse(""));
  EXPECT_FALSE(parse("$*00"));
  EXPECT_TRUE(parse("$A*41"));
}

// ---- rounding --------------------------------------------------------------------------------

TEST(Nmea, LatLonRoundingCarriesIntoDegrees) {
  GllFields g;
  g.valid = true;
  g.mode = 'A';
  g.position = LatLon{12.0 + 59.999999 / 60.0, -(122.0 + 59.999999 / 60.0)};
  EXPECT_EQ(encoded(g, Format::ublox()), "$GPGLL,1300.00000,N,12300.00000,W,000000.00,A,A*79\r\n");
  g.position = LatLon{-(89.0 + 59.99996 / 60.0), 179.0 + 59.99996 / 60.0};
  EXPECT_NE(encoded(g, Format::garmin()).find("9000.0000,S,18000.0000,E,000000,A"),
            std::string::npos);
  // Just below the carry: stays in the old degree.
  g.position = LatLon{12.0 + 59.999994 / 60.0, 0.0};
  EXPECT_NE(encoded(g, Format::ublox()).find("1259.99999,N,00000.00000,E,"), std::string::npos);
  // A coordinate that rounds to zero keeps the positive hemisphere.
  g.position = LatLon{-1e-12, -1e-12};
  EXPECT_NE(encoded(g, Format::ublox()).find("0000.00000,N,00000.00000,E,"), std::string::npos);
}

TEST(Nmea, TimeRoundsAsAWholeIntoTheNextDay) {
  RmcFields r;
  r.utc = UtcTime{2020, 12, 31, 23, 59, 59.999};
  const std::string s = encoded(r, Format::ublox());
  EXPECT_EQ(s.substr(0, 17), "$GPRMC,000000.00,");
  EXPECT_NE(s.find(",010121,"), std::string::npos) << s;
  EXPECT_EQ(encoded(ZdaFields{"GP", r.utc, 0, 0}, Format::ublox()).substr(0, 34),
            "$GPZDA,000000.00,01,01,2021,00,00*");
  // Garmin's whole seconds; 12:59:59.5 rounds up through the hour.
  EXPECT_EQ(encoded(ZdaFields{"GP", UtcTime{2024, 2, 28, 12, 59, 59.5}, 0, 0}, Format::garmin())
                .substr(0, 31),
            "$GPZDA,130000,28,02,2024,00,00*");
  // 2024 is a leap year: 28 February 23:59:59.996 -> 29 February.
  EXPECT_EQ(encoded(ZdaFields{"GP", UtcTime{2024, 2, 28, 23, 59, 59.996}, 0, 0}, Format::ublox())
                .substr(0, 34),
            "$GPZDA,000000.00,29,02,2024,00,00*");
  // Never 60 seconds, and no carry when the rounding does not reach it.
  EXPECT_EQ(encoded(ZdaFields{"GP", UtcTime{2024, 1, 1, 10, 20, 59.994}, 0, 0}, Format::ublox())
                .substr(0, 17),
            "$GPZDA,102059.99,");
  EXPECT_EQ(encoded(ZdaFields{"GP", UtcTime{2024, 1, 1, 10, 20, 59.995}, 0, 0}, Format::ublox())
                .substr(0, 17),
            "$GPZDA,102100.00,");
}

TEST(Nmea, CourseRoundingTo360IsSentAsZero) {
  VtgFields v;
  v.course_true_deg = 359.996;
  v.course_magnetic_deg = -0.5;
  v.speed_mps = 1.0;
  v.mode = 'A';
  const std::string s = encoded(v, Format::ublox());
  EXPECT_EQ(s.substr(0, 24), "$GPVTG,0.00,T,359.50,M,1") << s;
}

TEST(Nmea, NoNegativeZero) {
  GgaFields g;
  g.quality = 1;
  g.alt_msl_m = -0.04;
  g.geoid_separation_m = -0.01;
  EXPECT_NE(encoded(g, Format::ublox()).find(",0.0,M,0.0,M,"), std::string::npos);
}

// ---- empty fields ---------------------------------------------------------------------------
// Expected checksums of sentences not quoted from a receiver were computed with Python:
//   functools.reduce(lambda a, c: a ^ ord(c), body, 0)

// Without a fix u-blox sends empty fields and HDOP/DOP 99.99; the sentences below are u-blox
// output quoted in public bug reports and forum threads, checksums included.
TEST(Nmea, NoFixSentencesInTheUbloxStyle) {
  GgaFields gga;
  gga.utc = UtcTime{2020, 1, 1, 18, 52, 53.0};
  gga.quality = 0;
  gga.num_sats = 0;
  gga.hdop = 99.99;
  EXPECT_EQ(encoded(gga, Format::ublox()), "$GPGGA,185253.00,,,,,0,00,99.99,,,,,,*6E\r\n");

  VtgFields vtg;
  vtg.talker = "GN";
  EXPECT_EQ(encoded(vtg, Format::ublox()), "$GNVTG,,,,,,,,,N*2E\r\n");

  GsaFields gsa;
  gsa.talker = "GN";
  gsa.pdop = gsa.hdop = gsa.vdop = 99.99;
  EXPECT_EQ(encoded(gsa, Format::ublox()), "$GNGSA,A,1,,,,,,,,,,,,,99.99,99.99,99.99,1*33\r\n");

  GsvFields gsv;  // signal ID 1, sent as 0 ("all signals") without satellites
  EXPECT_EQ(encoded(gsv, Format::ublox()), "$GPGSV,1,1,00,0*65\r\n");
  EXPECT_EQ(encoded(gsv, Format::garmin()), "$GPGSV,1,1,00*79\r\n");

  RmcFields rmc;
  rmc.talker = "GN";
  rmc.utc = UtcTime{2020, 7, 11, 16, 32, 23.91};
  EXPECT_EQ(encoded(rmc, Format::ublox()), "$GNRMC,163223.91,V,,,,,,,110720,,,N,V*13\r\n");
  const auto f = parse(encoded(rmc, Format::ublox()));
  ASSERT_TRUE(f);
  EXPECT_EQ(f->size(), 14u);

  GllFields gll;
  gll.utc = UtcTime{2020, 7, 11, 16, 32, 23.91};
  EXPECT_EQ(encoded(gll, Format::ublox()), "$GPGLL,,,,,163223.91,V,N*45\r\n");

  EXPECT_EQ(encoded(PgrmeFields{}, Format::garmin()), "$PGRME,,,,,,*4D\r\n");
  EXPECT_EQ(encoded(GstFields{}, Format::ublox()), "$GPGST,000000.00,,,,,,,*79\r\n");
}

TEST(Nmea, NonFiniteValuesGiveEmptyFields) {
  GgaFields g;
  g.position = LatLon{std::nan(""), 10.0};
  g.hdop = std::numeric_limits<double>::infinity();
  g.alt_msl_m = std::nan("");
  EXPECT_EQ(encoded(g, Format::ublox()), encoded(GgaFields{}, Format::ublox()));
}

// ---- GSV splitting ---------------------------------------------------------------------------

std::vector<Fields> split_sentences(const std::string& out) {
  std::vector<Fields> r;
  for (std::size_t start = 0; start < out.size();) {
    const std::size_t end = out.find("\r\n", start);
    EXPECT_NE(end, std::string::npos);
    if (end == std::string::npos) break;
    const auto f = parse(std::string_view(out).substr(start, end + 2 - start));
    EXPECT_TRUE(f);
    if (f) r.push_back(*f);
    start = end + 2;
  }
  return r;
}

TEST(Nmea, GsvSplitsIntoSentencesOfFour) {
  for (const std::size_t n : {0u, 1u, 4u, 5u, 8u, 13u}) {
    std::vector<GsvSatellite> sats;
    for (std::size_t i = 0; i < n; ++i)
      sats.push_back({static_cast<int>(i + 1), 45, static_cast<int>(10 * i), 40});
    for (const Format& fmt : {Format::ublox(), Format::garmin()}) {
      GsvFields f;
      f.satellites = sats;
      const auto sentences = split_sentences(encoded(f, fmt));
      const std::size_t expected = n == 0 ? 1 : (n + 3) / 4;
      ASSERT_EQ(sentences.size(), expected) << n;
      std::size_t seen = 0;
      for (std::size_t k = 0; k < sentences.size(); ++k) {
        const Fields& s = sentences[k];
        EXPECT_EQ(s[1], std::to_string(expected));
        EXPECT_EQ(s[2], std::to_string(k + 1));
        EXPECT_EQ(std::stoul(s[3]), n);
        const std::size_t in_this = std::min<std::size_t>(4, n - seen);
        EXPECT_EQ(s.size(), 4 + 4 * in_this + (fmt.system_signal_ids ? 1 : 0));
        for (std::size_t j = 0; j < in_this; ++j)
          EXPECT_EQ(std::stoi(s[4 + 4 * j]), static_cast<int>(seen + j + 1));
        seen += in_this;
      }
      EXPECT_EQ(seen, n);
    }
  }
}

TEST(Nmea, GsvUntrackedSatelliteHasEmptySnr) {
  const std::vector<GsvSatellite> sats{{7, std::nullopt, std::nullopt, std::nullopt}, {3, 5, 7, 9}};
  GsvFields f;
  f.satellites = sats;
  const std::string s = encoded(f, Format::ublox());
  EXPECT_EQ(s.substr(0, 35), "$GPGSV,1,1,02,07,,,,03,05,007,09,1*");
}

// ---- the 82-character limit ----------------------------------------------------------------

// Every sentence of `out` is framed, checksummed and at most 82 characters with CR LF.
void expect_valid_sentences(const std::string& out) {
  ASSERT_FALSE(out.empty());
  std::size_t start = 0;
  while (start < out.size()) {
    const std::size_t end = out.find("\r\n", start);
    ASSERT_NE(end, std::string::npos) << out;
    const std::string_view s = std::string_view(out).substr(start, end + 2 - start);
    EXPECT_LE(s.size(), 82u) << s;
    EXPECT_TRUE(parse(s)) << s;
    start = end + 2;
  }
}

// The widest knobs allowed (and beyond, clamped).
Format widest_format() {
  Format f;
  f.time_decimals = 9;
  f.latlon_minute_decimals = 9;
  f.dop_decimals = 9;
  f.altitude_decimals = 9;
  f.speed_decimals = 9;
  f.speed_integer_digits = 9;
  f.course_decimals = 9;
  f.course_integer_digits = 9;
  f.snr_digits = 9;
  f.gst_significant_digits = 9;
  return f;
}

TEST(Nmea, ExtremeValuesFitIn82Characters) {
  const UtcTime late{2099, 12, 31, 23, 59, 59.9994};
  const LatLon far{-89.99999, -179.99999};
  std::vector<int> prns;
  for (int i = 0; i < 14; ++i) prns.push_back(150 + i);
  std::vector<GsvSatellite> sats;
  for (int i = 0; i < 13; ++i) sats.push_back({190 + i, 90, 359, 99});

  for (const Format& fmt : {Format::ublox(), Format::garmin(), widest_format()}) {
    std::string out;
    encode(GgaFields{"GN", late, far, 5, 99, 99.99, 99999.0, -999.0, 99.9, 1023}, fmt, out);
    encode(RmcFields{"GN", late, true, far, 5000.0, 359.994, -179.99, 'R', 'U'}, fmt, out);
    encode(GsaFields{"GN", 'M', 3, prns, 99.99, 99.99, 99.99, 15}, fmt, out);
    encode(GsvFields{"GB", sats, 15}, fmt, out);
    encode(VtgFields{"GN", 359.9, 359.9, 5000.0, 'D'}, fmt, out);
    encode(GllFields{"GN", far, late, true, 'D'}, fmt, out);
    encode(GstFields{"GN", late, 999999.0, 99999.9, 0.0123, 179.9, 9.99, 999999.0, 123456.7}, fmt,
           out);
    encode(ZdaFields{"GN", late, -13, 59}, fmt, out);
    encode(PgrmeFields{99999.9, 99999.9, 99999.9}, fmt, out);
    expect_valid_sentences(out);
  }
  // The u-blox style keeps what fits: exactly 82 characters with a 5-digit altitude...
  std::string gga;
  encode(GgaFields{"GN", late, far, 2, 12, 0.54, 99999.0, -29.5, std::nullopt, 0}, Format::ublox(),
         gga);
  EXPECT_EQ(gga,
            "$GNGGA,000000.00,8959.99940,S,17959.99940,W,2,12,0.54,99999.0,M,-29.5,M,,0000*68\r\n");
  // ... and with a DGPS age too, the altitude and then the age lose their decimal.
  gga.clear();
  encode(GgaFields{"GN", late, far, 2, 12, 0.54, 99999.0, -29.5, 1.0, 0}, Format::ublox(), gga);
  EXPECT_EQ(gga,
            "$GNGGA,000000.00,8959.99940,S,17959.99940,W,2,12,0.54,99999,M,-29.5,M,1,0000*47\r\n");
  // Twelve 3-digit PRNs: the DOPs lose decimals, VDOP first.
  std::vector<int> twelve(prns.begin(), prns.begin() + 12);
  std::string gsa12;
  encode(GsaFields{"GN", 'A', 3, twelve, 99.99, 99.99, 99.99, 1}, Format::ublox(), gsa12);
  EXPECT_EQ(gsa12,
            "$GNGSA,A,3,150,151,152,153,154,155,156,157,158,159,160,161,99.99,99.99,100,1*2E\r\n");
  // Twelve of the 14 PRNs are sent.
  std::string gsa;
  encode(GsaFields{"GN", 'A', 3, prns, 1.5, 0.9, 1.2, 1}, Format::ublox(), gsa);
  EXPECT_EQ(parse(gsa)->at(14), "161");
  EXPECT_EQ(parse(gsa)->at(15), "1.50");
}

TEST(Nmea, ExtremeValuesAreClamped) {
  std::string out;
  encode(GgaFields{"GPX", {}, LatLon{123.0, -500.0}, 42, 1000, 1e9, -1e9, 1e9, 1e9, 99999},
         Format::garmin(), out);
  EXPECT_EQ(out,
            "$GPGGA,000000,9000.0000,N,18000.0000,W,9,99,100.0,-9999.0,M,999.0,M,99.9,1023*6A\r\n");
}

// Random values, including non-finite and absurd ones, with random knobs: every sentence is
// well formed and within 82 characters.
TEST(Nmea, RandomValuesWithRandomFormatsFit) {
  std::mt19937_64 rng(20240501);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const auto value = [&]() -> std::optional<double> {
    const double u = unit(rng);
    if (u < 0.05) return std::nullopt;
    if (u < 0.08) return std::nan("");
    if (u < 0.10) return -std::numeric_limits<double>::infinity();
    const double mag = std::pow(10.0, 14.0 * unit(rng) - 6.0);
    return unit(rng) < 0.3 ? -mag : mag;
  };
  const auto integer = [&] { return static_cast<int>(rng() % 3000) - 1000; };
  const auto knob = [&] { return static_cast<int>(rng() % 12) - 2; };
  for (int trial = 0; trial < 3000; ++trial) {
    Format fmt;
    fmt.time_decimals = knob();
    fmt.latlon_minute_decimals = knob();
    fmt.dop_decimals = knob();
    fmt.altitude_decimals = knob();
    fmt.speed_decimals = knob();
    fmt.speed_integer_digits = knob();
    fmt.course_decimals = knob();
    fmt.course_integer_digits = knob();
    fmt.snr_digits = knob();
    fmt.gst_significant_digits = knob();
    fmt.gga_sats_two_digits = rng() % 2 == 0;
    fmt.mode_indicator = rng() % 2 == 0;
    fmt.nav_status = rng() % 2 == 0;
    fmt.system_signal_ids = rng() % 2 == 0;
    const UtcTime t{integer(), integer(), integer(), integer(), integer(), value().value_or(0.0)};
    const LatLon p{value().value_or(0.0), value().value_or(0.0)};
    std::vector<int> prns;
    for (int i = integer() % 20; i > 0; --i) prns.push_back(integer());
    std::vector<GsvSatellite> sats;
    for (int i = std::abs(integer()) % 110; i > 0; --i)
      sats.push_back({integer(), integer(), integer(), integer()});
    std::string out;
    encode(
        GgaFields{"GN", t, p, integer(), integer(), value(), value(), value(), value(), integer()},
        fmt, out);
    encode(RmcFields{"GN", t, true, p, value(), value(), value(), 'A', 'S'}, fmt, out);
    encode(GsaFields{"GN", 'A', integer(), prns, value(), value(), value(), integer()}, fmt, out);
    encode(GsvFields{"GP", sats, integer()}, fmt, out);
    encode(VtgFields{"GN", value(), value(), value(), 'A'}, fmt, out);
    encode(GllFields{"GN", p, t, true, 'A'}, fmt, out);
    encode(GstFields{"GN", t, value(), value(), value(), value(), value(), value(), value()}, fmt,
           out);
    encode(ZdaFields{"GN", t, integer(), integer()}, fmt, out);
    encode(PgrmeFields{value(), value(), value()}, fmt, out);
    expect_valid_sentences(out);
    if (HasFailure()) {
      ADD_FAILURE() << "trial " << trial;
      return;
    }
  }
}

}  // namespace
}  // namespace navemu::nmea
