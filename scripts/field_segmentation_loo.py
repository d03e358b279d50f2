#!/usr/bin/env python3
"""Leave-one-image-out check of evaluate_field_segmentation's defaults: runs the tool over a small
grid of the settings the defaults were chosen from, then for each image picks the grid point best
on the OTHER images (mean of field and line IoU) and scores it on the held-out image. Prints the
per-image choice and a last line `field_segmentation_loo: images=.. field_iou=.. line_iou=..
default_field_iou=.. default_line_iou=..` (the defaults' own figures beside).

usage: field_segmentation_loo.py TOOL IMAGES_DIR MASKS_DIR OUTPUT_DIR
(TOOL: the evaluate_field_segmentation executable; OUTPUT_DIR receives one folder per grid point)
"""
import csv
import itertools
import os
import subprocess
import sys

GRID = {
    "boundary_line_weight": ["0", "-0.5", "-1"],
    "boundary_min_width_share": ["0", "0.1"],
    "line_window_share": ["0.03", "0.05"],
    "line_contrast_sigma": ["1", "1.5", "2"],
}


def run(tool, images, masks, out, settings):
    args = [tool, "--images", images, "--masks", masks, "--output", out]
    for k, v in settings:
        args += ["--" + k, v]
    subprocess.run(args, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    with open(os.path.join(out, "images.csv")) as f:
        return {r["image"]: (float(r["field_iou"]), float(r["line_iou"])) for r in csv.DictReader(f)}


def main():
    if len(sys.argv) != 5:
        sys.exit(__doc__)
    tool, images, masks, out = sys.argv[1:]
    points = [tuple(zip(GRID, values)) for values in itertools.product(*GRID.values())]
    scores = []
    for i, p in enumerate(points):
        scores.append(run(tool, images, masks, os.path.join(out, "grid%02d" % i), p))
    default = run(tool, images, masks, os.path.join(out, "default"), ())
    names = sorted(scores[0])
    field = line = 0.0
    for held in names:
        def others(s):
            return sum(s[n][0] + s[n][1] for n in names if n != held)
        best = max(range(len(points)), key=lambda i: others(scores[i]))
        f, l = scores[best][held]
        field += f
        line += l
        print("%s: %s -> field_iou=%.3f line_iou=%.3f" % (
            held, " ".join("%s=%s" % kv for kv in points[best]), f, l))
    n = len(names)
    print("field_segmentation_loo: images=%d field_iou=%.3f line_iou=%.3f default_field_iou=%.3f "
          "default_line_iou=%.3f" % (n, field / n, line / n,
                                     sum(default[k][0] for k in names) / n,
                                     sum(default[k][1] for k in names) / n))


if __name__ == "__main__":
    main()
