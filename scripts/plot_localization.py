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


def draw_field(ax, field):
    length = field.get("field_length_m", 5.4)
    width = field.get("field_width_m", 3.6)
    margin = field.get("carpet_margin_m", 0.3)
    goal_w = field.get("goal_width_m", 0.8)
    goal_d = field.get("goal_depth_m", 0.3)
    circle = field.get("centre_circle_diameter_m", 0.36)
    bx, by = field.get("beacon_x_m", 1.35), field.get("beacon_y_m", 1.95)
    ax.add_patch(patches.Rectangle((-length / 2 - margin, -width / 2 - margin), length + 2 * margin,
                                   width + 2 * margin, color="#2e8b3a", zorder=0))
    ax.add_patch(patches.Rectangle((-length / 2, -width / 2), length, width, fill=False,
                                   edgecolor="white", lw=1.5, zorder=1))
    ax.plot([0, 0], [-width / 2, width / 2], color="white", lw=1.5, zorder=1)
    ax.add_patch(patches.Circle((0, 0), circle / 2, fill=False, edgecolor="white", lw=1.5, zorder=1))
    ax.add_patch(patches.Rectangle((-length / 2 - goal_d, -goal_w / 2), goal_d, goal_w,
                                   color="gold", zorder=1))
    ax.add_patch(patches.Rectangle((length / 2, -goal_w / 2), goal_d, goal_w, color="deepskyblue",
                                   zorder=1))
    for sx in (-1, 1):
        for sy in (-1, 1):
            ax.add_patch(patches.Circle((sx * bx, sy * by), 0.07, color="hotpink", zorder=2))


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
    ax.set_xlim(-3.3, 3.3)
    ax.set_ylim(-2.4, 2.4)
    ax.legend(loc="upper right", fontsize=8)
    ax.set_title(title)
    fig.tight_layout()
    fig.savefig(os.path.join(run, "field.png"), dpi=100)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
