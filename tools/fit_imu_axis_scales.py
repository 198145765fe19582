#!/usr/bin/env python3
"""Per-axis noise multipliers of an IMU profile from measured per-axis Allan curves.

Reads imu_utils' curves data_<NAME>_{gyr,acc}_{t,x,y,z}.txt (one value a line: tau in s, then
the Allan deviation per axis, gyroscope in deg/h, accelerometer in m/s^2;
../shared/data/imu/imu_utils_allan) and the profile's triad values (configs/imu/<profile>.yaml:
white density, bias instability and its correlation time, random walk, SI units), and prints
the profile's per-axis YAML lines:

  <sensor>_white_density_axis_scale, <sensor>_bias_instability_axis_scale,
  <sensor>_random_walk_axis_scale: [x, y, z]

1. Start: white = ADEV(1 s) of the axis / the mean over the axes; bias = minimum of the axis'
   curve / the mean of the minima; random walk = ADEV at the longest tau <= 1000 s / the mean
   (only where the profile has a random walk; otherwise 1).
2. Refinement: per axis, the three multipliers are adjusted (coordinate search in log space)
   to minimise the worst |log(model / measured)| over tau 0.1 .. 1000 s, the model being the
   analytic Allan deviation of the configured terms (IEEE Std 952-1997 annex C):
   N^2 / tau + K^2 tau / 3 + the first-order Gauss-Markov term of 1-sigma 1.07600 B and
   correlation time T (models/imu_model.hpp), each point's |log| increased by the relative
   1-sigma 1 / sqrt(2 (n - 1)) of an Allan deviation from n = run / tau clusters of the
   generated run (--run-s, default 0: off), so the long-tau end, where a
   generated curve scatters most, keeps a margin. With --no-refine only step 1.

Python 3 standard library only.

  tools/fit_imu_axis_scales.py PROFILE NAME [--dir DIR] [--no-refine]
  e.g. tools/fit_imu_axis_scales.py configs/imu/bmi160.yaml BMI160
"""

import argparse
import math
import os
import sys

AXES = "xyz"
SENSORS = (("gyr", "gyro"), ("acc", "accel"))


def read_column(path):
    with open(path, encoding="ascii") as f:
        return [float(x) for x in f.read().split()]


def at_tau(tau, adev, t):
    """Log-log interpolation of the curve at t (the nearest end outside it)."""
    if t <= tau[0]:
        return adev[0]
    for i in range(1, len(tau)):
        if tau[i - 1] <= t <= tau[i]:
            u = math.log(t / tau[i - 1]) / math.log(tau[i] / tau[i - 1])
            return math.exp(math.log(adev[i - 1]) + u * math.log(adev[i] / adev[i - 1]))
    return adev[-1]


def normalised(values):
    mean = sum(values) / len(values)
    return [v / mean for v in values]


def yaml_line(key, scales):
    return "{}: [{}]".format(key, ", ".join("{:.3f}".format(s) for s in scales))


GM_SIGMA_PER_B = 0.66428247 / 0.61736428  # models/imu_model.hpp kGmSigmaPerBiasInstability
RAD_PER_DEG_PER_H = math.pi / 180.0 / 3600.0

# The triad keys read from a profile (SI suffixes only).
KEYS = {
    "white": ("white_density_mps2_per_rthz", "white_density_radps_per_rthz"),
    "bias": ("bias_instability_mps2", "bias_instability_radps"),
    "tau": ("bias_instability_tau_s",),
    "rw": ("random_walk_mps3_per_rthz", "random_walk_radps2_per_rthz"),
}


def read_profile(path, prefix):
    """The triad's white density, bias instability, its tau and random walk (SI; 0 if absent)."""
    values = {}
    with open(path, encoding="utf-8") as f:
        for line in f:
            line = line.split("#", 1)[0].strip()
            if ":" in line:
                key, value = (x.strip() for x in line.split(":", 1))
                values[key] = value
    out = {}
    for term, suffixes in KEYS.items():
        out[term] = 100.0 if term == "tau" else 0.0
        for suffix in suffixes:
            if prefix + "_" + suffix in values:
                out[term] = float(values[prefix + "_" + suffix])
    if out["white"] <= 0.0:
        raise SystemExit("{}: no {}_white_density in SI units".format(path, prefix))
    return out


def model_adev(p, scales, tau):
    n = p["white"] * scales[0]
    sigma = GM_SIGMA_PER_B * p["bias"] * scales[1]
    k = p["rw"] * scales[2]
    t = p["tau"]
    x = tau / t
    gm = 2.0 * sigma * sigma * t / tau * (1.0 - t / (2.0 * tau) * (3.0 - 4.0 * math.exp(-x) +
                                                                  math.exp(-2.0 * x)))
    return math.sqrt(n * n / tau + k * k * tau / 3.0 + gm)


