#!/usr/bin/python3
"""Paper Table 1 / Fig. 1: mean receiver offset per GPS error source (navemu-paper-table1)."""

import os
import re
import sys

sys.dont_write_bytecode = True
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import _common as c  # noqa: E402

S = c.Section("paper_table1", __doc__)

tool = os.path.join(os.path.dirname(os.path.dirname(S.navemu)), "tools", "navemu-paper-table1")
if not os.access(tool, os.X_OK):
    c.die(f"paper_table1: {tool} not found (built next to navemu: build/tools/navemu-paper-table1)")

POINTS = 16
SEEDS = list(range(1, 11))


def table1(seed):
    """Runs the tool; returns (header line, [(source, expected, paper, navemu, in_band)], rc)."""
    r = c.subprocess.run([tool, "--points", str(POINTS), "--seed", str(seed)],
                         capture_output=True, text=True)
    if r.returncode not in (0, 1):
        c.die(f"paper_table1: {tool} failed ({r.returncode}):\n{r.stderr}", 1)
    rows = []
    for line in r.stdout.splitlines():
        m = re.match(r"\|\s*([^|]+?)\s*\|\s*(\+/-([\d.]+)|varies)\s*\|\s*([\d.]+)\s*\|\s*([\d.]+)\s*\|\s*(yes|NO)\s*\|", line)
        if m:
            exp = float(m.group(3)) if m.group(3) else None
            rows.append((m.group(1), exp, float(m.group(4)), float(m.group(5)), m.group(6) == "yes"))
    if len(rows) != 4:
        c.die(f"paper_table1: could not read the tool's table:\n{r.stdout}", 1)
    return r.stdout.splitlines()[0], rows, r.returncode


header, rows, rc1 = table1(1)
spread = {name: [] for name, *_ in rows}
for s in SEEDS:
    _, rs, _ = table1(s)
    for name, _, _, v, _ in rs:
        spread[name].append(v)

for name, exp, paper, nav, ok in rows:
    if exp is not None:
        S.band(f"table1 {name} offset (m)", nav, 0.0, exp, "{:.2f}")
    else:
        print(f"INFO table1 {name} offset (m): {nav:.2f} (paper {paper:.2f}; no band: 'varies')")
if (rc1 == 0) != (S.failed == 0):
    print("paper_table1: the tool's exit code disagrees with the band checks", file=sys.stderr)
    S.failed += 1

# Fig. 1 stand-in: the tool reports the mean over the circle only, so a bar chart per source.
dat = os.path.join(S.work, "t1.dat")
with open(dat, "w") as f:
    for i, (name, exp, paper, nav, ok) in enumerate(rows):
        lo, hi = min(spread[name]), max(spread[name])
        f.write(f'{i} "{name}" {exp if exp is not None else "NaN"} {paper} {nav} {lo} {hi}\n')
png = "paper_table1_offsets.png"
c.gnuplot(f"""
set title "Mean receiver offset per error source ({POINTS} points on a 9.144 m circle, 32.3 N 90.9 W,\\n2010-11-17T13:00Z, 7 satellites, seed 1; whiskers: seeds 1-10)"
set ylabel "mean 3-D offset from the true position (m)"
set xlabel "error source (alone)"
set style data histogram
set style histogram cluster gap 1
set style fill solid 0.8 border -1
set boxwidth 0.9
set yrange [0:7]
set xtics nomirror
set key inside right top
plot '{dat}' using 3:xtic(2) title "paper: expected offset (band)" lc rgb '#bbbbbb', \\
     '' using 4 title "paper: model offset" lc rgb '#4477aa', \\
     '' using 5 title "navemu (seed 1)" lc rgb '#ee6677', \\
     '' using ($1+0.27):5:6:7 with yerrorbars lc rgb 'black' pt 0 lw 1.5 title "navemu, seeds 1-10 (min-max)"
""", os.path.join(S.out, png))

md = [f"## Paper Table 1 / Fig. 1: receiver offset per error source", "",
      "`build/tools/navemu-paper-table1 --points 16 --seed 1`: a receiver at 16 points on the "
      "paper's 30 ft (9.144 m) circle at 32.3 N 90.9 W, 2010-11-17T13:00:00Z, the seven highest "
      "satellites of navemu's built-in constellation (the paper's SOPAC file is not available), "
      "each error source alone, plain trilateration; the mean 3-D offset of the fix from the "
      "true position. The paper's models are used (VTEC 12 mapping, its ephemeris-error formula, "
      "1022 hPa / 12.8 degC / 80 %); for the troposphere row the receiver applies its standard "
      "Saastamoinen model, because the paper's \"expected offset\" is the error budget after "
      "standard corrections (see the tool's header comment). The \"DOP\" row is the receiver's "
      "tracking noise through the geometry and the only random one.", "",
      "| error source | expected offset (paper) | model offset (paper) | navemu, seed 1 (m) | "
      "navemu, seeds 1-10 min-max (m) |", "|---|---|---|---|---|"]
for name, exp, paper, nav, ok in rows:
    md.append(f"| {name} | {'+/-%.1f' % exp if exp is not None else 'varies'} | {paper:.2f} | "
              f"{nav:.2f} | {min(spread[name]):.2f} - {max(spread[name]):.2f} |")
md += ["", "Band: each offset inside the paper's expected column (offset <= the +/- value; "
       "the DOP row has none).", "", S.band_table(), "",
       f"![Table 1 offsets]({png})", "",
       f"*Figure: {png}. Configuration: navemu-paper-table1, 16 points, radius 9.144 m, seed 1 "
       "(whiskers seeds 1-10).* The paper's Fig. 1 scatters the fix of every point; the tool "
       "reports only the mean offset per source, so a bar chart against the paper's Table 1 "
       "stands in for it.", "",
       "Differences from the paper: the troposphere row is near zero (navemu's receiver removes "
       "the modelled troposphere almost exactly with its own Saastamoinen model; uncorrected it "
       "would be about 7 m, mostly in height, according to the tool's header comment; not "
       "re-measured here); the paper's 0.57 m is a residual it does not explain. The "
       "ionosphere row (4.98 m) sits just inside the 5 m band: a deterministic value, "
       "not seed-dependent, but with no margin. "
       "The satellite and DOP rows depend on the geometry of the seven satellites, which is "
       "not the paper's (its 2010 ephemeris is not available), so only the bands are "
       "comparable, not the paper's model values."]
S.write_md("\n".join(md))
S.finish()
