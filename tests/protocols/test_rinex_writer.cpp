// RINEX 3.04 observation writer: round trip through the reader, fixed-column layout against
// hand-written records (RINEX 3.04 appendix, observation header and data record
// descriptions), and RTKLIB (rnx2rtkp) positioning from a written file.

#include <gtest/gtest.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/time.hpp"
#include "core/vec.hpp"
#include "protocols/rinex.hpp"
#include "protocols/rinex_writer.hpp"
#include "tests/test_support.hpp"

namespace navemu {
namespace {

GpsTime gps(int y, int mo, int d, int h, int mi, double s) {
  return gps_from_calendar(CalendarTime{y, mo, d, h, mi, s});
}

SatObs sat(char sys, int number, std::vector<double> values) {
  SatObs s;
  s.system = sys;
  s.number = number;
  s.lli.assign(values.size(), 0);
  s.ssi.assign(values.size(), 0);
  s.values = std::move(values);
  return s;
}

std::string write(const ObsHeader& h, const std::vector<ObsEpoch>& epochs,
                  const ObsWriterInfo& info = {}) {
  std::ostringstream out;
  write_rinex3_obs(out, h, epochs, info);
  return out.str();
}

ObsData read_back(const std::string& text) {
  std::istringstream in(text);
  return parse_rinex_obs(in, "written.obs");
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  return lines;
}

// GPS with C1C L1C D1C S1C C2W L2W, three epochs 1 s apart; some values missing, LLI and SSI
// on one phase value.
struct GpsFixture {
  ObsHeader header;
  std::vector<ObsEpoch> epochs;

  GpsFixture() {
    header.types['G'] = {"C1C", "L1C", "D1C", "S1C", "C2W", "L2W"};
    header.marker_name = "NAVEMU TEST";
    header.approx_position_ecef_m = Vec3(-3976219.1454, 3382371.6073, 3652511.1964);
    header.antenna_delta_hen_m = Vec3(0.1234, 0.0, -0.05);
    header.interval_s = 1.0;
    header.leap_seconds = 13;
    for (int k = 0; k < 3; ++k) {
      ObsEpoch e;
      e.time = gps(2005, 4, 2, 0, 0, 30.0 + k);
      const double dk = k;
      e.sats.push_back(sat('G', 5, {23619095.450 + 800.0 * dk, 124121298.172 + 4200.0 * dk,
                                    -1234.567, 45.0, 23619098.0 + 800.0 * dk,
                                    96717892.5 + 3270.0 * dk}));
      e.sats.push_back(sat('G', 12, {20000000.125 - 100.0 * dk, kMissing, 321.5, 38.25, kMissing,
                                     kMissing}));
      epochs.push_back(std::move(e));
    }
    epochs[0].sats[0].lli[1] = 1;  // G05 L1C: loss of lock
    epochs[0].sats[0].ssi[1] = 7;
    epochs[1].receiver_clock_offset_s = -1.25e-4;
  }
};

TEST(RinexWriter, RoundTripThroughReader) {
  const GpsFixture fx;
  const std::string text = write(fx.header, fx.epochs);
  const ObsData d = read_back(text);

  EXPECT_DOUBLE_EQ(d.header.version, 3.04);
  EXPECT_EQ(d.header.file_system, 'G');
  EXPECT_EQ(d.header.time_system, 'G');
  EXPECT_EQ(d.header.types, fx.header.types);
  EXPECT_EQ(d.header.marker_name, "NAVEMU TEST");
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(d.header.approx_position_ecef_m[k], fx.header.approx_position_ecef_m[k], 1e-4);
    EXPECT_NEAR(d.header.antenna_delta_hen_m[k], fx.header.antenna_delta_hen_m[k], 1e-4);
  }
  EXPECT_DOUBLE_EQ(d.header.interval_s, 1.0);
  ASSERT_TRUE(d.header.leap_seconds.has_value());
  EXPECT_EQ(*d.header.leap_seconds, 13);
  EXPECT_TRUE(d.warnings.empty());

  // TIME OF FIRST OBS: 5I6,F13.7,5X,A3 with time system GPS in columns 49-51.
  bool found_first = false;
  for (const std::string& l : lines_of(text)) {
    if (l.size() > 60 && l.substr(60) == "TIME OF FIRST OBS") {
      found_first = true;
      EXPECT_EQ(l.substr(0, 60), "  2005     4     2     0     0   30.0000000     GPS         ");
    }
  }
  EXPECT_TRUE(found_first);

