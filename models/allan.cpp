#include "models/allan.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <stdexcept>

namespace navemu {

// Overlapping Allan variance of rate (frequency) data y_0..y_(M-1) through its integral, the
// "phase" theta_k = dt * sum_(j<k) (y_j - mean), k = 0..M (NIST SP 1065 section 5.2.4: phase
// from frequency data; the mean is removed first, which leaves the variance unchanged and
// keeps the sums small). With tau = m dt, eq. 11 of NIST SP 1065 (IEEE Std 952-1997 C.2):
//   sigma^2(tau) = 1 / (2 tau^2 (M + 1 - 2m)) * sum_(k=0)^(M-2m) (theta_(k+2m) - 2 theta_(k+m)
//                                                                  + theta_k)^2,
// which equals eq. 10 (the average of all overlapping differences of adjacent m-sample means).
// Each tau costs O(M); m runs over the unique integers round(10^(i / points_per_decade)) up to
// floor((M - 1) / 2), so that at least two differences are averaged.
std::vector<AllanPoint> overlapping_allan_deviation(const std::vector<double>& samples,
                                                    double dt_s, int points_per_decade) {
  if (!(dt_s > 0.0) || !std::isfinite(dt_s))
    throw std::invalid_argument("overlapping_allan_deviation: dt_s must be positive");
  if (points_per_decade < 1)
    throw std::invalid_argument("overlapping_allan_deviation: points_per_decade must be >= 1");
  std::vector<AllanPoint> out;
  const std::size_t n = samples.size();
  if (n < 3) return out;

  long double mean = 0.0L;
  for (double y : samples) mean += y;
  mean /= static_cast<long double>(n);

  std::vector<double> theta(n + 1);
  theta[0] = 0.0;
  long double acc = 0.0L;
  for (std::size_t k = 0; k < n; ++k) {
    acc += (static_cast<long double>(samples[k]) - mean) * dt_s;
    theta[k + 1] = static_cast<double>(acc);
  }

  const std::size_t m_max = (n - 1) / 2;
  std::size_t last_m = 0;
  for (int i = 0;; ++i) {
    const double m_real = std::pow(10.0, static_cast<double>(i) / points_per_decade);
    const auto m = static_cast<std::size_t>(std::llround(m_real));
    if (m > m_max) break;
    if (m == last_m) continue;
    last_m = m;
    const std::size_t count = n + 1 - 2 * m;
    const double* t0 = theta.data();
    const double* t1 = theta.data() + m;
    const double* t2 = theta.data() + 2 * m;
    double sum = 0.0;
    for (std::size_t k = 0; k < count; ++k) {
      const double d = t2[k] - 2.0 * t1[k] + t0[k];
      sum += d * d;
    }
    const double tau = static_cast<double>(m) * dt_s;
    const double var = sum / (2.0 * tau * tau * static_cast<double>(count));
    out.push_back({tau, std::sqrt(var), static_cast<long long>(count)});
  }
  return out;
}

double allan_white(double density, double tau_s) { return density / std::sqrt(tau_s); }

double allan_random_walk(double k, double tau_s) { return k * std::sqrt(tau_s / 3.0); }

namespace {

// The fit works on ln(tau), ln(adev) of the points it trusts.
struct LogPoint {
  double lt = 0.0;     // ln tau
  double la = 0.0;     // ln adev
  double slope = 0.0;  // local d ln(adev) / d ln(tau)
  double weight = 1.0; // inverse variance of la, up to a factor: N/m (1 without counts)
};

// A point is trusted when its estimate averages at least this many independent cluster pairs
// (about N/m): the relative uncertainty of the overlapping estimate is then below roughly
// 1/sqrt(10) (NIST SP 1065 section 5.3), so the local slopes below mean something.
constexpr double kMinIndependentClusters = 10.0;

// Half-width, in decades of tau, of the window over which the local slope is fitted.
constexpr double kSlopeHalfWindowDecades = 0.25;

// The number of independent clusters N/m of each point, inferred from `clusters` = N + 1 - 2m
// (what overlapping_allan_deviation stores): consecutive points give dt from
// clusters_i - clusters_j = 2 (tau_j - tau_i) / dt. Empty when the curve does not carry
// consistent counts (e.g. a curve read from a file); every point is then trusted.
std::vector<double> independent_clusters(const std::vector<AllanPoint>& curve) {
  if (curve.size() < 2) return {};
  for (const AllanPoint& p : curve)
    if (p.clusters <= 0) return {};
  const double dc = static_cast<double>(curve[0].clusters - curve[1].clusters);
  if (!(dc > 0.0)) return {};
  const double dt = 2.0 * (curve[1].tau_s - curve[0].tau_s) / dc;
  if (!(dt > 0.0)) return {};
  const double m0 = std::round(curve[0].tau_s / dt);
  const double n = static_cast<double>(curve[0].clusters) + 2.0 * m0 - 1.0;
  std::vector<double> out;
  out.reserve(curve.size());
  for (const AllanPoint& p : curve) out.push_back(n / std::max(1.0, std::round(p.tau_s / dt)));
  return out;
}

// Least-squares slope of ln(adev) on ln(tau) over the points within the window around each
// point (at least its neighbours).
void local_slopes(std::vector<LogPoint>& pts) {
  const double half = kSlopeHalfWindowDecades * std::log(10.0);
  const std::size_t n = pts.size();
  for (std::size_t i = 0; i < n; ++i) {
    std::size_t lo = i, hi = i;
    while (lo > 0 && pts[i].lt - pts[lo - 1].lt <= half) --lo;
    while (hi + 1 < n && pts[hi + 1].lt - pts[i].lt <= half) ++hi;
    if (lo == hi) {
      if (lo > 0) --lo;
      if (hi + 1 < n) ++hi;
    }
    if (lo == hi) {
      pts[i].slope = 0.0;
      continue;
    }
    double sx = 0, sy = 0;
    for (std::size_t j = lo; j <= hi; ++j) {
      sx += pts[j].lt;
      sy += pts[j].la;
    }
    const double cnt = static_cast<double>(hi - lo + 1);
    const double mx = sx / cnt, my = sy / cnt;
    double sxx = 0, sxy = 0;
    for (std::size_t j = lo; j <= hi; ++j) {
      sxx += (pts[j].lt - mx) * (pts[j].lt - mx);
      sxy += (pts[j].lt - mx) * (pts[j].la - my);
    }
    pts[i].slope = sxx > 0.0 ? sxy / sxx : 0.0;
  }
}

struct Run {
  std::size_t first = 0, last = 0;  // inclusive indices into the trusted points
};

// Maximal runs of consecutive points whose local slope is within `tol` of `target`.
std::vector<Run> slope_runs(const std::vector<LogPoint>& pts, double target, double tol) {
  std::vector<Run> runs;
  bool open = false;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const bool in = std::abs(pts[i].slope - target) <= tol;
    if (in && !open) runs.push_back({i, i});
    if (in) runs.back().last = i;
    open = in;
  }
  return runs;
}

// ln of the coefficient c of the line adev = c * tau^slope fitted (in the log domain, slope
// fixed) to the points of a run, each weighted by its inverse variance: the variance of
// ln(adev) goes as m/N (NIST SP 1065 section 5.3), so the weight is N/m.
double line_log_coefficient(const std::vector<LogPoint>& pts, const Run& r, double slope) {
  double s = 0.0, w = 0.0;
  for (std::size_t i = r.first; i <= r.last; ++i) {
    s += pts[i].weight * (pts[i].la - slope * pts[i].lt);
    w += pts[i].weight;
  }
  return s / w;
}

}  // namespace

