// Scene ray tracing (models/scene.hpp) on Embree 3: mesh validation, grouping of triangles
// into planar faces, the orientation grid used to pick candidate reflectors, and the direct,
// first- and second-order specular paths by mirror construction (image method).
//
// Precision: Embree traces in single precision and is used only to decide *which* face a ray
// hits first and whether a leg is blocked. Reflection points, path lengths and the foliage
// chords are recomputed in double precision from the face planes and the mesh's own vertices.

#include "models/scene.hpp"

#include <Eigen/Geometry>
#include <embree3/rtcore.h>
#include <fmt/format.h>
#include <sys/types.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <mutex>
#include <numeric>
#include <unordered_map>
#include <utility>

namespace navemu {
namespace {

constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
constexpr float kInfF = std::numeric_limits<float>::infinity();
constexpr double kInf = std::numeric_limits<double>::infinity();

// Planar faces: triangles sharing an edge whose planes agree within these tolerances (and
// whose materials are the same) are one reflector.
constexpr double kFacePlaneTolM = 1e-3;
constexpr double kFaceNormalTol = 1e-6;
// Orientation classes: face normals (up to sign) equal after rounding to this quantum share
// one class and hence one search ray.
constexpr double kOrientationQuantum = 1e-6;
// Below this |cos| between a ray and a plane, a reflection is treated as grazing and skipped
// (the excess path 2 d |cos| vanishes there anyway).
constexpr double kGrazingCosMin = 1e-9;
// Largest coordinate accepted (Embree stores vertices as float: 1e7 m keeps ~1 m resolution,
// the scenes are a few km).
constexpr double kMaxCoordinateM = 1e7;
// The orientation grid: cells at least this large, at most this many along an axis.
constexpr double kGridMinCellM = 16.0;
constexpr double kGridCellsPerAxis = 512.0;
constexpr std::size_t kMaxPaths = 64;

std::atomic<std::uint64_t> g_next_scene_id{1};

// Disjoint sets (union by smaller index, path halving): the root is the smallest member.
class UnionFind {
 public:
  explicit UnionFind(std::size_t n) : parent_(n) {
    std::iota(parent_.begin(), parent_.end(), std::uint32_t{0});
  }
  std::uint32_t find(std::uint32_t x) {
    while (parent_[x] != x) {
      parent_[x] = parent_[parent_[x]];
      x = parent_[x];
    }
    return x;
  }
  void unite(std::uint32_t a, std::uint32_t b) {
    a = find(a);
    b = find(b);
    if (a != b) parent_[std::max(a, b)] = std::min(a, b);
  }

