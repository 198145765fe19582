// navemu imu: offline samples of a MEMS IMU profile (configs/imu/) for a given truth, as CSV.

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <optional>
#include <ostream>

#include "emulator/commands.hpp"
#include "emulator/imu_channel.hpp"
#include "emulator/imu_profile.hpp"
#include "emulator/truth_source.hpp"
#include "emulator/truth_csv.hpp"
#include "core/errors.hpp"
#include "models/imu_kinematics.hpp"
#include "models/imu_model.hpp"

namespace navemu {

struct ImuOptions {
  std::string profile;
  std::optional<double> duration_s;  // required with --truth static; a truth file's span else
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
      "time_s counts from the start of the run (in a truth file's own time base) and includes\n"
      "the profile's latency. Body frame x forward, y right, z down: a level IMU at rest senses\n"
      "f = (0, 0, -g) and the Earth rate projected on its axes.\n"
      "--truth static: level, facing north, at rest at --at.\n"
      "--truth FILE: a truth CSV (--at ignored), header row then one row per sample, any rate,\n"
      "time strictly increasing, at least 3 rows; columns, in any order (others ignored):\n"
      "  time_s,lat_deg,lon_deg,h_m,v_n_mps,v_e_mps,v_d_mps,roll_deg,pitch_deg,yaw_deg\n"
      "  [f_x_mps2,f_y_mps2,f_z_mps2,w_x_radps,w_y_radps,w_z_radps] [temperature_c]\n"
      "(WGS-84 position, NED velocity, ZYX Euler angles of the FRD body; the optional six are\n"
      "the simulator's own body specific force and angular rate, all six or none). The truth is\n"
      "interpolated to the internal-rate instants: position and velocity by cubic Hermite,\n"
      "attitude by quaternion slerp, f, w and temperature linearly. Without f/w columns the\n"
      "ideal output comes from the kinematics at the instants +-1/internal rate around each\n"
      "(exact for constant body rate and velocity, e.g. circles at constant speed). The run\n"
      "covers the file's span (--duration may shorten it).\n"
      "The same --seed gives a byte-identical file.\n"
      "Examples:\n"
      "  navemu imu --profile bmi160 --duration 600 --out bmi160.csv --seed 7\n"
      "  navemu imu --profile bmi160 --truth configs/truth/circle_paper.csv --out circle.csv");
  imu->add_option("--profile", opt->profile, "IMU profile name (configs/imu/NAME.yaml) or file")
      ->required();
  imu->add_option("--duration", opt->duration_s,
                  "Length of the run in seconds (with --truth FILE: at most, and by default, the "
                  "file's span)");
  imu->add_option("--rate", opt->rate_hz, "Output rate in Hz (default: the profile's)");
  imu->add_option("--truth", opt->truth,
                  "Truth: static (level, north-facing, at rest) or a truth CSV file")
      ->capture_default_str();
  imu->add_option("--at", opt->at, "Position LAT,LON,H (deg, deg, m above the WGS-84 ellipsoid)")
      ->capture_default_str();
  imu->add_option("--seed", opt->seed, "Seed of every random error term")->capture_default_str();
  imu->add_option("--out", opt->out_file, "Output CSV file")->required();
  return opt;
}

namespace {

// A truth CSV file as a truth source, streaming (TruthTrack): the truth at the file's instants,
// none outside its span. Queries must come at non-decreasing times, as the IMU's rolling window
// asks them (emulator/imu_channel.hpp).
class TrackSource final : public TruthSource {
 public:
  TrackSource(const std::string& path, const TruthCsvSummary& summary)
      : track_(path), summary_(summary), t0_(GpsTime::from_seconds(summary.first_time_s)) {}
  std::optional<ImuTruth> at(GpsTime t) override {
    const double s = summary_.first_time_s + seconds_between(t, t0_);
    if (t < t0_ || s > summary_.last_time_s + 1e-9) return std::nullopt;
    ImuTruth truth = track_.at(s);
    truth.t = t;
    return truth;
  }
  std::string describe() const override { return "truth CSV"; }
  GpsTime first() const { return t0_; }

