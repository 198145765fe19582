#include "emulator/scene_loader.hpp"

#include <fmt/format.h>
#include <tiny_obj_loader.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <istream>
#include <iterator>
#include <set>
#include <streambuf>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>

#include "emulator/yaml_reader.hpp"
#include "core/errors.hpp"

namespace navemu {

// ---------------------------------------------------------------------------------------------
// Materials table

std::vector<SceneMaterial> load_scene_materials(const std::filesystem::path& file) {
  const YAML::Node root = parse_yaml_file(file, "scene materials");
  YamlMap top(file, root, "");
  if (!top.has("materials"))
    top.fail("materials", "required: a mapping of material names to their properties");
  top.map("materials");  // a mapping, or an error naming its line
  top.reject_unknown_keys();

  const std::string where_file = file.string();
  std::vector<SceneMaterial> out;
  std::set<std::string> seen;
  for (const auto& kv : root["materials"]) {
    const std::string name = kv.first.Scalar();
    const int line = kv.first.Mark().is_null() ? 0 : kv.first.Mark().line + 1;
    const std::string field = "materials." + name;
    if (name.empty() || name.find_first_of(" \t#") != std::string::npos)
      throw InputError(where_file, line, field,
                       "a material name must be one word (it follows usemtl in the OBJ file)");
    if (!seen.insert(name).second)
      throw InputError(where_file, line, field, "duplicate material name");

    YamlMap m(file, kv.second, field);
    SceneMaterial mat;
    mat.name = name;
    const std::optional<double> eps = m.positive("relative_permittivity");
    const std::optional<double> sigma = m.positive("conductivity_spm", true);
    const std::optional<double> loss = m.positive("reflection_loss_db", true);
    const std::optional<double> foliage = m.positive("foliage_db_per_m", true);
    const std::optional<bool> pec = m.boolean("perfect_conductor");
    m.reject_unknown_keys();

    mat.perfect_conductor = pec.value_or(false);
    mat.foliage_db_per_m = foliage.value_or(0.0);
    if (mat.perfect_conductor && mat.foliage_db_per_m > 0.0)
      m.fail("perfect_conductor", "a material is either a perfect conductor or foliage, not both");
    if (!eps && !mat.perfect_conductor && mat.foliage_db_per_m <= 0.0 && !loss)
      throw InputError(where_file, line, field,
                       "relative_permittivity required (or perfect_conductor: true, "
                       "foliage_db_per_m, or reflection_loss_db)");
    if (eps) mat.relative_permittivity = *eps;
    if (sigma) mat.conductivity_spm = *sigma;
    if (loss) mat.reflection_loss_db = *loss;
    out.push_back(std::move(mat));
  }
  if (out.empty()) top.fail("materials", "the table is empty");
  return out;
}

// ---------------------------------------------------------------------------------------------
// OBJ mesh

namespace {

// An istream over text already in memory (tinyobjloader reads from a stream; no second copy).
class MemoryBuffer : public std::streambuf {
 public:
  MemoryBuffer(char* begin, std::size_t size) { setg(begin, begin, begin + size); }
};

bool is_blank(char c) { return c == ' ' || c == '\t'; }

std::string_view skip_blanks(std::string_view s) {
  std::size_t i = 0;
  while (i < s.size() && is_blank(s[i])) ++i;
  return s.substr(i);
}

// Splits off the next blank-separated token of `s` (empty at the end of the line).
std::string_view next_token(std::string_view& s) {
  s = skip_blanks(s);
  std::size_t i = 0;
  while (i < s.size() && !is_blank(s[i])) ++i;
  const std::string_view token = s.substr(0, i);
  s = s.substr(i);
  return token;
}

bool starts_keyword(std::string_view s, std::string_view keyword) {
  return s.size() > keyword.size() && s.substr(0, keyword.size()) == keyword &&
         is_blank(s[keyword.size()]);
}

struct FaceRecord {
  std::uint32_t line = 0;
  std::uint32_t vertices = 0;  // polygon size before triangulation
  std::uint32_t material = 0;  // index into the materials table
};

// What the pre-scan learns: the line of every vertex and face (tinyobjloader reports none) and
// each face's material; it also checks what tinyobjloader would silently accept (unparsable
// or non-finite coordinates read as 0, index 0, indices out of range).
struct Prescan {
  std::vector<std::uint32_t> vertex_line;
  std::vector<FaceRecord> faces;
  std::vector<std::pair<std::size_t, std::size_t>> polygons;  // (face, byte offset of its line)
                                                               // for faces of >= 5 vertices
  std::size_t expected_triangles = 0;
  int lines = 0;
};

class ObjError {
 public:
  explicit ObjError(std::string file) : file_(std::move(file)) {}
  [[noreturn]] void operator()(int line, const std::string& field,
                               const std::string& problem) const {
    throw InputError(file_, line, field, problem);
  }

