// navemu sky: where every GPS satellite is, seen from one place at one time.

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <algorithm>
#include <ostream>
#include <set>

#include "emulator/commands.hpp"
#include "models/atmosphere.hpp"
#include "models/orbit.hpp"
#include "models/solver.hpp"

namespace navemu {

void add_sky_command(CLI::App& app, SkyOptions& opt) {
  CLI::App* sky = app.add_subcommand(
      "sky", "GPS satellites seen from one place at one time (CSV), with the DOPs of the set");
  sky->footer(
      "Output: a '#' line with the time (UTC and GPS week:TOW), place and navigation source; a\n"
      "CSV header; one row per satellite above the mask; a '#' line with the DOPs of that set.\n"
      "Columns:\n"
      "  prn                      GPS PRN\n"
      "  sat_x_m, sat_y_m, sat_z_m  position at transmit time, rotated into the ECEF frame at\n"
      "                           reception (light time and Earth rotation, IS-GPS-200 20.3.3.4.3)\n"
      "  sat_clock_m              c * (clock bias incl. relativistic term - TGD), the L1 C/A\n"
      "                           satellite clock correction\n"
      "  az_deg, el_deg           azimuth (from north, clockwise) and elevation on the ellipsoid normal\n"
      "  range_m                  geometric range including the Earth-rotation correction\n"
      "  iono_m                   L1 ionospheric delay: the nav file's Klobuchar model, or the\n"
      "                           paper's mapping of 12 TECU when it has none\n"
      "  tropo_m                  tropo_hydro_m + tropo_wet_m: Saastamoinen zenith delays of the\n"
      "                           standard atmosphere (50 % humidity), Niell mapping\n"
      "Examples:\n"
      "  navemu sky --nominal --time 2023-01-08T09:59:42Z --at 30,95,0\n"
      "  navemu sky --nav brdc.23n --time 2244:36000 --at 30,95,0 --mask 10");
  auto* nav = sky->add_option("--nav", opt.nav_file, "RINEX navigation file (2.x, 3.x, 4.x)");
  sky->add_flag("--nominal", opt.nominal,
                "Use the built-in nominal 24-slot constellation (the default without --nav)")
      ->excludes(nav);
  sky->add_option("--time", opt.time,
                  "Reception time: ISO-8601 UTC (2023-01-08T09:59:42Z), GPS WEEK:TOW "
                  "(2244:36000) or 'now'")
      ->capture_default_str();
  sky->add_option("--at", opt.at,
                  "Receiver LAT,LON,H (deg, deg, m above the WGS-84 ellipsoid); default: the "
                  "paper's test site in Vicksburg, MS")
      ->capture_default_str();
  sky->add_option("--mask", opt.mask_deg, "Elevation mask in degrees")
      ->capture_default_str()
      ->check(number_between(-90.0, 90.0));
}

int run_sky(const SkyOptions& opt, std::ostream& out, std::ostream& err) {
  const GpsTime t = time_option(opt.time, "--time");
  const Geodetic rx = parse_geodetic(opt.at, "--at");
  const Vec3 p_rx = ecef_from_geodetic(rx);
  const NavData nav = load_nav_or_nominal(opt.nav_file, t);
  // The sky needs no fix: one satellite with data is a sky to show.
  require_nav_coverage(nav, t, t, {"--nav", "--time", "--time", nullptr}, 1);

  std::set<SatId> sats;
  for (const GpsEphemeris& e : nav.gps) sats.insert(e.sat);

  fmt::print(out, "# navemu sky: {} = GPS {}, receiver {:.9f},{:.9f},{:.3f}, {}, mask {:.1f} deg\n",
             format_iso_utc(t, nav.leap_seconds), format_week_tow(t), rx.lat_deg, rx.lon_deg,
             rx.h_m, nav.source, opt.mask_deg);
  fmt::print(out,
             "prn,sat_x_m,sat_y_m,sat_z_m,sat_clock_m,az_deg,el_deg,range_m,iono_m,tropo_m,"
             "tropo_hydro_m,tropo_wet_m\n");
  const Meteo meteo = standard_atmosphere(std::max(rx.h_m, 0.0), 0.5);

  std::vector<AzEl> visible;
  int stale = 0;
  for (SatId sat : sats) {
    const GpsEphemeris* eph = select_ephemeris(nav, sat, t);
    if (eph == nullptr) continue;
    if (std::abs(seconds_between(t, eph->toe)) > kMaxEphemerisAge_s) {
      ++stale;
      continue;
    }
    const SatGeometry g = gps_sat_geometry(*eph, t, p_rx);
    if (g.dir.el_rad < opt.mask_deg * kDegToRad) continue;
    visible.push_back(g.dir);
    const double iono_m =
        nav.klobuchar
            ? kSpeedOfLight_mps * klobuchar_delay_l1_s(*nav.klobuchar, rx, g.dir, t)
            : iono_paper_mapping(g.dir.el_rad) * iono_zenith_delay_m(kPaperValidationVtec_tecu, kGpsL1_Hz);
    const TropoDelay tropo = tropo_slant_delay(rx, g.dir.el_rad, t, meteo);
    fmt::print(out, "{},{:.4f},{:.4f},{:.4f},{:.4f},{:.6f},{:.6f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f}\n",
               sat.number(), g.sat.p_ecef_m.x(), g.sat.p_ecef_m.y(), g.sat.p_ecef_m.z(),
               kSpeedOfLight_mps * (g.sat.clock_bias_s - eph->tgd_s), g.dir.az_rad * kRadToDeg,
               g.dir.el_rad * kRadToDeg, g.range_m, iono_m, tropo.total_m(), tropo.hydrostatic_m,
               tropo.wet_m);
  }
  if (stale > 0)
    fmt::print(err, "navemu sky: {} satellites skipped: no ephemeris within {:.0f} h\n", stale,
               kMaxEphemerisAge_s / 3600);

  const Dops d = dops_from_directions(visible);
  if (visible.size() >= 4)
    fmt::print(out, "# visible {}: GDOP {:.3f} PDOP {:.3f} HDOP {:.3f} VDOP {:.3f} TDOP {:.3f}\n",
               visible.size(), d.gdop, d.pdop, d.hdop, d.vdop, d.tdop);
  else
    fmt::print(out, "# visible {}: too few satellites for DOP\n", visible.size());
  return 0;
}

}  // namespace navemu
