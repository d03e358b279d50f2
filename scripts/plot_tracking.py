#!/usr/bin/env python3
"""Success and precision plots of evaluate_tracking runs (OTB one-pass evaluation), every tracker
on one plot: the curves of one run, or averaged over several (each sequence weighs the same).

usage: plot_tracking.py OUT.png TITLE RUN_DIR [RUN_DIR ...]
Each RUN_DIR holds evaluate_tracking's curves.csv. The legend gives each tracker's success AUC
(left) and precision at 20 px (right), as the benchmarks' plots do.
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

NAMES = {"ours": "ours (box CONDENSATION)", "csrt": "OpenCV CSRT", "kcf": "OpenCV KCF",
         "camshift": "CamShift"}
COLOURS = {"ours": "tab:green", "csrt": "tab:blue", "kcf": "tab:cyan", "camshift": "tab:purple"}


def read(run_dir):
    curves = {}
    with open(os.path.join(run_dir, "curves.csv")) as f:
        for row in csv.DictReader(f):
            key = (row["tracker"], row["curve"])
            curves.setdefault(key, []).append((float(row["threshold"]), float(row["value"])))
    return curves


def main():
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    out, title, runs = sys.argv[1], sys.argv[2], sys.argv[3:]
    total, count = {}, {}
    for run in runs:
        for key, points in read(run).items():
            if key not in total:
                total[key] = [list(p) for p in points]
                count[key] = 1
            else:
                for acc, p in zip(total[key], points):
                    acc[1] += p[1]
                count[key] += 1
    fig, (ax_s, ax_p) = plt.subplots(1, 2, figsize=(11, 4.2))
    trackers = [t for t in ["ours", "csrt", "kcf", "camshift"] if (t, "success") in total]
    for t in trackers:
        s = [(x, v / count[(t, "success")]) for x, v in total[(t, "success")]]
        p = [(x, v / count[(t, "precision")]) for x, v in total[(t, "precision")]]
        auc = sum(v for _, v in s) / len(s)
        p20 = dict(p).get(20.0, float("nan"))
        width = 2.5 if t == "ours" else 1.5
        ax_s.plot([x for x, _ in s], [v for _, v in s], color=COLOURS[t], lw=width,
                  label="%s [%.3f]" % (NAMES[t], auc))
        ax_p.plot([x for x, _ in p], [v for _, v in p], color=COLOURS[t], lw=width,
                  label="%s [%.3f]" % (NAMES[t], p20))
    ax_s.set(xlabel="overlap threshold (IoU)", ylabel="success rate", xlim=(0, 1), ylim=(0, 1),
             title="Success plot of OPE")
    ax_p.set(xlabel="location error threshold (px)", ylabel="precision", xlim=(0, 50),
             ylim=(0, 1), title="Precision plot of OPE")
    for ax in (ax_s, ax_p):
        ax.grid(alpha=0.3)
        ax.legend(loc="lower left" if ax is ax_s else "lower right", fontsize=8)
    n = len(runs)
    fig.suptitle("%s (%d sequence%s)" % (title, n, "" if n == 1 else "s"))
    fig.tight_layout()
    fig.savefig(out, dpi=100)


if __name__ == "__main__":
    main()
