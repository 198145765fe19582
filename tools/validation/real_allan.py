#!/usr/bin/python3
"""Validation section "real_allan": navemu's IMU Allan deviation against real parts.

For each IMU profile fitted to a measured part (configs/imu: bmi160, adis16448, xsens_mti100,
microstrain_gx4), a static run `navemu imu --profile P --duration S --seed 11` goes through
`navemu allan`, and its curves are overlaid with the part's measured Allan curves from
gaowenliang/imu_utils (../shared/data/imu/imu_utils_allan: data_<part>_{gyr,acc}_{t,x,y,z}.txt,
tau in s, gyroscope in deg/h, accelerometer in m/s^2). Band (as the README states): the average
of the three generated axes within a factor 1.5 of the average of the three measured axes at
every measured tau from 0.1 s to min(1000 s, S/10), per part and sensor.

Usage: tools/validation/real_allan.py --navemu PATH --out DIR [--quick]
Writes DIR/real_allan.md and DIR/real_allan_<profile>.png; prints one "BAND ..." line per part
and sensor; exit 1 if one is out, 2 on usage errors or missing data, 0 (with a note) without
../shared. Full: 3 h runs (as tests/integration/test_imu_acceptance.cpp), 10 tau per decade;
quick: 1 h runs, 5 tau per decade, tau up to 360 s. Standard library only; gnuplot.
"""
import concurrent.futures
import csv
import math
import os
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.dont_write_bytecode = True
sys.path.insert(0, HERE)
import _common as common  # noqa: E402
ROOT = os.path.dirname(os.path.dirname(HERE))
NAME = "real_allan"
FACTOR = 1.5
SEED = 11
TAU_MIN, TAU_MAX = 0.1, 1000.0
# profile, imu_utils file prefix, part
PARTS = [("bmi160", "BMI160", "Bosch BMI160"),
         ("adis16448", "16448", "Analog Devices ADIS16448"),
         ("xsens_mti100", "xsens", "Xsens MTi-100"),
         ("microstrain_gx4", "gx4", "LORD MicroStrain 3DM-GX4")]
RADPS_TO_DEGPH = 180.0 / math.pi * 3600.0
SENSORS = [("gyr", "gyroscope", ["w_x_radps", "w_y_radps", "w_z_radps"], RADPS_TO_DEGPH, "deg/h"),
           ("acc", "accelerometer", ["f_x_mps2", "f_y_mps2", "f_z_mps2"], 1.0, "m/s^2")]


def read_column(path):
    with open(path) as f:
        return [float(x) for x in f.read().split()]


def at_tau(tau, adev, t):
    """Log-log interpolation; None outside the curve."""
    for i in range(1, len(tau)):
        if tau[i - 1] <= t <= tau[i]:
            u = math.log(t / tau[i - 1]) / math.log(tau[i] / tau[i - 1])
            return math.exp(math.log(adev[i - 1]) + u * (math.log(adev[i]) - math.log(adev[i - 1])))
    return None


def generate(navemu, profile, duration, ppd, work):
    """Static run and its Allan curves: {column: (tau list, adev list)}."""
    samples = os.path.join(work, profile + ".csv")
    curves = os.path.join(work, profile + "_adev.csv")
    for cmd in ([navemu, "imu", "--profile", profile, "--duration", str(duration), "--seed", str(SEED),
                 "--out", samples],
                [navemu, "allan", samples, "--points-per-decade", str(ppd), "--out", curves]):
        r = subprocess.run(cmd, capture_output=True, text=True)
        if r.returncode != 0:
            raise RuntimeError(f"{' '.join(cmd)} failed: {r.stderr.strip()}")
    os.remove(samples)
    with open(curves) as f:
        rows = list(csv.DictReader(f))
    tau = [float(r["tau_s"]) for r in rows]
    return {c: (tau, [float(r[c]) for r in rows]) for c in rows[0] if c != "tau_s"}


