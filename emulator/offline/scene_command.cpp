// navemu scene: writes synthetic 3D scenes for the GNSS signal paths as Wavefront OBJ files
// (urban canyon, open field, tree rows, city), with the material names of
// configs/scenes/materials.yaml. Read back by load_scene_mesh (emulator/scene_loader.hpp).

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "emulator/commands.hpp"
#include "core/errors.hpp"
#include "models/random.hpp"

#ifndef NAVEMU_VERSION
#define NAVEMU_VERSION "unknown"
#endif

namespace navemu {

struct SceneOptions {
  std::string kind;
  std::string out_file;
  std::uint64_t seed = 1;
  // Kind-specific parameters: unset means the kind's default (and lets the command reject a
  // parameter that the kind does not take).
  std::optional<double> street_width_m, length_m, building_length_m, building_depth_m, gap_m,
      glass_fraction, facade_cell_m, size_m, block_m, alley_m, min_height_m, max_height_m,
      tree_height_m, spacing_m, crown_m, crown_base_m;
  std::optional<std::string> building_height_m;
  std::optional<int> rows, lots;
};

std::shared_ptr<SceneOptions> add_scene_command(CLI::App& app) {
  auto opt = std::make_shared<SceneOptions>();
  CLI::App* cmd = app.add_subcommand(
      "scene", "Write a synthetic 3D scene (buildings, trees, ground) as an OBJ file");
  cmd->footer(
      "Writes the scene KIND to --out as a Wavefront OBJ file for the GNSS signal paths (direct\n"
      "path blocked or attenuated, ground and wall reflections). Coordinates are metres in the\n"
      "scene's local east-north-up frame (x east, y north, z up; the ground at z = 0), the\n"
      "origin in the middle of the scene, in a street where there are streets. Every face\n"
      "follows a 'usemtl NAME' naming an entry of configs/scenes/materials.yaml (concrete,\n"
      "glass, brick, metal, asphalt, ground, foliage); faces are counter-clockwise seen from\n"
      "outside. Buildings and tree crowns are closed boxes (2-manifold); the ground is separate\n"
      "flat sheets (a street's asphalt and the ground beside it do not share vertices). Each\n"
      "box and sheet is a named object (o building_N, tree_N, ground_N).\n"
      "A comment header records the command with every parameter. The same parameters and\n"
      "--seed give a byte-identical file.\n"
      "\n"
      "Kinds and their parameters (default in brackets):\n"
      "  urban-canyon  one straight street along north, a row of buildings on each side.\n"
      "      --street-width-m [20]   wall-to-wall width of the street (asphalt)\n"
      "      --length-m [300]        length of the street\n"
      "      --building-height-m [30]  one height, a list cycled along each side (20,35,50),\n"
      "                              or a range MIN:MAX drawn per building with --seed\n"
      "      --building-length-m [48] along the street; --gap-m [2] between buildings;\n"
      "                              as many as fit in --length-m, centred\n"
      "      --building-depth-m [20] away from the street\n"
      "      --glass-fraction [0.5]  share of buildings with glass walls (else concrete),\n"
      "                              drawn with --seed; roofs are concrete\n"
      "      --facade-cell-m [0]     split walls and roofs into cells of at most this size\n"
      "                              (0: two triangles per side)\n"
      "  open-field    a flat square of medium-dry ground and nothing else.\n"
      "      --size-m [1000]         side of the square\n"
      "  tree-rows     a road along north with rows of trees (foliage crowns as boxes; trunks\n"
      "                are not modelled) on both sides, alternately east and west.\n"
      "      --street-width-m [10]   road width; --length-m [300] road length\n"
      "      --rows [2]              rows of trees (row 1 east, row 2 west, row 3 east, ...)\n"
      "      --spacing-m [10]        between trees along a row and between rows on a side\n"
      "      --tree-height-m [12]    top of the crowns; --crown-base-m [3] bottom of the crowns\n"
      "      --crown-m [6]           crown width (east and north), less than --spacing-m;\n"
      "                              the first row's crowns start 1 m from the road\n"
      "  city          a grid of blocks with streets between them (asphalt ground).\n"
      "      --size-m [1000]         side of the square city (blocks wholly inside)\n"
      "      --block-m [100]         side of a block; --street-width-m [20] between blocks\n"
      "      --lots [2]              buildings per block side (lots x lots per block),\n"
      "                              --alley-m [4] apart\n"
      "      --min-height-m [10], --max-height-m [60]  building heights drawn with --seed\n"
      "                              (0.5 m steps); walls concrete 45 %, glass 30 %, brick\n"
      "                              15 %, metal 10 % (metal buildings have metal roofs)\n"
      "      --facade-cell-m [0]     as above: 2 m cells make the default city about 1.4\n"
      "                              million triangles (a benchmark scene)\n"
      "The defaults make: urban-canyon 150 triangles, open-field 2, tree-rows 726, city 3074\n"
      "(256 buildings in 64 blocks, about 1 km^2). A progress line goes to standard error for\n"
      "scenes of 250000 triangles or more.\n"
      "Examples:\n"
      "  navemu scene urban-canyon --out canyon.obj --building-height-m 20:60 --seed 3\n"
      "  navemu scene city --out city_bench.obj --facade-cell-m 2\n"
      "Load with: configs/scenes/materials.yaml as the materials table.");
  cmd->add_option("kind", opt->kind, "urban-canyon, open-field, tree-rows or city")
      ->required()
      ->check(CLI::IsMember({"urban-canyon", "open-field", "tree-rows", "city"}));
  cmd->add_option("--out", opt->out_file, "Output OBJ file")->required();
  cmd->add_option("--seed", opt->seed, "Seed of the random heights and materials (urban-canyon, city)")
      ->capture_default_str();
  cmd->add_option("--street-width-m", opt->street_width_m, "Street width (m)");
  cmd->add_option("--length-m", opt->length_m, "Street or road length (m)");
  cmd->add_option("--building-height-m", opt->building_height_m,
                  "Building height (m): H, H1,H2,... or MIN:MAX");
  cmd->add_option("--building-length-m", opt->building_length_m, "Building length along the street (m)");
  cmd->add_option("--building-depth-m", opt->building_depth_m, "Building depth (m)");
  cmd->add_option("--gap-m", opt->gap_m, "Gap between neighbouring buildings (m)");
  cmd->add_option("--glass-fraction", opt->glass_fraction, "Share of glass-walled buildings, 0..1");
  cmd->add_option("--facade-cell-m", opt->facade_cell_m,
                  "Largest cell of the wall and roof grids (m); 0: no subdivision");
  cmd->add_option("--size-m", opt->size_m, "Side of the square scene (m)");
  cmd->add_option("--block-m", opt->block_m, "Side of a city block (m)");
  cmd->add_option("--lots", opt->lots, "Buildings per block side");
  cmd->add_option("--alley-m", opt->alley_m, "Gap between the buildings of a block (m)");
  cmd->add_option("--min-height-m", opt->min_height_m, "Lowest building (m)");
  cmd->add_option("--max-height-m", opt->max_height_m, "Highest building (m)");
  cmd->add_option("--rows", opt->rows, "Rows of trees");
  cmd->add_option("--tree-height-m", opt->tree_height_m, "Top of the tree crowns (m)");
  cmd->add_option("--spacing-m", opt->spacing_m, "Tree spacing along and across rows (m)");
  cmd->add_option("--crown-m", opt->crown_m, "Crown width (m)");
  cmd->add_option("--crown-base-m", opt->crown_base_m, "Bottom of the crowns (m)");
  return opt;
}

namespace {

// Material names: keys of configs/scenes/materials.yaml.
constexpr std::string_view kConcrete = "concrete";
constexpr std::string_view kGlass = "glass";
constexpr std::string_view kBrick = "brick";
constexpr std::string_view kMetal = "metal";
constexpr std::string_view kAsphalt = "asphalt";
constexpr std::string_view kGround = "ground";
constexpr std::string_view kFoliage = "foliage";

// Above this many triangles the command refuses (a typo in --facade-cell-m would fill the
// disk); about 1.5 GB of OBJ.
constexpr std::uint64_t kMaxTriangles = 50'000'000;
constexpr std::uint64_t kProgressTriangles = 250'000;

// Cells along an edge of length `len` with cells of at most `cell` (0: one).
std::uint32_t divisions(double len, double cell) {
  if (cell <= 0.0) return 1;
  return static_cast<std::uint32_t>(std::max(1.0, std::ceil(len / cell - 1e-9)));
}

// One closed box or one flat ground sheet of the plan.
struct Part {
  bool sheet = false;
  double x0 = 0, x1 = 0, y0 = 0, y1 = 0, z0 = 0, z1 = 0;  // sheet: z0 = z1
  std::uint32_t nx = 1, ny = 1, nz = 1;
  std::string_view walls, roof;  // sheet: walls only

