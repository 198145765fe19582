#pragma once
// The GNSS measurement generator: what a receiver at a true position measures from every
// satellite in view. Each pseudorange is assembled from its physical terms (Durst & Goodin
// section 2.1, extended):
//   P = R + dR_iono + dR_trop,hydro + dR_trop,wet + dR_SV + c (dt_rx - dt_sv) + noise
// with Doppler and carrier phase consistent with it. Every term evolves continuously in time
// and draws from its own seeded random stream, so a stationary receiver wanders as a real
// one does and the same seed gives the same numbers.
//
// The emulator's receiver is this generator plus the solver (models/solver.hpp).

#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <vector>

#include "core/satellite.hpp"
#include "core/signal.hpp"
#include "models/atmosphere.hpp"
#include "models/ephemeris.hpp"
#include "models/geodesy.hpp"
#include "models/interference.hpp"
#include "models/orbit.hpp"
#include "models/random.hpp"
#include "models/receiver_clock.hpp"
#include "models/sat_errors.hpp"
#include "models/signal_environment.hpp"
#include "models/solver.hpp"
#include "core/time.hpp"
#include "models/tracking.hpp"

namespace navemu {

// Receiver modes of the paper (section 2.1): which errors reach the position engine.
enum class ReceiverMode {
  kStandalone,     // single frequency, every error; broadcast corrections applied
  kDualFrequency,  // L1 + L2: the ionosphere removed by the iono-free combination
  kDgps,           // differential code: only the differential troposphere and noise remain
  kRtkFixed,       // carrier-phase fixed: centimetre-level noise only
};

enum class IonoModel {
  kKlobuchar,  // the broadcast model of the navigation file (default when it carries one)
  kPaperVtec,  // the paper's mapping of a configured vertical TEC
};

// The signals generated, by band: L1 C/A, L2C (the CL pilot) and the L5 pilot (Q).
enum class Band { kL1 = 0, kL2 = 1, kL5 = 2 };
constexpr std::uint32_t band_bit(Band b) { return 1u << static_cast<unsigned>(b); }
inline constexpr std::uint32_t kAllBands = band_bit(Band::kL1) | band_bit(Band::kL2) | band_bit(Band::kL5);

// Scheduled impairments, each acting through the signals (EventWindow: seconds from the
// scenario's start; ramps where they apply).
//
// A jammer: its J/S at the antenna on one band at full level and its spectrum.
struct JammingEvent {
  EventWindow window;
  double j_over_s_db = 0.0;
  InterferenceKind kind = InterferenceKind::kWideband;
  Band band = Band::kL1;
};
// A sky mask (a tunnel, an urban canyon): signals arriving from azimuths from az_from_deg
// clockwise to az_to_deg and below below_el_deg are blocked. The defaults block everything.
struct OutageEvent {
  EventWindow window;
  double az_from_deg = 0.0, az_to_deg = 360.0;
  double below_el_deg = 90.0;
};
// The antenna open (cable cut) or shorted: no signal reaches the receiver; the antenna
// supervisor reports it (u-blox MON-HW aStatus, MON-RF antStatus).
enum class AntennaFault { kOpen, kShort };
struct AntennaEvent {
  EventWindow window;
  AntennaFault fault = AntennaFault::kOpen;
};
// A satellite fault. What the broadcast data do not show: a clock error (the satellite's
// ranges, code and carrier, grow by clock_error_m times the event's level, so a ramp is a clock
// drifting off) and an orbit error (the satellite orbits orbit_error_rac_m, radial, along-track
// and cross-track, off its broadcast position: the ranges change by its projection on the line
// of sight). And what they do show: the satellite flagged unhealthy (IS-GPS-200 20.3.3.3.1.4
// SV health), so receivers track it and leave it out of the fix while the event's level is > 0.
struct SatelliteFaultEvent {
  EventWindow window;
  SatId sat;
  double clock_error_m = 0.0;
  Vec3 orbit_error_rac_m = Vec3::Zero();
  bool unhealthy = false;
};
// An ionospheric storm: the true ionospheric delay of every signal scaled by 1 + (scale - 1) x
// level while the broadcast model receivers correct with stays as it was, so single-frequency
// fixes take the difference and dual-frequency ones remove it, as in the field (storm-time
// total electron content reaches several times its quiet value: Mannucci et al. 2005,
// Geophys. Res. Lett. 32, L12S02, the 2003 "Halloween" storms).
struct IonosphereEvent {
  EventWindow window;
  double scale = 1.0;
};
// Multipath intensity: every code, carrier and Doppler multipath error (the scene's, or the
// statistical model's in open sky) scaled by 1 + (scale - 1) x level: a rougher or more
// reflective surrounding than the scenario's.
struct MultipathEvent {
  EventWindow window;
  double scale = 1.0;
};
// A spoofer sending a coherent false signal set: every satellite's signal as it would arrive at
// a false position offset_enu_m (east, north, up) from the antenna, times the event's level,
// and power_advantage_db stronger than the true signals, so the tracking loops follow it. A
// ramp walks the receiver off gradually, as a takeover does (its ranges, Doppler and position
// stay consistent: the pull's rate shows as velocity). The receiver's spoofing monitor
// indicates it (u-blox NAV-STATUS spoofDetState) when the signals come kSpoofDetectPower_db or
// more above the true ones: C/N0 above what the sky gives is the monitor's telltale, and a
// spoofer matched in power goes unnoticed (a navemu assumption: u-blox does not publish its
// detector).
// A time spoofer pulls the receiver's time instead (or as well): it sends the sky as it will be
// time_offset_s x level later (earlier when negative), satellites and time stamps alike, so the
// receiver's fix stays where it is and the time it keeps, and reports, is off by that much.
inline constexpr double kSpoofDetectPower_db = 3.0;
struct SpoofingEvent {
  EventWindow window;
  Vec3 offset_enu_m = Vec3::Zero();
  double power_advantage_db = 3.0;
  double time_offset_s = 0.0;
};
// Events of the receiver as a device, acted on by its channel (emulator/gnss_channel.cpp), not
// by the signal model:
//  - the cable unplugged: the receiver's ports carry nothing either way while it lasts (the
//    receiver keeps running);
//  - a reset (a power cycle, a watchdog): the receiver goes silent for kResetSilence_s, then
//    searches (no fix, no satellites) until its time to first fix for the start it makes
//    (a hot start keeps ephemerides and position, a warm start the almanac, a cold start
//    nothing); a u-blox receiver rebuilds its RAM configuration from the layers below, so a
//    client's unsaved settings are lost. The window: its start (the duration is the reset's).
enum class RestartKind : std::uint8_t { kHot, kWarm, kCold };
// The time to first fix after a restart (u-blox M8 data sheet, UBX-15031086: hot start 1 s,
// cold start 26 s; a warm start still has to collect the ephemerides, about as long: 25 s).
inline double restart_ttff_s(RestartKind k) {
  return k == RestartKind::kHot ? 1.0 : k == RestartKind::kWarm ? 25.0 : 26.0;
}
// The boot after a reset, output silent (a navemu assumption; u-blox does not publish it).
inline constexpr double kResetSilence_s = 0.5;
struct CableEvent {
  EventWindow window;
};
struct ResetEvent {
  EventWindow window;
  RestartKind kind = RestartKind::kHot;
};
struct GnssEvents {
  std::vector<JammingEvent> jamming;
  std::vector<OutageEvent> outages;
  std::vector<AntennaEvent> antenna;
  std::vector<SatelliteFaultEvent> satellites;
  std::vector<SpoofingEvent> spoofing;
  std::vector<IonosphereEvent> ionosphere;
  std::vector<MultipathEvent> multipath;
  std::vector<CableEvent> cable;
  std::vector<ResetEvent> resets;
  std::size_t size() const {
    return jamming.size() + outages.size() + antenna.size() + satellites.size() + spoofing.size() +
           ionosphere.size() + multipath.size() + cable.size() + resets.size();
  }
  // fn(events) for each kind's list.
  template <class Fn>
  void for_each_list(Fn&& fn) {
    fn(jamming);
    fn(outages);
    fn(antenna);
    fn(satellites);
    fn(spoofing);
    fn(ionosphere);
    fn(multipath);
    fn(cable);
    fn(resets);
  }
  // fn(EventWindow&) for every event's window.
  template <class Fn>
  void for_each_window(Fn&& fn) {
    for_each_list([&](auto& list) {
      for (auto& e : list) fn(e.window);
    });
  }
  void append(const GnssEvents& e) {
    const auto add = [](auto& to, const auto& from) { to.insert(to.end(), from.begin(), from.end()); };
    add(jamming, e.jamming);
    add(outages, e.outages);
    add(antenna, e.antenna);
    add(satellites, e.satellites);
    add(spoofing, e.spoofing);
    add(ionosphere, e.ionosphere);
    add(multipath, e.multipath);
    add(cable, e.cable);
    add(resets, e.resets);
  }
};

enum class SatErrorModel {
  kGaussMarkov,  // correlated radial/along/cross orbit and clock errors (default)
  kPaper,        // the paper's formula (Hwang & Parkinson)
};

// Every error source can be switched off on its own.
struct ErrorSwitches {
  bool ionosphere = true;
  bool troposphere = true;
  bool satellite = true;       // broadcast orbit and clock errors
  bool receiver_clock = true;
  bool noise = true;           // tracking noise of code, phase and Doppler
  bool multipath = true;       // statistical code multipath (the scene model replaces it)
};

struct MeasurementConfig {
  ReceiverMode mode = ReceiverMode::kStandalone;
  ErrorSwitches errors;

