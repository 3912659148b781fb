#!/usr/bin/env python3
"""Collates the eye-tracker latency study (scripts/eye-tracker-latency.sh): writes
latency-study.csv (one row per recording × scene × latency × prediction × seed) and
latency-study.svg (means over seeds, recordings and scenes against latency, one line per predictor:
foveal relMSE, FovVideoVDP JOD scored at the true gaze, rendered-fovea-to-gaze distance, share of
frames with the gaze outside the rendered fovea) and latency-study.html (that plot, then per
recording its own plot and table) into the first STUDY_DIR. Each seed's values come
from the point's per-frame files (frames-<scene>.csv, gaze-<scene>.csv, jod.csv), so studies of the
same grid under other seeds combine (e.g. `-- --set 'experiment.seeds=[3]'` into another folder): a
seed found in two folders must carry the same values and is kept once; each seed's relMSE and JOD
are taken relative to the same seed's 0 ms / none point, then averaged; --markdown prints one
table per recording with the mean and the range over the seeds. Standard library only."""
import argparse
import csv
import json
from pathlib import Path

FIELDS = ["seed", "recording", "scene", "latency_ms", "prediction", "foveal_relmse", "whole_relmse", "jod",
          "foveal_relmse_fixation", "foveal_relmse_saccade", "fovea_distance_deg_mean",
          "outside_fovea_share", "saccades", "recovery_ms_mean", "recovery_ms_median", "unrecovered"]
PANELS = [("foveal_relmse", "foveal relMSE"), ("jod", "FovVideoVDP JOD"), ("fovea_distance_deg_mean", "fovea to true gaze (deg)"),
          ("outside_fovea_share", "gaze outside rendered fovea (share)")]
COLOURS = {"none": "#d62728", "cv": "#1f77b4", "landing": "#2ca02c"}


def mean(values):
    return sum(values) / len(values) if values else None


def per_seed(point, scene, variant):
    """{seed: {column: value}} from a point's per-frame files: foveal and whole-image relMSE (mean
    over eyes and frames), the foveal relMSE of fixation and of saccade frames (gaze-<scene>.csv's
    saccade flag) and FovVideoVDP's JOD (mean over eyes; None without jod.csv)."""
    saccade = {r["frame"]: r["saccade"] == "1" for r in csv.DictReader(open(point / f"gaze-{scene}.csv"))}
    values = {}
    for r in csv.DictReader(open(point / f"frames-{scene}.csv")):
        if r["variant"] != variant or r["metric"] != "relmse" or r["region"] not in ("fovea", "whole"):
            continue
        v = values.setdefault(int(r["seed"]), {"fovea": [], "whole": [], "fixation": [], "saccade": [], "jod": []})
        v[r["region"]].append(float(r["value"]))
        if r["region"] == "fovea":
            v["saccade" if saccade[r["frame"]] else "fixation"].append(float(r["value"]))
    if (point / "jod.csv").exists():
        for r in csv.DictReader(open(point / "jod.csv")):
            if r["scene"] == scene and r["variant"] == variant:
                values[int(r["seed"])]["jod"].append(float(r["jod"]))
    return {seed: {"foveal_relmse": mean(v["fovea"]), "whole_relmse": mean(v["whole"]), "jod": mean(v["jod"]),
                   "foveal_relmse_fixation": mean(v["fixation"]), "foveal_relmse_saccade": mean(v["saccade"])}
            for seed, v in values.items()}


def rows_of(root):
    """One row per point, scene and seed of the study folder `root`."""
    for summary_path in sorted((root / "runs").glob("*/latency-*/*/summary.json")):
        point = summary_path.parent
        prediction = point.name
        latency = float(point.parent.name.split("-", 1)[1])
        recording = point.parent.parent.name
        summary = json.loads(summary_path.read_text())
        for scene, scene_json in summary["scenes"].items():
            variants = scene_json["variants"]
            variant = next(iter(variants))
            gaze = summary["gaze_tracking"].get(scene, {})
            seeds = per_seed(point, scene, variant)
            if len(seeds) == 1:  # the files and the summary must tell the same story
                only = next(iter(seeds.values()))
                summary_relmse = variants[variant]["fovea"]["relmse"]["mean"]
                if abs(only["foveal_relmse"] - summary_relmse) > 1e-6 * abs(summary_relmse):
                    raise SystemExit(f"{point}: frames-{scene}.csv disagrees with summary.json on the foveal relMSE")
            for seed, values in sorted(seeds.items()):
                yield {"seed": seed, "study": str(root), "recording": recording, "scene": scene, "latency_ms": latency,
                       "prediction": prediction, **values,
                       "fovea_distance_deg_mean": gaze["fovea_distance_deg"]["mean"],
                       "outside_fovea_share": gaze["outside_fovea_share"], "saccades": gaze["saccades"],
                       "recovery_ms_mean": gaze["recovery_ms"]["mean"], "recovery_ms_median": gaze["recovery_ms"]["median"],
                       "unrecovered": gaze["unrecovered"]}