 private:
  std::vector<std::uint32_t> parent_;
};

// Vertex welding by exact position: weld[i] is the smallest index of a vertex at the same
// position as vertex i, so meshes that repeat vertices per face still share edges.
std::vector<std::uint32_t> weld_vertices(const std::vector<Vec3>& v) {
  std::vector<std::uint32_t> order(v.size());
  std::iota(order.begin(), order.end(), std::uint32_t{0});
  std::sort(order.begin(), order.end(), [&v](std::uint32_t a, std::uint32_t b) {
    const Vec3& x = v[a];
    const Vec3& y = v[b];
    if (x.x() != y.x()) return x.x() < y.x();
    if (x.y() != y.y()) return x.y() < y.y();
    if (x.z() != y.z()) return x.z() < y.z();
    return a < b;
  });
  std::vector<std::uint32_t> weld(v.size());
  for (std::size_t i = 0; i < order.size(); ++i) {
    const std::uint32_t k = order[i];
    weld[k] = (i > 0 && v[k] == v[order[i - 1]]) ? weld[order[i - 1]] : k;
  }
  return weld;
}

// The normal's sign made canonical (largest component positive), so that both windings of a
// plane fall into one orientation class.
Vec3 canonical_normal(const Vec3& n) {
  Eigen::Index k = 0;
  n.cwiseAbs().maxCoeff(&k);
  return n[k] < 0.0 ? Vec3(-n) : n;
}

struct OrientationKey {
  std::int64_t a, b, c;
  bool operator==(const OrientationKey&) const = default;
};
struct OrientationKeyHash {
  std::size_t operator()(const OrientationKey& k) const {
    const auto h = static_cast<std::uint64_t>(k.a) * 0x9E3779B97F4A7C15ull ^
                   static_cast<std::uint64_t>(k.b) * 0xC2B2AE3D27D4EB4Full ^
                   static_cast<std::uint64_t>(k.c) * 0x165667B19E3779F9ull;
    return static_cast<std::size_t>(h ^ (h >> 29));
  }
};

// u mirrored in the plane with unit normal n: u - 2 (u . n) n.
Vec3 mirror(const Vec3& u, const Vec3& n) { return u - 2.0 * u.dot(n) * n; }

bool same_plane_normal(const Vec3& a, const Vec3& b) { return a == b || a == -b; }

// Per-query state of the filter functions. Embree hands the filter the RTCIntersectContext,
// which is the first member: the rest is reached by a cast (standard layout).
struct QueryContext {
  RTCIntersectContext base;
  const std::uint32_t* face_of_prim = nullptr;  // ignore_face_filter
  std::uint32_t ignore_face = kNone;
  std::vector<std::uint32_t>* collected = nullptr;  // collect_all_filter
};

// Skips the hits on one face: a leg leaving a face cannot be blocked by that face's own plane,
// and its origin (rounded to float) may lie a hair behind it.
void ignore_face_filter(const RTCFilterFunctionNArguments* args) {
  const auto* ctx = reinterpret_cast<const QueryContext*>(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    const unsigned prim = RTCHitN_primID(args->hit, args->N, i);
    if (ctx->face_of_prim[prim] == ctx->ignore_face) args->valid[i] = 0;
  }
}

// Records every hit and rejects it, so that traversal continues to the end of the ray.
void collect_all_filter(const RTCFilterFunctionNArguments* args) {
  const auto* ctx = reinterpret_cast<const QueryContext*>(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    ctx->collected->push_back(RTCHitN_primID(args->hit, args->N, i));
    args->valid[i] = 0;
  }
}

void set_ray(RTCRay& ray, const Vec3& o, const Vec3& d, float tfar) {
  ray.org_x = static_cast<float>(o.x());
  ray.org_y = static_cast<float>(o.y());
  ray.org_z = static_cast<float>(o.z());
  ray.tnear = 0.0f;
  ray.dir_x = static_cast<float>(d.x());
  ray.dir_y = static_cast<float>(d.y());
  ray.dir_z = static_cast<float>(d.z());
  ray.time = 0.0f;
  ray.tfar = tfar;
  ray.mask = ~0u;
  ray.id = 0;
  ray.flags = 0;
}

// A ray for rtcIntersect1, with no hit yet.
void set_ray_hit(RTCRayHit& rh, const Vec3& o, const Vec3& d, float tfar) {
  set_ray(rh.ray, o, d, tfar);
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
}

struct FoliageHit {
  std::uint32_t component;
  double t_m;
  std::uint32_t triangle;
};

// Per-thread scratch, so that queries allocate nothing once warmed up and may run
// concurrently.
struct Scratch {
  // Orientations near the last antenna position (the emulator asks for every satellite at one
  // position in turn).
  std::uint64_t near_scene = 0;
  Vec3 near_p = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
  double near_range_m = -1.0;
  std::vector<std::uint32_t> near_orientations;
  // Stamps for de-duplicating orientations across grid cells.
  std::uint64_t mark_scene = 0;
  std::uint32_t mark_generation = 0;
  std::vector<std::uint32_t> mark;
  std::vector<std::uint32_t> foliage_prims;
  std::vector<FoliageHit> foliage_hits;
};
Scratch& scratch() {
  static thread_local Scratch s;
  return s;
}

void validate(const SceneMesh& m) {
  if (m.triangles.empty()) throw InvalidScene("scene: no triangles");
  if (m.triangle_material.size() != m.triangles.size()) {
    throw InvalidScene(fmt::format("scene: {} triangle materials for {} triangles",
                                   m.triangle_material.size(), m.triangles.size()));
  }
  for (std::size_t i = 0; i < m.materials.size(); ++i) {
    const SceneMaterial& mat = m.materials[i];
    const auto bad = [&](const char* what) {
      return InvalidScene(fmt::format("scene: material {} (\"{}\") has {}", i, mat.name, what));
    };
    if (!std::isfinite(mat.relative_permittivity) || mat.relative_permittivity <= 0.0)
      throw bad("a relative permittivity that is not finite and positive");
    if (!std::isfinite(mat.conductivity_spm) || mat.conductivity_spm < 0.0)
      throw bad("a conductivity that is not finite and >= 0");
    if (!std::isfinite(mat.reflection_loss_db)) throw bad("a non-finite reflection loss");
    if (!std::isfinite(mat.foliage_db_per_m) || mat.foliage_db_per_m < 0.0)
      throw bad("a foliage attenuation that is not finite and >= 0");
  }
  const std::size_t nv = m.vertices_enu_m.size();
  for (std::size_t i = 0; i < m.triangles.size(); ++i) {
    const auto& tri = m.triangles[i];
    for (const std::uint32_t k : tri) {
      if (k >= nv) {
        throw InvalidScene(fmt::format(
            "scene: triangle {} has vertex index {} out of range ({} vertices)", i, k, nv));
      }
    }
    for (const std::uint32_t k : tri) {
      const Vec3& v = m.vertices_enu_m[k];
      if (!v.allFinite())
        throw InvalidScene(fmt::format("scene: triangle {} has a non-finite vertex {}", i, k));
      if (v.cwiseAbs().maxCoeff() > kMaxCoordinateM) {
        throw InvalidScene(fmt::format(
            "scene: triangle {} has vertex {} farther than {} m from the origin", i, k,
            kMaxCoordinateM));
      }
    }
    if (m.triangle_material[i] >= m.materials.size()) {
      throw InvalidScene(fmt::format("scene: triangle {} has material {} out of range ({} materials)",
                                     i, m.triangle_material[i], m.materials.size()));
    }
    const Vec3& a = m.vertices_enu_m[tri[0]];
    const Vec3& b = m.vertices_enu_m[tri[1]];
    const Vec3& c = m.vertices_enu_m[tri[2]];
    const double twice_area = (b - a).cross(c - a).norm();
    const double longest2 =
        std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
    // Degenerate: repeated or collinear vertices (the sine of the largest angle below 1e-10).
    if (!(twice_area > 1e-10 * longest2)) {
      throw InvalidScene(fmt::format("scene: triangle {} is degenerate (vertices {}, {}, {})", i,
                                     tri[0], tri[1], tri[2]));
    }
  }
  for (std::size_t k = 0; k < nv; ++k) {
    if (!m.vertices_enu_m[k].allFinite())
      throw InvalidScene(fmt::format("scene: vertex {} is not finite", k));
  }
}

// A planar reflector: edge-connected coplanar triangles of one material.
struct SceneFace {
  Vec3 n_enu = Vec3::Zero();  // unit normal (sign: that of the face's first triangle)
  double offset_m = 0.0;       // n . x for every point x of the plane
  std::uint32_t material = 0;
  std::uint32_t orientation = 0;  // class of faces with the same normal up to sign
};

// What Embree reports through its device callbacks: allocated bytes and the first error.
struct EmbreeStatus {
  std::atomic<std::int64_t> bytes{0};
  std::mutex mutex;
  std::string error;
};

void on_embree_error(void* user, RTCError code, const char* str) {
  auto* status = static_cast<EmbreeStatus*>(user);
  const std::lock_guard lock(status->mutex);
  if (status->error.empty())
    status->error = fmt::format("error {}: {}", static_cast<int>(code), str ? str : "");
}

bool on_embree_memory(void* user, ssize_t bytes, bool /*post*/) {
  static_cast<EmbreeStatus*>(user)->bytes.fetch_add(static_cast<std::int64_t>(bytes),
                                                     std::memory_order_relaxed);
  return true;
}

template <class T>
std::size_t bytes_of(const std::vector<T>& v) {
  return v.capacity() * sizeof(T);
}

}  // namespace

struct Scene::Impl {
  std::uint64_t id = g_next_scene_id.fetch_add(1);
  SceneMesh mesh;

