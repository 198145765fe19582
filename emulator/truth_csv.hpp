#pragma once
// Truth trajectories from CSV files (a simulator's log or a generated track), read line by line
// and interpolated to an IMU's sampling instants.
//
// Format. One header row naming the columns (any order), then one row per truth sample; comma
// separated, blank lines and lines starting with '#' skipped; any rate, time strictly increasing,
// at least 3 rows.
//   required: time_s, lat_deg, lon_deg, h_m (WGS-84 ellipsoid), v_n_mps, v_e_mps, v_d_mps
//             (velocity over the Earth in NED), roll_deg, pitch_deg, yaw_deg (ZYX Euler angles
//             of the FRD body frame relative to NED, models/imu_kinematics.hpp)
//   optional, all six or none: f_x_mps2, f_y_mps2, f_z_mps2 (body specific force),
//             w_x_radps, w_y_radps, w_z_radps (body angular rate w_ib): the simulator's own ideal
//             IMU output, used instead of the rates derived from the kinematics
//   optional: temperature_c
// Other columns are ignored; no name may appear twice.
// Errors: navemu::InputError "<file>:<line>: column <n> (<name>): <problem>", n counted from 1.
//
// Interpolation (TruthTrack, through models/truth_interpolation.hpp), between the two rows
// around an instant:
//   position  cubic Hermite on latitude, longitude (unwrapped) and height, with the rows'
//             velocities as derivatives: dlat/dt = v_n / (R_N + h), dlon/dt = v_e / ((R_E + h)
//             cos lat), dh/dt = -v_d (R_N, R_E the WGS-84 radii of curvature);
//   velocity  cubic Hermite with derivatives by the three-point (non-uniform) finite difference
//             of the rows' velocities, one-sided at the file's first and last row;
//   attitude  slerp of the rows' quaternions (the shorter arc; exact for a constant body rate
//             relative to NED);
//   f, w, temperature  linear.

#include <cstdint>
#include <deque>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "emulator/numeric_csv.hpp"

#include "models/geodesy.hpp"
#include "models/imu_kinematics.hpp"

namespace navemu {

// One row of a truth CSV file, in SI units (angles in radians).
struct TruthRow {
  double time_s = 0.0;
  Geodetic position;
  Vec3 v_ned_mps = Vec3::Zero();
  Vec3 rpy_rad = Vec3::Zero();
  std::optional<Vec3> f_body_mps2;
  std::optional<Vec3> w_ib_body_radps;
  std::optional<double> temperature_c;
};

// Incremental reader: the header when constructed, then one row per next().
class TruthCsvReader {
 public:
  // Opens `path` and reads the header; InputError on a missing file or a bad header.
  // `time_must_increase` false: rows out of time order are passed on (to a TruthBuffer, which
  // applies the streamed-truth rules to them), not refused.
  explicit TruthCsvReader(std::string path, bool time_must_increase = true);
  // The next row, checked (finite numbers, time increasing, latitude inside (-90, 90)); false
  // at the end of the file, or InputError at the end when the file has fewer than 3 rows.
  bool next(TruthRow& row);

  bool has_rates() const { return has_rates_; }
  bool has_temperature() const { return has_temperature_; }
  const std::string& path() const { return csv_.path(); }
  int line() const { return csv_.line(); }  // the line last read (1-based)
  std::int64_t rows() const { return rows_; }

 private:
  NumericCsvReader csv_;
  bool has_rates_ = false;
  bool has_temperature_ = false;
  std::int64_t rows_ = 0;
  std::vector<double> values_;
};

// What a whole pass over a file found (every row checked).
struct TruthCsvSummary {
  std::int64_t rows = 0;
  double first_time_s = 0.0;
  double last_time_s = 0.0;
  bool has_rates = false;
  bool has_temperature = false;
};
TruthCsvSummary scan_truth_csv(const std::string& path);

// The truth at any instant inside the file's span, streaming: only the few rows around the
// current instant are held, so queries must come at non-decreasing times.
class TruthTrack {
 public:
  explicit TruthTrack(const std::string& path);

  double first_time_s() const { return first_time_s_; }
  bool has_rates() const { return reader_.has_rates(); }
  bool has_temperature() const { return reader_.has_temperature(); }

  // The interpolated truth at t_s (seconds in the file's time base, inside its span, not
  // earlier than the previous query). ImuTruth::t is t_s rounded to the nanosecond; f/w and
  // temperature are set when the file has them.
  ImuTruth at(double t_s);

 private:
  struct Knot {
    double t_s;      // the row's time as read (ImuTruth::t is it rounded to the nanosecond)
    ImuTruth truth;  // f/w and temperature set when the file has them
  };
  bool load_next();
  Vec3 velocity_slope(std::size_t i) const;

  TruthCsvReader reader_;
  std::deque<Knot> knots_;
  bool end_ = false;
  double first_time_s_ = 0.0;
};

}  // namespace navemu
