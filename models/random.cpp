#include "models/random.hpp"

#include <cmath>

namespace navemu {

namespace {

// SplitMix64 finaliser (Steele, Lea, Flood 2014): decorrelates nearby seeds and ids.
std::uint64_t mix64(std::uint64_t z) {
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

}  // namespace

std::uint64_t stream_id(std::string_view name, std::int64_t index) {
  std::uint64_t h = 0xcbf29ce484222325ULL;  // FNV-1a 64-bit offset basis
  for (char c : name) {
    h ^= static_cast<unsigned char>(c);
    h *= 0x100000001b3ULL;  // FNV prime
  }
  return mix64(h ^ mix64(static_cast<std::uint64_t>(index)));
}

RandomStream::RandomStream(std::uint64_t scenario_seed, std::uint64_t id)
    : engine_(mix64(scenario_seed) ^ mix64(id + 0x632be59bd9b4e019ULL)) {}

double RandomStream::uniform() {
  return static_cast<double>(engine_() >> 11) * 0x1.0p-53;
}

double RandomStream::normal() {
  if (has_spare_) {
    has_spare_ = false;
    return spare_;
  }
  // Marsaglia polar method: a point uniform in the unit disc gives two independent normals.
  double u, v, s;
  do {
    u = 2.0 * uniform() - 1.0;
    v = 2.0 * uniform() - 1.0;
    s = u * u + v * v;
  } while (s >= 1.0 || s == 0.0);
  const double f = std::sqrt(-2.0 * std::log(s) / s);
  spare_ = v * f;
  has_spare_ = true;
  return u * f;
}

GaussMarkov::GaussMarkov(double sigma, double tau_s, RandomStream& rng)
    : sigma_(sigma), tau_s_(tau_s), x_(sigma * rng.normal()) {}

const GaussMarkovTransition& GaussMarkovTransition::at(double step_dt_s, double step_tau_s) {
  if (step_dt_s != dt_s || step_tau_s != tau_s) {
    dt_s = step_dt_s;
    tau_s = step_tau_s;
    phi = std::exp(-step_dt_s / step_tau_s);
    sqrt_one_minus_phi2 = std::sqrt(1.0 - phi * phi);
  }
  return *this;
}

double GaussMarkov::step(double dt_s, RandomStream& rng) {
  return step(last_.at(dt_s, tau_s_), rng);
}

double GaussMarkov::step(const GaussMarkovTransition& tr, RandomStream& rng) {
  x_ = tr.phi * x_ + sigma_ * tr.sqrt_one_minus_phi2 * rng.normal();
  return x_;
}

double InterpolatedGaussMarkov::at(double t_s, RandomStream& rng) {
  if (!anchored_) {
    anchored_ = true;
    t_knot_s_ = t_s;
    x1_ = gm_.step(knot_s_, rng);
  }
  if (const double behind = std::floor((t_s - t_knot_s_) / knot_s_); behind >= 1.0) {
    // The knots passed: x0 moves to the last one at or before t_s (one step over any gap).
    if (behind >= 2.0) gm_.step((behind - 1.0) * knot_s_, rng);
    x0_ = gm_.value();
    x1_ = gm_.step(knot_s_, rng);
    t_knot_s_ += behind * knot_s_;
  }
  value_ = x0_ + (x1_ - x0_) * (t_s - t_knot_s_) / knot_s_;
  return value_;
}

}  // namespace navemu