def estimate_uncertainty(tau, run_s):
    """Relative 1-sigma of an Allan deviation estimated from a run of run_s seconds at tau:
    1 / sqrt(2 (n - 1)), n = run_s / tau clusters (IEEE Std 952-1997 annex C)."""
    n = run_s / tau
    return 1.0 / math.sqrt(2.0 * (n - 1.0)) if n > 2.0 else 1.0


FLOOR_TAUS = [10.0 ** (k / 20.0) for k in range(-20, 81)]  # 0.1 s .. 10^4 s
ALLAN_FLOOR_PER_B = 0.66428247  # the flicker floor sqrt(2 ln 2 / pi) B (IEEE Std 952 C.1.3)


def inconsistency(p, scales):
    """How far the axis' model curve is from showing its own configured terms the way a profile
    means them (and tests/integration/test_imu_acceptance.cpp ImuProfileAllan checks): ADEV(1 s)
    equal to the axis' white density (within 4 %) and the curve's minimum equal to the floor
    0.664 B of the axis' bias instability (within 15 %). 0 when consistent, else the excess
    |log| (a penalty)."""
    white = p["white"] * scales[0]
    excess = max(0.0, abs(math.log(model_adev(p, scales, 1.0) / white)) - math.log(1.04))
    if p["bias"] > 0.0:
        floor = min(model_adev(p, scales, t) for t in FLOOR_TAUS)
        b = ALLAN_FLOOR_PER_B * p["bias"] * scales[1]
        excess += max(0.0, abs(math.log(floor / b)) - math.log(1.15))
    return excess


def worst_log_ratio(p, scales, points, run_s=0.0, consistent=False):
    """The worst |log(model / measured)|, each point's plus the estimate's relative uncertainty
    of a run_s run at its tau (a margin for the generated curve's scatter; 0: none); with
    `consistent`, plus 10 times the inconsistency penalty."""
    w = max(abs(math.log(model_adev(p, scales, t) / m)) +
            (estimate_uncertainty(t, run_s) if run_s > 0.0 else 0.0) for t, m in points)
    return w + 10.0 * inconsistency(p, scales) if consistent else w


SCALE_MIN, SCALE_MAX = 0.2, 5.0  # the refinement's bounds on a multiplier


def pattern_search(p, start, points, run_s, active):
    """Pattern search over the 26 neighbour directions in log space, shrinking step."""
    best_s = list(start)
    best = worst_log_ratio(p, best_s, points, run_s, True)
    directions = [(i, j, k) for i in (-1, 0, 1) for j in (-1, 0, 1) for k in (-1, 0, 1)
                  if (i, j, k) != (0, 0, 0) and (k == 0 or 2 in active)]
    step = 0.1
    while step > 1e-4:
        improved = False
        for d in directions:
            trial = [best_s[j] * math.exp(d[j] * step) for j in range(3)]
            if not all(SCALE_MIN <= x <= SCALE_MAX for x in trial):
                continue
            w = worst_log_ratio(p, trial, points, run_s, True)
            if w < best - 1e-12:
                best_s, best, improved = trial, w, True
        if not improved:
            step /= 2.0
    return best_s, best


def nelder_mead(f, x0, step=0.3, iterations=600, restarts=3):
    """Nelder-Mead minimisation of f over x (here log-scales), restarted at its result."""
    x_best = list(x0)
    for _ in range(restarts):
        n = len(x_best)
        simplex = [list(x_best)] + [[x_best[j] + (step if j == i else 0.0) for j in range(n)]
                                    for i in range(n)]
        values = [f(x) for x in simplex]
        for _ in range(iterations):
            order = sorted(range(n + 1), key=lambda i: values[i])
            simplex = [simplex[i] for i in order]
            values = [values[i] for i in order]
            centroid = [sum(x[j] for x in simplex[:-1]) / n for j in range(n)]
            worst = simplex[-1]
            reflected = [c + (c - w) for c, w in zip(centroid, worst)]
            fr = f(reflected)
            if fr < values[0]:
                expanded = [c + 2.0 * (c - w) for c, w in zip(centroid, worst)]
                fe = f(expanded)
                simplex[-1], values[-1] = (expanded, fe) if fe < fr else (reflected, fr)
            elif fr < values[-2]:
                simplex[-1], values[-1] = reflected, fr
            else:
                contracted = [c + 0.5 * (w - c) for c, w in zip(centroid, worst)]
                fc = f(contracted)
                if fc < values[-1]:
                    simplex[-1], values[-1] = contracted, fc
                else:
                    simplex = [simplex[0]] + [[b + 0.5 * (x - b) for b, x in zip(simplex[0], y)]
                                              for y in simplex[1:]]
                    values = [values[0]] + [f(x) for x in simplex[1:]]
        x_best = simplex[min(range(n + 1), key=lambda i: values[i])]
        step /= 3.0
    return x_best


