#!/usr/bin/env python3
"""Writes evaluate_field_localization's --list for the NAO field development set (or a session of
the same layout): one line per point folder with its top (or bottom) camera image, the head angles
the robot recorded at the picture, the torso's pitch from its inertial unit (AngleY), and the
motion-capture position (median of the take's last two seconds, when the robot was no longer
touched; field frame x = X, y = -Z).

usage: nao_field_list.py SESSION_DIR OUTPUT.csv [top|bottom]
SESSION_DIR holds puntN/ folders with imagetop.jpg, imagebottom.jpg, record.csv and pointN.csv
(../shared/data/field/README.md). Image paths are written absolute (the session folder's symlinks resolved).
OUTPUT.csv is not replaced if it exists.
"""
import csv
import os
import statistics
import sys


def mocap_last_seconds(path, seconds=2.0):
    """The take's rows of its last `seconds` that hold a rotation and a position."""
    with open(path, newline="") as f:
        rows = [r for r in csv.reader(f)][7:]
    rows = [r for r in rows if len(r) >= 8 and all(r[i] for i in (1, 2, 3, 4, 5, 6, 7))]
    if not rows:
        raise SystemExit(f"{path}: no motion-capture rows with a rotation and a position")
    end = float(rows[-1][1])
    return [r for r in rows if float(r[1]) >= end - seconds]


def mocap_xy(path):
    last = mocap_last_seconds(path)
    return (statistics.median(float(r[5]) for r in last),
            -statistics.median(float(r[7]) for r in last))


def mocap_rotation_deg(path):
    """The rigid body's rotation X, Y, Z (degrees, the export's XYZ order), medians."""
    last = mocap_last_seconds(path)
    return tuple(statistics.median(float(r[i]) for r in last) for i in (2, 3, 4))


def head_angles(path):
    """HeadPitch, HeadYaw (sensors) and the inertial unit's torso pitch (AngleY; None if the record
    has no angley column) at the picture."""
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows or "headpitchsens" not in rows[-1] or "headyawsens" not in rows[-1]:
        raise SystemExit(f"{path}: expected columns headpitchsens and headyawsens")
    torso = rows[-1].get("angley")
    return (float(rows[-1]["headpitchsens"]), float(rows[-1]["headyawsens"]),
            float(torso) if torso else None)


def main():
    if len(sys.argv) not in (3, 4) or (len(sys.argv) == 4 and sys.argv[3] not in ("top", "bottom")):
        raise SystemExit(__doc__)
    session, output = sys.argv[1], sys.argv[2]
    camera = sys.argv[3] if len(sys.argv) == 4 else "top"
    if os.path.exists(output):
        raise SystemExit(f"{output} exists; remove it first")
    points = sorted((d for d in os.listdir(session) if d.startswith("punt")),
                    key=lambda d: int("".join(ch for ch in d if ch.isdigit()) or 0))
    if not points:
        raise SystemExit(f"{session}: no puntN folders")
    lines = ["image,head_pitch_rad,head_yaw_rad,x_m,y_m,torso_pitch_rad"]
    for p in points:
        folder = os.path.join(session, p)
        number = "".join(ch for ch in p if ch.isdigit())
        x, y = mocap_xy(os.path.join(folder, f"point{number}.csv"))
        pitch, yaw, torso = head_angles(os.path.join(folder, "record.csv"))
        image = os.path.join(os.path.realpath(session), p, f"image{camera}.jpg")
        torso_text = f"{torso:.6f}" if torso is not None else ""
        lines.append(f"{image},{pitch:.6f},{yaw:.6f},{x:.4f},{y:.4f},{torso_text}")
    with open(output, "w") as f:
        f.write("\n".join(lines) + "\n")
    print(f"nao_field_list: points={len(points)} output={output}")


if __name__ == "__main__":
    main()