  // Opaque triangles (reflect and block): Embree primitive -> mesh triangle and face.
  std::vector<std::uint32_t> opaque_triangle;
  std::vector<std::uint32_t> face_of_prim;
  std::vector<SceneFace> faces;
  std::vector<Vec3> orientation_normal;  // canonical unit normal of each class

  // Foliage triangles: Embree primitive -> mesh triangle and connected component.
  std::vector<std::uint32_t> foliage_triangle;
  std::vector<std::uint32_t> foliage_component;

  // Orientation grid: a uniform east-north grid over the opaque triangles; each cell lists
  // (ascending) the orientation classes of the faces whose triangles' boxes overlap it.
  double grid_e0_m = 0.0, grid_n0_m = 0.0, grid_cell_m = 1.0;
  std::int64_t grid_ne = 0, grid_nn = 0;
  std::vector<std::uint32_t> cell_start;
  std::vector<std::uint32_t> cell_orientations;

  RTCDevice device = nullptr;
  RTCScene opaque = nullptr;
  RTCScene foliage = nullptr;  // null when the mesh has no foliage

  EmbreeStatus embree;
  mutable std::atomic<std::uint64_t> rays{0};
  std::size_t own_bytes = 0;

  Impl() = default;
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;
  ~Impl() {
    if (foliage != nullptr) rtcReleaseScene(foliage);
    if (opaque != nullptr) rtcReleaseScene(opaque);
    if (device != nullptr) rtcReleaseDevice(device);
  }

  void build(SceneMesh m);
  Vec3 area_normal(std::uint32_t triangle) const;  // (b - a) x (c - a): twice the area
  void build_faces(const std::vector<std::uint32_t>& weld);
  void build_grid();
  void build_foliage_components(const std::vector<std::uint32_t>& weld);
  RTCScene build_embree_scene(const std::vector<std::uint32_t>& triangles);