def refine(p, scales, points, run_s):
    """Minimises worst_log_ratio (a minimax, not smooth, with local minima): Nelder-Mead then
    a pattern search, from the start and from the 8 best points of a coarse log-spaced grid
    over [SCALE_MIN, SCALE_MAX]; the best result."""
    active = [0, 1] + ([2] if p["rw"] > 0.0 else [])
    lo, hi, n = math.log(SCALE_MIN), math.log(SCALE_MAX), 17
    grid = [math.exp(lo + (hi - lo) * i / (n - 1)) for i in range(n)]
    axes = [grid if j in active else [scales[j]] for j in range(3)]
    ranked = sorted((worst_log_ratio(p, [a, b, c], points, run_s, True), [a, b, c])
                    for a in axes[0] for b in axes[1] for c in axes[2])
    starts = [list(scales)] + [s for _, s in ranked[:8]]
    results = []
    for start in starts:
        # Nelder-Mead in log space over the active multipliers (clamped to the bounds), then a
        # pattern search to polish.
        def objective(x, start=start):
            trial = list(start)
            for j, v in zip(active, x):
                trial[j] = min(max(math.exp(v), SCALE_MIN), SCALE_MAX)
            return worst_log_ratio(p, trial, points, run_s, True)
        x = nelder_mead(objective, [math.log(start[j]) for j in active])
        trial = list(start)
        for j, v in zip(active, x):
            trial[j] = min(max(math.exp(v), SCALE_MIN), SCALE_MAX)
        results.append(pattern_search(p, trial, points, run_s, active))
    return min(results, key=lambda r: r[1])


def fit(profile, directory, name, do_refine, run_s):
    lines = []
    for kind, prefix in SENSORS:
        p = read_profile(profile, prefix)
        to_si = RAD_PER_DEG_PER_H if kind == "gyr" else 1.0
        base = os.path.join(directory, "data_{}_{}_".format(name, kind))
        tau = read_column(base + "t.txt")
        curves = [[v * to_si for v in read_column(base + a + ".txt")] for a in AXES]
        for c in curves:
            if len(c) != len(tau):
                raise SystemExit("{}: axis curves and tau differ in length".format(base))
        white = normalised([at_tau(tau, c, 1.0) for c in curves])
        bias = normalised([min(c) for c in curves])
        if p["rw"] > 0.0:
            i = max(k for k, t in enumerate(tau) if t <= 1000.0)
            rw = normalised([c[i] for c in curves])
        else:
            rw = [1.0, 1.0, 1.0]
        per_axis = [[white[a], bias[a], rw[a]] for a in range(3)]
        for a in range(3):
            points = [(t, m) for t, m in zip(tau, curves[a]) if 0.1 <= t <= 1000.0]
            before = worst_log_ratio(p, per_axis[a], points)
            if do_refine:
                per_axis[a], _ = refine(p, per_axis[a], points, run_s)
            after = worst_log_ratio(p, per_axis[a], points)
            margin = worst_log_ratio(p, per_axis[a], points, run_s)
            lines.append("# {} {}: model/measured worst factor {:.3f} at the start, {:.3f} "
                         "fitted ({:.3f} with the {:.0f} s run's scatter){}".format(
                             prefix, AXES[a], math.exp(before), math.exp(after),
                             math.exp(margin), run_s,
                             "" if inconsistency(p, per_axis[a]) == 0.0 else ", INCONSISTENT"))
        names = ("white_density", "bias_instability", "random_walk")
        for j, term in enumerate(names):
            if term == "random_walk" and p["rw"] <= 0.0:
                continue
            lines.append(yaml_line("{}_{}_axis_scale".format(prefix, term),
                                   [per_axis[a][j] for a in range(3)]))
    return lines


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    default_dir = os.path.normpath(
        os.path.join(here, "..", "..", "shared", "data", "imu", "imu_utils_allan"))
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("profile", help="the profile's YAML file, e.g. configs/imu/bmi160.yaml")
    ap.add_argument("name", help="imu_utils file prefix: BMI160, 16448, xsens, gx4, ...")
    ap.add_argument("--dir", default=default_dir, help="directory of the data_*.txt curves")
    ap.add_argument("--no-refine", action="store_true", help="only the start values (step 1)")
    ap.add_argument("--run-s", type=float, default=0.0,
                    help="length of a generated run to keep a margin for (e.g. 10800, the "
                         "acceptance test's 3 h): its Allan scatter is added; default 0: none")
    args = ap.parse_args()
    print("# tools/fit_imu_axis_scales.py {} {}{}".format(
        args.profile, args.name, " --no-refine" if args.no_refine else ""))
    for line in fit(args.profile, args.dir, args.name, not args.no_refine, args.run_s):
        print(line)
    return 0


if __name__ == "__main__":
    sys.exit(main())
