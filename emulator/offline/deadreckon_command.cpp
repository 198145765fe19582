// navemu deadreckon: strapdown dead reckoning of an IMU sample file (the paper's Fig. 3 and
// Fig. 7), with the error against a truth run and the per-axis gyro-only headings.

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "emulator/commands.hpp"
#include "emulator/numeric_csv.hpp"
#include "core/errors.hpp"
#include "models/geodesy.hpp"
#include "models/imu_kinematics.hpp"

namespace navemu {

struct DeadreckonOptions {
  std::string file;
  std::string truth;                 // empty: none; "static": stationary at the start
  std::string at = "32.3,-90.9,60";  // the paper's test site, Vicksburg, MS
  std::optional<double> start_lat_deg, start_lon_deg, start_h_m;
  std::string initial_rpy_deg = "0,0,0";
  double bias_removal_s = 0.0;       // 0: none
  std::optional<long long> every;    // output decimation; unset: one row per second
  std::string out_file = "-";        // "-": standard output
  bool gyro_only_heading = false;
};

namespace {

// ---------------------------------------------------------------------------------------------
// Reading the IMU CSV written by `navemu imu`.

struct ImuRow {
  double t_s = 0.0;
  Vec3 f_body_mps2 = Vec3::Zero();
  Vec3 w_body_radps = Vec3::Zero();
};

const std::array<std::string, 7> kImuColumns = {
    "time_s", "f_x_mps2", "f_y_mps2", "f_z_mps2", "w_x_radps", "w_y_radps", "w_z_radps"};

// The IMU rows of a sample file, through the shared numeric CSV reader.
class ImuCsvReader {
 public:
  explicit ImuCsvReader(const std::string& path)
      : csv_(path, {kImuColumns.begin(), kImuColumns.end()}, {}, "time_s") {}

  const std::string& path() const { return csv_.path(); }
  int line() const { return csv_.line(); }

  // The next sample; false at the end of the file.
  bool next(ImuRow& row) {
    if (!csv_.next(values_)) return false;
    row.t_s = values_[0];
    row.f_body_mps2 = Vec3(values_[1], values_[2], values_[3]);
    row.w_body_radps = Vec3(values_[4], values_[5], values_[6]);
    return true;
  }

 private:
  NumericCsvReader csv_;
  std::vector<double> values_;
};

// ---------------------------------------------------------------------------------------------
// The dead-reckoned quantities reported per row.

struct DrState {
  StrapdownState nav;
  Vec3 heading_rad = Vec3::Zero();  // gyro-only headings, integral of w - w_static per axis
};

// Everything needed to print and compare: attitude (deg), position relative to the start
// (NED, m), velocity, gyro-only headings (deg).
struct DrReport {
  Vec3 rpy_deg = Vec3::Zero();
  Vec3 p_ned_m = Vec3::Zero();
  Vec3 v_ned_mps = Vec3::Zero();
  Vec3 heading_deg = Vec3::Zero();
};

class StartFrame {
 public:
  explicit StartFrame(const Geodetic& start)
      : p0_ecef_(ecef_from_geodetic(start)), R_(R_ned_from_ecef(start)) {}
  DrReport report(const DrState& s) const {
    DrReport r;
    r.rpy_deg = euler_rpy_from_quat(s.nav.q_ned_from_body) * kRadToDeg;
    r.p_ned_m = R_ * (ecef_from_geodetic(s.nav.position) - p0_ecef_);
    r.v_ned_mps = s.nav.v_ned_mps;
    r.heading_deg = s.heading_rad * kRadToDeg;
    return r;
  }

