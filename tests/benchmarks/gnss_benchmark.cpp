// One GNSS receiver epoch on one core, split into its parts: the receiver update alone
// (measurement generator and position engine, models/receiver.hpp) with exactly 12 and 40
// satellites in view and used, and in the urban scene; then the encoding of one epoch as NMEA
// (ublox-nmea-5hz) and as UBX (the configured F9P), each on precomputed fixes.
//   navemu_benchmarks --benchmark_filter='GnssReceiver|GnssEncode'

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "emulator/gnss_device.hpp"
#include "emulator/gnss_scene.hpp"
#include "emulator/nmea_output.hpp"
#include "protocols/ubx_config_db.hpp"
#include "protocols/ubx_messages.hpp"
#include "models/constellation.hpp"
#include "models/geodesy.hpp"
#include "models/orbit.hpp"
#include "models/receiver.hpp"
#include "tests/benchmarks/benchmark_setups.hpp"

namespace navemu {
namespace {

constexpr std::int64_t kEpochNs = 200'000'000;  // 5 Hz
// The receiver starts over (timing paused) after this many epochs (5 min), so the sky stays
// the one the satellites were chosen for.
constexpr std::int64_t kEpochsPerRun = 1500;

// A dense GPS-format constellation: the 24 nominal slots (models/constellation.hpp) repeated
// with their nodes turned by 0, 15, 30 and 45 deg and their satellites advanced by 0 and 180
// deg along the orbit, 192 satellites in 24 planes (Walker-like), each with the nominal records
// every 2 h. PRNs 1..192 here; highest() numbers the chosen ones 1..n.
NavData dense_constellation(GpsTime t) {
  const NavData nominal = nominal_constellation(t);
  NavData nav = nominal;
  nav.gps.clear();
  constexpr double kTwoPi = 2.0 * std::numbers::pi;
  for (int copy = 0; copy < 8; ++copy) {
    for (GpsEphemeris e : nominal.gps) {
      e.sat = gps_sat(e.sat.number() + 24 * copy);
      e.omega0_rad = std::remainder(e.omega0_rad + (copy / 2) * 15.0 * kDegToRad, kTwoPi);
      e.m0_rad = std::remainder(e.m0_rad + (copy % 2) * 180.0 * kDegToRad, kTwoPi);
      nav.gps.push_back(e);
    }
  }
  return nav;
}

// The records of the `n` highest satellites of `all` seen from `site` at t, as PRNs 1..n
// (receivers keep per-satellite state for the numbers GPS defines, 1..63), or none when fewer
// than n are 15 deg up (so that all stay above the 5 deg mask for a run).
NavData highest(const NavData& all, std::size_t n, GpsTime t, const Geodetic& site) {
  const Vec3 p_rx = ecef_from_geodetic(site);
  std::set<SatId> sats;
  for (const GpsEphemeris& e : all.gps) sats.insert(e.sat);
  std::vector<std::pair<double, SatId>> by_el;  // (elevation, satellite)
  for (SatId sat : sats)
    if (const GpsEphemeris* e = select_ephemeris(all, sat, t))
      by_el.emplace_back(azimuth_elevation(p_rx, gps_sat_state(*e, t).p_ecef_m).el_rad, sat);
  std::sort(by_el.rbegin(), by_el.rend());
  NavData nav = all;
  nav.gps.clear();
  if (by_el.size() < n || by_el[n - 1].first < 15.0 * kDegToRad) return nav;
  for (const GpsEphemeris& e : all.gps) {
    for (std::size_t i = 0; i < n; ++i) {
      if (by_el[i].second != e.sat) continue;
      nav.gps.push_back(e);
      nav.gps.back().sat = gps_sat(static_cast<int>(i) + 1);
    }
  }
  return nav;
}

const Geodetic kSite{32.3, -90.9, 60.0};

ReceiverParams consumer_receiver() {
  ReceiverParams p;
  apply_receiver_class(p.measurement, ReceiverClass::kConsumer);
  p.max_channels = 64;  // every satellite in view is tracked
  return p;
}

// Receiver updates at 5 Hz from the scenario start, the truth of epoch e (since the run's
// start) from `truth_at(e)`; reports the satellites tracked and used per epoch.
template <class TruthAt>
void receiver_epochs(benchmark::State& state, const NavData& nav, const ReceiverParams& p,
                     TruthAt truth_at) {
  if (nav.gps.empty()) {
    state.SkipWithError("not enough satellites in view");
    return;
  }
  const GpsTime start = bench::scenario_start();
  std::unique_ptr<Receiver> rx;
  std::int64_t k = 0, used = 0, tracked = 0, nlos = 0;
  for (auto _ : state) {
    const std::int64_t e = k++ % kEpochsPerRun;
    if (e == 0) {
      state.PauseTiming();
      rx = std::make_unique<Receiver>(nav, p);
      state.ResumeTiming();
    }
    ImuTruth truth = truth_at(e);
    truth.t = GpsTime{start.ns + e * kEpochNs};
    const ReceiverFix fix = rx->update(truth.t, &truth);
    benchmark::DoNotOptimize(fix.p_ecef_m);
    used += fix.num_used;
    tracked += static_cast<std::int64_t>(fix.satellites.size());
    for (const SatMeasurement& m : rx->measurements().sats) nlos += m.nlos ? 1 : 0;
  }
  const auto n = static_cast<double>(std::max<std::int64_t>(k, 1));
  state.counters["sats_tracked"] = static_cast<double>(tracked) / n;
  state.counters["sats_used"] = static_cast<double>(used) / n;
  if (p.measurement.environment) state.counters["sats_nlos"] = static_cast<double>(nlos) / n;
}

ImuTruth static_truth(const Geodetic& at) {
  ImuTruth t;
  t.position = at;
  return t;
}

void receiver_open_sky(benchmark::State& state, std::size_t sats) {
  const GpsTime start = bench::scenario_start();
  const NavData nav = highest(dense_constellation(start), sats, start, kSite);
  receiver_epochs(state, nav, consumer_receiver(),
                  [](std::int64_t) { return static_truth(kSite); });
}

// Open sky, every error term on, no encoding: exactly 12 (40) satellites in view and used.
void BM_GnssReceiverEpoch12Sats(benchmark::State& state) { receiver_open_sky(state, 12); }
BENCHMARK(BM_GnssReceiverEpoch12Sats)->Unit(benchmark::kMicrosecond);

void BM_GnssReceiverEpoch40Sats(benchmark::State& state) { receiver_open_sky(state, 40); }
BENCHMARK(BM_GnssReceiverEpoch40Sats)->Unit(benchmark::kMicrosecond);

// Four systems of the built-in constellations (GPS, GLONASS, Galileo, BeiDou) at Tokyo, every
// satellite above the horizon tracked: about 40 L1 signals per epoch (the issue's "40 signals
// of 4 systems").
void BM_GnssReceiverEpochFourSystems(benchmark::State& state) {
  const GpsTime start = bench::scenario_start();
  ReceiverParams p = consumer_receiver();
  for (GnssSystem s : {GnssSystem::kGps, GnssSystem::kGlonass, GnssSystem::kGalileo, GnssSystem::kBeidou})
    p.measurement.systems |= system_bit(s);
  const NavData nav = nominal_constellation(start, p.measurement.systems);
  receiver_epochs(state, nav, p, [](std::int64_t) { return static_truth(Geodetic{35.68, 139.69, 40.0}); });
}
BENCHMARK(BM_GnssReceiverEpochFourSystems)->Unit(benchmark::kMicrosecond);

// In the urban scene (bench::mission_city, built once before timing), under the nominal
// 24-slot sky: a vehicle 2 m above the street x = 0, driving back and forth at 2.5 m/s
// between the crossings at y = -120 and y = 0 (y -100 .. -20 m), so every satellite is
// traced (direct path, first-order reflections) from a new place each epoch.
void BM_GnssReceiverEpochUrban(benchmark::State& state) {
  const GpsTime start = bench::scenario_start();
  const NavData nav = nominal_constellation(start);
  ReceiverParams p = consumer_receiver();
  std::ostringstream log;
  p.measurement.environment =
      make_scene_environment(bench::mission_city(), bench::city_origin(), p.measurement.tracking,
                             patch_antenna_pattern(), log);
  // One lap (160 m at 0.5 m per epoch), positions converted before timing.
  const Geodetic o = bench::city_origin();
  const Vec3 p0 = ecef_from_geodetic(o);
  const Mat3 ecef_from_enu = R_enu_from_ecef(o).transpose();
  std::vector<ImuTruth> lap;
  for (int e = 0; e < 320; ++e) {
    const double s = 0.5 * e;
    const bool north = s < 80.0;
    ImuTruth t = static_truth(
        geodetic_from_ecef(p0 + ecef_from_enu * Vec3(0.0, north ? -100.0 + s : 60.0 - s, 2.0)));
    t.v_ned_mps = Vec3(north ? 2.5 : -2.5, 0.0, 0.0);
    lap.push_back(t);
  }
  receiver_epochs(state, nav, p,
                  [&](std::int64_t e) { return lap[static_cast<std::size_t>(e) % lap.size()]; });
}
BENCHMARK(BM_GnssReceiverEpochUrban)->Unit(benchmark::kMicrosecond);

// Consecutive epochs of the 12-satellite open-sky receiver at 5 Hz with their measurements
// and epoch indices (whole periods since the GPS epoch), for the encoders. 30 epochs (6 s):
// encoding them in turn counts sentences and messages with divisors (GSV every 5th epoch,
// RXM-SFRBX every 6 s) at their average rate.
struct EncodedEpoch {
  ReceiverFix fix;
  EpochMeasurements meas;
  std::int64_t index = 0;
};

const NavData& twelve_sats() {
  static const NavData nav =
      highest(dense_constellation(bench::scenario_start()), 12, bench::scenario_start(), kSite);
  return nav;
}

std::vector<EncodedEpoch> twelve_sat_epochs() {
  Receiver rx(twelve_sats(), consumer_receiver());
  const ImuTruth truth = static_truth(kSite);
  std::vector<EncodedEpoch> out;
  for (std::int64_t e = 0; e < 30; ++e) {
    const GpsTime t{bench::scenario_start().ns + e * kEpochNs};
    EncodedEpoch x;
    x.fix = rx.update(t, &truth);
    x.meas = rx.measurements();
    x.index = t.ns / kEpochNs;
    out.push_back(std::move(x));
  }
  return out;
}

// Encodes the precomputed epochs in turn with `encode(epoch, out)`; reports bytes per epoch.
template <class Encode>
void encode_epochs(benchmark::State& state, Encode encode) {
  const std::vector<EncodedEpoch> epochs = twelve_sat_epochs();
  if (epochs.back().fix.num_used != 12) {
    state.SkipWithError("the 12-satellite receiver has no 12-satellite fix");
    return;
  }
  std::string out;
  out.reserve(16384);
  std::size_t k = 0, bytes = 0;
  for (auto _ : state) {
    out.clear();
    encode(epochs[k++ % epochs.size()], out);
    benchmark::DoNotOptimize(out.data());
    bytes += out.size();
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(bytes));
  state.counters["bytes_per_epoch"] =
      static_cast<double>(bytes) / static_cast<double>(std::max<std::size_t>(k, 1));
}

// NMEA of the ublox-nmea-5hz profile (RMC VTG GGA GSA GLL GST ZDA every epoch, GSV each second).
void BM_GnssEncodeNmeaEpoch(benchmark::State& state) {
  NmeaOutput nmea(load_gnss_profile("ublox-nmea-5hz"), ReceiverMode::kStandalone);
  encode_epochs(state,
                [&](const EncodedEpoch& e, std::string& out) { nmea.encode(e.fix, e.index, out); });
}
BENCHMARK(BM_GnssEncodeNmeaEpoch)->Unit(benchmark::kMicrosecond);

// UBX of the configured F9P (bench::ublox_f9p_configured, NMEA off): NAV-PVT, NAV-DOP,
// NAV-SAT, NAV-EOE, RXM-RAWX every epoch, RXM-SFRBX (12 subframes) every 6 s.
void BM_GnssEncodeUbxEpoch(benchmark::State& state) {
  const std::unique_ptr<GnssDevice> ubx = make_gnss_device(
      bench::ublox_f9p_configured(false), ReceiverMode::kStandalone, twelve_sats());
  encode_epochs(state, [&](const EncodedEpoch& e, std::string& out) {
    ubx->encode_epoch(e.fix, e.meas, e.index, out);
  });
}
BENCHMARK(BM_GnssEncodeUbxEpoch)->Unit(benchmark::kMicrosecond);

// Command handling off the hot path: a CFG-VALGET of 64 items (the most one message may ask)
// and a CFG-VALSET of the same items, each answered with its ACK, must fit in one 10 ms service
// tick with room to spare (issue 21); the epoch encoders above are the same run's baseline.
std::vector<std::uint8_t> config_frame(bool set) {
  std::vector<ubx::CfgKeyValue> items;
  for (const ubx::CfgKey& k : ubx::config_keys())
    if ((k.firmware & ubx::kFwHpg113) && items.size() < 64) items.push_back({k.id, k.default_raw});
  std::vector<std::uint8_t> out;
  if (set) {
    ubx::CfgValset m;
    m.values = items;
    ubx::append(m, out);
  } else {
    ubx::CfgValgetRequest m;
    for (const ubx::CfgKeyValue& kv : items) m.keys.push_back(kv.key_id);
    ubx::append(m, out);
  }
  return out;
}

void config_exchange(benchmark::State& state, bool set) {
  const std::unique_ptr<GnssDevice> ubx =
      make_gnss_device(load_gnss_profile("ublox-f9p"), ReceiverMode::kStandalone, twelve_sats());
  const std::vector<std::uint8_t> frame = config_frame(set);
  std::string replies;
  for (auto _ : state) {
    replies.clear();
    ubx->receive(frame, replies);
    benchmark::DoNotOptimize(replies.data());
  }
  state.counters["reply_bytes"] = static_cast<double>(replies.size());
}
void BM_UbxValget64Items(benchmark::State& state) { config_exchange(state, false); }
BENCHMARK(BM_UbxValget64Items)->Unit(benchmark::kMicrosecond);
void BM_UbxValset64Items(benchmark::State& state) { config_exchange(state, true); }
BENCHMARK(BM_UbxValset64Items)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace navemu