  ASSERT_EQ(d.epochs.size(), fx.epochs.size());
  for (std::size_t e = 0; e < d.epochs.size(); ++e) {
    const ObsEpoch& got = d.epochs[e];
    const ObsEpoch& want = fx.epochs[e];
    EXPECT_EQ(got.time, want.time) << "epoch " << e;
    EXPECT_EQ(got.flag, 0);
    EXPECT_NEAR(got.receiver_clock_offset_s, want.receiver_clock_offset_s, 1e-12);
    ASSERT_EQ(got.sats.size(), want.sats.size());
    for (std::size_t s = 0; s < got.sats.size(); ++s) {
      const SatObs& g = got.sats[s];
      const SatObs& w = want.sats[s];
      EXPECT_EQ(g.system, w.system);
      EXPECT_EQ(g.number, w.number);
      ASSERT_EQ(g.values.size(), w.values.size());
      for (std::size_t k = 0; k < g.values.size(); ++k) {
        if (std::isnan(w.values[k])) {
          EXPECT_TRUE(std::isnan(g.values[k])) << "epoch " << e << " sat " << s << " type " << k;
        } else {
          EXPECT_NEAR(g.values[k], w.values[k], 1e-3) << "epoch " << e << " sat " << s << " type " << k;
        }
      }
      EXPECT_EQ(g.lli, w.lli);
      EXPECT_EQ(g.ssi, w.ssi);
    }
  }
}

TEST(RinexWriter, ByteIdenticalAndColumnLayout) {
  const GpsFixture fx;
  ObsWriterInfo info;
  info.run_by = "tests";
  info.date = "20050402 000000 UTC";
  info.comments = {"identical input, identical bytes"};
  const std::string a = write(fx.header, fx.epochs, info);
  const std::string b = write(fx.header, fx.epochs, info);
  EXPECT_EQ(a, b);

  const std::vector<std::string> lines = lines_of(a);
  ASSERT_FALSE(lines.empty());
  // Header records: content in columns 1-60, label in 61-80; END OF HEADER closes it.
  std::size_t end = 0;
  for (; end < lines.size(); ++end) {
    const std::string& l = lines[end];
    ASSERT_GT(l.size(), 60u) << l;
    ASSERT_LE(l.size(), 80u) << l;
    if (l.substr(60) == "END OF HEADER") break;
  }
  ASSERT_LT(end, lines.size());
  EXPECT_EQ(lines[0],
            "     3.04           OBSERVATION DATA    G                   RINEX VERSION / TYPE");
  EXPECT_EQ(lines[1],
            "navemu              tests               20050402 000000 UTC PGM / RUN BY / DATE");
  std::set<std::string> labels;
  for (std::size_t i = 0; i <= end; ++i) labels.insert(lines[i].substr(60));
  for (const char* label :
       {"COMMENT", "MARKER NAME", "MARKER TYPE", "OBSERVER / AGENCY", "REC # / TYPE / VERS",
        "ANT # / TYPE", "APPROX POSITION XYZ", "ANTENNA: DELTA H/E/N", "SYS / # / OBS TYPES",
        "SIGNAL STRENGTH UNIT", "INTERVAL", "TIME OF FIRST OBS", "SYS / PHASE SHIFT",
        "LEAP SECONDS"})
    EXPECT_EQ(labels.count(label), 1u) << label;
  EXPECT_EQ(labels.count("GLONASS COD/PHS/BIS"), 0u);  // no GLONASS in this file

  const auto record = [&](const std::string& label) {
    std::vector<std::string> out;
    for (std::size_t i = 0; i <= end; ++i)
      if (lines[i].substr(60) == label) out.push_back(lines[i]);
    return out;
  };
  EXPECT_EQ(record("SYS / # / OBS TYPES").at(0),
            "G    6 C1C L1C D1C S1C C2W L2W                              SYS / # / OBS TYPES");
  EXPECT_EQ(record("SIGNAL STRENGTH UNIT").at(0),
            "DBHZ                                                        SIGNAL STRENGTH UNIT");
  EXPECT_EQ(record("MARKER TYPE").at(0),
            "NON_GEODETIC                                                MARKER TYPE");
  EXPECT_EQ(record("APPROX POSITION XYZ").at(0),
            " -3976219.1454  3382371.6073  3652511.1964                  APPROX POSITION XYZ");
  EXPECT_EQ(record("INTERVAL").at(0),
            "     1.000                                                  INTERVAL");
  EXPECT_EQ(record("LEAP SECONDS").at(0),
            "    13                                                      LEAP SECONDS");
  const std::vector<std::string> shifts = record("SYS / PHASE SHIFT");
  ASSERT_EQ(shifts.size(), 2u);
  EXPECT_EQ(shifts[0], "G L1C  0.00000                                              SYS / PHASE SHIFT");
  EXPECT_EQ(shifts[1], "G L2W  0.00000                                              SYS / PHASE SHIFT");

  // First epoch record: A1,1X,I4,4(1X,I2.2),F11.7,2X,I1,I3 (receiver clock offset blank),
  // then G05: A1,I2.2, m(F14.3,I1,I1), trailing blanks not written.
  ASSERT_GT(lines.size(), end + 3);
  EXPECT_EQ(lines[end + 1], "> 2005 04 02 00 00 30.0000000  0  2");
  EXPECT_EQ(lines[end + 2],
            "G05  23619095.450   124121298.17217     -1234.567          45.000    23619098.000    "
            "96717892.500");
  EXPECT_EQ(lines[end + 3], "G12  20000000.125                         321.500          38.250");
  // The second epoch carries the receiver clock offset, F15.12 in columns 42-56.
  EXPECT_EQ(lines[end + 4], "> 2005 04 02 00 00 31.0000000  0  2      -0.000125000000");
}

TEST(RinexWriter, MixedSystemsSortedAndContinuationLines) {
  ObsHeader h;
  h.types['G'] = {"C1C", "L1C", "D1C", "S1C", "C2W", "L2W", "D2W", "S2W",
                  "C5Q", "L5Q", "D5Q", "S5Q", "C2L", "L2L", "S2L"};  // 15: one continuation
  h.types['R'] = {"C1C", "L1C", "S1C"};
  h.types['S'] = {"C1C", "S1C"};  // no phase: a bare SYS / PHASE SHIFT record
  h.marker_name = "MIXED";
  ObsEpoch e;
  e.time = gps(2023, 1, 8, 9, 59, 42.5);
  std::vector<double> g15(15, kMissing);
  g15[0] = 21000000.0;
  g15[14] = 44.0;
  e.sats.push_back(sat('R', 7, {19100000.0, 102000000.0, 40.0}));
  e.sats.push_back(sat('G', 12, g15));
  e.sats.push_back(sat('E', 11, {1.0}));  // no Galileo types: left out
  e.sats.push_back(sat('G', 5, g15));
  e.sats.push_back(sat('S', 20, {38000000.0, 41.0}));
  ObsWriterInfo info;
  info.glonass_frequency_numbers = {{7, 5}, {1, 1}};
  const std::string text = write(h, {e}, info);

  const ObsData d = read_back(text);
  EXPECT_EQ(d.header.file_system, 'M');
  EXPECT_EQ(d.header.types, h.types);
  ASSERT_EQ(d.epochs.size(), 1u);
  EXPECT_EQ(d.epochs[0].time, e.time);
  std::vector<std::string> ids;
  for (const SatObs& s : d.epochs[0].sats) ids.push_back(fmt::format("{}{:02d}", s.system, s.number));
  EXPECT_EQ(ids, (std::vector<std::string>{"G05", "G12", "R07", "S20"}));
  EXPECT_NEAR(d.epochs[0].sats[1].values[14], 44.0, 1e-9);
  EXPECT_TRUE(d.warnings.empty());

  const std::vector<std::string> lines = lines_of(text);
  const auto has = [&](const std::string& l) {
    return std::find(lines.begin(), lines.end(), l) != lines.end();
  };
  EXPECT_TRUE(has("G   15 C1C L1C D1C S1C C2W L2W D2W S2W C5Q L5Q D5Q S5Q C2L  SYS / # / OBS TYPES"));
  EXPECT_TRUE(has("       L2L S2L                                              SYS / # / OBS TYPES"));
  EXPECT_TRUE(has("G L5Q  0.00000                                              SYS / PHASE SHIFT"));
  EXPECT_TRUE(has("S                                                           SYS / PHASE SHIFT"));
  EXPECT_TRUE(has("  2 R01  1 R07  5                                           GLONASS SLOT / FRQ #"));
  EXPECT_TRUE(has(" C1C    0.000 C1P    0.000 C2C    0.000 C2P    0.000        GLONASS COD/PHS/BIS"));
  EXPECT_TRUE(has("> 2023 01 08 09 59 42.5000000  0  4"));
}

// Runs the writer expecting std::invalid_argument whose message contains every `needle`;
// the stream must stay empty.
void expect_invalid(const ObsHeader& h, const std::vector<ObsEpoch>& epochs,
                    const std::vector<std::string>& needles, const ObsWriterInfo& info = {}) {
  std::ostringstream out;
  try {
    write_rinex3_obs(out, h, epochs, info);
    ADD_FAILURE() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& ex) {
    for (const std::string& n : needles)
      EXPECT_NE(std::string(ex.what()).find(n), std::string::npos) << ex.what() << " lacks " << n;
  }
  EXPECT_TRUE(out.str().empty());
}

TEST(RinexWriter, RejectsWhatTheColumnsCannotHold) {
  GpsFixture fx;
  // F14.3 holds 9999999999.999 and -999999999.999; beyond that the columns would shift.
  fx.epochs[1].sats[0].values[0] = 9999999999.999;
  fx.epochs[1].sats[1].values[0] = -999999999.999;
  EXPECT_NO_THROW(write(fx.header, fx.epochs));

  GpsFixture big;
  big.epochs[2].sats[0].values[4] = 1.0e10;
  expect_invalid(big.header, big.epochs, {"G05", "C2W", "F14.3"});
  GpsFixture neg;
  neg.epochs[0].sats[1].values[2] = -1.0e9;
  expect_invalid(neg.header, neg.epochs, {"G12", "D1C"});
  GpsFixture inf;
  inf.epochs[0].sats[1].values[3] = std::numeric_limits<double>::infinity();
  expect_invalid(inf.header, inf.epochs, {"G12", "S1C"});
  GpsFixture lli;
  lli.epochs[0].sats[0].lli[1] = 12;
  expect_invalid(lli.header, lli.epochs, {"G05", "L1C", "LLI"});
  GpsFixture flag;
  flag.epochs[1].flag = 4;
  expect_invalid(flag.header, flag.epochs, {"epoch flag 4"});
  GpsFixture count;
  count.epochs[0].sats[0].values.pop_back();
  expect_invalid(count.header, count.epochs, {"G05", "5 values", "6 types"});
  GpsFixture dup;
  dup.epochs[0].sats[1].number = 5;
  expect_invalid(dup.header, dup.epochs, {"G05", "twice"});
  GpsFixture name;
  name.header.marker_name = std::string(61, 'x');
  expect_invalid(name.header, name.epochs, {"MARKER NAME", "60 columns"});
  GpsFixture code;
  code.header.types['G'][0] = "C1";
  expect_invalid(code.header, code.epochs, {"SYS / # / OBS TYPES", "'C1'"});
  expect_invalid(GpsFixture().header, {}, {"no epochs"});
}

TEST(RinexWriter, LongCommentsWrap) {
  const GpsFixture fx;
  ObsWriterInfo info;
  info.comments = {std::string(50, 'a') + " " + std::string(30, 'b'), "two\nlines"};
  const std::vector<std::string> lines = lines_of(write(fx.header, fx.epochs, info));
  std::vector<std::string> comments;
  for (const std::string& l : lines)
    if (l.size() > 60 && l.substr(60) == "COMMENT") comments.push_back(l.substr(0, 60));
  ASSERT_EQ(comments.size(), 4u);
  EXPECT_EQ(comments[0], std::string(50, 'a') + std::string(10, ' '));
  EXPECT_EQ(comments[1], std::string(30, 'b') + std::string(30, ' '));
  EXPECT_EQ(comments[2].substr(0, 4), "two ");
  EXPECT_EQ(comments[3].substr(0, 6), "lines ");
}

}  // namespace
}  // namespace navemu