 private:
  Vec3 p0_ecef_;
  Mat3 R_;
};

double wrap_deg(double a) {
  a = std::fmod(a + 180.0, 360.0);
  if (a < 0.0) a += 360.0;
  return a - 180.0;
}

DrReport difference(const DrReport& a, const DrReport& b) {
  DrReport d;
  for (int i = 0; i < 3; ++i) d.rpy_deg[i] = wrap_deg(a.rpy_deg[i] - b.rpy_deg[i]);
  d.p_ned_m = a.p_ned_m - b.p_ned_m;
  d.v_ned_mps = a.v_ned_mps - b.v_ned_mps;
  d.heading_deg = a.heading_deg - b.heading_deg;
  return d;
}

DrReport interpolate(const DrReport& a, const DrReport& b, double alpha) {
  DrReport r;
  for (int i = 0; i < 3; ++i) r.rpy_deg[i] = a.rpy_deg[i] + alpha * wrap_deg(b.rpy_deg[i] - a.rpy_deg[i]);
  r.p_ned_m = a.p_ned_m + alpha * (b.p_ned_m - a.p_ned_m);
  r.v_ned_mps = a.v_ned_mps + alpha * (b.v_ned_mps - a.v_ned_mps);
  r.heading_deg = a.heading_deg + alpha * (b.heading_deg - a.heading_deg);
  return r;
}

// One integration of a sample stream: strapdown plus the gyro-only headings.
class Integrator {
 public:
  Integrator(const StrapdownState& start, const Vec3& w_static_body, const Vec3& bias_f,
             const Vec3& bias_w)
      : sd_(start), w_static_(w_static_body), bias_f_(bias_f), bias_w_(bias_w) {}

  // Sample k is held over (t_(k-1), t_k].
  void step(const ImuRow& row, double dt_s) {
    const Vec3 w = row.w_body_radps - bias_w_;
    sd_.step(row.f_body_mps2 - bias_f_, w, dt_s);
    heading_rad_ += (w - w_static_) * dt_s;
  }
  DrState state() const { return DrState{sd_.state(), heading_rad_}; }

 private:
  Strapdown sd_;
  Vec3 w_static_, bias_f_, bias_w_;
  Vec3 heading_rad_ = Vec3::Zero();
};

// The truth run: another IMU file integrated the same way, sampled at the data's times (linear
// interpolation between its own samples; attitude angles interpolated on the short arc).
class TruthTrack {
 public:
  TruthTrack(const std::string& path, const StrapdownState& start, const Vec3& w_static,
             const StartFrame& frame)
      : reader_(path), frame_(frame) {
    ImuRow first;
    if (!reader_.next(first)) throw InputError(path, reader_.line(), "", "no samples");
    StrapdownState s = start;
    s.t = GpsTime::from_seconds(first.t_s);
    integ_.emplace(s, w_static, Vec3::Zero(), Vec3::Zero());
    t_cur_ = first.t_s;
    cur_ = frame_.report(integ_->state());
    read_pending();
  }

  DrReport at(double t_s) {
    constexpr double kTol = 1e-9;
    while (pending_ && pending_->t_s <= t_s + kTol) {
      integ_->step(*pending_, pending_->t_s - t_cur_);
      t_cur_ = pending_->t_s;
      cur_ = frame_.report(integ_->state());
      read_pending();
    }
    if (std::abs(t_cur_ - t_s) <= kTol) return cur_;
    if (t_s < t_cur_ || !pending_)
      throw InputError(reader_.path(), reader_.line(), "time_s",
                       fmt::format("the truth does not cover time {} s of the data", t_s));
    Integrator ahead = *integ_;
    ahead.step(*pending_, pending_->t_s - t_cur_);
    return interpolate(cur_, frame_.report(ahead.state()),
                       (t_s - t_cur_) / (pending_->t_s - t_cur_));
  }

 private:
  void read_pending() {
    ImuRow r;
    if (reader_.next(r))
      pending_ = r;
    else
      pending_.reset();
  }

