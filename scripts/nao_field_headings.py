#!/usr/bin/env python3
"""Each point's heading on the field from the motion capture: the rigid body's yaw (the direction of
its X axis in the ground plane, field frame x = X, y = -Z) plus one offset, the body's markers' turn
against the robot's forward axis, which the capture does not know. The offset is fitted at the points
whose heading was calibrated from the image (docs/cameras.md: calibrate_head_camera.py), and its spread
over them says how far the two agree.

usage: nao_field_headings.py SESSION_DIR POINT=HEADING_DEG [POINT=HEADING_DEG ...]
e.g.   nao_field_headings.py ../shared/data/field/nao_spl_field/red1 punt1=-153.9 punt4=1.6
Prints one line a point (point, mocap_yaw_deg, heading_deg, heading_rad) and a summary line
  nao_field_headings: offset_deg=.. offset_spread_deg=.. calibrated=N
"""
import math
import os
import sys

from nao_field_list import mocap_rotation_deg


def rotation(axis, degrees):
    c, s = math.cos(math.radians(degrees)), math.sin(math.radians(degrees))
    if axis == "x":
        return [[1, 0, 0], [0, c, -s], [0, s, c]]
    if axis == "y":
        return [[c, 0, s], [0, 1, 0], [-s, 0, c]]
    return [[c, -s, 0], [s, c, 0], [0, 0, 1]]


def matmul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(3)) for j in range(3)] for i in range(3)]


def mocap_yaw_deg(path):
    rx, ry, rz = mocap_rotation_deg(path)
    r = matmul(matmul(rotation("x", rx), rotation("y", ry)), rotation("z", rz))
    x_axis = [r[0][0], r[1][0], r[2][0]]  # the body's X axis in the capture's frame (Y up)
    return math.degrees(math.atan2(-x_axis[2], x_axis[0]))


def wrap(deg):
    return (deg + 180.0) % 360.0 - 180.0


def main():
    if len(sys.argv) < 3:
        raise SystemExit(__doc__)
    session = sys.argv[1]
    calibrated = {}
    for arg in sys.argv[2:]:
        point, _, value = arg.partition("=")
        try:
            calibrated[point] = float(value)
        except ValueError:
            raise SystemExit(f"{arg}: expected POINT=HEADING_DEG, e.g. punt1=-153.9")
    points = sorted((d for d in os.listdir(session) if d.startswith("punt")),
                    key=lambda d: int("".join(ch for ch in d if ch.isdigit()) or 0))
    yaw = {}
    for p in points:
        number = "".join(ch for ch in p if ch.isdigit())
        yaw[p] = mocap_yaw_deg(os.path.join(session, p, f"point{number}.csv"))
    missing = [p for p in calibrated if p not in yaw]
    if missing:
        raise SystemExit(f"{session}: no point folder for {', '.join(missing)}")
    # The offset: the circular mean of calibrated minus capture.
    diffs = [math.radians(wrap(h - yaw[p])) for p, h in calibrated.items()]
    offset = math.degrees(math.atan2(sum(math.sin(d) for d in diffs),
                                     sum(math.cos(d) for d in diffs)))
    spread = max(abs(wrap(math.degrees(d) - offset)) for d in diffs)
    print("point,mocap_yaw_deg,heading_deg,heading_rad")
    for p in points:
        h = wrap(yaw[p] + offset)
        print(f"{p},{yaw[p]:.1f},{h:.1f},{math.radians(h):.3f}")
    print(f"nao_field_headings: offset_deg={offset:.1f} offset_spread_deg={spread:.1f} "
          f"calibrated={len(calibrated)}")


if __name__ == "__main__":
    main()
