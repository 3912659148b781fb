#!/usr/bin/env python3
"""Collates the eye-tracker latency study (scripts/eye-tracker-latency.sh) from each point's
summary.json: writes latency-study.csv (one row per recording × scene × latency × prediction) and
latency-study.svg (means over recordings and scenes against latency, one line per predictor:
foveal relMSE, FovVideoVDP JOD scored at the true gaze, rendered-fovea-to-gaze distance, share of
frames with the gaze outside the rendered fovea). Standard library only."""
import csv
import json
import sys
from pathlib import Path

FIELDS = ["recording", "scene", "latency_ms", "prediction", "foveal_relmse", "whole_relmse", "jod",
          "foveal_relmse_fixation", "foveal_relmse_saccade", "fovea_distance_deg_mean",
          "outside_fovea_share", "saccades", "recovery_ms_mean", "recovery_ms_median", "unrecovered"]
PANELS = [("foveal_relmse", "foveal relMSE"), ("jod", "FovVideoVDP JOD"), ("fovea_distance_deg_mean", "fovea to true gaze (deg)"),
          ("outside_fovea_share", "gaze outside rendered fovea (share)")]
COLOURS = {"none": "#d62728", "cv": "#1f77b4", "landing": "#2ca02c"}


def rows_of(root):
    for summary_path in sorted((root / "runs").glob("*/latency-*/*/summary.json")):
        prediction = summary_path.parent.name
        latency = float(summary_path.parent.parent.name.split("-", 1)[1])
        recording = summary_path.parent.parent.parent.name
        summary = json.loads(summary_path.read_text())
        for scene, scene_json in summary["scenes"].items():
            variants = scene_json["variants"]
            variant = next(iter(variants))
            gaze = summary["gaze_tracking"].get(scene, {})
            split = gaze.get("foveal_relmse", {}).get(variant, {})
            vdp = summary.get("fovvideovdp", {}).get("scenes", {}).get(scene, {}).get(variant, {})
            yield {"recording": recording, "scene": scene, "latency_ms": latency, "prediction": prediction,
                   "foveal_relmse": variants[variant]["fovea"]["relmse"]["mean"],
                   "whole_relmse": variants[variant]["whole"]["relmse"]["mean"], "jod": vdp.get("jod"),
                   "foveal_relmse_fixation": split.get("fixation"), "foveal_relmse_saccade": split.get("saccade"),
                   "fovea_distance_deg_mean": gaze["fovea_distance_deg"]["mean"],
                   "outside_fovea_share": gaze["outside_fovea_share"], "saccades": gaze["saccades"],
                   "recovery_ms_mean": gaze["recovery_ms"]["mean"], "recovery_ms_median": gaze["recovery_ms"]["median"],
                   "unrecovered": gaze["unrecovered"]}


def means(rows, key):
    """{prediction: [(latency, mean over recordings and scenes)]}, relMSE normalised per
    (recording, scene) by its latency-0 'none' value so scenes of different error weigh alike, JOD
    as the difference to that value (JOD is a difference scale)."""
    base = {}
    for r in rows:
        if r["latency_ms"] == 0 and r["prediction"] == "none":
            base[(r["recording"], r["scene"])] = r[key]
    out = {}
    for r in rows:
        value = r[key]
        if value is None:
            continue
        if key == "jod":
            b = base.get((r["recording"], r["scene"]))
            if b is None:
                continue
            value = value - b
        elif key.endswith("relmse"):
            b = base.get((r["recording"], r["scene"]))
            if not b:
                continue
            value = value / b
        out.setdefault(r["prediction"], {}).setdefault(r["latency_ms"], []).append(value)
    return {p: sorted((lat, sum(v) / len(v)) for lat, v in d.items()) for p, d in out.items()}


def svg(rows):
    width, height, margin = 300, 220, 48
    parts = []
    for i, (key, label) in enumerate(PANELS):
        series = means(rows, key)
        values = [v for s in series.values() for _, v in s] or [0.0]
        latencies = [lat for s in series.values() for lat, _ in s] or [0.0]
        lo, hi = min(0.0, min(values)), max(values) * 1.1 or 1.0
        if hi <= lo:  # all at or below 0 (a JOD loss): the axis ends at 0
            hi = 0.0 if lo < 0.0 else 1.0
        x_max = max(latencies) or 1.0
        ox = i * (width + 20)
        fx = lambda lat: ox + margin + (width - margin - 10) * lat / x_max
        fy = lambda v: height - margin + (margin + 10 - height) * (v - lo) / (hi - lo)
        title = label + (" / latency-0 none" if key.endswith("relmse") else
                         " − latency-0 none" if key == "jod" else "")
        parts.append(f'<text x="{ox + width / 2}" y="14" text-anchor="middle" font-size="12">{title}</text>')
        parts.append(f'<line x1="{fx(0)}" y1="{fy(lo)}" x2="{fx(x_max)}" y2="{fy(lo)}" stroke="black"/>')
        parts.append(f'<line x1="{fx(0)}" y1="{fy(lo)}" x2="{fx(0)}" y2="{fy(hi)}" stroke="black"/>')
        for lat in sorted(set(latencies)):
            parts.append(f'<text x="{fx(lat)}" y="{fy(lo) + 14}" text-anchor="middle" font-size="10">{lat:g}</text>')
        parts.append(f'<text x="{ox + width / 2}" y="{height - 8}" text-anchor="middle" font-size="11">'
                     'tracker latency (ms)</text>')
        for frac in (0.0, 0.5, 1.0):
            v = lo + frac * (hi - lo)
            parts.append(f'<text x="{fx(0) - 4}" y="{fy(v) + 4}" text-anchor="end" font-size="10">{v:.3g}</text>')
        for n, (prediction, points) in enumerate(sorted(series.items())):
            colour = COLOURS.get(prediction, "gray")
            path = " ".join(f"{fx(lat):.1f},{fy(v):.1f}" for lat, v in points)
            parts.append(f'<polyline points="{path}" fill="none" stroke="{colour}" stroke-width="2"/>')
            if i == 0:
                parts.append(f'<text x="{fx(0) + 8}" y="{32 + 14 * n}" font-size="11" fill="{colour}">{prediction}</text>')
    total = len(PANELS) * (width + 20)
    return (f'<svg xmlns="http://www.w3.org/2000/svg" width="{total}" height="{height}" '
            f'font-family="sans-serif">\n' + "\n".join(parts) + "\n</svg>\n")


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: eye_tracker_latency_collate.py STUDY_DIR")
    root = Path(sys.argv[1])
    rows = list(rows_of(root))
    if not rows:
        sys.exit(f"{root}: no runs/*/latency-*/*/summary.json (run scripts/eye-tracker-latency.sh)")
    with open(root / "latency-study.csv", "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=FIELDS)
        writer.writeheader()
        writer.writerows(rows)
    (root / "latency-study.svg").write_text(svg(rows))
    print(f"{root / 'latency-study.csv'}: {len(rows)} rows; plot {root / 'latency-study.svg'}")
    for key, label in PANELS:
        print(label + (" (relative to latency 0, none)" if key.endswith("relmse") else
                       " (difference to latency 0, none)" if key == "jod" else ""))
        for prediction, points in sorted(means(rows, key).items()):
            print(f"  {prediction:<8} " + "  ".join(f"{lat:g} ms: {v:.4g}" for lat, v in points))


if __name__ == "__main__":
    main()
