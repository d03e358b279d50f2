#!/usr/bin/env python3
"""Calibrates a robot camera from field features marked by hand on images taken at known robot
positions (data/calibration/nao_v6_top_marks.csv): a least-squares fit of the focal length (shared by
all images, square pixels, principal point at the image centre) and, per image, the height of the
pan axis above the ground (base_to_pan_m z), the camera's pitch beyond the recorded head pitch, and
the robot's heading (not known from the motion capture). The lens's offset from the pitch axis is the
published one (--lens_x_m, --lens_z_m). Where the marks give each image's torso pitch (the inertial
unit's), each fit also prints torso_pitch_reference_rad: their mean, at which camera_pitch_rad holds.
Prints each image's fit and residuals, the fit over all images (the numbers
config/cameras/nao_v6_top.yaml holds) and a leave-one-image-out fit for each image (the camera to
evaluate that image with, calibrated without it).

usage: calibrate_head_camera.py MARKS.csv [--width 640 --height 480 --lens_x_m 0.05871 --lens_z_m 0.06364]
"""
import argparse
import csv
import math

import numpy as np


def read_marks(path):
    with open(path, newline="") as f:
        rows = [r for r in csv.reader(line for line in f if not line.startswith("#"))]
    header, rows = rows[0], rows[1:]
    out = {}
    for r in rows:
        d = dict(zip(header, r))
        p = out.setdefault(d["point"], {"robot": (float(d["robot_x_m"]), float(d["robot_y_m"])),
                                        "head_pitch": float(d["head_pitch_rad"]),
                                        "head_yaw": float(d["head_yaw_rad"]),
                                        "torso_pitch": float(d["torso_pitch_rad"])
                                        if d.get("torso_pitch_rad") else None, "marks": []})
        p["marks"].append((float(d["field_x_m"]), float(d["field_y_m"]), float(d["u_px"]),
                           float(d["v_px"])))
    return out


def project(point, pan_z, pitch_extra, heading, f, args):
    """Pixels of the point's marks for a camera on the chain: yaw turns about the pan axis, the lens
    sits lens_x ahead and lens_z above the pitch axis and pitches with it."""
    p = point["head_pitch"] + pitch_extra
    yaw = heading + point["head_yaw"]
    lx = args.lens_x_m * math.cos(p) + args.lens_z_m * math.sin(p)
    lz = pan_z + args.lens_z_m * math.cos(p) - args.lens_x_m * math.sin(p)
    cx, cy = args.width / 2.0, args.height / 2.0
    out = []
    for fx, fy, _, _ in point["marks"]:
        dx, dy = fx - point["robot"][0], fy - point["robot"][1]
        fwd = math.cos(yaw) * dx + math.sin(yaw) * dy - lx
        left = -math.sin(yaw) * dx + math.cos(yaw) * dy
        up = -lz
        depth = math.cos(p) * fwd - math.sin(p) * up
        down = -(math.sin(p) * fwd + math.cos(p) * up)
        out += [cx + f * (-left) / depth, cy + f * down / depth]
    return np.array(out)


def fit(points, names, args):
    """Gauss-Newton with a numeric Jacobian over [f, (pan_z, pitch_extra, heading) per image]."""
    def residuals(x):
        res = []
        for i, n in enumerate(names):
            pan_z, pitch, heading = x[1 + 3 * i:4 + 3 * i]
            obs = np.array([v for m in points[n]["marks"] for v in m[2:]])
            res.append(project(points[n], pan_z, pitch, heading, x[0], args) - obs)
        return np.concatenate(res)

    x = [600.0]
    for n in names:  # heading: towards the marks' centre
        mx = np.mean([m[0] for m in points[n]["marks"]]) - points[n]["robot"][0]
        my = np.mean([m[1] for m in points[n]["marks"]]) - points[n]["robot"][1]
        x += [0.35, 0.0, math.atan2(my, mx)]
    x = np.array(x)
    for _ in range(100):
        r = residuals(x)
        jac = np.empty((r.size, x.size))
        for k in range(x.size):
            h = 1e-6 * max(1.0, abs(x[k]))
            e = np.zeros_like(x)
            e[k] = h
            jac[:, k] = (residuals(x + e) - r) / h
        step = np.linalg.lstsq(jac, -r, rcond=None)[0]
        x += step
        if np.max(np.abs(step)) < 1e-10:
            break
    return x, residuals(x)


def summary(label, names, x, r):
    pan_z = np.mean(x[1::3])
    pitch = np.mean(x[2::3])
    hfov = math.degrees(2 * math.atan(0.5 * args.width / x[0]))
    # The inertial unit's torso pitch at which camera_pitch_rad holds: the mean over the same
    # images (HeadChain::leanRad() leans the head by a later reading's difference from it).
    torso = [points[n]["torso_pitch"] for n in names]
    reference = (f" torso_pitch_reference_rad={np.mean(torso):.4f}"
                 if all(t is not None for t in torso) else "")
    print(f"calibrate_head_camera: fit={label} images={len(names)} fx_px={x[0]:.1f} "
          f"hfov_deg={hfov:.2f} base_to_pan_z_m={pan_z:.4f} camera_pitch_rad={pitch:.4f}"
          f"{reference} rms_px={math.sqrt(np.mean(r ** 2)):.2f} max_px={np.max(np.abs(r)):.2f}")
    return x[0], pan_z, pitch


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("marks")
    ap.add_argument("--width", type=int, default=640)
    ap.add_argument("--height", type=int, default=480)
    ap.add_argument("--lens_x_m", type=float, default=0.05871)
    ap.add_argument("--lens_z_m", type=float, default=0.06364)
    args = ap.parse_args()
    points = read_marks(args.marks)
    names = sorted(points)
    x, r = fit(points, names, args)
    offset = 0
    for i, n in enumerate(names):
        k = 2 * len(points[n]["marks"])
        ri = r[offset:offset + k]
        offset += k
        print(f"  {n}: base_to_pan_z_m={x[1 + 3 * i]:.4f} camera_pitch_rad={x[2 + 3 * i]:.4f} "
              f"heading_deg={math.degrees(x[3 + 3 * i]):.1f} rms_px={math.sqrt(np.mean(ri ** 2)):.2f}")
    # Does the inertial unit see what the images do? Each image's pitch beyond the mean against
    # its torso pitch beyond theirs (the lean HeadChain::leanRad() would give it).
    torso = [points[n]["torso_pitch"] for n in names]
    if all(t is not None for t in torso):
        for i, n in enumerate(names):
            print(f"  {n}: pitch_beyond_mean_rad={x[2 + 3 * i] - np.mean(x[2::3]):.4f} "
                  f"torso_pitch_beyond_mean_rad={torso[i] - np.mean(torso):.4f}")
    summary("all", names, x, r)
    if len(names) > 1:
        for n in names:
            rest = [m for m in names if m != n]
            xr, rr = fit(points, rest, args)
            summary("without_" + n, rest, xr, rr)
