#pragma once
// Signal tracking: carrier-to-noise density by elevation and antenna gain, thermal noise of
// the code (DLL), carrier phase (PLL) and Doppler (FLL) loops, and carrier-phase arcs with an
// integer ambiguity and cycle slips.

#include <utility>
#include <vector>

#include "core/sat_table.hpp"
#include "core/satellite.hpp"
#include "models/random.hpp"

namespace navemu {

struct TrackingParams {
  double chip_length_m = 293.052;  // GPS C/A: c / 1.023 MHz
  double chip_spacing = 1.0;       // early-late spacing d, chips (standard 1, narrow 0.1)
  double dll_bandwidth_hz = 1.0;   // B_L of the code loop (carrier-aided)
  double pll_bandwidth_hz = 15.0;
  double fll_bandwidth_hz = 2.0;
  double integration_s = 0.020;      // predetection integration time T
  double tracking_threshold_dbhz = 28.0;  // below: loss of lock
  double reacquisition_s = 1.0;          // time to re-acquire after the signal returns
};

// Noncoherent early-minus-late power DLL thermal noise, 1-sigma, metres (Betz & Kolodziejski
// 2000; Kaplan & Hegarty, Understanding GPS, 2nd ed. 2006, 5.6.3, eq. 5.23, the branch for a
// front end wide against the spacing, d >= pi R_c / B_fe):
//   sigma = lambda_c sqrt( B_L d / (2 C/N0) (1 + 2 / (T C/N0 (2 - d))) ).
double dll_noise_m(double cn0_dbhz, const TrackingParams& p);
// PLL thermal noise, 1-sigma, cycles (Kaplan & Hegarty 2nd ed. 5.6.1.1, there in degrees,
// 360/(2 pi) times the root):
//   sigma = 1/(2 pi) sqrt( B_n / C/N0 (1 + 1 / (2 T C/N0)) ).
double pll_noise_cycles(double cn0_dbhz, const TrackingParams& p);
// FLL thermal noise, 1-sigma, Hz (Kaplan & Hegarty 2nd ed. 5.6.2, F = 1 at high C/N0):
//   sigma = 1/(2 pi T) sqrt( 4 F B_n / C/N0 (1 + 1 / (T C/N0)) ).
double fll_noise_hz(double cn0_dbhz, const TrackingParams& p);
// The three at one C/N0 (its ratio computed once).
struct TrackingNoise {
  double code_m = 0.0;
  double phase_cycles = 0.0;
  double doppler_hz = 0.0;
};
TrackingNoise tracking_noise(double cn0_dbhz, const TrackingParams& p);

// C/N0 by elevation: a zenith value plus the antenna gain relative to the zenith, linearly
// interpolated in a table of (elevation deg, gain dB) sorted by elevation and held at its end
// values outside it. Default table: a patch antenna whose gain falls ~10 dB from the zenith
// to 5 deg.
// (elevation deg, gain dB relative to the zenith) of a typical GPS patch antenna.
std::vector<std::pair<double, double>> patch_antenna_gain_table();

struct Cn0Model {
  double zenith_dbhz = 49.0;
  std::vector<std::pair<double, double>> gain_db_by_el_deg = patch_antenna_gain_table();
};
double cn0_dbhz(const Cn0Model& m, double el_rad);

// Carrier-phase bookkeeping per satellite: an integer ambiguity drawn when an arc starts, a new
// arc (new ambiguity, loss-of-lock indicator set) when the signal was lost or below threshold.
// The ambiguity of arc k (0, 1, ... per satellite) is uniform on the integers in [-1e6, 1e6],
// drawn from its own stream stream_id("carrier_arc", sat.stream_index() * 100000 + k) of the
// scenario seed.
class CarrierArcs {
 public:
  // `max_gap_s`: a tracked epoch more than this after the satellite's previous update starts a new
  // arc (no updates for that long counts as a loss of lock); about twice the longest epoch
  // interval in use.
  explicit CarrierArcs(std::uint64_t seed, double max_gap_s = 10.0)
      : seed_(seed), max_gap_s_(max_gap_s) {}
  struct Arc {
    double ambiguity_cycles = 0.0;  // integer
    double lock_time_s = 0.0;       // time since the arc started
    bool new_arc = true;            // first epoch of the arc (RINEX LLI bit 0)
  };
  // Updates the arc of `sat` at time t_s: `tracked` false ends the arc (next tracked epoch
  // starts a new one). A tracked epoch starts a new arc as well when it comes more than
  // max_gap_s after the previous update or before it. Returns the arc state for this epoch;
  // for an untracked epoch there is no arc and the result is all zero with new_arc false.
  Arc update(SatId sat, double t_s, bool tracked);

 private:
  struct State {
    bool active = false;
    double start_s = 0.0;
    double last_s = 0.0;
    double ambiguity = 0.0;
    long long arcs = 0;
  };
  std::uint64_t seed_;
  double max_gap_s_ = 10.0;
  SatTable<State> state_;
};

// Carrier-smoothed code: the Hatch filter (R. Hatch, "The synergism of GPS code and carrier
// measurements", 3rd Int. Geodetic Symposium on Satellite Doppler Positioning, 1982) in its
// time-constant form (T = 100 s in the SBAS and GBAS airborne standards, RTCA DO-229, DO-253):
//   rho_s(k) = w rho(k) + (1 - w) (rho_s(k-1) + Phi(k) - Phi(k-1)),  w = max(1/k, dt/T),
// rho the code, Phi the carrier range of the same arc (metres), k the epochs since the arc
// began, T the window. Code noise and code multipath are averaged down; what code and carrier
// share passes unchanged (and the ionosphere, which they see with opposite signs, diverges by
// twice its change over about T). The same recursion in variance gives what it leaves of the
// code's white noise and of a Gauss-Markov multipath of correlation time tau (unit variances;
// c = E[rho_s m], a = exp(-dt/tau)):
//   v_n(k) = w^2 + (1-w)^2 v_n(k-1)
//   v_m(k) = w^2 + (1-w)^2 v_m(k-1) + 2 w (1-w) a c(k-1),   c(k) = w + (1-w) a c(k-1).
class CarrierSmoother {
 public:
  // A code further than this from the smoothed code carried forward by the carrier means a
  // slip the arcs did not catch: the filter restarts.
  static constexpr double kMaxStepDisagreement_m = 30.0;
  // The smoothed code at t_s. Restarts with `new_arc`, after a gap longer than the window, and
  // at a disagreement as above.
  double update(double t_s, double code_m, double carrier_m, bool new_arc, double window_s,
                double multipath_tau_s);
  double noise_fraction() const { return v_noise_; }
  double multipath_fraction() const { return v_multipath_; }

 private:
  bool started_ = false;
  double last_t_s_ = 0.0;
  double smoothed_m_ = 0.0, carrier_m_ = 0.0;
  double epochs_ = 0.0;
  double v_noise_ = 1.0, v_multipath_ = 1.0, c_multipath_ = 1.0;
};

}  // namespace navemu
