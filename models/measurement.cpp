#include "models/measurement.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>

#include "core/sat_table.hpp"
#include "models/constellation.hpp"
#include "models/orbit.hpp"

namespace navemu {

namespace {

// (f_L1 / f)^2: ionospheric delay and group delays scale between frequencies
// (IS-GPS-200 20.3.3.3.3.2, 20.3.3.3.3.3).
constexpr double gamma(double carrier_hz) {
  const double r = kGpsL1_Hz / carrier_hz;
  return r * r;
}

// The group delay of a signal that the broadcast clock correction of the record leaves in the
// range, s: GPS and QZSS TGD scaled by gamma (IS-GPS-200 20.3.3.3.3.2); Galileo BGD(E1,E5b)
// or BGD(E1,E5a), the pair of the record's clock, on E1 and each BGD times gamma on E5b and
// E5a (OS SIS ICD 2.0 5.1.5); BeiDou TGD1 on B1I and TGD2 on B2I (BDS-SIS-ICD-B1I 3.0
// 5.2.4.10, both relative to B3I's clock); GLONASS none here (RINEX 3 records carry none).
double group_delay_s(const BroadcastRecord& r, Band band, double carrier_hz) {
  if (const auto* gps = std::get_if<const GpsEphemeris*>(&r))
    return gamma(carrier_hz) * (*gps)->tgd_s;
  if (const auto* gal = std::get_if<const GalileoEphemeris*>(&r)) {
    switch (band) {
      case Band::kL1: return (*gal)->bgd_e1_s();
      case Band::kL2: return gamma(carrier_hz) * (*gal)->bgd_e1e5b_s;
      case Band::kL5: return gamma(carrier_hz) * (*gal)->bgd_e1e5a_s;
    }
  }
  if (const auto* bds = std::get_if<const BeidouEphemeris*>(&r))
    return band == Band::kL1 ? (*bds)->tgd1_s : band == Band::kL2 ? (*bds)->tgd2_s : 0.0;
  return 0.0;
}

// C/N0 of the modernised signals relative to L1 C/A: L2C is broadcast ~1.5 dB weaker (IS-GPS-200
// Table 3-Va minimum powers -158.5 vs -158.5 dBW with the pilot/data split), L5 ~+0.5 dB.
constexpr std::array<double, 3> kCn0OffsetDb = {0.0, -3.0, 0.5};

// The receiver's tropospheric model error, zenith (SolverOptions::tropo_sigma_m): the wet delay's
// variability (MeasurementConfig::tropo_wet_sigma_m, 3 cm) and the wet delay the receiver's
// standard atmosphere (70 % humidity) mistakes, a few cm.
constexpr double kTropoModelSigma_m = 0.06;

// The error the ionosphere's horizontal gradients (MeasurementConfig::iono_gradient_sigma_m_per_deg,
// north and east alike) put on a satellite's delay, 1-sigma: the gradient times the pierce
// point's offset from the receiver, mapped with the obliquity.
// The statistical code multipath's size at an elevation (MeasurementConfig::
// multipath_zenith_sigma_m growing as 1 / sin(el), held from ~3 deg down): the generator's
// process and the receiver's budget for it.
double multipath_sigma_m(double zenith_sigma_m, double sin_el) { return zenith_sigma_m / std::max(sin_el, 0.05); }

double iono_gradient_error_sigma_m(double sigma_m_per_deg, double el_rad) {
  const PierceOffset p = iono_pierce_offset(el_rad);
  return sigma_m_per_deg * p.psi_deg * p.obliquity;
}

}  // namespace

std::optional<BandSignal> band_signal(GnssSystem system, Band band) {
  const std::size_t b = static_cast<std::size_t>(band);
  switch (system) {
    case GnssSystem::kGps: return BandSignal{kBandSignals[b], kBandChipRate_Hz[b]};
    case GnssSystem::kQzss: {
      constexpr std::array<SignalId, 3> kQzss{kQzssL1CA, kQzssL2CL, kQzssL5Q};
      return BandSignal{kQzss[b], kBandChipRate_Hz[b]};
    }
    case GnssSystem::kGalileo: {
      constexpr std::array<BandSignal, 3> kGalileo{{{kGalileoE1C, 1.023e6}, {kGalileoE5bQ, 10.23e6}, {kGalileoE5aQ, 10.23e6}}};
      return kGalileo[b];
    }
    case GnssSystem::kBeidou:
      if (band == Band::kL5) return std::nullopt;
      return BandSignal{band == Band::kL1 ? kBeidouB1I : kBeidouB2I, 2.046e6};
    case GnssSystem::kGlonass:
      if (band == Band::kL5) return std::nullopt;
      return BandSignal{band == Band::kL1 ? kGlonassL1OF : kGlonassL2OF, 0.511e6};
    default: return std::nullopt;
  }
}

void apply_receiver_class(MeasurementConfig& cfg, ReceiverClass rc) {
  switch (rc) {
    case ReceiverClass::kGeodetic:
      // Narrow correlator (0.1 chip) and a carrier-aided code loop of 0.1 Hz; a choke-ring
      // antenna: 50 dB-Hz at the zenith and little multipath.
      cfg.tracking.chip_spacing = 0.1;
      cfg.tracking.dll_bandwidth_hz = 0.1;
      cfg.cn0.zenith_dbhz = 50.0;
      cfg.multipath_zenith_sigma_m = 0.05;
      break;
    case ReceiverClass::kConsumer:
      // Standard 1-chip correlator, 1 Hz code loop; a patch antenna at 45 dB-Hz at the zenith
      // on a less benign site.
      cfg.tracking.chip_spacing = 1.0;
      cfg.tracking.dll_bandwidth_hz = 1.0;
      cfg.cn0.zenith_dbhz = 45.0;
      cfg.multipath_zenith_sigma_m = 0.3;
      break;
  }
}

// The ionosphere's errors (the broadcast model's scale and gradients, each satellite's own part)
// vary smoothly over minutes (medium-scale travelling disturbances have periods of 10-60 min):
// Gauss-Markov processes drawn 30 s apart and interpolated (InterpolatedGaussMarkov). At epochs
// on the knots (30 s RINEX files) the values are the first-order process's own.
constexpr double kIonoKnot_s = 30.0;

// Per-satellite processes, created when the satellite is first seen. One random stream per
// term and satellite, so switching one term (or a band) leaves the others' numbers unchanged.
struct SatProcesses {
  using BandStreams = std::array<RandomStream, 3>;
  static BandStreams band_streams(std::uint64_t seed, const char* term, SatId sat) {
    auto one = [&](int band) {
      return RandomStream(seed, stream_id(term, sat.stream_index() * 10 + band));
    };
    return {one(0), one(1), one(2)};
  }