  // Queries.
  void init_context(QueryContext& ctx, std::uint32_t ignore) const;
  std::uint32_t first_face(const Vec3& o, const Vec3& d, float tfar, std::uint32_t ignore) const;
  bool occluded(const Vec3& o, const Vec3& d, std::uint32_t ignore) const;
  double plane_distance(std::uint32_t face, const Vec3& o, const Vec3& d) const;
  double foliage_loss_db(const Vec3& o, const Vec3& d, double length_m) const;
  const std::vector<std::uint32_t>& orientations_near(const Vec3& p, double range_m) const;
  bool first_order(const Vec3& p, const Vec3& u, std::uint32_t orientation, double range_m,
                   ReflectedPath& path) const;
  bool second_order(const Vec3& p, const Vec3& u, std::uint32_t o1, std::uint32_t o2,
                    double range_m, ReflectedPath& path) const;
};

void Scene::Impl::build(SceneMesh m) {
  validate(m);
  mesh = std::move(m);
  const std::size_t nt = mesh.triangles.size();

  opaque_triangle.reserve(nt);
  for (std::size_t i = 0; i < nt; ++i) {
    const bool is_foliage = mesh.materials[mesh.triangle_material[i]].foliage_db_per_m > 0.0;
    (is_foliage ? foliage_triangle : opaque_triangle).push_back(static_cast<std::uint32_t>(i));
  }
  if (!foliage_triangle.empty()) opaque_triangle.shrink_to_fit();

  const std::vector<std::uint32_t> weld = weld_vertices(mesh.vertices_enu_m);
  build_faces(weld);
  build_grid();
  build_foliage_components(weld);

  device = rtcNewDevice(nullptr);
  if (device == nullptr) {
    throw InvalidScene(fmt::format("scene: cannot create the Embree device (error {})",
                                   static_cast<int>(rtcGetDeviceError(nullptr))));
  }
  rtcSetDeviceErrorFunction(device, on_embree_error, &embree);
  rtcSetDeviceMemoryMonitorFunction(device, on_embree_memory, &embree);
  opaque = build_embree_scene(opaque_triangle);
  if (!foliage_triangle.empty()) foliage = build_embree_scene(foliage_triangle);
  {
    const std::lock_guard lock(embree.mutex);
    if (!embree.error.empty()) throw InvalidScene("scene: Embree " + embree.error);
  }

  own_bytes = sizeof(Impl) + bytes_of(mesh.vertices_enu_m) + bytes_of(mesh.triangles) +
              bytes_of(mesh.triangle_material) + mesh.materials.size() * sizeof(SceneMaterial) +
              bytes_of(opaque_triangle) + bytes_of(face_of_prim) + bytes_of(faces) +
              bytes_of(orientation_normal) + bytes_of(foliage_triangle) +
              bytes_of(foliage_component) + bytes_of(cell_start) + bytes_of(cell_orientations);
}

Vec3 Scene::Impl::area_normal(std::uint32_t triangle) const {
  const auto& t = mesh.triangles[triangle];
  const Vec3& a = mesh.vertices_enu_m[t[0]];
  return (mesh.vertices_enu_m[t[1]] - a).cross(mesh.vertices_enu_m[t[2]] - a);
}

// Planar faces: union of opaque triangles across shared (welded) edges when their planes and
// materials agree; then each face's area-weighted normal, plane offset and orientation class.
// (Triangle normals are recomputed where needed rather than stored: on a million triangles
// the arithmetic is cheaper than touching the extra memory.)
void Scene::Impl::build_faces(const std::vector<std::uint32_t>& weld) {
  const std::size_t np = opaque_triangle.size();
  const auto& V = mesh.vertices_enu_m;

  // Triangles around each welded vertex (compressed rows), to find the triangles sharing an
  // edge (a, b): those around a that also use b.
  std::vector<std::uint32_t> start(V.size() + 1, 0);
  for (std::size_t p = 0; p < np; ++p) {
    for (const std::uint32_t k : mesh.triangles[opaque_triangle[p]]) ++start[weld[k] + 1];
  }
  for (std::size_t k = 0; k < V.size(); ++k) start[k + 1] += start[k];
  std::vector<std::uint32_t> around(start.back());
  for (std::size_t p = 0; p < np; ++p) {
    // start[w] serves as the fill position and ends as start[w + 1]; shifted back below.
    for (const std::uint32_t k : mesh.triangles[opaque_triangle[p]])
      around[start[weld[k]]++] = static_cast<std::uint32_t>(p);
  }
  for (std::size_t k = V.size(); k > 0; --k) start[k] = start[k - 1];
  start[0] = 0;

  const auto uses = [&](std::uint32_t p, std::uint32_t w) {
    const auto& t = mesh.triangles[opaque_triangle[p]];
    return weld[t[0]] == w || weld[t[1]] == w || weld[t[2]] == w;
  };
  const auto coplanar = [&](std::uint32_t pa, std::uint32_t pb) {
    const std::uint32_t ta = opaque_triangle[pa], tb = opaque_triangle[pb];
    if (mesh.triangle_material[ta] != mesh.triangle_material[tb]) return false;
    const Vec3 na = area_normal(ta).normalized();
    const Vec3 nb = area_normal(tb).normalized();
    const double s = na.dot(nb) < 0.0 ? -1.0 : 1.0;
    if ((na - s * nb).norm() > kFaceNormalTol) return false;
    const Vec3& a0 = V[mesh.triangles[ta][0]];
    for (const std::uint32_t k : mesh.triangles[tb]) {
      if (std::abs(na.dot(V[k] - a0)) > kFacePlaneTolM) return false;
    }
    return true;
  };

  UnionFind sets(np);
  for (std::size_t p = 0; p < np; ++p) {
    const auto& t = mesh.triangles[opaque_triangle[p]];
    for (std::size_t k = 0; k < 3; ++k) {
      const std::uint32_t a = weld[t[k]], b = weld[t[(k + 1) % 3]];
      for (std::uint32_t i = start[a]; i < start[a + 1]; ++i) {
        const std::uint32_t q = around[i];
        if (q > p && uses(q, b) && coplanar(static_cast<std::uint32_t>(p), q))
          sets.unite(static_cast<std::uint32_t>(p), q);
      }
    }
  }
  start = {};
  around = {};

  // Face ids in order of their first (= root) triangle.
  face_of_prim.resize(np);
  std::size_t nfaces = 0;
  for (std::size_t p = 0; p < np; ++p) {
    const std::uint32_t root = sets.find(static_cast<std::uint32_t>(p));
    face_of_prim[p] =
        root == p ? static_cast<std::uint32_t>(nfaces++) : face_of_prim[root];
  }
  faces.resize(nfaces);
  // Area-weighted normal: the sum of the triangles' cross products (each twice the area times
  // the unit normal), each oriented along the running sum. For coplanar triangles the sum's
  // length is twice the face's area, which weights the plane offset: the area-weighted mean of
  // n . centroid over the triangles.
  for (std::size_t p = 0; p < np; ++p) {
    SceneFace& f = faces[face_of_prim[p]];
    const Vec3 c = area_normal(opaque_triangle[p]);
    f.n_enu += f.n_enu.dot(c) < 0.0 ? Vec3(-c) : c;
    f.material = mesh.triangle_material[opaque_triangle[p]];
  }
  for (std::size_t p = 0; p < np; ++p) {
    SceneFace& f = faces[face_of_prim[p]];
    const auto& tri = mesh.triangles[opaque_triangle[p]];
    const Vec3 centroid = (V[tri[0]] + V[tri[1]] + V[tri[2]]) / 3.0;
    f.offset_m += area_normal(opaque_triangle[p]).norm() * f.n_enu.dot(centroid);
  }
  for (SceneFace& f : faces) {
    const double twice_area = f.n_enu.norm();
    f.n_enu /= twice_area;
    f.offset_m /= twice_area * twice_area;  // one |sum| for the weights, one for n
  }

  // Orientation classes (consecutive faces often share one: try the previous class first).
  std::unordered_map<OrientationKey, std::uint32_t, OrientationKeyHash> classes;
  for (SceneFace& f : faces) {
    const Vec3 n = canonical_normal(f.n_enu);
    // Most scenes have a few orientations: look at the first ones before hashing.
    const std::size_t few = std::min<std::size_t>(orientation_normal.size(), 8);
    const auto hit = std::find(orientation_normal.begin(),
                               orientation_normal.begin() + static_cast<std::ptrdiff_t>(few), n);
    if (hit != orientation_normal.begin() + static_cast<std::ptrdiff_t>(few)) {
      f.orientation = static_cast<std::uint32_t>(hit - orientation_normal.begin());
      continue;
    }
    const OrientationKey key{std::llround(n.x() / kOrientationQuantum),
                             std::llround(n.y() / kOrientationQuantum),
                             std::llround(n.z() / kOrientationQuantum)};
    const auto [it, inserted] =
        classes.try_emplace(key, static_cast<std::uint32_t>(orientation_normal.size()));
    if (inserted) orientation_normal.push_back(n);
    f.orientation = it->second;
  }
}

void Scene::Impl::build_grid() {
  if (faces.empty()) return;
  const auto& V = mesh.vertices_enu_m;
  const std::size_t np = opaque_triangle.size();
  double e0 = kInf, n0 = kInf, e1 = -kInf, n1 = -kInf;
  for (const std::uint32_t t : opaque_triangle) {
    for (const std::uint32_t k : mesh.triangles[t]) {
      e0 = std::min(e0, V[k].x());
      n0 = std::min(n0, V[k].y());
      e1 = std::max(e1, V[k].x());
      n1 = std::max(n1, V[k].y());
    }
  }
  grid_e0_m = e0;
  grid_n0_m = n0;
  grid_cell_m = std::max(std::max(e1 - e0, n1 - n0) / kGridCellsPerAxis, kGridMinCellM);
  grid_ne = static_cast<std::int64_t>(std::floor((e1 - e0) / grid_cell_m)) + 1;
  grid_nn = static_cast<std::int64_t>(std::floor((n1 - n0) / grid_cell_m)) + 1;
  const auto cell_e = [&](double e) {
    return std::clamp(static_cast<std::int64_t>(std::floor((e - grid_e0_m) / grid_cell_m)),
                      std::int64_t{0}, grid_ne - 1);
  };
  const auto cell_n = [&](double n) {
    return std::clamp(static_cast<std::int64_t>(std::floor((n - grid_n0_m) / grid_cell_m)),
                      std::int64_t{0}, grid_nn - 1);
  };

  // Triangles by orientation (counting sort), so that a cell receives each orientation once
  // (last-seen stamp); each triangle marks the cells its east-north bounding box overlaps.
  std::vector<std::uint32_t> order(np);
  {
    std::vector<std::uint32_t> first(orientation_normal.size() + 1, 0);
    for (std::size_t p = 0; p < np; ++p) ++first[faces[face_of_prim[p]].orientation + 1];
    for (std::size_t o = 0; o + 1 < first.size(); ++o) first[o + 1] += first[o];
    for (std::size_t p = 0; p < np; ++p)
      order[first[faces[face_of_prim[p]].orientation]++] = static_cast<std::uint32_t>(p);
  }
  const auto ncells = static_cast<std::size_t>(grid_ne * grid_nn);
  std::vector<std::uint32_t> last(ncells, kNone);
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;  // (cell, orientation)
  for (const std::uint32_t p : order) {
    const std::uint32_t o = faces[face_of_prim[p]].orientation;
    const auto& t = mesh.triangles[opaque_triangle[p]];
    const Vec3& a = V[t[0]];
    const Vec3& b = V[t[1]];
    const Vec3& c = V[t[2]];
    const std::int64_t ce1 = cell_e(std::max({a.x(), b.x(), c.x()}));
    const std::int64_t cn1 = cell_n(std::max({a.y(), b.y(), c.y()}));
    for (std::int64_t cn = cell_n(std::min({a.y(), b.y(), c.y()})); cn <= cn1; ++cn) {
      for (std::int64_t ce = cell_e(std::min({a.x(), b.x(), c.x()})); ce <= ce1; ++ce) {
        const auto cell = static_cast<std::size_t>(cn * grid_ne + ce);
        if (last[cell] == o) continue;
        last[cell] = o;
        pairs.emplace_back(static_cast<std::uint32_t>(cell), o);
      }
    }
  }
  // Compressed rows by cell (counting sort keeps the ascending orientation order).
  cell_start.assign(ncells + 1, 0);
  for (const auto& [c, o] : pairs) ++cell_start[c + 1];
  for (std::size_t c = 0; c < ncells; ++c) cell_start[c + 1] += cell_start[c];
  cell_orientations.resize(pairs.size());
  std::vector<std::uint32_t> fill(cell_start.begin(), cell_start.end() - 1);
  for (const auto& [c, o] : pairs) cell_orientations[fill[c]++] = o;
}

// Closed foliage meshes: foliage triangles connected through shared (welded) vertices.
void Scene::Impl::build_foliage_components(const std::vector<std::uint32_t>& weld) {
  const std::size_t nf = foliage_triangle.size();
  if (nf == 0) return;
  UnionFind sets(nf);
  std::unordered_map<std::uint32_t, std::uint32_t> first_user;  // welded vertex -> prim
  for (std::size_t p = 0; p < nf; ++p) {
    for (const std::uint32_t k : mesh.triangles[foliage_triangle[p]]) {
      const auto [it, inserted] = first_user.try_emplace(weld[k], static_cast<std::uint32_t>(p));
      if (!inserted) sets.unite(it->second, static_cast<std::uint32_t>(p));
    }
  }
  foliage_component.resize(nf);
  for (std::size_t p = 0; p < nf; ++p) foliage_component[p] = sets.find(static_cast<std::uint32_t>(p));
}

RTCScene Scene::Impl::build_embree_scene(const std::vector<std::uint32_t>& triangles) {
  RTCScene scene = rtcNewScene(device);
  // Robust: watertight-ish triangle tests, so rays do not slip through the shared edges of a
  // face; compact: indexed leaves (about a quarter less memory, traversal barely slower);
  // context filter: ignore_face_filter and collect_all_filter.
  rtcSetSceneFlags(scene, static_cast<RTCSceneFlags>(RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_COMPACT |
                                                     RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION));
  // A static scene queried many times: medium quality (binned SAH) builds fast; high quality
  // (spatial splits) would build several times slower for a traversal we barely use.
  rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_MEDIUM);
  if (!triangles.empty()) {
    // Compact vertex buffer of the vertices these triangles use.
    std::vector<std::uint32_t> remap(mesh.vertices_enu_m.size(), kNone);
    std::vector<std::uint32_t> used;
    for (const std::uint32_t t : triangles) {
      for (const std::uint32_t k : mesh.triangles[t]) {
        if (remap[k] == kNone) {
          remap[k] = static_cast<std::uint32_t>(used.size());
          used.push_back(k);
        }
      }
    }
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetGeometryBuildQuality(geom, RTC_BUILD_QUALITY_MEDIUM);
    auto* vb = static_cast<float*>(rtcSetNewGeometryBuffer(
        geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), used.size()));
    auto* ib = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
        geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), triangles.size()));
    if (vb == nullptr || ib == nullptr) {
      rtcReleaseGeometry(geom);
      rtcReleaseScene(scene);
      throw InvalidScene("scene: Embree could not allocate the geometry buffers");
    }
    for (std::size_t i = 0; i < used.size(); ++i) {
      const Vec3& v = mesh.vertices_enu_m[used[i]];
      vb[3 * i + 0] = static_cast<float>(v.x());
      vb[3 * i + 1] = static_cast<float>(v.y());
      vb[3 * i + 2] = static_cast<float>(v.z());
    }
    for (std::size_t i = 0; i < triangles.size(); ++i) {
      const auto& t = mesh.triangles[triangles[i]];
      for (std::size_t k = 0; k < 3; ++k) ib[3 * i + k] = remap[t[k]];
    }
    rtcCommitGeometry(geom);
    rtcAttachGeometry(scene, geom);
    rtcReleaseGeometry(geom);
  }
  rtcCommitScene(scene);
  return scene;
}

