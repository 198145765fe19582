#pragma once
// IMU profiles: YAML files in configs/imu/ (units in every key name) loaded, validated and
// converted to SI once into the model's plain parameter structs (models/imu_model.hpp).
//
// A profile is a flat YAML mapping. Text keys: model (required: datasheet or paper), name,
// description, source, notes. Every numeric key ends in its unit; the accepted suffixes are
// listed after each key (SI first).
//
// Both models:
//   output_rate_hz (required), internal_rate_hz (default: the output rate; a whole multiple of
//   it), bandwidth_hz (output first-order low-pass; 0 or absent: none), latency_s | _ms.
// model: datasheet (IEEE Std 952 style; prefix accel_ or gyro_, "U" the sensor's unit:
//   accel mps2 | mg | ug | g, gyro radps | dps | degph):
//   white_density (required): accel mps2_per_rthz | ug_per_rthz | mps_per_rth (VRW),
//                             gyro radps_per_rthz | dps_per_rthz | deg_per_rth (ARW);
//   bias_instability_U (IEEE B: the Allan floor is 0.664 B), bias_instability_tau_s;
//   random_walk: accel mps3_per_rthz | mps2_per_rth, gyro radps2_per_rthz | degph_per_rth;
//   turn_on_bias_sigma_U, null_offset_U ([x, y, z]), scale_factor_sigma_ppm | _percent,
//   nonlinearity_ppm | _percent (of full scale), misalignment_sigma_rad | _mrad | _deg,
//   bias_temp_coeff: accel mps2_per_c | mg_per_c, gyro radps_per_c | dps_per_c | degph_per_c;
//   scale_temp_coeff_ppm_per_c, full_scale_U, resolution_U,
//   gyro_g_sensitivity_radps_per_mps2 | _dps_per_g | _degph_per_g; reference_temperature_c;
//   per-axis multipliers (no unit; [x, y, z] of positive numbers, default [1, 1, 1]) of the
//   noise terms: white_density_axis_scale, bias_instability_axis_scale,
//   random_walk_axis_scale (axis i gets e.g. white density white_density * scale[i]).
// model: paper (Durst & Goodin section 2.2 and 3; see imu_params_from_paper):
//   quality_factor, gm_correlation_time_s, accel_white_noise_mps2, gyro_white_noise_dps |
//   _radps (all required); temperature_k, accel_omega0_radps | _hz, accel_proof_mass_kg,
//   gyro_spring_constant_n_per_m, gyro_damping_resistance_ohm, gyro_noise_bandwidth_hz,
//   quantization_run_time_h | _s (default: the run's duration), accel_null_offset_U,
//   gyro_null_offset_U, accel_gm_sigma_U, gyro_gm_sigma_U.

#include <filesystem>
#include <string>
#include <vector>

#include "models/imu_model.hpp"

namespace navemu {

struct ImuProfile {
  std::string name;  // the file's stem
  std::filesystem::path file;
  std::string model;        // "datasheet" or "paper"
  std::string description;  // free text from the file
  // The model parameters. For a paper profile: the common keys (rates, bandwidth, latency);
  // the rest comes from `paper` through imu_params_for_run.
  ImuParams params;
  PaperImuParams paper;
  bool paper_run_time_given = false;    // quantization_run_time_h in the file
  bool internal_rate_given = false;     // internal_rate_hz in the file
};

// configs/ of the source tree (compile definition NAVEMU_CONFIG_DIR), or $NAVEMU_CONFIG_DIR.
std::filesystem::path config_dir();
// The profile names in config_dir()/imu, sorted.
std::vector<std::string> available_imu_profiles();

// Loads and validates one YAML file; navemu::InputError "<file>:<line>: <key>: <problem>" on a
// bad file (unknown key, missing required key, non-numeric, NaN/inf, negative sigma or tau, ...).
ImuProfile load_imu_profile_file(const std::filesystem::path& file);
// A profile by name (config_dir()/imu/<name>.yaml) or by path (contains '/' or ends in .yaml);
// an unknown name gives an InputError listing the available profiles.
ImuProfile load_imu_profile(const std::string& name_or_path);

// The parameters for a run of `duration_s` seconds: a datasheet profile's as they are; a paper
// profile's mapped by imu_params_from_paper, with the quantization run time = the run's duration
// unless the file fixes it. `output_rate_hz` > 0 overrides the profile's output rate (the
// internal rate then becomes the nearest multiple of it not below the profile's internal rate).
ImuParams imu_params_for_run(const ImuProfile& profile, double duration_s,
                             double output_rate_hz = 0.0);

}  // namespace navemu