  IonoModel iono_model = IonoModel::kKlobuchar;
  double vtec_tecu = 12.0;  // for kPaperVtec (the paper's validation value)
  // The broadcast model describes the true ionosphere only to ~50 % RMS (Klobuchar 1987).
  // The true delay is the model's times (1 + s), s a Gauss-Markov scale error common to the
  // sky, plus the horizontal gradients the model lacks: north and east gradients of the
  // vertical delay (Gauss-Markov, m per degree) evaluated at each satellite's ionospheric
  // pierce point (IS-GPS-200 20.3.3.5.2.5 geometry) and mapped with the Klobuchar obliquity,
  // plus a small per-satellite fraction. The sizes were set so that synthetic and real
  // single-point solutions of the reference stations agree (tools/real-vs-synthetic).
  double iono_common_error_fraction = 0.3;
  double iono_gradient_sigma_m_per_deg = 0.05;
  double iono_satellite_error_fraction = 0.03;
  double iono_error_tau_s = 1800.0;

  // Surface meteorology for the true troposphere (Saastamoinen zenith delays, Niell mapping);
  // unset: standard atmosphere at the receiver height, 50 % relative humidity.
  std::optional<Meteo> meteo;
  // Wet zenith delay variability not described by surface meteorology.
  double tropo_wet_sigma_m = 0.03;
  double tropo_wet_tau_s = 3600.0;
  // DGPS: the residual of the troposphere difference between base and rover, zenith.
  double dgps_tropo_residual_sigma_m = 0.05;

