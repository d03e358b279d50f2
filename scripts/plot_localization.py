#!/usr/bin/env python3
"""Plots one evaluate_localization run: errors and classification rate over time (error.png) and the
field with the true and estimated paths (field.png, the colour paper's Fig. 3).

usage: plot_localization.py RUN_DIR FIELD.yaml TITLE
RUN_DIR holds evaluate_localization's frames.csv, estimate.tum and truth.tum.
"""
import csv
import math
import os
import sys

import matplotlib
import yaml

matplotlib.use("Agg")
import matplotlib.patches as patches  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402


def tum(path):
    xs, ys = [], []
    with open(path) as f:
        for line in f:
            v = line.split()
            if len(v) >= 3:
                xs.append(float(v[1]))
                ys.append(float(v[2]))
    return xs, ys


COLOURS = {"green": "#3cb043", "white": "white", "pink": "hotpink", "yellow": "gold",
           "cyan": "deepskyblue", "orange": "darkorange"}
# The four-legged field's beacons (world::fourLeggedBeacons): a file without `landmarks` has them.
DEFAULT_LANDMARKS = [
    {"x_m": sx * 1.35, "y_m": sy * 1.95, "radius_m": 0.05,
     "bands": [{"color": "white"}, {"color": ("yellow" if sx < 0 else "cyan") if sy < 0 else "pink"},
               {"color": "pink" if sy < 0 else ("yellow" if sx < 0 else "cyan")}]}
    for sx in (-1, 1) for sy in (-1, 1)]


def draw_field(ax, field):
    """The field as docs/fields.md describes it: carpet, lines, goals in their colours, and each
    landmark as a disc in its top band's colour ringed by the band below."""
    length = field.get("field_length_m", 5.4)
    width = field.get("field_width_m", 3.6)
    margin = field.get("carpet_margin_m", 0.3)
    goal_w = field.get("goal_width_m", 0.8)
    goal_d = field.get("goal_depth_m", 0.3)
    circle = field.get("centre_circle_diameter_m", 0.36)
    ax.add_patch(patches.Rectangle((-length / 2 - margin, -width / 2 - margin), length + 2 * margin,
                                   width + 2 * margin, color="#2e8b3a", zorder=0))
    ax.add_patch(patches.Rectangle((-length / 2, -width / 2), length, width, fill=False,
                                   edgecolor="white", lw=1.5, zorder=1))
    ax.plot([0, 0], [-width / 2, width / 2], color="white", lw=1.5, zorder=1)
    ax.add_patch(patches.Circle((0, 0), circle / 2, fill=False, edgecolor="white", lw=1.5, zorder=1))
    for sign, key, default in ((-1, "goal_color_minus_x", "yellow"), (1, "goal_color_plus_x", "cyan")):
        colour = COLOURS.get(field.get(key, default), "gray")
        x0 = -length / 2 - goal_d if sign < 0 else length / 2
        ax.add_patch(patches.Rectangle((x0, -goal_w / 2), goal_d, goal_w, fill=False,
                                       edgecolor=colour, lw=2.5, zorder=1))
    for lm in field.get("landmarks", DEFAULT_LANDMARKS) or []:
        bands = lm.get("bands") or [{"color": "white"}]
        r = max(lm.get("radius_m", 0.05), 0.07)
        below = bands[-2]["color"] if len(bands) > 1 else bands[-1]["color"]
        ax.add_patch(patches.Circle((lm["x_m"], lm["y_m"]), r * 1.6, color=COLOURS.get(below, "gray"),
                                    zorder=2))
        ax.add_patch(patches.Circle((lm["x_m"], lm["y_m"]), r, color=COLOURS.get(bands[-1]["color"], "gray"),
                                    zorder=3))


def main(argv):
    if len(argv) != 4:
        print(__doc__)
        return 2
    run, field_file, title = argv[1:]
    with open(field_file) as f:
        field = yaml.safe_load(f) or {}
    rows = list(csv.DictReader(open(os.path.join(run, "frames.csv"))))
    t = [float(r["t_s"]) for r in rows]
    fig, ax = plt.subplots(3, 1, figsize=(8, 6), sharex=True)
    ax[0].plot(t, [float(r["position_error_m"]) for r in rows], color="tab:blue")
    ax[0].axhline(0.1, color="gray", ls="--", lw=0.8)
    ax[0].set_ylabel("position error (m)")
    ax[0].set_yscale("log")
    ax[1].plot(t, [float(r["heading_error_deg"]) for r in rows], color="tab:orange")
    ax[1].axhline(5.0, color="gray", ls="--", lw=0.8)
    ax[1].set_ylabel("heading error (deg)")
    ax[1].set_yscale("log")
    ax[2].plot(t, [float(r["classification_rate"]) for r in rows], color="tab:green")
    ax[2].set_ylabel("classification rate")
    ax[2].set_xlabel("time (s)")
    ax[2].set_ylim(0, 1.02)
    ax[0].set_title(title)
    fig.tight_layout()
    fig.savefig(os.path.join(run, "error.png"), dpi=100)

    fig, ax = plt.subplots(figsize=(7, 5))
    draw_field(ax, field)
    tx, ty = tum(os.path.join(run, "truth.tum"))
    ex, ey = tum(os.path.join(run, "estimate.tum"))
    ax.plot(tx, ty, color="red", lw=2, label="true path")
    ax.plot(ex, ey, color="cyan", lw=1, marker=".", ms=3, label="estimate")
    if tx:
        ax.plot(tx[0], ty[0], "o", color="red", ms=6)
    ax.set_aspect("equal")
    half_l = field.get("field_length_m", 5.4) / 2 + field.get("carpet_margin_m", 0.3) + 0.3
    half_w = field.get("field_width_m", 3.6) / 2 + field.get("carpet_margin_m", 0.3) + 0.3
    ax.set_xlim(-half_l, half_l)
    ax.set_ylim(-half_w, half_w)
    ax.legend(loc="upper right", fontsize=8)
    ax.set_title(title)
    fig.tight_layout()
    fig.savefig(os.path.join(run, "field.png"), dpi=100)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
