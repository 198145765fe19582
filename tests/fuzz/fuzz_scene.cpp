// The scene loader (emulator/scene_loader.hpp): an input that starts with "materials:" is a
// materials table, loaded with a one-triangle OBJ; any other input is an OBJ mesh, loaded with
// the project's materials table (configs/scenes/materials.yaml). Either loads or is refused
// with an InputError naming file and line; a loaded mesh's triangles name vertices of the mesh
// and materials of the table.

#include <cstdint>
#include <string_view>

#include "emulator/imu_profile.hpp"
#include "emulator/scene_loader.hpp"
#include "core/errors.hpp"
#include "tests/fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const auto project_materials = navemu::config_dir() / "scenes" / "materials.yaml";
  const std::string_view text = navemu::fuzz::text_of(data, size);
  try {
    navemu::SceneMesh mesh;
    if (text.starts_with("materials:")) {
      const auto materials = navemu::fuzz::write_scratch("materials.yaml", text);
      const auto obj = navemu::fuzz::write_scratch(
          "one.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl concrete\nf 1 2 3\n");
      mesh = navemu::load_scene_mesh(obj, materials);
    } else {
      mesh = navemu::load_scene_mesh(navemu::fuzz::write_scratch("scene.obj", text), project_materials);
    }
    if (mesh.triangle_material.size() != mesh.triangles.size())
      navemu::fuzz::fail("not one material per triangle");
    for (const auto m : mesh.triangle_material)
      if (m >= mesh.materials.size()) navemu::fuzz::fail("a triangle names a material outside the table");
    for (const auto& triangle : mesh.triangles)
      for (const auto v : triangle)
        if (v >= mesh.vertices_enu_m.size()) navemu::fuzz::fail("a triangle names a vertex outside the mesh");
  } catch (const navemu::InputError&) {
  }
  return 0;
}