 private:
  std::string file_;
};

// Parses a vertex index token of an `f` line ("7", "7/2", "7//3", "7/2/3", "-1") and returns
// the 0-based vertex index, or an error naming the line.
std::int64_t face_vertex(std::string_view token, std::int64_t vertices_so_far, int line,
                         const ObjError& fail) {
  std::int64_t parts[3] = {0, 0, 0};
  std::size_t part = 0;
  std::size_t pos = 0;
  while (true) {
    const std::size_t slash = token.find('/', pos);
    const std::string_view text =
        token.substr(pos, slash == std::string_view::npos ? std::string_view::npos : slash - pos);
    if (part == 0 || !text.empty()) {
      std::int64_t v = 0;
      const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
      if (ec != std::errc() || end != text.data() + text.size() || v == 0)
        fail(line, "f",
             fmt::format("'{}' is not a vertex reference (v, v/vt, v//vn or v/vt/vn with "
                         "indices from 1, or negative for relative)",
                         token));
      parts[part] = v;
    }
    if (slash == std::string_view::npos) break;
    if (++part == 3)
      fail(line, "f", fmt::format("'{}' is not a vertex reference (too many '/')", token));
    pos = slash + 1;
  }
  const std::int64_t v = parts[0];
  const std::int64_t index = v > 0 ? v - 1 : vertices_so_far + v;
  if (index < 0)
    fail(line, "f",
         fmt::format("relative vertex index {} reaches before the first vertex ({} so far)", v,
                     vertices_so_far));
  return index;
}

Prescan prescan(const std::string& text, const std::unordered_map<std::string, std::uint32_t>&
                                             material_index,
                const std::string& materials_file, const ObjError& fail) {
  Prescan scan;
  constexpr std::uint32_t kNone = 0xffffffffu;
  std::uint32_t material = kNone;  // of the faces that follow
  int usemtl_line = 0;
  std::string usemtl_name;
  bool usemtl_known = false;
  // Faces referring to vertices not defined yet (allowed if defined later): (line, largest
  // such index), checked against the final count.
  std::vector<std::pair<int, std::int64_t>> forward;

  std::size_t pos = 0;
  int line = 0;
  const std::size_t n = text.size();
  while (pos < n) {
    // Lines end at \n, \r\n or a lone \r, as tinyobjloader splits them.
    std::size_t end = pos;
    while (end < n && text[end] != '\n' && text[end] != '\r') ++end;
    const std::size_t line_start = pos;
    std::string_view s(text.data() + pos, end - pos);
    pos = end == n ? n : end + 1;
    if (end < n && text[end] == '\r' && pos < n && text[pos] == '\n') ++pos;
    ++line;

    s = skip_blanks(s);
    if (s.empty() || s[0] == '#') continue;

    if (starts_keyword(s, "v")) {
      s.remove_prefix(2);
      double xyz[3];
      for (double& c : xyz) {
        std::string_view token = next_token(s);
        if (token.empty())
          fail(line, "v",
               fmt::format("vertex {}: expected three coordinates x y z (east, north, up in "
                           "metres)",
                           scan.vertex_line.size() + 1));
        std::string_view digits = token;
        if (digits[0] == '+') digits.remove_prefix(1);
        const auto [p, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), c);
        if (ec == std::errc::result_out_of_range || (ec == std::errc() && !std::isfinite(c) &&
                                                     p == digits.data() + digits.size()))
          fail(line, "v",
               fmt::format("vertex {}: coordinate '{}' is not a finite number",
                           scan.vertex_line.size() + 1, token));
        if (ec != std::errc() || p != digits.data() + digits.size())
          fail(line, "v",
               fmt::format("vertex {}: '{}' is not a number", scan.vertex_line.size() + 1, token));
      }
      scan.vertex_line.push_back(static_cast<std::uint32_t>(line));
      continue;
    }

    if (starts_keyword(s, "usemtl")) {
      s.remove_prefix(7);
      const std::string_view name = next_token(s);
      if (name.empty()) fail(line, "usemtl", "material name missing");
      usemtl_name.assign(name);
      usemtl_line = line;
      const auto it = material_index.find(usemtl_name);
      usemtl_known = it != material_index.end();
      material = usemtl_known ? it->second : kNone;
      continue;
    }

    if (starts_keyword(s, "f")) {
      s.remove_prefix(2);
      if (usemtl_line == 0)
        fail(line, "f", "face without a material (no usemtl line before it)");
      if (!usemtl_known)
        fail(usemtl_line, "usemtl",
             fmt::format("unknown material '{}' (not in {})", usemtl_name, materials_file));
      const auto so_far = static_cast<std::int64_t>(scan.vertex_line.size());
      std::uint32_t count = 0;
      std::int64_t largest = -1;
      for (std::string_view token = next_token(s); !token.empty(); token = next_token(s)) {
        largest = std::max(largest, face_vertex(token, so_far, line, fail));
        ++count;
      }
      if (largest >= so_far) forward.emplace_back(line, largest);
      if (count < 3)
        fail(line, "f", fmt::format("a face needs at least 3 vertices (this one has {})", count));
      if (count >= 5) scan.polygons.emplace_back(scan.faces.size(), line_start);
      scan.faces.push_back({static_cast<std::uint32_t>(line), count, material});
      scan.expected_triangles += count - 2;
      continue;
    }
    // Everything else (vn, vt, g, o, s, mtllib, l, p, ...) does not matter here.
  }
  scan.lines = line;

