#!/usr/bin/python3
"""Summary of the paper's mission runs (tools/mission): per run, from OUT/{low,high}/gnss.csv,
the horizontal and vertical error (max, 95 %), vertical jumps (consecutive fixes whose vertical
error changes by more than 2 m: five sigma of the low-fidelity run's epoch-to-epoch change),
outages (epochs without a fix, and the longest run of them), satellites tracked and HDOP.
Writes OUT/summary.md and, with gnuplot, OUT/mission.png and OUT/track.png.

Usage: mission_report.py OUT
"""
import csv
import math
import os
import subprocess
import sys

JUMP_M = 2.0
PERIOD_S = 0.2


def pct(values, p):
    if not values:
        return float("nan")
    v = sorted(values)
    return v[min(len(v) - 1, int(math.ceil(p * len(v))) - 1)]


def summarize(path):
    rows = list(csv.DictReader(open(path)))
    fixes = [r for r in rows if r["fix"] != "0"]
    eh = [float(r["err_h_m"]) for r in fixes]
    eu = [abs(float(r["err_u_m"])) for r in fixes]
    jumps, prev, outage, longest = 0, None, 0, 0
    for r in rows:
        if r["fix"] == "0":
            prev = None
            outage += 1
            longest = max(longest, outage)
            continue
        outage = 0
        u = float(r["err_u_m"])
        if prev is not None and abs(u - prev) > JUMP_M:
            jumps += 1
        prev = u
    hdop = [float(r["hdop"]) for r in fixes if float(r["hdop"]) > 0]
    return {
        "epochs": len(rows),
        "fixes": len(fixes),
        "h_max": max(eh, default=float("nan")),
        "h_95": pct(eh, 0.95),
        "v_max": max(eu, default=float("nan")),
        "v_95": pct(eu, 0.95),
        "jumps": jumps,
        "no_fix": len(rows) - len(fixes),
        "longest_s": longest * PERIOD_S,
        "sats": sum(int(r["num_tracked"]) for r in rows) / max(len(rows), 1),
        "hdop": pct(hdop, 0.5),
    }


def main():
    out = sys.argv[1]
    runs = {name: summarize(os.path.join(out, name, "gnss.csv")) for name in ("low", "high")}
    lines = [
        "| | low fidelity (truth + 40 cm) | high fidelity (DGPS receiver in the city) |",
        "| --- | --- | --- |",
    ]
    fmt = [
        ("GNSS epochs (with a fix)", lambda s: f"{s['epochs']} ({s['fixes']})"),
        ("horizontal error max / 95 % (m)", lambda s: f"{s['h_max']:.2f} / {s['h_95']:.2f}"),
        ("vertical error max / 95 % (m)", lambda s: f"{s['v_max']:.2f} / {s['v_95']:.2f}"),
        (f"vertical jumps > {JUMP_M:g} m between fixes", lambda s: str(s["jumps"])),
        ("epochs without a fix (longest outage, s)", lambda s: f"{s['no_fix']} ({s['longest_s']:.1f})"),
        ("satellites tracked (mean), HDOP (median)", lambda s: f"{s['sats']:.1f}, {s['hdop']:.2f}"),
    ]
    for label, f in fmt:
        lines.append(f"| {label} | {f(runs['low'])} | {f(runs['high'])} |")
    table = "\n".join(lines) + "\n"
    open(os.path.join(out, "summary.md"), "w").write(table)
    print(table, end="")

    plot = f"""
set terminal pngcairo size 1200,800 font ',10'
set datafile separator ','
set output '{out}/mission.png'
set multiplot layout 2,1 title 'The paper''s mission: low versus high fidelity GNSS (seed 1)'
set ylabel 'horizontal error (m)'
set logscale y
set yrange [0.01:*]
set key top left
plot '{out}/low/gnss.csv' every ::1 using 1:19 with lines title 'low fidelity', \\
     '{out}/high/gnss.csv' every ::1 using 1:19 with lines title 'high fidelity'
unset logscale y
set yrange [*:*]
set xlabel 'time since start (s)'
set ylabel 'vertical error (m)'
plot '{out}/low/gnss.csv' every ::1 using 1:18 with lines title 'low fidelity', \\
     '{out}/high/gnss.csv' every ::1 using 1:18 with lines title 'high fidelity'
unset multiplot
set output '{out}/track.png'
set terminal pngcairo size 900,900 font ',10'
set title 'Plan view: truth and fixes (degrees)'
set xlabel 'longitude (deg)'
set ylabel 'latitude (deg)'
set size ratio -1
set xrange [-90.906:-90.894]
set yrange [32.295:32.305]
plot '{out}/high/gnss.csv' every ::1 using 11:10 with points pt 7 ps 0.3 title 'high fidelity fixes', \\
     '{out}/low/gnss.csv' every ::1 using 11:10 with points pt 7 ps 0.3 title 'low fidelity fixes', \\
     '{out}/low/gnss.csv' every ::1 using 5:4 with lines lw 2 title 'truth'
"""
    try:
        subprocess.run(["gnuplot"], input=plot, text=True, check=True)
        print(f"plots: {out}/mission.png, {out}/track.png")
    except (OSError, subprocess.CalledProcessError) as e:
        print(f"mission_report: no plots ({e}); install gnuplot-nox (tools/install-deps)", file=sys.stderr)


if __name__ == "__main__":
    main()
