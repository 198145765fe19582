"""Helpers shared by the tools/validation section scripts (standard library only).

Not a section itself: tools/reproduce skips files whose name starts with '_'.
Section interface: NAME.py --navemu PATH --out DIR [--quick]; writes DIR/NAME.md and
DIR/NAME_*.png, prints one "BAND <name>: <value> in [lo, hi]: ok|known gap|OUT" line per band
check, exits 1 when a band check is OUT, 2 on usage errors or missing tools. A "known gap" is a
figure outside its band that known_gaps.json records, with why, and that stays inside the range
measured when it was recorded.
"""

import argparse
import csv
import functools
import json
import math
import os
import shutil
import subprocess
import sys


ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def check_tools(name, navemu):
    """Exits 2 unless navemu is an executable and gnuplot is installed."""
    if not (os.path.isfile(navemu) and os.access(navemu, os.X_OK)):
        die(f"{name}: navemu not found or not executable: {navemu}")
    if shutil.which("gnuplot") is None:
        die(f"{name}: gnuplot not found (apt-get install gnuplot-nox)")


OK, GAP, OUT = "ok", "known gap", "OUT"


@functools.lru_cache(maxsize=None)
def known_gaps():
    """known_gaps.json: band label -> {"measured": [lo, hi], "why": text}."""
    with open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "known_gaps.json")) as f:
        return {k: v for k, v in json.load(f).items() if not k.startswith("_")}


def gap_why(label):
    return known_gaps().get(label, {}).get("why", "not a recorded gap: investigate")


def print_band(label, value, lo, hi, fmt="{:.3f}"):
    """Prints the band line of the section interface and returns OK, GAP or OUT; only OUT fails.
    GAP: outside the band, but a recorded known gap still inside the range it was measured in."""
    status = OK if lo <= value <= hi else OUT
    gap = known_gaps().get(label)
    if status == OUT and gap and gap["measured"][0] <= value <= gap["measured"][1]:
        status = GAP
    print(f"BAND {label}: {fmt.format(value)} in [{fmt.format(lo)}, {fmt.format(hi)}]: {status}",
          flush=True)
    return status


def real_data_args(name, description, title, quick_help=None):
    """Arguments of a section on ../shared data: --navemu, --out, --quick, --shared (default
    $NAVEMU_SHARED or ../shared). Without the data it writes a fragment titled `title` saying
    so and exits 0; without navemu or gnuplot it exits 2."""
    ap = argparse.ArgumentParser(prog=f"{name}.py", description=description,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--navemu", required=True, help="path of the navemu binary")
    ap.add_argument("--out", required=True, help="output folder (created)")
    ap.add_argument("--quick", action="store_true", help=quick_help or "shorter runs")
    ap.add_argument("--shared", default=os.environ.get("NAVEMU_SHARED", os.path.join(ROOT, "..", "shared")))
    try:
        a = ap.parse_args()
    except SystemExit as e:
        sys.exit(0 if e.code == 0 else 2)
    os.makedirs(a.out, exist_ok=True)
    if not os.path.isdir(a.shared):
        print(f"{name}: {a.shared} not found: skipped (real data absent)")
        with open(os.path.join(a.out, name + ".md"), "w") as f:
            f.write(f"## {title}\n\nThe real data (`{a.shared}`) is absent: section skipped, "
                    "no band checks made.\n")
        sys.exit(0)
    check_tools(name, a.navemu)
    return a


def run_gnuplot(script, what, cwd=None):
    """Runs a whole gnuplot script; on failure says so on stderr and returns False."""
    r = subprocess.run(["gnuplot"], input=script, capture_output=True, text=True, cwd=cwd)
    if r.returncode != 0:
        print(f"gnuplot failed for {what}:\n{r.stderr}", file=sys.stderr)
    return r.returncode == 0


class Section:
    def __init__(self, name, description):
        self.name = name
        p = argparse.ArgumentParser(prog=f"{name}.py", description=description)
        p.add_argument("--navemu", required=True, help="path of the navemu binary")
        p.add_argument("--out", required=True, help="output folder (created)")
        p.add_argument("--quick", action="store_true", help="shorter runs")
        try:
            self.args = p.parse_args()
        except SystemExit as e:
            sys.exit(0 if e.code == 0 else 2)
        self.navemu = os.path.abspath(self.args.navemu)
        check_tools(name, self.navemu)
        self.out = os.path.abspath(self.args.out)
        self.quick = self.args.quick
        self.work = os.path.join(self.out, f"{name}_work")
        os.makedirs(self.work, exist_ok=True)
        self.failed = 0
        self.bands = []

    def band(self, label, value, lo, hi, fmt="{:.3g}"):
        status = print_band(label, value, lo, hi, fmt)
        self.failed += status == OUT
        self.bands.append((label, value, lo, hi, status, fmt))
        return status

    def band_table(self):
        rows = ["| band check | value | band | result |", "|---|---|---|---|"]
        for label, v, lo, hi, status, fmt in self.bands:
            rows.append(f"| {label} | {fmt.format(v)} | [{fmt.format(lo)}, {fmt.format(hi)}] | "
                        f"{'**OUT**' if status == OUT else status} |")
        gaps = [label for label, *_, status, _ in self.bands if status == GAP]
        if gaps:
            rows += ["", "Known gaps (tools/validation/known_gaps.json):", ""]
            rows += [f"- {label}: {gap_why(label)}." for label in gaps]
        return "\n".join(rows)

    def write_md(self, text):
        with open(os.path.join(self.out, f"{self.name}.md"), "w") as f:
            f.write(text.rstrip() + "\n")

    def finish(self, keep_work=False):
        if not keep_work:
            shutil.rmtree(self.work, ignore_errors=True)
        sys.exit(1 if self.failed else 0)


def die(msg, code=2):
    print(msg, file=sys.stderr)
    sys.exit(code)


def run(cmd, **kw):
    """Runs a command; on failure prints its stderr and exits 1 (the section failed)."""
    r = subprocess.run(cmd, capture_output=True, text=True, **kw)
    if r.returncode != 0:
        print(f"command failed ({r.returncode}): {' '.join(cmd)}\n{r.stderr}{r.stdout}", file=sys.stderr)
        sys.exit(1)
    return r


def read_csv(path, every=1, columns=None):
    """Dict of column -> list of floats (every n-th row)."""
    with open(path, newline="") as f:
        rd = csv.reader(f)
        head = next(rd)
        idx = [(c, head.index(c)) for c in (columns or head)]
        cols = {c: [] for c, _ in idx}
        for i, row in enumerate(rd):
            if i % every:
                continue
            for c, j in idx:
                cols[c].append(float(row[j]))
    return cols


def mean(v):
    return sum(v) / len(v)


def pvar(v):
    m = mean(v)
    return sum((x - m) ** 2 for x in v) / len(v)


def pstd(v):
    return math.sqrt(pvar(v))


def write_dat(path, columns):
    with open(path, "w") as f:
        for row in zip(*columns):
            f.write(" ".join(repr(x) if isinstance(x, float) else str(x) for x in row) + "\n")


def gnuplot(script, png, size="1000,700", cwd=None):
    """Runs a gnuplot script writing PNG `png` (pngcairo, legible fonts)."""
    head = (f"set terminal pngcairo size {size} font 'DejaVu Sans,12' noenhanced\n"
            f"set output '{png}'\nset grid\nset key outside right top\n")
    if not run_gnuplot(head + script, png, cwd):
        sys.exit(1)


def yaml_quote(s):
    return '"' + s.replace('"', '\\"') + '"'
