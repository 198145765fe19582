#pragma once
// Overlapping Allan deviation and the IEEE-Std-952 noise terms read from it.

#include <vector>

namespace navemu {

struct AllanPoint {
  double tau_s = 0.0;
  double adev = 0.0;          // in the unit of the samples
  long long clusters = 0;     // number of overlapping differences averaged
};

// Overlapping Allan deviation (IEEE Std 952-1997 Annex C; Riley, NIST SP 1065, eq. 11) of a
// rate signal sampled every dt_s, at cluster lengths m = 1..N/2 spaced `points_per_decade`
// per decade (log-spaced, unique integers).
std::vector<AllanPoint> overlapping_allan_deviation(const std::vector<double>& samples,
                                                    double dt_s, int points_per_decade = 10);

// The noise terms of a curve (IEEE Std 952-1997 Annex C):
//   white noise N (ARW/VRW): the -1/2 slope line's value at tau = 1 s;
//   bias instability B: the curve's minimum (flat floor) / 0.664, and the tau where it is;
//   random walk K (RRW/AccRW): the +1/2 slope line's value at tau = 3 s, when the curve rises.
struct AllanFit {
  double white_density = 0.0;      // unit/sqrt(Hz), e.g. rad/s/sqrt(Hz)
  double bias_instability = 0.0;   // unit, e.g. rad/s
  double bias_instability_tau_s = 0.0;
  double random_walk = 0.0;        // unit*sqrt(Hz), e.g. rad/s^2/sqrt(Hz); 0 when not seen
};
AllanFit fit_allan(const std::vector<AllanPoint>& curve);

}  // namespace navemu