  SatProcesses(std::uint64_t seed, SatId sat, const MeasurementConfig& cfg, double t_s)
      : iono_rng(seed, stream_id("iono", sat.stream_index())),
        multipath_rng(seed, stream_id("multipath", sat.stream_index())),
        rtk_rng(seed, stream_id("rtk_noise", sat.stream_index())),
        code_rng(band_streams(seed, "code_noise", sat)),
        phase_rng(band_streams(seed, "phase_noise", sat)),
        doppler_rng(band_streams(seed, "doppler_noise", sat)),
        iono_fraction(cfg.iono_satellite_error_fraction, cfg.iono_error_tau_s, kIonoKnot_s, iono_rng),
        multipath(1.0, cfg.multipath_tau_s, multipath_rng),
        last_t_s(t_s) {
    iono_fraction.at(t_s, iono_rng);
  }
  // `multipath_tr`: the transition every satellite's multipath shares.
  void advance(double t_s, GaussMarkovTransition& multipath_tr) {
    const double dt = t_s - last_t_s;
    iono_fraction.at(t_s, iono_rng);
    multipath.step(multipath_tr.at(dt, multipath.tau_s()), multipath_rng);
    last_t_s = t_s;
  }

  RandomStream iono_rng, multipath_rng, rtk_rng;
  BandStreams code_rng, phase_rng, doppler_rng;
  InterpolatedGaussMarkov iono_fraction;
  GaussMarkov multipath;  // unit variance, scaled by the elevation-dependent sigma
  double last_t_s = 0.0;
  CarrierSmoother smoother;  // of the engine's pseudorange
};

// A satellite's C/N0 departure from the elevation model (MeasurementConfig::cn0_*): an
// offset drawn once and a Gauss-Markov fluctuation, from the satellite's own stream, seen
// through the receiver's C/N0 estimator (a first-order average over cn0_estimator_tau_s).
struct Cn0Departure {
  Cn0Departure(std::uint64_t seed, SatId sat, const MeasurementConfig& cfg, double t_s)
      : rng(seed, stream_id("cn0", sat.stream_index())),
        offset_db(cfg.cn0_satellite_sigma_db * rng.normal()),
        fluctuation(cfg.cn0_fluctuation_sigma_db, cfg.cn0_fluctuation_tau_s, rng),
        estimate_db(fluctuation.value()),
        estimator_tau_s(cfg.cn0_estimator_tau_s),
        last_t_s(t_s) {}
  double at(double t_s) {
    if (const double dt = t_s - last_t_s; dt > 0.0) {
      fluctuation.step(dt, rng);
      const double keep = std::exp(-dt / estimator_tau_s);
      estimate_db = keep * estimate_db + (1.0 - keep) * fluctuation.value();
    }
    last_t_s = t_s;
    return offset_db + estimate_db;
  }
  RandomStream rng;
  double offset_db;
  GaussMarkov fluctuation;
  double estimate_db;
  double estimator_tau_s;
  double last_t_s;
};

struct MeasurementGenerator::State {
  explicit State(const MeasurementConfig& cfg)
      : clock(cfg.clock, RandomStream(cfg.seed, stream_id("receiver_clock"))),
        sat_errors(cfg.sat_errors, cfg.seed),
        arcs(cfg.seed),
        iono_common_rng(cfg.seed, stream_id("iono_common")),
        tropo_wet_rng(cfg.seed, stream_id("tropo_wet")),
        dgps_tropo_rng(cfg.seed, stream_id("dgps_tropo")),
        iono_gradient_rng(cfg.seed, stream_id("iono_gradient")),
        iono_common(cfg.iono_common_error_fraction, cfg.iono_error_tau_s, kIonoKnot_s, iono_common_rng),
        iono_gradient_north(cfg.iono_gradient_sigma_m_per_deg, cfg.iono_error_tau_s, kIonoKnot_s, iono_gradient_rng),
        iono_gradient_east(cfg.iono_gradient_sigma_m_per_deg, cfg.iono_error_tau_s, kIonoKnot_s, iono_gradient_rng),
        tropo_wet(cfg.tropo_wet_sigma_m, cfg.tropo_wet_tau_s, tropo_wet_rng),
        dgps_tropo(cfg.dgps_tropo_residual_sigma_m, cfg.tropo_wet_tau_s, dgps_tropo_rng) {}

  ReceiverClock clock;
  SatErrors sat_errors;
  CarrierArcs arcs;
  RandomStream iono_common_rng, tropo_wet_rng, dgps_tropo_rng, iono_gradient_rng;
  InterpolatedGaussMarkov iono_common, iono_gradient_north, iono_gradient_east;
  GaussMarkov tropo_wet;
  GaussMarkov dgps_tropo;
  SatTable<SatProcesses> sats;
  SatTable<Cn0Departure> cn0_departure;  // of the satellites above the horizon so far
  // The Gauss-Markov transitions shared by processes of one correlation time and step.
  GaussMarkovTransition tropo_tr, sat_multipath_tr;
  SatTable<double> receivable_since;  // time the satellite's signal became receivable, s
  SatTable<std::pair<double, double>> scene_phase;  // (t s, carrier multipath m)
  // The last light-time solution (t s, flight time s, its rate): the next one starts from its
  // extrapolation and converges in one or two orbit evaluations.
  struct FlightTime {
    double t_s, tau_s, rate;
  };
  SatTable<FlightTime> flight_time;
  SatTable<double> below_horizon_until_s;  // no orbit evaluation before then
  SatTable<GlonassArc> glonass_arcs;  // each GLONASS satellite's record in use, integrated once
  Vec3 below_horizon_from = Vec3::Zero();  // the receiver's place when those were decided
  std::optional<GpsTime> last;
  std::optional<GpsTime> event_origin;  // the events' times count from here
  std::vector<SatId> sat_ids;  // the satellites with records, in SatId order
  std::vector<SatId> lnav_sat_ids, other_sat_ids;  // those of GPS and QZSS, of the others
  SatTable<std::vector<const GpsEphemeris*>> records;  // each GPS and QZSS satellite's records
  SatTable<std::vector<const GalileoEphemeris*>> galileo_records;
  SatTable<std::vector<const BeidouEphemeris*>> beidou_records;
  SatTable<std::vector<const GlonassEphemeris*>> glonass_records;
  // Each satellite's record choice with the span of times it holds for (the records change only
  // when renewed, which clears it).
  SatTable<EphemerisSelection> selection;
  // Data that renew (NavData::renews, the built-in constellation): from `renew_at` on, each
  // satellite's latest set goes on with a new upload every 2 h (reuploaded(); GLONASS every
  // 30 min) for the next day, Galileo's and BeiDou's as their nominal orbits give them anew. The
  // sets in use are renewed[0]; renewed[1] keeps the ones before them, which the last epoch's
  // measurements may still point to, until the next renewal.
  std::array<std::vector<GpsEphemeris>, 2> renewed;
  std::array<std::vector<GalileoEphemeris>, 2> renewed_galileo;
  std::array<std::vector<BeidouEphemeris>, 2> renewed_beidou;
  std::array<std::vector<GlonassEphemeris>, 2> renewed_glonass;
  GpsTime renew_at{std::numeric_limits<std::int64_t>::max()};
  // The uploads a renewal at t holds per satellite: toe from t - 2 h (the set in use) to t + 26 h.
  static constexpr double kRenewFrom_s = -kUploadInterval_s, kRenewTo_s = 26 * 3600.0;
  static constexpr std::size_t kRenewedPerSat =
      static_cast<std::size_t>((kRenewTo_s - kRenewFrom_s) / kUploadInterval_s) + 1;

