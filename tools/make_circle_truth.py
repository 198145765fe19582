#!/usr/bin/env python3
"""Writes configs/truth/circle_paper.csv: the paper's circular test track as a navemu truth CSV.

Durst & Goodin drove 8 loops of a 30 ft (9.144 m) radius circle at their site near Vicksburg,
MS (32.3 N, 90.9 W). Here: centre at 32.3 N, 90.9 W, 60 m above the WGS-84 ellipsoid;
constant speed 2 m/s, clockwise seen from above (north, east, south, west: a right turn, so in
the FRD body frame the centripetal specific force is +y and the yaw rate +z); level, heading
tangent to the circle; sampled at 10 Hz from t = 0 until just past the end of the eighth loop.

The circle is laid out in the local north/east plane of the centre and mapped to latitude and
longitude with the WGS-84 radii of curvature at the centre (Groves eqs. 2.105, 2.106):
lat = lat0 + n / (R_N + h), lon = lon0 + e / ((R_E + h) cos lat0).

Usage: python3 tools/make_circle_truth.py [OUT.csv]   (standard library only)
"""

import math
import sys

LAT0_DEG, LON0_DEG, H_M = 32.3, -90.9, 60.0
RADIUS_M = 9.144  # 30 ft
SPEED_MPS = 2.0
LOOPS = 8
RATE_HZ = 10.0

# WGS-84 (NIMA TR8350.2)
A_M = 6378137.0
F = 1.0 / 298.257223563
E2 = F * (2.0 - F)


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "configs/truth/circle_paper.csv"
    lat0 = math.radians(LAT0_DEG)
    s = math.sin(lat0)
    d = 1.0 - E2 * s * s
    r_n = A_M * (1.0 - E2) / (d * math.sqrt(d)) + H_M
    r_e = A_M / math.sqrt(d) + H_M
    omega = SPEED_MPS / RADIUS_M  # rad/s
    period_s = 2.0 * math.pi / omega
    rows = math.ceil(LOOPS * period_s * RATE_HZ) + 1  # the last row just past the eighth loop
    with open(out, "w", newline="\n") as f:
        f.write("time_s,lat_deg,lon_deg,h_m,v_n_mps,v_e_mps,v_d_mps,roll_deg,pitch_deg,yaw_deg\n")
        for k in range(rows):
            t = k / RATE_HZ
            phi = omega * t  # angle about the centre, from north, clockwise
            north = RADIUS_M * math.cos(phi)
            east = RADIUS_M * math.sin(phi)
            v_n = -SPEED_MPS * math.sin(phi)
            v_e = SPEED_MPS * math.cos(phi)
            lat = LAT0_DEG + math.degrees(north / r_n)
            lon = LON0_DEG + math.degrees(east / (r_e * math.cos(lat0)))
            yaw = math.degrees(phi) + 90.0
            yaw -= 360.0 * math.floor((yaw + 180.0) / 360.0)  # [-180, 180)
            f.write(f"{t:.1f},{lat:.11f},{lon:.11f},{H_M:.3f},{v_n:.9f},{v_e:.9f},0,0,0,{yaw:.9f}\n")


if __name__ == "__main__":
    main()
