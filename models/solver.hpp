#pragma once
// Receiver position/velocity/clock by iterative weighted least squares on pseudoranges
// (and Doppler), with elevation mask, elevation-dependent weights and dilution of precision.
// This same solver is the emulator's receiver: DOP enters the output through it.

#include <array>
#include <optional>
#include <span>
#include <vector>

#include "core/satellite.hpp"
#include "models/atmosphere.hpp"
#include "models/ephemeris.hpp"
#include "models/geodesy.hpp"
#include "core/time.hpp"

namespace navemu {

class GlonassArc;  // models/orbit.hpp
struct SatStateAt;

// One satellite's measurement, with the satellite's state already evaluated at its
// transmit time, in the ECEF frame of that transmit time (the solver applies the Earth
// rotation during the signal's flight for the current position estimate).
struct RangeMeasurement {
  SatId sat;
  Vec3 sat_p_ecef_m = Vec3::Zero();
  Vec3 sat_v_ecef_mps = Vec3::Zero();
  double sat_clock_m = 0.0;       // c * (satellite clock bias incl. relativistic, minus TGD)
  double sat_clock_drift_mps = 0.0;
  double pseudorange_m = 0.0;
  double sat_variance_m2 = 0.0;          // orbit and clock error variance (URA bound^2, or a SISRE^2)
  std::optional<double> range_rate_mps;  // -lambda * Doppler, when Doppler is measured
  double carrier_hz = kGpsL1_Hz;  // of the ranging signal: scales the L1 ionospheric delay
  // The receiver's own variance of this measurement's errors besides the orbit and clock and the
  // models' (code noise, multipath, ...: a receiver model's error budget,
  // MeasurementGenerator::solver_input); unset: SolverOptions' sigma_a/sigma_b.
  std::optional<double> code_variance_m2;
  // The receiver's variance of range_rate_mps (its Doppler noise, m^2/s^2): the velocity's
  // weights and covariance; unset for any one: equal weights and no velocity covariance.
  std::optional<double> range_rate_variance_m2ps2;
};

// The receiver clocks the solver estimates: one per time scale of the systems in the solution
// (as RTKLIB's pntpos): GPS, QZSS (whose time is steered to GPS time, IS-QZSS-PNT 3.2.1.2) and
// SBAS share the first; GLONASS, Galileo, BeiDou and NavIC each have their own, the receiver's
// clock in that system's time, i.e. GPS's plus an inter-system bias that holds the systems'
// time offset (GGTO etc.) and the receiver's inter-system hardware delays.
inline constexpr std::size_t kClockGroups = 5;
constexpr std::size_t clock_group(GnssSystem s) {
  switch (s) {
    case GnssSystem::kGlonass: return 1;
    case GnssSystem::kGalileo: return 2;
    case GnssSystem::kBeidou: return 3;
    case GnssSystem::kNavic: return 4;
    default: return 0;
  }
}

enum class FixType { kNone = 0, kDeadReckoning = 1, k2D = 2, k3D = 3 };
enum class SolverFixMode { k2DOnly, k3DOnly, kAuto };

struct Dops {
  double gdop = 0.0, pdop = 0.0, hdop = 0.0, vdop = 0.0, tdop = 0.0;
};

struct SolverOptions {
  double elevation_mask_deg = 15.0;
  std::optional<KlobucharCoefficients> klobuchar;  // none: no ionospheric correction
  bool saastamoinen = false;                       // tropospheric correction
  double relative_humidity = 0.7;                  // for the standard atmosphere
  int max_iterations = 10;
  double convergence_m = 1e-4;
  // Elevation-dependent code noise: sigma^2 = a^2 + b^2 / sin(el) (RTKLIB pntpos' varerr
  // with its default a = b = 0.3 m), plus URA^2, plus the model variances of the
  // ionospheric (half the correction) and tropospheric (0.3 m / (sin(el) + 0.1)) corrections.
  double sigma_a_m = 0.3;
  double sigma_b_m = 0.3;
  // The model variances' sizes: the ionospheric correction's error as a fraction of it (RTKLIB:
  // half) and the tropospheric one's, tropo_sigma_m / (sin(el) + 0.1) (RTKLIB: 0.3 m).
  double iono_error_fraction = 0.5;
  double tropo_sigma_m = 0.3;
  // Errors every satellite shares, which make theirs correlated (0: none, RTKLIB): a common
  // scale error of the broadcast ionosphere (1-sigma, a fraction of each correction) and the
  // north and east gradients of the vertical delay it lacks (1-sigma, m per degree at the
  // pierce point). The weights keep their variances; the covariance adds the correlations.
  double iono_shared_scale_sigma = 0.0;
  double iono_shared_gradient_sigma_m_per_deg = 0.0;
  // GLONASS's code noise variance is scaled by 1.5^2 (its C/A code chips at half GPS's rate;
  // RTKLIB's EFACT_GLO), SBAS's by 3^2 (EFACT_SBS).
  Vec3 initial_p_ecef_m = Vec3::Zero();  // zero: start at the Earth's centre
  // Fix mode (u-blox CFG-NAVSPG-FIXMODE; F9P integration manual, "Navigation input filters"):
  // kAuto solves a 2D fix with exactly three usable satellites and a known initial position,
  // the height held at the initial position's; k3DOnly never solves 2D; k2DOnly always holds
  // the height, at fixed_height_m (ellipsoidal), once the estimate is near the Earth's surface.
  SolverFixMode fix_mode = SolverFixMode::kAuto;
  double fixed_height_m = 0.0;
  // Receiver autonomous integrity monitoring with fault detection and exclusion (RTKLIB
  // pntpos' valsol and raim_fde; Kaplan & Hegarty, Understanding GPS/GNSS 3rd ed., 10.4): a fix
  // whose weighted sum of squared residuals (the variances above) exceeds the chi-square
  // distribution's raim_probability point for its degrees of freedom (rows - unknowns) fails;
  // then each used satellite in turn is left out and the fix with the smallest sum is taken (its satellite reported excluded); while that fix still fails, the
  // next satellite is left out the same way, up to raim_max_exclusions (RTKLIB: one); when the
  // last still fails, or no fix is left to test, there is no fix.
  bool raim = false;
  double raim_probability = 0.999;  // RTKLIB's chisqr table: alpha = 0.001
  int raim_max_exclusions = 3;
  // A receiver's way instead of "no fix" when no exclusion passes (errors no single satellite
  // explains: a storm, multipath everywhere): the fix over every satellite is kept, flagged
  // integrity_failed, its covariance scaled by the a-posteriori variance factor chi^2 / dof
  // (the variances were that much too small), so the accuracy it reports grows with its errors.
  bool raim_keeps_failed_fix = false;
};

struct SatResidual {
  SatId sat;
  double az_deg = 0.0, el_deg = 0.0;
  double residual_m = 0.0;  // measured minus modelled pseudorange after the final iteration
  double iono_m = 0.0, tropo_m = 0.0;
  bool used = false;      // false: below mask, or excluded
  bool excluded = false;  // left out by the residual test (SolverOptions::raim)
};

struct Solution {
  FixType fix = FixType::kNone;
  Vec3 p_ecef_m = Vec3::Zero();
  // Receiver clock bias * c: GPS time's when GPS, QZSS or SBAS satellites are used, otherwise
  // the first used system's of GLONASS, Galileo, BeiDou, NavIC.
  double clock_m = 0.0;
  // Each clock group's (kClockGroups) that has a satellite in the solution.
  std::array<std::optional<double>, kClockGroups> group_clock_m{};
  std::optional<Vec3> v_ecef_mps;
  // Its covariance (H^T W H)^-1 with the range rates' variances as weights, ECEF, m^2/s^2; zero
  // when a range rate has no variance (RangeMeasurement::range_rate_variance_m2ps2).
  Mat3 cov_v_ecef_m2ps2 = Mat3::Zero();
  double clock_drift_mps = 0.0;
  Dops dops;
  // Covariance of the position from the weighted least squares, (H^T W H)^-1 with the
  // measurement variances above as weights, ECEF, m^2 (zero without a fix).
  Mat3 cov_ecef_m2 = Mat3::Zero();
  int num_used = 0;
  int iterations = 0;
  // The residual test: the weighted sum of squared residuals of the fix (or of the attempt
  // without a fix) and its degrees of freedom (rows - unknowns; 0: not testable); failed: the
  // test (SolverOptions::raim) failed and no exclusion made a fix pass it.
  double chi_square = 0.0;
  int degrees_of_freedom = 0;
  bool integrity_failed = false;
  std::vector<SatResidual> sats;
};

// The p-quantile of the chi-square distribution with `dof` degrees of freedom (p in (0, 1),
// dof >= 1): the x with P(dof / 2, x / 2) = p, P the regularised lower incomplete gamma
// function (Abramowitz & Stegun 26.4.19), found by bisection.
double chi_square_quantile(double p, int dof);

// A measurement from a pseudorange observed at receiver time t_receive: the satellite state
// at transmit time t_receive - P/c - dt_sat (IS-GPS-200 20.3.3.3.3.1), the L1 C/A clock
// correction (dt_sat - TGD), URA^2 as orbit/clock variance, and the range rate from an L1
// Doppler in Hz when given. GPS and QZSS (IS-QZSS-PNT: GPS's LNAV algorithms) records.
// `near`: the record's state at a time near the transmit time when the caller has it (the
// measurement generator's, at the true transmit time, which the receiver's estimate
// t_receive - P/c - dt_sat misses by the pseudorange's errors over c, microseconds). Within 1 ms
// it is carried there to first order instead of solving Kepler's equation again: the
// acceleration (0.6 m/s^2 for GPS) leaves 0.3 nm after 1 us and 0.3 um after 1 ms, the clock's
// af2 less.
RangeMeasurement make_range_measurement(const GpsEphemeris& eph, GpsTime t_receive,
                                        double pseudorange_m,
                                        std::optional<double> doppler_l1_hz = {},
                                        const SatStateAt* near = nullptr);
// The same for the single-frequency signal of each other system, with its group delay and
// accuracy:
// - Galileo E1: dt_sat - BGD(E1,E5b) for an I/NAV record, - BGD(E1,E5a) for F/NAV (OS SIS ICD
//   2.0 5.1.5); variance SISA^2 (5.1.11), (500 m)^2 for "no accuracy prediction" (NAPA, a SISA
//   that is not positive).
// - BeiDou B1I: dt_sat - TGD1 (BDS-SIS-ICD-B1I 3.0 5.2.4.10); variance the URA bound^2.
// - GLONASS L1OF on the satellite's frequency channel: the clock as glonass_sat_state; the
//   broadcast data have no accuracy in RINEX 3, so (5 m)^2 (RTKLIB's ERREPH_GLO).
RangeMeasurement make_range_measurement(const GalileoEphemeris& eph, GpsTime t_receive,
                                        double pseudorange_m,
                                        std::optional<double> doppler_e1_hz = {},
                                        const SatStateAt* near = nullptr);
RangeMeasurement make_range_measurement(const BeidouEphemeris& eph, GpsTime t_receive,
                                        double pseudorange_m,
                                        std::optional<double> doppler_b1i_hz = {},
                                        const SatStateAt* near = nullptr);
//   `arc`: the record's integrated arc when the caller keeps one (GlonassArc; the same state
//   to the integration's sub-millimetre differences, without integrating from tb again).
RangeMeasurement make_range_measurement(const GlonassEphemeris& eph, GpsTime t_receive,
                                        double pseudorange_m,
                                        std::optional<double> doppler_l1_hz = {},
                                        const GlonassArc* arc = nullptr);
// The one of these for whichever record `r` holds (it must hold one); `near` for Kepler records.
RangeMeasurement make_range_measurement(const BroadcastRecord& r, GpsTime t_receive,
                                        double pseudorange_m, std::optional<double> doppler_hz = {},
                                        const GlonassArc* glonass_arc = nullptr,
                                        const SatStateAt* near = nullptr);

// The solver's matrices live on the stack up to this many satellites (no allocation per epoch);
// measurements beyond it are not used.
inline constexpr std::size_t kMaxSolverSatellites = 127;

Solution solve(const std::vector<RangeMeasurement>& meas, GpsTime t, const SolverOptions& opt);
// The storage the exclusion step (SolverOptions::raim) works in, kept between epochs; room for
// `satellites` from the start (no allocation when the first exclusion comes).
struct SolverScratch {
  explicit SolverScratch(std::size_t satellites = 0);
  std::vector<std::size_t> kept, excluded;
  std::vector<RangeMeasurement> without;
  Solution trial, best, current;
};
// The same into `sol`, reusing its storage and the scratch's: the real-time loop's form (no
// allocation once sol.sats has grown to the satellites in view).
void solve(std::span<const RangeMeasurement> meas, GpsTime t, const SolverOptions& opt,
           Solution& sol, SolverScratch& scratch);
void solve(std::span<const RangeMeasurement> meas, GpsTime t, const SolverOptions& opt,
           Solution& sol);

// DOPs of a satellite set seen from a receiver (unit weights), from the line-of-sight unit
// vectors in ENU. Needs at least 4 directions; all zero otherwise.
Dops dops_from_directions(std::span<const AzEl> dirs);
Dops dops_from_directions(std::span<const Direction> dirs);

}  // namespace navemu
