// OBJ scenes: the navemu scene generator, the materials table, and the loader's file:line
// errors for every kind of bad input.

#include "emulator/scene_loader.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "tests/emulator/cli_runner.hpp"
#include "tests/test_support.hpp"

namespace navemu {
namespace {

using test::CliRun;
using test::navemu;

const std::filesystem::path kMaterials =
    std::filesystem::path(NAVEMU_SOURCE_DIR) / "configs" / "scenes" / "materials.yaml";

std::filesystem::path temp_path(const std::string& name) {
  return std::filesystem::path(::testing::TempDir()) / ("scene_" + name);
}

std::filesystem::path write_temp(const std::string& name, const std::string& content) {
  const auto p = temp_path(name);
  std::ofstream(p, std::ios::binary) << content;
  return p;
}

// The message of the InputError that loading `obj` throws ("" if none).
std::string load_error(const std::filesystem::path& obj,
                       const std::filesystem::path& materials = kMaterials) {
  try {
    load_scene_mesh(obj, materials);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

std::string materials_error(const std::filesystem::path& yaml) {
  try {
    load_scene_materials(yaml);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// Generates a scene with navemu scene and loads it back.
SceneMesh generate(const std::string& name, std::vector<std::string> args) {
  const auto obj = temp_path(name + ".obj");
  args.insert(args.begin(), {"scene"});
  args.push_back("--out");
  args.push_back(obj.string());
  const CliRun r = navemu(args);
  EXPECT_EQ(r.code, 0) << r.err;
  return load_scene_mesh(obj, kMaterials);
}

// Edges used by exactly one triangle (a closed body has none) and the signed volume enclosed
// by the triangles of the given materials (positive when the normals point outwards).
struct Topology {
  std::size_t boundary_edges = 0;
  std::size_t crowded_edges = 0;  // used by more than two triangles
  double volume_m3 = 0.0;
};

Topology topology(const SceneMesh& m, const std::set<std::string>& body_materials) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses;
  Topology t;
  for (std::size_t i = 0; i < m.triangles.size(); ++i) {
    const auto& tri = m.triangles[i];
    for (std::size_t k = 0; k < 3; ++k) {
      const std::uint32_t a = tri[k], b = tri[(k + 1) % 3];
      ++uses[{std::min(a, b), std::max(a, b)}];
    }
    if (body_materials.count(m.materials[m.triangle_material[i]].name) != 0) {
      const Vec3& a = m.vertices_enu_m[tri[0]];
      const Vec3& b = m.vertices_enu_m[tri[1]];
      const Vec3& c = m.vertices_enu_m[tri[2]];
      t.volume_m3 += a.dot(b.cross(c)) / 6.0;
    }
  }
  for (const auto& [edge, n] : uses) {
    if (n == 1) ++t.boundary_edges;
    if (n > 2) ++t.crowded_edges;
  }
  return t;
}

std::set<std::string> used_materials(const SceneMesh& m) {
  std::set<std::string> names;
  for (const std::uint32_t i : m.triangle_material) names.insert(m.materials.at(i).name);
  return names;
}

// Triangles of a box subdivided into cells of at most `cell` (0: none).
std::size_t box_triangles(double dx, double dy, double dz, double cell) {
  auto n = [&](double len) {
    return cell <= 0.0 ? std::size_t{1} : static_cast<std::size_t>(std::ceil(len / cell - 1e-9));
  };
  return 4 * (n(dx) * n(dy) + n(dx) * n(dz) + n(dy) * n(dz));
}

// ---------------------------------------------------------------------------------------------
// Materials table

TEST(SceneMaterials, TableParses) {
  const std::vector<SceneMaterial> mats = load_scene_materials(kMaterials);
  std::map<std::string, SceneMaterial> by_name;
  for (const SceneMaterial& m : mats) by_name[m.name] = m;
  ASSERT_EQ(mats.size(), 7u);
  for (const char* name : {"concrete", "brick", "glass", "metal", "asphalt", "ground", "foliage"})
    EXPECT_EQ(by_name.count(name), 1u) << name;
  // ITU-R P.2040-2 Table 3 at 1.57542 GHz: sigma = c f^d.
  const double f = 1.57542;
  EXPECT_DOUBLE_EQ(by_name["concrete"].relative_permittivity, 5.24);
  EXPECT_NEAR(by_name["concrete"].conductivity_spm, 0.0462 * std::pow(f, 0.7822), 1e-4);
  EXPECT_NEAR(by_name["brick"].conductivity_spm, 0.0238 * std::pow(f, 0.16), 1e-4);
  EXPECT_NEAR(by_name["glass"].conductivity_spm, 0.0036 * std::pow(f, 1.3394), 1e-5);
  EXPECT_NEAR(by_name["ground"].relative_permittivity, 15.0 * std::pow(f, -0.1), 0.01);
  EXPECT_NEAR(by_name["ground"].conductivity_spm, 0.035 * std::pow(f, 1.63), 1e-4);
  EXPECT_TRUE(by_name["metal"].perfect_conductor);
  EXPECT_DOUBLE_EQ(by_name["foliage"].foliage_db_per_m, 1.3);
  EXPECT_LT(by_name["concrete"].reflection_loss_db, 0.0);  // unset
  for (const SceneMaterial& m : mats) {
    if (m.name != "foliage") {
      EXPECT_EQ(m.foliage_db_per_m, 0.0) << m.name;
    }
  }
}

TEST(SceneMaterials, BadValuesNameFileLineAndKey) {
  const auto neg = write_temp("neg.yaml",
                              "materials:\n"
                              "  concrete:\n"
                              "    relative_permittivity: -2\n");
  EXPECT_EQ(materials_error(neg),
            neg.string() + ":3: materials.concrete.relative_permittivity: must be positive (got -2)");

  const auto sigma = write_temp("sigma.yaml",
                                "materials:\n"
                                "  glass:\n"
                                "    relative_permittivity: 6.31\n"
                                "    conductivity_spm: -0.1\n");
  EXPECT_EQ(materials_error(sigma), sigma.string() +
                                        ":4: materials.glass.conductivity_spm: must be zero or "
                                        "more (got -0.1)");

  const auto text = write_temp("text.yaml",
                               "materials:\n"
                               "  glass:\n"
                               "    relative_permittivity: six\n");
  EXPECT_EQ(materials_error(text),
            text.string() + ":3: materials.glass.relative_permittivity: 'six' is not a number");

  const auto unknown = write_temp("unknown.yaml",
                                  "materials:\n"
                                  "  glass:\n"
                                  "    relative_permittivity: 6.31\n"
                                  "    colour: blue\n");
  EXPECT_EQ(materials_error(unknown).rfind(unknown.string() +
                                               ":4: materials.glass.colour: unknown key",
                                           0),
            0u)
      << materials_error(unknown);

  const auto missing = write_temp("missing.yaml",
                                  "materials:\n"
                                  "  glass:\n"
                                  "    conductivity_spm: 0.1\n");
  EXPECT_EQ(materials_error(missing).rfind(missing.string() +
                                               ":2: materials.glass: relative_permittivity "
                                               "required",
                                           0),
            0u)
      << materials_error(missing);

  const auto both = write_temp("both.yaml",
                               "materials:\n"
                               "  odd:\n"
                               "    foliage_db_per_m: 1\n"
                               "    perfect_conductor: true\n");
  EXPECT_EQ(materials_error(both).rfind(both.string() + ":4: materials.odd.perfect_conductor:", 0),
            0u)
      << materials_error(both);

  const auto top = write_temp("top.yaml", "materials:\n  glass: {relative_permittivity: 6}\nfoo: 1\n");
  EXPECT_EQ(materials_error(top).rfind(top.string() + ":3: foo: unknown key", 0), 0u)
      << materials_error(top);

  const auto empty = write_temp("empty.yaml", "materials: {}\n");
  EXPECT_EQ(materials_error(empty), empty.string() + ":1: materials: the table is empty");

  EXPECT_EQ(materials_error(temp_path("nope.yaml")),
            temp_path("nope.yaml").string() + ": no such scene materials file");
}

TEST(SceneMaterials, BadYamlValueThroughTheMeshLoader) {
  const auto yaml = write_temp("bad_mesh_table.yaml",
                               "# table\n"
                               "materials:\n"
                               "  concrete:\n"
                               "    relative_permittivity: 5.24\n"
                               "    reflection_loss_db: -3\n");
  const auto obj = write_temp("ok.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl concrete\nf 1 2 3\n");
  EXPECT_EQ(load_error(obj, yaml),
            yaml.string() +
                ":5: materials.concrete.reflection_loss_db: must be zero or more (got -3)");
}

// ---------------------------------------------------------------------------------------------
// Generated scenes

TEST(SceneGenerator, UrbanCanyonLoadsBackClosedAndOutward) {
  const SceneMesh m = generate("canyon", {"urban-canyon"});
  // 6 buildings of 48 m per side in 300 m (2 m gaps): 12 boxes of 12 triangles, 3 sheets.
  EXPECT_EQ(m.triangles.size(), 12u * 12u + 3u * 2u);
  EXPECT_EQ(m.triangle_material.size(), m.triangles.size());
  const std::set<std::string> used = used_materials(m);
  EXPECT_TRUE(used.count("concrete") && used.count("asphalt") && used.count("ground"));
  for (const std::string& name : used)
    EXPECT_TRUE(name == "concrete" || name == "glass" || name == "asphalt" || name == "ground")
        << name;
  const Topology t = topology(m, {"concrete", "glass"});
  EXPECT_EQ(t.boundary_edges, 3u * 4u);  // only the sheets' outlines are open
  EXPECT_EQ(t.crowded_edges, 0u);
  EXPECT_NEAR(t.volume_m3, 12 * 48.0 * 20.0 * 30.0, 1e-6);  // closed, normals outwards
  // Ground at z = 0; the street (asphalt) between the building rows at x = +-10 m.
  double zmin = 1e9, zmax = -1e9;
  for (const Vec3& v : m.vertices_enu_m) zmin = std::min(zmin, v.z()), zmax = std::max(zmax, v.z());
  EXPECT_EQ(zmin, 0.0);
  EXPECT_EQ(zmax, 30.0);
}

TEST(SceneGenerator, UrbanCanyonSubdividedAndVariedHeights) {
  const SceneMesh m = generate("canyon_cells", {"urban-canyon", "--facade-cell-m", "5",
                                                "--building-height-m", "20,30,45"});
  std::size_t expected = 6;
  const double heights[] = {20, 30, 45};
  for (int i = 0; i < 12; ++i) expected += box_triangles(20, 48, heights[i % 3], 5);
  EXPECT_EQ(m.triangles.size(), expected);
  const Topology t = topology(m, {"concrete", "glass"});
  EXPECT_EQ(t.boundary_edges, 12u);
  EXPECT_EQ(t.crowded_edges, 0u);
  double volume = 0;
  for (int i = 0; i < 12; ++i) volume += 48.0 * 20.0 * heights[i % 3];
  EXPECT_NEAR(t.volume_m3, volume, 1e-6 * volume);
}

TEST(SceneGenerator, OpenFieldAndTreeRows) {
  const SceneMesh field = generate("field", {"open-field", "--size-m", "500"});
  EXPECT_EQ(field.triangles.size(), 2u);
  EXPECT_EQ(used_materials(field), std::set<std::string>{"ground"});

  const SceneMesh trees = generate("trees", {"tree-rows", "--rows", "3", "--length-m", "100"});
  // 10 trees per row of 100 m at 10 m spacing, 3 rows, 12 triangles per crown; 3 sheets.
  EXPECT_EQ(trees.triangles.size(), 3u * 10u * 12u + 6u);
  EXPECT_EQ(used_materials(trees), (std::set<std::string>{"foliage", "asphalt", "ground"}));
  const Topology t = topology(trees, {"foliage"});
  EXPECT_EQ(t.boundary_edges, 12u);
  EXPECT_NEAR(t.volume_m3, 30 * 6.0 * 6.0 * (12.0 - 3.0), 1e-6);
}

TEST(SceneGenerator, DefaultCityIsAMissionSizedGrid) {
  const auto obj = temp_path("city.obj");
  const CliRun r = navemu({"scene", "city", "--out", obj.string()});
  ASSERT_EQ(r.code, 0) << r.err;
  const SceneMesh m = load_scene_mesh(obj, kMaterials);
  // 8 x 8 blocks of 100 m with 20 m streets in 1 km, 2 x 2 buildings each; one ground sheet.
  EXPECT_EQ(m.triangles.size(), 256u * 12u + 2u);
  const std::set<std::string> used = used_materials(m);
  for (const char* name : {"concrete", "glass", "brick", "metal", "asphalt"})
    EXPECT_EQ(used.count(name), 1u) << name;
  const Topology t = topology(m, {"concrete", "glass", "brick", "metal"});
  EXPECT_EQ(t.boundary_edges, 4u);
  EXPECT_EQ(t.crowded_edges, 0u);
  EXPECT_GT(t.volume_m3, 0.0);
  // The header records the full command.
  const std::string text = test::read_file(obj);
  EXPECT_NE(text.find("# command: navemu scene city --size-m 1000 --block-m 100 "
                      "--street-width-m 20 --lots 2 --alley-m 4 --min-height-m 10 "
                      "--max-height-m 60 --facade-cell-m 0 --seed 1\n"),
            std::string::npos)
      << text.substr(0, 600);
}

TEST(SceneGenerator, SubdividedCityCountsByConstruction) {
  const SceneMesh m = generate("city_cells", {"city", "--size-m", "260", "--facade-cell-m", "7",
                                              "--min-height-m", "21", "--max-height-m", "21"});
  // 260 m, pitch 120 m: the blocks wholly inside [-130, 130] m are [-110, -10] and [10, 110]:
  // 2 x 2 blocks, 16 buildings of 48 m x 48 m x 21 m.
  EXPECT_EQ(m.triangles.size(), 16u * box_triangles(48, 48, 21, 7) + 2u);
  const Topology t = topology(m, {"concrete", "glass", "brick", "metal"});
  EXPECT_EQ(t.crowded_edges, 0u);
  EXPECT_EQ(t.boundary_edges, 4u);
  EXPECT_NEAR(t.volume_m3, 16 * 48.0 * 48.0 * 21.0, 1e-3);
}

TEST(SceneGenerator, SameSeedSameBytes) {
  const std::vector<std::string> args = {"scene", "urban-canyon", "--building-height-m", "15:60",
                                         "--seed", "7", "--out"};
  auto with_out = [&](const std::string& name, const std::string& seed) {
    std::vector<std::string> a = args;
    a[5] = seed;
    a.push_back(temp_path(name).string());
    const CliRun r = navemu(a);
    EXPECT_EQ(r.code, 0) << r.err;
    return test::read_file(temp_path(name));
  };
  const std::string a = with_out("seed_a.obj", "7");
  const std::string b = with_out("seed_b.obj", "7");
  const std::string c = with_out("seed_c.obj", "8");
  EXPECT_FALSE(a.empty());
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
  const CliRun c1 = navemu({"scene", "city", "--seed", "3", "--out", temp_path("c1.obj").string()});
  const CliRun c2 = navemu({"scene", "city", "--seed", "3", "--out", temp_path("c2.obj").string()});
  ASSERT_EQ(c1.code, 0);
  ASSERT_EQ(c2.code, 0);
  EXPECT_EQ(test::read_file(temp_path("c1.obj")), test::read_file(temp_path("c2.obj")));
}

TEST(SceneGenerator, HelpAndUsageErrors) {
  const CliRun help = navemu({"scene", "--help"});
  EXPECT_EQ(help.code, 0);
  for (const char* s : {"urban-canyon", "open-field", "tree-rows", "city", "--facade-cell-m",
                        "--building-height-m", "--street-width-m", "--rows", "--seed",
                        "materials.yaml", "east-north-up"})
    EXPECT_NE(help.out.find(s), std::string::npos) << s;
  EXPECT_NE(navemu({"--help"}).out.find("scene"), std::string::npos);

  EXPECT_EQ(navemu({"scene", "forest", "--out", temp_path("x.obj").string()}).code, 2);
  EXPECT_EQ(navemu({"scene", "city"}).code, 2);  // --out required

  const CliRun wrong = navemu({"scene", "open-field", "--rows", "3", "--out",
                               temp_path("x.obj").string()});
  EXPECT_EQ(wrong.code, 1);
  EXPECT_EQ(wrong.err, "navemu: --rows: does not apply to open-field (only to tree-rows)\n");
  const CliRun crown = navemu({"scene", "tree-rows", "--crown-m", "12", "--out",
                               temp_path("x.obj").string()});
  EXPECT_EQ(crown.code, 1);
  EXPECT_NE(crown.err.find("--crown-m: 12 m must be less than --spacing-m (10 m)"),
            std::string::npos)
      << crown.err;
  const CliRun range = navemu({"scene", "urban-canyon", "--building-height-m", "50:20", "--out",
                               temp_path("x.obj").string()});
  EXPECT_EQ(range.code, 1);
  EXPECT_NE(range.err.find("--building-height-m"), std::string::npos) << range.err;
  const CliRun huge = navemu({"scene", "city", "--facade-cell-m", "0.05", "--out",
                              temp_path("x.obj").string()});
  EXPECT_EQ(huge.code, 1);
  EXPECT_NE(huge.err.find("triangles (at most 50000000)"), std::string::npos) << huge.err;
}

// ---------------------------------------------------------------------------------------------
// The loader on hand-written files

constexpr const char* kTetrahedron =
    "# a closed tetrahedron, counter-clockwise from outside\n"
    "v 0 0 0\n"
    "v 1 0 0\n"
    "v 0 1 0\n"
    "v 0 0 1\n"
    "usemtl concrete\n"
    "f 1 3 2\n"
    "f 1 2 4\n"
    "usemtl glass\n"
    "f 2 3 4\n"
    "f 1 4 3\n";

TEST(SceneLoader, HandWrittenMeshWithPolygonsAndRelativeIndices) {
  const auto obj = write_temp("tet.obj", std::string(kTetrahedron) +
                                             "o ground\n"
                                             "mtllib nowhere.mtl\n"
                                             "v -5 -5 -1\nv 5 -5 -1\nv 5 5 -1\nv -5 5 -1\n"
                                             "vn 0 0 1\n"
                                             "usemtl ground\n"
                                             "f -4//1 -3//1 -2//1 -1//1\n"
                                             "v 0 0 -2\nv 2 0 -2\nv 3 1 -2\nv 1 3 -2\nv -1 1 -2\n"
                                             "usemtl asphalt\n"
                                             "f 9/1 10/1 11/1 12/1 13/1\n");
  const SceneMesh m = load_scene_mesh(obj, kMaterials);
  ASSERT_EQ(m.vertices_enu_m.size(), 13u);
  ASSERT_EQ(m.triangles.size(), 4u + 2u + 3u);  // quad -> 2, pentagon -> 3
  auto index_of = [&](const std::string& name) {
    for (std::size_t i = 0; i < m.materials.size(); ++i)
      if (m.materials[i].name == name) return static_cast<std::uint32_t>(i);
    return 0xffffffffu;
  };
  EXPECT_EQ(m.triangle_material[0], index_of("concrete"));
  EXPECT_EQ(m.triangle_material[1], index_of("concrete"));
  EXPECT_EQ(m.triangle_material[2], index_of("glass"));
  EXPECT_EQ(m.triangle_material[3], index_of("glass"));
  EXPECT_EQ(m.triangle_material[4], index_of("ground"));
  EXPECT_EQ(m.triangle_material[5], index_of("ground"));
  for (std::size_t t = 6; t < 9; ++t) EXPECT_EQ(m.triangle_material[t], index_of("asphalt"));
  EXPECT_EQ(m.triangles[0], (std::array<std::uint32_t, 3>{0, 2, 1}));
  for (std::size_t t = 4; t < 6; ++t)
    for (const std::uint32_t v : m.triangles[t]) EXPECT_TRUE(v >= 4 && v < 8);
  EXPECT_EQ(m.vertices_enu_m[7], Vec3(-5, 5, -1));
  const Topology t = topology(m, {"concrete", "glass"});
  EXPECT_NEAR(t.volume_m3, 1.0 / 6.0, 1e-12);
}

TEST(SceneLoader, MissingFileAndEmptyMesh) {
  const auto none = temp_path("does_not_exist.obj");
  EXPECT_EQ(load_error(none), none.string() + ": no such scene (OBJ) file");
  const auto empty = write_temp("empty.obj", "# nothing\nv 0 0 0\nusemtl concrete\n");
  EXPECT_EQ(load_error(empty),
            empty.string() + ": no faces: the mesh is empty (3 lines, 1 vertices)");
  const auto zero = write_temp("zero.obj", "");
  EXPECT_EQ(load_error(zero), zero.string() + ": no faces: the mesh is empty (0 lines, 0 vertices)");
}

TEST(SceneLoader, BadVertexNamesItsLine) {
  const auto nan = write_temp("nan.obj", "v 0 0 0\n\nv 1 nan 0\nv 0 1 0\nusemtl concrete\nf 1 2 3\n");
  EXPECT_EQ(load_error(nan), nan.string() + ":3: v: vertex 2: coordinate 'nan' is not a finite number");
  const auto inf = write_temp("inf.obj", "v 0 0 0\nv 1 0 -inf\n");
  EXPECT_EQ(load_error(inf), inf.string() + ":2: v: vertex 2: coordinate '-inf' is not a finite number");
  const auto big = write_temp("big.obj", "v 0 0 1e999\n");
  EXPECT_EQ(load_error(big), big.string() + ":1: v: vertex 1: coordinate '1e999' is not a finite number");
  const auto text = write_temp("text.obj", "# x\nv 0 0 0\nv 1 0x 0\n");
  EXPECT_EQ(load_error(text), text.string() + ":3: v: vertex 2: '0x' is not a number");
  const auto few = write_temp("few.obj", "v 0 0\n");
  EXPECT_EQ(load_error(few), few.string() +
                                 ":1: v: vertex 1: expected three coordinates x y z (east, "
                                 "north, up in metres)");
  // Windows and old Mac line ends count lines the same way.
  const auto crlf = write_temp("crlf.obj", "v 0 0 0\r\nv 0 0 0\r\n\r\nv 1 nan 0\r\n");
  EXPECT_EQ(load_error(crlf), crlf.string() + ":4: v: vertex 3: coordinate 'nan' is not a finite number");
  const auto cr = write_temp("cr.obj", "v 0 0 0\rv 1 nan 0\r");
  EXPECT_EQ(load_error(cr), cr.string() + ":2: v: vertex 2: coordinate 'nan' is not a finite number");
}

TEST(SceneLoader, MaterialErrorsNameTheUsemtlOrFaceLine) {
  const auto unknown = write_temp("unknown_mtl.obj",
                                  "v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl concrete\nf 1 2 3\n"
                                  "usemtl plastic\n# a comment\nf 1 3 2\n");
  EXPECT_EQ(load_error(unknown), unknown.string() + ":6: usemtl: unknown material 'plastic' (not in " +
                                     kMaterials.string() + ")");
  const auto none = write_temp("no_mtl.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  EXPECT_EQ(load_error(none),
            none.string() + ":4: f: face without a material (no usemtl line before it)");
  // An unknown name that no face uses is harmless.
  const auto unused = write_temp("unused_mtl.obj",
                                 "v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl plastic\nusemtl glass\nf 1 2 3\n");
  EXPECT_EQ(load_error(unused), "");
}

TEST(SceneLoader, BadFacesNameTheirLine) {
  const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 2 0 0\nusemtl concrete\n";
  const auto three = write_temp("three.obj", tri + "f 1 2 3\nf 2 1 4\ng other\nf 2 1 3\n");
  EXPECT_EQ(load_error(three), three.string() +
                                   ":10: f: non-manifold geometry: the edge between vertices 1 "
                                   "and 2 is shared by more than two faces (this is the third)");
  const auto flat = write_temp("flat.obj", tri + "f 1 3 4\nf 1 2 5\n");
  EXPECT_EQ(load_error(flat), flat.string() + ":8: f: degenerate face (zero area)");
  const auto repeated = write_temp("repeated.obj", tri + "f 1 2 2\n");
  EXPECT_EQ(load_error(repeated), repeated.string() + ":7: f: degenerate face (zero area)");
  const auto range = write_temp("range.obj", tri + "f 1 2 3\nf 1 2 9\n");
  EXPECT_EQ(load_error(range),
            range.string() + ":8: f: vertex index 9 out of range (the file has 5 vertices)");
  const auto before = write_temp("before.obj", tri + "f -1 -2 -6\n");
  EXPECT_EQ(load_error(before),
            before.string() +
                ":7: f: relative vertex index -6 reaches before the first vertex (5 so far)");
  const auto zero = write_temp("zero_index.obj", tri + "f 0 1 2\n");
  EXPECT_EQ(load_error(zero).rfind(zero.string() + ":7: f: '0' is not a vertex reference", 0), 0u)
      << load_error(zero);
  const auto two = write_temp("two.obj", tri + "f 1 2\n");
  EXPECT_EQ(load_error(two),
            two.string() + ":7: f: a face needs at least 3 vertices (this one has 2)");
  // A quad with three collinear corners: one of its triangles has no area.
  const auto quad = write_temp("quad.obj", tri + "f 1 5 2 3\n");
  EXPECT_NE(load_error(quad).find(quad.string() + ":7: f: degenerate face (zero area)"),
            std::string::npos)
      << load_error(quad);
  // A forward reference is fine when the vertex comes later.
  const auto forward = write_temp("forward.obj", "usemtl glass\nf 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n");
  EXPECT_EQ(load_error(forward), "");
}

}  // namespace
}  // namespace navemu