  // `records` and `sat_ids` from a set of records (reusing their storage: a renewal of as many
  // records allocates nothing).
  void index(const std::vector<GpsEphemeris>& gps, const std::vector<GpsEphemeris>* qzss = nullptr) {
    for (SatId sat : lnav_sat_ids) records.find(sat)->clear();
    for (const GpsEphemeris& e : gps) records.try_emplace(e.sat).first.push_back(&e);
    if (qzss != nullptr)
      for (const GpsEphemeris& e : *qzss) records.try_emplace(e.sat).first.push_back(&e);
    lnav_sat_ids.clear();
    records.for_each([this](SatId sat, const std::vector<const GpsEphemeris*>& r) {
      if (!r.empty()) lnav_sat_ids.push_back(sat);
    });
    sat_ids = lnav_sat_ids;
    sat_ids.insert(sat_ids.end(), other_sat_ids.begin(), other_sat_ids.end());
    std::sort(sat_ids.begin(), sat_ids.end());
    selection.clear();
  }
  // The other systems' tables from their records (the same satellites at every renewal).
  template <class Eph>
  static void index_other(const std::vector<Eph>& list, SatTable<std::vector<const Eph*>>& table) {
    table.for_each([](SatId, std::vector<const Eph*>& r) { r.clear(); });
    for (const Eph& e : list) table.try_emplace(e.sat).first.push_back(&e);
  }

  template <class Eph>
  static const Eph& latest(const std::vector<const Eph*>& r) {
    return **std::max_element(r.begin(), r.end(),
                              [](const Eph* a, const Eph* b) { return reference_time(*a) < reference_time(*b); });
  }

  // When renewing data would run short: an upload before the earliest of the satellites' latest
  // sets, so the nearest one stays within half an upload interval.
  void schedule_renewal() {
    renew_at = GpsTime{std::numeric_limits<std::int64_t>::max()};
    const auto earliest = [this](const auto& table, double interval_s) {
      table.for_each([&](SatId, const auto& r) {
        if (!r.empty()) renew_at = std::min(renew_at, reference_time(latest(r)).plus_s(-interval_s));
      });
    };
    earliest(records, kUploadInterval_s);
    earliest(galileo_records, kUploadInterval_s);
    earliest(beidou_records, kUploadInterval_s);
    earliest(glonass_records, kGlonassUploadInterval_s);
  }

  // Each satellite's sets in force from t on: those held with reference times from t - one
  // interval on, then its latest set uploaded anew every interval to t + 26 h.
  template <class Eph>
  void continue_uploads(const SatTable<std::vector<const Eph*>>& table, GpsTime t, double interval_s,
                        std::vector<Eph>& next) {
    const GpsTime from = t.plus_s(-interval_s), to = t.plus_s(kRenewTo_s);
    table.for_each([&](SatId, const std::vector<const Eph*>& r) {
      if (r.empty()) return;
      for (const Eph* e : r)
        if (reference_time(*e) >= from) next.push_back(*e);
      const Eph& newest = latest(r);
      const double k0 = std::max(1.0, std::ceil(seconds_between(from, reference_time(newest)) / interval_s));
      for (double k = k0; reference_time(newest).plus_s(k * interval_s) <= to; ++k) {
        // A Keplerian set is parametrised anew from the newest; a GLONASS state integrates on
        // from the one before (the same steps, not all of them again).
        const GpsTime ref = reference_time(newest).plus_s(k * interval_s);
        if constexpr (std::is_same_v<Eph, GlonassEphemeris>)
          next.push_back(reuploaded(k == k0 ? newest : next.back(), ref));
        else
          next.push_back(reuploaded(newest, ref));
      }
    });
  }

