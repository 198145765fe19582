#pragma once
// A 3D scene around the receiver and the GNSS signal paths through it (Embree 3 behind this
// interface; its headers stay in scene.cpp).
//
// Frame: a local east-north-up frame in metres at the scene's geodetic origin (the emulator
// converts receiver positions and satellite directions into it). Satellites are at infinity
// for the geometry of one scene (a few km): a satellite is a unit direction u_enu pointing from
// the scene towards it; its signal arrives along -u_enu everywhere.
//
// Paths, for an antenna at p and a satellite in direction u:
// - direct: the segment from p along u to the scene's bounds. Blocked when it hits an opaque
//   triangle; foliage triangles (material with foliage_db_per_m > 0) attenuate it instead, by
//   the length of the path inside each closed foliage mesh (entry to exit) times its dB/m
//   (foliage_loss_db is reported whether or not the path is blocked). A foliage mesh is a set
//   of foliage triangles connected by shared vertices; it must be closed (entries and exits
//   pair up), and an antenna inside it counts from its own position to the exit.
// - specular reflections of first order, by mirror construction (image method): for every
//   reflecting planar face F (normal n oriented towards p, point q; faces reflect on both sides,
//   the winding of the mesh does not matter) with p in front of it (dot(p - q, n) > 0) and the
//   satellite in front of it (dot(u, n) > 0), the reflected ray leaves the face in direction u
//   and reaches p from the reflection point r, where r is the first hit of the ray from p in
//   direction m = u - 2 dot(u, n) n (u mirrored in the plane). The path exists when that first
//   hit lies on F itself, within max_range_m of p, and the ray from r along u is not blocked.
//   Excess path over the direct one (satellite at infinity):
//     excess = |r - p| - dot(r - p, u) = |r - p| (1 - cos angle(r - p, u)),
//   which equals 2 d dot(u, n) for a plane at distance d from p (the image-method value: for a
//   ground plane 2 h sin(elevation), for a vertical wall 2 d cos(elevation) cos(az - az_n)).
// - second order (max_order 2): the same construction through two faces in turn: the path
//   p <- r1 (face F1) <- r2 (face F2) <- satellite, with m1 the direction from p to r1 and the
//   direction leaving F2 towards F1 equal to u mirrored in F2; found by mirroring u in F2, then
//   in F1, casting from p, and checking each leg (both reflection points within max_range_m).
// Since the first hit along a direction is unique, there is at most one first-order path per
// face orientation and one second-order path per ordered pair of orientations: the search
// casts one ray per distinct face normal (resp. pair of normals) found near p, so its cost
// grows with the number of orientations near p (3 in a city of axis-aligned boxes), not with
// the number of faces.
// Faces: triangles are grouped into planar faces (same plane within 1 mm and 1e-6 in the
// normal, same material, edge-connected; vertices are matched by position, so meshes need not
// share vertex indices), so a building wall made of two triangles is one reflector.
//
// Thread safety: a built Scene is immutable; its queries may run concurrently.

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "models/geodesy.hpp"

namespace navemu {

// Electromagnetic properties of a surface at the GNSS frequencies (L1 1575.42 MHz).
struct SceneMaterial {
  std::string name;
  double relative_permittivity = 5.0;  // epsilon_r (real part)
  double conductivity_spm = 0.0;       // sigma, S/m: epsilon = epsilon_r - j 60 lambda sigma
  // When set: a fixed reflection loss (dB, >= 0) for both polarisations instead of Fresnel.
  double reflection_loss_db = -1.0;    // < 0: unset
  double foliage_db_per_m = 0.0;       // > 0: a foliage volume (attenuates, does not block or
                                       // reflect)
  bool perfect_conductor = false;      // |Gamma| = 1 (metal)
};

struct SceneMesh {
  std::vector<Vec3> vertices_enu_m;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::vector<std::uint32_t> triangle_material;  // index into materials, one per triangle
  std::vector<SceneMaterial> materials;
};

struct ScenePathOptions {
  int max_order = 1;           // reflections: 0 none, 1 first order, 2 also second order
  double max_range_m = 300.0;  // reflection points farther from the antenna are ignored
};

struct DirectPath {
  bool blocked = false;
  double foliage_loss_db = 0.0;
};

// Entries [0, order) of the arrays are used ([0] is the reflection nearest the antenna, the
// last one is on the satellite side); unused entries stay zero.
struct ReflectedPath {
  std::array<Vec3, 2> points_enu_m{};       // reflection points, satellite side last
  std::array<std::uint32_t, 2> material{};  // of each reflection
  std::array<double, 2> grazing_rad{};      // angle between the incoming ray and the face
  int order = 1;
  double excess_m = 0.0;  // path length minus the direct path's
  double foliage_loss_db = 0.0;  // along all legs
  Vec3 arrival_enu = Vec3::Zero();  // unit vector from the antenna towards points_enu_m[0]
};

struct SceneStats {
  std::size_t triangles = 0;
  std::size_t faces = 0;          // planar reflecting faces
  std::size_t memory_bytes = 0;   // mesh, faces and Embree's BVH (estimate)
};

class Scene {
 public:
  // Validates (InvalidScene with a message naming the triangle/vertex index: empty mesh,
  // non-finite vertex, index out of range, degenerate triangle, material index out of range)
  // and builds the acceleration structure.
  explicit Scene(SceneMesh mesh);
  ~Scene();
  Scene(const Scene&) = delete;
  Scene& operator=(const Scene&) = delete;

  DirectPath direct(const Vec3& p_enu_m, const Vec3& u_enu) const;
  // Reflected paths that reach p from the satellite in direction u (order 1, and 2 when asked).
  // Appends to `out` (cleared first); at most 64 paths, strongest geometry first (shortest
  // excess).
  void reflections(const Vec3& p_enu_m, const Vec3& u_enu, const ScenePathOptions& opt,
                   std::vector<ReflectedPath>& out) const;

  const SceneMaterial& material(std::uint32_t index) const;  // std::out_of_range if invalid
  SceneStats stats() const;
  std::uint64_t rays_cast() const;  // since construction (all threads), for benchmarks

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

struct InvalidScene : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace navemu
