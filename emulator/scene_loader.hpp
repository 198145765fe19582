#pragma once
// Loading a 3D scene for the GNSS signal paths (models/scene.hpp) from files: a Wavefront OBJ
// mesh and a YAML table of materials (configs/scenes/materials.yaml). Every problem is an
// InputError naming the file and line.
//
// OBJ conventions (navemu scene writes them):
// - coordinates in metres in the scene's local east-north-up frame: x east, y north, z up;
// - every face follows a `usemtl NAME` whose NAME is a key of the materials table (the .mtl
//   file named by `mtllib` is not read: the radio properties come from the YAML table);
// - faces are counter-clockwise seen from outside (the normal points to where a reflection can
//   come from); polygons of more than 3 vertices are triangulated by tinyobjloader;
// - closed bodies are 2-manifold: no edge is shared by more than two faces; no face has zero
//   area.
// Only `v`, `f` and `usemtl` matter; normals, texture coordinates, groups, lines and points
// are ignored.

#include <filesystem>
#include <vector>

#include "models/scene.hpp"

namespace navemu {

// The materials table, in file order:
//   materials:
//     NAME:
//       relative_permittivity: 5.24   # > 0; required unless perfect_conductor or foliage
//       conductivity_spm: 0.066       # >= 0, S/m (default 0)
//       reflection_loss_db: 6         # >= 0: fixed loss instead of Fresnel (default: unset)
//       foliage_db_per_m: 1.3         # > 0: a foliage volume (attenuates, never reflects)
//       perfect_conductor: false      # true: |Gamma| = 1 (metal)
// Unknown keys, duplicate names, names with spaces and an empty table are errors.
std::vector<SceneMaterial> load_scene_materials(const std::filesystem::path& materials_yaml);

// The mesh of `obj` with the materials of `materials_yaml`. SceneMesh::materials is the whole
// table in file order (also the materials no face uses); triangle_material indexes it.
// Triangles are in file order (a polygon's triangles in a row).
SceneMesh load_scene_mesh(const std::filesystem::path& obj,
                          const std::filesystem::path& materials_yaml);

}  // namespace navemu