def merge_seeds(rows):
    """Each (point, scene, seed) once: a seed found in two study folders must carry the same values
    (the same seed under the same settings renders the same frames), else the folders differ in
    settings or build and are not combined."""
    kept = {}
    for r in rows:
        key = (r["recording"], r["scene"], r["latency_ms"], r["prediction"], r["seed"])
        if key in kept:
            other = kept[key]
            if any(other[c] != r[c] for c in ("foveal_relmse", "whole_relmse", "jod")):
                raise SystemExit(f"{key[0]}, {key[1]}, {key[2]:g} ms, {key[3]}: seed {key[4]} differs between "
                                 f"{other['study']} and {r['study']} (other settings or build?); not combined")
            continue
        kept[key] = r
    return list(kept.values())


def relative(rows, key):
    """Yields (row, value): relMSE divided by the latency-0 'none' value of the same seed,
    recording and scene, so scenes of different error weigh alike; JOD as the difference to that
    value (JOD is a difference scale); the gaze columns as they are."""
    base = {}
    for r in rows:
        if r["latency_ms"] == 0 and r["prediction"] == "none":
            base[(r["seed"], r["recording"], r["scene"])] = r[key]
    for r in rows:
        value = r[key]
        if value is None:
            continue
        b = base.get((r["seed"], r["recording"], r["scene"]))
        if key == "jod":
            if b is None:
                continue
            value = value - b
        elif key.endswith("relmse"):
            if not b:
                continue
            value = value / b
        yield r, value


def means(rows, key):
    """{prediction: [(latency, mean over seeds, recordings and scenes)]} of relative()."""
    out = {}
    for r, value in relative(rows, key):
        out.setdefault(r["prediction"], {}).setdefault(r["latency_ms"], []).append(value)
    return {p: sorted((lat, sum(v) / len(v)) for lat, v in d.items()) for p, d in out.items()}


def spread(values, digits, signed=False):
    """'mean' for one value, 'mean [min, max]' over seeds for several."""
    f = (lambda v: f"{v:+.{digits}f}".replace("-", "−")) if signed else (lambda v: f"{v:.{digits}f}")
    mean = sum(values) / len(values)
    return f(mean) if len(values) == 1 else f"{f(mean)} [{f(min(values))}, {f(max(values))}]"


def recording_tables(rows):
    """Per recording: (recording, seeds, header, body rows) of its table: the gaze columns (the same
    for every seed and scene) and, per scene, the foveal relMSE and JOD relative to the 0 ms / none
    point of the same seed, mean [min, max] over the seeds."""
    rel = {key: {} for key in ("foveal_relmse", "jod")}
    for key in rel:
        for r, value in relative(rows, key):
            rel[key].setdefault((r["recording"], r["latency_ms"], r["prediction"], r["scene"]), []).append(value)
    scenes = sorted({r["scene"] for r in rows})
    order = {"none": 0, "cv": 1, "landing": 2}
    points = sorted({(r["recording"], r["latency_ms"], r["prediction"]) for r in rows},
                    key=lambda k: (k[0], k[1], order.get(k[2], 9), k[2]))
    first = {}
    for r in rows:
        first.setdefault((r["recording"], r["latency_ms"], r["prediction"]), r)
    header = (["latency (ms)", "predictor", "fovea to true gaze, mean (°)", "gaze outside the rendered fovea"]
              + [f"{s} foveal relMSE / (0 ms, none)" for s in scenes] + [f"{s} JOD − (0 ms, none)" for s in scenes]
              + ["recovery after saccades, mean / median (ms), unrecovered"])
    tables = []
    for recording in sorted({k[0] for k in points}):
        seeds = sorted({r["seed"] for r in rows if r["recording"] == recording})
        body = []
        for key in (k for k in points if k[0] == recording):
            r = first[key]
            cells = [f"{key[1]:g}", key[2], f"{r['fovea_distance_deg_mean']:.2f}", f"{100 * r['outside_fovea_share']:.1f} %"]
            cells += [spread(rel["foveal_relmse"].get(key + (s,), [float("nan")]), 3) for s in scenes]
            cells += [spread(rel["jod"].get(key + (s,), [float("nan")]), 3, signed=True) for s in scenes]
            cells.append(f"{r['recovery_ms_mean']:.0f} / {r['recovery_ms_median']:.0f}, {r['unrecovered']} of {r['saccades']}")
            body.append(cells)
        tables.append((recording, seeds, header, body))
    return tables


