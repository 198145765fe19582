#pragma once
// What a receiver makes of the signal paths the scene yields (models/scene.hpp): reflection
// coefficients, antenna gain, the code and carrier tracking error of the composite signal, and
// the composite C/N0. Pure functions; no randomness.
//
// Phasor convention: time dependence e^{+j omega t} throughout (the one ITU-R P.527 and P.2040
// use; it is what makes a lossy permittivity have a negative imaginary part). A path that is
// longer than the direct one by Delta metres therefore carries a factor e^{-j 2 pi Delta /
// lambda}; reflection coefficients and antenna gains multiply onto that.

#include <complex>
#include <optional>
#include <utility>
#include <vector>

#include "core/signal.hpp"

namespace navemu {

inline constexpr double kL1WavelengthM = 299792458.0 / carrier_frequency_hz(kGpsL1CA);  // 0.1903 m

// ---- Reflection coefficients ---------------------------------------------------------------
// Fresnel coefficients of a smooth half-space with complex relative permittivity
//   eps = eps_r - j 60 lambda sigma            (ITU-R P.527, lambda in m, sigma in S/m;
//                                               60 stands for 1 / (2 pi c eps_0) = 59.96)
// for a wave from free space arriving at grazing angle psi (between the ray and the surface;
// the incidence angle from the normal is 90 deg - psi):
//   Gamma_perp (horizontal/TE) = (sin psi - sqrt(eps - cos^2 psi)) / (sin psi + sqrt(eps - cos^2 psi))
//   Gamma_par  (vertical/TM)   = (eps sin psi - sqrt(eps - cos^2 psi)) / (eps sin psi + sqrt(eps - cos^2 psi))
// (ITU-R P.2040 sect. 2.2.1, incident wave in air, written with the grazing angle; the same as
// Born & Wolf's / Hecht's r_s and r_p with the complex Snell law). sqrt is the principal
// branch (Re > 0, Im <= 0 here: the transmitted wave decays). Texts differ in the reference
// direction of the parallel field and so in the sign of Gamma_par; in this one both
// coefficients tend to -1 at grazing incidence, Gamma_par vanishes at the Brewster angle
// (tan(90 deg - psi_B) = sqrt(eps_r) when lossless) and changes sign there, at normal incidence
// Gamma_par = -Gamma_perp = (sqrt(eps) - 1) / (sqrt(eps) + 1), and a perfect conductor has
// Gamma_perp = -1, Gamma_par = +1. A right-hand circular wave reflects into a co-polar (still
// RHCP) and a cross-polar (LHCP) part:
//   Gamma_co = (Gamma_par + Gamma_perp) / 2,   Gamma_cross = (Gamma_par - Gamma_perp) / 2
// (Zavorotny et al. 2010, Nievinski & Larson 2014 "Forward modeling of GPS multipath",
// GPS Solutions 18; Braasch, "Multipath", Springer Handbook of GNSS, 2017, ch. 15): below the
// Brewster angle the reflection stays mostly RHCP, above it mostly LHCP, and all of a perfect
// conductor's reflection is LHCP. The grazing angle is clamped to [0, pi/2].
//
// Materials at L1 (1.57542 GHz) from ITU-R P.2040-2/-3 Table 3 (eps_r = a f^b,
// sigma = c f^d, f in GHz; the fits are for 1-100 GHz, the grounds 1-10 GHz):
//   material            a      b      c        d       eps_r   sigma S/m   60 lambda sigma
//   concrete            5.24   0      0.0462   0.7822  5.24    0.0659      0.753
//   brick               3.91   0      0.0238   0.16    3.91    0.0256      0.292
//   plasterboard        2.73   0      0.0085   0.9395  2.73    0.0130      0.149
//   wood                1.99   0      0.0047   1.0718  1.99    0.00765     0.0874
//   glass               6.31   0      0.0036   1.3394  6.31    0.00662     0.0756
//   ceiling board       1.48   0      0.0011   1.075   1.48    0.00179     0.0205
//   chipboard           2.58   0      0.0217   0.78    2.58    0.0309      0.353
//   marble              7.074  0      0.0055   0.9262  7.07    0.00838     0.0957
//   metal               1      0      1e7      0       1       1e7         1.1e8 (use the
//                                                                          perfect conductor)
//   very dry ground     3      0      0.00015  2.52    3.00    0.000472    0.0054
//   medium dry ground   15     -0.1   0.035    1.63    14.33   0.0734      0.838
//   wet ground          30     -0.4   0.15     1.30    25.01   0.271       3.09
// (P.2040-1 (2015) had concrete 5.31 / 0.0326 / 0.8095, plasterboard 2.94 / 0.0116 / 0.7076,
// glass 6.27 / 0.0043 / 1.1925: at L1 these change |Gamma| by a few hundredths.)
struct Fresnel {
  std::complex<double> perp, par, co, cross;
};
Fresnel fresnel(double relative_permittivity, double conductivity_spm, double grazing_rad,
                double wavelength_m = kL1WavelengthM);
Fresnel fresnel_perfect_conductor();

// ---- Antenna ---------------------------------------------------------------------------------
// Gain of a GNSS antenna for a signal arriving from elevation el (relative to the antenna's
// zenith; negative below the horizon): RHCP gain from a table (dB relative to zenith, linearly
// interpolated, held at the ends) and the LHCP rejection (dB, how much weaker LHCP is received
// than RHCP from the same direction).
struct AntennaPattern {
  std::vector<std::pair<double, double>> rhcp_gain_db_by_el_deg;  // sorted by elevation
  double lhcp_rejection_db = 15.0;
};
// A typical patch: above the horizon the C/N0 model's table (patch_antenna_gain_table() in
// models/tracking.hpp: 0 dB at the zenith, -5 dB at 20 deg, -13 dB at the horizon), below it
// falling linearly to -20 dB at the nadir (back lobe).
AntennaPattern patch_antenna_pattern();
double antenna_gain_db(const AntennaPattern& a, double el_rad, bool lhcp);

// ---- Signal paths seen by the receiver -------------------------------------------------------
// One path: its code delay relative to the direct path, metres, and its complex amplitude
// relative to the unobstructed direct signal (1 = the direct signal at full strength, 0
// blocked), whose argument is the path's carrier phase relative to the direct path in the
// convention above (excess Delta: factor e^{-j 2 pi Delta / lambda}).
struct PathSignal {
  double delay_m = 0.0;
  std::complex<double> amplitude{1.0, 0.0};
};

// ---- Code tracking of the composite signal -----------------------------------------------------
// Coherent early-minus-late DLL with early-late spacing d chips on a BPSK signal with the
// ideal triangular autocorrelation R(x) = max(0, 1 - |x|) (x in chips, infinite bandwidth),
// its carrier locked to the composite phase phi_c = arg(P(eps)), P(eps) = sum a_i R(eps - tau_i):
//   D(eps) = sum_i Re(a_i e^{-j phi_c}) [R(eps - tau_i - d/2) - R(eps - tau_i + d/2)]
// (Braasch, Springer Handbook of GNSS ch. 15; van Nee, IEEE TAES 29(4), 1993). D > 0 when the
// replica is late; the loop settles where D crosses zero from negative to positive. The zero
// is found as a sign change of |P| D = Re(conj(P) Q) (Q the early-minus-late sum), which is
// piecewise quadratic in eps: bracketed between the correlation functions' corners and the
// quadratics' vertices, then bisected. A stretch where D vanishes identically with signal
// present (a neutral plateau, e.g. two equal paths a chip apart) yields its middle; zeros
// where the prompt P vanishes (no carrier reference) are discarded.
// Which zero: the paths within kEmlSignificantPathRatio of the strongest path's amplitude are
// "significant"; the tracking point is the stable zero nearest to the earliest significant path
// within its pull-in range (|eps - tau| <= 1 + d/2), else nearest to the next significant path,
// else the stable zero with the largest prompt. Returns eps in metres (the code-phase error
// relative to the direct path's delay 0), or nullopt when no path has signal, no stable zero
// exists, or d <= 0.
inline constexpr double kEmlSignificantPathRatio = 0.5;  // amplitude, -6 dB
std::optional<double> eml_tracking_error_m(const std::vector<PathSignal>& paths,
                                           double chip_spacing, double chip_length_m = 293.052);

// Composite signal power relative to the unobstructed direct signal, dB: 20 log10 |P(eps)|,
// the prompt correlator's amplitude at the tracking point; floored at kCompositePowerFloorDb
// (complete cancellation).
inline constexpr double kCompositePowerFloorDb = -200.0;
double composite_power_db(const std::vector<PathSignal>& paths, double tracking_error_m,
                          double chip_length_m = 293.052);

// Carrier phase error of the composite at the tracking point as a range error, metres
// (positive: the carrier phase measures a longer range, as a longer path does):
// -arg(P(eps)) lambda / 2 pi modulo lambda. The whole wavelengths are those of the path that
// contributes most to P(eps) (largest |a_i R(eps - tau_i)|, delay tau_k): the result is
//   tau_k - arg(P(eps) e^{+j 2 pi tau_k / lambda}) lambda / 2 pi,  the arg in (-pi, pi],
// so that a receiver tracking a lone reflection (NLOS) sees its whole excess path in the
// carrier phase as in the code, and one dominated by the direct path a small error. 0 when
// P(eps) = 0.
double composite_phase_error_m(const std::vector<PathSignal>& paths, double tracking_error_m,
                               double wavelength_m = kL1WavelengthM,
                               double chip_length_m = 293.052);

// ---- The paper's rule ------------------------------------------------------------------------
// The paper (sect. 2.1): "The first return multipath range for an SV is used when the time
// difference between the first and second returns is less than the cut-off time for the
// modeled receiver (typically 150 ns or 45-meter path difference)." Read here as: returns are
// the paths with non-zero amplitude, sorted by delay; when the second return is less than
// cutoff_m behind the first (or there is only one), the pseudorange follows the first return;
// otherwise the correlator resolves them and the receiver, having acquired the strongest peak,
// follows the strongest return (the earliest of equally strong ones). Returns the delay (m)
// the pseudorange follows, nullopt when no path has signal.
std::optional<double> paper_rule_delay_m(const std::vector<PathSignal>& paths, double cutoff_m = 45.0);

}  // namespace navemu
