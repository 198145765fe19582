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

// The Allan deviation of a white rate noise of density N at tau: N / sqrt(tau); and of a rate
// random walk of strength K: K sqrt(tau / 3) (IEEE Std 952-1997 Table C.1).
double allan_white(double density, double tau_s);
double allan_random_walk(double k, double tau_s);

// Flicker floor factor of IEEE Std 952-1997 C.1.3: the flat part of the curve is
// sqrt(2 ln 2 / pi) B = 0.664 B.
inline constexpr double kAllanBiasInstabilityFactor = 0.6642824702679837;

// Datasheet units of the fitted terms. The SI terms convert as
//   gyro ARW    [deg/sqrt(h)]   = N [rad/s/sqrt(Hz) = rad/s^0.5] * (180/pi) * sqrt(3600 s/h)
//   gyro BI     [deg/h]         = B [rad/s] * (180/pi) * 3600 s/h
//   gyro RRW    [deg/h/sqrt(h)] = K [rad/s^2/sqrt(Hz) = rad/s^1.5] * (180/pi) * (3600 s/h)^1.5
//   accel VRW   [m/s/sqrt(h)]   = N [m/s^2/sqrt(Hz) = m/s^1.5] * sqrt(3600 s/h)
//   accel BI    [mg]            = B [m/s^2] / 9.80665 m/s^2 * 1000   (standard gravity)
//   accel AccRW [m/s/h^1.5]     = K [m/s^3/sqrt(Hz) = m/s^2.5] * (3600 s/h)^1.5
inline constexpr double kAllanDegPerRad = 57.295779513082320876798;
inline constexpr double kAllanStandardGravity_mps2 = 9.80665;
inline constexpr double arw_deg_per_sqrt_h(double n_radps_per_sqrt_hz) {
  return n_radps_per_sqrt_hz * kAllanDegPerRad * 60.0;
}
inline constexpr double gyro_bias_instability_deg_per_h(double b_radps) {
  return b_radps * kAllanDegPerRad * 3600.0;
}
inline constexpr double rrw_deg_per_h_per_sqrt_h(double k_radps2_per_sqrt_hz) {
  return k_radps2_per_sqrt_hz * kAllanDegPerRad * 216000.0;
}
inline constexpr double vrw_mps_per_sqrt_h(double n_mps2_per_sqrt_hz) {
  return n_mps2_per_sqrt_hz * 60.0;
}
inline constexpr double accel_bias_instability_mg(double b_mps2) {
  return b_mps2 / kAllanStandardGravity_mps2 * 1000.0;
}
inline constexpr double accrw_mps_per_h_1p5(double k_mps3_per_sqrt_hz) {
  return k_mps3_per_sqrt_hz * 216000.0;
}

}  // namespace navemu
