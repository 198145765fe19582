// Speed of the emulator's loop offline (`navemu simulate`): one hour of the default
// configuration (5 Hz GNSS receiver with every error term and NMEA encoding, 125 Hz IMU, all
// files written) on one core, reported as the real-time factor; and one GNSS epoch (measurement
// generator, solver, NMEA) on its own.
//   navemu_benchmarks --benchmark_filter='Simulate|GnssEpoch'

#include <benchmark/benchmark.h>

#include <filesystem>
#include <sstream>

#include "emulator/engine.hpp"
#include "emulator/nmea_output.hpp"
#include "models/constellation.hpp"
#include "models/receiver.hpp"

namespace navemu {
namespace {

void BM_SimulateOneHour(benchmark::State& state) {
  RunConfig cfg = load_run_config(default_run_config());
  const GpsTime start = parse_time("2010-11-17T13:00:00Z");
  EngineOptions opt;
  opt.realtime = false;
  opt.duration_s = 3600.0;
  opt.out_dir = std::filesystem::temp_directory_path() / "navemu_bench_simulate";
  double factor = 0.0;
  for (auto _ : state) {
    std::ostringstream log;
    const EngineSummary s = run_engine(cfg, start, opt, log);
    factor = s.scenario_s / s.wall_s;
    benchmark::DoNotOptimize(s.gnss_epochs);
  }
  state.counters["realtime_factor"] = factor;
  std::filesystem::remove_all(opt.out_dir);
}
BENCHMARK(BM_SimulateOneHour)->Unit(benchmark::kSecond)->Iterations(1);

void BM_GnssEpoch(benchmark::State& state) {
  const GpsTime start = parse_time("2010-11-17T13:00:00Z");
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
