// Encoding one IMU sample as CAN frames (protocols/can_frames.hpp), per layout, on one core:
// what the 125 Hz (or 1 kHz) loop spends per sample before the frames reach their port.
//   navemu_benchmarks --benchmark_filter=Can

#include <benchmark/benchmark.h>

#include "protocols/can_frames.hpp"

namespace navemu {
namespace {

can::ImuSample sample(std::int64_t k) {
  can::ImuSample s;
  s.gps_time_ns = 1'000'000'000'000'000'000 + k * 8'000'000;
  s.sequence = static_cast<std::uint16_t>(k);
  s.w_body_radps = {0.01 + 1e-6 * static_cast<double>(k % 7), -0.02, 0.11};
  s.f_body_mps2 = {0.3, -0.1 + 1e-5 * static_cast<double>(k % 5), -9.81};
  s.latency_s = 0.002;
  return s;
}

void BM_CanEncodeJ1939(benchmark::State& state) {
  std::int64_t k = 0;
  for (auto _ : state) {
    const can::ImuSample s = sample(k++);
    benchmark::DoNotOptimize(can::j1939::encode_ari(s));
    benchmark::DoNotOptimize(can::j1939::encode_accs(s));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_CanEncodeJ1939);

void BM_CanEncodeHighResClassic(benchmark::State& state) {
  std::int64_t k = 0;
  for (auto _ : state) benchmark::DoNotOptimize(can::highres::encode_classic(sample(k++)));
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_CanEncodeHighResClassic);

void BM_CanEncodeHighResFd(benchmark::State& state) {
  std::int64_t k = 0;
  for (auto _ : state) benchmark::DoNotOptimize(can::highres::encode_fd(sample(k++)));
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_CanEncodeHighResFd);

}  // namespace
}  // namespace navemu
