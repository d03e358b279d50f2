#!/usr/bin/env python3
"""Plots classification rate over time from evaluate_color_estimation's frames.csv (the colour paper's
Fig. 6). Several CSVs may be given as LABEL=FILE to compare filters on one plot.

usage: plot_color_rates.py FRAMES.csv|LABEL=FRAMES.csv [...] OUTPUT.png TITLE
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return rows


def main(argv):
    if len(argv) < 4:
        print(__doc__)
        return 2
    inputs, out, title = argv[1:-2], argv[-2], argv[-1]
    fig, ax = plt.subplots(figsize=(8, 3.5))
    dark_spans_drawn = False
    for spec in inputs:
        label, path = spec.split("=", 1) if "=" in spec else ("overall", spec)
        rows = read(path)
        t = [float(r["t_s"]) for r in rows]
        y = [float(r["overall"]) for r in rows]
        ax.plot(t, y, marker=".", label=label)
        if not dark_spans_drawn:
            for r, t0, t1 in zip(rows, t, t[1:] + [t[-1]]):
                if r.get("condition") == "dark":
                    ax.axvspan(t0, t1, color="0.85", lw=0)
            dark_spans_drawn = True
    ax.set_ylim(0.0, 1.02)
    ax.set_xlabel("time [s] (grey: lights off)")
    ax.set_ylabel("classification rate")
    ax.set_title(title)
    ax.grid(alpha=0.3)
    ax.legend(loc="lower right")
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