  std::uint64_t triangles() const {
    if (sheet) return 2;
    return 4ull * (std::uint64_t{nx} * ny + std::uint64_t{nx} * nz + std::uint64_t{ny} * nz);
  }
  std::uint64_t vertices() const {
    if (sheet) return 4;
    const std::uint64_t all = std::uint64_t{nx + 1} * (ny + 1) * (nz + 1);
    const std::uint64_t inner = std::uint64_t{nx - 1} * (ny - 1) * (nz - 1);
    return all - inner;
  }
};

Part box(double x0, double x1, double y0, double y1, double z0, double z1, double cell,
         std::string_view walls, std::string_view roof) {
  Part p;
  p.x0 = x0, p.x1 = x1, p.y0 = y0, p.y1 = y1, p.z0 = z0, p.z1 = z1;
  p.nx = divisions(x1 - x0, cell);
  p.ny = divisions(y1 - y0, cell);
  p.nz = divisions(z1 - z0, cell);
  p.walls = walls;
  p.roof = roof;
  return p;
}

Part sheet(double x0, double x1, double y0, double y1, std::string_view material) {
  Part p;
  p.sheet = true;
  p.x0 = x0, p.x1 = x1, p.y0 = y0, p.y1 = y1;
  p.walls = material;
  return p;
}

struct Plan {
  std::vector<Part> parts;
  std::string command;      // the canonical command line, every parameter
  std::string description;  // one line for the header
};

// Writes OBJ text through a buffer, flushed in large blocks.
class ObjWriter {
 public:
  explicit ObjWriter(const std::string& path) : path_(path), out_(path, std::ios::binary) {
    if (!out_) throw InputError(path, 0, "--out", "cannot open for writing");
  }

