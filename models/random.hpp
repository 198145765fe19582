#pragma once
// Explicit, reproducible randomness (../shared/DESIGN.md): one stream per error term and
// satellite, seeded from the scenario seed and a stable stream id. The engine is
// std::mt19937_64, whose output the C++ standard specifies exactly; the uniform and normal
// samplers are our own, so the same seed gives the same numbers on every compiler.

#include <cstdint>
#include <random>
#include <string_view>

namespace navemu {

// A stable 64-bit id for a named stream and an index (e.g. "iono", PRN 12): FNV-1a of the
// name, mixed with the index. Never changes between versions, so seeds stay meaningful.
std::uint64_t stream_id(std::string_view name, std::int64_t index = 0);

class RandomStream {
 public:
  RandomStream(std::uint64_t scenario_seed, std::uint64_t id);

  // Uniform in [0, 1) with 53 random bits.
  double uniform();
  // Standard normal N(0, 1), Marsaglia's polar method.
  double normal();

 private:
  std::mt19937_64 engine_;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

// The transition of a first-order Gauss-Markov step of length dt_s for a correlation time
// tau_s: phi = exp(-dt / tau) and sqrt(1 - phi^2). Processes of one correlation time stepped by
// the same dt (every satellite's processes of a kind, in an epoch) share it; `at` refreshes it
// only when dt or tau differs from the last (keyed exactly by both).
struct GaussMarkovTransition {
  double dt_s = -1.0;
  double tau_s = 0.0;
  double phi = 0.0;
  double sqrt_one_minus_phi2 = 0.0;
  const GaussMarkovTransition& at(double step_dt_s, double step_tau_s);
};

// First-order Gauss-Markov process with stationary standard deviation `sigma` and correlation
// time `tau_s`, advanced with its exact discretisation (e.g. Brown & Hwang, Introduction to
// Random Signals and Applied Kalman Filtering, 4th ed., 2.9):
//   x_k = phi x_(k-1) + w_k,  phi = exp(-dt / tau),  Var(w_k) = sigma^2 (1 - phi^2).
// Starts from a draw of the stationary distribution, so every epoch has variance sigma^2.
class GaussMarkov {
 public:
  GaussMarkov() = default;
  GaussMarkov(double sigma, double tau_s, RandomStream& rng);
  double step(double dt_s, RandomStream& rng);
  // The same with a transition computed for this process's tau_s (shared by processes).
  double step(const GaussMarkovTransition& tr, RandomStream& rng);
  double value() const { return x_; }
  double sigma() const { return sigma_; }
  double tau_s() const { return tau_s_; }

 private:
  double sigma_ = 0.0;
  double tau_s_ = 1.0;
  double x_ = 0.0;
  // The transition of the last step length (steps usually repeat it).
  GaussMarkovTransition last_;
};

// A first-order Gauss-Markov process drawn at knots `knot_s` apart and linearly interpolated
// in between: its variance at the knots (a little less between them) and its correlation over
// times longer than the spacing, but smooth within it, as slowly varying physical errors are.
// (A first-order process is a random walk at short times, its change over dt having the sigma
// sqrt(2 dt / tau): for tau = 30 min 3 % of its sigma every second, which a carrier-smoothed
// fix shows as jitter that real receivers do not have.) The first call anchors the knots.
class InterpolatedGaussMarkov {
 public:
  InterpolatedGaussMarkov() = default;
  InterpolatedGaussMarkov(double sigma, double tau_s, double knot_s, RandomStream& rng)
      : gm_(sigma, tau_s, rng), knot_s_(knot_s), x0_(gm_.value()), x1_(x0_), value_(x0_) {}
  // The value at t_s; calls come in increasing time.
  double at(double t_s, RandomStream& rng);
  double value() const { return value_; }

 private:
  GaussMarkov gm_;
  double knot_s_ = 1.0;
  bool anchored_ = false;
  double t_knot_s_ = 0.0;  // of x0_; x1_ is one knot later
  double x0_ = 0.0, x1_ = 0.0, value_ = 0.0;
};

}  // namespace navemu