  ImuCsvReader reader_;
  const StartFrame& frame_;
  std::optional<Integrator> integ_;
  double t_cur_ = 0.0;
  DrReport cur_;
  std::optional<ImuRow> pending_;
};

Vec3 parse_rpy_deg(const std::string& text) {
  const std::vector<double> v = parse_numbers(text, "--initial-rpy", {"roll", "pitch", "yaw"},
                                              "ROLL,PITCH,YAW in degrees");
  return Vec3(v[0], v[1], v[2]);
}

void print_row(std::ostream& os, double t_s, const DrReport& r, bool headings,
               const DrReport* err) {
  auto body = [&](const DrReport& x) {
    fmt::print(os, ",{:.9f},{:.9f},{:.9f},{:.6f},{:.6f},{:.6f},{:.9f},{:.9f},{:.9f}",
               x.rpy_deg.x(), x.rpy_deg.y(), x.rpy_deg.z(), x.p_ned_m.x(), x.p_ned_m.y(),
               x.p_ned_m.z(), x.v_ned_mps.x(), x.v_ned_mps.y(), x.v_ned_mps.z());
    if (headings)
      fmt::print(os, ",{:.9f},{:.9f},{:.9f}", x.heading_deg.x(), x.heading_deg.y(),
                 x.heading_deg.z());
  };
  fmt::print(os, "{:.6f}", t_s);
  body(r);
  if (err != nullptr) body(*err);
  os << '\n';
}

}  // namespace

std::shared_ptr<DeadreckonOptions> add_deadreckon_command(CLI::App& app) {
  auto opt = std::make_shared<DeadreckonOptions>();
  CLI::App* cmd = app.add_subcommand(
      "deadreckon", "Strapdown dead reckoning of an IMU sample file (attitude, velocity, position)");
  cmd->footer(
      "Reads the CSV written by 'navemu imu' (header row; columns time_s, f_x_mps2, f_y_mps2,\n"
      "f_z_mps2, w_x_radps, w_y_radps, w_z_radps; others ignored). Body frame FRD, navigation\n"
      "frame NED; starts at rest at --at with the --initial-rpy attitude and integrates in the\n"
      "WGS-84 NED mechanization (normal gravity, Earth rate, transport rate, Coriolis).\n"
      "CSV columns: time_s, roll_deg, pitch_deg, yaw_deg, north_m, east_m, down_m (relative to\n"
      "the start), v_n_mps, v_e_mps, v_d_mps; with --gyro-only-heading also heading_x_deg,\n"
      "heading_y_deg, heading_z_deg (each gyroscope integrated alone, minus the Earth rate a\n"
      "stationary gyroscope senses: the paper's Fig. 2/3 heading); with --truth the same\n"
      "columns again prefixed err_ (data minus truth). A drift summary goes to stderr.\n"
      "Example:\n"
      "  navemu deadreckon phidget.csv --truth static --bias-removal 10 --out dr.csv");
  cmd->add_option("FILE", opt->file, "IMU sample CSV")->required();
  cmd->add_option("--truth", opt->truth,
                  "Truth: an IMU CSV of an error-free run (integrated the same way), or "
                  "'static' (stationary at the start). Adds the err_ columns");
  cmd->add_option("--at", opt->at, "Start position LAT,LON,H (deg, deg, m above the ellipsoid)")
      ->capture_default_str();
  cmd->add_option("--start-lat", opt->start_lat_deg, "Start latitude (deg), overrides --at")
      ->check(number_between(-90.0, 90.0));
  cmd->add_option("--start-lon", opt->start_lon_deg, "Start longitude (deg), overrides --at")
      ->check(number_between(-180.0, 360.0));
  cmd->add_option("--start-h", opt->start_h_m, "Start ellipsoidal height (m), overrides --at");
  cmd->add_option("--initial-rpy", opt->initial_rpy_deg,
                  "Initial attitude ROLL,PITCH,YAW (deg, ZYX Euler angles of body FRD in NED)")
      ->capture_default_str();
  cmd->add_option("--bias-removal", opt->bias_removal_s,
                  "Estimate the sensor biases as the mean of the first S seconds minus the "
                  "ideal stationary output, and remove them (0: off)")
      ->capture_default_str()
      ->check(non_negative_number());
  cmd->add_option("--every", opt->every,
                  "Write every N-th sample (default: the number of samples in 1 s)")
      ->check(positive_number());
  cmd->add_option("--out", opt->out_file, "Output CSV ('-': standard output)")
      ->capture_default_str();
  cmd->add_flag("--gyro-only-heading", opt->gyro_only_heading,
                "Also integrate each gyroscope axis alone (heading_x/y/z_deg columns, drift in "
                "deg/h)");
  return opt;
}

namespace {

// The mean over the first --bias-removal seconds minus what a perfect stationary IMU at the
// start (`ideal`) would output; said on `err`.
void estimate_bias(const DeadreckonOptions& opt, const IdealImu& ideal, std::ostream& err, Vec3& bias_f,
                   Vec3& bias_w) {
  ImuCsvReader pre(opt.file);
  ImuRow r;
  std::optional<double> t0;
  Vec3 sum_f = Vec3::Zero(), sum_w = Vec3::Zero();
  long long n = 0;
  while (pre.next(r)) {
    if (!t0) t0 = r.t_s;
    if (n > 0 && r.t_s - *t0 >= opt.bias_removal_s) break;
    sum_f += r.f_body_mps2;
    sum_w += r.w_body_radps;
    ++n;
  }
  if (n == 0) throw InputError(opt.file, pre.line(), "", "no samples");
  bias_f = sum_f / static_cast<double>(n) - ideal.f_body_mps2;
  bias_w = sum_w / static_cast<double>(n) - ideal.w_ib_body_radps;
  fmt::print(err,
             "navemu deadreckon: bias over the first {} s ({} samples): accel {:.6g} {:.6g} "
             "{:.6g} m/s^2, gyro {:.6g} {:.6g} {:.6g} deg/h (removed)\n",
             opt.bias_removal_s, n, bias_f.x(), bias_f.y(), bias_f.z(),
             bias_w.x() * kRadToDeg * 3600.0, bias_w.y() * kRadToDeg * 3600.0,
             bias_w.z() * kRadToDeg * 3600.0);
}

}  // namespace

int run_deadreckon(const DeadreckonOptions& opt, std::ostream& out, std::ostream& err) {
  Geodetic start = parse_geodetic(opt.at, "--at");
  if (opt.start_lat_deg) start.lat_deg = *opt.start_lat_deg;
  if (opt.start_lon_deg) start.lon_deg = *opt.start_lon_deg;
  if (opt.start_h_m) start.h_m = *opt.start_h_m;
  const Vec3 rpy0_deg = parse_rpy_deg(opt.initial_rpy_deg);
  const Quat q0 = quat_from_euler_rpy(rpy0_deg * kDegToRad);
  const IdealImu ideal = ideal_imu_static(start, q0);

  // Bias estimate (--bias-removal): none, or removed from every sample.
  Vec3 bias_f = Vec3::Zero(), bias_w = Vec3::Zero();
  if (opt.bias_removal_s > 0.0) estimate_bias(opt, ideal, err, bias_f, bias_w);

  ImuCsvReader reader(opt.file);
  ImuRow row;
  if (!reader.next(row)) throw InputError(opt.file, reader.line(), "", "no samples");

  StrapdownState s0;
  s0.t = GpsTime::from_seconds(row.t_s);
  s0.position = start;
  s0.v_ned_mps = Vec3::Zero();
  s0.q_ned_from_body = q0;
  const StartFrame frame(start);
  Integrator integ(s0, ideal.w_ib_body_radps, bias_f, bias_w);

  // The truth, if any: a stationary start, or another file integrated alongside.
  const bool static_truth = opt.truth == "static";
  const bool have_truth = !opt.truth.empty();
  std::optional<TruthTrack> truth;
  if (have_truth && !static_truth) truth.emplace(opt.truth, s0, ideal.w_ib_body_radps, frame);
  const DrReport start_report = frame.report(integ.state());
  auto truth_at = [&](double t_s) { return truth ? truth->at(t_s) : start_report; };

  std::ofstream file_out;
  std::ostream* os = &out;
  if (opt.out_file != "-") {
    file_out.open(opt.out_file);
    if (!file_out) throw InputError(opt.out_file, 0, "--out", "cannot open for writing");
    os = &file_out;
  }

  auto header = [&](const std::string& prefix) {
    std::string h = fmt::format(
        "{0}roll_deg,{0}pitch_deg,{0}yaw_deg,{0}north_m,{0}east_m,{0}down_m,{0}v_n_mps,"
        "{0}v_e_mps,{0}v_d_mps",
        prefix);
    if (opt.gyro_only_heading)
      h += fmt::format(",{0}heading_x_deg,{0}heading_y_deg,{0}heading_z_deg", prefix);
    return h;
  };
  *os << "time_s," << header("");
  if (have_truth) *os << ',' << header("err_");
  *os << '\n';

  auto emit = [&](double t_s, const DrReport& r) {
    if (have_truth) {
      const DrReport e = difference(r, truth_at(t_s));
      print_row(*os, t_s, r, opt.gyro_only_heading, &e);
    } else {
      print_row(*os, t_s, r, opt.gyro_only_heading, nullptr);
    }
  };

  const double t_first = row.t_s;
  emit(t_first, start_report);
  long long every = opt.every ? *opt.every : 0;
  long long k = 0;
  double t_prev = row.t_s;
  bool last_written = true;
  while (reader.next(row)) {
    ++k;
    const double dt = row.t_s - t_prev;
    if (every == 0) every = std::max(1LL, std::llround(1.0 / dt));
    integ.step(row, dt);
    t_prev = row.t_s;
    last_written = k % every == 0;
    if (last_written) emit(row.t_s, frame.report(integ.state()));
  }
  const DrReport final_report = frame.report(integ.state());
  if (!last_written) emit(t_prev, final_report);
  if (!*os) throw InputError(opt.out_file, 0, "--out", "write failed");

  // Summary: drift against the truth (or the stationary start).
  const double span_s = t_prev - t_first;
  const double span_h = span_s / 3600.0;
  const DrReport d = difference(final_report, truth_at(t_prev));
  auto per_hour = [&](double deg) { return span_h > 0.0 ? deg / span_h : 0.0; };
  const std::string against = truth ? opt.truth : std::string("the stationary start");
  fmt::print(err,
             "navemu deadreckon: {}: {} samples over {:.3f} s ({:.6g} Hz), start {:.7f},{:.7f},"
             "{:.3f}, initial rpy {:g},{:g},{:g} deg\n",
             opt.file, k + 1, span_s, span_s > 0.0 ? static_cast<double>(k) / span_s : 0.0,
             start.lat_deg, start.lon_deg, start.h_m, rpy0_deg.x(), rpy0_deg.y(), rpy0_deg.z());
  fmt::print(err,
             "navemu deadreckon: attitude drift vs {}: roll {:.6f} deg ({:.4f} deg/h), pitch "
             "{:.6f} deg ({:.4f} deg/h), yaw {:.6f} deg ({:.4f} deg/h)\n",
             against, d.rpy_deg.x(), per_hour(d.rpy_deg.x()), d.rpy_deg.y(),
             per_hour(d.rpy_deg.y()), d.rpy_deg.z(), per_hour(d.rpy_deg.z()));
  fmt::print(err,
             "navemu deadreckon: position drift: north {:.4f} m, east {:.4f} m, down {:.4f} m, "
             "horizontal {:.4f} m, 3-D {:.4f} m; velocity {:.6f} {:.6f} {:.6f} m/s\n",
             d.p_ned_m.x(), d.p_ned_m.y(), d.p_ned_m.z(), d.p_ned_m.head<2>().norm(),
             d.p_ned_m.norm(), d.v_ned_mps.x(), d.v_ned_mps.y(), d.v_ned_mps.z());
  if (opt.gyro_only_heading)
    fmt::print(err,
               "navemu deadreckon: gyro-only heading drift: x {:.6f} deg ({:.4f} deg/h), y "
               "{:.6f} deg ({:.4f} deg/h), z {:.6f} deg ({:.4f} deg/h)\n",
               d.heading_deg.x(), per_hour(d.heading_deg.x()), d.heading_deg.y(),
               per_hour(d.heading_deg.y()), d.heading_deg.z(), per_hour(d.heading_deg.z()));
  return 0;
}

}  // namespace navemu