  void text(std::string_view s) { buf_.append(s.data(), s.data() + s.size()); }

  // Coordinates rounded to 0.1 mm, written in the shortest form that reads back the same.
  std::uint32_t vertex(double x, double y, double z) {
    fmt::format_to(std::back_inserter(buf_), "v {} {} {}\n", tidy(x), tidy(y), tidy(z));
    maybe_flush();
    return ++vertices_;
  }

  // A named object (one box or sheet), for the users' 3D tools.
  void object(std::string_view kind, std::size_t index) {
    fmt::format_to(std::back_inserter(buf_), "o {}_{}\n", kind, index);
  }

  void use(std::string_view material) {
    if (material == material_) return;
    material_ = material;
    fmt::format_to(std::back_inserter(buf_), "usemtl {}\n", material);
  }

  // A quadrilateral a-b-c-d (counter-clockwise seen from the side it faces): two triangles.
  void quad(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
    fmt::format_to(std::back_inserter(buf_), "f {} {} {} {}\n", a, b, c, d);
    triangles_ += 2;
    maybe_flush();
  }

  void finish() {
    flush();
    out_.close();
    if (!out_) throw InputError(path_, 0, "--out", "write failed");
  }

  std::uint64_t vertices() const { return vertices_; }
  std::uint64_t triangles() const { return triangles_; }
  std::uint64_t bytes() const { return bytes_ + buf_.size(); }

 private:
  static double tidy(double v) { return std::round(v * 1e4) / 1e4 + 0.0; }  // no "-0"
  void maybe_flush() {
    if (buf_.size() > (1u << 20)) flush();
  }
  void flush() {
    out_.write(buf_.data(), static_cast<std::streamsize>(buf_.size()));
    bytes_ += buf_.size();
    buf_.clear();
  }

