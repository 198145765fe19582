// The measurement generator: pseudorange assembly term by term, carrier and Doppler consistent
// with it, the paper's receiver modes, continuity in time, determinism and seeded statistics.

#include "models/measurement.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>

#include "models/constellation.hpp"
#include "models/solver.hpp"

namespace navemu {
namespace {

const Geodetic kSite{32.3, -90.9, 60.0};  // the paper's test site, Vicksburg, MS
const GpsTime kStart = from_week_tow(2244, 36000.0);

MeasurementConfig all_off() {
  MeasurementConfig c;
  c.errors = ErrorSwitches{false, false, false, false, false, false};
  return c;
}

TEST(Measurement, ErrorFreePseudorangesAreRangeMinusBroadcastClock) {
  const NavData nav = nominal_constellation(kStart);
  MeasurementGenerator gen(nav, all_off());
  const Vec3 p = ecef_from_geodetic(kSite);
  const EpochMeasurements e = gen.generate(kStart, p);
  ASSERT_GE(e.sats.size(), 6u);
  for (const SatMeasurement& m : e.sats) {
    ASSERT_TRUE(m.signals[0]);
    EXPECT_NEAR(m.signals[0]->pseudorange_m, m.range_m - m.sat_clock_m, 1e-6) << m.sat.number();
  }
  // ... and the solver gets the position back exactly.
  SolverOptions o;
  o.elevation_mask_deg = 0.0;
  const Solution s = solve(gen.solver_input(e), e.t_receiver, o);
  ASSERT_EQ(s.fix, FixType::k3D);
  EXPECT_LT((s.p_ecef_m - p).norm(), 1e-3);
}

// Galileo satellites keep GST: a receiver on GPS time measures their pseudoranges short by c
// times the broadcast GST - GPST (the GGTO, RINEX GAGP; Galileo OS SIS ICD 2.0 5.1.8), at the
// epoch's time; GPS is untouched, and the solver's inter-system bias takes the offset up.
TEST(Measurement, GalileoPseudorangesCarryTheGstGpsTimeOffset) {
  const unsigned systems = system_bit(GnssSystem::kGps) | system_bit(GnssSystem::kGalileo);
  const NavData plain = nominal_constellation(kStart, systems);
  NavData with = plain;
  with.time_offsets.push_back(TimeSystemOffset{"GAGP", 20e-9, 1e-12, 0.0, kStart.plus_s(-1000.0), "test"});
  MeasurementConfig cfg = all_off();
  cfg.systems = systems;
  MeasurementGenerator a(plain, cfg), b(with, cfg);
  const Vec3 p = ecef_from_geodetic(kSite);
  const EpochMeasurements ea = a.generate(kStart, p), eb = b.generate(kStart, p);
  ASSERT_EQ(ea.sats.size(), eb.sats.size());
  const double expected_m = -kSpeedOfLight_mps * (20e-9 + 1e-12 * 1000.0);  // -6.3 m
  int galileo = 0;
  for (std::size_t i = 0; i < ea.sats.size(); ++i) {
    const bool gal = ea.sats[i].sat.system() == GnssSystem::kGalileo;
    galileo += gal ? 1 : 0;
    EXPECT_NEAR(eb.sats[i].signals[0]->pseudorange_m - ea.sats[i].signals[0]->pseudorange_m, gal ? expected_m : 0.0, 1e-6)
        << ea.sats[i].sat.rinex();
  }
  EXPECT_GE(galileo, 4);
  SolverOptions o;
  o.elevation_mask_deg = 0.0;
  const Solution s = solve(b.solver_input(eb), eb.t_receiver, o);
  ASSERT_EQ(s.fix, FixType::k3D);
  EXPECT_LT((s.p_ecef_m - p).norm(), 1e-3);
}

TEST(Measurement, PseudorangeIsTheSumOfItsTermsAndCarrierAndDopplerAgree) {
  NavData nav = nominal_constellation(kStart);
  MeasurementConfig c;
  c.errors.noise = false;
  c.bands = kAllBands;
  MeasurementGenerator gen(nav, c);
  const Vec3 p = ecef_from_geodetic(kSite);
  const EpochMeasurements e0 = gen.generate(kStart, p);
  const EpochMeasurements e1 = gen.generate(kStart.plus_s(1.0), p);
  const double cc = kSpeedOfLight_mps;
  for (const SatMeasurement& m : e0.sats) {
    const double tgd_m = cc * m.eph->tgd_s;
    const double rest = m.range_m + cc * e0.rx_clock_bias_s - m.sat_clock_m + m.tropo_hydro_m +
                        m.tropo_wet_m + m.sat_error_m + m.multipath_m;
    EXPECT_NEAR(m.signals[0]->pseudorange_m, rest + m.iono_l1_m, 1e-6);
    // L2: the ionosphere and TGD scale with (f1/f2)^2 (IS-GPS-200 20.3.3.3.3.2); only from the
    // satellites that send L2C.
    const double g2 = std::pow(kGpsL1_Hz / kGpsL2_Hz, 2);
    ASSERT_EQ(m.signals[1].has_value(), broadcasts(m.sat, kGpsL2CL, kStart)) << m.sat.rinex();
    if (m.signals[1]) {
      EXPECT_NEAR(m.signals[1]->pseudorange_m, rest + g2 * m.iono_l1_m + (g2 - 1) * tgd_m, 1e-6);
    }
    // Carrier: advanced by the ionosphere by as much as the code is delayed, plus N lambda;
    // code multipath (metres) does not reach the carrier (centimetres at most).
    const double lambda1 = cc / kGpsL1_Hz;
    const double n =
        (m.signals[0]->carrier_cycles * lambda1 - (rest - m.multipath_m - m.iono_l1_m)) / lambda1;
    EXPECT_NEAR(n, std::round(n), 1e-3);
    EXPECT_TRUE(m.signals[0]->loss_of_lock);  // first epoch of the arc
  }
}

TEST(Measurement, DopplerIsMinusTheCarrierPhaseRate) {
  // The deterministic terms only: the Gauss-Markov error terms have no derivative.
  const NavData nav = nominal_constellation(kStart);
  MeasurementGenerator gen(nav, all_off());
  const Vec3 p = ecef_from_geodetic(kSite);
  const EpochMeasurements e0 = gen.generate(kStart, p);
  const EpochMeasurements e1 = gen.generate(kStart.plus_s(1.0), p);
  ASSERT_EQ(e0.sats.size(), e1.sats.size());
  for (const SatMeasurement& m1 : e1.sats) {
    for (const SatMeasurement& m0 : e0.sats) {
      if (m0.sat != m1.sat) continue;
      const double phase_rate = m1.signals[0]->carrier_cycles - m0.signals[0]->carrier_cycles;
      const double mean_doppler = 0.5 * (m0.signals[0]->doppler_hz + m1.signals[0]->doppler_hz);
      EXPECT_NEAR(-phase_rate, mean_doppler, 0.005) << m1.sat.number();
      EXPECT_FALSE(m1.signals[0]->loss_of_lock);
    }
  }
}

TEST(Measurement, SameSeedSameNumbersOtherSeedOther) {
  const NavData nav = nominal_constellation(kStart);
  MeasurementConfig c;
  c.seed = 11;
  MeasurementGenerator a(nav, c), b(nav, c);
  c.seed = 12;
  MeasurementGenerator d(nav, c);
  const Vec3 p = ecef_from_geodetic(kSite);
  for (int k = 0; k < 5; ++k) {
    const GpsTime t = kStart.plus_s(k);
    const auto ea = a.generate(t, p), eb = b.generate(t, p), ed = d.generate(t, p);
    ASSERT_EQ(ea.sats.size(), eb.sats.size());
    for (std::size_t i = 0; i < ea.sats.size(); ++i) {
      EXPECT_EQ(ea.sats[i].signals[0]->pseudorange_m, eb.sats[i].signals[0]->pseudorange_m);
      EXPECT_NE(ea.sats[i].signals[0]->pseudorange_m, ed.sats[i].signals[0]->pseudorange_m);
    }
  }
}

// Position error of the configured receiver over a run, ENU, per epoch.
std::vector<Vec3> position_errors(MeasurementConfig c, double duration_s, double step_s) {
  const NavData nav = nominal_constellation(kStart);
  MeasurementGenerator gen(nav, c);
  const Vec3 p = ecef_from_geodetic(kSite);
  std::vector<Vec3> out;
  SolverOptions o = gen.solver_options();
  for (double t = 0; t <= duration_s; t += step_s) {
    const auto e = gen.generate(kStart.plus_s(t), p);
    const Solution s = solve(gen.solver_input(e), e.t_receiver, o);
    if (s.fix != FixType::k3D) continue;
    o.initial_p_ecef_m = s.p_ecef_m;
    out.push_back(enu_from_ecef(s.p_ecef_m, kSite));
  }
  return out;
}

double rms(const std::vector<Vec3>& v) {
  double s = 0;
  for (const Vec3& x : v) s += x.squaredNorm();
  return std::sqrt(s / static_cast<double>(v.size()));
}

TEST(Measurement, StationaryReceiverDriftsSmoothlyRatherThanJumpingWhite) {
  MeasurementConfig c;
  // The slowly varying terms only (code multipath, with its one-minute correlation time, moves
  // faster than this bound allows).
  c.errors.noise = false;
  c.errors.multipath = false;
  const auto err = position_errors(c, 600.0, 1.0);
  ASSERT_GT(err.size(), 590u);
  // Epoch-to-epoch change far below the error itself: a drift, as in the paper's Fig. 4-5
  // (white errors would step by sqrt(2) times their RMS; what steps here are satellites rising
  // and setting, which change the solution's geometry and weights).
  double step2 = 0;
  for (std::size_t i = 1; i < err.size(); ++i) step2 += (err[i] - err[i - 1]).squaredNorm();
  const double step_rms = std::sqrt(step2 / static_cast<double>(err.size() - 1));
  EXPECT_GT(rms(err), 0.3);
  EXPECT_LT(step_rms, 0.06 * rms(err));
}

TEST(Measurement, ModesOrderTheAccuracyAsThePaperDescribes) {
  // A geodetic receiver: its code noise is below the ionospheric error, so removing the
  // ionosphere pays for the iono-free combination's ~3x noise.
  MeasurementConfig c;
  apply_receiver_class(c, ReceiverClass::kGeodetic);
  c.seed = 3;
  c.mode = ReceiverMode::kStandalone;
  const double standalone = rms(position_errors(c, 1800.0, 30.0));
  c.mode = ReceiverMode::kDualFrequency;
  const double dual = rms(position_errors(c, 1800.0, 30.0));
  c.mode = ReceiverMode::kDgps;
  const double dgps = rms(position_errors(c, 1800.0, 30.0));
  c.mode = ReceiverMode::kRtkFixed;
  const double rtk = rms(position_errors(c, 1800.0, 30.0));
  std::printf("position RMS: standalone %.2f m, dual %.2f m, DGPS %.2f m, RTK %.3f m\n",
              standalone, dual, dgps, rtk);
  EXPECT_LT(dgps, standalone);
  EXPECT_LT(rtk, 0.1);  // centimetre noise through a DOP of a few
  EXPECT_LT(rtk, dgps);
  // Dual frequency: no ionosphere (the largest term here) but ~3x noise; still below standalone.
  EXPECT_LT(dual, standalone);
}

TEST(Measurement, IonosphericModelErrorHasItsConfiguredSigma) {
  // Across many seeds, the true/model ratio of the ionosphere minus one has the standard
  // deviation sqrt(common^2 + satellite^2) (both Gauss-Markov, stationary from the start);
  // the gradient term is switched off here and checked below.
  const NavData nav = nominal_constellation(kStart);
  MeasurementConfig c;
  c.errors = ErrorSwitches{true, false, false, false, false, false};
  c.iono_model = IonoModel::kPaperVtec;
  c.iono_gradient_sigma_m_per_deg = 0.0;
  const Vec3 p = ecef_from_geodetic(kSite);
  double sum = 0, sum2 = 0;
  int n = 0;
  for (std::uint64_t seed = 1; seed <= 400; ++seed) {
    c.seed = seed;
    MeasurementGenerator gen(nav, c);
    const auto e = gen.generate(kStart, p);
    const SatMeasurement& m = e.sats.front();
    const double model = iono_paper_mapping(m.dir.el_rad) * iono_zenith_delay_m(12.0, kGpsL1_Hz);
    const double x = m.iono_l1_m / model - 1.0;
    sum += x;
    sum2 += x * x;
    ++n;
  }
  const double sd = std::sqrt(sum2 / n - (sum / n) * (sum / n));
  const double expected = std::hypot(c.iono_common_error_fraction, c.iono_satellite_error_fraction);
  // Standard error of a standard deviation: sd / sqrt(2 n); bound at 5 sigma.
  EXPECT_NEAR(sd, expected, 5.0 * expected / std::sqrt(2.0 * n));
  EXPECT_NEAR(sum / n, 0.0, 5.0 * expected / std::sqrt(n));
}

TEST(Measurement, IonosphericGradientErrorVanishesOverheadAndGrowsTowardTheHorizon) {
  // Gradients only: the error of a satellite is obliquity x (gradient . pierce-point offset),
  // zero at the zenith; its spread across seeds grows with the pierce point's distance.
  const NavData nav = nominal_constellation(kStart);
  MeasurementConfig c;
  c.errors = ErrorSwitches{true, false, false, false, false, false};
  c.iono_model = IonoModel::kPaperVtec;
  c.iono_common_error_fraction = 0.0;
  c.iono_satellite_error_fraction = 0.0;
  const Vec3 p = ecef_from_geodetic(kSite);
  std::map<int, std::pair<double, double>> err2_and_el;  // PRN -> (sum of error^2, elevation)
  const int n = 200;
  for (std::uint64_t seed = 1; seed <= static_cast<std::uint64_t>(n); ++seed) {
    c.seed = seed;
    MeasurementGenerator gen(nav, c);
    for (const SatMeasurement& m : gen.generate(kStart, p).sats) {
      const double model = iono_paper_mapping(m.dir.el_rad) * iono_zenith_delay_m(12.0, kGpsL1_Hz);
      auto& [e2, el] = err2_and_el[m.sat.number()];
      e2 += (m.iono_l1_m - model) * (m.iono_l1_m - model);
      el = m.dir.el_rad;
    }
  }
  double highest_el = 0, rms_highest = 0, lowest_el = kPi, rms_lowest = 0;
  for (const auto& [prn, v] : err2_and_el) {
    const double r = std::sqrt(v.first / n);
    if (v.second > highest_el) highest_el = v.second, rms_highest = r;
    if (v.second < lowest_el) lowest_el = v.second, rms_lowest = r;
  }
  EXPECT_LT(rms_highest, 0.3);  // a high satellite's pierce point is near the receiver
  EXPECT_GT(rms_lowest, 3.0 * rms_highest);
}

TEST(Measurement, TrackingThresholdDropsWeakSignals) {
  const NavData nav = nominal_constellation(kStart);
  MeasurementConfig c = all_off();
  c.cn0.zenith_dbhz = 30.0;  // with the default gain table only high satellites stay above 28
  MeasurementGenerator gen(nav, c);
  const auto e = gen.generate(kStart, ecef_from_geodetic(kSite));
  ASSERT_FALSE(e.sats.empty());
  for (const SatMeasurement& m : e.sats) EXPECT_GE(m.signals[0]->cn0_dbhz, 28.0);
  MeasurementGenerator strong(nav, all_off());
  EXPECT_GT(strong.generate(kStart, ecef_from_geodetic(kSite)).sats.size(), e.sats.size());
}

TEST(Measurement, RisingSatelliteIsTrackedAfterTheReacquisitionTime) {
  // First epoch at which each PRN is tracked, with immediate and with 60 s re-acquisition.
  const NavData nav = nominal_constellation(kStart);
  auto first_tracked = [&](double reacq_s) {
    MeasurementConfig c = all_off();
    c.tracking.reacquisition_s = reacq_s;
    MeasurementGenerator gen(nav, c);
    std::map<int, double> first;
    for (double t = 0; t <= 7200; t += 10)
      for (const SatMeasurement& m : gen.generate(kStart.plus_s(t), ecef_from_geodetic(kSite)).sats)
        first.try_emplace(m.sat.number(), t);
    return first;
  };
  const auto immediate = first_tracked(0.0), delayed = first_tracked(60.0);
  int risers = 0;
  for (const auto& [prn, t] : immediate) {
    ASSERT_TRUE(delayed.count(prn));
    if (t == 0.0) {
      EXPECT_EQ(delayed.at(prn), 0.0) << "in track at the start: PRN " << prn;
    } else {
      ++risers;
      EXPECT_EQ(delayed.at(prn), t + 60.0) << "rising: PRN " << prn;
    }
  }
  EXPECT_GT(risers, 0);
}

// A jammer lowers every tracked signal's C/N0 on its band by the effective-C/N0 formula
// (models/interference.hpp), written out here: over a sweep of wideband J/S on L1, each
// satellite's C/N0 is the clear one's (same seed, no jammer) combined with (J/S)/(2 Rc) within
// 1 dB (to rounding); L2 and L5 keep theirs. Signals that fall below the tracking threshold are
// lost, and come back the re-acquisition time after the jammer goes.
TEST(Measurement, JammingLowersCn0ByTheFormulaAndLosesWeakSignals) {
  const NavData nav = nominal_constellation(kStart);
  MeasurementConfig clear_cfg = all_off();
  clear_cfg.bands = kAllBands;
  MeasurementGenerator clear(nav, clear_cfg);
  const auto ref = clear.generate(kStart, ecef_from_geodetic(kSite));
  ASSERT_GE(ref.sats.size(), 6u);
  std::size_t previous = ref.sats.size();
  for (double js = 0.0; js <= 50.0; js += 5.0) {
    MeasurementConfig c = clear_cfg;
    c.events.jamming = {JammingEvent{{0.0, 100.0, 0.0}, js, InterferenceKind::kWideband, Band::kL1}};
    MeasurementGenerator gen(nav, c);
    gen.set_event_origin(kStart);
    const auto e = gen.generate(kStart, ecef_from_geodetic(kSite));
    std::size_t matched = 0;
    for (const SatMeasurement& m : e.sats) {
      const auto r = std::find_if(ref.sats.begin(), ref.sats.end(), [&](const SatMeasurement& x) { return x.sat == m.sat; });
      ASSERT_NE(r, ref.sats.end());
      const double cn0 = r->signals[0]->cn0_dbhz;
      const double expected = -10.0 * std::log10(std::pow(10.0, -cn0 / 10.0) + std::pow(10.0, js / 10.0) / (2.0 * 1.023e6));
      EXPECT_NEAR(m.signals[0]->cn0_dbhz, expected, 1e-6) << "J/S " << js << " dB";
      EXPECT_GE(m.signals[0]->cn0_dbhz, c.tracking.tracking_threshold_dbhz);
      EXPECT_EQ(m.signals[1]->cn0_dbhz, r->signals[1]->cn0_dbhz) << "L2 has no jammer";
      EXPECT_EQ(m.signals[2]->cn0_dbhz, r->signals[2]->cn0_dbhz) << "L5 has no jammer";
      ++matched;
    }
    // Every clear signal that stays above the threshold under the jammer is still tracked.
    std::size_t expected_tracked = 0;
    for (const SatMeasurement& r : ref.sats) {
      const double cn0 = r.signals[0]->cn0_dbhz;
      if (-10.0 * std::log10(std::pow(10.0, -cn0 / 10.0) + std::pow(10.0, js / 10.0) / 2.046e6) >=
          c.tracking.tracking_threshold_dbhz)
        ++expected_tracked;
    }
    EXPECT_EQ(matched, expected_tracked) << "J/S " << js << " dB";
    std::printf("J/S %2.0f dB wideband on L1: %zu of %zu satellites tracked\n", js, matched, ref.sats.size());
    EXPECT_LE(matched, previous);
    previous = matched;
    EXPECT_NEAR(e.interference[0].j_over_s, std::pow(10.0, js / 10.0), 1e-6 * std::pow(10.0, js / 10.0));
    EXPECT_FALSE(e.interference[1].any());
  }
  EXPECT_EQ(previous, 0u) << "J/S 50 dB leaves 13 dB-Hz: nothing is tracked";

  // 45 dB from 10 s to 20 s: nothing tracked then; everything back 1 s (re-acquisition) later.
  MeasurementConfig c = all_off();
  c.events.jamming = {JammingEvent{{10.0, 10.0, 0.0}, 45.0, InterferenceKind::kWideband, Band::kL1}};
  MeasurementGenerator gen(nav, c);
  std::map<double, std::size_t> tracked;
  for (double t = 0.0; t <= 25.0; t += 0.5) tracked[t] = gen.generate(kStart.plus_s(t), ecef_from_geodetic(kSite)).sats.size();
  EXPECT_EQ(tracked[9.5], ref.sats.size()) << "the first epoch is the events' origin";
  EXPECT_EQ(tracked[10.0], 0u);
  EXPECT_EQ(tracked[19.5], 0u);
  EXPECT_EQ(tracked[20.5], 0u) << "re-acquiring";
  EXPECT_EQ(tracked[21.0], ref.sats.size());
}

// The other impairments act on the signals too. Against the same generator without events,
// every 0.5 s: a sky mask (azimuth 90..270 deg below 40 deg) blocks exactly the satellites in it
// and they return a re-acquisition time (1 s) after; an open antenna blocks every signal and is
// reported; a satellite clock fault ramping to 30 m over 10 s adds to that satellite's code
// and carrier ranges only (15 m half-way up the ramp), and nothing once it is over.
TEST(Measurement, SkyMasksAntennaAndSatelliteFaultsActOnTheSignals) {
  const NavData nav = nominal_constellation(kStart);
  MeasurementConfig c = all_off();
  MeasurementGenerator ref(nav, c);
  const SatId faulty = ref.generate(kStart, ecef_from_geodetic(kSite)).sats.front().sat;
  MeasurementGenerator clear(nav, c);
  c.events.outages = {OutageEvent{{10.0, 10.0, 0.0}, 90.0, 270.0, 40.0}};
  c.events.antenna = {AntennaEvent{{30.0, 5.0, 0.0}, AntennaFault::kOpen}};
  c.events.satellites = {SatelliteFaultEvent{{40.0, 40.0, 10.0}, faulty, 30.0}};
  MeasurementGenerator gen(nav, c);
  const auto in_mask = [](const SatMeasurement& m) {
    const double az = m.dir.az_rad * kRadToDeg, el = m.dir.el_rad * kRadToDeg;
    return az >= 90.0 && az <= 270.0 && el < 40.0;
  };
  int masked_seen = 0;
  std::map<SatId, double> carrier_at_40_m;
  for (double t = 0.0; t <= 90.0; t += 0.5) {
    const auto a = clear.generate(kStart.plus_s(t), ecef_from_geodetic(kSite));
    const auto b = gen.generate(kStart.plus_s(t), ecef_from_geodetic(kSite));
    std::set<SatId> expected;
    for (const SatMeasurement& m : a.sats) {
      const bool masked = t >= 10.0 && t < 21.0 && in_mask(m);  // back 1 s after the end
      const bool antenna = t >= 30.0 && t < 36.0;
      masked_seen += masked && t < 20.0;
      if (!masked && !antenna) expected.insert(m.sat);
    }
    std::set<SatId> got;
    for (const SatMeasurement& m : b.sats) got.insert(m.sat);
    EXPECT_EQ(got, expected) << "t " << t << " s";
    EXPECT_EQ(b.antenna_fault.has_value(), t >= 30.0 && t < 35.0) << "t " << t << " s";
    for (const SatMeasurement& m : b.sats) {
      const auto r = std::find_if(a.sats.begin(), a.sats.end(), [&](const SatMeasurement& x) { return x.sat == m.sat; });
      ASSERT_NE(r, a.sats.end());
      const double level = t < 40.0 || t >= 80.0 ? 0.0 : std::min({1.0, (t - 40.0) / 10.0, (80.0 - t) / 10.0});
      const double extra_m = m.sat == faulty ? 30.0 * level : 0.0;
      EXPECT_NEAR(m.signals[0]->pseudorange_m - r->signals[0]->pseudorange_m, extra_m, 1e-6) << "t " << t;
      // The carrier: against its difference when the fault began (the arcs after the antenna
      // fault have their own integer ambiguities).
      const double carrier_diff_m =
          (m.signals[0]->carrier_cycles - r->signals[0]->carrier_cycles) * kSpeedOfLight_mps / kBandFreq_Hz[0];
      if (t == 40.0) carrier_at_40_m[m.sat] = carrier_diff_m;
      if (t >= 40.0) {
        EXPECT_NEAR(carrier_diff_m - carrier_at_40_m.at(m.sat), extra_m, 1e-6) << "t " << t;
      }
    }
    if (t == 45.0) {
      const auto f = std::find_if(b.sats.begin(), b.sats.end(), [&](const SatMeasurement& x) { return x.sat == faulty; });
      ASSERT_NE(f, b.sats.end());
      EXPECT_NEAR(f->engine_pseudorange_m - std::find_if(a.sats.begin(), a.sats.end(), [&](const SatMeasurement& x) {
                                               return x.sat == faulty;
                                             })->engine_pseudorange_m,
                  15.0, 1e-6);
    }
  }
  EXPECT_GT(masked_seen, 0) << "some satellite lies in the mask";
}

// Storms, multipath intensity, orbit faults and health flags. Against the same generator
// without events: the true ionospheric delay is x (1 + 3 level) for a storm of scale 4, the
// multipath error x (1 + 2 level) for an intensity of 3, exactly; a radial orbit error of
// 100 m lengthens the satellite's range by 100 m x cos(nadir angle), the nadir angle from
// sin(eta) = R cos(el) / r (spherical Earth, R 6371 km, r 26560 km); an along-track one moves it
// by at most 100 m x sin(eta); an unhealthy flag marks the satellite in its window only.
TEST(Measurement, StormsMultipathOrbitFaultsAndHealthFlags) {
  const NavData nav = nominal_constellation(kStart);
  MeasurementConfig c = all_off();
  c.errors.ionosphere = c.errors.multipath = true;
  MeasurementGenerator ref(nav, c);
  const auto first = ref.generate(kStart, ecef_from_geodetic(kSite));
  ASSERT_GE(first.sats.size(), 3u);
  const SatId radial = first.sats[0].sat, along = first.sats[1].sat, sick = first.sats[2].sat;
  MeasurementGenerator clear(nav, c);
  c.events.ionosphere = {IonosphereEvent{{10.0, 20.0, 5.0}, 4.0}};
  c.events.multipath = {MultipathEvent{{40.0, 20.0, 5.0}, 3.0}};
  c.events.satellites = {SatelliteFaultEvent{{70.0, 10.0, 0.0}, radial, 0.0, Vec3(100.0, 0.0, 0.0)},
                         SatelliteFaultEvent{{70.0, 10.0, 0.0}, along, 0.0, Vec3(0.0, 100.0, 0.0)},
                         SatelliteFaultEvent{{70.0, 10.0, 0.0}, sick, 0.0, Vec3::Zero(), true}};
  MeasurementGenerator gen(nav, c);
  int checked = 0;
  for (double t = 0.0; t <= 90.0; t += 0.5) {
    const auto a = clear.generate(kStart.plus_s(t), ecef_from_geodetic(kSite));
    const auto b = gen.generate(kStart.plus_s(t), ecef_from_geodetic(kSite));
    ASSERT_EQ(a.sats.size(), b.sats.size()) << t;
    const double storm = 1.0 + 3.0 * event_level(c.events.ionosphere[0].window, t);
    const double rough = 1.0 + 2.0 * event_level(c.events.multipath[0].window, t);
    const bool fault = t >= 70.0 && t < 80.0;
    for (std::size_t i = 0; i < a.sats.size(); ++i) {
      const SatMeasurement &x = a.sats[i], &y = b.sats[i];
      ASSERT_EQ(x.sat, y.sat);
      EXPECT_NEAR(y.iono_l1_m, storm * x.iono_l1_m, 1e-9) << t;
      EXPECT_NEAR(y.multipath_m, rough * x.multipath_m, 1e-9) << t;
      EXPECT_EQ(y.unhealthy, fault && y.sat == sick) << t;
      const double dr_m = y.sat_error_m - x.sat_error_m;
      const double eta = std::asin(6371e3 * std::cos(y.dir.el_rad) / 26560e3);
      if (fault && y.sat == radial) {
        EXPECT_NEAR(dr_m, 100.0 * std::cos(eta), 0.1) << t;
        ++checked;
      } else if (fault && y.sat == along) {
        EXPECT_LE(std::abs(dr_m), 100.0 * std::sin(eta) + 0.1) << t;
        EXPECT_GT(std::abs(dr_m), 0.01) << t;
      } else {
        EXPECT_EQ(dr_m, 0.0) << t;
      }
    }
  }
  EXPECT_EQ(checked, 20);
}

// A time spoofer: the measurements are those of the sky pull x level later (the same
// generator asked at that time, to the millimetre: the error processes follow the true time
// and are off here) and carry the pulled time tag; a fix from them lies where the receiver is
// and its time is the pulled one.
TEST(Measurement, TimeSpoofingSendsTheSkyOfAnotherTime) {
  const NavData nav = nominal_constellation(kStart);
  MeasurementConfig c = all_off();
  c.events.spoofing = {SpoofingEvent{{10.0, 20.0, 5.0}, Vec3::Zero(), 6.0, 2.0}};
  MeasurementGenerator gen(nav, c);
  const Vec3 p = ecef_from_geodetic(kSite);
  for (double t = 0.0; t <= 40.0; t += 0.5) {
    const double level = event_level(c.events.spoofing[0].window, t);
    MeasurementGenerator later(nav, all_off());
    later.set_event_origin(kStart);
    const auto a = later.generate(kStart.plus_s(t + 2.0 * level), p);
    const auto b = gen.generate(kStart.plus_s(t), p);
    EXPECT_NEAR(b.spoofed_time_s, 2.0 * level, 1e-12) << t;
    EXPECT_EQ(b.spoofed, level > 0.0) << t;
    EXPECT_EQ(b.t_receiver, kStart.plus_s(t + 2.0 * level)) << t;
    ASSERT_EQ(a.sats.size(), b.sats.size()) << t;
    for (std::size_t i = 0; i < a.sats.size(); ++i)
      EXPECT_NEAR(b.sats[i].signals[0]->pseudorange_m, a.sats[i].signals[0]->pseudorange_m, 1e-3) << t;
    std::vector<RangeMeasurement> in;
    gen.solver_input(b, in);
    const Solution sol = solve(in, b.t_receiver, SolverOptions{});
    EXPECT_LT((sol.p_ecef_m - p).norm(), 1e-3) << t;
  }
}

// The built-in constellation never runs out: over three days (the data made for the start hold
// 28 h), every epoch has the satellites above the horizon with a data set at most 1 h from its
// toe (the 2 h uploads), their IODEs move on as new sets are uploaded, and with every error
// source off the position comes back to the millimetre.
TEST(Measurement, BuiltInConstellationRenewsForDays) {
  const NavData nav = nominal_constellation(kStart);
  MeasurementGenerator gen(nav, all_off());
  const Vec3 p = ecef_from_geodetic(kSite);
  SolverOptions o;
  o.elevation_mask_deg = 0.0;
  std::set<std::pair<int, int>> prn_iode;
  std::size_t min_sats = 99;
  double max_age_s = 0.0, max_err_m = 0.0;
  for (double dt = 0.0; dt <= 3 * 86400.0; dt += 300.0) {
    const GpsTime t = kStart.plus_s(dt);
    const EpochMeasurements e = gen.generate(t, p);
    min_sats = std::min(min_sats, e.sats.size());
    for (const SatMeasurement& m : e.sats) {
      max_age_s = std::max(max_age_s, std::abs(seconds_between(t, m.eph->toe)));
      prn_iode.insert({m.sat.number(), m.eph->iode});
    }
    const Solution s = solve(gen.solver_input(e), e.t_receiver, o);
    ASSERT_EQ(s.fix, FixType::k3D) << "t + " << dt << " s";
    max_err_m = std::max(max_err_m, (s.p_ecef_m - p).norm());
  }
  EXPECT_GE(min_sats, 4u);
  EXPECT_LE(max_age_s, 3600.0);
  EXPECT_LT(max_err_m, 1e-3);
  // Satellites above a site at some time of each 2 h data set: 3 days of 12 uploads each.
  std::set<int> iodes;
  for (const auto& [prn, iode] : prn_iode) iodes.insert(iode);
  EXPECT_GE(iodes.size(), 36u);
  std::printf("[ renewal ] 3 days: min %zu satellites, max |t - toe| %.0f s, %zu (PRN, IODE) "
              "sets, %zu IODEs, max position error %.1e m\n",
              min_sats, max_age_s, prn_iode.size(), iodes.size(), max_err_m);
}

// Built-in data edited by their user (here: 8 of the 24 slots kept, as tools/paper_table1
// keeps the 7 highest) go on as edited: the renewal continues the sets it was given.
TEST(Measurement, EditedBuiltInDataKeepTheirSatellitesWhenRenewed) {
  NavData nav = nominal_constellation(kStart);
  std::erase_if(nav.gps, [](const GpsEphemeris& e) { return e.sat.number() > 8; });
  MeasurementGenerator gen(nav, all_off());
  const Vec3 p = ecef_from_geodetic(kSite);
  std::set<int> late;
  for (double dt = 0.0; dt <= 2 * 86400.0; dt += 600.0) {
    for (const SatMeasurement& m : gen.generate(kStart.plus_s(dt), p).sats) {
      EXPECT_LE(m.sat.number(), 8);
      if (dt > 30 * 3600.0) late.insert(m.sat.number());
    }
  }
  EXPECT_GE(late.size(), 6u);
}

}  // namespace
}  // namespace navemu

