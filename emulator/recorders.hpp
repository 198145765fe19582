#pragma once
// Recorders: the files of a run as sinks attached to a channel, each with one named schema
// (its columns, in order). Offline (`navemu simulate`): truth.csv and gnss.csv on the GNSS
// channel, imu.csv on the IMU channel; live: the IMU sample log (imu.log, the imu.csv schema).
// Rows are formatted into one reused buffer and written in blocks: no allocation per row.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "models/imu_kinematics.hpp"
#include "models/imu_model.hpp"
#include "models/receiver.hpp"
#include "core/time.hpp"

namespace navemu {

namespace transport {
class BytePort;
}

// A CSV file's name and columns; its header is the columns joined by commas.
struct CsvSchema {
  std::string_view name;
  std::span<const std::string_view> columns;
  std::string header() const;  // with the line end
};
extern const CsvSchema kTruthCsv;  // truth.csv: the truth at each GNSS epoch (replayable)
extern const CsvSchema kGnssCsv;   // gnss.csv: truth, fix, satellites, error, DOPs per epoch
extern const CsvSchema kImuCsv;    // imu.csv / imu.log: one row per IMU output sample

// One GNSS epoch as the recorders see it; `t_rel_s` counts from the scenario's start.
struct EpochRecord {
  GpsTime t;
  double t_rel_s = 0.0;
  const std::optional<ImuTruth>& truth;
  const ReceiverFix& fix;
};

// One IMU output sample.
struct SampleRecord {
  const ImuSample& sample;
  double t_rel_s = 0.0;
  bool truth_valid = true;
  GpsTime t_meas;          // the sample's time of validity
  std::uint16_t sequence = 0;
};

class EpochRecorder {
 public:
  virtual ~EpochRecorder() = default;
  virtual void record(const EpochRecord& e) = 0;
  virtual void close() = 0;  // InputError when a write failed
};

class SampleRecorder {
 public:
  virtual ~SampleRecorder() = default;
  virtual void record(const SampleRecord& s) = 0;
  virtual void flush() {}  // live logs: out once per status interval
  virtual void close() = 0;
};

// truth.csv (rows only for epochs with truth) and gnss.csv, in `dir`.
std::unique_ptr<EpochRecorder> make_truth_csv(const std::filesystem::path& dir);
std::unique_ptr<EpochRecorder> make_gnss_csv(const std::filesystem::path& dir);
// imu.csv in `dir`, or the same rows on a byte port (the live IMU log).
std::unique_ptr<SampleRecorder> make_imu_csv(const std::filesystem::path& dir);
std::unique_ptr<SampleRecorder> make_imu_log(std::unique_ptr<transport::BytePort> port);

}  // namespace navemu