  std::string path_;
  std::ofstream out_;
  fmt::memory_buffer buf_;
  std::string_view material_;
  std::uint32_t vertices_ = 0;
  std::uint64_t triangles_ = 0;
  std::uint64_t bytes_ = 0;
};

// A box as a conforming grid on its six sides: the lattice points (i, j, k) of the surface get
// one vertex each, so neighbouring cells and sides share edges (2-manifold, closed). Normals
// point outwards.
void write_box(ObjWriter& w, const Part& p, std::vector<std::uint32_t>& lattice) {
  const std::uint32_t nx = p.nx, ny = p.ny, nz = p.nz;
  const std::size_t sx = nx + 1, sy = ny + 1;
  lattice.assign(sx * sy * (nz + 1), 0);
  auto at = [&](std::uint32_t i, std::uint32_t j, std::uint32_t k) -> std::uint32_t& {
    return lattice[(std::size_t{k} * sy + j) * sx + i];
  };
  auto coord = [](double a, double b, std::uint32_t i, std::uint32_t n) {
    return i == n ? b : a + (b - a) * static_cast<double>(i) / static_cast<double>(n);
  };
  for (std::uint32_t k = 0; k <= nz; ++k)
    for (std::uint32_t j = 0; j <= ny; ++j)
      for (std::uint32_t i = 0; i <= nx; ++i) {
        const bool surface = i == 0 || i == nx || j == 0 || j == ny || k == 0 || k == nz;
        if (!surface) continue;
        at(i, j, k) = w.vertex(coord(p.x0, p.x1, i, nx), coord(p.y0, p.y1, j, ny),
                               coord(p.z0, p.z1, k, nz));
      }
  w.use(p.roof);
  for (std::uint32_t j = 0; j < ny; ++j)  // bottom, normal -z
    for (std::uint32_t i = 0; i < nx; ++i)
      w.quad(at(i, j, 0), at(i, j + 1, 0), at(i + 1, j + 1, 0), at(i + 1, j, 0));
  for (std::uint32_t j = 0; j < ny; ++j)  // roof, normal +z
    for (std::uint32_t i = 0; i < nx; ++i)
      w.quad(at(i, j, nz), at(i + 1, j, nz), at(i + 1, j + 1, nz), at(i, j + 1, nz));
  w.use(p.walls);
  for (std::uint32_t k = 0; k < nz; ++k) {
    for (std::uint32_t i = 0; i < nx; ++i) {
      w.quad(at(i, 0, k), at(i + 1, 0, k), at(i + 1, 0, k + 1), at(i, 0, k + 1));  // south, -y
      w.quad(at(i, ny, k), at(i, ny, k + 1), at(i + 1, ny, k + 1), at(i + 1, ny, k));  // north
    }
    for (std::uint32_t j = 0; j < ny; ++j) {
      w.quad(at(0, j, k), at(0, j, k + 1), at(0, j + 1, k + 1), at(0, j + 1, k));  // west, -x
      w.quad(at(nx, j, k), at(nx, j + 1, k), at(nx, j + 1, k + 1), at(nx, j, k + 1));  // east
    }
  }
}

void write_sheet(ObjWriter& w, const Part& p) {
  const std::uint32_t a = w.vertex(p.x0, p.y0, p.z0);
  const std::uint32_t b = w.vertex(p.x1, p.y0, p.z0);
  const std::uint32_t c = w.vertex(p.x1, p.y1, p.z0);
  const std::uint32_t d = w.vertex(p.x0, p.y1, p.z0);
  w.use(p.walls);
  w.quad(a, b, c, d);  // normal +z
}

double positive_option(const std::optional<double>& v, double fallback, const char* name,
                       bool allow_zero = false) {
  const double x = v.value_or(fallback);
  if (!std::isfinite(x) || x < 0.0 || (x == 0.0 && !allow_zero))
    throw InputError(name, fmt::format("must be {} (got {})",
                                       allow_zero ? "zero or more" : "positive", x));
  return x;
}

// Heights of --building-height-m: "30", "20,35,50" (cycled) or "20:50" (uniform, drawn).
struct HeightSpec {
  std::vector<double> list;
  bool range = false;
};

HeightSpec parse_heights(const std::string& text) {
  HeightSpec spec;
  const std::size_t colon = text.find(':');
  if (colon != std::string::npos) {
    if (text.find(':', colon + 1) != std::string::npos)
      throw InputError("--building-height-m", fmt::format("expected MIN:MAX, got '{}'", text));
    const std::vector<double> v =
        parse_numbers(text.substr(0, colon) + "," + text.substr(colon + 1), "--building-height-m",
                      {"MIN", "MAX"}, "MIN:MAX");
    if (v[0] <= 0.0 || v[1] < v[0])
      throw InputError("--building-height-m",
                       fmt::format("range {} needs 0 < MIN <= MAX", text));
    spec.list = v;
    spec.range = true;
    return spec;
  }
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    const std::string item = text.substr(start, comma == std::string::npos ? comma : comma - start);
    const std::vector<double> v = parse_numbers(item, "--building-height-m", {"H"}, "H, H1,H2,... or MIN:MAX");
    if (v[0] <= 0.0)
      throw InputError("--building-height-m", fmt::format("heights must be positive (got {})", v[0]));
    spec.list.push_back(v[0]);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return spec;
}

std::string num(double v) { return fmt::format("{}", v); }

Plan plan_urban_canyon(const SceneOptions& o) {
  const double w = positive_option(o.street_width_m, 20.0, "--street-width-m");
  const double len = positive_option(o.length_m, 300.0, "--length-m");
  const double bl = positive_option(o.building_length_m, 48.0, "--building-length-m");
  const double depth = positive_option(o.building_depth_m, 20.0, "--building-depth-m");
  const double gap = positive_option(o.gap_m, 2.0, "--gap-m");
  const double glass = o.glass_fraction.value_or(0.5);
  if (!(glass >= 0.0 && glass <= 1.0))
    throw InputError("--glass-fraction", fmt::format("must be in [0, 1] (got {})", glass));
  const double cell = positive_option(o.facade_cell_m, 0.0, "--facade-cell-m", true);
  const std::string heights_text = o.building_height_m.value_or("30");
  const HeightSpec heights = parse_heights(heights_text);
  if (bl > len)
    throw InputError("--building-length-m",
                     fmt::format("{} m is longer than the street ({} m)", bl, len));

  const auto n = static_cast<int>(std::floor((len + gap) / (bl + gap) + 1e-9));
  const double span = n * bl + (n - 1) * gap;
  RandomStream rng(o.seed, stream_id("scene.urban-canyon"));
  Plan plan;
  int index = 0;
  for (const int side : {-1, 1}) {  // west, then east
    const double xa = side < 0 ? -w / 2 - depth : w / 2;
    for (int i = 0; i < n; ++i, ++index) {
      double h = heights.list[static_cast<std::size_t>(index) % heights.list.size()];
      if (heights.range) {
        h = heights.list[0] + (heights.list[1] - heights.list[0]) * rng.uniform();
        h = std::clamp(std::round(h * 2.0) / 2.0, heights.list[0], heights.list[1]);
      }
      const bool is_glass = rng.uniform() < glass;
      const double y0 = -span / 2 + i * (bl + gap);
      plan.parts.push_back(box(xa, xa + depth, y0, y0 + bl, 0.0, h, cell,
                               is_glass ? kGlass : kConcrete, kConcrete));
    }
  }
  plan.parts.push_back(sheet(-w / 2, w / 2, -len / 2, len / 2, kAsphalt));
  const double outer = w / 2 + depth + 10.0;
  plan.parts.push_back(sheet(-outer, -w / 2, -len / 2, len / 2, kGround));
  plan.parts.push_back(sheet(w / 2, outer, -len / 2, len / 2, kGround));
  plan.command = fmt::format(
      "navemu scene urban-canyon --street-width-m {} --length-m {} --building-height-m {} "
      "--building-length-m {} --building-depth-m {} --gap-m {} --glass-fraction {} "
      "--facade-cell-m {} --seed {}",
      num(w), num(len), heights_text, num(bl), num(depth), num(gap), num(glass), num(cell),
      o.seed);
  plan.description = fmt::format(
      "street along north (y), x in [{}, {}] m, y in [{}, {}] m; {} buildings per side", num(-w / 2),
      num(w / 2), num(-len / 2), num(len / 2), n);
  return plan;
}

Plan plan_open_field(const SceneOptions& o) {
  const double size = positive_option(o.size_m, 1000.0, "--size-m");
  Plan plan;
  plan.parts.push_back(sheet(-size / 2, size / 2, -size / 2, size / 2, kGround));
  plan.command = fmt::format("navemu scene open-field --size-m {}", num(size));
  plan.description = fmt::format("flat ground, {} m x {} m", num(size), num(size));
  return plan;
}

Plan plan_tree_rows(const SceneOptions& o) {
  const double w = positive_option(o.street_width_m, 10.0, "--street-width-m");
  const double len = positive_option(o.length_m, 300.0, "--length-m");
  const int rows = o.rows.value_or(2);
  if (rows < 1 || rows > 100)
    throw InputError("--rows", fmt::format("must be 1 to 100 (got {})", rows));
  const double spacing = positive_option(o.spacing_m, 10.0, "--spacing-m");
  const double top = positive_option(o.tree_height_m, 12.0, "--tree-height-m");
  const double crown = positive_option(o.crown_m, 6.0, "--crown-m");
  const double base = positive_option(o.crown_base_m, 3.0, "--crown-base-m", true);
  if (crown >= spacing)
    throw InputError("--crown-m", fmt::format("{} m must be less than --spacing-m ({} m) so that "
                                              "crowns do not touch",
                                              crown, spacing));
  if (base >= top)
    throw InputError("--crown-base-m", fmt::format("{} m must be below --tree-height-m ({} m)",
                                                   base, top));
  if (spacing > len)
    throw InputError("--spacing-m", fmt::format("{} m is longer than the road ({} m)", spacing, len));
  constexpr double kVerge = 1.0;  // road edge to the first row's crowns

  const auto per_row = static_cast<int>(std::floor(len / spacing + 1e-9));
  Plan plan;
  double outermost = w / 2;
  for (int r = 0; r < rows; ++r) {
    const double side = r % 2 == 0 ? 1.0 : -1.0;
    const double xc = side * (w / 2 + kVerge + crown / 2 + (r / 2) * spacing);
    outermost = std::max(outermost, std::abs(xc) + crown / 2);
    for (int j = 0; j < per_row; ++j) {
      const double yc = -(per_row - 1) * spacing / 2 + j * spacing;
      plan.parts.push_back(box(xc - crown / 2, xc + crown / 2, yc - crown / 2, yc + crown / 2,
                               base, top, 0.0, kFoliage, kFoliage));
    }
  }
  plan.parts.push_back(sheet(-w / 2, w / 2, -len / 2, len / 2, kAsphalt));
  const double outer = outermost + 5.0;
  plan.parts.push_back(sheet(-outer, -w / 2, -len / 2, len / 2, kGround));
  plan.parts.push_back(sheet(w / 2, outer, -len / 2, len / 2, kGround));
  plan.command = fmt::format(
      "navemu scene tree-rows --street-width-m {} --length-m {} --rows {} --spacing-m {} "
      "--tree-height-m {} --crown-m {} --crown-base-m {}",
      num(w), num(len), rows, num(spacing), num(top), num(crown), num(base));
  plan.description = fmt::format("road along north (y), x in [{}, {}] m; {} rows of {} trees",
                                 num(-w / 2), num(w / 2), rows, per_row);
  return plan;
}

Plan plan_city(const SceneOptions& o) {
  const double size = positive_option(o.size_m, 1000.0, "--size-m");
  const double block = positive_option(o.block_m, 100.0, "--block-m");
  const double street = positive_option(o.street_width_m, 20.0, "--street-width-m");
  const int lots = o.lots.value_or(2);
  if (lots < 1 || lots > 50)
    throw InputError("--lots", fmt::format("must be 1 to 50 (got {})", lots));
  const double alley = positive_option(o.alley_m, 4.0, "--alley-m");
  const double hmin = positive_option(o.min_height_m, 10.0, "--min-height-m");
  const double hmax = positive_option(o.max_height_m, 60.0, "--max-height-m");
  if (hmax < hmin)
    throw InputError("--max-height-m",
                     fmt::format("{} m is below --min-height-m ({} m)", hmax, hmin));
  const double cell = positive_option(o.facade_cell_m, 0.0, "--facade-cell-m", true);
  const double lot = (block - (lots - 1) * alley) / lots;
  if (lot <= 0.0)
    throw InputError("--lots", fmt::format("{} lots with {} m alleys do not fit in a {} m block",
                                           lots, alley, block));
  // Blocks at x = i * pitch + street / 2 (one street centred on x = 0, one on y = 0), wholly
  // inside [-size/2, size/2].
  const double pitch = block + street;
  const auto first = static_cast<int>(std::ceil((-size / 2 - street / 2) / pitch - 1e-9));
  const auto last = static_cast<int>(std::floor((size / 2 - street / 2 - block) / pitch + 1e-9));
  if (last < first)
    throw InputError("--size-m", fmt::format("{} m holds no {} m block", size, block));

  RandomStream rng(o.seed, stream_id("scene.city"));
  Plan plan;
  for (int by = first; by <= last; ++by)
    for (int bx = first; bx <= last; ++bx)
      for (int ly = 0; ly < lots; ++ly)
        for (int lx = 0; lx < lots; ++lx) {
          const double x0 = bx * pitch + street / 2 + lx * (lot + alley);
          const double y0 = by * pitch + street / 2 + ly * (lot + alley);
          double h = hmin + (hmax - hmin) * rng.uniform();
          h = std::clamp(std::round(h * 2.0) / 2.0, hmin, hmax);
          const double u = rng.uniform();
          const std::string_view walls =
              u < 0.45 ? kConcrete : u < 0.75 ? kGlass : u < 0.90 ? kBrick : kMetal;
          plan.parts.push_back(box(x0, x0 + lot, y0, y0 + lot, 0.0, h, cell, walls,
                                   walls == kMetal ? kMetal : kConcrete));
        }
  const std::size_t buildings = plan.parts.size();
  plan.parts.push_back(sheet(-size / 2, size / 2, -size / 2, size / 2, kAsphalt));
  plan.command = fmt::format(
      "navemu scene city --size-m {} --block-m {} --street-width-m {} --lots {} --alley-m {} "
      "--min-height-m {} --max-height-m {} --facade-cell-m {} --seed {}",
      num(size), num(block), num(street), lots, num(alley), num(hmin), num(hmax), num(cell),
      o.seed);
  const int per_side = last - first + 1;
  plan.description = fmt::format(
      "{} x {} blocks of {} m, {} buildings; streets centred on x = 0 and y = 0; ground "
      "x, y in [{}, {}] m",
      per_side, per_side, num(block), buildings, num(-size / 2), num(size / 2));
  return plan;
}

// The parameters each kind takes (--seed is accepted by all: it is ignored where nothing is
// drawn).
void check_applicable(const SceneOptions& o) {
  struct Use {
    const char* name;
    bool given;
    std::vector<std::string_view> kinds;
  };
  const std::vector<Use> uses = {
      {"--street-width-m", o.street_width_m.has_value(), {"urban-canyon", "tree-rows", "city"}},
      {"--length-m", o.length_m.has_value(), {"urban-canyon", "tree-rows"}},
      {"--building-height-m", o.building_height_m.has_value(), {"urban-canyon"}},
      {"--building-length-m", o.building_length_m.has_value(), {"urban-canyon"}},
      {"--building-depth-m", o.building_depth_m.has_value(), {"urban-canyon"}},
      {"--gap-m", o.gap_m.has_value(), {"urban-canyon"}},
      {"--glass-fraction", o.glass_fraction.has_value(), {"urban-canyon"}},
      {"--facade-cell-m", o.facade_cell_m.has_value(), {"urban-canyon", "city"}},
      {"--size-m", o.size_m.has_value(), {"open-field", "city"}},
      {"--block-m", o.block_m.has_value(), {"city"}},
      {"--lots", o.lots.has_value(), {"city"}},
      {"--alley-m", o.alley_m.has_value(), {"city"}},
      {"--min-height-m", o.min_height_m.has_value(), {"city"}},
      {"--max-height-m", o.max_height_m.has_value(), {"city"}},
      {"--rows", o.rows.has_value(), {"tree-rows"}},
      {"--tree-height-m", o.tree_height_m.has_value(), {"tree-rows"}},
      {"--spacing-m", o.spacing_m.has_value(), {"tree-rows"}},
      {"--crown-m", o.crown_m.has_value(), {"tree-rows"}},
      {"--crown-base-m", o.crown_base_m.has_value(), {"tree-rows"}},
  };
  for (const Use& u : uses) {
    if (!u.given || std::find(u.kinds.begin(), u.kinds.end(), o.kind) != u.kinds.end()) continue;
    std::string kinds;
    for (const std::string_view k : u.kinds) kinds += fmt::format("{}{}", kinds.empty() ? "" : ", ", k);
    throw InputError(u.name, fmt::format("does not apply to {} (only to {})", o.kind, kinds));
  }
}

}  // namespace

int run_scene(const SceneOptions& opt, std::ostream&, std::ostream& err) {
  const auto t0 = std::chrono::steady_clock::now();
  check_applicable(opt);
  Plan plan = opt.kind == "urban-canyon" ? plan_urban_canyon(opt)
              : opt.kind == "open-field" ? plan_open_field(opt)
              : opt.kind == "tree-rows"  ? plan_tree_rows(opt)
                                         : plan_city(opt);
  std::uint64_t triangles = 0, vertices = 0, boxes = 0;
  for (const Part& p : plan.parts) {
    triangles += p.triangles();
    vertices += p.vertices();
    boxes += p.sheet ? 0 : 1;
  }
  if (triangles > kMaxTriangles)
    throw InputError("--facade-cell-m",
                     fmt::format("the scene would have {} triangles (at most {}); use larger cells",
                                 triangles, kMaxTriangles));
  if (vertices >= 0xffffffffull)
    throw InputError("--facade-cell-m", "too many vertices for 32-bit indices");

  ObjWriter w(opt.out_file);
  w.text(fmt::format(
      "# navemu {} scene: {}\n"
      "# command: {}\n"
      "# {}\n"
      "# frame: local east-north-up, metres (x east, y north, z up), ground at z = 0\n"
      "# materials: usemtl names are keys of configs/scenes/materials.yaml (no .mtl file)\n"
      "# {} closed boxes, {} ground sheets, {} vertices, {} triangles (as {} quadrilaterals)\n",
      NAVEMU_VERSION, opt.kind, plan.command, plan.description, boxes, plan.parts.size() - boxes,
      vertices, triangles, triangles / 2));

  const bool progress = triangles >= kProgressTriangles;
  std::uint64_t next_tenth = 1;  // report at 10 %, 20 %, ... 90 %
  std::vector<std::uint32_t> lattice;
  std::size_t n_boxes = 0, n_sheets = 0;
  for (const Part& p : plan.parts) {
    if (p.sheet) {
      w.object("ground", ++n_sheets);
      write_sheet(w, p);
    } else {
      w.object(opt.kind == "tree-rows" ? "tree" : "building", ++n_boxes);
      write_box(w, p, lattice);
    }
    if (progress && next_tenth <= 9 && w.triangles() >= next_tenth * triangles / 10) {
      err << fmt::format("navemu scene: {}% ({} of {} triangles)\n",
                         100 * w.triangles() / triangles, w.triangles(), triangles);
      err.flush();
      while (next_tenth <= 9 && w.triangles() >= next_tenth * triangles / 10) ++next_tenth;
    }
  }
  w.finish();
  if (w.triangles() != triangles || w.vertices() != vertices)
    throw std::logic_error(fmt::format("scene: wrote {} vertices and {} triangles, planned {} and {}",
                                       w.vertices(), w.triangles(), vertices, triangles));
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  err << fmt::format(
      "navemu scene: {} written to {}: {} boxes, {} vertices, {} triangles, {:.1f} MB in {:.2f} s\n",
      opt.kind, opt.out_file, boxes, vertices, triangles, static_cast<double>(w.bytes()) / 1e6,
      seconds);
  return 0;
}

}  // namespace navemu