  SatErrorModel sat_error_model = SatErrorModel::kGaussMarkov;
  SatErrorParams sat_errors;

  ReceiverClockParams clock;
  TrackingParams tracking;
  Cn0Model cn0;
  // C/N0 differs between satellites at one elevation (transmit power, antenna patterns) and
  // drifts along each arc; with the noise switch, each satellite's C/N0 is the model's plus an
  // offset drawn once per satellite and a Gauss-Markov fluctuation seen through the receiver's
  // C/N0 estimator (a first-order average). Against the real ZED-F9T of
  // receiver_logs/nav-solutions (NAV-SAT, 5 min, whole dB-Hz): across satellites at 40-90 deg
  // 2.2 dB; along arcs above 30 deg, about a linear trend, 0.60 dB with a correlation of 0.58
  // at 10 s (test Cn0Spread.SatellitesDifferAndDriftLikeTheRealF9t).
  double cn0_satellite_sigma_db = 2.0;
  double cn0_fluctuation_sigma_db = 0.6;
  double cn0_fluctuation_tau_s = 25.0;
  double cn0_estimator_tau_s = 3.0;
  // Code multipath, 1-sigma at the zenith, growing as 1/sin(el) toward the horizon, with a
  // correlation time of a minute (typical open-sky geodetic site).
  double multipath_zenith_sigma_m = 0.1;
  double multipath_tau_s = 60.0;
  double rtk_noise_sigma_m = 0.01;

