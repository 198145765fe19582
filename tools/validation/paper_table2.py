#!/usr/bin/python3
"""Paper Table 2 / Fig. 4-6: GPS position standard deviations, stationary and on the test tracks."""

import math
import os
import sys
from concurrent.futures import ThreadPoolExecutor

sys.dont_write_bytecode = True
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import _common as c  # noqa: E402

S = c.Section("paper_table2", __doc__)

START = "2010-11-17T13:00:00Z"
SEED = 1
PROFILE = "garmin-18x-5hz"
STAT_S = 1200  # 20 minutes, as the paper's text (its Table 2 caption says 30)
LOOPS, PASSES = (2, 3) if S.quick else (8, 10)
SPREAD_SEEDS = [] if S.quick else list(range(1, 11))
R_M, LINE_M, V = 9.144, 18.288, 1.0

# Paper Table 2: truth (Garmin GPSmap 76CS / 18x-5Hz) and the paper's simulation.
PAPER = {
    "Trail 1": (1.943, 4.465e-5, 1.68, 2.40e-5),
    "Trail 2": (7.729, 2.2389e-5, 3.661, 1.0746e-4),
    "Circle track": (2.67, 4.5e-3, 0.85, 7.83e-5),
    "Linear track": (2.65, 6.5e-5, 0.85, 4.02e-5),
}
RUNS = [  # name, key, truth yaml, duration, points on the track (passes), lat, lon
    ("Trail 1", "trail1", "source: stationary", STAT_S, 1, 32.3, -90.9),
    ("Trail 2", "trail2", "source: stationary", STAT_S, 1, 32.305, -90.895),
    ("Circle track", "circle",
     f"source: circle\n  circle: {{radius_m: {R_M}, speed_mps: {V}, loops: {LOOPS}}}",
     LOOPS * 2 * math.pi * R_M / V + 20, LOOPS, 32.3, -90.9),
    ("Linear track", "line",
     f"source: line\n  line: {{heading_deg: 0, length_m: {LINE_M}, speed_mps: {V}, passes: {PASSES}}}",
     PASSES * (LINE_M / V + 8) + 20, PASSES, 32.3, -90.9),
]


def config(key, truth, lat, lon):
    path = os.path.join(S.out, f"paper_table2_{key}.yaml")
    with open(path, "w") as f:
        f.write(f"""# tools/validation/paper_table2.py: {key} (navemu simulate {os.path.basename(path)} --duration ...)
scenario: {{start: {START}, seed: {SEED}, status_interval_s: 0}}
truth:
  position: {{lat_deg: {lat}, lon_deg: {lon}, h_m: 60}}
  {truth}
gnss: {{profile: {PROFILE}, mode: standalone, outputs: []}}
imu: {{enabled: false}}
""")
    return path


def simulate(cfg, dur, out, seed=SEED):
    c.run([S.navemu, "simulate", cfg, "--start", START, "--seed", str(seed),
           "--duration", f"{dur:.0f}", "--out", out])
    return out


def stats(d, t_end=None):
    """Rows with a fix up to t_end; std of the 3-D error about its mean (m), of lat/long (deg)."""
    g = c.read_csv(os.path.join(d, "gnss.csv"))
    keep = [i for i, f in enumerate(g["fix"]) if f >= 2 and (t_end is None or g["time_s"][i] <= t_end)]
    col = {k: [g[k][i] for i in keep] for k in g}
    tot = math.sqrt(c.pvar(col["err_e_m"]) + c.pvar(col["err_n_m"]) + c.pvar(col["err_u_m"]))
    ll = math.sqrt((c.pvar(col["lat_deg"]) + c.pvar(col["lon_deg"])) / 2)
    return col, tot, ll, len(g["fix"]) - len([f for f in g["fix"] if f >= 2])


def motion_end(d):
    t = c.read_csv(os.path.join(d, "truth.csv"), columns=["time_s", "v_n_mps", "v_e_mps"])
    last = 0.0
    for ts, vn, ve in zip(t["time_s"], t["v_n_mps"], t["v_e_mps"]):
        if abs(vn) + abs(ve) > 1e-6:
            last = ts
    return last


