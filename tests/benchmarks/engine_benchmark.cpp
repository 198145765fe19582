// Speed of the emulator's loop offline (`navemu simulate`) on one core, as the real-time factor
// of one hour (scenario time / wall time of the loop; setup such as building a scene is not
// counted, as run_engine measures it):
// - the default configuration: 5 Hz receiver with every error term and NMEA, 125 Hz IMU, its
//   CAN frames (can.log) and every CSV;
// - every output encoded: the u-blox F9P as a client configures it (5 Hz UBX and NMEA, ubx.bin;
//   bench::ublox_f9p_configured) with the same IMU, CAN log and CSVs, in open sky and in the
//   urban scene (bench::mission_city; the vehicle on the paper's circle in the central crossing).
// And one GNSS epoch (measurement generator, solver, NMEA) of the default receiver on its own.
//   navemu_benchmarks --benchmark_filter='Simulate|GnssEpoch'

#include <benchmark/benchmark.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <sstream>
#include <string>

#include "emulator/engine.hpp"
#include "emulator/nmea_output.hpp"
#include "models/constellation.hpp"
#include "models/receiver.hpp"
#include "tests/benchmarks/benchmark_setups.hpp"

namespace navemu {
namespace {

void simulate_one_hour(benchmark::State& state, const RunConfig& cfg, int threads = 1) {
  EngineOptions opt;
  opt.realtime = false;
  opt.threads = threads;
  opt.duration_s = 3600.0;
  // Per process: other runs of the benchmarks may be writing theirs.
  opt.out_dir = std::filesystem::temp_directory_path() /
                ("navemu_bench_simulate_" + std::to_string(getpid()));
  EngineSummary s;
  for (auto _ : state) {
    std::ostringstream log;
    s = run_engine(cfg, bench::scenario_start(), opt, log);
    benchmark::DoNotOptimize(s.gnss_epochs);
  }
  state.counters["realtime_factor"] = s.scenario_s / s.wall_s;
  // Epochs with a fix: shows that the receiver really tracked satellites (in the scene too).
  state.counters["fix_fraction"] = static_cast<double>(s.gnss_fixes) /
                                   static_cast<double>(std::max<std::int64_t>(s.gnss_epochs, 1));
  std::filesystem::remove_all(opt.out_dir);
}

void BM_SimulateOneHour(benchmark::State& state) {
  simulate_one_hour(state, load_run_config(default_run_config()));
}
BENCHMARK(BM_SimulateOneHour)->Unit(benchmark::kSecond)->Iterations(1);

// The ublox-f9p scenario (the paper's circle) with the configured F9P, the antenna 2 m above
// the city's street level (as configs/mission/high.yaml; at street level the ground would block
// every signal) with or without the city around it.
RunConfig every_output() {
  RunConfig cfg = load_run_config(bench::configs_dir() / "ublox-f9p.yaml");
  cfg.gnss = bench::ublox_f9p_configured();
  cfg.truth.position = bench::city_origin();
  cfg.truth.position.h_m += 2.0;
  cfg.truth.circle.center = cfg.truth.position;
  return cfg;
}

void BM_SimulateOneHourAllOutputs(benchmark::State& state) {
  simulate_one_hour(state, every_output());
}
BENCHMARK(BM_SimulateOneHourAllOutputs)->Unit(benchmark::kSecond)->Iterations(1);

// The same as navemu simulate runs it on two or more cores: the IMU on a thread of its own
// (EngineOptions::threads; the same files). The factor is scenario time over wall time.
void BM_SimulateOneHourTwoThreads(benchmark::State& state) {
  simulate_one_hour(state, load_run_config(default_run_config()), 2);
}
BENCHMARK(BM_SimulateOneHourTwoThreads)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();

void BM_SimulateOneHourAllOutputsTwoThreads(benchmark::State& state) {
  simulate_one_hour(state, every_output(), 2);
}
BENCHMARK(BM_SimulateOneHourAllOutputsTwoThreads)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();

void BM_SimulateOneHourAllOutputsUrban(benchmark::State& state) {
  RunConfig cfg = every_output();
  cfg.gnss_scene = bench::mission_city();
  simulate_one_hour(state, cfg);
}
BENCHMARK(BM_SimulateOneHourAllOutputsUrban)->Unit(benchmark::kSecond)->Iterations(1);

void BM_GnssEpoch(benchmark::State& state) {
  const GpsTime start = bench::scenario_start();
  const NavData nav = nominal_constellation(start);
  ReceiverParams p;
  apply_receiver_class(p.measurement, ReceiverClass::kConsumer);
  Receiver rx(nav, p);
  NmeaOutput out(load_gnss_profile("ublox-nmea-5hz"), ReceiverMode::kStandalone);
  ImuTruth truth;
  truth.position = Geodetic{32.3, -90.9, 60.0};
  std::string text;
  text.reserve(4096);
  std::int64_t k = 0;
  for (auto _ : state) {
    truth.t = GpsTime{start.ns + k * 200'000'000};
    const ReceiverFix fix = rx.update(truth.t, &truth);
    text.clear();
    out.encode(fix, k, text);
    benchmark::DoNotOptimize(text.data());
    ++k;
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_GnssEpoch);

}  // namespace
}  // namespace navemu
