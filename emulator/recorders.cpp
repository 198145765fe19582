#include "emulator/recorders.hpp"

#include <fmt/compile.h>
#include <fmt/format.h>

#include <cmath>
#include <fstream>

#include "core/errors.hpp"
#include "models/geodesy.hpp"
#include "transports/byte_port.hpp"

namespace navemu {

namespace {

constexpr std::string_view kTruthColumns[] = {"time_s",  "lat_deg",  "lon_deg",   "h_m",
                                              "v_n_mps", "v_e_mps",  "v_d_mps",   "roll_deg",
                                              "pitch_deg", "yaw_deg"};
constexpr std::string_view kGnssColumns[] = {
    "time_s",  "gps_week", "gps_tow_s", "truth_lat_deg", "truth_lon_deg", "truth_h_m", "fix",
    "num_tracked", "num_used", "lat_deg", "lon_deg", "h_m", "v_n_mps", "v_e_mps", "v_d_mps",
    "err_e_m", "err_n_m", "err_u_m", "err_h_m", "pdop", "hdop", "vdop", "sigma_h_m", "sigma_v_m"};
constexpr std::string_view kImuColumns[] = {"time_s",    "f_x_mps2",  "f_y_mps2",      "f_z_mps2",
                                            "w_x_radps", "w_y_radps", "w_z_radps",     "temperature_c",
                                            "truth_valid", "gps_time_ns", "sequence"};

// A CSV file written through one buffer. The buffer is flushed past kFlushBytes and holds twice
// that from the start, so it never grows (rows are short).
class CsvWriter {
 public:
  static constexpr std::size_t kFlushBytes = 1u << 16;
  CsvWriter(const std::filesystem::path& path, const CsvSchema& schema) : path_(path), out_(path) {
    if (!out_) throw InputError(path.string(), 0, "--out", "cannot open for writing");
    buf_.reserve(2 * kFlushBytes);
    buf_.append(schema.header());
  }
  ~CsvWriter() { flush(); }
  fmt::memory_buffer& buf() { return buf_; }
  void maybe_flush() {
    if (buf_.size() > kFlushBytes) flush();
  }
  void flush() {
    out_.write(buf_.data(), static_cast<std::streamsize>(buf_.size()));
    buf_.clear();
    out_.flush();
  }
  void close() {
    flush();
    out_.close();
    if (!out_) throw InputError(path_.string(), 0, "--out", "write failed (disk full?)");
  }

 private:
  std::filesystem::path path_;
  std::ofstream out_;
  fmt::memory_buffer buf_;
};

class TruthCsv final : public EpochRecorder {
 public:
  explicit TruthCsv(const std::filesystem::path& dir) : csv_(dir / kTruthCsv.name, kTruthCsv) {}
  void record(const EpochRecord& e) override {
    if (!e.truth) return;
    const ImuTruth& tr = *e.truth;
    const Vec3 rpy = euler_rpy_from_quat(tr.q_ned_from_body) * kRadToDeg;
    fmt::format_to(std::back_inserter(csv_.buf()),
                   "{:.3f},{:.9f},{:.9f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f}\n", e.t_rel_s,
                   tr.position.lat_deg, tr.position.lon_deg, tr.position.h_m, tr.v_ned_mps.x(),
                   tr.v_ned_mps.y(), tr.v_ned_mps.z(), rpy.x(), rpy.y(), rpy.z());
    csv_.maybe_flush();
  }
  void close() override { csv_.close(); }