 private:
  TruthTrack track_;
  TruthCsvSummary summary_;
  GpsTime t0_;
};

// The IMU's signal path (emulator/imu_channel.hpp, as in `navemu run`) over `steps` internal
// instants from `t0`, one CSV row per output sample.
struct RunCounts {
  std::int64_t rows = 0, saturated = 0;
};
RunCounts write_samples(const ImuParams& params, std::uint64_t seed, GpsTime t0, std::int64_t steps,
                        TruthSource& truth, const IdealImu& initial, const std::string& out_file) {
  std::ofstream out(out_file, std::ios::binary);
  if (!out) throw InputError(out_file, 0, "--out", "cannot open for writing");
  ImuPipeline pipe(params, seed, t0, initial);
  fmt::memory_buffer buf;
  fmt::format_to(std::back_inserter(buf),
                 "time_s,f_x_mps2,f_y_mps2,f_z_mps2,w_x_radps,w_y_radps,w_z_radps,temperature_c\n");
  RunCounts counts;
  ImuSample s;
  bool valid = true;
  for (std::int64_t n = 0; n < steps; ++n) {
    if (!pipe.run_to(n, truth, s, valid)) continue;
    fmt::format_to(std::back_inserter(buf), "{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g}\n",
                   seconds_between(s.t, GpsTime{0}), s.f_body_mps2.x(), s.f_body_mps2.y(),
                   s.f_body_mps2.z(), s.w_body_radps.x(), s.w_body_radps.y(), s.w_body_radps.z(),
                   s.temperature_c);
    ++counts.rows;
    if (s.saturated) ++counts.saturated;
    if (buf.size() > (1u << 16)) {
      out.write(buf.data(), static_cast<std::streamsize>(buf.size()));
      buf.clear();
    }
  }
  out.write(buf.data(), static_cast<std::streamsize>(buf.size()));
  out.close();
  if (!out) throw InputError(out_file, 0, "--out", "write failed");
  return counts;
}

ImuParams run_params(const ImuOptions& opt, double duration_s, std::string& profile_name) {
  const ImuProfile profile = load_imu_profile(opt.profile);
  profile_name = profile.name;
  const ImuParams params = imu_params_for_run(profile, duration_s, opt.rate_hz);
  if (std::fabs(std::round(params.internal_rate_hz / params.output_rate_hz) * params.output_rate_hz -
                params.internal_rate_hz) > 1e-9 * params.internal_rate_hz)
    throw InputError(profile.file.string(), 0, "internal_rate_hz", "must be a whole multiple of output_rate_hz");
  return params;
}

}  // namespace

int run_imu(const ImuOptions& opt, std::ostream&, std::ostream& err) {
  if (opt.duration_s && (!std::isfinite(*opt.duration_s) || *opt.duration_s <= 0.0))
    throw InputError("--duration", fmt::format("must be positive (got {})", *opt.duration_s));
  if (!std::isfinite(opt.rate_hz) || opt.rate_hz < 0.0)
    throw InputError("--rate", fmt::format("must be positive (got {})", opt.rate_hz));

  RunCounts counts;
  ImuParams params;
  std::string profile_name, truth_note;
  if (opt.truth == "static") {
    if (!opt.duration_s) throw InputError("--duration", "required with --truth static");
    TruthSpec spec;
    spec.kind = TruthSourceKind::kStationary;
    spec.position = parse_geodetic(opt.at, "--at");
    params = run_params(opt, *opt.duration_s, profile_name);
    const std::unique_ptr<TruthSource> truth = make_truth_source(spec, GpsTime{0}, GpsTime{0});
    const auto steps = static_cast<std::int64_t>(std::llround(*opt.duration_s * params.internal_rate_hz));
    counts = write_samples(params, opt.seed, GpsTime{0}, steps, *truth,
                           ideal_imu_static(spec.position, Quat::Identity()), opt.out_file);
  } else {
    // A first pass checks the whole file (so that a bad row fails before any output) and gives
    // its span; the second streams it through the interpolator.
    const TruthCsvSummary summary = scan_truth_csv(opt.truth);
    const double span_s = summary.last_time_s - summary.first_time_s;
    if (opt.duration_s && *opt.duration_s > span_s * (1.0 + 1e-12))
      throw InputError("--duration",
                       fmt::format("{} s is longer than the truth file's span ({} s, {} to {} s)",
                                   *opt.duration_s, span_s, summary.first_time_s,
                                   summary.last_time_s));
    const double duration_s = opt.duration_s.value_or(span_s);
    params = run_params(opt, duration_s, profile_name);
    const double rate = params.internal_rate_hz;
    // Instants t0 + n / rate, all inside the span.
    const auto inside = static_cast<std::int64_t>(std::floor(span_s * rate + 1e-9));
    const std::int64_t steps =
        opt.duration_s ? std::min(static_cast<std::int64_t>(std::llround(duration_s * rate)), inside) : inside;
    if (steps < 1)
      throw InputError(opt.truth, 0, "time_s",
                       fmt::format("the span ({} s) holds no instant at {} Hz", span_s, rate));
    TrackSource truth(opt.truth, summary);
    counts = write_samples(params, opt.seed, truth.first(), steps, truth, IdealImu{}, opt.out_file);
    truth_note = fmt::format(", truth {} ({} s of {} s)", opt.truth, static_cast<double>(steps) / rate, span_s);
  }

  err << fmt::format("navemu imu: {} samples written to {} (profile {}, {} Hz output, {} Hz "
                     "internal, seed {}{}{})\n",
                     counts.rows, opt.out_file, profile_name, params.output_rate_hz,
                     params.internal_rate_hz, opt.seed, truth_note,
                     counts.saturated > 0 ? fmt::format(", {} saturated", counts.saturated) : "");
  return 0;
}

}  // namespace navemu