jobs = []
with ThreadPoolExecutor(max_workers=2) as ex:
    for name, key, truth, dur, n, lat, lon in RUNS:
        cfg = config(key, truth, lat, lon)
        jobs.append(ex.submit(simulate, cfg, dur, os.path.join(S.work, key)))
    sp_cfg = os.path.join(S.out, "paper_table2_trail1.yaml")
    spread_jobs = [ex.submit(simulate, sp_cfg, STAT_S, os.path.join(S.work, f"trail1_seed{s}"), s)
                   for s in SPREAD_SEEDS]
    dirs = [j.result() for j in jobs]
    sdirs = [j.result() for j in spread_jobs]

results = {}
for (name, key, truth, dur, n, lat, lon), d in zip(RUNS, dirs):
    t_end = motion_end(d) if n > 1 or key in ("circle", "line") else None
    col, tot, ll, nofix = stats(d, t_end)
    # pass-to-pass drift: the moving span cut into n equal parts, range of their mean E/N error
    drift = None
    if key in ("circle", "line"):
        span = (t_end - col["time_s"][0]) / n
        me, mn = [], []
        for k in range(n):
            idx = [i for i, ts in enumerate(col["time_s"]) if k * span <= ts < (k + 1) * span]
            me.append(c.mean([col["err_e_m"][i] for i in idx]))
            mn.append(c.mean([col["err_n_m"][i] for i in idx]))
        drift = math.hypot(max(me) - min(me), max(mn) - min(mn))
    results[key] = dict(name=name, col=col, tot=tot, ll=ll, nofix=nofix, t_end=t_end, drift=drift,
                        lat=lat, lon=lon)

spread = [stats(d)[1:3] for d in sdirs]

# band checks: stationary runs within a factor 2 of the paper's truth (Garmin) column
for key in ("trail1", "trail2"):
    r = results[key]
    pt = PAPER[r["name"]]
    S.band(f"table2 {r['name']} STDEV(total) (m)", r["tot"], pt[0] / 2, pt[0] * 2, "{:.3g}")
    S.band(f"table2 {r['name']} STDEV(lat,long) (deg)", r["ll"], pt[1] / 2, pt[1] * 2, "{:.3g}")
for key in ("circle", "line"):
    r = results[key]
    print(f"INFO table2 {r['name']}: STDEV(total) {r['tot']:.3g} m, STDEV(lat,long) {r['ll']:.3g} deg, "
          f"pass-to-pass drift {r['drift']:.2f} m (no band)")

# ---- figures ----
figs = []
for key, fig in (("trail1", "Fig. 4"), ("trail2", "Fig. 5")):
    r = results[key]
    col = r["col"]
    dat = os.path.join(S.work, f"{key}.dat")
    c.write_dat(dat, [[t / 60 for t in col["time_s"]], col["lat_deg"], col["lon_deg"], col["h_m"]])
    png = f"paper_table2_{key}.png"
    c.gnuplot(f"""
set multiplot layout 3,1 title "{fig}-like: stationary receiver at {r['lat']}, {r['lon']} (h 60 m), {PROFILE}, start {START}, seed {SEED}"
set key off
set format y '%.5f'
set ylabel "latitude (deg)"
set xlabel ""
plot '{dat}' u 1:2 w l lc rgb '#4477aa', {r['lat']} w l dt 2 lc rgb 'black'
set ylabel "longitude (deg)"
plot '{dat}' u 1:3 w l lc rgb '#4477aa', {r['lon']} w l dt 2 lc rgb 'black'
set format y '%.0f'
set ylabel "height (m)"
set xlabel "time since start (min)"
plot '{dat}' u 1:4 w l lc rgb '#4477aa', 60 w l dt 2 lc rgb 'black'
unset multiplot
""", os.path.join(S.out, png), size="1000,900")
    figs.append((png, f"{fig}-like: lat/long/height of the stationary run {r['name']} (dashed: truth). "
                      f"Configuration `paper_table2_{key}.yaml` ({STAT_S} s), seed {SEED}."))

