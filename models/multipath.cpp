#include "models/multipath.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "models/geodesy.hpp"
#include "models/tracking.hpp"

namespace navemu {

namespace {

constexpr double kPiExact = 3.14159265358979323846;

// Ideal BPSK autocorrelation, x in chips.
double tri(double x) {
  const double ax = std::abs(x);
  return ax < 1.0 ? 1.0 - ax : 0.0;
}

bool has_signal(const PathSignal& p) {
  return std::isfinite(p.delay_m) && std::isfinite(p.amplitude.real()) &&
         std::isfinite(p.amplitude.imag()) && std::abs(p.amplitude) > 0.0;
}

// Prompt correlator sum P(eps) = sum a_i R(eps - tau_i), eps and tau in chips.
std::complex<double> prompt(const std::vector<PathSignal>& paths, double eps_chips,
                            double chip_length_m) {
  std::complex<double> sum{0.0, 0.0};
  for (const PathSignal& p : paths) {
    if (!has_signal(p)) continue;
    sum += p.amplitude * tri(eps_chips - p.delay_m / chip_length_m);
  }
  return sum;
}

double wrap_pi(double a) {
  // Into (-pi, pi].
  a = std::remainder(a, 2.0 * kPiExact);
  return a <= -kPiExact ? a + 2.0 * kPiExact : a;
}

}  // namespace

// ---- Reflection coefficients -------------------------------------------------------------------

Fresnel fresnel(double relative_permittivity, double conductivity_spm, double grazing_rad,
                double wavelength_m) {
  // ITU-R P.527: eps = eps_r - j 60 lambda sigma; coefficients as documented in the header.
  const std::complex<double> eps{relative_permittivity,
                                 -60.0 * wavelength_m * conductivity_spm};
  const double psi = std::clamp(grazing_rad, 0.0, kPiExact / 2.0);
  const double s = std::sin(psi);
  const double c = std::cos(psi);
  const std::complex<double> root = std::sqrt(eps - c * c);
  Fresnel f;
  f.perp = (s - root) / (s + root);
  f.par = (eps * s - root) / (eps * s + root);
  f.co = 0.5 * (f.par + f.perp);
  f.cross = 0.5 * (f.par - f.perp);
  return f;
}

Fresnel fresnel_perfect_conductor() {
  Fresnel f;
  f.perp = {-1.0, 0.0};
  f.par = {1.0, 0.0};
  f.co = {0.0, 0.0};
  f.cross = {1.0, 0.0};
  return f;
}

// ---- Antenna -------------------------------------------------------------------------------------

AntennaPattern patch_antenna_pattern() {
  // Above the horizon the C/N0 model's table (one source for both); below it a straight fall
  // to the back lobe at the nadir.
  AntennaPattern a;
  a.rhcp_gain_db_by_el_deg = patch_antenna_gain_table();
  a.rhcp_gain_db_by_el_deg.insert(a.rhcp_gain_db_by_el_deg.begin(), {-90.0, -20.0});
  return a;
}

double antenna_gain_db(const AntennaPattern& a, double el_rad, bool lhcp) {
  const double rejection = lhcp ? a.lhcp_rejection_db : 0.0;
  const auto& t = a.rhcp_gain_db_by_el_deg;
  if (t.empty()) return -rejection;
  const double el_deg = el_rad * kRadToDeg;
  if (el_deg <= t.front().first) return t.front().second - rejection;
  if (el_deg >= t.back().first) return t.back().second - rejection;
  // First entry at or above el (el is strictly inside the table here).
  const auto hi = std::lower_bound(t.begin(), t.end(), el_deg,
                                   [](const std::pair<double, double>& e, double v) { return e.first < v; });
  const auto lo = hi - 1;
  const double span = hi->first - lo->first;
  const double f = span > 0.0 ? (el_deg - lo->first) / span : 1.0;
  return lo->second + f * (hi->second - lo->second) - rejection;
}

// ---- Code tracking ---------------------------------------------------------------------------------

std::optional<double> eml_tracking_error_m(const std::vector<PathSignal>& paths,
                                           double chip_spacing, double chip_length_m) {
  const double d = chip_spacing;
  if (!(d > 0.0) || !std::isfinite(d) || !(chip_length_m > 0.0)) return std::nullopt;

  double a_max = 0.0, a_sum = 0.0;
  for (const PathSignal& p : paths) {
    if (!has_signal(p)) continue;
    a_max = std::max(a_max, std::abs(p.amplitude));
    a_sum += std::abs(p.amplitude);
  }
  if (a_max <= 0.0) return std::nullopt;

  // P(eps) and Q(eps) (the early-minus-late sum) are piecewise linear: R(x) has slope changes
  // +1, -2, +1 at x = -1, 0, 1. Sweep the slope changes in order of eps, carrying P, Q and
  // their slopes; on each segment between corners N = Re(conj(P) Q) is the quadratic
  // c0 + c1 t + c2 t^2 (t from the segment's start).
  struct Corner {
    double x;
    std::complex<double> dp, dq;  // slope increments
  };
  thread_local std::vector<Corner> corners;
  corners.clear();
  for (const PathSignal& p : paths) {
    if (!has_signal(p)) continue;
    const double tau = p.delay_m / chip_length_m;
    const std::complex<double> a = p.amplitude;
    const std::complex<double> zero{0.0, 0.0};
    for (const auto& [off, w] : {std::pair{-1.0, 1.0}, std::pair{0.0, -2.0}, std::pair{1.0, 1.0}}) {
      corners.push_back({tau + off, w * a, zero});
      corners.push_back({tau + 0.5 * d + off, zero, w * a});   // early: R(x - d/2)
      corners.push_back({tau - 0.5 * d + off, zero, -w * a});  // late: -R(x + d/2)
    }
  }
  std::sort(corners.begin(), corners.end(),
            [](const Corner& l, const Corner& r) { return l.x < r.x; });

  struct Segment {
    double x0, h;
    double c0, c1, c2;
  };
  struct Sample {
    double x, n;
    std::size_t seg;  // the segment [x0, x0 + h] the sample starts or lies in
  };
  thread_local std::vector<Segment> segs;
  thread_local std::vector<Sample> s;
  segs.clear();
  s.clear();
  std::complex<double> P{0.0, 0.0}, Q{0.0, 0.0}, dP{0.0, 0.0}, dQ{0.0, 0.0};
  for (std::size_t k = 0; k < corners.size();) {
    const double x0 = corners[k].x;
    while (k < corners.size() && corners[k].x == x0) {
      dP += corners[k].dp;
      dQ += corners[k].dq;
      ++k;
    }
    const double h = k < corners.size() ? corners[k].x - x0 : 0.0;
    Segment g{x0, h, (std::conj(P) * Q).real(),
              (std::conj(P) * dQ + std::conj(dP) * Q).real(), (std::conj(dP) * dQ).real()};
    segs.push_back(g);
    const std::size_t gi = segs.size() - 1;
    s.push_back({x0, g.c0, gi});
    // The vertex inside the segment, so that N is monotonic between consecutive samples.
    if (g.c2 != 0.0) {
      const double t = -g.c1 / (2.0 * g.c2);
      if (t > 0.0 && t < h) s.push_back({x0 + t, g.c0 + t * (g.c1 + t * g.c2), gi});
    }
    P += dP * h;
    Q += dQ * h;
  }

  // Stable zeros: N goes from negative to positive, directly (bisection of the segment's
  // quadratic) or through a run of zero samples (a point zero or a neutral plateau: its middle).
  const double tol_n = 1e-12 * a_sum * a_sum;
  const double tol_p = 1e-9 * a_sum;
  auto sign = [&](double v) { return v > tol_n ? 1 : (v < -tol_n ? -1 : 0); };
  thread_local std::vector<std::pair<double, double>> zeros;  // (eps chips, |P|)
  zeros.clear();
  std::size_t last = s.size();  // last sample with a non-zero sign
  for (std::size_t k = 0; k < s.size(); ++k) {
    const int sk = sign(s[k].n);
    if (sk == 0) continue;
    if (sk > 0 && last < s.size() && sign(s[last].n) < 0) {
      double root = 0.0;
      if (last + 1 == k) {
        const Segment& g = segs[s[last].seg];
        auto n_at = [&g](double x) {
          const double t = x - g.x0;
          return g.c0 + t * (g.c1 + t * g.c2);
        };
        double lo = s[last].x, hi = s[k].x;
        for (int it = 0; it < 200; ++it) {
          const double mid = 0.5 * (lo + hi);
          if (mid <= lo || mid >= hi) break;
          if (n_at(mid) < 0.0) lo = mid; else hi = mid;
        }
        root = 0.5 * (lo + hi);
      } else {
        root = 0.5 * (s[last + 1].x + s[k - 1].x);
      }
      const double p_abs = std::abs(prompt(paths, root, chip_length_m));
      if (p_abs > tol_p) zeros.emplace_back(root, p_abs);
    }
    last = k;
  }
  if (zeros.empty()) return std::nullopt;

  // The zero nearest to the earliest significant path within its pull-in range.
  thread_local std::vector<double> significant;
  significant.clear();
  for (const PathSignal& p : paths)
    if (has_signal(p) && std::abs(p.amplitude) >= kEmlSignificantPathRatio * a_max)
      significant.push_back(p.delay_m / chip_length_m);
  std::sort(significant.begin(), significant.end());
  const double pull_in = 1.0 + 0.5 * d;
  for (double tau : significant) {
    const std::pair<double, double>* best = nullptr;
    for (const auto& z : zeros) {
      const double dist = std::abs(z.first - tau);
      if (dist > pull_in) continue;
      if (best == nullptr || dist < std::abs(best->first - tau)) best = &z;
    }
    if (best != nullptr) return best->first * chip_length_m;
  }
  const auto strongest = std::max_element(
      zeros.begin(), zeros.end(), [](const auto& a, const auto& b) { return a.second < b.second; });
  return strongest->first * chip_length_m;
}

double composite_power_db(const std::vector<PathSignal>& paths, double tracking_error_m,
                          double chip_length_m) {
  const double p = std::abs(prompt(paths, tracking_error_m / chip_length_m, chip_length_m));
  if (!(p > 0.0)) return kCompositePowerFloorDb;
  return std::max(20.0 * std::log10(p), kCompositePowerFloorDb);
}

double composite_phase_error_m(const std::vector<PathSignal>& paths, double tracking_error_m,
                               double wavelength_m, double chip_length_m) {
  const double eps = tracking_error_m / chip_length_m;
  std::complex<double> sum{0.0, 0.0};
  double ref_delay_m = 0.0, ref_mag = -1.0;
  for (const PathSignal& p : paths) {
    if (!has_signal(p)) continue;
    const std::complex<double> c = p.amplitude * tri(eps - p.delay_m / chip_length_m);
    sum += c;
    if (std::abs(c) > ref_mag) {
      ref_mag = std::abs(c);
      ref_delay_m = p.delay_m;
    }
  }
  if (!(std::abs(sum) > 0.0)) return 0.0;
  // The dominant path's propagation phase e^{-j 2 pi tau_k / lambda} taken out, its delay put
  // back as whole range: the same value modulo lambda as -arg(P) lambda / 2 pi.
  const double k = 2.0 * kPiExact / wavelength_m;
  const double ref_phase = std::fmod(ref_delay_m, wavelength_m) * k;
  const double residual = wrap_pi(std::arg(sum) + ref_phase);
  return ref_delay_m - residual / k;
}

// ---- The paper's rule ----------------------------------------------------------------------------

std::optional<double> paper_rule_delay_m(const std::vector<PathSignal>& paths, double cutoff_m) {
  const PathSignal* first = nullptr;
  const PathSignal* second = nullptr;
  const PathSignal* strongest = nullptr;
  for (const PathSignal& p : paths) {
    if (!has_signal(p)) continue;
    if (first == nullptr || p.delay_m < first->delay_m) {
      second = first;
      first = &p;
    } else if (second == nullptr || p.delay_m < second->delay_m) {
      second = &p;
    }
    const double a = std::abs(p.amplitude);
    if (strongest == nullptr || a > std::abs(strongest->amplitude) ||
        (a == std::abs(strongest->amplitude) && p.delay_m < strongest->delay_m))
      strongest = &p;
  }
  if (first == nullptr) return std::nullopt;
  if (second == nullptr || second->delay_m - first->delay_m < cutoff_m) return first->delay_m;
  return strongest->delay_m;
}

}  // namespace navemu