 private:
  CsvWriter csv_;
};

class GnssCsv final : public EpochRecorder {
 public:
  explicit GnssCsv(const std::filesystem::path& dir) : csv_(dir / kGnssCsv.name, kGnssCsv) {}
  void record(const EpochRecord& e) override {
    auto& b = csv_.buf();
    const auto out = std::back_inserter(b);
    const WeekTow wt = to_week_tow(e.t);
    const ReceiverFix& fix = e.fix;
    fmt::format_to(out, "{:.3f},{},{:.3f},", e.t_rel_s, wt.week, wt.tow_s);
    if (e.truth)
      fmt::format_to(out, "{:.9f},{:.9f},{:.4f},", e.truth->position.lat_deg,
                     e.truth->position.lon_deg, e.truth->position.h_m);
    else
      fmt::format_to(out, ",,,");
    fmt::format_to(out, "{},{},{},", static_cast<int>(fix.fix), fix.satellites.size(), fix.num_used);
    if (fix.fix != FixType::kNone && e.truth) {
      const Vec3 v = fix.v_ned_mps.value_or(Vec3::Zero());
      const Vec3 err = enu_from_ecef(fix.p_ecef_m, e.truth->position);  // east, north, up
      fmt::format_to(out,
                     "{:.9f},{:.9f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},"
                     "{:.3f},{:.3f},{:.3f},{:.3f},{:.3f}\n",
                     fix.position.lat_deg, fix.position.lon_deg, fix.position.h_m, v.x(), v.y(), v.z(),
                     err.x(), err.y(), err.z(), std::hypot(err.x(), err.y()), fix.dops.pdop,
                     fix.dops.hdop, fix.dops.vdop, fix.sigma_h_m, fix.sigma_v_m);
    } else {
      fmt::format_to(out, ",,,,,,,,,,,,,,\n");
    }
    csv_.maybe_flush();
  }
  void close() override { csv_.close(); }

 private:
  CsvWriter csv_;
};

void format_imu_row(const SampleRecord& r, fmt::memory_buffer& b) {
  const ImuSample& s = r.sample;
  fmt::format_to(std::back_inserter(b),
                 FMT_COMPILE("{:.6f},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.4g},{},{},{}\n"),
                 r.t_rel_s, s.f_body_mps2.x(), s.f_body_mps2.y(), s.f_body_mps2.z(), s.w_body_radps.x(),
                 s.w_body_radps.y(), s.w_body_radps.z(), s.temperature_c, r.truth_valid ? 1 : 0,
                 r.t_meas.ns, r.sequence);
}

class ImuCsv final : public SampleRecorder {
 public:
  explicit ImuCsv(const std::filesystem::path& dir) : csv_(dir / kImuCsv.name, kImuCsv) {}
  void record(const SampleRecord& r) override {
    format_imu_row(r, csv_.buf());
    csv_.maybe_flush();
  }
  void close() override { csv_.close(); }

 private:
  CsvWriter csv_;
};

// The live IMU log: each row written to the log port (buffered there, written out as it fills
// and once per status interval).
class ImuLog final : public SampleRecorder {
 public:
  explicit ImuLog(std::unique_ptr<transport::BytePort> port) : port_(std::move(port)) {
    port_->write(kImuCsv.header());
  }
  void record(const SampleRecord& r) override {
    line_.clear();
    format_imu_row(r, line_);
    port_->write(std::string_view(line_.data(), line_.size()));
  }
  void flush() override { port_->service(); }
  void close() override {}

 private:
  std::unique_ptr<transport::BytePort> port_;
  fmt::memory_buffer line_;
};

}  // namespace

const CsvSchema kTruthCsv{"truth.csv", kTruthColumns};
const CsvSchema kGnssCsv{"gnss.csv", kGnssColumns};
const CsvSchema kImuCsv{"imu.csv", kImuColumns};

std::string CsvSchema::header() const {
  std::string h;
  for (std::string_view c : columns) {
    if (!h.empty()) h += ',';
    h += c;
  }
  return h + '\n';
}

std::unique_ptr<EpochRecorder> make_truth_csv(const std::filesystem::path& dir) {
  return std::make_unique<TruthCsv>(dir);
}
std::unique_ptr<EpochRecorder> make_gnss_csv(const std::filesystem::path& dir) {
  return std::make_unique<GnssCsv>(dir);
}
std::unique_ptr<SampleRecorder> make_imu_csv(const std::filesystem::path& dir) {
  return std::make_unique<ImuCsv>(dir);
}
std::unique_ptr<SampleRecorder> make_imu_log(std::unique_ptr<transport::BytePort> port) {
  return std::make_unique<ImuLog>(std::move(port));
}

}  // namespace navemu
