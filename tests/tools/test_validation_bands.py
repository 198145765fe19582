#!/usr/bin/python3
"""The band check of tools/validation (_common.print_band) and its known-gap list.

A known gap passes only inside the range recorded for it; anything else outside its band is
OUT. Every recorded gap must name a finite range and a reason. Exit 0 when all hold.
"""
import contextlib
import io
import math
import os
import sys

sys.dont_write_bytecode = True
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools",
                                "validation"))
import _common as c  # noqa: E402

failures = []


def expect(label, value, lo, hi, status):
    with contextlib.redirect_stdout(io.StringIO()) as out:
        got = c.print_band(label, value, lo, hi)
    line = out.getvalue().strip()
    if got != status or not line.endswith(": " + status) or not line.startswith(f"BAND {label}: "):
        failures.append(f"{label} = {value} in [{lo}, {hi}]: got {got!r} / {line!r}, want {status!r}")


gaps = c.known_gaps()
if not gaps:
    failures.append("known_gaps.json has no entries")
for label, g in gaps.items():
    lo, hi = g.get("measured", [math.nan, math.nan])
    if not (math.isfinite(lo) and math.isfinite(hi) and lo < hi):
        failures.append(f"{label}: 'measured' must be [lo, hi] with lo < hi")
    if len(g.get("why", "")) < 20:
        failures.append(f"{label}: 'why' must say why")

label, g = next(iter(gaps.items()))
lo, hi = g["measured"]
mid = (lo + hi) / 2
expect("no such band", 1.0, 0.5, 2.0, c.OK)
expect("no such band", 3.0, 0.5, 2.0, c.OUT)
expect(label, mid, mid * 10 + 1, mid * 10 + 2, c.GAP)              # outside its band, inside the record
expect(label, hi + (hi - lo), hi * 10 + 1, hi * 10 + 2, c.OUT)     # left the recorded range
expect(label, lo - (hi - lo), hi * 10 + 1, hi * 10 + 2, c.OUT)
expect(label, mid, mid - 1, mid + 1, c.OK)                        # a closed gap is simply ok
if "investigate" not in c.gap_why("no such band"):
    failures.append("gap_why of an unrecorded band must ask for an investigation")

for f in failures:
    print("FAIL:", f)
print(f"validation bands: {len(gaps)} known gaps, {len(failures)} failures")
sys.exit(1 if failures else 0)
