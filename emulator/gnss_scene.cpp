#include "emulator/gnss_scene.hpp"

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <chrono>
#include <ostream>

#include "emulator/scene_loader.hpp"
#include "core/errors.hpp"

namespace navemu {

std::shared_ptr<const SignalEnvironmentModel> make_scene_environment(
    const SceneSpec& spec, const Geodetic& default_origin, const TrackingParams& tracking,
    const AntennaPattern& antenna, std::ostream& log) {
  const auto t0 = std::chrono::steady_clock::now();
  SceneMesh mesh = load_scene_mesh(spec.obj, spec.materials);
  std::shared_ptr<const Scene> scene;
  try {
    scene = std::make_shared<const Scene>(std::move(mesh));
  } catch (const InvalidScene& e) {
    throw InputError(spec.obj, 0, "", e.what());
  }
  const double build_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  SceneEnvironmentParams p;
  p.origin = spec.origin.value_or(default_origin);
  p.offset_enu_m = spec.offset_enu_m;
  p.paths.max_order = spec.max_order;
  p.paths.max_range_m = spec.max_range_m;
  p.response = spec.response == "paper" ? MultipathResponse::kPaperRule
                                        : MultipathResponse::kDiscriminator;
  p.cutoff_m = spec.cutoff_m;
  p.chip_spacing = spec.chip_spacing.value_or(tracking.chip_spacing);
  p.antenna = antenna;
  const SceneStats st = scene->stats();
  fmt::print(log,
             "navemu: scene {}: {} triangles, {} reflecting faces, {:.1f} MB, loaded and built in "
             "{:.2f} s; reflections up to order {}, {} response ({})\n",
             spec.obj, st.triangles, st.faces, static_cast<double>(st.memory_bytes) / 1e6, build_s,
             spec.max_order, spec.response,
             spec.response == "paper" ? fmt::format("cut-off {} m", spec.cutoff_m)
                                      : fmt::format("{} chip early-late spacing", p.chip_spacing));
  return std::make_shared<SceneEnvironment>(std::move(scene), p);
}

}  // namespace navemu
