#include "emulator/truth_buffer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>

#include "models/truth_interpolation.hpp"

namespace navemu {

namespace {

constexpr double kMinHeight_m = -1'000.0;
constexpr double kMaxHeight_m = 100'000.0;
constexpr double kMaxSpeed_mps = 2'000.0;
constexpr double kQuatNormTolerance = 1e-3;

bool finite(const Vec3& v) { return v.allFinite(); }

bool all_finite(const ImuTruth& s) {
  return std::isfinite(s.position.lat_deg) && std::isfinite(s.position.lon_deg) &&
         std::isfinite(s.position.h_m) && finite(s.v_ned_mps) &&
         s.q_ned_from_body.coeffs().allFinite() && (!s.f_body_mps2 || finite(*s.f_body_mps2)) &&
         (!s.w_ib_body_radps || finite(*s.w_ib_body_radps)) &&
         (!s.temperature_c || std::isfinite(*s.temperature_c));
}

// a + b, held at the ends of the int64 range: datagram times may be anything.
std::int64_t saturating_add(std::int64_t a, std::int64_t b) {
  std::int64_t r = 0;
  if (!__builtin_add_overflow(a, b, &r)) return r;
  return b > 0 ? std::numeric_limits<std::int64_t>::max() : std::numeric_limits<std::int64_t>::min();
}

GpsTime span(double seconds, const char* name) {
  if (!(std::isfinite(seconds) && seconds >= 0.0))
    throw std::invalid_argument(std::string("TruthBuffer: ") + name +
                                " must be finite and not negative");
  return GpsTime::from_seconds(seconds);
}

}  // namespace

const char* to_string(TruthVerdict v) {
  switch (v) {
    case TruthVerdict::kAccepted: return "accepted";
    case TruthVerdict::kNotFinite: return "not finite";
    case TruthVerdict::kOutOfRange: return "out of range";
    case TruthVerdict::kDuplicate: return "duplicate";
    case TruthVerdict::kBackwards: return "backwards";
    case TruthVerdict::kFuture: return "future";
    case TruthVerdict::kResync: return "resync";
  }
  return "?";
}

TruthBuffer::TruthBuffer(double max_extrapolation_s, double window_s)
    : TruthBuffer(TruthStreamLimits{max_extrapolation_s, window_s}) {}

TruthBuffer::TruthBuffer(const TruthStreamLimits& limits)
    : max_extrapolation_(span(limits.timeout_s, "timeout_s")),
      window_(span(limits.window_s, "window_s")),
      max_jump_(limits.max_jump_s == std::numeric_limits<double>::infinity()
                    ? GpsTime{std::numeric_limits<std::int64_t>::max()}
                    : span(limits.max_jump_s, "max_jump_s")),
      resync_samples_(limits.resync_samples) {
  if (resync_samples_ < 2) throw std::invalid_argument("TruthBuffer: resync_samples must be at least 2");
}

TruthVerdict TruthBuffer::push(ImuTruth sample, std::optional<GpsTime> clock) {
  // The checks in the documented order; the first that fails decides the verdict.
  if (!all_finite(sample)) {
    ++counters_.not_finite;
    return TruthVerdict::kNotFinite;
  }
  const double q_norm = sample.q_ned_from_body.norm();
  if (std::abs(sample.position.lat_deg) > 90.0 || sample.position.h_m < kMinHeight_m ||
      sample.position.h_m > kMaxHeight_m || sample.v_ned_mps.norm() > kMaxSpeed_mps ||
      !(std::abs(q_norm - 1.0) <= kQuatNormTolerance)) {
    ++counters_.out_of_range;
    return TruthVerdict::kOutOfRange;
  }
  sample.q_ned_from_body.coeffs() /= q_norm;
  sample.t = GpsTime{saturating_add(sample.t.ns, offset_ns_)};
  TruthVerdict in_time = TruthVerdict::kAccepted;
  if (!empty()) {
    const GpsTime newest = samples_.back().t;
    if (sample.t == newest) {
      ++counters_.duplicate;
      return TruthVerdict::kDuplicate;
    }
    if (sample.t < newest) in_time = TruthVerdict::kBackwards;
    // Against the clock when there is one: a stream may resume after a pause of any length.
    else if (!clock && sample.t.ns > saturating_add(newest.ns, max_jump_.ns)) in_time = TruthVerdict::kFuture;
  }
  if (in_time == TruthVerdict::kAccepted && clock) {
    if (sample.t.ns > saturating_add(clock->ns, max_jump_.ns)) in_time = TruthVerdict::kFuture;
    else if (sample.t.ns < saturating_add(clock->ns, -max_jump_.ns)) in_time = TruthVerdict::kBackwards;
  }
  if (in_time != TruthVerdict::kAccepted) return reject_in_time(in_time, sample, clock);
  outlier_run_ = 0;
  accept(std::move(sample));
  return TruthVerdict::kAccepted;
}

TruthVerdict TruthBuffer::reject_in_time(TruthVerdict verdict, ImuTruth& sample,
                                         std::optional<GpsTime> clock) {
  // Does it continue the run of outliers (later than the last one, by at most max_jump)?
  if (outlier_run_ > 0 && sample.t > outlier_newest_ &&
      sample.t.ns <= saturating_add(outlier_newest_.ns, max_jump_.ns)) {
    outlier_step_ = GpsTime{sample.t.ns - outlier_newest_.ns};
    ++outlier_run_;
  } else {
    outlier_run_ = 1;
  }
  outlier_newest_ = sample.t;
  const bool limited = max_jump_.ns != std::numeric_limits<std::int64_t>::max();
  if (outlier_run_ < resync_samples_ || !limited) {
    ++(verdict == TruthVerdict::kFuture ? counters_.future : counters_.backwards);
    return verdict;
  }

  // Re-synchronise: this sample goes on from where the scenario is.
  TruthResync r;
  r.against_clock = clock.has_value();
  r.reference = clock ? *clock : samples_.back().t;  // without a clock, only a held sample makes outliers
  r.jump_ns = saturating_add(sample.t.ns, -r.reference.ns);
  const GpsTime mapped = clock ? *clock : GpsTime{saturating_add(r.reference.ns, outlier_step_.ns)};
  offset_ns_ = saturating_add(offset_ns_, saturating_add(mapped.ns, -sample.t.ns));
  r.offset_ns = offset_ns_;
  sample.t = mapped;
  samples_.clear();  // keeps its capacity
  head_ = 0;
  outlier_run_ = 0;
  last_resync_ = r;
  ++counters_.resync;
  accept(std::move(sample));
  return TruthVerdict::kResync;
}

void TruthBuffer::accept(ImuTruth sample) {
  samples_.push_back(std::move(sample));
  ++counters_.accepted;

  // Forget what the window no longer needs: the oldest sample goes once the next one is itself
  // at or before the window's start, so any instant inside the window stays interpolable.
  const GpsTime window_start{saturating_add(samples_.back().t.ns, -window_.ns)};
  while (size() > 2 && samples_[head_ + 1].t <= window_start) ++head_;
  // Forgotten samples are removed in bulk once they are the larger part; the vector keeps its
  // capacity, so a steady stream stops allocating once the window is full.
  if (head_ > samples_.size() / 2) {
    samples_.erase(samples_.begin(), samples_.begin() + static_cast<std::ptrdiff_t>(head_));
    head_ = 0;
  }
}

std::optional<ImuTruth> TruthBuffer::at(GpsTime t) const {
  const std::span<const ImuTruth> held(samples_.data() + head_, size());
  if (held.empty() || t < held.front().t) return std::nullopt;
  const ImuTruth& newest = held.back();
  if (t >= newest.t) {
    if (t.ns > saturating_add(newest.t.ns, max_extrapolation_.ns)) return std::nullopt;
    return extrapolate_truth(newest, t);
  }
  // The first sample after t; t lies in [*(it - 1), *it).
  const auto it = std::upper_bound(held.begin(), held.end(), t,
                                   [](GpsTime x, const ImuTruth& s) { return x < s.t; });
  return interpolate_truth(*(it - 1), *it, t);
}

std::optional<GpsTime> TruthBuffer::newest_time() const {
  if (empty()) return std::nullopt;
  return samples_.back().t;
}

}  // namespace navemu
