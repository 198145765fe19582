#!/usr/bin/python3
"""Validation section "real_ublox": real u-blox NAV-PVT reports against navemu's.

Parses the UBX NAV-PVT frames (sync 0xB5 0x62, class 0x01, id 0x07, Fletcher checksum; payload
little-endian per the u-blox 8 / M8 protocol specification: fixType U1 at 20, flags X1 at 21,
numSV U1 at 23, lon/lat I4 1e-7 deg at 24/28, height I4 mm at 32, hAcc/vAcc U4 mm at 40/44,
pDOP U2 0.01 at 76) of the real u-blox captures under ../shared/data/receiver_logs, and of
`navemu simulate` runs of the matching u-blox profile (ublox-m8 for u-blox 8/M8/M10, ublox-f9p
for ZED-F9P/F9T, with NAV-PVT enabled at 1 Hz), stationary at the capture's mean position,
starting at the capture's first NAV-PVT time, for the same duration. Compares the median and
95th percentile of hAcc, vAcc, pDOP and numSV, and of the 3D jump between consecutive fixes
(ECEF distance, WGS 84); band: navemu's median hAcc and median vAcc within a factor 2 of the real
receiver's, for the captures with an ordinary navigation fix, and its median fix-to-fix jump for
those of them at least JUMP_MIN_EPOCHS long.

Usage: tools/validation/real_ublox.py --navemu PATH --out DIR [--quick]
Writes DIR/real_ublox.md and DIR/real_ublox_medians.png; one "BAND ..." line per check; exit 1
if one is out, 2 on usage errors or missing data, 0 (with a note) without ../shared.
Full: seeds 1..20 pooled per capture; quick: seed 1, at most 180 s per capture.
Standard library only; gnuplot for the figure.
"""
import csv
import datetime
import math
import os
import shutil
import statistics
import struct
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.dont_write_bytecode = True
sys.path.insert(0, HERE)
import _common as common  # noqa: E402
ROOT = os.path.dirname(os.path.dirname(HERE))
NAME = "real_ublox"
FACTOR = 2.0
SEEDS_FULL, SEEDS_QUICK = 20, 1
QUICK_MAX_S = 180
JUMP_MIN_EPOCHS = 100  # shorter captures give no median jump worth a band

# file under receiver_logs, short label, receiver, navemu profile, band-checked, note
CAPTURES = [
    ("gpsd/ublox8-uniqid-monhw.log", "u-blox 8 (GR8013)", "Navisys GR8013, u-blox 8, PROTVER 18",
     "ublox-m8", True, ""),
    ("gpsd/ublox-lea-m8f.log", "LEA-M8F", "u-blox LEA-M8F, PROTVER 16", "ublox-m8", False,
     "time mode (fixType 5): the receiver holds a fixed antenna position, so hAcc/vAcc are the "
     "accuracy of that stored position, not of a navigation fix; the ublox-m8 profile, a "
     "standard-precision part, has no time mode (the F9P profiles have it)"),
    ("gpsd/ublox-glo.log", "M10 (GLONASS)", "u-blox M10, PROTVER 34.10", "ublox-m8", False,
     "GLONASS-only capture with 3-4 satellites (2D and 3D fixes, pDOP up to 99.99): a degraded, "
     "single-constellation sky that navemu's open multi-GNSS sky does not reproduce "
     "(no M10 profile either; ublox-m8 is used)"),
    ("gpsd/ublox-zed-f9p-sfrbx.log", "ZED-F9P", "u-blox ZED-F9P, HPG 1.12", "ublox-f9p", True, ""),
    ("gpsd/ublox-zed-f9t-ubx_nmea_l5.log", "ZED-F9T (L5)", "u-blox ZED-F9T-20B, TIM 2.25",
     "ublox-f9p", True, ""),
    ("nav-solutions/F9T-L2-5min.ubx", "ZED-F9T (L2)", "u-blox ZED-F9T, L1/L2", "ublox-f9p", True, ""),
]
QUANTITIES = [("hacc", "hAcc", "m"), ("vacc", "vAcc", "m"), ("pdop", "pDOP", "-"), ("numsv", "numSV", "-")]


def strip_comments(data):
    """gpsd logs start with '#' lines; UBX payloads may contain '#', so only leading lines go."""
    while data.startswith(b"#"):
        j = data.find(b"\n")
        data = data[j + 1:] if j >= 0 else b""
    return data