def plot(out, profile, part, per_sensor, duration, ppd):
    png = f"{NAME}_{profile}.png"
    with tempfile.TemporaryDirectory() as t:
        panels = []
        for kind, label, unit, real_t, real_axes, gen_t, gen_axes, lo, hi in per_sensor:
            rd, gd = os.path.join(t, kind + "_real.dat"), os.path.join(t, kind + "_gen.dat")
            with open(rd, "w") as f:
                for i, x in enumerate(real_t):
                    f.write(f"{x:.6g} " + " ".join(f"{a[i]:.6g}" for a in real_axes) +
                            f" {sum(a[i] for a in real_axes) / 3:.6g}\n")
            with open(gd, "w") as f:
                for i, x in enumerate(gen_t):
                    f.write(f"{x:.6g} " + " ".join(f"{a[i]:.6g}" for a in gen_axes) +
                            f" {sum(a[i] for a in gen_axes) / 3:.6g}\n")
            panels.append(f"""
set title "{part}: {label}"
set xlabel "averaging time tau (s)"
set ylabel "Allan deviation ({unit})"
set obj 1 rect from {lo},graph 0 to {hi},graph 1 behind fc rgb "#f0f0f0" fs solid noborder
plot "{rd}" using 1:5 with lines lw 3 lc rgb "black" title "real, axis average", \\
     "{rd}" using 1:($5*{FACTOR}) with lines lw 1 dt 2 lc rgb "black" title "real x/÷ 1.5", \\
     "{rd}" using 1:($5/{FACTOR}) with lines lw 1 dt 2 lc rgb "black" notitle, \\
     "{rd}" using 1:2 with lines lw 1 lc rgb "#9999ff" title "real x, y, z", \\
     "{rd}" using 1:3 with lines lw 1 lc rgb "#9999ff" notitle, \\
     "{rd}" using 1:4 with lines lw 1 lc rgb "#9999ff" notitle, \\
     "{gd}" using 1:5 with lines lw 3 lc rgb "red" title "navemu, axis average"
""")
        script = f"""
set terminal pngcairo size 1500,650 font "Sans,12"
set output "{os.path.join(out, png)}"
set multiplot layout 1,2 title "{part} (profile {profile}): measured (imu\\\\_utils) vs navemu static {duration:g} s, seed {SEED}, {ppd} tau/decade; shaded: band range"
set logscale xy
set format x "10^{{%L}}"
set format y "10^{{%L}}"
set grid xtics ytics mxtics mytics
set key bottom left font "Sans,10"
""" + "\n".join(panels) + "\nunset multiplot\n"
        if not common.run_gnuplot(script, png):
            return None
    return png


