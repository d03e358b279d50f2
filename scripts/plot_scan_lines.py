#!/usr/bin/env python3
"""Draws one laser scan (DIR/scan_points.csv) with its extracted segments (DIR/scan_segments.csv) into
DIR/scan.png. usage: plot_scan_lines.py DIR TITLE"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(argv):
    if len(argv) != 3:
        print(__doc__)
        return 2
    d, title = argv[1], argv[2]
    pts = list(csv.DictReader(open(os.path.join(d, "scan_points.csv"))))
    segs = list(csv.DictReader(open(os.path.join(d, "scan_segments.csv"))))
    fig, ax = plt.subplots(figsize=(6, 6))
    ax.scatter([float(p["x"]) for p in pts], [float(p["y"]) for p in pts], s=3, c="0.45", label="returns")
    for i, s in enumerate(segs):
        ax.plot([float(s["x0"]), float(s["x1"])], [float(s["y0"]), float(s["y1"])], "-", lw=2.5, color="tab:red",
                label="segments" if i == 0 else None)
    ax.plot([0], [0], "b^", ms=9, label="laser")
    ax.set_aspect("equal")
    ax.set_xlabel("x [m] (laser frame)")
    ax.set_ylabel("y [m]")
    ax.set_title("%s: %d segments" % (title, len(segs)))
    ax.grid(alpha=0.3)
    ax.legend(loc="upper right", fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(d, "scan.png"), dpi=100)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