// ---- Queries ---------------------------------------------------------------------------------

// A query context that skips the triangles of face `ignore` (kNone: none), so that a leg
// leaving a face does not hit the face itself.
void Scene::Impl::init_context(QueryContext& ctx, std::uint32_t ignore) const {
  rtcInitIntersectContext(&ctx.base);
  if (ignore != kNone) {
    ctx.base.filter = ignore_face_filter;
    ctx.face_of_prim = face_of_prim.data();
    ctx.ignore_face = ignore;
  }
}

std::uint32_t Scene::Impl::first_face(const Vec3& o, const Vec3& d, float tfar,
                                      std::uint32_t ignore) const {
  QueryContext ctx;
  init_context(ctx, ignore);
  RTCRayHit rh;
  set_ray_hit(rh, o, d, tfar);
  rtcIntersect1(opaque, &ctx.base, &rh);
  rays.fetch_add(1, std::memory_order_relaxed);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return kNone;
  return face_of_prim[rh.hit.primID];
}

bool Scene::Impl::occluded(const Vec3& o, const Vec3& d, std::uint32_t ignore) const {
  QueryContext ctx;
  init_context(ctx, ignore);
  RTCRay ray;
  set_ray(ray, o, d, kInfF);
  rtcOccluded1(opaque, &ctx.base, &ray);
  rays.fetch_add(1, std::memory_order_relaxed);
  return ray.tfar < 0.0f;  // Embree sets tfar to -inf on a hit
}

