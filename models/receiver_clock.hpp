#pragma once
// Receiver oscillator: a two-state (bias, drift) clock driven by white frequency noise and
// random-walk frequency noise, parameterised by the power-law coefficients h0 and h_-2 of
// its Allan variance (Brown & Hwang, 4th ed., 9.3; van Dierendonck 1996). The flicker term
// h_-1 has no finite-dimensional state and is left out, as in the two-state model.

#include "models/random.hpp"

namespace navemu {

struct ReceiverClockParams {
  // Allan variance coefficients: sigma_y^2(tau) = h0 / (2 tau) + 2 pi^2 h_-2 tau / 3.
  // Defaults: a typical TCXO (h0 = 2e-19, h_-2 = 2e-20; Brown & Hwang 4th ed. 9.3, p. 327,
  // table of typical oscillator Allan-variance parameters).
  double h0 = 2e-19;
  double h_minus2 = 2e-20;
  double initial_bias_s = 0.0;     // clock offset at the start
  double initial_drift_sps = 0.0;  // frequency offset at the start (s/s)
  // A part's start-up state drawn once from the clock's own stream, added to the two above
  // (0: not drawn): a bias uniform in +-initial_bias_max_s and a frequency offset with standard
  // deviation frequency_offset_sigma_sps (a free-running TCXO's, receiver profiles' `clock`).
  double initial_bias_max_s = 0.0;
  double frequency_offset_sigma_sps = 0.0;
};

class ReceiverClock {
 public:
  ReceiverClock(const ReceiverClockParams& p, RandomStream rng);
  // Advances by dt with the exact discrete process noise
  //   Q = [[Sf dt + Sg dt^3/3, Sg dt^2/2], [Sg dt^2/2, Sg dt]],  Sf = h0/2, Sg = 2 pi^2 h_-2.
  // dt <= 0 leaves the state unchanged.
  void step(double dt_s);
  double bias_s() const { return bias_s_; }
  double drift_sps() const { return drift_sps_; }

 private:
  ReceiverClockParams p_;
  RandomStream rng_;
  double bias_s_ = 0.0;
  double drift_sps_ = 0.0;
};

}  // namespace navemu
