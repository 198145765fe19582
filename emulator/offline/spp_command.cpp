// navemu spp: single-point positioning on a real RINEX observation file (single-frequency
// code of GPS, GLONASS, Galileo, BeiDou and QZSS).

#include <fmt/format.h>
#include <fmt/ostream.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <ostream>

#include "emulator/commands.hpp"
#include "core/errors.hpp"
#include "emulator/rinex_files.hpp"
#include "models/solver.hpp"

namespace navemu {

namespace {

// The systems `navemu spp` solves with, as RINEX letters (RINEX 3.05 section 3.5).
constexpr std::array<GnssSystem, 5> kSppSystems{GnssSystem::kGps, GnssSystem::kGlonass,
                                                GnssSystem::kGalileo, GnssSystem::kBeidou,
                                                GnssSystem::kQzss};

// The single-frequency code observation used per system, in order of preference (RINEX 3.05
// Tables 4-8): GPS and QZSS L1 C/A; GLONASS L1 C/A then P; Galileo E1 C then B+C; BeiDou B1I
// (band 2 since RINEX 3.02, band 1 in 3.00/3.01). RINEX 2 files name only the band (C1).
std::vector<std::string> code_preference(GnssSystem system, double version) {
  if (version < 3.0) return {"C1"};
  switch (system) {
    case GnssSystem::kGlonass: return {"C1C", "C1P"};
    case GnssSystem::kGalileo: return {"C1C", "C1X"};
    case GnssSystem::kBeidou:
      return version < 3.02 ? std::vector<std::string>{"C1I"}
                            : std::vector<std::string>{"C2I", "C2X"};
    default: return {"C1C"};
  }
}

// Where a system's pseudorange and Doppler are in its observation list.
struct SystemColumns {
  std::string code;       // the observation code used ("C1C")
  int code_index = -1;    // -1: the system is not solved with
  int doppler_index = -1;
};

}  // namespace

void add_spp_command(CLI::App& app, SppOptions& opt) {
  CLI::App* spp = app.add_subcommand(
      "spp", "Single-point positions from a real RINEX observation file (GPS, GLONASS, Galileo, "
             "BeiDou, QZSS)");
  spp->footer(
      "Solves every epoch of OBS by weighted least squares on single-frequency pseudoranges\n"
      "with the broadcast ephemerides of NAV: GPS and QZSS L1 C/A (RINEX 3 C1C, RINEX 2 C1),\n"
      "GLONASS L1 (C1C, C1P), Galileo E1 (C1C, C1X), BeiDou B1I (C2I, C2X; C1I before RINEX\n"
      "3.02). One receiver clock for GPS and QZSS plus an inter-system bias for each of\n"
      "GLONASS, Galileo and BeiDou in use; the broadcast Klobuchar delay scaled to each\n"
      "signal's frequency.\n"
      "CSV columns: time (UTC), lat_deg, lon_deg, h_m (ellipsoidal), x_m, y_m, z_m (ECEF),\n"
      "clock_m (receiver clock bias * c in GPS time, or in the first solved system's time\n"
      "without GPS/QZSS), nsat (satellites used), pdop, gps_week, gps_tow_s, sigma_e_m,\n"
      "sigma_n_m, sigma_u_m (1-sigma east, north, up from the least squares' covariance with\n"
      "the weights of RTKLIB's error model).\n"
      "Each fix is tested by its residuals (RAIM: the weighted sum of squared residuals\n"
      "against the chi-square distribution's 99.9 % point, as RTKLIB's pntpos); a fix that\n"
      "fails is solved again without each satellite in turn and the best one is kept, that\n"
      "satellite reported excluded, up to 3 satellites until the fix passes; when it does not\n"
      "the epoch has no fix (--no-raim: every fix is written untested).\n"
      "Epochs without a fix, exclusions and a closing count go to stderr.\n"
      "Examples:\n"
      "  navemu spp 07590920.05o 07590920.05n --mask 15 > 0759.csv\n"
      "  navemu spp ESBC00DNK_R_20201770000_01H_30S_MO.rnx ESBC00DNK_R_20201770000_01D_MN.rnx \\\n"
      "      --systems G,E > esbc.csv");
  spp->add_option("OBS", opt.obs_file, "RINEX observation file")->required();
  spp->add_option("NAV", opt.nav_file, "RINEX navigation file")->required();
  spp->add_option("--mask", opt.mask_deg, "Elevation mask in degrees")
      ->capture_default_str()
      ->check(number_between(0.0, 90.0));
  spp->add_option("--systems", opt.systems,
                  "Systems to solve with, RINEX letters separated by commas: G GPS, R GLONASS, "
                  "E Galileo, C BeiDou, J QZSS")
      ->delimiter(',')
      ->capture_default_str()
      ->check(CLI::IsMember({"G", "R", "E", "C", "J"}));
  spp->add_option("--iono", opt.iono, "Ionospheric correction: klobuchar (broadcast) or off")
      ->capture_default_str()
      ->check(CLI::IsMember({"klobuchar", "off"}));
  spp->add_option("--tropo", opt.tropo,
                  "Tropospheric correction: saastamoinen (standard atmosphere) or off")
      ->capture_default_str()
      ->check(CLI::IsMember({"saastamoinen", "off"}));
  spp->add_option("--residuals", opt.residuals_file,
                  "Also write per-satellite residuals of every solved epoch to this CSV file "
                  "(gps_week, gps_tow_s, sat (RINEX name), az_deg, el_deg, residual_m, iono_m, "
                  "tropo_m, used, excluded: 1 when the residual test left the satellite out)");
  spp->add_flag("!--no-raim", opt.raim, "Write every fix without the residual test and exclusion");
}

int run_spp(const SppOptions& opt, std::ostream& out, std::ostream& err) {
  const ObsData obs = read_rinex_obs(opt.obs_file);
  const NavData nav = read_rinex_nav(opt.nav_file);
  for (const std::string& w : obs.warnings) fmt::print(err, "navemu spp: warning: {}\n", w);

  // Each requested system's observation columns; the start-up line says what is used.
  const bool rinex3 = obs.header.version >= 3.0;
  std::array<SystemColumns, kGnssSystemCount> columns;
  std::vector<std::string> used, unused;
  for (const GnssSystem system : kSppSystems) {
    const GnssSystemInfo& info = system_info(system);
    if (std::find(opt.systems.begin(), opt.systems.end(), std::string(1, info.rinex_letter)) ==
        opt.systems.end())
      continue;
    SystemColumns& c = columns[static_cast<std::size_t>(system)];
    for (const std::string& code : code_preference(system, obs.header.version)) {
      c.code_index = obs.header.index_of(info.rinex_letter, code);
      if (c.code_index < 0) continue;
      c.code = code;
      c.doppler_index = obs.header.index_of(info.rinex_letter, "D" + code.substr(1));
      break;
    }
    if (c.code_index >= 0)
      used.push_back(fmt::format("{} {}", info.name, c.code));
    else
      unused.push_back(info.name);
  }
  if (used.empty())
    throw InputError(opt.obs_file, 0, "OBS TYPES",
                     fmt::format("no single-frequency pseudorange ({}) of the systems asked for "
                                 "(--systems {}) in the header",
                                 rinex3 ? "C1C, C2I, ..." : "C1", fmt::join(opt.systems, ",")));
  fmt::print(err, "navemu spp: solving with {}{}\n", fmt::join(used, ", "),
             unused.empty() ? std::string()
                            : fmt::format("; no pseudorange of {} in {}", fmt::join(unused, ", "),
                                          opt.obs_file));

  SolverOptions so;
  so.elevation_mask_deg = opt.mask_deg;
  so.raim = opt.raim;
  so.saastamoinen = opt.tropo == "saastamoinen";
  if (opt.iono == "klobuchar") {
    if (nav.klobuchar)
      so.klobuchar = nav.klobuchar;
    else
      fmt::print(err, "navemu spp: {} has no Klobuchar coefficients: ionosphere not corrected\n",
                 opt.nav_file);
  }
  const std::optional<int> leap = obs.header.leap_seconds ? obs.header.leap_seconds
                                                          : nav.leap_seconds;

  std::ofstream residuals;
  if (!opt.residuals_file.empty()) {
    residuals.open(opt.residuals_file);
    if (!residuals)
      throw InputError(opt.residuals_file, 0, "--residuals", "cannot open for writing");
    fmt::print(residuals, "gps_week,gps_tow_s,sat,az_deg,el_deg,residual_m,iono_m,tropo_m,used,excluded\n");
  }

  fmt::print(out, "time,lat_deg,lon_deg,h_m,x_m,y_m,z_m,clock_m,nsat,pdop,gps_week,gps_tow_s,sigma_e_m,sigma_n_m,"
                 "sigma_u_m\n");
  int solved = 0, unsolved = 0, failed_test = 0, with_exclusion = 0;
  std::vector<RangeMeasurement> meas;
  for (const ObsEpoch& epoch : obs.epochs) {
    meas.clear();
    for (const SatObs& s : epoch.sats) {
      const std::optional<SatId> sat = s.sat();
      if (!sat) continue;
      const SystemColumns& c = columns[static_cast<std::size_t>(sat->system())];
      if (c.code_index < 0) continue;
      const double pr = s.values[static_cast<std::size_t>(c.code_index)];
      if (!std::isfinite(pr) || pr <= 0.0) continue;
      std::optional<double> d;
      if (c.doppler_index >= 0) {
        const double v = s.values[static_cast<std::size_t>(c.doppler_index)];
        if (std::isfinite(v)) d = v;
      }
      if (const BroadcastRecord r = select_record(nav, *sat, epoch.time);
          !std::holds_alternative<std::monostate>(r))
        meas.push_back(make_range_measurement(r, epoch.time, pr, d));
    }
    const Solution sol = solve(meas, epoch.time, so);
    const std::string when = fmt::format("{} (GPS {})", format_iso_utc(epoch.time, leap), format_week_tow(epoch.time));
    if (sol.fix != FixType::k3D) {
      ++unsolved;
      if (sol.integrity_failed) {
        ++failed_test;
        fmt::print(err,
                   "navemu spp: {}: no fix: the residual test failed (chi-square {:.1f} > {:.1f} for {} "
                   "degrees of freedom) and excluding up to {} satellites does not pass it\n",
                   when, sol.chi_square, chi_square_quantile(so.raim_probability, sol.degrees_of_freedom),
                   sol.degrees_of_freedom, so.raim_max_exclusions);
      } else {
        fmt::print(err, "navemu spp: {}: no 3D fix ({} pseudoranges with ephemeris)\n", when, meas.size());
      }
      continue;
    }
    ++solved;
    bool any_excluded = false;
    for (const SatResidual& r : sol.sats)
      if (r.excluded) {
        any_excluded = true;
        fmt::print(err, "navemu spp: {}: {} excluded by the residual test (residual {:.1f} m)\n", when,
                   r.sat.rinex(), r.residual_m);
      }
    with_exclusion += any_excluded ? 1 : 0;
    // The next epoch starts from this one's position (faster convergence, and the mask applies
    // from the first iteration).
    so.initial_p_ecef_m = sol.p_ecef_m;
    const Geodetic g = geodetic_from_ecef(sol.p_ecef_m);
    const WeekTow wt = to_week_tow(epoch.time);
    const Mat3 r_enu = R_enu_from_ecef(g);
    const Vec3 var_enu = (r_enu * sol.cov_ecef_m2 * r_enu.transpose()).diagonal();
    fmt::print(out, "{},{:.9f},{:.9f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{},{:.3f},{},{:.3f},{:.4f},{:.4f},{:.4f}\n",
               format_iso_utc(epoch.time, leap), g.lat_deg, g.lon_deg, g.h_m, sol.p_ecef_m.x(),
               sol.p_ecef_m.y(), sol.p_ecef_m.z(), sol.clock_m, sol.num_used, sol.dops.pdop,
               wt.week, wt.tow_s, std::sqrt(std::max(var_enu.x(), 0.0)), std::sqrt(std::max(var_enu.y(), 0.0)),
               std::sqrt(std::max(var_enu.z(), 0.0)));
    if (residuals.is_open())
      for (const SatResidual& r : sol.sats)
        fmt::print(residuals, "{},{:.3f},{},{:.3f},{:.3f},{:.4f},{:.4f},{:.4f},{},{}\n", wt.week,
                   wt.tow_s, r.sat.rinex(), r.az_deg, r.el_deg, r.residual_m, r.iono_m, r.tropo_m,
                   r.used ? 1 : 0, r.excluded ? 1 : 0);
  }
  fmt::print(err, "navemu spp: {} epochs, {} with a 3D fix ({} after excluding satellites), {} without{}\n",
             obs.epochs.size(), solved, with_exclusion, unsolved,
             opt.raim ? fmt::format(" ({} failing the residual test)", failed_test) : std::string(" (no residual test)"));
  return 0;
}

}  // namespace navemu