// Distance t along o + t d to the plane of a face, in double precision; NaN when the ray is
// (nearly) parallel to it.
double Scene::Impl::plane_distance(std::uint32_t face, const Vec3& o, const Vec3& d) const {
  const SceneFace& f = faces[face];
  const double cos_nd = f.n_enu.dot(d);
  if (std::abs(cos_nd) < kGrazingCosMin) return std::numeric_limits<double>::quiet_NaN();
  return (f.offset_m - f.n_enu.dot(o)) / cos_nd;
}

// Foliage attenuation along o + t d, t in [0, length]: every hit of the (infinite) ray on the
// foliage triangles, grouped by closed mesh and sorted by distance; since the ray ends outside
// every closed mesh, an odd number of hits means o is inside it, and the hits pair up into
// [entry, exit] chords (the first chord starting at 0 when o is inside). Each chord, clipped to
// [0, length], costs the dB/m of the material at its exit.
double Scene::Impl::foliage_loss_db(const Vec3& o, const Vec3& d, double length_m) const {
  if (foliage == nullptr) return 0.0;
  Scratch& s = scratch();
  s.foliage_prims.clear();
  QueryContext ctx;
  rtcInitIntersectContext(&ctx.base);
  ctx.base.filter = collect_all_filter;
  ctx.collected = &s.foliage_prims;
  RTCRayHit rh;
  set_ray_hit(rh, o, d, kInfF);
  rtcIntersect1(foliage, &ctx.base, &rh);
  rays.fetch_add(1, std::memory_order_relaxed);
  if (s.foliage_prims.empty()) return 0.0;

  // Distances recomputed in double precision on each triangle's plane.
  s.foliage_hits.clear();
  const auto& V = mesh.vertices_enu_m;
  for (const std::uint32_t prim : s.foliage_prims) {
    const std::uint32_t tri = foliage_triangle[prim];
    const auto& t = mesh.triangles[tri];
    const Vec3& a = V[t[0]];
    const Vec3 n = (V[t[1]] - a).cross(V[t[2]] - a);
    const double cos_nd = n.dot(d);
    if (cos_nd == 0.0) continue;
    s.foliage_hits.push_back({foliage_component[prim], n.dot(a - o) / cos_nd, tri});
  }
  std::sort(s.foliage_hits.begin(), s.foliage_hits.end(),
            [](const FoliageHit& x, const FoliageHit& y) {
              if (x.component != y.component) return x.component < y.component;
              if (x.t_m != y.t_m) return x.t_m < y.t_m;
              return x.triangle < y.triangle;
            });
  // One crossing reported twice: by a primitive referenced twice, or by the two triangles of an
  // edge the ray passes through.
  const auto last = std::unique(
      s.foliage_hits.begin(), s.foliage_hits.end(), [](const FoliageHit& x, const FoliageHit& y) {
        return x.component == y.component &&
               (x.triangle == y.triangle ||
                std::abs(x.t_m - y.t_m) <= 1e-9 * (1.0 + std::abs(x.t_m)));
      });
  s.foliage_hits.erase(last, s.foliage_hits.end());

  double loss_db = 0.0;
  for (std::size_t i = 0; i < s.foliage_hits.size();) {
    std::size_t j = i;
    while (j < s.foliage_hits.size() && s.foliage_hits[j].component == s.foliage_hits[i].component)
      ++j;
    bool inside = (j - i) % 2 == 1;
    double entry_m = 0.0;
    for (std::size_t k = i; k < j; ++k) {
      const FoliageHit& h = s.foliage_hits[k];
      if (inside) {
        const double chord_m = std::min(h.t_m, length_m) - std::max(entry_m, 0.0);
        if (chord_m > 0.0) {
          loss_db += chord_m *
                     mesh.materials[mesh.triangle_material[h.triangle]].foliage_db_per_m;
        }
      } else {
        entry_m = h.t_m;
      }
      inside = !inside;
    }
    i = j;
  }
  return loss_db;
}