  // The bands whose signals are generated (band_bit): the receiver's front ends, e.g. L1 and L2
  // for the ZED-F9P. L1 always; all three in kDualFrequency. A satellite that does not broadcast
  // a band's signal at the time (broadcasts(): GPS L2C and L5 by block, BeiDou B2I) has none,
  // except in kDualFrequency (see generate()).
  std::uint32_t bands = band_bit(Band::kL1);
  // The systems tracked (system_bit) among those the navigation data have records of.
  std::uint32_t systems = system_bit(GnssSystem::kGps);
  double elevation_mask_deg = 5.0;      // the position engine's mask
  // A scene around the receiver (models/signal_environment.hpp): visibility, multipath of
  // code, carrier and Doppler, and the composite C/N0 per satellite; replaces the statistical
  // multipath. None: open sky.
  std::shared_ptr<const SignalEnvironmentModel> environment;
  // Impairments. Jammers (models/interference.hpp) lower every signal's C/N0 on their band by
  // the effective-C/N0 formula, and signals below the tracking threshold lose lock; sky masks
  // and antenna faults block signals; satellite faults add to one satellite's ranges.
  GnssEvents events;
  std::uint64_t seed = 1;
  // The position engine's code smoothed by the carrier (CarrierSmoother, models/tracking.hpp)
  // over this window, s, in the standalone and dual-frequency modes (the L1 carrier, the
  // iono-free one); 0: raw code. Raw measurements (SignalObs) are never smoothed.
  double carrier_smoothing_s = 0.0;
};

inline constexpr std::array<SignalId, 3> kBandSignals = {kGpsL1CA, kGpsL2CL, kGpsL5Q};
inline constexpr std::array<double, 3> kBandFreq_Hz = {carrier_frequency_hz(kBandSignals[0]),
                                                       carrier_frequency_hz(kBandSignals[1]),
                                                       carrier_frequency_hz(kBandSignals[2])};
// Their spreading codes' chip rates (IS-GPS-200 3.3.2: C/A 1.023 Mchip/s; L2C's CM and CL
// time-multiplexed, 1.023 Mchip/s together; IS-GPS-705 3.3.2: L5 10.23 Mchip/s).
inline constexpr std::array<double, 3> kBandChipRate_Hz = {1.023e6, 1.023e6, 10.23e6};

// The signal each system sends in each Band slot, as a multi-band receiver's front ends take
// them (the ZED-F9P's L1 and L2 bands, the F9 L1/L5 products' L5 band), with its chip rate:
//   L1: GPS and QZSS L1 C/A, Galileo E1 C, BeiDou B1I (2.046 Mchip/s, BDS-SIS-ICD-B1I 3.0
//       4.2.2), GLONASS L1OF (0.511 Mchip/s, GLONASS ICD 5.1 3.3.1.2);
//   L2: GPS and QZSS L2C, Galileo E5b Q, BeiDou B2I (2.046 Mchip/s), GLONASS L2OF;
//   L5: GPS and QZSS L5 Q, Galileo E5a Q (10.23 Mchip/s, Galileo OS SIS ICD 2.0 2.3); none for
//       BeiDou B1I/B2I-class satellites and GLONASS FDMA.
// Galileo E1's 1.023 Mchip/s: OS SIS ICD 2.0 2.3.
struct BandSignal {
  SignalId id;
  double chip_rate_hz = 0.0;
};
std::optional<BandSignal> band_signal(GnssSystem system, Band band);

struct SignalObs {
  SignalId signal;
  double carrier_hz = 0.0;  // for GLONASS of the satellite's frequency channel
  double pseudorange_m = 0.0;
  double carrier_cycles = 0.0;  // accumulated carrier phase (advances with the ionosphere)
  double doppler_hz = 0.0;
  double cn0_dbhz = 0.0;
  bool loss_of_lock = false;  // first epoch of a new carrier arc
  double lock_time_s = 0.0;
  // The tracking loops' 1-sigma at cn0_dbhz (tracking_noise), also when no noise is applied:
  // the measurement quality the receiver reports (RXM-RAWX prStdev, cpStdev, doStdev).
  TrackingNoise sigma;
};

struct SatMeasurement {
  SatId sat;
  BroadcastRecord record;  // the broadcast record used
  const GpsEphemeris* eph = nullptr;  // the same for GPS and QZSS (LNAV), else null
  int glonass_channel = 0;  // GLONASS frequency channel k
  AzEl dir;
  SatStateAt transmit;           // the broadcast state at the true transmit time (its own frame)
  double range_m = 0.0;          // true geometric range (light time and Earth rotation)
  double range_rate_mps = 0.0;
  // The terms of the L1 pseudorange, metres (for inspection and tests).
  double iono_l1_m = 0.0;
  double tropo_hydro_m = 0.0;
  double tropo_wet_m = 0.0;
  double sat_error_m = 0.0;        // broadcast orbit + clock error on the line of sight
  double sat_clock_m = 0.0;        // c (dt_sv - L1 group delay) from the broadcast record
  double multipath_m = 0.0;
  bool nlos = false;               // tracked on reflections only (scene)
  bool unhealthy = false;          // flagged so by its broadcast data (SatelliteFaultEvent)
  std::array<std::optional<SignalObs>, 3> signals;  // by Band (band_signal)
  // The pseudorange the position engine uses in the configured mode (L1 in standalone, the
  // iono-free combination in dual-frequency, the differentially corrected one in DGPS/RTK).
  double engine_pseudorange_m = 0.0;
  // That pseudorange smoothed by its carrier (MeasurementConfig::carrier_smoothing_s; equal to
  // it when not smoothed), and the fractions of the code noise's and code multipath's variance
  // the smoothing leaves in it (CarrierSmoother; 1: none).
  double smoothed_pseudorange_m = 0.0;
  double smoothed_noise_fraction = 1.0, smoothed_multipath_fraction = 1.0;
};

struct EpochMeasurements {
  // The receiver's time tag: its clock's millisecond tick nearest the epoch (+ a spoofer's pull).
  GpsTime t_receiver;
  GpsTime t_true;               // true GPS time of reception
  double rx_clock_bias_s = 0.0;
  double rx_clock_drift_sps = 0.0;
  std::vector<SatMeasurement> sats;  // tracked satellites above the horizon, by SatId
  std::array<BandInterference, 3> interference{};  // by Band, at the epoch
  std::optional<AntennaFault> antenna_fault;       // at the epoch
  bool spoofed = false;             // a spoofer's signals are tracked (SpoofingEvent)
  bool spoofing_indicated = false;  // and the spoofing monitor sees it
  double spoofed_time_s = 0.0;      // how far the spoofer pulled the receiver's time
};

// Receiver classes: tracking loops, antenna and site as they differ between a geodetic receiver
// (narrow correlator, carrier-aided code loop, choke-ring antenna) and a mass-market one
// (standard correlator, patch antenna); everything else keeps its defaults.
enum class ReceiverClass { kGeodetic, kConsumer };
void apply_receiver_class(MeasurementConfig& cfg, ReceiverClass rc);

class MeasurementGenerator {
 public:
  // `nav` must outlive the generator (a temporary does not compile).
  MeasurementGenerator(const NavData& nav, const MeasurementConfig& cfg);
  MeasurementGenerator(NavData&&, const MeasurementConfig&) = delete;
  ~MeasurementGenerator();
  MeasurementGenerator(const MeasurementGenerator&) = delete;
  MeasurementGenerator& operator=(const MeasurementGenerator&) = delete;