def main():
    a = common.real_data_args(NAME, __doc__, "IMU Allan deviation against real parts")
    md_path = os.path.join(a.out, NAME + ".md")
    data = os.path.join(a.shared, "data", "imu", "imu_utils_allan")
    for _, prefix, _ in PARTS:
        for kind in ("gyr", "acc"):
            for ax in "txyz":
                p = os.path.join(data, f"data_{prefix}_{kind}_{ax}.txt")
                if not os.path.isfile(p):
                    print(f"{NAME}: missing data file {p}", file=sys.stderr)
                    return 2
    duration, ppd = (3600.0, 5) if a.quick else (10800.0, 10)
    tau_hi = min(TAU_MAX, duration / 10.0)
    t0 = time.time()
    with tempfile.TemporaryDirectory() as work, \
            concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
        futures = {p: pool.submit(generate, a.navemu, p, duration, ppd, work) for p, _, _ in PARTS}
        try:
            gen = {p: f.result() for p, f in futures.items()}
        except RuntimeError as e:
            print(f"{NAME}: {e}", file=sys.stderr)
            return 2
    failures = 0
    rows, figs = [], []
    for profile, prefix, part in PARTS:
        per_sensor = []
        for kind, label, cols, scale, unit in SENSORS:
            real_t = read_column(os.path.join(data, f"data_{prefix}_{kind}_t.txt"))
            real_axes = [read_column(os.path.join(data, f"data_{prefix}_{kind}_{ax}.txt")) for ax in "xyz"]
            gen_t = gen[profile][cols[0]][0]
            gen_axes = [[v * scale for v in gen[profile][c][1]] for c in cols]
            worst, worst_tau, n = 1.0, None, 0
            for i, t in enumerate(real_t):
                if not TAU_MIN <= t <= tau_hi:
                    continue
                g = [at_tau(gen_t, ax, t) for ax in gen_axes]
                if None in g:
                    continue
                m = sum(ax[i] for ax in real_axes) / 3.0
                ratio = sum(g) / 3.0 / m
                n += 1
                if abs(math.log(ratio)) > abs(math.log(worst)):
                    worst, worst_tau = ratio, t
            lo_t = min(t for t in real_t if t >= TAU_MIN)
            hi_t = max(t for t in real_t if t <= tau_hi)
            status = (common.print_band(f"real_allan {profile} {label} worst ratio", worst,
                                        1 / FACTOR, FACTOR) if n else common.OUT)
            failures += status == common.OUT
            rows.append(f"| {part} | `{profile}` | {label} | {n} ({lo_t:.2g}-{hi_t:.3g} s) | "
                        f"{worst:.3f} at {worst_tau:.3g} s | {status} |"
                        if n else f"| {part} | `{profile}` | {label} | 0 | - | OUT |")
            per_sensor.append((kind, label, unit, real_t, real_axes, gen_t, gen_axes, lo_t, hi_t))
        png = plot(a.out, profile, part, per_sensor, duration, ppd)
        if png:
            figs.append((part, profile, png))
    print(f"{NAME}: {2 * len(PARTS) - failures} of {2 * len(PARTS)} curves within a factor {FACTOR} "
          f"({time.time() - t0:.1f} s)")
    md = ["## IMU Allan deviation against real parts", "",
          "Measured Allan deviation curves of four real IMUs (gaowenliang/imu_utils, static logs of "
          "about 2 h; `../shared/data/imu/imu_utils_allan`) against navemu's static runs of the "
          "profiles fitted to them. Compared: the average over the three axes of the generated curve "
          "(log-log interpolated) against the average over the three measured axes, at every "
          f"measured tau from {TAU_MIN:g} s to {tau_hi:g} s (min(1000 s, run length / 10), where a "
          "generated point still averages at least ~10 clusters); band: ratio within 1/1.5..1.5. "
          "The worst ratio over that range is the band value.", "",
          f"Configuration: `navemu imu --profile P --duration {duration:g} --seed {SEED} --out "
          f"static.csv` (level, north-facing, at rest at the default position, the profile's output "
          f"rate), then `navemu allan static.csv --points-per-decade {ppd} --out adev.csv`"
          f"{' (quick mode: the full run uses 10800 s and 10 tau per decade, up to 1000 s)' if a.quick else ''}.",
          "",
          "| part | profile | sensor | measured tau compared | worst navemu / real | band 1/1.5..1.5 |",
          "|---|---|---|---|---|---|"] + rows + [""]
    for part, profile, png in figs:
        md += [f"![{part} Allan deviation, real vs navemu]({png})", "",
               f"*Figure: {part}, profile `{profile}`, static {duration:g} s, seed {SEED}: measured "
               "axis average (black, with the 1.5 band dashed), measured axes (blue), navemu axis "
               "average (red); the shaded tau range is the one checked.*", ""]
    md += ["Not covered: imu_utils' DJI A3 and N3 curves (navemu has no profiles for them). The "
           "per-axis curves are drawn but not band-checked (the README's claim and the acceptance "
           "test use axis averages; the real axes differ by up to ~4x and the profiles carry "
           "per-axis multipliers fitted by `tools/fit_imu_axis_scales.py`).", ""]
    if failures:
        md += [f"**{failures} curve(s) outside the band**: see the table; the generated curve of one "
               "seed scatters most at the long-tau end (few clusters).", ""]
    with open(md_path, "w") as f:
        f.write("\n".join(md))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