// Reading the terms off the curve (IEEE Std 952-1997 C.1; El-Sheimy, Hou & Niu, "Analysis and
// Modeling of Inertial Sensors Using Allan Variance", IEEE TIM 57(1), 2008):
// - Only points averaging >= 10 independent clusters are used (all points of a curve without
//   cluster counts). Local slopes are least-squares slopes in ln-ln over +-1/4 decade.
// - White noise: the runs of points whose local slope is -1/2 +- 0.1 (+- 0.2 when there is
//   none); the run containing tau = 1 s, else the nearest one (ties: the longer). The line
//   N / sqrt(tau) is fitted to it in the log domain, weighting each point by its number of
//   independent clusters N/m (inverse variance), and N is its value at 1 s; for a curve
//   that ends before or starts after 1 s this is the extrapolated line. 0 when no such run.
// - Bias instability: past the first point where the curve falls (local slope < 0; a rise at
//   the shortest tau, from an output filter, is skipped), the first point where the local
//   slope turns >= 0 marks the floor; B is the minimum of the curve from the fall to half a
//   decade beyond that point, divided by 0.664 (flicker floor, C.1.3), with its tau. A curve
//   that never stops falling has no floor: B is read at its flattest point when that slope
//   is >= -0.35 (a shoulder, e.g. a Gauss-Markov bias), otherwise at its last trusted point
//   (an upper bound).
// - Random walk: the runs with local slope +1/2 +- 0.1 of at least two points; the one with
//   the largest sum of weights N/m, i.e. the best determined (without counts: the most
//   points; ties: the later), not counting a rise before the curve first falls. K is the
//   line K sqrt(tau/3), fitted with the same weights, read at tau = 3 s. 0 when the curve
//   does not rise so.
AllanFit fit_allan(const std::vector<AllanPoint>& curve) {
  AllanFit fit;
  const std::vector<double> indep = independent_clusters(curve);
  std::vector<LogPoint> pts;
  for (std::size_t i = 0; i < curve.size(); ++i) {
    const AllanPoint& p = curve[i];
    if (!(p.tau_s > 0.0) || !(p.adev > 0.0) || !std::isfinite(p.adev)) continue;
    if (!indep.empty() && indep[i] < kMinIndependentClusters) continue;
    pts.push_back({std::log(p.tau_s), std::log(p.adev), 0.0, indep.empty() ? 1.0 : indep[i]});
  }
  if (pts.empty()) return fit;
  local_slopes(pts);

  // White noise: slope -1/2 around tau = 1 s.
  for (double tol : {0.1, 0.2}) {
    const std::vector<Run> runs = slope_runs(pts, -0.5, tol);
    if (runs.empty()) continue;
    const Run* best = nullptr;
    double best_dist = 0.0;
    for (const Run& r : runs) {
      const double a = pts[r.first].lt, b = pts[r.last].lt;
      const double dist = (a <= 0.0 && b >= 0.0) ? 0.0 : std::min(std::abs(a), std::abs(b));
      if (best == nullptr || dist < best_dist ||
          (dist == best_dist && r.last - r.first > best->last - best->first)) {
        best = &r;
        best_dist = dist;
      }
    }
    fit.white_density = std::exp(line_log_coefficient(pts, *best, -0.5));  // line at 1 s
    break;
  }

  // Bias instability: the minimum of the first valley. A curve may first rise (an output
  // filter or oversampling correlates the shortest clusters); the valley starts where it
  // first falls.
  std::size_t fall = 0;
  while (fall < pts.size() && pts[fall].slope >= 0.0) ++fall;
  if (fall == pts.size()) fall = 0;  // never falls: a rising curve, read at its start
  std::size_t turn = pts.size();
  for (std::size_t i = fall; i < pts.size(); ++i)
    if (pts[i].slope >= 0.0) {
      turn = i;
      break;
    }
  std::size_t at = pts.size() - 1;
  if (turn < pts.size()) {
    const double limit = pts[turn].lt + 0.5 * std::log(10.0);
    at = fall;
    for (std::size_t i = fall; i < pts.size() && pts[i].lt <= limit; ++i)
      if (pts[i].la < pts[at].la) at = i;
  } else {
    std::size_t flattest = fall;
    for (std::size_t i = fall; i < pts.size(); ++i)
      if (pts[i].slope > pts[flattest].slope) flattest = i;
    if (pts[flattest].slope >= -0.35) at = flattest;
  }
  fit.bias_instability = std::exp(pts[at].la) / kAllanBiasInstabilityFactor;
  fit.bias_instability_tau_s = std::exp(pts[at].lt);

  // Random walk: slope +1/2.
  const std::vector<Run> rising = slope_runs(pts, 0.5, 0.1);
  const Run* best = nullptr;
  double best_weight = 0.0;
  for (const Run& r : rising) {
    if (r.last == r.first || r.first < fall) continue;
    double w = 0.0;
    for (std::size_t i = r.first; i <= r.last; ++i) w += pts[i].weight;
    if (best == nullptr || w >= best_weight) {
      best = &r;
      best_weight = w;
    }
  }
  if (best != nullptr)
    fit.random_walk = std::exp(line_log_coefficient(pts, *best, 0.5)) * std::sqrt(3.0);
  return fit;
}

}  // namespace navemu
