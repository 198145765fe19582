#pragma once
// Errors of the broadcast satellite orbit and clock as the user sees them.


#include "models/geodesy.hpp"
#include "core/sat_table.hpp"
#include "core/satellite.hpp"
#include "models/random.hpp"

namespace navemu {

// The paper's range error for satellite ephemeris errors (Durst & Goodin section 2.1, after
// Hwang and Parkinson): sqrt((1 + sin(theta)/2) 10^(2 R_ref / R_0) + c^2 1e-18 + 0.918), with
// theta the satellite's latitude, R_ref = 26 550 000 m and R_0 the satellite's orbit radius.
// For a GPS orbit (R_0 ~ R_ref) it evaluates to ~10 m: sqrt(100 + 0.0899 + 0.918) = 10.05 m at
// theta = 0 and 12.29 m at theta = 90 deg, an order of magnitude above today's broadcast
// errors; SatErrors below models those instead.
double paper_sv_ephemeris_error_m(double sat_lat_rad, double orbit_radius_m);

// Rotation from ECEF into the satellite's radial / along-track / cross-track frame: its rows
// are the unit vectors radial = p/|p|, cross = p x v / |p x v|, along = cross x radial.
Mat3 R_rac_from_ecef(const Vec3& sat_p_ecef_m, const Vec3& sat_v_ecef_mps);

struct SatErrorParams {
  // Broadcast orbit error, 1-sigma, in the radial / along-track / cross-track frame, and the
  // clock error, all first-order Gauss-Markov with one correlation time. Defaults: GPS
  // broadcast accuracy of recent years (signal-in-space range error ~0.6 m RMS).
  double radial_sigma_m = 0.2;
  double along_sigma_m = 1.0;
  double cross_sigma_m = 0.6;
  double clock_sigma_m = 0.5;
  double tau_s = 3600.0;
  // Drawn this far apart and interpolated (InterpolatedGaussMarkov): broadcast orbit and clock
  // errors vary over the orbit and between uploads, smoothly from one second to the next.
  double knot_s = 30.0;

  // Global-average signal-in-space range error of these parameters (Montenbruck et al. 2015,
  // GPS Solutions 19: SISRE^2 = (w_r sigma_r - sigma_clk)^2 + w_ac^2 (sigma_a^2 + sigma_c^2) with
  // w_r = 0.98, w_ac^2 = 1/49 for GPS; the radial and clock errors taken as uncorrelated).
  double sisre_m() const;
  // The same parameters scaled to a given SISRE (the ratios between the terms kept).
  SatErrorParams scaled_to_sisre(double sisre) const;
};

// How much larger each system's broadcast orbit and clock errors are than GPS's: the global
// average RMS signal-in-space range errors of 2017, 0.2 m Galileo, 0.6 m GPS, 1 m BeiDou-2 and
// 2 m GLONASS (Montenbruck, Steigenberger, Hauschild, "Multi-GNSS signal-in-space range error
// assessment - methodology and results", Adv. Space Res. 61 (2018) 3020-3038), over GPS's.
// QZSS, which that average leaves out, as GPS; SBAS and NavIC likewise.
double sisre_relative_to_gps(GnssSystem system);

// Per-satellite orbit and clock error processes, one random stream per term and satellite. The
// parameters are GPS's; the other systems' sigmas are scaled by sisre_relative_to_gps.
class SatErrors {
 public:
  SatErrors(const SatErrorParams& p, std::uint64_t seed);
  // Advances the processes of `sat` to time t_s (seconds, any origin) by the time elapsed since
  // that satellite's previous call (the first call for a satellite starts its processes from their
  // stationary distribution; a t_s not after the previous one leaves them unchanged).
  // Returns the range error: orbit error projected on the line of sight plus clock error, m.
  // `los_unit_ecef` points from the receiver to the satellite.
  //
  // Sign convention. The orbit terms are the error of the broadcast orbit, dr = broadcast -
  // true position, dr = radial e_r + along e_a + cross e_c. The emulator computes the true
  // range from the ephemeris position, so it plays the broadcast position; the satellite is
  // "really" at broadcast - dr and the range to it is |p - u| - dr.los (first order). The
  // returned value is what must be ADDED to a pseudorange computed from the ephemeris
  // position:  range_error = -dr.los + clock_m.  A positive radial error seen from directly
  // below the satellite (los = e_r) therefore shortens the pseudorange by `radial`. The clock
  // term is the satellite clock error left after the broadcast correction, in metres, added
  // as it is.
  double range_error_m(SatId sat, double t_s, const Vec3& sat_p_ecef_m, const Vec3& sat_v_ecef_mps,
                       const Vec3& los_unit_ecef);

  // The current error terms of `sat` as used by the last range_error_m call for it (all zero
  // for a satellite never seen), metres.
  struct Terms {
    double radial_m = 0.0;
    double along_m = 0.0;
    double cross_m = 0.0;
    double clock_m = 0.0;
  };
  Terms terms(SatId sat) const;

 private:
  struct Sat {
    double t_s = 0.0;
    InterpolatedGaussMarkov radial, along, cross, clock;
    RandomStream rng;
  };
  SatErrorParams p_;
  std::uint64_t seed_;
  SatTable<Sat> sats_;
};

}  // namespace navemu
