#pragma once
// Streamed truth (UDP datagrams, a CSV replay) as the sensor models see it: samples are checked
// and counted, kept for a short window, and interpolated to any sensor epoch.
//
// Checks, in this order; a rejected sample is counted and never applied:
//   not finite   any NaN or infinity
//   out of range latitude outside [-90, 90], height outside [-1 km, 100 km], speed above
//                2 km/s, quaternion norm not within 1 +- 1e-3 (it is then normalised)
//   duplicate    same time as the newest accepted sample
//   backwards    earlier than the newest accepted sample
// Interpolation between the two samples around t (models/truth_interpolation.hpp): cubic
// Hermite for position with the velocities as derivatives, linear velocity, slerp attitude,
// linear f, w and temperature. After the newest sample: constant-velocity extrapolation of
// position, attitude held, for at most `max_extrapolation_s`; beyond that (or before the oldest
// sample) there is no truth and the sensors report its loss.

#include <cstdint>
#include <optional>
#include <vector>

#include "models/imu_kinematics.hpp"
#include "models/time.hpp"

namespace navemu {

enum class TruthVerdict { kAccepted, kNotFinite, kOutOfRange, kDuplicate, kBackwards };
const char* to_string(TruthVerdict v);

struct TruthCounters {
  std::uint64_t accepted = 0;
  std::uint64_t not_finite = 0;
  std::uint64_t out_of_range = 0;
  std::uint64_t duplicate = 0;
  std::uint64_t backwards = 0;
  std::uint64_t bad_framing = 0;  // datagrams that did not decode (CRC, magic, JSON); counted by
                                  // the source that decodes them
  std::uint64_t lost = 0;  // datagrams the kernel dropped unread (queue full; neither accepted
                           // nor rejected)
  std::uint64_t rejected() const {
    return not_finite + out_of_range + duplicate + backwards + bad_framing;
  }
};

class TruthBuffer {
 public:
  // `max_extrapolation_s` is the truth timeout: how long outputs continue from the last sample.
  // std::invalid_argument when either span is negative or not finite.
  explicit TruthBuffer(double max_extrapolation_s = 1.0, double window_s = 10.0);

  TruthVerdict push(ImuTruth sample);
  // The truth at t, or none when t lies before the oldest sample or more than the timeout after
  // the newest. Samples older than `window_s` before the newest are forgotten.
  std::optional<ImuTruth> at(GpsTime t) const;
  std::optional<GpsTime> newest_time() const;
  bool empty() const { return size() == 0; }
  // Samples held: those within `window_s` of the newest, and the one just before that span.
  std::size_t size() const { return samples_.size() - head_; }

  const TruthCounters& counters() const { return counters_; }
  TruthCounters& counters() { return counters_; }

 private:
  std::vector<ImuTruth> samples_;  // held from index head_ on, oldest first
  std::size_t head_ = 0;
  GpsTime max_extrapolation_;
  GpsTime window_;
  TruthCounters counters_;
};

}  // namespace navemu