// Orientation classes of the faces with a triangle whose east-north bounding box meets the grid
// cells of the square of half side range_m around p (a superset of those within range; the
// rays themselves stop at range).
const std::vector<std::uint32_t>& Scene::Impl::orientations_near(const Vec3& p,
                                                                 double range_m) const {
  Scratch& s = scratch();
  if (s.near_scene == id && s.near_p == p && s.near_range_m == range_m) return s.near_orientations;
  s.near_scene = id;
  s.near_p = p;
  s.near_range_m = range_m;
  s.near_orientations.clear();
  if (grid_ne == 0) return s.near_orientations;
  const double e_lo = p.x() - range_m, e_hi = p.x() + range_m;
  const double n_lo = p.y() - range_m, n_hi = p.y() + range_m;
  if (e_hi < grid_e0_m || n_hi < grid_n0_m ||
      e_lo > grid_e0_m + static_cast<double>(grid_ne) * grid_cell_m ||
      n_lo > grid_n0_m + static_cast<double>(grid_nn) * grid_cell_m) {
    return s.near_orientations;
  }
  const auto cell = [&](double x, double x0, std::int64_t count) {
    return std::clamp(static_cast<std::int64_t>(std::floor((x - x0) / grid_cell_m)),
                      std::int64_t{0}, count - 1);
  };
  if (s.mark_scene != id || s.mark.size() != orientation_normal.size()) {
    s.mark_scene = id;
    s.mark.assign(orientation_normal.size(), 0);
    s.mark_generation = 0;
  }
  if (++s.mark_generation == 0) {
    std::fill(s.mark.begin(), s.mark.end(), 0);
    s.mark_generation = 1;
  }
  const std::int64_t ce0 = cell(e_lo, grid_e0_m, grid_ne), ce1 = cell(e_hi, grid_e0_m, grid_ne);
  const std::int64_t cn0 = cell(n_lo, grid_n0_m, grid_nn), cn1 = cell(n_hi, grid_n0_m, grid_nn);
  for (std::int64_t cn = cn0; cn <= cn1; ++cn) {
    for (std::int64_t ce = ce0; ce <= ce1; ++ce) {
      const auto c = static_cast<std::size_t>(cn * grid_ne + ce);
      for (std::uint32_t k = cell_start[c]; k < cell_start[c + 1]; ++k) {
        const std::uint32_t o = cell_orientations[k];
        if (s.mark[o] == s.mark_generation) continue;
        s.mark[o] = s.mark_generation;
        s.near_orientations.push_back(o);
      }
    }
  }
  return s.near_orientations;
}

// First order through the faces of one orientation class (header: mirror construction). The
// ray from p along m = u mirrored in the class's plane can only reflect on the first face it
// hits; when that face's own normal differs from the class's (within the class quantum), the
// construction is repeated with the face's exact normal.
bool Scene::Impl::first_order(const Vec3& p, const Vec3& u, std::uint32_t orientation,
                              double range_m, ReflectedPath& path) const {
  Vec3 n = orientation_normal[orientation];
  std::uint32_t face = kNone;
  Vec3 m;
  for (int attempt = 0; attempt < 2; ++attempt) {
    if (std::abs(u.dot(n)) < kGrazingCosMin) return false;
    m = mirror(u, n);
    const std::uint32_t f = first_face(p, m, static_cast<float>(range_m), kNone);
    if (f == kNone || faces[f].orientation != orientation) return false;
    if (attempt == 1 && f != face) return false;
    face = f;
    if (same_plane_normal(faces[f].n_enu, n)) break;
    if (attempt == 1) return false;
    n = faces[f].n_enu;
  }
  const double t_m = plane_distance(face, p, m);
  if (!(t_m > 0.0) || t_m > range_m) return false;
  const Vec3 r = p + t_m * m;
  if (occluded(r, u, face)) return false;

  const double cos_un = std::abs(u.dot(n));
  path = ReflectedPath{};
  path.order = 1;
  path.points_enu_m[0] = r;
  path.material[0] = faces[face].material;
  path.grazing_rad[0] = std::asin(std::min(1.0, cos_un));
  // |r - p| - (r - p).u = t (1 - m.u) = 2 t (u.n)^2 (= 2 d (u.n) with d = t |u.n|).
  path.excess_m = 2.0 * t_m * cos_un * cos_un;
  path.foliage_loss_db = foliage_loss_db(p, m, t_m) + foliage_loss_db(r, u, kInf);
  path.arrival_enu = m;
  return true;
}

