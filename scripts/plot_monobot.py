#!/usr/bin/env python3
"""Plots monobot_experiment's first runs like the paper's Figs. 4-6: one row per model (standard,
anchor, external), columns: trajectory with estimates and 2-sigma bounds, robot error, landmark
error, Kalman gains. Writes DIR/monobot.png.

usage: plot_monobot.py DIR
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def load(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return {k: [float(r[k]) for r in rows] for k in rows[0]}


def main():
    out = sys.argv[1]
    models = ["standard", "anchor", "external"]
    fig, axes = plt.subplots(3, 4, figsize=(16, 10), sharex=True)
    for row, model in enumerate(models):
        d = load(os.path.join(out, model + "_run.csv"))
        k = d["step"]
        ax = axes[row][0]
        ax.plot(k, d["true_robot_m"], "k", label="robot (true)")
        ax.plot(k, d["est_robot_m"], color="tab:blue", label="robot (estimate)")
        ax.fill_between(k, [e - 2 * s for e, s in zip(d["est_robot_m"], d["robot_std_m"])],
                        [e + 2 * s for e, s in zip(d["est_robot_m"], d["robot_std_m"])],
                        color="tab:blue", alpha=0.2)
        ax.plot(k, d["true_landmark_m"], "k--", label="landmark (true)")
        ax.plot(k, d["est_landmark_m"], color="tab:red", label="landmark (estimate)")
        ax.fill_between(k, [e - 2 * s for e, s in zip(d["est_landmark_m"], d["landmark_std_m"])],
                        [e + 2 * s for e, s in zip(d["est_landmark_m"], d["landmark_std_m"])],
                        color="tab:red", alpha=0.2)
        ax.set_ylabel(model + "\nposition (m)")
        if row == 0:
            ax.legend(fontsize=7)
        for col, (est, true, sd, label) in enumerate(
                [("est_robot_m", "true_robot_m", "robot_std_m", "robot error (m)"),
                 ("est_landmark_m", "true_landmark_m", "landmark_std_m", "landmark error (m)")]):
            ax = axes[row][col + 1]
            err = [a - b for a, b in zip(d[est], d[true])]
            ax.plot(k, err, "k")
            ax.plot(k, [2 * s for s in d[sd]], "k:")
            ax.plot(k, [-2 * s for s in d[sd]], "k:")
            ax.axhline(0, color="gray", lw=0.5)
            ax.set_title(label if row == 0 else "")
        ax = axes[row][3]
        ax.plot(k[1:], d["robot_gain"][1:], "k", label="robot gain")
        ax.plot(k[1:], d["landmark_gain"][1:], color="tab:orange", label="landmark gain")
        if row == 0:
            ax.set_title("Kalman gains (landmark 1 innovation)")
            ax.legend(fontsize=7)
    for ax in axes[2]:
        ax.set_xlabel("step")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "monobot.png"), dpi=80)


if __name__ == "__main__":
    main()
