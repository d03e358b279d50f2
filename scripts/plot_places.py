#!/usr/bin/env python3
"""Precision-recall curves of an `evaluate_places --reference A --query B` run: every method on one
plot, the legend giving each method's recall@1 and PR AUC.

usage: plot_places.py RUN_DIR [TITLE]
Reads RUN_DIR/pr_curves.csv and RUN_DIR/queries.csv, writes RUN_DIR/pr_curve.png.
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    run = sys.argv[1]
    title = sys.argv[2] if len(sys.argv) > 2 else os.path.basename(os.path.normpath(run))
    curves, right, total = {}, {}, {}
    with open(os.path.join(run, "pr_curves.csv")) as f:
        for row in csv.DictReader(f):
            curves.setdefault(row["method"], []).append(
                (float(row["recall"]), float(row["precision"])))
    with open(os.path.join(run, "queries.csv")) as f:
        for row in csv.DictReader(f):
            m = row["method"]
            right[m] = right.get(m, 0) + int(row["right"])
            total[m] = total.get(m, 0) + 1
    fig, ax = plt.subplots(figsize=(6, 5))
    for method, points in curves.items():
        r = [0.0] + [p[0] for p in points]
        p = [points[0][1]] + [p[1] for p in points]
        auc = sum((r[i] - r[i - 1]) * 0.5 * (p[i] + p[i - 1]) for i in range(1, len(r)))
        label = "%s (R@1 %.2f, AUC %.2f)" % (method, right[method] / total[method], auc)
        ax.plot(r, p, label=label, linewidth=2.5 if method == "sequence" else 1.2)
    ax.set_xlabel("recall")
    ax.set_ylabel("precision")
    ax.set_xlim(0, 1)
    ax.set_ylim(0, 1.02)
    ax.grid(alpha=0.3)
    ax.set_title(title)
    ax.legend(loc="lower left", fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(run, "pr_curve.png"), dpi=100)


if __name__ == "__main__":
    main()
