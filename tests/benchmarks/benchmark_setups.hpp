#pragma once
// Set-ups the GNSS and engine benchmarks share: the scenario start, a u-blox F9P as a
// navigation client configures it, and the urban scene.

#include <filesystem>

#include "emulator/run_config.hpp"
#include "core/time.hpp"

namespace navemu::bench {

// The paper's day and hour (configs/mission/high.yaml), as BM_SimulateOneHour has always used.
inline GpsTime scenario_start() { return parse_time("2010-11-17T13:00:00Z"); }

inline std::filesystem::path configs_dir() { return default_run_config().parent_path(); }

// The ublox-f9p profile after a client set it up for navigation and raw data (the profile
// itself powers up with NMEA only): 5 Hz (CFG-RATE) and NAV-PVT, NAV-DOP, NAV-SAT, NAV-EOE,
// RXM-RAWX, RXM-SFRBX every epoch (CFG-MSG), NMEA kept on unless `nmea` is false.
inline GnssProfile ublox_f9p_configured(bool nmea = true) {
  GnssProfile p = load_gnss_profile("ublox-f9p");
  p.rate_hz = 5.0;
  p.ubx->messages = {{"NAV-PVT", 1}, {"NAV-DOP", 1},  {"NAV-SAT", 1},
                     {"NAV-EOE", 1}, {"RXM-RAWX", 1}, {"RXM-SFRBX", 1}};
  p.ubx->nmea_out = nmea;
  return p;
}

// The urban scene: the generated city of the paper's mission (configs/mission/city.obj, `navemu
// scene city --seed 1`: 8 x 8 blocks of 100 m, 20 m streets centred on x = 0 and y = 0,
// buildings 6..30 m), its origin at street level at the paper's site, first-order reflections.
inline Geodetic city_origin() { return Geodetic{32.3, -90.9, 60.0}; }
inline SceneSpec mission_city() {
  SceneSpec s;
  s.obj = (configs_dir() / "mission" / "city.obj").string();
  s.materials = (configs_dir() / "scenes" / "materials.yaml").string();
  s.origin = city_origin();
  s.max_order = 1;
  return s;
}

}  // namespace navemu::bench