// Second order: satellite -> r2 on a face of class o2 -> r1 on a face of class o1 -> p. With
// u2 = u mirrored in the o2 plane (the direction from r1 towards r2) and u1 = u2 mirrored in the
// o1 plane (from p towards r1): r1 is the first hit from p along u1, r2 the first hit from r1
// along u2, and the leg from r2 along u must be clear.
bool Scene::Impl::second_order(const Vec3& p, const Vec3& u, std::uint32_t o1, std::uint32_t o2,
                               double range_m, ReflectedPath& path) const {
  Vec3 n1 = orientation_normal[o1], n2 = orientation_normal[o2];
  std::uint32_t f1 = kNone, f2 = kNone;
  Vec3 u1, u2, r1, r2;
  double t1_m = 0.0, t2_m = 0.0;
  for (int attempt = 0; attempt < 2; ++attempt) {
    if (std::abs(u.dot(n2)) < kGrazingCosMin) return false;
    u2 = mirror(u, n2);
    if (std::abs(u2.dot(n1)) < kGrazingCosMin) return false;
    u1 = mirror(u2, n1);
    const std::uint32_t g1 = first_face(p, u1, static_cast<float>(range_m), kNone);
    if (g1 == kNone || faces[g1].orientation != o1) return false;
    t1_m = plane_distance(g1, p, u1);
    if (!(t1_m > 0.0) || t1_m > range_m) return false;
    r1 = p + t1_m * u1;
    const std::uint32_t g2 = first_face(r1, u2, static_cast<float>(2.0 * range_m), g1);
    if (g2 == kNone || faces[g2].orientation != o2) return false;
    t2_m = plane_distance(g2, r1, u2);
    if (!(t2_m > 0.0)) return false;
    r2 = r1 + t2_m * u2;
    if ((r2 - p).norm() > range_m) return false;
    if (attempt == 1 && (g1 != f1 || g2 != f2)) return false;
    f1 = g1;
    f2 = g2;
    if (same_plane_normal(faces[f1].n_enu, n1) && same_plane_normal(faces[f2].n_enu, n2)) break;
    if (attempt == 1) return false;
    n1 = faces[f1].n_enu;
    n2 = faces[f2].n_enu;
  }
  if (occluded(r2, u, f2)) return false;

  const double c2 = u.dot(n2), c1 = u2.dot(n1);
  path = ReflectedPath{};
  path.order = 2;
  path.points_enu_m = {r1, r2};
  path.material = {faces[f1].material, faces[f2].material};
  path.grazing_rad = {std::asin(std::min(1.0, std::abs(c1))), std::asin(std::min(1.0, std::abs(c2)))};
  // |r1 - p| + |r2 - r1| - (r2 - p).u = t1 (1 - u1.u) + t2 (1 - u2.u), with
  // 1 - u2.u = 2 (u.n2)^2 and 1 - u1.u = 2 (u.n2)^2 + 2 (u2.n1)(u.n1).
  path.excess_m = t1_m * (2.0 * c2 * c2 + 2.0 * c1 * u.dot(n1)) + t2_m * 2.0 * c2 * c2;
  path.foliage_loss_db = foliage_loss_db(p, u1, t1_m) + foliage_loss_db(r1, u2, t2_m) +
                         foliage_loss_db(r2, u, kInf);
  path.arrival_enu = u1;
  return true;
}

// ---- Scene -----------------------------------------------------------------------------------

Scene::Scene(SceneMesh mesh) : impl_(std::make_unique<Impl>()) { impl_->build(std::move(mesh)); }

Scene::~Scene() = default;

DirectPath Scene::direct(const Vec3& p_enu_m, const Vec3& u_enu) const {
  const Vec3 u = u_enu.normalized();
  DirectPath out;
  out.blocked = impl_->occluded(p_enu_m, u, kNone);
  out.foliage_loss_db = impl_->foliage_loss_db(p_enu_m, u, kInf);
  return out;
}

void Scene::reflections(const Vec3& p_enu_m, const Vec3& u_enu, const ScenePathOptions& opt,
                        std::vector<ReflectedPath>& out) const {
  out.clear();
  if (opt.max_order < 1 || !(opt.max_range_m > 0.0)) return;
  const Vec3 u = u_enu.normalized();
  const Impl& s = *impl_;
  const std::vector<std::uint32_t>& near = s.orientations_near(p_enu_m, opt.max_range_m);
  ReflectedPath path;
  for (const std::uint32_t o : near) {
    if (s.first_order(p_enu_m, u, o, opt.max_range_m, path)) out.push_back(path);
  }
  if (opt.max_order >= 2) {
    for (const std::uint32_t o2 : near) {
      for (const std::uint32_t o1 : near) {
        if (s.second_order(p_enu_m, u, o1, o2, opt.max_range_m, path)) out.push_back(path);
      }
    }
  }
  std::sort(out.begin(), out.end(), [](const ReflectedPath& a, const ReflectedPath& b) {
    return a.excess_m < b.excess_m;
  });
  if (out.size() > kMaxPaths) out.resize(kMaxPaths);
}

const SceneMaterial& Scene::material(std::uint32_t index) const {
  if (index >= impl_->mesh.materials.size()) {
    throw std::out_of_range(fmt::format("scene: material {} out of range ({} materials)", index,
                                        impl_->mesh.materials.size()));
  }
  return impl_->mesh.materials[index];
}

SceneStats Scene::stats() const {
  SceneStats st;
  st.triangles = impl_->mesh.triangles.size();
  st.faces = impl_->faces.size();
  st.memory_bytes = impl_->own_bytes +
                    static_cast<std::size_t>(std::max<std::int64_t>(0, impl_->embree.bytes.load()));
  return st;
}

std::uint64_t Scene::rays_cast() const { return impl_->rays.load(std::memory_order_relaxed); }

}  // namespace navemu
