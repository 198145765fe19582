#pragma once
// Radio-frequency interference (jamming) as a receiver sees it: the loss of C/N0 after the
// correlator and what the front end's monitors (AGC, noise level, CW indicator) show.
//
// Effective C/N0 (Ward 1994; Kaplan & Hegarty, "Understanding GPS", 2nd ed., section 9.2.2):
//   (C/N0)_eff = [ 1/(C/N0) + (J/S) / (Q Rc) ]^-1
// J/S the jammer-to-signal power ratio at the antenna, Rc the spreading code's chip rate and Q
// the spectral separation coefficient of the jammer's spectrum against the code's: 1 for a
// narrowband (CW) jammer on a spectral line, 1.5 for a matched-spectrum one, 2 for a wideband
// one. With strong wideband jamming on C/A (Rc = 1.023 Mchip/s), C/N0 -> 10 log10(2 Rc) - J/S
// = 63.1 dB-Hz - J/S: the rule of thumb "C/N0 = 63 - J/S" for C/A.
//
// Several jammers on a band add their powers; their (J/S)/Q terms add in the formula.

#include <cstdint>
#include <optional>

#include "models/event_window.hpp"

namespace navemu {

enum class InterferenceKind { kCw, kMatchedSpectrum, kWideband };

// Q of the formula above (Kaplan & Hegarty section 9.2.2).
double spectral_separation_q(InterferenceKind k);

// The interference on one band at one instant, as linear power ratios to the nominal received
// signal power S (all 0: none).
struct BandInterference {
  double j_over_s = 0.0;     // every jammer's power
  double cw_j_over_s = 0.0;  // the narrowband (CW) jammers' part of it
  double j_over_qs = 0.0;    // sum of (J/S)/Q: what reaches the correlator
  void add(double j_over_s_db, InterferenceKind k);
  bool any() const { return j_over_s > 0.0; }
};

// (C/N0)_eff of a signal of `cn0_dbhz` and chip rate `chip_rate_hz` under `i`.
double effective_cn0_dbhz(double cn0_dbhz, const BandInterference& i, double chip_rate_hz);

// A jammer's J/S at an event level: linear in dB over the kJammerRampDepth_db below its peak, as
// the power of an approaching or receding jammer changes by decades (1/r^2), not in a linear
// power ramp that would reach within 10 dB of the peak in the first tenth of the ramp. Level 0:
// off (nullopt).
inline constexpr double kJammerRampDepth_db = 40.0;
std::optional<double> ramped_j_over_s_db(double peak_db, double level);

// The RF front end's monitors (u-blox MON-HW / MON-RF noisePerMS, agcCnt, jamInd), from their
// open-sky readings and the interference on the band.
//  - J/N over the front end's bandwidth: J/N = J/S + S/N, S/N = (S/N0) - 10 log10(B) with the
//    nominal S/N0 of IS-GPS-200's minimum received power (-158.5 dBW, section 3.3.1.6) over
//    kT0 (-204 dBW/Hz) and a 2 dB noise figure: 43.5 dB-Hz; B the C/A main lobe, 2.046 MHz.
//  - AGC: the gain falls by the rise of the in-band power, 10 log10(1 + J/N) dB. The scale of
//    agcCnt (0..8191) is not published; navemu takes it as a 60 dB range (136.5 counts per dB).
//  - Noise level: the noise density after the correlator rises by the C/N0 loss of a nominal
//    signal, 10 log10(1 + (S/N0) (J/S)/(Q Rc)); noisePerMS is scaled by that ratio.
//  - CW indicator: rises by 5 counts per dB of CW J/N above 0 (navemu's scale; 255 at 51 dB).
struct FrontEndReading {
  std::uint16_t noise_per_ms = 0, agc_cnt = 0;  // agcCnt of 8191
  std::uint8_t jam_ind = 0;                     // of 255
};
struct FrontEndMonitor {
  FrontEndReading reading;     // what the monitors show
  double broadband_j_over_n_db = -300.0;  // the non-CW jammers over the front end's noise
  double cw_j_over_n_db = -300.0;         // the CW jammers
};
inline constexpr double kNominalSignalToNoiseDensity_dbhz = 43.5;
inline constexpr double kFrontEndBandwidth_hz = 2.046e6;
FrontEndMonitor front_end_monitor(const FrontEndReading& open_sky, const BandInterference& i,
                                  double chip_rate_hz);

}  // namespace navemu