namespace navemu {
namespace {

// Dual-frequency mode uses the iono-free combination, so a satellite whose second band is
// switched off (the signal-enable items: here BeiDou's B2I) cannot be used: it is left out,
// and the other systems still give a fix (before, its missing L2 was read: no fix at all).
TEST(Measurement, DualFrequencyLeavesOutSatellitesWithoutTheirSecondBand) {
  MeasurementConfig c;
  apply_receiver_class(c, ReceiverClass::kGeodetic);
  c.mode = ReceiverMode::kDualFrequency;
  c.systems = system_bit(GnssSystem::kGps) | system_bit(GnssSystem::kBeidou);
  const NavData nav = nominal_constellation(kStart, c.systems);
  MeasurementGenerator gen(nav, c);
  gen.set_active_systems(c.systems, system_bit(GnssSystem::kGps));
  const Vec3 p = ecef_from_geodetic(kSite);
  const EpochMeasurements e = gen.generate(kStart, p);
  ASSERT_GE(e.sats.size(), 6u);
  for (const SatMeasurement& m : e.sats) {
    EXPECT_EQ(m.sat.system(), GnssSystem::kGps);
    EXPECT_TRUE(m.signals[1].has_value());
  }
  SolverOptions o = gen.solver_options();
  const Solution s = solve(gen.solver_input(e), e.t_receiver, o);
  ASSERT_EQ(s.fix, FixType::k3D);
  EXPECT_LT((s.p_ecef_m - p).norm(), 10.0);
}

}  // namespace
}  // namespace navemu
