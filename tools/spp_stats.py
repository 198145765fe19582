#!/usr/bin/env python3
"""Accuracy statistics of a `navemu spp` run: horizontal and vertical error percentiles against
a known position, and the standard deviation of pseudorange residuals by elevation bin.

Usage: spp_stats.py SPP_CSV RESIDUALS_CSV X Y Z      (prints one JSON object)
Standard library only."""
import csv
import json
import math
import sys

ELEVATION_BINS_DEG = [(10.0, 30.0), (30.0, 60.0), (60.0, 90.0)]


def enu(p, ref):
    """ENU of ECEF point p relative to ECEF ref (WGS-84 geodetic normal at ref)."""
    a, f = 6378137.0, 1 / 298.257223563
    e2 = f * (2 - f)
    x, y, z = ref
    lon = math.atan2(y, x)
    r = math.hypot(x, y)
    lat = math.atan2(z, r * (1 - e2))
    for _ in range(10):
        n = a / math.sqrt(1 - e2 * math.sin(lat) ** 2)
        h = r / math.cos(lat) - n
        lat = math.atan2(z, r * (1 - e2 * n / (n + h)))
    d = [p[i] - ref[i] for i in range(3)]
    sl, cl, so, co = math.sin(lat), math.cos(lat), math.sin(lon), math.cos(lon)
    e = -so * d[0] + co * d[1]
    nn = -sl * co * d[0] - sl * so * d[1] + cl * d[2]
    u = cl * co * d[0] + cl * so * d[1] + sl * d[2]
    return e, nn, u


def percentile(values, q):
    """Linear-interpolated percentile (q in [0, 100]) of a non-empty list."""
    v = sorted(values)
    k = (len(v) - 1) * q / 100.0
    lo, hi = math.floor(k), math.ceil(k)
    return v[lo] + (v[hi] - v[lo]) * (k - lo)


def stdev(values):
    m = sum(values) / len(values)
    return math.sqrt(sum((x - m) ** 2 for x in values) / (len(values) - 1))


def spp_stats(spp_csv, residuals_csv, truth):
    horiz, vert = [], []
    with open(spp_csv) as f:
        for row in csv.DictReader(f):
            e, n, u = enu((float(row["x_m"]), float(row["y_m"]), float(row["z_m"])), truth)
            horiz.append(math.hypot(e, n))
            vert.append(abs(u))
    bins = {b: [] for b in ELEVATION_BINS_DEG}
    with open(residuals_csv) as f:
        for row in csv.DictReader(f):
            if row["used"] != "1":
                continue
            el = float(row["el_deg"])
            for lo, hi in ELEVATION_BINS_DEG:
                if lo <= el < hi or (hi == 90.0 and el == 90.0):
                    bins[(lo, hi)].append(float(row["residual_m"]))
    if not horiz:
        raise SystemExit(f"{spp_csv}: no solved epochs")
    out = {
        "epochs": len(horiz),
        "h50_m": percentile(horiz, 50), "h95_m": percentile(horiz, 95),
        "v50_m": percentile(vert, 50), "v95_m": percentile(vert, 95),
    }
    for (lo, hi), vals in bins.items():
        out[f"res_sd_{int(lo)}_{int(hi)}_m"] = stdev(vals) if len(vals) > 1 else float("nan")
    return out


if __name__ == "__main__":
    if len(sys.argv) != 6:
        sys.exit(__doc__)
    print(json.dumps(spp_stats(sys.argv[1], sys.argv[2], tuple(float(v) for v in sys.argv[3:6]))))
