// navemu spp: single-point positioning on a real RINEX observation file (GPS L1 C/A code).

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <cmath>
#include <fstream>
#include <ostream>

#include "emulator/commands.hpp"
#include "core/errors.hpp"
#include "emulator/rinex_files.hpp"
#include "models/solver.hpp"

namespace navemu {

void add_spp_command(CLI::App& app, SppOptions& opt) {
  CLI::App* spp = app.add_subcommand(
      "spp", "Single-point positions from a real RINEX observation file (GPS L1 C/A)");
  spp->footer(
      "Solves every epoch of OBS by weighted least squares on the GPS L1 C/A pseudoranges\n"
      "(RINEX 2 C1, RINEX 3 C1C) with the broadcast ephemeris of NAV.\n"
      "CSV columns: time (UTC), lat_deg, lon_deg, h_m (ellipsoidal), x_m, y_m, z_m (ECEF),\n"
      "clock_m (receiver clock bias * c), nsat (satellites used), pdop, gps_week, gps_tow_s.\n"
      "Epochs without a fix and a closing count go to stderr.\n"
      "Example:\n"
      "  navemu spp 07590920.05o 07590920.05n --mask 15 > 0759.csv");
  spp->add_option("OBS", opt.obs_file, "RINEX observation file")->required();
  spp->add_option("NAV", opt.nav_file, "RINEX navigation file")->required();
  spp->add_option("--mask", opt.mask_deg, "Elevation mask in degrees")
      ->capture_default_str()
      ->check(number_between(0.0, 90.0));
  spp->add_option("--iono", opt.iono, "Ionospheric correction: klobuchar (broadcast) or off")
      ->capture_default_str()
      ->check(CLI::IsMember({"klobuchar", "off"}));
  spp->add_option("--tropo", opt.tropo,
                  "Tropospheric correction: saastamoinen (standard atmosphere) or off")
      ->capture_default_str()
      ->check(CLI::IsMember({"saastamoinen", "off"}));
  spp->add_option("--residuals", opt.residuals_file,
                  "Also write per-satellite residuals of every solved epoch to this CSV file "
                  "(gps_week, gps_tow_s, prn, az_deg, el_deg, residual_m, iono_m, tropo_m, used)");
}

int run_spp(const SppOptions& opt, std::ostream& out, std::ostream& err) {
  const ObsData obs = read_rinex_obs(opt.obs_file);
  const NavData nav = read_rinex_nav(opt.nav_file);
  for (const std::string& w : obs.warnings) fmt::print(err, "navemu spp: warning: {}\n", w);

  const bool rinex3 = obs.header.version >= 3.0;
  const std::string code = rinex3 ? "C1C" : "C1";
  const std::string doppler = rinex3 ? "D1C" : "D1";
  const int code_index = obs.header.index_of('G', code);
  const int doppler_index = obs.header.index_of('G', doppler);
  if (code_index < 0)
    throw InputError(opt.obs_file, 0, "OBS TYPES",
                     fmt::format("no GPS L1 C/A pseudorange ({}) in the header", code));

  SolverOptions so;
  so.elevation_mask_deg = opt.mask_deg;
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
    fmt::print(residuals, "gps_week,gps_tow_s,prn,az_deg,el_deg,residual_m,iono_m,tropo_m,used\n");
  }

  fmt::print(out, "time,lat_deg,lon_deg,h_m,x_m,y_m,z_m,clock_m,nsat,pdop,gps_week,gps_tow_s\n");
  int solved = 0;
  int unsolved = 0;
  for (const ObsEpoch& epoch : obs.epochs) {
    std::vector<RangeMeasurement> meas;
    for (const SatObs& s : epoch.sats) {
      const std::optional<SatId> sat = s.sat();
      if (!sat || sat->system() != GnssSystem::kGps) continue;
      const double pr = s.values[static_cast<std::size_t>(code_index)];
      if (!std::isfinite(pr) || pr <= 0.0) continue;
      const GpsEphemeris* eph = select_ephemeris(nav, *sat, epoch.time);
      if (eph == nullptr || std::abs(seconds_between(epoch.time, eph->toe)) > kMaxEphemerisAge_s)
        continue;
      std::optional<double> d;
      if (doppler_index >= 0) {
        const double v = s.values[static_cast<std::size_t>(doppler_index)];
        if (std::isfinite(v)) d = v;
      }
      meas.push_back(make_range_measurement(*eph, epoch.time, pr, d));
    }
    const Solution sol = solve(meas, epoch.time, so);
    if (sol.fix != FixType::k3D) {
      ++unsolved;
      fmt::print(err, "navemu spp: {} (GPS {}): no 3D fix ({} GPS pseudoranges with ephemeris)\n",
                 format_iso_utc(epoch.time, leap), format_week_tow(epoch.time), meas.size());
      continue;
    }
    ++solved;
    // The next epoch starts from this one's position (faster convergence, and the mask applies
    // from the first iteration).
    so.initial_p_ecef_m = sol.p_ecef_m;
    const Geodetic g = geodetic_from_ecef(sol.p_ecef_m);
    const WeekTow wt = to_week_tow(epoch.time);
    fmt::print(out, "{},{:.9f},{:.9f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{},{:.3f},{},{:.3f}\n",
               format_iso_utc(epoch.time, leap), g.lat_deg, g.lon_deg, g.h_m, sol.p_ecef_m.x(),
               sol.p_ecef_m.y(), sol.p_ecef_m.z(), sol.clock_m, sol.num_used, sol.dops.pdop,
               wt.week, wt.tow_s);
    if (residuals.is_open())
      for (const SatResidual& r : sol.sats)
        fmt::print(residuals, "{},{:.3f},{},{:.3f},{:.3f},{:.4f},{:.4f},{:.4f},{}\n", wt.week,
                   wt.tow_s, r.sat.number(), r.az_deg, r.el_deg, r.residual_m, r.iono_m, r.tropo_m,
                   r.used ? 1 : 0);
  }
  fmt::print(err, "navemu spp: {} epochs, {} with a 3D fix, {} without\n", obs.epochs.size(),
             solved, unsolved);
  return 0;
}

}  // namespace navemu
