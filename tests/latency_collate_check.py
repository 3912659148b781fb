#!/usr/bin/env python3
"""Checks scripts/eye_tracker_latency_collate.py on synthetic studies of one recording: per-seed
values are read from each point's per-frame files (frames-, gaze- and jod.csv) and taken relative
to the same seed's 0 ms / none point before they are averaged (a wrong baseline or a mean of raw
values gives other numbers); the table shows mean [min, max]; a seed found in two folders with the
same values is kept once, with other values it is refused, as are folders that disagree on the
gaze columns and a summary.json that disagrees with its frames. Usage: latency_collate_check.py REPO_ROOT WORK_DIR"""
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


def write_point(study, seeds, latency, prediction, distance=None, summary_relmse=None):
    """A point that ran `seeds`: two eyes × two frames per seed (frame 1 in a saccade), values of POINTS."""
    point = study / "runs" / "rec-a" / f"latency-{latency}" / prediction
    point.mkdir(parents=True)
    dist, share = GAZE[latency]
    frames, jods = ["seed,frame,eye,variant,region,metric,value"], ["scene,seed,eye,variant,jod,jod_sustained,jod_transient"]
    for seed in seeds:
        relmse, jod = POINTS[(seed, latency, prediction)]
        for eye in (0, 1):
            jods.append(f"cornell,{seed},{eye},svgf,{jod},{jod},{jod}")
            for frame in (0, 1):
                frames.append(f"{seed},{frame},{eye},svgf,fovea,relmse,{relmse}")
                frames.append(f"{seed},{frame},{eye},svgf,whole,relmse,{relmse / 2}")
                frames.append(f"{seed},{frame},{eye},svgf,fovea,ssim,0.9")
    (point / "frames-cornell.csv").write_text("\n".join(frames) + "\n")
    (point / "jod.csv").write_text("\n".join(jods) + "\n")
    (point / "gaze-cornell.csv").write_text("frame,time_s,blink,speed_deg_s,saccade,fovea_distance_deg,outside_fovea\n"
                                            "0,0,0,0,0,1,0\n1,0.01,0,200,1,1,0\n")
    mean_relmse = sum(POINTS[(s_, latency, prediction)][0] for s_ in seeds) / len(seeds)
    summary = {
        "scenes": {"cornell": {"variants": {"svgf": {"fovea": {"relmse": {"mean": summary_relmse or mean_relmse}}}}}},
        "gaze_tracking": {"cornell": {"fovea_distance_deg": {"mean": distance if distance is not None else dist},
                                      "outside_fovea_share": share, "saccades": 4, "unrecovered": 1,
                                      "recovery_ms": {"mean": 10.0, "median": 5.0}}},
    }
    (point / "summary.json").write_text(json.dumps(summary))


def run(*args):
    return subprocess.run([sys.executable, str(collate), *map(str, args)], capture_output=True, text=True)


def fail(message):
    sys.exit(f"latency_collate_check: {message}")


for latency in (0, 40):
    write_point(work / "seed1", [1], latency, "none")   # seed 1 alone
    write_point(work / "seed12", [1, 2], latency, "none")  # seeds 1 and 2: seed 1 again, the same values

result = run(work / "seed1", work / "seed12", "--markdown")
if result.returncode != 0:
    fail(f"collate failed: {result.stderr.strip()}")
with open(work / "seed1" / "latency-study.csv") as f:
    rows = list(csv.DictReader(f))
if sorted(r["seed"] for r in rows) != ["1", "1", "2", "2"]:
    fail(f"expected one row per point and seed (seed 1 kept once), got seeds {[r['seed'] for r in rows]}")
if not all(r["foveal_relmse_saccade"] == r["foveal_relmse_fixation"] for r in rows):
    fail("the fixation/saccade split of the foveal relMSE is off")
# 40 ms: relMSE ×1.2 (seed 1) and ×1.4 (seed 2) → mean 1.3; JOD −0.10 and −0.30 → −0.20.
expected = "| 40 | none | 3.00 | 5.0 % | 1.300 [1.200, 1.400] | −0.200 [−0.300, −0.100] | 10 / 5, 1 of 4 |"
if expected not in result.stdout:
    fail(f"expected the row\n{expected}\nin\n{result.stdout}")
if "| 0 | none | 0.20 | 0.0 % | 1.000 [1.000, 1.000] | +0.000 [+0.000, +0.000] |" not in result.stdout:
    fail(f"the 0 ms / none row is not its own baseline:\n{result.stdout}")
if not (work / "seed1" / "latency-study.svg").read_text().startswith("<svg"):
    fail("no plot written")
report = (work / "seed1" / "latency-study.html").read_text()
if report.count("<svg") != 2 or "<h2>rec-a (seeds 1, 2)</h2>" not in report or \
        "<td>1.300 [1.200, 1.400]</td><td>−0.200 [−0.300, −0.100]</td>" not in report:
    fail(f"the HTML report lacks the plots, the recording or its row:\n{report}")

# A seed whose values differ between folders, folders that disagree on the gaze, and a summary
# that disagrees with its frames are refused.
POINTS[(1, 40, "none")] = (1.3e-3, 8.90)
write_point(work / "other", [1], 0, "none")
write_point(work / "other", [1], 40, "none")
result = run(work / "seed1", work / "other")
if result.returncode == 0 or "seed 1 differs between" not in result.stderr:
    fail(f"a seed with other values was combined: rc {result.returncode}, {result.stderr.strip()}")
POINTS[(1, 40, "none")] = (1.2e-3, 8.90)
write_point(work / "gaze", [1], 0, "none")
write_point(work / "gaze", [1], 40, "none", distance=4.0)
result = run(work / "seed1", work / "gaze")
if result.returncode == 0 or "disagree on the gaze columns" not in result.stderr:
    fail(f"studies with different gaze were averaged: rc {result.returncode}, {result.stderr.strip()}")
write_point(work / "tampered", [1], 0, "none", summary_relmse=5.0e-3)
result = run(work / "tampered")
if result.returncode == 0 or "disagrees with summary.json" not in result.stderr:
    fail(f"a summary that disagrees with its frames was read: {result.stderr.strip()}")
# --recording keeps the named recordings only.
result = run(work / "seed1", "--recording", "rec-b")
if result.returncode == 0 or "no runs/" not in result.stderr or "rec-b" not in result.stderr:
    fail(f"--recording of an absent recording was not refused: {result.stderr.strip()}")
result = run(work / "seed1", work / "seed12", "--recording", "rec-a", "--markdown")
if result.returncode != 0 or expected not in result.stdout:
    fail(f"--recording rec-a changed the table: {result.stderr.strip()}")
result = run(work / "empty")
if result.returncode == 0 or "no runs/" not in result.stderr:
    fail(f"an empty study was not refused: {result.stderr.strip()}")
print("latency_collate_check: ok")
