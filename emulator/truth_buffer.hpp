#pragma once
// Streamed truth (UDP datagrams, a CSV replay) as the sensor models see it: samples are checked
// and counted, kept for a short window, and interpolated to any sensor epoch.
//
// Checks, in this order; a rejected sample is counted and never applied:
//   not finite   any NaN or infinity
//   out of range latitude outside [-90, 90], height outside [-1 km, 100 km], speed above
//                2 km/s, quaternion norm not within 1 +- 1e-3 (it is then normalised)
//   duplicate    same time as the newest accepted sample
//   backwards    earlier than the newest accepted sample or, when the scenario clock is given
//                (real time), more than max_jump_s behind the clock
//   future       more than max_jump_s after the scenario clock when it is given (a stream may
//                resume after a pause of any length), otherwise after the newest accepted sample
// Re-synchronisation: a stream that really jumped (a simulator reset, a clock stepped by an
// hour) sends samples that are all backwards or future, but consistent with each other. After
// `resync_samples` consecutive such samples, each after the one before by at most max_jump_s,
// the stream is re-synchronised: the held samples are dropped, and from the last of them on
// every sample's time is shifted by one offset so that the stream continues where the
// scenario is (onto the scenario clock when it is given; otherwise one step of the new stream
// after the newest sample held before). That sample is accepted and counted as a resync; the
// ones before it stay rejected. An accepted sample in between starts the count again.
// Interpolation between the two samples around t (models/truth_interpolation.hpp): cubic
// Hermite for position with the velocities as derivatives, linear velocity, slerp attitude,
// linear f, w and temperature. After the newest sample: constant-velocity extrapolation of
// position, attitude held, for at most `timeout_s`; beyond that (or before the oldest sample)
// there is no truth and the sensors report its loss.

#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include "models/imu_kinematics.hpp"
#include "core/time.hpp"

namespace navemu {

enum class TruthVerdict { kAccepted, kNotFinite, kOutOfRange, kDuplicate, kBackwards, kFuture, kResync };
const char* to_string(TruthVerdict v);

struct TruthCounters {
  std::uint64_t accepted = 0;  // applied, including the samples that re-synchronised
  std::uint64_t not_finite = 0;
  std::uint64_t out_of_range = 0;
  std::uint64_t duplicate = 0;
  std::uint64_t backwards = 0;
  std::uint64_t future = 0;
  std::uint64_t bad_framing = 0;  // datagrams that did not decode (CRC, magic, JSON); counted by
                                  // the source that decodes them
  std::uint64_t resync = 0;  // re-synchronisations (each also one accepted sample)
  std::uint64_t lost = 0;  // datagrams the kernel dropped unread (queue full; neither accepted
                           // nor rejected)
  std::uint64_t rejected() const {
    return not_finite + out_of_range + duplicate + backwards + future + bad_framing;
  }
};

struct TruthStreamLimits {
  double timeout_s = 1.0;    // extrapolation past the newest sample; then no truth
  double window_s = 10.0;    // samples older than this before the newest are forgotten
  // A sample further ahead than this is an outlier (future); infinity: no limit and no
  // re-synchronisation (times must only increase).
  double max_jump_s = std::numeric_limits<double>::infinity();
  int resync_samples = 3;    // consecutive consistent outliers that re-synchronise (>= 2)
};

// The last re-synchronisation: how far the stream had jumped and how its times now map.
struct TruthResync {
  GpsTime reference;        // what the jump is measured from: the scenario clock when given,
                            // otherwise the newest sample held before
  bool against_clock = false;
  std::int64_t jump_ns = 0;    // the re-synchronising sample's time (as mapped before) minus reference
  std::int64_t offset_ns = 0;  // added to every sample's stamp from then on
};

class TruthBuffer {
 public:
  // `max_extrapolation_s` is the truth timeout: how long outputs continue from the last sample.
  // std::invalid_argument when either span is negative or not finite.
  explicit TruthBuffer(double max_extrapolation_s = 1.0, double window_s = 10.0);
  // std::invalid_argument for spans that are negative or not finite, or resync_samples < 2.
  explicit TruthBuffer(const TruthStreamLimits& limits);

  // `clock`: the scenario time now, when the stream is expected to follow it (real time).
  TruthVerdict push(ImuTruth sample, std::optional<GpsTime> clock = std::nullopt);
  // The truth at t, or none when t lies before the oldest sample or more than the timeout after
  // the newest. Samples older than `window_s` before the newest are forgotten.
  std::optional<ImuTruth> at(GpsTime t) const;
  std::optional<GpsTime> newest_time() const;
  bool empty() const { return size() == 0; }
  // Samples held: those within `window_s` of the newest, and the one just before that span.
  std::size_t size() const { return samples_.size() - head_; }
  const std::optional<TruthResync>& last_resync() const { return last_resync_; }

  const TruthCounters& counters() const { return counters_; }
  TruthCounters& counters() { return counters_; }

 private:
  TruthVerdict reject_in_time(TruthVerdict verdict, ImuTruth& sample, std::optional<GpsTime> clock);
  void accept(ImuTruth sample);

  std::vector<ImuTruth> samples_;  // held from index head_ on, oldest first
  std::size_t head_ = 0;
  GpsTime max_extrapolation_;
  GpsTime window_;
  GpsTime max_jump_;
  int resync_samples_ = 3;
  std::int64_t offset_ns_ = 0;  // added to every stamp (changed by re-synchronisation)
  // The run of consecutive outliers that may re-synchronise: its length and its newest time.
  int outlier_run_ = 0;
  GpsTime outlier_newest_;
  GpsTime outlier_step_;
  std::optional<TruthResync> last_resync_;
  TruthCounters counters_;
};

}  // namespace navemu