def ubx_frames(data):
    i, n = 0, len(data)
    while True:
        i = data.find(b"\xb5\x62", i)
        if i < 0 or i + 8 > n:
            return
        length = struct.unpack_from("<H", data, i + 4)[0]
        if i + 8 + length > n:
            return
        a = b = 0
        for c in data[i + 2:i + 6 + length]:
            a = (a + c) & 0xFF
            b = (b + a) & 0xFF
        if data[i + 6 + length] == a and data[i + 7 + length] == b:
            yield data[i + 2], data[i + 3], data[i + 6:i + 6 + length]
            i += 8 + length
        else:
            i += 1


def nav_pvt(path):
    with open(path, "rb") as f:
        data = strip_comments(f.read())
    out = []
    for cls, mid, p in ubx_frames(data):
        if cls != 0x01 or mid != 0x07 or len(p) < 84:
            continue
        itow, year, month, day, hour, minute, sec, valid = struct.unpack_from("<IHBBBBBB", p, 0)
        fix_type, flags, _, num_sv = struct.unpack_from("<BBBB", p, 20)
        lon, lat, height, _, hacc, vacc = struct.unpack_from("<iiiiII", p, 24)
        pdop = struct.unpack_from("<H", p, 76)[0]
        out.append(dict(itow=itow, utc=(year, month, day, hour, minute, sec), valid=valid,
                        fix=fix_type, fix_ok=bool(flags & 1), numsv=num_sv, lat=lat * 1e-7,
                        lon=lon * 1e-7, h=height * 1e-3, hacc=hacc * 1e-3, vacc=vacc * 1e-3,
                        pdop=pdop * 0.01))
    return out


def ecef_m(p):
    """WGS 84 geodetic (deg, deg, m) to ECEF (m)."""
    a, f = 6378137.0, 1 / 298.257223563
    e2 = f * (2 - f)
    lat, lon = math.radians(p["lat"]), math.radians(p["lon"])
    n = a / math.sqrt(1 - e2 * math.sin(lat) ** 2)
    return ((n + p["h"]) * math.cos(lat) * math.cos(lon), (n + p["h"]) * math.cos(lat) * math.sin(lon),
            (n * (1 - e2) + p["h"]) * math.sin(lat))


def fix_jumps(pvts):
    """3D distances between consecutive 3D fixes (m): how a navigation filter moves a fix."""
    fixes = [ecef_m(p) for p in pvts if p["fix_ok"] and p["fix"] == 3]
    return [math.dist(a, b) for a, b in zip(fixes, fixes[1:])]


def pct(values, q):
    v = sorted(values)
    if not v:
        return float("nan")
    k = (len(v) - 1) * q
    lo, hi = math.floor(k), math.ceil(k)
    return v[lo] + (v[hi] - v[lo]) * (k - lo)