  void renew(GpsTime t) {
    std::vector<GpsEphemeris>& next = renewed[1];  // nothing points into it any more
    next.clear();
    continue_uploads(records, t, kUploadInterval_s, next);
    std::swap(renewed[0], renewed[1]);
    index(renewed[0]);
    renew_other(renewed_galileo, galileo_records, [&](auto& v) { nominal_galileo(t, v); });
    renew_other(renewed_beidou, beidou_records, [&](auto& v) { nominal_beidou(t, v); });
    renew_other(renewed_glonass, glonass_records, [&](auto& v) {
      v.clear();
      continue_uploads(glonass_records, t, kGlonassUploadInterval_s, v);
    });
    schedule_renewal();
  }
  template <class Eph, class Fill>
  void renew_other(std::array<std::vector<Eph>, 2>& sets, SatTable<std::vector<const Eph*>>& table, Fill fill) {
    if (!tracks(table)) return;
    fill(sets[1]);
    // Only the satellites the data had (edited built-in data stay edited).
    std::erase_if(sets[1], [&](const Eph& e) {
      const auto* r = table.find(e.sat);
      return r == nullptr || r->empty();
    });
    std::swap(sets[0], sets[1]);
    index_other(sets[0], table);
  }
  template <class Eph>
  static bool tracks(const SatTable<std::vector<const Eph*>>& table) {
    bool any = false;
    table.for_each([&](SatId, const std::vector<const Eph*>& r) { any = any || !r.empty(); });
    return any;
  }
};

MeasurementGenerator::MeasurementGenerator(const NavData& nav, const MeasurementConfig& cfg)
    : nav_(nav), cfg_(cfg), state_(std::make_unique<State>(cfg)) {
  cfg_.bands |= band_bit(Band::kL1);
  if (cfg_.mode == ReceiverMode::kDualFrequency) cfg_.bands = kAllBands;
  if (cfg_.iono_model == IonoModel::kKlobuchar && !nav_.klobuchar)
    cfg_.iono_model = IonoModel::kPaperVtec;
  // The records of the systems tracked, indexed once and at each renewal.
  State& st = *state_;
  const auto tracked = [&](GnssSystem s) { return (cfg_.systems & system_bit(s)) != 0; };
  if (tracked(GnssSystem::kGalileo)) State::index_other(nav_.galileo, st.galileo_records);
  if (tracked(GnssSystem::kBeidou)) State::index_other(nav_.beidou, st.beidou_records);
  if (tracked(GnssSystem::kGlonass)) State::index_other(nav_.glonass, st.glonass_records);
  const auto add_sats = [&](auto& table) {
    table.for_each([&](SatId sat, const auto& r) {
      if (!r.empty()) st.other_sat_ids.push_back(sat);
    });
  };
  add_sats(st.galileo_records);
  add_sats(st.beidou_records);
  add_sats(st.glonass_records);
  static const std::vector<GpsEphemeris> kNone;
  st.index(tracked(GnssSystem::kGps) ? nav_.gps : kNone, tracked(GnssSystem::kQzss) ? &nav_.qzss : nullptr);
  if (nav_.renews) {  // a steady run renews without allocating
    st.schedule_renewal();
    for (auto& r : st.renewed) r.reserve(st.sat_ids.size() * State::kRenewedPerSat);
    for (auto& r : st.renewed_galileo) r.reserve(2 * nav_.galileo.size());
    for (auto& r : st.renewed_beidou) r.reserve(2 * nav_.beidou.size());
    for (auto& r : st.renewed_glonass) r.reserve(2 * nav_.glonass.size());
  }
}

MeasurementGenerator::~MeasurementGenerator() = default;

void MeasurementGenerator::set_event_origin(GpsTime start) {
  state_->event_origin = start;
  cfg_.events.for_each_window([&](EventWindow& w) { resolve_start(w, start); });
}

void MeasurementGenerator::add_events(const GnssEvents& e) {
  cfg_.events.append(e);
  if (state_->event_origin) set_event_origin(*state_->event_origin);
}

EpochMeasurements MeasurementGenerator::generate(GpsTime t_epoch, const Vec3& p_rx,
                                                 const Vec3& v_rx) {
  EpochMeasurements out;
  generate(t_epoch, p_rx, v_rx, out);
  return out;
}

void MeasurementGenerator::generate(GpsTime t_epoch, const Vec3& p_rx, const Vec3& v_rx,
                                    EpochMeasurements& out) {
  State& st = *state_;
  const ErrorSwitches& on = cfg_.errors;
  const double dt = st.last ? seconds_between(t_epoch, *st.last) : 0.0;
  const bool first = !st.last;
  st.last = t_epoch;

  st.iono_common.at(t_epoch.seconds(), st.iono_common_rng);
  st.iono_gradient_north.at(t_epoch.seconds(), st.iono_gradient_rng);
  st.iono_gradient_east.at(t_epoch.seconds(), st.iono_gradient_rng);
  if (!first) {
    st.clock.step(dt);
    st.tropo_wet.step(st.tropo_tr.at(dt, st.tropo_wet.tau_s()), st.tropo_wet_rng);
    st.dgps_tropo.step(st.tropo_tr.at(dt, st.dgps_tropo.tau_s()), st.dgps_tropo_rng);
  }

  out.sats.clear();
  out.rx_clock_bias_s = on.receiver_clock ? st.clock.bias_s() : 0.0;
  out.rx_clock_drift_sps = on.receiver_clock ? st.clock.drift_sps() : 0.0;
  // The receiver's clock runs ahead of GPS time by its bias. Its measurements are synchronised
  // with its 1 kHz clock, and each epoch is the tick nearest the desired time in GNSS time
  // (u-blox ZED-F9P integration manual UBX-18010802 3.10.1 "Receiver local time", 3.10.2
  // "Navigation epochs"; the M8 receiver description alike): the time tag is the nominal epoch
  // plus the bias in whole milliseconds, the true time within 0.5 ms of the nominal epoch.
  out.t_receiver = t_epoch.plus_s(std::round(out.rx_clock_bias_s * 1e3) * 1e-3);
  out.t_true = out.t_receiver.plus_s(-out.rx_clock_bias_s);
  const double t_s = out.t_true.seconds();
  // The receiver counts its tracking times (re-acquisition, lock time) in epochs: on the nominal
  // epoch, not on the true time, which drifts with the clock by up to 0.5 ms.
  const double t_epoch_s = t_epoch.seconds();
  // The events on at this epoch (by its time tag: they follow the scenario's epochs).
  if (!st.event_origin) set_event_origin(t_epoch);
  out.interference = {};
  out.antenna_fault.reset();
  out.spoofed = out.spoofing_indicated = false;
  out.spoofed_time_s = 0.0;
  const double t_event_s = seconds_between(t_epoch, *st.event_origin);
  const Geodetic geo = geodetic_from_ecef(p_rx);
  const Mat3 R_enu = R_enu_from_ecef(geo);
  const GnssEvents& ev = cfg_.events;
  for (const JammingEvent& j : ev.jamming)
    if (const auto js = ramped_j_over_s_db(j.j_over_s_db, event_level(j.window, t_event_s)))
      out.interference[static_cast<std::size_t>(j.band)].add(*js, j.kind);
  for (const AntennaEvent& a : ev.antenna)
    if (event_level(a.window, t_event_s) > 0.0) out.antenna_fault = a.fault;
  const auto masked = [&](const AzEl& dir) {
    for (const OutageEvent& o : ev.outages) {
      if (event_level(o.window, t_event_s) <= 0.0 || dir.el_rad * kRadToDeg >= o.below_el_deg) continue;
      const double span = std::fmod(o.az_to_deg - o.az_from_deg + 720.0, 360.0);
      const double off = std::fmod(dir.az_rad * kRadToDeg - o.az_from_deg + 720.0, 360.0);
      if (span == 0.0 || off <= span) return true;  // from == to (0, 360): every azimuth
    }
    return false;
  };

  // A spoofer: the signals of a false position (and the velocity of its pull), stronger.
  Vec3 spoof_offset_m = Vec3::Zero(), spoof_velocity_mps = Vec3::Zero();
  double spoof_gain_db = 0.0;
  for (const SpoofingEvent& s : ev.spoofing) {
    const double level = event_level(s.window, t_event_s);
    if (level <= 0.0) continue;
    spoof_offset_m += R_enu.transpose() * s.offset_enu_m * level;
    spoof_velocity_mps += R_enu.transpose() * s.offset_enu_m * event_level_rate(s.window, t_event_s);
    out.spoofed_time_s += s.time_offset_s * level;
    spoof_gain_db = std::max(spoof_gain_db, s.power_advantage_db);
    out.spoofed = true;
    out.spoofing_indicated = out.spoofing_indicated || s.power_advantage_db >= kSpoofDetectPower_db;
  }
  // Storms and multipath intensity: scale factors of the epoch.
  double iono_scale = 1.0, multipath_scale = 1.0;
  for (const IonosphereEvent& i : ev.ionosphere) iono_scale += (i.scale - 1.0) * event_level(i.window, t_event_s);
  for (const MultipathEvent& m : ev.multipath) multipath_scale += (m.scale - 1.0) * event_level(m.window, t_event_s);
  const ReceiverPlace rx{p_rx + spoof_offset_m, v_rx + spoof_velocity_mps, R_enu};
  // A time spoofer sends the sky of spoofed_time_s later (satellites where they will be, their
  // signals stamped so), which the receiver, locked to it, takes for now: its time tag moves
  // with it and its fix stays where it is.
  const GpsTime t_signal = out.t_true.plus_s(out.spoofed_time_s);
  out.t_receiver = out.t_receiver.plus_s(out.spoofed_time_s);
  const Meteo meteo = cfg_.meteo ? *cfg_.meteo : standard_atmosphere(std::max(geo.h_m, 0.0), 0.5);
  const TropoDelay tropo_zenith = tropo_zenith_delay(geo, meteo);
  // What the atmosphere models need of the receiver and the epoch, for every satellite.
  const NiellCoefficients niell = niell_coefficients(geo, out.t_true);
  const double tow_s = to_week_tow(out.t_true).tow_s;
  const double c = kSpeedOfLight_mps;

  // A satellite 5 deg or more below the horizon cannot rise within a minute (seen from the
  // ground GPS elevations change by less than 1 deg/min), so its orbit is not evaluated for
  // that long: nothing about it is reported or drawn meanwhile.
  constexpr double kFarBelow_rad = -5.0 * kDegToRad;
  constexpr double kFarBelowSkip_s = 60.0;
  if ((p_rx - st.below_horizon_from).norm() > 10e3) {  // another horizon (a jump, a fast ride)
    st.below_horizon_until_s.clear();
    st.below_horizon_from = p_rx;
  }
  if (out.t_true >= st.renew_at) st.renew(out.t_true);  // renewing data (the built-in sky)
  // Galileo and QZSS satellites keep their systems' time: GST = GPST + GGTO (Galileo OS SIS ICD
  // 2.0 5.1.8; the navigation data's GAGP), QZSST = GPST + QZGP. Against the receiver's GPS time
  // their pseudoranges come short by c times that offset, which the receiver's inter-system
  // bias takes up (models/solver.hpp). Zero where the data give none (the built-in sky).
  const double gst_minus_gpst_s = nav_.time_offset_s("GAGP", out.t_true),
               qzsst_minus_gpst_s = nav_.time_offset_s("QZGP", out.t_true);
  for (SatId sat : st.sat_ids) {
    if (!(active_systems_ & system_bit(sat.system()))) {  // switched off: not tracked
      st.receivable_since.erase(sat);
      st.arcs.update(sat, t_epoch_s, false);
      continue;
    }
    if (const double* until = st.below_horizon_until_s.find(sat); until && t_s < *until) continue;
    // The record in use: GPS and QZSS by their selection spans, the others by their rules.
    BroadcastRecord record;
    const GpsEphemeris* eph = nullptr;
    switch (sat.system()) {
      case GnssSystem::kGps:
      case GnssSystem::kQzss: {
        EphemerisSelection& chosen = st.selection.try_emplace(sat).first;
        if (!chosen.covers(t_signal))
          chosen = select_ephemeris_span(*st.records.find(sat), t_signal);
        eph = chosen.eph;
        if (eph != nullptr && std::abs(seconds_between(t_signal, eph->toe)) <= kMaxEphemerisAge_s)
          record = eph;
        break;
      }
      case GnssSystem::kGalileo:
        if (const auto* e = select_galileo_ephemeris(*st.galileo_records.find(sat), t_signal)) record = e;
        break;
      case GnssSystem::kBeidou:
        if (const auto* e = select_beidou_ephemeris(*st.beidou_records.find(sat), t_signal)) record = e;
        break;
      case GnssSystem::kGlonass:
        if (const auto* e = select_glonass_ephemeris(*st.glonass_records.find(sat), t_signal)) record = e;
        break;
      default: break;
    }
    if (std::holds_alternative<std::monostate>(record)) continue;
    const auto* glonass = std::get_if<const GlonassEphemeris*>(&record);
    const int glonass_channel = glonass ? (*glonass)->frequency_channel : 0;
    State::FlightTime& flight = st.flight_time.try_emplace(sat, State::FlightTime{t_s, 0.075, 0.0}).first;
    const GlonassArc* glonass_arc = nullptr;
    if (glonass != nullptr) {
      GlonassArc& a = st.glonass_arcs.try_emplace(sat).first;
      if (!a.of(**glonass)) a = GlonassArc(**glonass);
      glonass_arc = &a;
    }
    const SatGeometry g =
        sat_geometry(record, t_signal, rx, flight.tau_s + flight.rate * (t_s - flight.t_s), glonass_arc);
    flight = {t_s, g.flight_time_s, g.range_rate_mps / c};
    if (g.dir.el_rad < kFarBelow_rad) st.below_horizon_until_s.try_emplace(sat).first = t_s + kFarBelowSkip_s;
    // The scene: blocked, reflected, attenuated signals (open sky without one).
    SignalEnvironment env;
    if (cfg_.environment && g.dir.el_rad > 0.0)
      env = cfg_.environment->evaluate(p_rx, (g.sat.p_ecef_m - p_rx).normalized());
    // Without interference, and as tracked (the effective C/N0 under the jammers on L1).
    double cn0_clear_l1 = cn0_dbhz(cfg_.cn0, g.dir.el_rad) + env.power_db + spoof_gain_db;
    if (on.noise && g.dir.el_rad > 0.0)
      cn0_clear_l1 += st.cn0_departure.try_emplace(sat, cfg_.seed, sat, cfg_, t_s).first.at(t_s);
    const BandSignal l1 = *band_signal(sat.system(), Band::kL1);
    const double cn0_l1 = effective_cn0_dbhz(cn0_clear_l1, out.interference[0], l1.chip_rate_hz);
    // Tracked while above the threshold; a signal that returns (rises, or comes back above the
    // threshold) is re-acquired only after the receiver's re-acquisition time.
    const bool receivable = g.dir.el_rad > 0.0 && env.received && !out.antenna_fault && !masked(g.dir) &&
                            cn0_l1 >= cfg_.tracking.tracking_threshold_dbhz;
    bool tracked = false;
    if (!receivable) {
      st.receivable_since.erase(sat);
    } else {
      auto [since, fresh] = st.receivable_since.try_emplace(sat, t_epoch_s);
      if (fresh && first) since = t_epoch_s - cfg_.tracking.reacquisition_s;  // in track at the start
      tracked = t_epoch_s - since >= cfg_.tracking.reacquisition_s - 1e-9;
    }
    const CarrierArcs::Arc arc = st.arcs.update(sat, t_epoch_s, tracked);
    if (!tracked) continue;

    auto [sp, inserted] = st.sats.try_emplace(sat, cfg_.seed, sat, cfg_, t_s);
    if (!inserted) sp.advance(t_s, st.sat_multipath_tr);

    SatMeasurement m;
    m.sat = sat;
    m.record = record;
    m.eph = eph;
    m.glonass_channel = glonass_channel;
    m.dir = g.dir;
    m.transmit = {g.t_transmit, g.sat_transmit};
    m.range_m = g.range_m;
    m.range_rate_mps = g.range_rate_mps;
    const double sin_el = g.direction.sin_el;

    // Ionosphere on L1: the broadcast (or the paper's) model, with the model's error.
    if (on.ionosphere) {
      double model_m = 0.0;
      if (cfg_.iono_model == IonoModel::kKlobuchar)
        model_m = c * klobuchar_delay_l1_s(*nav_.klobuchar, geo, g.direction, tow_s);
      else
        model_m = iono_paper_mapping(g.dir.el_rad) * iono_zenith_delay_m(cfg_.vtec_tecu, kGpsL1_Hz);
      const PiercePoint ipp = iono_pierce_point(geo, g.direction);
      const double gradient_m =
          ipp.obliquity * (st.iono_gradient_north.value() * ipp.dlat_deg +
                           st.iono_gradient_east.value() * ipp.dlon_deg * std::cos(geo.lat_deg * kDegToRad));
      m.iono_l1_m = iono_scale * std::max(0.0, model_m * (1.0 + st.iono_common.value() + sp.iono_fraction.value()) +
                                                   gradient_m);
    }
    // Troposphere: Saastamoinen zenith delays from the meteorology, Niell mapping, plus the
    // wet delay's unmodelled variability.
    // (tropo_slant_delay's product, with the zenith delays of the epoch computed once.)
    if (on.troposphere) {
      const NiellMapping nm = niell_mapping(niell, g.dir.el_rad);
      m.tropo_hydro_m = tropo_zenith.hydrostatic_m * nm.hydrostatic;
      m.tropo_wet_m = std::max(0.0, tropo_zenith.wet_m * nm.wet + nm.wet * st.tropo_wet.value());
    }
    // Broadcast orbit and clock errors on the line of sight.
    if (on.satellite) {
      if (cfg_.sat_error_model == SatErrorModel::kPaper) {
        const Vec3& ps = g.sat.p_ecef_m;
        m.sat_error_m = paper_sv_ephemeris_error_m(std::asin(ps.z() / ps.norm()), ps.norm());
      } else {
        const Vec3 los = (g.sat.p_ecef_m - p_rx).normalized();
        m.sat_error_m = st.sat_errors.range_error_m(sat, t_s, g.sat.p_ecef_m, g.sat.v_ecef_mps, los);
      }
    }
    // A satellite fault: clock and orbit errors on the range, not in the broadcast record; the
    // health flag in it. The orbit error in the satellite's radial / along-track / cross-track
    // frame: radial along p, cross-track along p x v with v the inertial velocity
    // (v_ecef + omega_e x p).
    for (const SatelliteFaultEvent& f : ev.satellites) {
      const double level = f.sat == sat ? event_level(f.window, t_event_s) : 0.0;
      if (level <= 0.0) continue;
      m.unhealthy = m.unhealthy || f.unhealthy;
      m.sat_error_m += f.clock_error_m * level;
      if (!f.orbit_error_rac_m.isZero()) {
        const Vec3 radial = g.sat.p_ecef_m.normalized();
        const Vec3 v_inertial_mps = g.sat.v_ecef_mps + Vec3(0.0, 0.0, kOmegaEarth_radps).cross(g.sat.p_ecef_m);
        const Vec3 cross = g.sat.p_ecef_m.cross(v_inertial_mps).normalized();
        const Vec3 error_ecef_m = f.orbit_error_rac_m.x() * radial + f.orbit_error_rac_m.y() * cross.cross(radial) +
                                  f.orbit_error_rac_m.z() * cross;
        m.sat_error_m += level * error_ecef_m.dot((g.sat.p_ecef_m - p_rx).normalized());
      }
    }
    // Multipath: the scene's composite-signal errors, or the statistical model in open sky.
    // The carrier error's rate of change is the Doppler error.
    double phase_mp_m = 0.0, doppler_mp_mps = 0.0;
    if (cfg_.environment) {
      m.multipath_m = multipath_scale * env.code_error_m;
      m.nlos = env.nlos;
      phase_mp_m = multipath_scale * env.phase_error_m;
      auto [prev, fresh_phase] = st.scene_phase.try_emplace(sat, t_s, phase_mp_m);
      // A jump of half a wavelength or more (the dominant path changed) is a cycle slip, not
      // a Doppler: no rate across it.
      const double step_m = phase_mp_m - prev.second;
      if (!fresh_phase && t_s > prev.first && !arc.new_arc &&
          std::abs(step_m) < 0.5 * kSpeedOfLight_mps / carrier_frequency_hz(l1.id, glonass_channel))
        doppler_mp_mps = step_m / (t_s - prev.first);
      prev = {t_s, phase_mp_m};
    } else if (on.multipath) {
      m.multipath_m = multipath_scale * multipath_sigma_m(cfg_.multipath_zenith_sigma_m, sin_el) * sp.multipath.value();
    }

    // Satellite clock as the broadcast record gives it (relativistic term included): what a
    // user corrects with; the single-frequency correction subtracts the L1 group delay (TGD,
    // IS-GPS-200 20.3.3.3.3.2; group_delay_s).
    const double l1_delay_s = group_delay_s(record, Band::kL1, carrier_frequency_hz(l1.id, glonass_channel));
    m.sat_clock_m = c * (g.sat.clock_bias_s - l1_delay_s);
    const double rx_clock_m = c * out.rx_clock_bias_s;
    const double system_time_s = sat.system() == GnssSystem::kGalileo ? gst_minus_gpst_s
                                 : sat.system() == GnssSystem::kQzss  ? qzsst_minus_gpst_s
                                                                      : 0.0;
    const double common_m = m.range_m + rx_clock_m - c * (g.sat.clock_bias_s + system_time_s) +
                             m.tropo_hydro_m + m.tropo_wet_m + m.sat_error_m;
    const double rate_mps = m.range_rate_mps + c * (out.rx_clock_drift_sps - g.sat.clock_drift_sps);

    double l1_code_noise_m = 0.0;
    for (int b = 0; b < 3; ++b) {
      const Band band = static_cast<Band>(b);
      if (!(cfg_.bands & band_bit(band))) continue;
      if (band == Band::kL2 && !(active_l2_systems_ & system_bit(sat.system()))) continue;
      const std::optional<BandSignal> signal = band_signal(sat.system(), band);
      // The paper's dual-frequency receiver is a geodetic one, which tracks L2 on every GPS
      // satellite (P(Y) semi-codeless where there is no L2C, as the ESBC station's C2W); it is
      // generated as the band's signal. Receivers of L2C and L5 see only the satellites that
      // send them.
      if (!signal || (cfg_.mode != ReceiverMode::kDualFrequency && !broadcasts(sat, signal->id, out.t_true)))
        continue;
      SignalObs so;
      so.signal = signal->id;
      so.carrier_hz = carrier_frequency_hz(signal->id, glonass_channel);
      const double gm = gamma(so.carrier_hz);
      const double lambda = kSpeedOfLight_mps / so.carrier_hz;
      const double delay_m = c * group_delay_s(record, band, so.carrier_hz);
      so.cn0_dbhz = effective_cn0_dbhz(cn0_clear_l1 + kCn0OffsetDb[static_cast<std::size_t>(b)],
                                       out.interference[static_cast<std::size_t>(b)],
                                       signal->chip_rate_hz);
      so.sigma = tracking_noise(so.cn0_dbhz, cfg_.tracking);
      const TrackingNoise noise = on.noise ? so.sigma : TrackingNoise{};
      const double code_sigma = noise.code_m;
      const double phase_sigma = noise.phase_cycles;
      const double doppler_sigma = noise.doppler_hz;
      // Code: the group delay; multipath shared by the bands at this level of modelling.
      const std::size_t bi = static_cast<std::size_t>(b);
      const double code_noise_m = code_sigma * sp.code_rng[bi].normal();
      if (b == 0) l1_code_noise_m = code_noise_m;
      so.pseudorange_m = common_m + delay_m + gm * m.iono_l1_m + m.multipath_m + code_noise_m;
      // Carrier: advanced by the ionosphere, an integer ambiguity per arc.
      so.carrier_cycles = (common_m + delay_m - gm * m.iono_l1_m + phase_mp_m) / lambda +
                          arc.ambiguity_cycles + phase_sigma * sp.phase_rng[bi].normal();
      so.doppler_hz = -(rate_mps + doppler_mp_mps) / lambda + doppler_sigma * sp.doppler_rng[bi].normal();
      so.loss_of_lock = arc.new_arc;
      so.lock_time_s = arc.lock_time_s;
      m.signals[static_cast<std::size_t>(b)] = so;
    }

    // What the position engine uses in each mode of the paper.
    const double geometric_m = m.range_m + rx_clock_m - m.sat_clock_m;  // clocks as broadcast
    switch (cfg_.mode) {
      case ReceiverMode::kStandalone:
        m.engine_pseudorange_m = m.signals[0]->pseudorange_m;
        break;
      case ReceiverMode::kDualFrequency: {
        // Iono-free combination of L1 and L2 (IS-GPS-200 20.3.3.3.3.3): the ionosphere cancels
        // and the noise grows ~3x; the combination's own group delay (zero for GPS, whose TGD
        // is defined so) is replaced by the L1 one the solver's clock correction removes. A
        // satellite whose second band is switched off (the signal-enable items) has no
        // combination and is left out.
        if (!m.signals[1]) continue;
        const SignalObs& s1 = *m.signals[0];
        const SignalObs& s2 = *m.signals[1];
        const double g12 = gamma(s2.carrier_hz) / gamma(s1.carrier_hz);  // (f1 / f2)^2
        const double d1 = group_delay_s(record, Band::kL1, s1.carrier_hz);
        const double d2 = group_delay_s(record, Band::kL2, s2.carrier_hz);
        m.engine_pseudorange_m = (g12 * s1.pseudorange_m - s2.pseudorange_m) / (g12 - 1.0) -
                                 c * (g12 * d1 - d2) / (g12 - 1.0) + c * d1;
        break;
      }
      case ReceiverMode::kDgps: {
        // Corrections from a nearby base remove what base and rover share (ionosphere,
        // troposphere, broadcast orbit and clock); the troposphere difference, the rover's
        // multipath and the noise of both receivers remain.
        const NiellMapping nm = niell_mapping(niell, g.dir.el_rad);
        const double dtropo = on.troposphere ? nm.wet * st.dgps_tropo.value() : 0.0;
        m.engine_pseudorange_m =
            geometric_m + dtropo + m.multipath_m + std::sqrt(2.0) * l1_code_noise_m;
        break;
      }
      case ReceiverMode::kRtkFixed:
        // Carrier phase with fixed ambiguities: centimetre-level noise only.
        m.engine_pseudorange_m =
            geometric_m + (on.noise ? cfg_.rtk_noise_sigma_m * sp.rtk_rng.normal() : 0.0);
        break;
    }
    // Carrier smoothing with the carrier that shares every term of the engine's code but its
    // noise and multipath (and, on L1 alone, the ionosphere's sign): L1's in standalone, the
    // iono-free combination's in dual-frequency. DGPS and RTK ranges are left as they are.
    m.smoothed_pseudorange_m = m.engine_pseudorange_m;
    if (cfg_.carrier_smoothing_s > 0.0 &&
        (cfg_.mode == ReceiverMode::kStandalone || cfg_.mode == ReceiverMode::kDualFrequency)) {
      const SignalObs& s1 = *m.signals[0];
      double carrier_m = s1.carrier_cycles * kSpeedOfLight_mps / s1.carrier_hz;
      if (cfg_.mode == ReceiverMode::kDualFrequency) {
        const SignalObs& s2 = *m.signals[1];
        const double g12 = gamma(s2.carrier_hz) / gamma(s1.carrier_hz);
        carrier_m = (g12 * carrier_m - s2.carrier_cycles * kSpeedOfLight_mps / s2.carrier_hz) / (g12 - 1.0);
      }
      m.smoothed_pseudorange_m = sp.smoother.update(t_s, m.engine_pseudorange_m, carrier_m, arc.new_arc,
                                                    cfg_.carrier_smoothing_s, cfg_.multipath_tau_s);
      m.smoothed_noise_fraction = sp.smoother.noise_fraction();
      m.smoothed_multipath_fraction = sp.smoother.multipath_fraction();
    }
    out.sats.push_back(std::move(m));
  }
}

SolverOptions MeasurementGenerator::solver_options() const {
  SolverOptions o;
  o.elevation_mask_deg = cfg_.elevation_mask_deg;
  switch (cfg_.mode) {
    case ReceiverMode::kStandalone:
      o.klobuchar = nav_.klobuchar;
      o.saastamoinen = true;
      // The receiver knows its own error budget (solver_input): the broadcast ionosphere's
      // error is the model error fraction here, the troposphere's the wet delay's variability.
      o.iono_error_fraction = std::hypot(cfg_.iono_common_error_fraction, cfg_.iono_satellite_error_fraction);
      o.tropo_sigma_m = kTropoModelSigma_m;
      // The ionosphere's common scale error and gradients are the same for every satellite:
      // the covariance carries the correlations they make.
      if (cfg_.errors.ionosphere) {
        o.iono_shared_scale_sigma = cfg_.iono_common_error_fraction;
        o.iono_shared_gradient_sigma_m_per_deg = cfg_.iono_gradient_sigma_m_per_deg;
      }
      break;
    case ReceiverMode::kDualFrequency:
      o.saastamoinen = true;
      o.tropo_sigma_m = kTropoModelSigma_m;
      break;
    case ReceiverMode::kDgps:
    case ReceiverMode::kRtkFixed:
      break;
  }
  return o;
}

std::vector<RangeMeasurement> MeasurementGenerator::solver_input(const EpochMeasurements& e) const {
  std::vector<RangeMeasurement> out;
  solver_input(e, out);
  return out;
}

void MeasurementGenerator::solver_input(const EpochMeasurements& e,
                                        std::vector<RangeMeasurement>& out) const {
  out.clear();
  // The variances are the receiver's own error budget, as a real receiver's accuracy
  // estimates are calibrated to its errors: per mode, what remains of the terms generate()
  // puts into the engine's pseudorange, each at its configured size.
  const ErrorSwitches& on = cfg_.errors;
  const double sisre_gps_m = on.satellite ? cfg_.sat_errors.sisre_m() : 0.0;
  for (const SatMeasurement& m : e.sats) {
    RangeMeasurement& r = out.emplace_back(make_range_measurement(
        m.record, e.t_receiver, m.smoothed_pseudorange_m, m.signals[0]->doppler_hz,
        state_->glonass_arcs.find(m.sat), &m.transmit));
    const double sin_el = std::max(std::sin(m.dir.el_rad), 0.05);
    // The signal-in-space range error of the system (not the broadcast URA, a bound); the
    // code's tracking noise at its C/N0; multipath as the statistical model sizes it here.
    const double sisre_m = sisre_gps_m * sisre_relative_to_gps(m.sat.system());
    // (Both as much as the carrier smoothing leaves of them.)
    const double noise1_m = on.noise ? m.signals[0]->sigma.code_m * std::sqrt(m.smoothed_noise_fraction) : 0.0;
    const double multipath_m = on.multipath ? multipath_sigma_m(cfg_.multipath_zenith_sigma_m, sin_el) *
                                                  std::sqrt(m.smoothed_multipath_fraction)
                                            : 0.0;
    double variance_m2 = 0.0;
    switch (cfg_.mode) {
      case ReceiverMode::kStandalone: {
        // And the ionosphere's gradients (its model error proper is
        // SolverOptions::iono_error_fraction).
        const double gradient_m =
            on.ionosphere ? iono_gradient_error_sigma_m(cfg_.iono_gradient_sigma_m_per_deg, m.dir.el_rad) : 0.0;
        r.sat_variance_m2 = sisre_m * sisre_m;
        variance_m2 = noise1_m * noise1_m + multipath_m * multipath_m + gradient_m * gradient_m;
        break;
      }
      case ReceiverMode::kDualFrequency: {
        // The iono-free combination weighs the bands' noise by g12 / (g12 - 1) and
        // 1 / (g12 - 1); the multipath both bands share passes unchanged.
        const SignalObs& s2 = *m.signals[1];
        const double g12 = gamma(s2.carrier_hz) / gamma(m.signals[0]->carrier_hz);
        const double noise2_m = on.noise ? s2.sigma.code_m * std::sqrt(m.smoothed_noise_fraction) : 0.0;
        r.sat_variance_m2 = sisre_m * sisre_m;
        variance_m2 = (g12 * g12 * noise1_m * noise1_m + noise2_m * noise2_m) / ((g12 - 1.0) * (g12 - 1.0)) +
                      multipath_m * multipath_m;
        break;
      }
      case ReceiverMode::kDgps: {
        // Both receivers' noise, the rover's multipath and the troposphere difference.
        const double dtropo_m = on.troposphere ? cfg_.dgps_tropo_residual_sigma_m / sin_el : 0.0;
        r.sat_variance_m2 = 0.0;
        variance_m2 = 2.0 * noise1_m * noise1_m + multipath_m * multipath_m + dtropo_m * dtropo_m;
        break;
      }
      case ReceiverMode::kRtkFixed:
        r.sat_variance_m2 = 0.0;
        variance_m2 = on.noise ? cfg_.rtk_noise_sigma_m * cfg_.rtk_noise_sigma_m : 0.0;
        break;
    }
    // (At least a millimetre: a receiver whose errors are all switched off still weighs.)
    r.code_variance_m2 = std::max(variance_m2, 1e-6);
    // The range rate's: the Doppler's tracking noise (at least a millimetre per second).
    const SignalObs& l1 = *m.signals[0];
    const double doppler_mps = on.noise ? l1.sigma.doppler_hz * kSpeedOfLight_mps / l1.carrier_hz : 0.0;
    r.range_rate_variance_m2ps2 = std::max(doppler_mps * doppler_mps, 1e-6);
  }
}

}  // namespace navemu
