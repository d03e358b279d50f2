#!/usr/bin/env python3
"""Leave-one-venue-out check of evaluate_field_segmentation's defaults: runs the tool over a small
grid of the settings the defaults were chosen from, then for each venue picks the grid point best
on the OTHER venues' images (mean of field and line IoU) and scores it on the held-out venue's
images. A venue is an image's name without its trailing frame number (`opx_frame005575` and
`opx_frame005620` are one recording). Prints the per-venue choice and a last line
`field_segmentation_loo: images=.. venues=.. field_iou=.. line_iou=.. default_field_iou=..
default_line_iou=..` (means over images; the defaults' own figures beside).

usage: field_segmentation_loo.py TOOL IMAGES_DIR MASKS_DIR OUTPUT_DIR
(TOOL: the evaluate_field_segmentation executable; OUTPUT_DIR receives one folder per grid point)
"""
import csv
import itertools
import os
import subprocess
import sys

GRID = {
    "seed_luma_share": ["0.3", "0.5", "0.8"],
    "line_object_window_share": ["0.03", "0.06", "0.1"],
    "line_max_object_share": ["0.05", "0.1", "0.2", "1"],
    "dark_chroma_sigma": ["2", "3", "5"],
    "line_min_elongation": ["0", "3", "6", "10"],
}


def venue(name):
    """As evaluate_color_priors' venueOf: the name without its extension, a trailing "_copy" and
    the trailing frame number (digits, '_' and '-'); a name that is all number is its own venue."""
    stem = os.path.splitext(name)[0]
    v = stem[:-5] if len(stem) > 5 and stem.endswith("_copy") else stem
    v = v.rstrip("0123456789_-")
    return v or stem


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
    venues = sorted({venue(n) for n in names})
    field = line = 0.0
    for held in venues:
        def others(s):
            return sum(s[n][0] + s[n][1] for n in names if venue(n) != held)
        best = max(range(len(points)), key=lambda i: others(scores[i]))
        mine = [n for n in names if venue(n) == held]
        f = sum(scores[best][n][0] for n in mine)
        l = sum(scores[best][n][1] for n in mine)
        field += f
        line += l
        print("%s (%d images): %s -> field_iou=%.3f line_iou=%.3f" % (
            held, len(mine), " ".join("%s=%s" % kv for kv in points[best]), f / len(mine),
            l / len(mine)))
    n = len(names)
    print("field_segmentation_loo: images=%d venues=%d field_iou=%.3f line_iou=%.3f "
          "default_field_iou=%.3f default_line_iou=%.3f" % (n, len(venues), field / n, line / n,
                                     sum(default[k][0] for k in names) / n,
                                     sum(default[k][1] for k in names) / n))


if __name__ == "__main__":
    main()
