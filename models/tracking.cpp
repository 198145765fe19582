#include "models/tracking.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "models/geodesy.hpp"

namespace navemu {

namespace {

constexpr double kTwoPi = 2.0 * 3.14159265358979323846;

// C/N0 from dB-Hz to a ratio in Hz.
double cn0_ratio_hz(double cn0_dbhz) { return std::pow(10.0, cn0_dbhz / 10.0); }

// The loops' noise from C/N0 as a ratio in Hz.
double dll_noise_from_ratio_m(double cn0, const TrackingParams& p) {
  // Kaplan & Hegarty 2nd ed. eq. 5.23 (noncoherent early-minus-late power, wide front end),
  // in chips, times the chip length.
  const double d = p.chip_spacing;
  const double squaring_loss = 1.0 + 2.0 / (p.integration_s * cn0 * (2.0 - d));
  return p.chip_length_m * std::sqrt(p.dll_bandwidth_hz * d / (2.0 * cn0) * squaring_loss);
}

double pll_noise_from_ratio_cycles(double cn0, const TrackingParams& p) {
  // Kaplan & Hegarty 2nd ed. 5.6.1.1, in cycles instead of degrees.
  const double squaring_loss = 1.0 + 1.0 / (2.0 * p.integration_s * cn0);
  return std::sqrt(p.pll_bandwidth_hz / cn0 * squaring_loss) / kTwoPi;
}

double fll_noise_from_ratio_hz(double cn0, const TrackingParams& p) {
  // Kaplan & Hegarty 2nd ed. 5.6.2, with F = 1 (high C/N0).
  constexpr double kF = 1.0;
  const double t = p.integration_s;
  const double squaring_loss = 1.0 + 1.0 / (t * cn0);
  return std::sqrt(4.0 * kF * p.fll_bandwidth_hz / cn0 * squaring_loss) / (kTwoPi * t);
}

}  // namespace

double dll_noise_m(double cn0_dbhz, const TrackingParams& p) {
  return dll_noise_from_ratio_m(cn0_ratio_hz(cn0_dbhz), p);
}

double pll_noise_cycles(double cn0_dbhz, const TrackingParams& p) {
  return pll_noise_from_ratio_cycles(cn0_ratio_hz(cn0_dbhz), p);
}

double fll_noise_hz(double cn0_dbhz, const TrackingParams& p) {
  return fll_noise_from_ratio_hz(cn0_ratio_hz(cn0_dbhz), p);
}

TrackingNoise tracking_noise(double cn0_dbhz, const TrackingParams& p) {
  const double cn0 = cn0_ratio_hz(cn0_dbhz);
  return {dll_noise_from_ratio_m(cn0, p), pll_noise_from_ratio_cycles(cn0, p),
          fll_noise_from_ratio_hz(cn0, p)};
}

double cn0_dbhz(const Cn0Model& m, double el_rad) {
  const auto& table = m.gain_db_by_el_deg;
  if (table.empty()) return m.zenith_dbhz;
  const double el_deg = el_rad * kRadToDeg;
  // Held at the end values outside the table.
  if (el_deg <= table.front().first) return m.zenith_dbhz + table.front().second;
  if (el_deg >= table.back().first) return m.zenith_dbhz + table.back().second;
  for (std::size_t i = 1; i < table.size(); ++i) {
    const auto& [e1, g1] = table[i];
    if (el_deg > e1) continue;
    const auto& [e0, g0] = table[i - 1];
    const double span = e1 - e0;
    const double f = span > 0.0 ? (el_deg - e0) / span : 1.0;
    return m.zenith_dbhz + g0 + f * (g1 - g0);
  }
  return m.zenith_dbhz + table.back().second;  // not reached for a sorted table
}

CarrierArcs::Arc CarrierArcs::update(SatId sat, double t_s, bool tracked) {
  State& s = state_.try_emplace(sat).first;
  if (!tracked) {
    s.active = false;
    s.last_s = t_s;
    return Arc{0.0, 0.0, false};
  }
  const double gap = t_s - s.last_s;
  const bool new_arc = !s.active || gap > max_gap_s_ || gap < 0.0;
  if (new_arc) {
    // Arc k of this satellite draws its ambiguity from its own stream, so it does not depend on
    // the history of other satellites. Uniform on the 2e6 + 1 integers -1e6 ... 1e6.
    const std::int64_t arc_index = static_cast<std::int64_t>(sat.stream_index()) * 100000 + s.arcs;
    RandomStream rng(seed_, stream_id("carrier_arc", arc_index));
    constexpr double kMax = 1e6;
    s.ambiguity = std::floor(rng.uniform() * (2.0 * kMax + 1.0)) - kMax;
    s.arcs += 1;
    s.start_s = t_s;
    s.active = true;
  }
  s.last_s = t_s;
  return Arc{s.ambiguity, t_s - s.start_s, new_arc};
}

double CarrierSmoother::update(double t_s, double code_m, double carrier_m, bool new_arc, double window_s,
                               double multipath_tau_s) {
  const double dt = t_s - last_t_s_;
  // The code against the smoothed code carried forward by the carrier.
  const double predicted_m = smoothed_m_ + carrier_m - carrier_m_;
  const bool restart = !started_ || new_arc || dt <= 0.0 || dt > window_s ||
                       std::abs(code_m - predicted_m) > kMaxStepDisagreement_m;
  if (restart) {
    started_ = true;
    epochs_ = 1.0;
    smoothed_m_ = code_m;
    v_noise_ = v_multipath_ = c_multipath_ = 1.0;
  } else {
    epochs_ += 1.0;
    const double w = std::max(1.0 / epochs_, dt / window_s);
    const double a = std::exp(-dt / multipath_tau_s);
    smoothed_m_ = w * code_m + (1.0 - w) * predicted_m;
    v_noise_ = w * w + (1.0 - w) * (1.0 - w) * v_noise_;
    v_multipath_ = w * w + (1.0 - w) * (1.0 - w) * v_multipath_ + 2.0 * w * (1.0 - w) * a * c_multipath_;
    c_multipath_ = w + (1.0 - w) * a * c_multipath_;
  }
  last_t_s_ = t_s;
  carrier_m_ = carrier_m;
  return smoothed_m_;
}

std::vector<std::pair<double, double>> patch_antenna_gain_table() {
  return {{0.0, -13.0}, {5.0, -10.0}, {10.0, -8.0}, {20.0, -5.0}, {30.0, -3.5},
          {45.0, -2.0}, {60.0, -1.0}, {75.0, -0.3}, {90.0, 0.0}};
}

}  // namespace navemu