def markdown(rows):
    """One table per recording (recording_tables)."""
    lines = []
    for recording, seeds, header, body in recording_tables(rows):
        lines += [f"{recording} (seeds {', '.join(map(str, seeds))})", "",
                  "| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
        lines += ["| " + " | ".join(cells) + " |" for cells in body]
        lines.append("")
    return "\n".join(lines)


def html(rows, studies):
    """latency-study.html, self-contained (inline SVG, no script): the plot over every recording,
    then per recording its own plot and table."""
    esc = lambda t: str(t).replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")
    parts = ["<!DOCTYPE html>", '<html lang="en"><head><meta charset="utf-8"><title>Eye-tracker latency study</title>',
             "<style>body{font-family:sans-serif;margin:2em}table{border-collapse:collapse;font-size:13px}"
             "td,th{border:1px solid #ccc;padding:2px 6px;text-align:right;white-space:nowrap}th{background:#f4f4f4}</style></head><body>",
             "<h1>Eye-tracker latency study</h1>",
             "<p>Collated from " + ", ".join(f"<code>{esc(s)}</code>" for s in studies) + ". relMSE and JOD are relative "
             "to the same seed's 0 ms / no-prediction point of each scene, mean [min, max] over the seeds; the plots "
             "show means over seeds and scenes (and, in the first, recordings).</p>",
             "<h2>All recordings</h2>", svg(rows)]
    for recording, seeds, header, body in recording_tables(rows):
        parts += [f"<h2>{esc(recording)} (seeds {', '.join(map(str, seeds))})</h2>",
                  svg([r for r in rows if r["recording"] == recording]),
                  "<table><tr>" + "".join(f"<th>{esc(h)}</th>" for h in header) + "</tr>"]
        parts += ["<tr>" + "".join(f"<td>{esc(c)}</td>" for c in cells) + "</tr>" for cells in body]
        parts.append("</table>")
    parts.append("</body></html>")
    return "\n".join(parts) + "\n"


def svg(rows):
    width, height, margin = 300, 220, 48
    parts = []
    for i, (key, label) in enumerate(PANELS):
        series = means(rows, key)
        values = [v for s in series.values() for _, v in s] or [0.0]
        latencies = [lat for s in series.values() for lat, _ in s] or [0.0]
        if key.endswith("relmse") or key == "jod":  # ratios and differences: the data's own range
            pad = 0.05 * (max(values) - min(values)) or 0.01
            lo, hi = min(values) - pad, max(values) + pad
        else:  # distances and shares start at 0
            lo, hi = 0.0, max(values) * 1.1 or 1.0
        x_max = max(latencies) or 1.0
        ox = i * (width + 20)
        top = 30  # below the panel's title
        fx = lambda lat: ox + margin + (width - margin - 10) * lat / x_max
        fy = lambda v: height - margin + (top - (height - margin)) * (v - lo) / (hi - lo)
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
                parts.append(f'<text x="{fx(x_max) - 50}" y="{fy(lo) - 36 + 14 * n}" font-size="11" '
                             f'fill="{colour}">{prediction}</text>')
    total = len(PANELS) * (width + 20)
    return (f'<svg xmlns="http://www.w3.org/2000/svg" width="{total}" height="{height}" '
            f'font-family="sans-serif">\n' + "\n".join(parts) + "\n</svg>\n")


def gaze_consistent(rows):
    """The gaze columns depend on the recording, latency and predictor only; seed sets that
    disagree were run with different settings and must not be averaged."""
    seen = {}
    for r in rows:
        key = (r["recording"], r["latency_ms"], r["prediction"])
        gaze = (r["fovea_distance_deg_mean"], r["outside_fovea_share"], r["saccades"], r["unrecovered"])
        if seen.setdefault(key, (gaze, r["study"]))[0] != gaze:
            raise SystemExit(f"{key[0]}, {key[1]:g} ms, {key[2]}: {seen[key][1]} and {r['study']} "
                             "disagree on the gaze columns (different settings?); not averaged")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("study_dirs", nargs="+", type=Path, metavar="STUDY_DIR")
    parser.add_argument("--markdown", action="store_true", help="print one table per recording")
    parser.add_argument("--recording", action="append", metavar="NAME",
                        help="collate only this recording (repeatable; default: every recording found)")
    args = parser.parse_args()
    root = args.study_dirs[0]
    rows = []
    for study in args.study_dirs:
        found = [r for r in rows_of(study) if not args.recording or r["recording"] in args.recording]
        if not found:
            raise SystemExit(f"{study}: no runs/*/latency-*/*/summary.json"
                             + (f" of {', '.join(args.recording)}" if args.recording else "")
                             + " (run scripts/eye-tracker-latency.sh)")
        rows += found
    gaze_consistent(rows)
    rows = merge_seeds(rows)
    with open(root / "latency-study.csv", "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=FIELDS, extrasaction="ignore")
        writer.writeheader()
        writer.writerows(rows)
    (root / "latency-study.svg").write_text(svg(rows))
    (root / "latency-study.html").write_text(html(rows, args.study_dirs))
    print(f"{root / 'latency-study.csv'}: {len(rows)} rows; plot {root / 'latency-study.svg'}; "
          f"report {root / 'latency-study.html'}")
    for key, label in PANELS:
        print(label + (" (relative to latency 0, none)" if key.endswith("relmse") else
                       " (difference to latency 0, none)" if key == "jod" else ""))
        for prediction, points in sorted(means(rows, key).items()):
            print(f"  {prediction:<8} " + "  ".join(f"{lat:g} ms: {v:.4g}" for lat, v in points))
    if args.markdown:
        print()
        print(markdown(rows))


if __name__ == "__main__":
    main()
