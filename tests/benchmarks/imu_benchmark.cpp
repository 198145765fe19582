// Throughput of the MEMS IMU error model (models/imu_model.hpp) with every error term on:
// 6-axis internal-rate samples per second on one core, reported as items/s.
//   navemu_benchmarks --benchmark_filter=ImuModel

#include <benchmark/benchmark.h>

#include "models/imu_model.hpp"

namespace navemu {
namespace {

// A consumer MEMS IMU with every term of the datasheet model active.
ImuParams all_terms_on(double internal_rate_hz, double output_rate_hz, double bandwidth_hz) {
  ImuParams p;
  p.name = "benchmark";
  p.internal_rate_hz = internal_rate_hz;
  p.output_rate_hz = output_rate_hz;
  p.bandwidth_hz = bandwidth_hz;
  p.latency_s = 0.002;
  for (ImuSensorParams* s : {&p.accel, &p.gyro}) {
    s->white_density = 1e-3;
    s->bias_instability = 1e-4;
    s->bias_instability_tau_s = 100.0;
    s->random_walk = 1e-5;
    s->turn_on_bias_sigma = 1e-3;
    s->null_offset = Vec3(1e-3, -2e-3, 3e-3);
    s->scale_factor_sigma_ppm = 1000.0;
    s->nonlinearity_ppm = 500.0;
    s->misalignment_sigma_rad = 1e-3;
    s->bias_temp_coeff_per_c = 1e-5;
    s->scale_temp_coeff_ppm_per_c = 100.0;
    s->resolution = 1e-4;
  }
  p.accel.full_scale = 16.0 * 9.80665;
  p.gyro.full_scale = 34.9;
  p.gyro.g_sensitivity = 1e-4;
  return p;
}

void run(benchmark::State& state, const ImuParams& p) {
  ImuModel model(p, 42);
  IdealImu ideal;
  ideal.f_body_mps2 = Vec3(0.1, -0.2, -9.8);
  ideal.w_ib_body_radps = Vec3(6.2e-5, 0.0, -3.9e-5);
  ImuSample out;
  const std::int64_t dt_ns = static_cast<std::int64_t>(1e9 / p.internal_rate_hz);
  GpsTime t{0};
  std::int64_t emitted = 0;
  for (auto _ : state) {
    emitted += model.step(t, ideal, 30.0, out) ? 1 : 0;
    benchmark::DoNotOptimize(out);
    t.ns += dt_ns;
  }
  state.SetItemsProcessed(state.iterations());  // 6-axis samples at the internal rate
  state.counters["output_samples_per_s"] =
      benchmark::Counter(static_cast<double>(emitted), benchmark::Counter::kIsRate);
}

// Internal rate = output rate: every step is an output sample.
void BM_ImuModelAllTermsNoDecimation(benchmark::State& state) {
  run(state, all_terms_on(1000.0, 1000.0, 200.0));
}
BENCHMARK(BM_ImuModelAllTermsNoDecimation);

// 1 kHz internal, 125 Hz output (decimation 8), as the paper's Phidget profile.
void BM_ImuModelAllTermsDecimated(benchmark::State& state) {
  run(state, all_terms_on(1000.0, 125.0, 40.0));
}
BENCHMARK(BM_ImuModelAllTermsDecimated);

}  // namespace
}  // namespace navemu
