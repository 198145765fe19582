#include "emulator/truth_buffer.hpp"

#include <algorithm>
#include <cmath>
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
  }
  return "?";
}

TruthBuffer::TruthBuffer(double max_extrapolation_s, double window_s)
    : max_extrapolation_(span(max_extrapolation_s, "max_extrapolation_s")),
      window_(span(window_s, "window_s")) {}

TruthVerdict TruthBuffer::push(ImuTruth sample) {
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
  if (!empty()) {
    const GpsTime newest = samples_.back().t;
    if (sample.t == newest) {
      ++counters_.duplicate;
      return TruthVerdict::kDuplicate;
    }
    if (sample.t < newest) {
      ++counters_.backwards;
      return TruthVerdict::kBackwards;
    }
  }
  sample.q_ned_from_body.coeffs() /= q_norm;
  samples_.push_back(std::move(sample));
  ++counters_.accepted;

  // Forget what the window no longer needs: the oldest sample goes once the next one is itself
  // at or before the window's start, so any instant inside the window stays interpolable.
  const GpsTime window_start{samples_.back().t.ns - window_.ns};
  while (size() > 2 && samples_[head_ + 1].t <= window_start) ++head_;
  // Forgotten samples are removed in bulk once they are the larger part; the vector keeps its
  // capacity, so a steady stream stops allocating once the window is full.
  if (head_ > samples_.size() / 2) {
    samples_.erase(samples_.begin(), samples_.begin() + static_cast<std::ptrdiff_t>(head_));
    head_ = 0;
  }
  return TruthVerdict::kAccepted;
}

std::optional<ImuTruth> TruthBuffer::at(GpsTime t) const {
  const std::span<const ImuTruth> held(samples_.data() + head_, size());
  if (held.empty() || t < held.front().t) return std::nullopt;
  const ImuTruth& newest = held.back();
  if (t >= newest.t) {
    if (t.ns - newest.t.ns > max_extrapolation_.ns) return std::nullopt;
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
