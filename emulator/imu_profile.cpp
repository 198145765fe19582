#include "emulator/imu_profile.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <map>
#include <set>

#include "emulator/yaml_reader.hpp"
#include "core/errors.hpp"

#ifndef NAVEMU_CONFIG_DIR
#define NAVEMU_CONFIG_DIR "configs"
#endif

namespace navemu {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;            // rad per degree
constexpr double kDegPerHour = kDeg / 3600.0;   // rad/s per deg/h
constexpr double kStandardGravity = kStandardGravity_mps2;  // m/s^2 per g
constexpr double kRootHour = 60.0;              // sqrt(s) per sqrt(h)

// One accepted unit suffix of a key and the factor to SI (m/s^2, rad/s, s, Hz, rad).
struct Unit {
  const char* suffix;
  double to_si;
};

// Unit families. Densities: x/sqrt(Hz) = x sqrt(s); "per_rth" is x per sqrt(hour), as datasheets
// give ARW (deg/sqrt(h)) and VRW (m/s/sqrt(h)): 1 deg/sqrt(h) = (pi/180)/60 rad/s/sqrt(Hz).
const std::vector<Unit> kAccelUnits = {{"mps2", 1.0}, {"mg", 1e-3 * kStandardGravity},
                                       {"ug", 1e-6 * kStandardGravity}, {"g", kStandardGravity}};
const std::vector<Unit> kGyroUnits = {{"radps", 1.0}, {"dps", kDeg}, {"degph", kDegPerHour}};
const std::vector<Unit> kAccelDensityUnits = {{"mps2_per_rthz", 1.0},
                                              {"ug_per_rthz", 1e-6 * kStandardGravity},
                                              {"mps_per_rth", 1.0 / kRootHour}};
const std::vector<Unit> kGyroDensityUnits = {{"radps_per_rthz", 1.0},
                                             {"dps_per_rthz", kDeg},
                                             {"deg_per_rth", kDeg / kRootHour}};
// Random walk of the bias: x sqrt(Hz) = x / sqrt(s) (Kalibr's m/s^3/sqrt(Hz), rad/s^2/sqrt(Hz)).
const std::vector<Unit> kAccelRandomWalkUnits = {{"mps3_per_rthz", 1.0},
                                                 {"mps2_per_rth", 1.0 / kRootHour}};
const std::vector<Unit> kGyroRandomWalkUnits = {{"radps2_per_rthz", 1.0},
                                                {"degph_per_rth", kDegPerHour / kRootHour}};
const std::vector<Unit> kAngleUnits = {{"rad", 1.0}, {"mrad", 1e-3}, {"deg", kDeg}};
const std::vector<Unit> kTimeUnits = {{"s", 1.0}, {"ms", 1e-3}};
const std::vector<Unit> kRateUnits = {{"hz", 1.0}};
const std::vector<Unit> kPpmUnits = {{"ppm", 1.0}, {"percent", 1e4}};
const std::vector<Unit> kPpmPerCUnits = {{"ppm_per_c", 1.0}};

enum class Sign { kAny, kNonNegative, kPositive };

struct Field {
  std::string base;  // the key without its unit suffix
  const std::vector<Unit>* units;
  Sign sign = Sign::kNonNegative;
  bool required = false;
  bool vector = false;  // [x, y, z]
  std::function<void(double)> set_scalar;
  std::function<void(const Vec3&)> set_vector;
};

// The problem found in a file: "<file>:<line>: <key>: <problem>".
[[noreturn]] void fail(const std::filesystem::path& file, const YAML::Node& node,
                       const std::string& key, const std::string& problem) {
  const YAML::Mark m = node.Mark();
  throw InputError(file.string(), m.is_null() ? 0 : m.line + 1, key, problem);
}

double number(const std::filesystem::path& file, const YAML::Node& node, const std::string& key) {
  if (!node.IsScalar()) fail(file, node, key, "expected a number");
  double v = 0.0;
  try {
    v = node.as<double>();
  } catch (const YAML::Exception&) {
    fail(file, node, key, fmt::format("'{}' is not a number", node.Scalar()));
  }
  if (!std::isfinite(v)) fail(file, node, key, fmt::format("'{}' is not finite", node.Scalar()));
  return v;
}

void check_sign(const std::filesystem::path& file, const YAML::Node& node, const std::string& key,
                Sign sign, double v) {
  if (sign == Sign::kNonNegative && v < 0.0)
    fail(file, node, key, fmt::format("must not be negative (got {})", node.Scalar()));
  if (sign == Sign::kPositive && v <= 0.0)
    fail(file, node, key, fmt::format("must be positive (got {})", node.Scalar()));
}

void add_scalar(std::vector<Field>& f, std::string base, const std::vector<Unit>& units,
                double* target, Sign sign = Sign::kNonNegative, bool required = false) {
  Field x;
  x.base = std::move(base);
  x.units = &units;
  x.sign = sign;
  x.required = required;
  x.set_scalar = [target](double v) { *target = v; };
  f.push_back(std::move(x));
}

void add_vector(std::vector<Field>& f, std::string base, const std::vector<Unit>& units,
                Vec3* target, Sign sign = Sign::kAny) {
  Field x;
  x.base = std::move(base);
  x.units = &units;
  x.sign = sign;
  x.vector = true;
  x.set_vector = [target](const Vec3& v) { *target = v; };
  f.push_back(std::move(x));
}

// Keys shared by both models.
void common_fields(std::vector<Field>& f, ImuParams& p) {
  add_scalar(f, "output_rate", kRateUnits, &p.output_rate_hz, Sign::kPositive, true);
  add_scalar(f, "internal_rate", kRateUnits, &p.internal_rate_hz, Sign::kPositive);
  add_scalar(f, "bandwidth", kRateUnits, &p.bandwidth_hz);
  add_scalar(f, "latency", kTimeUnits, &p.latency_s);
}

// One triad of the datasheet model; `prefix` "accel" or "gyro".
void sensor_fields(std::vector<Field>& f, const std::string& prefix, ImuSensorParams& s) {
  const bool gyro = prefix == "gyro";
  const auto& unit = gyro ? kGyroUnits : kAccelUnits;
  const std::string p = prefix + "_";
  add_scalar(f, p + "white_density", gyro ? kGyroDensityUnits : kAccelDensityUnits,
             &s.white_density, Sign::kNonNegative, true);
  add_scalar(f, p + "bias_instability", unit, &s.bias_instability);
  add_scalar(f, p + "bias_instability_tau", kTimeUnits, &s.bias_instability_tau_s,
             Sign::kPositive);
  add_scalar(f, p + "random_walk", gyro ? kGyroRandomWalkUnits : kAccelRandomWalkUnits,
             &s.random_walk);
  add_scalar(f, p + "turn_on_bias_sigma", unit, &s.turn_on_bias_sigma);
  add_vector(f, p + "null_offset", unit, &s.null_offset);
  add_scalar(f, p + "scale_factor_sigma", kPpmUnits, &s.scale_factor_sigma_ppm);
  add_scalar(f, p + "nonlinearity", kPpmUnits, &s.nonlinearity_ppm);
  add_scalar(f, p + "misalignment_sigma", kAngleUnits, &s.misalignment_sigma_rad);
  if (gyro) {
    static const std::vector<Unit> g_sens = {{"radps_per_mps2", 1.0},
                                             {"dps_per_g", kDeg / kStandardGravity},
                                             {"degph_per_g", kDegPerHour / kStandardGravity}};
    add_scalar(f, p + "g_sensitivity", g_sens, &s.g_sensitivity, Sign::kAny);
  }
  static const std::vector<Unit> accel_tc = {{"mps2_per_c", 1.0},
                                             {"mg_per_c", 1e-3 * kStandardGravity}};
  static const std::vector<Unit> gyro_tc = {{"radps_per_c", 1.0}, {"dps_per_c", kDeg},
                                            {"degph_per_c", kDegPerHour}};
  add_scalar(f, p + "bias_temp_coeff", gyro ? gyro_tc : accel_tc, &s.bias_temp_coeff_per_c,
             Sign::kAny);
  add_scalar(f, p + "scale_temp_coeff", kPpmPerCUnits, &s.scale_temp_coeff_ppm_per_c, Sign::kAny);
  add_scalar(f, p + "full_scale", unit, &s.full_scale);
  add_scalar(f, p + "resolution", unit, &s.resolution);
  // Per-axis multipliers of the noise terms: [x, y, z], no unit, each > 0.
  static const std::vector<Unit> factor = {{"", 1.0}};
  add_vector(f, p + "white_density_axis_scale", factor, &s.white_axis_scale, Sign::kPositive);
  add_vector(f, p + "bias_instability_axis_scale", factor, &s.bias_axis_scale, Sign::kPositive);
  add_vector(f, p + "random_walk_axis_scale", factor, &s.random_walk_axis_scale,
             Sign::kPositive);
}

// The paper's parameterisation (section 2.2 and 3).
void paper_fields(std::vector<Field>& f, PaperImuParams& q) {
  static const std::vector<Unit> kelvin = {{"k", 1.0}};
  static const std::vector<Unit> radps = {{"radps", 1.0}, {"hz", 2.0 * kPi}};
  static const std::vector<Unit> kg = {{"kg", 1.0}};
  static const std::vector<Unit> n_per_m = {{"n_per_m", 1.0}};
  static const std::vector<Unit> ohm = {{"ohm", 1.0}};
  static const std::vector<Unit> none = {{"", 1.0}};
  static const std::vector<Unit> hours = {{"h", 1.0}, {"s", 1.0 / 3600.0}};
  add_scalar(f, "temperature", kelvin, &q.temperature_k, Sign::kPositive);
  add_scalar(f, "accel_omega0", radps, &q.accel_omega0_radps, Sign::kPositive);
  add_scalar(f, "accel_proof_mass", kg, &q.accel_proof_mass_kg, Sign::kPositive);
  add_scalar(f, "gyro_spring_constant", n_per_m, &q.gyro_k, Sign::kPositive);
  add_scalar(f, "gyro_damping_resistance", ohm, &q.gyro_r_ohm);
  add_scalar(f, "gyro_noise_bandwidth", kRateUnits, &q.gyro_bandwidth_hz, Sign::kPositive);
  add_scalar(f, "quality_factor", none, &q.quality_factor, Sign::kPositive, true);
  add_scalar(f, "quantization_run_time", hours, &q.run_time_h, Sign::kPositive);
  add_scalar(f, "gm_correlation_time", kTimeUnits, &q.tau_s, Sign::kPositive, true);
  add_scalar(f, "accel_white_noise", kAccelUnits, &q.accel_white_noise, Sign::kNonNegative, true);
  // The paper states the gyroscope coefficient in deg/s; PaperImuParams keeps it in deg/s.
  static const std::vector<Unit> gyro_dps = {{"dps", 1.0}, {"radps", 1.0 / kDeg}};
  add_scalar(f, "gyro_white_noise", gyro_dps, &q.gyro_white_noise, Sign::kNonNegative, true);
  add_vector(f, "accel_null_offset", kAccelUnits, &q.accel_null_offset);
  add_vector(f, "gyro_null_offset", kGyroUnits, &q.gyro_null_offset);
  add_scalar(f, "accel_gm_sigma", kAccelUnits, &q.accel_gm_sigma);
  add_scalar(f, "gyro_gm_sigma", kGyroUnits, &q.gyro_gm_sigma);
}

std::string key_of(const Field& f, const Unit& u) {
  return std::string(u.suffix).empty() ? f.base : f.base + "_" + u.suffix;
}

std::string suffix_list(const Field& f) {
  std::string s;
  for (const Unit& u : *f.units) s += (s.empty() ? "" : ", ") + key_of(f, u);
  return s;
}

}  // namespace

