#!/usr/bin/env python3
"""Checks scripts/eye_tracker_latency_collate.py on two synthetic studies of one recording under
seeds 1 and 2: each point's relMSE and JOD are taken relative to the 0 ms / none point of its own
seeds before the seed sets are averaged (a wrong baseline or a plain mean of raw values gives other
numbers), the table shows mean [min, max], and studies that repeat a seed set or disagree on the
gaze columns are refused. Usage: latency_collate_check.py REPO_ROOT WORK_DIR"""
import csv
import json
import shutil
import subprocess
import sys
from pathlib import Path

repo, work = Path(sys.argv[1]), Path(sys.argv[2])
collate = repo / "scripts" / "eye_tracker_latency_collate.py"
shutil.rmtree(work, ignore_errors=True)

# (seed, latency, prediction) → (foveal relMSE, JOD); the gaze columns depend on latency only.
POINTS = {
    (1, 0, "none"): (1.0e-3, 9.00), (1, 40, "none"): (1.2e-3, 8.90),
    (2, 0, "none"): (2.0e-3, 8.00), (2, 40, "none"): (2.8e-3, 7.70),
}
GAZE = {0: (0.2, 0.0), 40: (3.0, 0.05)}


def write_point(study, seed, latency, prediction, relmse, jod, distance=None):
    point = study / "runs" / "rec-a" / f"latency-{latency}" / prediction
    point.mkdir(parents=True)
    dist, share = GAZE[latency]
    stats = lambda v: {"relmse": {"mean": v}}
    summary = {
        "scenes": {"cornell": {"variants": {"svgf": {"fovea": stats(relmse), "whole": stats(relmse / 2)}}}},
        "gaze_tracking": {"cornell": {"fovea_distance_deg": {"mean": distance if distance is not None else dist},
                                      "outside_fovea_share": share, "saccades": 4, "unrecovered": 1,
                                      "recovery_ms": {"mean": 10.0, "median": 5.0},
                                      "foveal_relmse": {"svgf": {"fixation": relmse, "saccade": relmse}}}},
        "fovvideovdp": {"scenes": {"cornell": {"svgf": {"jod": jod}}}},
    }
    (point / "summary.json").write_text(json.dumps(summary))
    (point / "manifest.json").write_text(json.dumps({"scenes": [{"scene": "cornell", "seeds": [seed]}]}))


def run(*args):
    return subprocess.run([sys.executable, str(collate), *map(str, args)], capture_output=True, text=True)


def fail(message):
    sys.exit(f"latency_collate_check: {message}")


for (seed, latency, prediction), (relmse, jod) in POINTS.items():
    write_point(work / f"seed{seed}", seed, latency, prediction, relmse, jod)

result = run(work / "seed1", work / "seed2", "--markdown")
if result.returncode != 0:
    fail(f"collate failed: {result.stderr.strip()}")
with open(work / "seed1" / "latency-study.csv") as f:
    rows = list(csv.DictReader(f))
if sorted(r["seeds"] for r in rows) != ["1", "1", "2", "2"]:
    fail(f"expected one row per point and seed set, got seeds {[r['seeds'] for r in rows]}")
# 40 ms: relMSE ×1.2 (seed 1) and ×1.4 (seed 2) → mean 1.3; JOD −0.10 and −0.30 → −0.20.
expected = "| 40 | none | 3.00 | 5.0 % | 1.300 [1.200, 1.400] | −0.200 [−0.300, −0.100] | 10 / 5, 1 of 4 |"
if expected not in result.stdout:
    fail(f"expected the row\n{expected}\nin\n{result.stdout}")
if "| 0 | none | 0.20 | 0.0 % | 1.000 [1.000, 1.000] | +0.000 [+0.000, +0.000] |" not in result.stdout:
    fail(f"the 0 ms / none row is not its own baseline:\n{result.stdout}")
if not (work / "seed1" / "latency-study.svg").read_text().startswith("<svg"):
    fail("no plot written")

# The same seed set twice is refused, and so are seed sets whose gaze columns disagree.
result = run(work / "seed1", work / "seed1")
if result.returncode == 0 or "same point under the same seeds" not in result.stderr:
    fail(f"a repeated seed set was not refused: rc {result.returncode}, {result.stderr.strip()}")
write_point(work / "seed3", 3, 0, "none", 1.0e-3, 9.0)
write_point(work / "seed3", 3, 40, "none", 1.1e-3, 8.9, distance=4.0)
result = run(work / "seed1", work / "seed3")
if result.returncode == 0 or "disagree on the gaze columns" not in result.stderr:
    fail(f"seed sets with different gaze were averaged: rc {result.returncode}, {result.stderr.strip()}")
# --recording keeps the named recordings only.
result = run(work / "seed1", "--recording", "rec-b")
if result.returncode == 0 or "no runs/" not in result.stderr or "rec-b" not in result.stderr:
    fail(f"--recording of an absent recording was not refused: {result.stderr.strip()}")
result = run(work / "seed1", work / "seed2", "--recording", "rec-a", "--markdown")
if result.returncode != 0 or expected not in result.stdout:
    fail(f"--recording rec-a changed the table: {result.stderr.strip()}")
result = run(work / "empty")
if result.returncode == 0 or "no runs/" not in result.stderr:
    fail(f"an empty study was not refused: {result.stderr.strip()}")
print("latency_collate_check: ok")