  // Measurements of the navigation epoch `t_epoch` (the desired time: the receiver tags them at
  // its clock's nearest millisecond tick, EpochMeasurements::t_receiver) for a receiver at
  // `p_rx_ecef_m` moving with `v_rx_ecef_mps`. Calls must come in increasing time.
  EpochMeasurements generate(GpsTime t_epoch, const Vec3& p_rx_ecef_m,
                             const Vec3& v_rx_ecef_mps = Vec3::Zero());
  // The same into `out`, reusing its storage (the real-time loop's form).
  void generate(GpsTime t_epoch, const Vec3& p_rx_ecef_m, const Vec3& v_rx_ecef_mps,
                EpochMeasurements& out);

  // The measurements the receiver's position engine uses in the configured mode, with the
  // solver options that go with them (which corrections the receiver applies).
  std::vector<RangeMeasurement> solver_input(const EpochMeasurements& e) const;
  void solver_input(const EpochMeasurements& e, std::vector<RangeMeasurement>& out) const;
  SolverOptions solver_options() const;

  const MeasurementConfig& config() const { return cfg_; }
  // The scenario's start, from which the events' times count; unset: the first epoch's time.
  void set_event_origin(GpsTime start);
  // Events added while running (live control), and all of them ended.
  void add_events(const GnssEvents& e);
  void clear_events() { cfg_.events = {}; }
  // Of the systems configured (MeasurementConfig::systems), those tracked from the next epoch
  // on (system_bit; all by default): the others' satellites lose lock at once and are
  // re-acquired after the tracking loops' re-acquisition time when enabled again.
  // The same for the second band (Band::kL2, of the configured bands): the systems whose L2
  // signal is enabled (u-blox CFG-SIGNAL-*_L2*_ENA).
  void set_active_systems(std::uint32_t systems, std::uint32_t l2_systems = ~0u) {
    active_systems_ = systems;
    active_l2_systems_ = l2_systems;
  }

 private:
  struct State;
  const NavData& nav_;
  MeasurementConfig cfg_;
  std::uint32_t active_systems_ = ~0u, active_l2_systems_ = ~0u;
  std::unique_ptr<State> state_;
};

}  // namespace navemu