std::filesystem::path config_dir() {
  const char* env = std::getenv("NAVEMU_CONFIG_DIR");
  return env != nullptr && *env != '\0' ? std::filesystem::path(env)
                                        : std::filesystem::path(NAVEMU_CONFIG_DIR);
}

std::vector<std::string> available_imu_profiles() {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(config_dir() / "imu", ec))
    if (e.is_regular_file() && e.path().extension() == ".yaml")
      names.push_back(e.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

ImuProfile load_imu_profile_file(const std::filesystem::path& file) {
  const YAML::Node root = parse_yaml_file(file, "IMU profile");
  if (!root.IsMap()) fail(file, root, "", "expected a mapping of keys to values");

  ImuProfile prof;
  prof.file = file;
  prof.name = file.stem().string();
  prof.params.name = prof.name;

  const YAML::Node model = root["model"];
  if (!model) fail(file, root, "model", "missing required key (datasheet or paper)");
  if (!model.IsScalar() || (model.Scalar() != "datasheet" && model.Scalar() != "paper"))
    fail(file, model, "model", "must be 'datasheet' or 'paper'");
  prof.model = model.Scalar();

  std::vector<Field> fields;
  common_fields(fields, prof.params);
  if (prof.model == "datasheet") {
    static const std::vector<Unit> celsius = {{"c", 1.0}};
    add_scalar(fields, "reference_temperature", celsius, &prof.params.reference_temperature_c,
               Sign::kAny);
    sensor_fields(fields, "accel", prof.params.accel);
    sensor_fields(fields, "gyro", prof.params.gyro);
  } else {
    paper_fields(fields, prof.paper);
  }

  static const std::set<std::string> kText = {"model", "name", "description", "source", "notes"};
  std::set<std::string> seen_bases;
  for (const auto& kv : root) {
    const auto key = kv.first.as<std::string>();
    const YAML::Node& value = kv.second;
    if (kText.count(key) != 0) {
      if (!value.IsScalar()) fail(file, value, key, "expected text");
      if (key == "description") prof.description = value.Scalar();
      continue;
    }
    const Field* match = nullptr;
    const Unit* unit = nullptr;
    for (const Field& f : fields)
      for (const Unit& u : *f.units)
        if (key == key_of(f, u)) {
          match = &f;
          unit = &u;
        }
    if (match == nullptr) {
      for (const Field& f : fields)
        if (key.rfind(f.base + "_", 0) == 0 || key == f.base)
          fail(file, kv.first, key, "unknown unit; use one of " + suffix_list(f));
      fail(file, kv.first, key, fmt::format("unknown key for a '{}' profile", prof.model));
    }
    if (!seen_bases.insert(match->base).second)
      fail(file, kv.first, key, "given twice (in different units)");
    if (match->vector) {
      if (!value.IsSequence() || value.size() != 3)
        fail(file, value, key, "expected [x, y, z]");
      Vec3 v;
      for (std::size_t i = 0; i < 3; ++i) {
        const double x = number(file, value[i], key);
        check_sign(file, value[i], key, match->sign, x);
        v[static_cast<Eigen::Index>(i)] = x * unit->to_si;
      }
      match->set_vector(v);
    } else {
      const double v = number(file, value, key);
      check_sign(file, value, key, match->sign, v);
      match->set_scalar(v * unit->to_si);
    }
    if (match->base == "internal_rate") prof.internal_rate_given = true;
    if (match->base == "quantization_run_time") prof.paper_run_time_given = true;
  }
  for (const Field& f : fields)
    if (f.required && seen_bases.count(f.base) == 0)
      fail(file, root, key_of(f, f.units->front()),
           "missing required key");

  // Consistency of the rates: a whole number of internal samples per output sample, and a
  // filter below the internal Nyquist frequency.
  ImuParams& p = prof.params;
  if (!prof.internal_rate_given) p.internal_rate_hz = p.output_rate_hz;
  const double k = p.internal_rate_hz / p.output_rate_hz;
  if (k < 1.0 - 1e-9 || std::abs(k - std::round(k)) > 1e-6) {
    const YAML::Node at = root["internal_rate_hz"] ? root["internal_rate_hz"] : root;
    fail(file, at, "internal_rate_hz", "must be a whole multiple of output_rate_hz");
  }
  if (p.bandwidth_hz >= 0.5 * p.internal_rate_hz) {
    const YAML::Node at = root["bandwidth_hz"];
    fail(file, at, "bandwidth_hz", "must be below half the internal rate");
  }
  return prof;
}

ImuProfile load_imu_profile(const std::string& name_or_path) {
  const bool is_path = name_or_path.find('/') != std::string::npos ||
                       (name_or_path.size() > 5 &&
                        name_or_path.compare(name_or_path.size() - 5, 5, ".yaml") == 0);
  if (is_path) return load_imu_profile_file(name_or_path);
  const auto file = config_dir() / "imu" / (name_or_path + ".yaml");
  if (!std::filesystem::is_regular_file(file)) {
    std::string list;
    for (const std::string& n : available_imu_profiles()) list += (list.empty() ? "" : ", ") + n;
    throw InputError("--profile", fmt::format("unknown IMU profile '{}' (available: {})",
                                              name_or_path, list.empty() ? "none found" : list));
  }
  return load_imu_profile_file(file);
}

ImuParams imu_params_for_run(const ImuProfile& profile, double duration_s,
                             double output_rate_hz) {
  ImuParams p = profile.params;
  const double rate = output_rate_hz > 0.0 ? output_rate_hz : p.output_rate_hz;
  if (profile.model == "paper") {
    // The paper's noise coefficients are per time step, at the rate the run uses.
    PaperImuParams q = profile.paper;
    if (!profile.paper_run_time_given && duration_s > 0.0) q.run_time_h = duration_s / 3600.0;
    p = imu_params_from_paper(q, rate);
    p.output_rate_hz = profile.params.output_rate_hz;
    p.internal_rate_hz = profile.params.internal_rate_hz;
    p.bandwidth_hz = profile.params.bandwidth_hz;
    p.latency_s = profile.params.latency_s;
  }
  p.name = profile.name;
  if (output_rate_hz > 0.0) {
    const double k = std::max(1.0, std::ceil(p.internal_rate_hz / output_rate_hz - 1e-9));
    p.output_rate_hz = output_rate_hz;
    p.internal_rate_hz = k * output_rate_hz;
    if (p.bandwidth_hz >= 0.5 * p.internal_rate_hz) p.bandwidth_hz = 0.0;
  }
  return p;
}

}  // namespace navemu