# Fig. 6: plan view of the two tracks, metres east/north of the track origin
plan = []
for key in ("circle", "line"):
    r = results[key]
    col = r["col"]
    lat0, lon0 = math.radians(r["lat"]), r["lon"]
    m_lat = 111132.92 - 559.82 * math.cos(2 * lat0)
    m_lon = 111412.84 * math.cos(lat0)
    dat = os.path.join(S.work, f"{key}_plan.dat")
    c.write_dat(dat, [[(lo - lon0) * m_lon for lo in col["lon_deg"]],
                      [(la - r["lat"]) * m_lat for la in col["lat_deg"]],
                      [(lo - lon0) * m_lon for lo in col["truth_lon_deg"]],
                      [(la - r["lat"]) * m_lat for la in col["truth_lat_deg"]]])
    plan.append((key, r, dat))
png = "paper_table2_tracks.png"
loops_txt = f"{LOOPS} loops" + (" (quick)" if S.quick else "")
passes_txt = f"{PASSES} passes" + (" (quick)" if S.quick else "")
c.gnuplot(f"""
set multiplot layout 1,2 title "Fig. 6-like: {PROFILE} fixes on the test tracks at 32.3 N 90.9 W, start {START}, seed {SEED}"
set size ratio -1
set xlabel "east of the track origin (m)"
set ylabel "north of the track origin (m)"
set key bottom center outside
set title "30 ft (9.144 m) radius circle, {loops_txt}, 1 m/s"
plot '{plan[0][2]}' u 1:2 w l lc rgb '#4477aa' title "navemu fix", '' u 3:4 w l lw 2 lc rgb 'black' title "truth"
set xrange [-10:10]
set title "60 ft (18.288 m) line, {passes_txt}, 1 m/s"
plot '{plan[1][2]}' u 1:2 w l lc rgb '#4477aa' title "navemu fix", '' u 3:4 w l lw 2 lc rgb 'black' title "truth"
unset multiplot
""", os.path.join(S.out, png), size="1300,750")
figs.append((png, f"Fig. 6-like: plan view of the fixes on the circle ({loops_txt}) and the line "
                  f"({passes_txt}). Configurations `paper_table2_circle.yaml`, "
                  f"`paper_table2_line.yaml`, seed {SEED}."))

# ---- markdown ----
md = ["## Paper Table 2 / Fig. 4-6: GPS position scatter", "",
      f"`navemu simulate` with the default receiver profile `{PROFILE}` (standalone: every error "
      f"source, open sky), the built-in constellation, start {START}, seed {SEED}; one YAML "
      "configuration per run is written next to this page (`paper_table2_*.yaml`). "
      f"Trail 1 is at the paper's site 32.3, -90.9 (h 60 m); trail 2 at 32.305, -90.895, about "
      "0.7 km north-east: the paper gives only its test site, not its two points. Both stationary "
      f"runs last {STAT_S // 60} minutes, as the paper's text (its Table 2 caption says 30), also "
      "in quick mode (a 20-minute run takes under a second). The circle (30 ft radius) and the "
      f"line (60 ft) are driven at 1 m/s, {LOOPS} loops and {PASSES} passes"
      + (" (quick mode; the full run does 8 and 10)" if S.quick else " as in the paper")
      + "; their statistics cover the epochs until the vehicle stops.", "",
      "How the paper's columns are read: STDEV(total) is taken as the standard deviation of the "
      "3-D position about its mean, in metres: sqrt(var E + var N + var U) of the fix error; "
      "STDEV(lat,long) as the standard deviation of the reported latitude and longitude in "
      "degrees, sqrt((var lat + var lon) / 2). The paper does not define them and its values are "
      "not self-consistent under any one reading (trail 1: 4.5e-5 deg is about 5 m horizontally, "
      "more than its 3-D total of 1.9 m; the circle's truth 4.5e-3 deg is 500 m). On the tracks "
      "STDEV(lat,long) includes the track itself (the circle alone gives about 6.4e-5 deg, the "
      "line about 3.4e-5 deg), while STDEV(total) is of the error only, which matches the "
      "paper's simulated 0.85 m better than the track's extent would.", "",
      "| run | paper truth total (m) | paper truth lat,long (deg) | paper sim total (m) | "
      "paper sim lat,long (deg) | navemu total (m) | navemu lat,long (deg) | navemu / truth | "
      "navemu / paper sim |", "|---|---|---|---|---|---|---|---|---|"]