  for (const auto& [face_line, index] : forward)
    if (index >= static_cast<std::int64_t>(scan.vertex_line.size()))
      fail(face_line, "f",
           fmt::format("vertex index {} out of range (the file has {} vertices)", index + 1,
                       scan.vertex_line.size()));
  return scan;
}

// The vertex indices of the polygon on the line starting at `offset`, 0-based.
std::vector<std::int64_t> polygon_indices(const std::string& text, std::size_t offset,
                                          std::int64_t vertices_before, int line,
                                          const ObjError& fail) {
  std::size_t end = offset;
  while (end < text.size() && text[end] != '\n' && text[end] != '\r') ++end;
  std::string_view s = skip_blanks(std::string_view(text.data() + offset, end - offset));
  s.remove_prefix(2);
  std::vector<std::int64_t> out;
  for (std::string_view token = next_token(s); !token.empty(); token = next_token(s))
    out.push_back(face_vertex(token, vertices_before, line, fail));
  return out;
}

// How many triangles tinyobjloader makes of one polygon on its own (fewer than n - 2 when the
// polygon is degenerate or self-intersecting and its ear clipping gives up).
std::size_t triangulated_count(const std::vector<Vec3>& vertices,
                               const std::vector<std::int64_t>& polygon) {
  std::string obj;
  for (const std::int64_t i : polygon) {
    const Vec3& v = vertices[static_cast<std::size_t>(i)];
    obj += fmt::format("v {} {} {}\n", v.x(), v.y(), v.z());
  }
  obj += "f";
  for (std::size_t i = 1; i <= polygon.size(); ++i) obj += fmt::format(" {}", i);
  obj += "\n";
  MemoryBuffer buf(obj.data(), obj.size());
  std::istream in(&buf);
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string warn, err;
  if (!tinyobj::LoadObj(&attrib, &shapes, &materials, &warn, &err, &in, nullptr, true, false))
    return 0;
  std::size_t triangles = 0;
  for (const auto& shape : shapes) triangles += shape.mesh.num_face_vertices.size();
  return triangles;
}

// The line number tinyobjloader names in an error ("... line 12.)"), or 0.
int line_in_message(const std::string& message) {
  const std::size_t at = message.rfind("line ");
  if (at == std::string::npos) return 0;
  int line = 0;
  std::from_chars(message.data() + at + 5, message.data() + message.size(), line);
  return line;
}

// The OBJ file's text, read whole: a bound, so that a wrong file is an error rather than memory
// exhausted. A 1-million-triangle city is about 60 MB of OBJ text.
std::string read_obj_text(const std::filesystem::path& obj, const ObjError& fail) {
  std::ifstream in(obj, std::ios::binary);
  if (!in) fail(0, "", "cannot open for reading");
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  in.seekg(0, std::ios::beg);
  constexpr std::streamoff kMaxBytes = std::streamoff{1} << 30;
  if (size > kMaxBytes) fail(0, "", fmt::format("{} bytes: over the 1 GiB a scene may have", size));
  std::string text(static_cast<std::size_t>(std::max<std::streamoff>(size, 0)), '\0');
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  if (!in) fail(0, "", "read failed");
  return text;
}

// tinyobjloader made fewer triangles than the faces have: names the face that lost some.
[[noreturn]] void fail_untriangulated(const std::string& text, const Prescan& scan,
                                      const std::vector<Vec3>& vertices_enu_m, std::size_t triangle_count,
                                      const ObjError& fail) {
  // Only polygons of 5 or more vertices can lose triangles (ear clipping of a degenerate or
  // self-intersecting outline); find the first one.
  for (const auto& [face, offset] : scan.polygons) {
    const FaceRecord& rec = scan.faces[face];
    const int line = static_cast<int>(rec.line);
    // Relative indices count the vertices above the face's line.
    const auto before = static_cast<std::int64_t>(
        std::upper_bound(scan.vertex_line.begin(), scan.vertex_line.end(), rec.line) -
        scan.vertex_line.begin());
    const std::vector<std::int64_t> polygon =
        polygon_indices(text, offset, before, line, fail);
    if (triangulated_count(vertices_enu_m, polygon) != polygon.size() - 2)
      fail(line, "f",
           fmt::format("polygon of {} vertices cannot be triangulated (degenerate or "
                       "self-intersecting)",
                       polygon.size()));
  }
  fail(0, "", fmt::format("tinyobjloader made {} triangles of the faces, expected {}",
                          triangle_count, scan.expected_triangles));
}

// 2-manifold: no edge (pair of vertex indices) may belong to more than two triangles.
void require_two_manifold(const SceneMesh& mesh, const std::vector<std::uint32_t>& triangle_line,
                          const ObjError& fail) {
  // Sort all edge keys; only when some key occurs three times or more, walk the triangles in file
  // order to name the first triangle that is the third on such an edge.
  std::vector<std::uint64_t> keys;
  keys.reserve(3 * mesh.triangles.size());
  auto edge_key = [](std::uint32_t a, std::uint32_t b) {
    return (static_cast<std::uint64_t>(std::min(a, b)) << 32) | std::max(a, b);
  };
  for (const auto& t : mesh.triangles) {
    keys.push_back(edge_key(t[0], t[1]));
    keys.push_back(edge_key(t[1], t[2]));
    keys.push_back(edge_key(t[2], t[0]));
  }
  std::sort(keys.begin(), keys.end());
  std::unordered_map<std::uint64_t, int> crowded;  // edges of 3+ triangles -> seen so far
  for (std::size_t i = 0; i + 2 < keys.size(); ++i)
    if (keys[i] == keys[i + 2]) crowded.emplace(keys[i], 0);
  if (!crowded.empty()) {
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      const auto& tri = mesh.triangles[t];
      for (std::size_t k = 0; k < 3; ++k) {
        const std::uint64_t key = edge_key(tri[k], tri[(k + 1) % 3]);
        const auto it = crowded.find(key);
        if (it != crowded.end() && ++it->second == 3)
          fail(static_cast<int>(triangle_line[t]), "f",
               fmt::format("non-manifold geometry: the edge between vertices {} and {} is "
                           "shared by more than two faces (this is the third)",
                           (key >> 32) + 1, (key & 0xffffffffu) + 1));
      }
    }
  }
}

}  // namespace

