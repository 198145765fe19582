// navemu imu: offline samples of a MEMS IMU profile (configs/imu/) for a given truth, as CSV.

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <ostream>

#include "emulator/commands.hpp"
#include "emulator/imu_profile.hpp"
#include "models/errors.hpp"
#include "models/imu_kinematics.hpp"
#include "models/imu_model.hpp"

namespace navemu {

struct ImuOptions {
  std::string profile;
  double duration_s = 0.0;
  double rate_hz = 0.0;  // 0: the profile's output rate
  std::string truth = "static";
  std::string at = "32.3,-90.9,60";  // the paper's test site, Vicksburg, MS
  std::uint64_t seed = 1;
  std::string out_file;
};

std::shared_ptr<ImuOptions> add_imu_command(CLI::App& app) {
  auto opt = std::make_shared<ImuOptions>();
  CLI::App* imu = app.add_subcommand(
      "imu", "Offline MEMS IMU samples of a profile (noise, bias, scale, misalignment, ...)");
  imu->footer(
      "Runs the IMU error model of --profile (a name from configs/imu/ or a YAML file) at its\n"
      "internal rate for --duration seconds and writes one CSV row per output sample:\n"
      "  time_s,f_x_mps2,f_y_mps2,f_z_mps2,w_x_radps,w_y_radps,w_z_radps,temperature_c\n"
      "time_s counts from the start of the run and includes the profile's latency. Body frame\n"
      "x forward, y right, z down: a level IMU at rest senses f = (0, 0, -g) and the Earth rate\n"
      "projected on its axes. --truth static: level, facing north, at rest at --at.\n"
      "The same --seed gives a byte-identical file.\n"
      "Example:\n"
      "  navemu imu --profile bmi160 --duration 600 --out bmi160.csv --seed 7");
  imu->add_option("--profile", opt->profile, "IMU profile name (configs/imu/NAME.yaml) or file")
      ->required();
  imu->add_option("--duration", opt->duration_s, "Length of the run in seconds")->required();
  imu->add_option("--rate", opt->rate_hz, "Output rate in Hz (default: the profile's)");
  imu->add_option("--truth", opt->truth, "Truth: static (level, north-facing, at rest)")
      ->capture_default_str();
  imu->add_option("--at", opt->at, "Position LAT,LON,H (deg, deg, m above the WGS-84 ellipsoid)")
      ->capture_default_str();
  imu->add_option("--seed", opt->seed, "Seed of every random error term")->capture_default_str();
  imu->add_option("--out", opt->out_file, "Output CSV file")->required();
  return opt;
}

int run_imu(const ImuOptions& opt, std::ostream&, std::ostream& err) {
  if (!std::isfinite(opt.duration_s) || opt.duration_s <= 0.0)
    throw InputError("--duration", fmt::format("must be positive (got {})", opt.duration_s));
  if (!std::isfinite(opt.rate_hz) || opt.rate_hz < 0.0)
    throw InputError("--rate", fmt::format("must be positive (got {})", opt.rate_hz));
  if (opt.truth != "static")
    throw InputError("--truth", "only 'static' is supported (truth files are not yet read)");
  const Geodetic where = parse_geodetic(opt.at, "--at");
  const ImuProfile profile = load_imu_profile(opt.profile);
  const ImuParams params = imu_params_for_run(profile, opt.duration_s, opt.rate_hz);

  std::ofstream out(opt.out_file, std::ios::binary);
  if (!out) throw InputError(opt.out_file, 0, "--out", "cannot open for writing");

  ImuModel model(params, opt.seed);
  const IdealImu ideal = ideal_imu_static(where, Quat::Identity());
  const double temperature_c = params.reference_temperature_c;
  const auto steps = static_cast<std::int64_t>(std::llround(opt.duration_s * params.internal_rate_hz));
  const GpsTime t0{0};

  fmt::memory_buffer buf;
  fmt::format_to(std::back_inserter(buf),
                 "time_s,f_x_mps2,f_y_mps2,f_z_mps2,w_x_radps,w_y_radps,w_z_radps,temperature_c\n");
  std::int64_t rows = 0, saturated = 0;
  ImuSample s;
  for (std::int64_t n = 0; n < steps; ++n) {
    // Times from the sample index, rounded to the nanosecond, so that they do not drift.
    const GpsTime t{t0.ns + static_cast<std::int64_t>(std::llround(
                                static_cast<double>(n) * 1e9 / params.internal_rate_hz))};
    if (!model.step(t, ideal, temperature_c, s)) continue;
    fmt::format_to(std::back_inserter(buf), "{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g}\n",
                   seconds_between(s.t, t0), s.f_body_mps2.x(), s.f_body_mps2.y(),
                   s.f_body_mps2.z(), s.w_body_radps.x(), s.w_body_radps.y(), s.w_body_radps.z(),
                   s.temperature_c);
    ++rows;
    if (s.saturated) ++saturated;
    if (buf.size() > (1u << 16)) {
      out.write(buf.data(), static_cast<std::streamsize>(buf.size()));
      buf.clear();
    }
  }
  out.write(buf.data(), static_cast<std::streamsize>(buf.size()));
  out.close();
  if (!out) throw InputError(opt.out_file, 0, "--out", "write failed");

  err << fmt::format("navemu imu: {} samples written to {} (profile {}, {} Hz output, {} Hz "
                     "internal, seed {}{})\n",
                     rows, opt.out_file, profile.name, params.output_rate_hz,
                     params.internal_rate_hz, opt.seed,
                     saturated > 0 ? fmt::format(", {} saturated", saturated) : "");
  return 0;
}

}  // namespace navemu