for name, key, *_ in RUNS:
    r = results[key]
    pt = PAPER[name]
    md.append(f"| {name} | {pt[0]} | {pt[1]:.4g} | {pt[2]} | {pt[3]:.4g} | {r['tot']:.3g} | "
              f"{r['ll']:.3g} | {r['tot'] / pt[0]:.2f}, {r['ll'] / pt[1]:.2f} | "
              f"{r['tot'] / pt[2]:.2f}, {r['ll'] / pt[3]:.2f} |")
md += ["", "Per axis (1-sigma of the error, m): " + "; ".join(
    f"{results[k]['name']} E {c.pstd(results[k]['col']['err_e_m']):.2f}, "
    f"N {c.pstd(results[k]['col']['err_n_m']):.2f}, U {c.pstd(results[k]['col']['err_u_m']):.2f}"
    for k in ("trail1", "trail2", "circle", "line")) + ". As in the paper, height is the largest.",
       "", "Pass-to-pass drift (the moving span cut into equal parts per loop/pass; distance "
       "between the extremes of their mean east/north errors): "
       f"circle {results['circle']['drift']:.2f} m, line {results['line']['drift']:.2f} m. "
       f"Epochs without a fix: {sum(results[k]['nofix'] for k in results)}."]
if spread:
    tots = sorted(s[0] for s in spread)
    lls = sorted(s[1] for s in spread)
    md += ["", f"Seed spread (trail 1, seeds {SPREAD_SEEDS[0]}-{SPREAD_SEEDS[-1]}, 20 min each): "
           f"STDEV(total) {tots[0]:.2f} - {tots[-1]:.2f} m (median {tots[len(tots) // 2]:.2f}), "
           f"STDEV(lat,long) {lls[0]:.3g} - {lls[-1]:.3g} deg (median {lls[len(lls) // 2]:.3g}): "
           "a 20-minute standard deviation of errors correlated over minutes is itself uncertain by "
           "tens of percent."]
md += ["", "Band (stationary runs): each standard deviation within a factor 2 of the paper's "
       "truth (Garmin) column; the tracks are reported without a band.", "", S.band_table(), ""]
t1, t2 = results["trail1"], results["trail2"]
md += ["Where navemu lands: the two stationary runs are nearly identical "
       f"({t1['tot']:.2f} / {t2['tot']:.2f} m), because both use the same seed and start and the "
       "error streams (satellites, atmosphere, clock, noise) are seeded per scenario, not per "
       "place; 0.7 km changes the geometry and the atmosphere only slightly. The paper's trails "
       "were two separate collections with a real receiver, and its trail 2 scatter (7.7 m, four "
       "times trail 1) is not something an open-sky model with the same settings produces: "
       "the paper itself attributes the real receiver's height variability to multipath, which is "
       "off here as in the paper's runs. So navemu's 3-D total sits at about twice the paper's "
       "trail 1 truth and half its trail 2 truth (each band edge within a few percent, one just "
       "inside, one just outside), above the paper's own simulation (1.68 / 3.66 m). navemu's "
       "error is dominated by height (U about 3.3 m against E/N about 1.4 m). Its horizontal "
       "scatter, STDEV(lat,long), is about a third of the paper's trail 1 truth and 0.6 of its "
       "trail 2 truth; the paper's own simulated values straddle its truth by a factor 0.5 to 5, "
       "so this column constrains little. On the tracks navemu's total (error only) is "
       f"{results['circle']['tot']:.2f} / {results['line']['tot']:.2f} m, near the real "
       "receiver's 2.67 / 2.65 m and about four times the paper's simulated 0.85 m. The known "
       "gaps above are these differences, not failures to run.", ""]
for png, cap in figs:
    md += [f"![{png}]({png})", "", f"*Figure: {png}. {cap}*", ""]
S.write_md("\n".join(md))
S.finish()