def simulate(navemu, profile, lat, lon, h, start, duration, seed, work):
    """navemu simulate of a stationary receiver with NAV-PVT on; returns (NAV-PVT list, gnss.csv rows)."""
    src = os.path.join(ROOT, "configs", "gnss", profile + ".yaml")
    with open(src) as f:
        text = f.read()
    if "messages: {}" not in text:
        raise RuntimeError(f"{src}: no 'messages: {{}}' line to enable NAV-PVT in")
    prof = os.path.join(work, profile + "-navpvt.yaml")
    with open(prof, "w") as f:
        f.write(text.replace("messages: {}", "messages: {NAV-PVT: 1}"))
    cfg = os.path.join(work, "run.yaml")
    with open(cfg, "w") as f:
        f.write(config_text(prof, lat, lon, h, start, seed))
    out = os.path.join(work, f"sim{seed}")
    r = subprocess.run([navemu, "simulate", cfg, "--duration", f"{duration:g}", "--out", out],
                       capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(f"navemu simulate failed: {r.stderr.strip()}")
    pvt = nav_pvt(os.path.join(out, "ubx.bin"))
    with open(os.path.join(out, "gnss.csv")) as f:
        rows = list(csv.DictReader(f))
    shutil.rmtree(out)
    return pvt, rows


def config_text(profile_path, lat, lon, h, start, seed):
    return (f"scenario: {{start: \"{start}\", seed: {seed}, status_interval_s: 0}}\n"
            f"truth:\n  source: stationary\n"
            f"  position: {{lat_deg: {lat:.7f}, lon_deg: {lon:.7f}, h_m: {h:.2f}}}\n"
            f"gnss:\n  profile: {profile_path}\n  outputs: []\n"
            f"imu:\n  enabled: false\n")


def plot(out, results):
    png = NAME + "_medians.png"
    with tempfile.TemporaryDirectory() as t:
        dat = os.path.join(t, "m.dat")
        with open(dat, "w") as f:
            for i, r in enumerate(results):
                vals = []
                for key, _, _ in QUANTITIES:
                    vals += [r["real"][key][0], r["real"][key][1], r["sim"][key][0], r["sim"][key][1]]
                f.write(f"{i} " + " ".join(f"{v:.6g}" for v in vals) + f' "{r["label"]}"\n')
        panels = []
        for k, (key, label, unit) in enumerate(QUANTITIES):
            c = 2 + 4 * k
            logy = "set logscale y" if key in ("hacc", "vacc", "pdop") else "unset logscale y"
            logy += "\nset yrange [0.5:300]" if key == "pdop" else "\nset autoscale y"
            yl = f"{label} ({unit})" if unit != "-" else f"{label} (dimensionless)"
            if key == "numsv":
                yl = "numSV (satellites used)"
            panels.append(f"""
{logy}
set title "{label}: median (point) and 95th percentile (bar top)"
set ylabel "{yl}"
plot "{dat}" using ($1-0.12):{c}:{c}:{c + 1}:xticlabels(18) with yerrorbars pt 7 ps 1.4 lw 2 lc rgb "black" title "real receiver", \\
     "{dat}" using ($1+0.12):{c + 2}:{c + 2}:{c + 3} with yerrorbars pt 5 ps 1.4 lw 2 lc rgb "red" title "navemu"
""")
        n = len(results)
        script = f"""
set terminal pngcairo size 1500,1000 font "Sans,12"
set output "{os.path.join(out, png)}"
set multiplot layout 2,2 title "u-blox NAV-PVT reports: real captures vs navemu (same place, start and duration)"
set xrange [-0.6:{n - 0.4}]
set xtics rotate by 20 right font "Sans,10"
set grid ytics
set key top left font "Sans,10"
""" + "\n".join(panels) + "\nunset multiplot\n"
        if not common.run_gnuplot(script, png):
            return None
    return png


def main():
    a = common.real_data_args(NAME, __doc__, "Real u-blox receivers' accuracy reports")
    md_path = os.path.join(a.out, NAME + ".md")
    logs = os.path.join(a.shared, "data", "receiver_logs")
    for rel, *_ in CAPTURES:
        if not os.path.isfile(os.path.join(logs, rel)):
            print(f"{NAME}: missing data file {os.path.join(logs, rel)}", file=sys.stderr)
            return 2
    seeds = SEEDS_QUICK if a.quick else SEEDS_FULL
    t0 = time.time()
    results, failures, gaps, checks = [], 0, 0, 0
    with tempfile.TemporaryDirectory() as work:
        for rel, label, receiver, profile, checked, note in CAPTURES:
            real = nav_pvt(os.path.join(logs, rel))
            if not real:
                print(f"{NAME}: no NAV-PVT frame in {rel}", file=sys.stderr)
                return 2
            fixed = [p for p in real if p["fix_ok"] and p["fix"] in (2, 3, 4, 5)] or real
            lat = statistics.fmean(p["lat"] for p in fixed)
            lon = statistics.fmean(p["lon"] for p in fixed)
            h = statistics.fmean(p["h"] for p in fixed)
            first = real[0]
            if (first["valid"] & 0x03) != 0x03:
                print(f"{NAME}: {rel}: first NAV-PVT has no valid UTC date/time", file=sys.stderr)
                return 2
            start = datetime.datetime(*first["utc"]).strftime("%Y-%m-%dT%H:%M:%SZ")
            span = (real[-1]["itow"] - first["itow"]) / 1000.0 + 1.0
            duration = min(span, QUICK_MAX_S) if a.quick else span
            sim, rows, sim_jumps = [], [], []
            for seed in range(1, seeds + 1):
                p, r = simulate(a.navemu, profile, lat, lon, h, start, duration, seed, work)
                sim += p
                rows += r
                sim_jumps += fix_jumps(p)
            real_jumps = fix_jumps(real)
            res = dict(label=label, receiver=receiver, profile=profile, checked=checked, note=note,
                       rel=rel, n_real=len(real), n_sim=len(sim), start=start, span=span,
                       duration=duration, lat=lat, lon=lon, h=h,
                       fix_real=sorted({p["fix"] for p in real}),
                       hacc_first=real[0]["hacc"], hacc_last=real[-1]["hacc"],
                       config=config_text(f"configs/gnss/{profile}.yaml + messages: {{NAV-PVT: 1}}",
                                          lat, lon, h, start, 1),
                       err_h=(pct([float(r["err_h_m"]) for r in rows], 0.5),
                              pct([float(r["err_h_m"]) for r in rows], 0.95)),
                       err_v=(pct([abs(float(r["err_u_m"])) for r in rows], 0.5),
                              pct([abs(float(r["err_u_m"])) for r in rows], 0.95)))
            for src, lst in (("real", real), ("sim", sim)):
                res[src] = {k: (pct([p[k] for p in lst], 0.5), pct([p[k] for p in lst], 0.95))
                            for k, _, _ in QUANTITIES}
            res["n_jumps"] = len(real_jumps)
            res["jump"] = (pct(real_jumps, 0.5), pct(real_jumps, 0.95), pct(sim_jumps, 0.5),
                           pct(sim_jumps, 0.95))
            res["bands"] = []
            for k in ("hacc", "vacc", "jump"):
                if k == "jump" and len(real_jumps) < JUMP_MIN_EPOCHS:
                    continue
                real_median = res["jump"][0] if k == "jump" else res["real"][k][0]
                sim_median = res["jump"][2] if k == "jump" else res["sim"][k][0]
                ratio = sim_median / real_median if real_median > 0 else float("inf")
                if checked:
                    status = common.print_band(f"real_ublox {label.replace(' ', '_')} median {k} ratio",
                                               ratio, 1 / FACTOR, FACTOR)
                    checks += 1
                    failures += status == common.OUT
                    gaps += status == common.GAP
                    res["bands"].append((k, ratio, status))
                else:
                    res["bands"].append((k, ratio, "not checked"))
            results.append(res)
    png = plot(a.out, results)
    print(f"{NAME}: {checks - failures - gaps} of {checks} median hAcc/vAcc/jump checks within a factor "
          f"{FACTOR:g}, {gaps} known gaps, {failures} OUT ({time.time() - t0:.1f} s)")

    md = ["## Real u-blox receivers' accuracy reports against navemu's", "",
          "NAV-PVT frames (UBX class 0x01 id 0x07, checksum-verified, parsed here in Python) of six "
          "real u-blox captures (`../shared/data/receiver_logs`) and of `navemu simulate` runs of "
          "the matching u-blox profile with NAV-PVT enabled, stationary at the capture's mean "
          "NAV-PVT position, starting at its first NAV-PVT time (UTC) and running as long as the "
          f"capture{f' (quick mode: at most {QUICK_MAX_S} s, seed 1)' if a.quick else ''}; navemu "
          f"figures pool seeds 1..{seeds}. navemu uses its built-in constellations of the systems "
          "the profile tracks at power-up (ublox-m8: GPS, GLONASS, QZSS; ublox-f9p: GPS, GLONASS, "
          "Galileo, BeiDou, QZSS; no broadcast file of those days is in ../shared). Band: navemu's "
          "median hAcc and vAcc "
          "within a factor 2 of the real receiver's (ratio navemu / real), and its median 3D jump "
          f"between consecutive fixes for captures of at least {JUMP_MIN_EPOCHS} epochs.", "",
          "| capture | receiver | profile | start (UTC) | s | real epochs | navemu epochs | "
          "quantity | real median | real 95 % | navemu median | navemu 95 % | band |",
          "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in results:
        for k, label, unit in QUANTITIES:
            b = next((f"{x[1]:.2f}: {x[2]}" for x in r["bands"] if x[0] == k), "")
            fmt = "{:.2f}" if k != "numsv" else "{:.0f}"
            u = f" ({unit})" if unit != "-" else ""
            md.append(f"| {r['label']} | {r['receiver']} | `{r['profile']}` | {r['start']} | "
                      f"{r['duration']:g} | {r['n_real']} | {r['n_sim']} | {label}{u} | "
                      f"{fmt.format(r['real'][k][0])} | {fmt.format(r['real'][k][1])} | "
                      f"{fmt.format(r['sim'][k][0])} | {fmt.format(r['sim'][k][1])} | {b} |")
    md += ["", "Fix-to-fix 3D jumps (m; a real receiver's navigation filter keeps them to centimetres "
           "when stationary; both sides quantised by NAV-PVT's 1e-7 deg and 1 mm):", "",
           "| capture | real jumps | real 50 % / 95 % | navemu 50 % / 95 % | band |", "|---|---|---|---|---|"]
    for r in results:
        b = next((f"{x[1]:.2f}: {x[2]}" for x in r["bands"] if x[0] == "jump"), "")
        j = ["-" if math.isnan(x) else f"{x:.3f}" for x in r["jump"]]
        md.append(f"| {r['label']} | {r['n_jumps']} | {j[0]} / {j[1]} | {j[2]} / {j[3]} | {b} |")
    md.append("")
    if png:
        md += [f"![NAV-PVT hAcc, vAcc, pDOP, numSV: real vs navemu]({png})", "",
               "*Figure: per capture, median (point) and 95th percentile (bar top) of the reported "
               "hAcc, vAcc (m), pDOP and numSV; black the real receiver, red navemu (configurations "
               "below). A pDOP of 99.99 is u-blox's value for 'not available'.*", ""]
    md += ["navemu's own error against the truth in the same runs (from gnss.csv), to show whether "
           "its hAcc/vAcc are consistent with what it delivers:", "",
           "| capture | navemu horizontal error 50 % / 95 % (m) | navemu vertical error 50 % / 95 % (m) | "
           "navemu hAcc / vAcc median (m) |", "|---|---|---|---|"]
    for r in results:
        md.append(f"| {r['label']} | {r['err_h'][0]:.2f} / {r['err_h'][1]:.2f} | {r['err_v'][0]:.2f} / "
                  f"{r['err_v'][1]:.2f} | {r['sim']['hacc'][0]:.2f} / {r['sim']['vacc'][0]:.2f} |")
    md += ["", "Configurations (`navemu simulate CONFIG --duration S --out DIR`; the profile is "
           "the named one with `ubx.messages: {NAV-PVT: 1}` instead of `{}`):", ""]
    for r in results:
        md += [f"- {r['label']} (`{r['rel']}`, {r['duration']:g} s, seeds 1..{seeds}; seed 1 shown):", "",
               "  ```yaml"] + ["  " + line for line in r["config"].splitlines()] + ["  ```", ""]
    md += ["Captures not band-checked, and why:", ""]
    for r in results:
        if not r["checked"]:
            md.append(f"- {r['label']}: {r['note']} (ratios shown in the table for information).")
    md += ["", "Where navemu differs beyond the band (known gaps of tools/validation/known_gaps.json "
           "unless marked OUT), and why:", ""]
    outs = [r for r in results if r["checked"] and any(x[2] != common.OK for x in r["bands"])]
    if not outs:
        md.append("- none")
    for r in outs:
        md.append(f"- {r['label']}: real median {r['real']['numsv'][0]:.0f} satellites used, pDOP "
                  f"{r['real']['pdop'][0]:.2f}, hAcc first -> last epoch {r['hacc_first']:.2f} -> "
                  f"{r['hacc_last']:.2f} m; navemu {r['sim']['numsv'][0]:.0f} satellites, pDOP "
                  f"{r['sim']['pdop'][0]:.2f}, hAcc {r['sim']['hacc'][0] / max(r['err_h'][0], 1e-9):.1f}x "
                  "its own median horizontal error.")
        for k, ratio, status in r["bands"]:
            if status != common.OK:
                band = f"real_ublox {r['label'].replace(' ', '_')} median {k} ratio"
                md.append(f"  - {k} {ratio:.2f} ({status}): {common.gap_why(band)}.")
    md.append("")
    md += ["Limits: u-blox does not document how hAcc/vAcc are computed, so "
           "only the order of magnitude is comparable; the real captures are short (7-300 s) and "
           "one sky each; the real heights are used as ellipsoidal (NAV-PVT `height`).", ""]
    with open(md_path, "w") as f:
        f.write("\n".join(md))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
