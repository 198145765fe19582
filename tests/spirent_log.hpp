#pragma once
// The truth log of a commercial GNSS RF simulator (Spirent SimGEN) for a static receiver:
// ../shared/data/gnss/spirent_simgen_static_20230108/klobuchar_saastamoinen/sat_data_V1A1.csv
// (../shared/data/README.md section 1c), read once for the tests that compare against it.
//
// Layout: 5 header rows; row 2 holds the scenario start "GPS Time" (seconds since the GPS
// epoch), row 5 the column names; then one row per channel and epoch, every constellation,
// with Time_ms counting milliseconds from the start.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "models/geodesy.hpp"
#include "core/time.hpp"
#include "tests/test_support.hpp"

namespace navemu::test {

// The scenario's static antenna, 30 N, 95 E, 0 m ellipsoidal (exact simulator inputs), and
// its ECEF coordinates as given in ../shared/data/README.md 1c.
inline const Geodetic kSpirentRx{30.0, 95.0, 0.0};
inline const Vec3 kSpirentRxEcef{-481819.31349724, 5507219.95375401, 3170373.73538364};

struct SpirentRow {
  GpsTime t_receive;   // scenario start + Time_ms, exact in integer milliseconds
  std::string system;  // Sat_type: "GPS", "GALILEO", "GLONASS", "BeiDou", ...
  int prn = 0;         // Sat_PRN
  Vec3 p_ecef_m = Vec3::Zero();    // Sat_Pos_X/Y/Z
  Vec3 v_ecef_mps = Vec3::Zero();  // Sat_Vel_X/Y/Z
  double az_rad = 0.0;             // Azimuth, in (-pi, pi]
  double el_rad = 0.0;             // Elevation (rounded to 1e-4 rad in the log)
  double range_m = 0.0;            // Range
  double prange_l1_m = 0.0;        // P-Range Group A (GPS L1)
  double iono_l1_s = 0.0;          // Iono_delay Group A (GPS L1), seconds
  double tropo_s = 0.0;            // Tropo_delay, seconds
};

inline std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  for (std::string cell; std::getline(ss, cell, ',');) out.push_back(cell);
  return out;
}

inline std::filesystem::path spirent_log_path() {
  return shared_data(
      "gnss/spirent_simgen_static_20230108/klobuchar_saastamoinen/sat_data_V1A1.csv");
}

// Every row of the log, all constellations.
inline std::vector<SpirentRow> read_spirent_rows(
    const std::filesystem::path& path = spirent_log_path()) {
  std::ifstream in(path);
  EXPECT_TRUE(in.good()) << path;
  std::array<std::string, 5> header;
  for (auto& h : header) std::getline(in, h);
  const std::int64_t start_ms = std::llround(std::stod(split_csv(header[1]).at(1)) * 1e3);
  const auto names = split_csv(header[4]);
  std::map<std::string, std::size_t> col;
  for (std::size_t i = 0; i < names.size(); ++i) col[names[i]] = i;

  std::vector<SpirentRow> rows;
  for (std::string line; std::getline(in, line);) {
    const auto f = split_csv(line);
    if (f.size() < names.size() - 1) continue;  // blank or short line
    auto text = [&](const char* name) -> const std::string& { return f.at(col.at(name)); };
    auto num = [&](const char* name) { return std::stod(text(name)); };
    SpirentRow r;
    r.t_receive = GpsTime{(start_ms + std::stoll(text("Time_ms"))) * 1'000'000};
    r.system = text("Sat_type");
    r.prn = std::stoi(text("Sat_PRN"));
    r.p_ecef_m = Vec3(num("Sat_Pos_X"), num("Sat_Pos_Y"), num("Sat_Pos_Z"));
    r.v_ecef_mps = Vec3(num("Sat_Vel_X"), num("Sat_Vel_Y"), num("Sat_Vel_Z"));
    r.az_rad = num("Azimuth");
    r.el_rad = num("Elevation");
    r.range_m = num("Range");
    r.prange_l1_m = num("P-Range Group A");
    r.iono_l1_s = num("Iono_delay Group A");
    r.tropo_s = num("Tropo_delay");
    rows.push_back(r);
  }
  return rows;
}

// The GPS rows only (465 of them, per ../shared/data/README.md).
inline std::vector<SpirentRow> read_spirent_gps_rows(
    const std::filesystem::path& path = spirent_log_path()) {
  std::vector<SpirentRow> gps;
  for (SpirentRow& r : read_spirent_rows(path))
    if (r.system == "GPS") gps.push_back(std::move(r));
  return gps;
}

}  // namespace navemu::test
