#include "models/receiver_clock.hpp"

#include <algorithm>
#include <cmath>

namespace navemu {

namespace {
constexpr double kPiClock = 3.14159265358979323846;
}  // namespace

ReceiverClock::ReceiverClock(const ReceiverClockParams& p, RandomStream rng)
    : p_(p), rng_(rng), bias_s_(p.initial_bias_s), drift_sps_(p.initial_drift_sps) {
  if (p.initial_bias_max_s > 0.0) bias_s_ += p.initial_bias_max_s * (2.0 * rng_.uniform() - 1.0);
  if (p.frequency_offset_sigma_sps > 0.0) drift_sps_ += p.frequency_offset_sigma_sps * rng_.normal();
}

void ReceiverClock::step(double dt_s) {
  if (!(dt_s > 0.0)) return;
  // White-noise spectral densities of the two driving processes (Brown & Hwang 4th ed. 9.3):
  // white frequency noise on the bias, Sf = h0 / 2 (s^2/s), and random-walk frequency noise on
  // the drift, Sg = 2 pi^2 h_-2 (1/s). With them the Allan variance of the fractional
  // frequency is h0 / (2 tau) + 2 pi^2 h_-2 tau / 3.
  const double sf = p_.h0 / 2.0;
  const double sg = 2.0 * kPiClock * kPiClock * p_.h_minus2;
  const double dt2 = dt_s * dt_s;
  const double q11 = sf * dt_s + sg * dt2 * dt_s / 3.0;
  const double q12 = sg * dt2 / 2.0;
  const double q22 = sg * dt_s;

  // Correlated process noise w = L n, n ~ N(0, I), with L the lower Cholesky factor of Q:
  //   L11 = sqrt(q11), L21 = q12 / L11, L22 = sqrt(q22 - L21^2).
  // Both normals are drawn on every step (even when Q is zero) so that the stream position
  // depends only on the number of steps.
  const double n1 = rng_.normal();
  const double n2 = rng_.normal();
  const double l11 = std::sqrt(std::max(q11, 0.0));
  const double l21 = l11 > 0.0 ? q12 / l11 : 0.0;
  const double l22 = std::sqrt(std::max(q22 - l21 * l21, 0.0));
  const double w_bias = l11 * n1;
  const double w_drift = l21 * n1 + l22 * n2;

  // State transition Phi = [[1, dt], [0, 1]].
  bias_s_ += drift_sps_ * dt_s + w_bias;
  drift_sps_ += w_drift;
}

}  // namespace navemu
