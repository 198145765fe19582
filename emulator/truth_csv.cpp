#include "emulator/truth_csv.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <string_view>

#include "core/errors.hpp"
#include "models/truth_interpolation.hpp"

namespace navemu {

namespace {

constexpr const char* kRequired[10] = {"time_s",  "lat_deg",  "lon_deg",  "h_m",      "v_n_mps",
                                       "v_e_mps", "v_d_mps",  "roll_deg", "pitch_deg", "yaw_deg"};
constexpr const char* kForce[3] = {"f_x_mps2", "f_y_mps2", "f_z_mps2"};
constexpr const char* kRate[3] = {"w_x_radps", "w_y_radps", "w_z_radps"};
constexpr const char* kTemperature = "temperature_c";

}  // namespace

TruthCsvReader::TruthCsvReader(std::string path, bool time_must_increase)
    : csv_(std::move(path), {std::begin(kRequired), std::end(kRequired)},
           {kForce[0], kForce[1], kForce[2], kRate[0], kRate[1], kRate[2], kTemperature},
           time_must_increase ? std::optional<std::string>("time_s") : std::nullopt) {
  int rate_columns = 0;
  for (int i = 0; i < 3; ++i) rate_columns += csv_.has(kForce[i]) + csv_.has(kRate[i]);
  if (rate_columns != 0 && rate_columns != 6) {
    for (int i = 0; i < 3; ++i) {
      const char* missing = !csv_.has(kForce[i]) ? kForce[i] : !csv_.has(kRate[i]) ? kRate[i] : nullptr;
      if (missing)
        throw InputError(csv_.path(), csv_.line(), missing,
                         "missing column (f_x_mps2..f_z_mps2 and w_x_radps..w_z_radps: all six "
                         "or none)");
    }
  }
  has_rates_ = rate_columns == 6;
  has_temperature_ = csv_.has(kTemperature);
}

bool TruthCsvReader::next(TruthRow& row) {
  if (!csv_.next(values_)) {
    if (rows_ < 3)
      throw InputError(csv_.path(), csv_.line(), "",
                       fmt::format("fewer than 3 rows of truth (got {}); cubic interpolation "
                                   "needs at least 3",
                                   rows_));
    return false;
  }
  // values_: the ten required columns, then the optional ones the header has, in order.
  const std::vector<double>& v = values_;
  row.time_s = v[0];
  row.position = Geodetic{v[1], v[2], v[3]};
  if (!(std::abs(row.position.lat_deg) < 90.0))
    throw InputError(csv_.path(), csv_.line(), kRequired[1],
                     fmt::format("latitude out of range (-90, 90): {}", v[1]));
  if (!(std::abs(row.position.lon_deg) <= 360.0))
    throw InputError(csv_.path(), csv_.line(), kRequired[2],
                     fmt::format("longitude out of range [-360, 360]: {}", v[2]));
  row.v_ned_mps = Vec3(v[4], v[5], v[6]);
  row.rpy_rad = Vec3(v[7], v[8], v[9]) * kDegToRad;
  std::size_t k = 10;
  if (has_rates_) {
    row.f_body_mps2 = Vec3(v[k], v[k + 1], v[k + 2]);
    row.w_ib_body_radps = Vec3(v[k + 3], v[k + 4], v[k + 5]);
    k += 6;
  } else {
    row.f_body_mps2.reset();
    row.w_ib_body_radps.reset();
  }
  if (has_temperature_)
    row.temperature_c = v[k];
  else
    row.temperature_c.reset();
  ++rows_;
  return true;
}

TruthCsvSummary scan_truth_csv(const std::string& path) {
  TruthCsvReader reader(path);
  TruthCsvSummary s;
  s.has_rates = reader.has_rates();
  s.has_temperature = reader.has_temperature();
  TruthRow row;
  while (reader.next(row)) {
    if (s.rows == 0) s.first_time_s = row.time_s;
    s.last_time_s = row.time_s;
    ++s.rows;
  }
  return s;
}

TruthTrack::TruthTrack(const std::string& path) : reader_(path) {
  // Three rows: the least the slopes of the first interval need.
  for (int i = 0; i < 3; ++i)
    if (!load_next()) break;  // the reader throws before this for a file of fewer than 3 rows
  first_time_s_ = knots_.front().t_s;
}

bool TruthTrack::load_next() {
  if (end_) return false;
  TruthRow row;
  if (!reader_.next(row)) {
    end_ = true;
    return false;
  }
  Knot k;
  k.t_s = row.time_s;
  k.truth.t = GpsTime::from_seconds(row.time_s);
  k.truth.position = row.position;
  k.truth.v_ned_mps = row.v_ned_mps;
  k.truth.q_ned_from_body = quat_from_euler_rpy(row.rpy_rad);
  k.truth.f_body_mps2 = row.f_body_mps2;
  k.truth.w_ib_body_radps = row.w_ib_body_radps;
  k.truth.temperature_c = row.temperature_c;
  knots_.push_back(k);
  return true;
}

Vec3 TruthTrack::velocity_slope(std::size_t i) const {
  // Derivative of the quadratic through three rows (exact for a quadratic velocity):
  // central at an inner row, one-sided at the file's first and last rows.
  // (at() keeps the predecessor of every inner row it needs, so i == 0 is the file's first row.)
  std::size_t a = 0;
  if (i + 1 >= knots_.size())
    a = i - 2;  // the file's last row
  else if (i > 0)
    a = i - 1;
  const Knot& k0 = knots_[a];
  const Knot& k1 = knots_[a + 1];
  const Knot& k2 = knots_[a + 2];
  const double h1 = k1.t_s - k0.t_s, h2 = k2.t_s - k1.t_s;
  const double x = knots_[i].t_s;
  // Lagrange basis derivatives at x.
  const double d0 = ((x - k1.t_s) + (x - k2.t_s)) / (h1 * (h1 + h2));
  const double d1 = ((x - k0.t_s) + (x - k2.t_s)) / (-h1 * h2);
  const double d2 = ((x - k0.t_s) + (x - k1.t_s)) / ((h1 + h2) * h2);
  return d0 * k0.truth.v_ned_mps + d1 * k1.truth.v_ned_mps + d2 * k2.truth.v_ned_mps;
}

ImuTruth TruthTrack::at(double t_s) {
  constexpr double kTolerance_s = 1e-6;  // rounding of instants computed from the file's times
  if (t_s < knots_.front().t_s - kTolerance_s)
    throw InputError(reader_.path(), reader_.line(), "time_s",
                     fmt::format("instant {} s requested before the rows held (from {} s)", t_s,
                                 knots_.front().t_s));
  while (knots_.back().t_s < t_s && load_next()) {
  }
  if (t_s > knots_.back().t_s + kTolerance_s)
    throw InputError(reader_.path(), reader_.line(), "time_s",
                     fmt::format("the truth ends at {} s, before {} s", knots_.back().t_s, t_s));
  // The interval [k, k+1] holding t_s, and the row after it for the slope at k+1.
  std::size_t k = 0;
  while (k + 2 < knots_.size() && knots_[k + 1].t_s <= t_s) ++k;
  while (knots_.size() < k + 3 && load_next()) {
  }
  // Position Hermite on the rows' velocities, velocity Hermite on the finite-difference slopes,
  // slerp attitude, linear f, w and temperature (models/truth_interpolation.hpp).
  ImuTruth out = interpolate_truth(knots_[k].truth, knots_[k + 1].truth,
                                   GpsTime::from_seconds(t_s), velocity_slope(k),
                                   velocity_slope(k + 1));

  // Keep the interval's predecessor (the slope at k) and drop the rows before it.
  while (k >= 2) {
    knots_.pop_front();
    --k;
  }
  return out;
}

}  // namespace navemu
