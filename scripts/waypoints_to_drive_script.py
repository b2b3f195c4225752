#!/usr/bin/env python3
"""Turns a list of waypoints into an irgs drive script (turn on the spot, pause, drive straight).

usage: waypoints_to_drive_script.py START_THETA_DEG X0,Y0 X1,Y1 ... [--speed M/S] [--turn DEG/S]
       [--end-spin] [--end S]
Times are computed from the nominal speeds; the profile's acceleration limits make each move
start and stop smoothly (symmetric, so the distance comes out about right).
"""
import argparse
import math


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("theta_deg", type=float)
    ap.add_argument("points", nargs="+")
    ap.add_argument("--speed", type=float, default=0.25)
    ap.add_argument("--turn", type=float, default=60.0)
    ap.add_argument("--pause", type=float, default=0.6)
    ap.add_argument("--end-spin", action="store_true")
    ap.add_argument("--end", type=float, default=None)
    a = ap.parse_args()
    pts = [tuple(float(v) for v in p.split(",")) for p in a.points]
    t, theta = 0.0, math.radians(a.theta_deg)
    lines = []
    for (x0, y0), (x1, y1) in zip(pts, pts[1:]):
        heading = math.atan2(y1 - y0, x1 - x0)
        turn = math.atan2(math.sin(heading - theta), math.cos(heading - theta))
        if abs(turn) > 1e-3:
            omega = math.copysign(a.turn, turn)
            lines.append(f"{t:7.2f}  drive 0 {omega:g}")
            t += abs(math.degrees(turn)) / a.turn
            lines.append(f"{t:7.2f}  stop")
            t += a.pause
        dist = math.hypot(x1 - x0, y1 - y0)
        lines.append(f"{t:7.2f}  drive {a.speed:g} 0      # to ({x1:g}, {y1:g})")
        t += dist / a.speed
        lines.append(f"{t:7.2f}  stop")
        t += a.pause
        theta = heading
    if a.end_spin:
        lines.append(f"{t:7.2f}  drive 0 {a.turn:g}      # look around once")
        t += 360.0 / a.turn
        lines.append(f"{t:7.2f}  stop")
    if a.end is not None and a.end > t:
        lines.append(f"{a.end:7.2f}  stop")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
