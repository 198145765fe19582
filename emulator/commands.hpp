#pragma once
// The navemu subcommands. Each registers its options on the CLI11 app and returns the
// callback-free options struct the run function takes.

#include <CLI/CLI.hpp>
#include <iosfwd>
#include <optional>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "models/ephemeris.hpp"
#include "models/geodesy.hpp"
#include "core/time.hpp"

namespace navemu {

// Comma-separated finite numbers, one per name; InputError naming `field` and the expected
// `form` otherwise.
std::vector<double> parse_numbers(const std::string& text, const std::string& field,
                                  const std::vector<std::string>& names, const char* form);

// Checks of numeric options whose messages show the value as given and the bounds in plain
// notation (CLI11's own let NaN through and print the largest double in 309 digits): a finite
// number, inside [min, max], above 0, or not negative.
CLI::Validator number_between(double min, double max);
CLI::Validator positive_number();
CLI::Validator non_negative_number();

// "LAT,LON,H" in degrees, degrees and metres above the ellipsoid; InputError otherwise.
Geodetic parse_geodetic(const std::string& text, const std::string& field);

// The system clock as GPS time, to the nanosecond.
GpsTime gps_now();

// A --time/--start value: ISO-8601 UTC, GPS WEEK:TOW, or "now" (the system clock, whole
// seconds).
GpsTime time_option(const std::string& text, const std::string& field);

// The navigation data to use: the RINEX file when given, otherwise the built-in nominal
// constellations of `systems` (system_bit) around `t`.
NavData load_nav_or_nominal(const std::string& nav_file, GpsTime t,
                            std::uint32_t systems = system_bit(GnssSystem::kGps));

// What a user changes when navigation data do not cover the scenario: the option naming the
// file (reported as the field), the scenario's start (its names, and the flag to give an example
// with) and its duration (null: none to shorten).
struct ScenarioOptions {
  const char* nav = "--nav";
  const char* start = "--start";
  const char* start_flag = "--start";
  const char* duration = "--duration";
};

// Unless `nav` has data for `min_satellites` satellites inside their fit intervals over all of
// [from, to] (models/ephemeris.hpp covered_spans), an InputError of one line: the file, the
// intervals it covers and the scenario's (ISO UTC and GPS week:TOW), and how to fix it (a start
// inside the file's interval, a shorter duration, or a navigation file for the date).
void require_nav_coverage(const NavData& nav, GpsTime from, GpsTime to,
                          const ScenarioOptions& options,
                          int min_satellites = kSatellitesForFix);

// The navigation data of `navemu run` / `simulate` (scenario.nav, or the built-in constellation,
// which never runs out), checked to give a fix over [start, start + duration]. Without a
// duration (a run until stopped) only the start is checked, and `log` is told until when the
// file lasts.
void check_scenario_nav(const NavData& nav, GpsTime start, std::optional<double> duration_s,
                        std::ostream& log);
// load_nav_or_nominal(), then check_scenario_nav().
NavData load_scenario_nav(const std::string& nav_file, GpsTime start, std::optional<double> duration_s,
                          std::ostream& log);

struct SkyOptions {
  std::string nav_file;  // empty: built-in constellation
  bool nominal = false;
  std::string time = "now";
  std::string at = "32.3,-90.9,60";  // the paper's test site, Vicksburg, MS
  double mask_deg = 5.0;
};
void add_sky_command(CLI::App& app, SkyOptions& opt);
int run_sky(const SkyOptions& opt, std::ostream& out, std::ostream& err);

struct SppOptions {
  std::string obs_file;
  std::string nav_file;
  double mask_deg = 15.0;
  std::vector<std::string> systems{"G", "R", "E", "C", "J"};  // RINEX letters
  std::string iono = "klobuchar";
  std::string tropo = "saastamoinen";
  std::string residuals_file;  // empty: none
  bool raim = true;            // the residual test with exclusion (SolverOptions::raim)
};
void add_spp_command(CLI::App& app, SppOptions& opt);
int run_spp(const SppOptions& opt, std::ostream& out, std::ostream& err);

struct ObsOptions {
  std::string nav_file;  // empty: built-in constellation
  std::vector<std::string> systems{"G"};  // RINEX letters
  bool nominal = false;
  std::string at = "32.3,-90.9,60";
  std::string start;
  double duration_s = 3600.0;
  double interval_s = 30.0;
  std::string out_file;
  std::string mode = "standalone";
  std::string receiver = "consumer";
  std::optional<double> sisre_m;  // broadcast orbit/clock accuracy; unset: the model default
  std::string sat_errors = "gauss-markov";
  std::optional<double> clock_h0, clock_h_minus2;
  std::uint64_t seed = 1;
  std::vector<std::string> disable;  // error sources switched off
  std::string iono = "klobuchar";
  double vtec_tecu = 12.0;
  std::optional<double> pressure_hpa, temperature_c, humidity;
};
void add_obs_command(CLI::App& app, ObsOptions& opt);
int run_obs(const ObsOptions& opt, std::ostream& out, std::ostream& err);

// IMU commands (emulator/imu_command.cpp, allan_command.cpp, deadreckon_command.cpp). Each
// options struct is owned by its file's add_* function, which may add fields.
struct ImuOptions;
struct AllanOptions;
struct RunOptions;
struct DeadreckonOptions;
std::shared_ptr<ImuOptions> add_imu_command(CLI::App& app);
int run_imu(const ImuOptions& opt, std::ostream& out, std::ostream& err);
std::shared_ptr<AllanOptions> add_allan_command(CLI::App& app);
int run_allan(const AllanOptions& opt, std::ostream& out, std::ostream& err);
std::shared_ptr<DeadreckonOptions> add_deadreckon_command(CLI::App& app);
int run_deadreckon(const DeadreckonOptions& opt, std::ostream& out, std::ostream& err);
// navemu scene: synthetic 3D scenes as OBJ files (emulator/scene_command.cpp).
struct SceneOptions;
std::shared_ptr<SceneOptions> add_scene_command(CLI::App& app);
int run_scene(const SceneOptions& opt, std::ostream& out, std::ostream& err);
// navemu run (real time) and navemu simulate (offline), emulator/run_command.cpp.
std::shared_ptr<RunOptions> add_run_command(CLI::App& app);
std::shared_ptr<RunOptions> add_simulate_command(CLI::App& app);
int run_run(const RunOptions& opt, std::ostream& out, std::ostream& err);
// navemu ctl: live-control commands to a running navemu (emulator/ctl_command.cpp).
struct CtlOptions;
std::shared_ptr<CtlOptions> add_ctl_command(CLI::App& app);
int run_ctl(const CtlOptions& opt, std::ostream& out, std::ostream& err);
// navemu profiles: the profiles and ready scenarios, one line each (emulator/profiles_command.cpp).
int run_profiles(std::ostream& out);

}  // namespace navemu
