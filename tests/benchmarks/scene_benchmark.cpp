// Scene ray tracing (models/scene.hpp) on a procedural city of about a million triangles:
// building the scene (validation, planar faces, orientation grid, Embree BVH) and one receiver
// epoch (12 satellites: direct path and first-order reflections) on one core.
//   navemu_benchmarks --benchmark_filter=Scene

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "emulator/cli.hpp"
#include "emulator/scene_loader.hpp"
#include "models/scene.hpp"

namespace navemu {
namespace {

// City grid: kBlocks x kBlocks box buildings, 20 m x 20 m footprints on a 35 m pitch (15 m
// streets), heights 10..59 m from an integer hash; each building is 8 vertices and 10
// triangles (4 walls and a roof, no floor); one 2-triangle ground plane under everything.
// 317^2 buildings = 1,004,890 triangles + 2.
constexpr int kBlocks = 317;
constexpr double kPitchM = 35.0;
constexpr double kFootprintM = 20.0;
constexpr double kOriginM = -0.5 * kBlocks * kPitchM;

std::uint32_t hash2(std::uint32_t i, std::uint32_t j) {
  std::uint32_t h = i * 0x9E3779B1u ^ (j + 0x7F4A7C15u) * 0x85EBCA6Bu;
  h ^= h >> 15;
  h *= 0xC2B2AE35u;
  h ^= h >> 13;
  return h;
}

SceneMesh make_city() {
  SceneMesh m;
  m.materials.resize(3);
  m.materials[0].name = "ground";
  m.materials[0].relative_permittivity = 15.0;
  m.materials[1].name = "concrete";
  m.materials[1].relative_permittivity = 5.3;
  m.materials[2].name = "glass";
  m.materials[2].relative_permittivity = 6.3;
  const std::size_t buildings = static_cast<std::size_t>(kBlocks) * kBlocks;
  m.vertices_enu_m.reserve(8 * buildings + 4);
  m.triangles.reserve(10 * buildings + 2);
  m.triangle_material.reserve(10 * buildings + 2);

  const double lo = kOriginM - 100.0, hi = -kOriginM + 100.0;
  m.vertices_enu_m.insert(m.vertices_enu_m.end(),
                          {Vec3(lo, lo, 0), Vec3(hi, lo, 0), Vec3(hi, hi, 0), Vec3(lo, hi, 0)});
  m.triangles.push_back({0, 1, 2});
  m.triangles.push_back({0, 2, 3});
  m.triangle_material.insert(m.triangle_material.end(), {0u, 0u});

  // Box corners: bit 0 east, bit 1 north, bit 2 top.
  static constexpr std::uint32_t kFaces[5][4] = {
      {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}, {4, 5, 7, 6}};
  for (int i = 0; i < kBlocks; ++i) {
    for (int j = 0; j < kBlocks; ++j) {
      const auto ui = static_cast<std::uint32_t>(i), uj = static_cast<std::uint32_t>(j);
      const double x0 = kOriginM + i * kPitchM, y0 = kOriginM + j * kPitchM;
      const double h = 10.0 + static_cast<double>(hash2(ui, uj) % 50u);
      const auto base = static_cast<std::uint32_t>(m.vertices_enu_m.size());
      for (std::uint32_t c = 0; c < 8; ++c) {
        m.vertices_enu_m.emplace_back((c & 1u) ? x0 + kFootprintM : x0,
                                      (c & 2u) ? y0 + kFootprintM : y0, (c & 4u) ? h : 0.0);
      }
      const std::uint32_t mat = 1u + (hash2(uj, ui) & 1u);
      for (const auto& f : kFaces) {
        m.triangles.push_back({base + f[0], base + f[1], base + f[2]});
        m.triangles.push_back({base + f[0], base + f[2], base + f[3]});
        m.triangle_material.insert(m.triangle_material.end(), {mat, mat});
      }
    }
  }
  return m;
}

const SceneMesh& city_mesh() {
  static const SceneMesh mesh = make_city();
  return mesh;
}

const Scene& city_scene() {
  static const Scene scene(city_mesh());
  return scene;
}

// 12 satellites spread over the sky, elevations 10..81.5 deg.
std::vector<Vec3> satellites() {
  std::vector<Vec3> u;
  for (int k = 0; k < 12; ++k) {
    const double az = (15.0 + 30.0 * k) * kDegToRad, el = (10.0 + 6.5 * k) * kDegToRad;
    u.emplace_back(std::cos(el) * std::sin(az), std::cos(el) * std::cos(az), std::sin(el));
  }
  return u;
}

void BM_SceneBuildCity(benchmark::State& state) {
  const SceneMesh& mesh = city_mesh();
  SceneStats st;
  for (auto _ : state) {
    state.PauseTiming();
    SceneMesh copy = mesh;
    state.ResumeTiming();
    auto scene = std::make_unique<Scene>(std::move(copy));
    state.PauseTiming();
    st = scene->stats();
    scene.reset();
    state.ResumeTiming();
  }
  state.counters["triangles"] = static_cast<double>(st.triangles);
  state.counters["faces"] = static_cast<double>(st.faces);
  state.counters["memory_MB"] = static_cast<double>(st.memory_bytes) / 1e6;
}
BENCHMARK(BM_SceneBuildCity)->Unit(benchmark::kMillisecond)->Iterations(3);

// The city `navemu scene city --facade-cell-m 2` writes (1.46 M triangles: subdivided facades,
// so few planar faces): loading the OBJ and material table, then building the scene.
void BM_GeneratedCityLoadAndBuild(benchmark::State& state) {
  const std::filesystem::path obj = std::filesystem::temp_directory_path() / "navemu_bench_city.obj";
  std::vector<std::string> args{"navemu", "scene", "city", "--facade-cell-m", "2", "--out", obj.string()};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  std::ostringstream out, err;
  if (run_cli(static_cast<int>(argv.size()), argv.data(), out, err) != 0) {
    state.SkipWithError(err.str().c_str());
    return;
  }
  const std::filesystem::path materials =
      std::filesystem::path(NAVEMU_SOURCE_DIR) / "configs" / "scenes" / "materials.yaml";
  SceneStats st;
  for (auto _ : state) {
    Scene scene(load_scene_mesh(obj, materials));
    st = scene.stats();
  }
  std::filesystem::remove(obj);
  state.counters["triangles"] = static_cast<double>(st.triangles);
  state.counters["faces"] = static_cast<double>(st.faces);
  state.counters["memory_MB"] = static_cast<double>(st.memory_bytes) / 1e6;
}
BENCHMARK(BM_GeneratedCityLoadAndBuild)->Unit(benchmark::kMillisecond)->Iterations(2);

// One epoch: for each of 12 satellites the direct path and the reflections up to max_order,
// antenna 1.5 m above the middle of a street near the city centre. The antenna moves 0.37 m
// along the street every epoch (as a vehicle would), so no per-position cache helps.
void epoch(benchmark::State& state, int max_order) {
  const Scene& scene = city_scene();
  const std::vector<Vec3> u = satellites();
  const double street_e = kOriginM + (kBlocks / 2) * kPitchM + kFootprintM + 0.5 * (kPitchM - kFootprintM);
  const double street_n = kOriginM + (kBlocks / 2) * kPitchM;
  ScenePathOptions opt;
  opt.max_order = max_order;
  opt.max_range_m = 300.0;
  std::vector<ReflectedPath> out;
  out.reserve(64);
  std::vector<double> epoch_us;
  epoch_us.reserve(1 << 16);
  std::uint64_t paths = 0, blocked = 0, step = 0;
  const std::uint64_t rays0 = scene.rays_cast();
  for (auto _ : state) {
    const Vec3 p(street_e, street_n + 0.37 * static_cast<double>(step++ % 200), 1.5);
    const auto t0 = std::chrono::steady_clock::now();
    for (const Vec3& s : u) {
      const DirectPath d = scene.direct(p, s);
      blocked += d.blocked ? 1 : 0;
      scene.reflections(p, s, opt, out);
      paths += out.size();
      benchmark::DoNotOptimize(out.data());
    }
    const auto t1 = std::chrono::steady_clock::now();
    if (epoch_us.size() < epoch_us.capacity())
      epoch_us.push_back(std::chrono::duration<double, std::micro>(t1 - t0).count());
  }
  const auto rays = static_cast<double>(scene.rays_cast() - rays0);
  const auto n = static_cast<double>(state.iterations());
  std::nth_element(epoch_us.begin(), epoch_us.begin() + static_cast<std::ptrdiff_t>(epoch_us.size() / 2),
                   epoch_us.end());
  state.counters["median_epoch_us"] = epoch_us.empty() ? 0.0 : epoch_us[epoch_us.size() / 2];
  state.counters["rays_per_s"] = benchmark::Counter(rays, benchmark::Counter::kIsRate);
  state.counters["rays_per_epoch"] = rays / n;
  state.counters["paths_per_epoch"] = static_cast<double>(paths) / n;
  state.counters["blocked_per_epoch"] = static_cast<double>(blocked) / n;
}

void BM_SceneEpoch12Sats(benchmark::State& state) { epoch(state, 1); }
BENCHMARK(BM_SceneEpoch12Sats)->Unit(benchmark::kMicrosecond);

void BM_SceneEpoch12SatsSecondOrder(benchmark::State& state) { epoch(state, 2); }
BENCHMARK(BM_SceneEpoch12SatsSecondOrder)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace navemu