SceneMesh load_scene_mesh(const std::filesystem::path& obj,
                          const std::filesystem::path& materials_yaml) {
  SceneMesh mesh;
  mesh.materials = load_scene_materials(materials_yaml);
  std::unordered_map<std::string, std::uint32_t> material_index;
  for (std::size_t i = 0; i < mesh.materials.size(); ++i)
    material_index.emplace(mesh.materials[i].name, static_cast<std::uint32_t>(i));

  const std::string file = obj.string();
  const ObjError fail(file);
  if (!std::filesystem::is_regular_file(obj)) fail(0, "", "no such scene (OBJ) file");
  std::string text = read_obj_text(obj, fail);

  const Prescan scan = prescan(text, material_index, materials_yaml.string(), fail);
  if (scan.faces.empty())
    fail(0, "", fmt::format("no faces: the mesh is empty ({} lines, {} vertices)", scan.lines,
                            scan.vertex_line.size()));

  // The geometry itself: tinyobjloader (it also triangulates polygons). Without a material
  // reader `mtllib` is ignored; every face then has material id -1 and the faces of all
  // shapes come out in file order.
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  {
    std::vector<tinyobj::material_t> unused;
    std::string warn, err;
    MemoryBuffer buf(text.data(), text.size());
    std::istream in(&buf);
    if (!tinyobj::LoadObj(&attrib, &shapes, &unused, &warn, &err, &in, nullptr, true, false)) {
      std::string message = err.empty() ? std::string("tinyobjloader failed") : err;
      while (!message.empty() && (message.back() == '\n' || message.back() == '.'))
        message.pop_back();
      fail(line_in_message(message), "", message);
    }
  }
  if (attrib.vertices.size() != 3 * scan.vertex_line.size())
    fail(0, "", fmt::format("internal error: tinyobjloader read {} vertices, the pre-scan {}",
                            attrib.vertices.size() / 3, scan.vertex_line.size()));

  mesh.vertices_enu_m.resize(scan.vertex_line.size());
  for (std::size_t i = 0; i < mesh.vertices_enu_m.size(); ++i) {
    const Vec3 v(static_cast<double>(attrib.vertices[3 * i]),
                 static_cast<double>(attrib.vertices[3 * i + 1]),
                 static_cast<double>(attrib.vertices[3 * i + 2]));
    if (!v.allFinite())
      fail(static_cast<int>(scan.vertex_line[i]), "v",
           fmt::format("vertex {}: coordinates are not finite", i + 1));
    mesh.vertices_enu_m[i] = v;
  }
  attrib.vertices.clear();
  attrib.vertices.shrink_to_fit();

  std::size_t triangle_count = 0;
  for (const auto& shape : shapes) triangle_count += shape.mesh.num_face_vertices.size();
  if (triangle_count != scan.expected_triangles)
    fail_untriangulated(text, scan, mesh.vertices_enu_m, triangle_count, fail);
  text.clear();
  text.shrink_to_fit();

  // Triangles in file order, each with the material and line of its face.
  mesh.triangles.reserve(triangle_count);
  mesh.triangle_material.reserve(triangle_count);
  std::vector<std::uint32_t> triangle_line;
  triangle_line.reserve(triangle_count);
  std::size_t face = 0;
  std::uint32_t left_in_face = scan.faces[0].vertices - 2;
  const auto vertex_count = mesh.vertices_enu_m.size();
  for (auto& shape : shapes) {
    const auto& idx = shape.mesh.indices;
    for (std::size_t t = 0; t + 2 < idx.size(); t += 3) {
      if (left_in_face == 0) left_in_face = scan.faces[++face].vertices - 2;
      --left_in_face;
      const FaceRecord& rec = scan.faces[face];
      std::array<std::uint32_t, 3> tri{};
      for (std::size_t k = 0; k < 3; ++k) {
        const int v = idx[t + k].vertex_index;
        if (v < 0 || static_cast<std::size_t>(v) >= vertex_count)
          fail(static_cast<int>(rec.line), "f",
               fmt::format("vertex index {} out of range (the file has {} vertices)", v + 1,
                           vertex_count));
        tri[k] = static_cast<std::uint32_t>(v);
      }
      // Zero area: twice the area below 1e-10 of the longest edge squared (the sine of the
      // largest angle below about 1e-10), the rule models/scene.cpp applies.
      const Vec3& a = mesh.vertices_enu_m[tri[0]];
      const Vec3& b = mesh.vertices_enu_m[tri[1]];
      const Vec3& c = mesh.vertices_enu_m[tri[2]];
      const double longest2 =
          std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
      const double twice_area = (b - a).cross(c - a).norm();
      if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2] || longest2 == 0.0 ||
          !(twice_area > 1e-10 * longest2))
        fail(static_cast<int>(rec.line), "f",
             fmt::format("degenerate face (zero area){}",
                         rec.vertices > 3 ? fmt::format(" in the triangulated polygon of {} "
                                                        "vertices",
                                                        rec.vertices)
                                          : ""));
      mesh.triangles.push_back(tri);
      mesh.triangle_material.push_back(rec.material);
      triangle_line.push_back(rec.line);
    }
    shape.mesh = tinyobj::mesh_t{};  // free as we go
  }

  require_two_manifold(mesh, triangle_line, fail);
  return mesh;
}

}  // namespace navemu
