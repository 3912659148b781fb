#!/usr/bin/env python3
"""Markdown table of an experiment's frames-<scene>.csv (fovrt experiment output): per scene and
variant, relMSE, SSIM and temporal error (SVGF §5.4) for the whole image, the fovea and the
periphery, means over frames and eyes (temporal error over frames 1.., as the CSV holds it).

  python3 training/experiment_table.py out/rae          (the RAE experiment table in training/README.md)
"""
import csv
import glob
import os
import sys
from collections import defaultdict


def main(folder):
    cols = [("relmse", r) for r in ("whole", "fovea", "periphery")] + \
           [("ssim", r) for r in ("whole", "fovea", "periphery")] + \
           [("temporal", r) for r in ("whole", "fovea", "periphery")]
    print("| scene | variant | " + " | ".join(f"{m} {r}" for m, r in cols) + " |")
    print("|---|---|" + "---:|" * len(cols))
    for path in sorted(glob.glob(os.path.join(folder, "frames-*.csv"))):
        scene = os.path.basename(path)[len("frames-"):-len(".csv")]
        sums = defaultdict(lambda: [0.0, 0])
        order = []
        with open(path) as f:
            for row in csv.DictReader(f):
                key = (row["variant"], row["metric"], row["region"])
                if row["variant"] not in order:
                    order.append(row["variant"])
                s = sums[key]
                s[0] += float(row["value"])
                s[1] += 1
        for v in order:
            vals = []
            for m, r in cols:
                s = sums.get((v, m, r))
                vals.append(f"{s[0] / s[1]:.4g}" if s and s[1] else "-")
            print(f"| {scene} | {v} | " + " | ".join(vals) + " |")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "out/rae")
