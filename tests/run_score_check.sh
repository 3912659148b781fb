#!/usr/bin/env bash
# `fovrt run --score` (ctest app_run_score): a small run scored against the cached references
# gives the numbers `fovrt experiment` gives for the same config, seed and variants (same inputs,
# same references, same code: jod.csv and the per-frame CSV byte-identical), writes them where
# the manifest says, and leaves every other output of the run unchanged (frames byte-identical to
# an unscored run, no score files or manifest block without it). The experiment's memory budget
# counts the metric's frames.
# Usage: run_score_check.sh FOVRT WORK_DIR
set -euo pipefail
fovrt=$1; work=$2
rm -rf "$work"; mkdir -p "$work"; cd "$work"

cat > run.toml <<'TOML'
[scene]
name = "cornell"
[camera]
width = 96
height = 64
[run]
frames = 5
seed = 3
[gaze]
source = "static"
[denoise]
device = "cpu"
denoisers = ["svgf", "two-history"]
[reference]
spp = 8
cache_dir = "cache"
[output]
write_exr = true
TOML
{ cat run.toml; printf '[experiment]\nscenes = ["cornell"]\nvariants = ["svgf", "two-history"]\n'; } > exp.toml

"$fovrt" run -c run.toml --set output.dir=plain 2> plain.err || { cat plain.err; echo "FAIL: unscored run failed"; exit 1; }
"$fovrt" run -c run.toml --score --set output.dir=scored > scored.txt 2> scored.err ||
  { cat scored.err; echo "FAIL: scored run failed"; exit 1; }
"$fovrt" experiment exp.toml --set output.dir=exp --set output.report=false > exp.txt 2> exp.err ||
  { cat exp.err; echo "FAIL: experiment failed"; exit 1; }
cat scored.txt

# The run's scores are the experiment's: same frames, references and code.
for f in jod.csv frames-cornell.csv; do
  [[ -s scored/$f ]] || { echo "FAIL: scored/$f missing"; exit 1; }
  cmp scored/$f exp/$f || { diff scored/$f exp/$f | head; echo "FAIL: scored/$f differs from the experiment's"; exit 1; }
done
echo "jod.csv and frames-cornell.csv identical to the experiment's: yes"
python3 - <<'PY'
import json, sys
run = json.load(open("scored/summary.json"))["fovvideovdp"]["scenes"]["cornell"]
exp = json.load(open("exp/summary.json"))["fovvideovdp"]["scenes"]["cornell"]
for v in ("svgf", "two-history"):
    if run[v]["jod"] != exp[v]["jod"]: sys.exit(f"FAIL: summary JOD of {v}: run {run[v]['jod']} vs experiment {exp[v]['jod']}")
    if not 0 < run[v]["jod"] < 10: sys.exit(f"FAIL: JOD of {v} is {run[v]['jod']}")
score = json.load(open("scored/manifest.json"))["score"]
for key in ("reference", "relmse", "fovvideovdp", "files"):
    if key not in score: sys.exit(f"FAIL: the manifest's score block has no {key}")
jod = score["fovvideovdp"]["jod"]
for v in ("svgf", "two-history"):
    if abs(jod[v]["mean"] - (jod[v]["left"] + jod[v]["right"]) / 2) > 1e-9: sys.exit(f"FAIL: manifest JOD mean of {v}")
    if abs(jod[v]["mean"] - run[v]["jod"]) > 1e-12: sys.exit(f"FAIL: manifest JOD of {v} is not summary.json's")
    for region in ("whole", "fovea", "periphery"):
        if not score["relmse"][v][region] > 0: sys.exit(f"FAIL: manifest relMSE {v} {region}")
if score["reference"]["lookups"] != 10: sys.exit(f"FAIL: {score['reference']['lookups']} reference lookups, not 5 frames x 2 eyes")
if "score" in json.load(open("plain/manifest.json")): sys.exit("FAIL: an unscored run's manifest has a score block")
print("summary.json and the manifest agree: svgf", run["svgf"]["jod"], "two-history", run["two-history"]["jod"])
PY
grep -q "FovVideoVDP JOD" scored.txt || { echo "FAIL: the scored run printed no JOD table"; exit 1; }

# Scoring changes no other output.
for f in jod.csv summary.json frames-cornell.csv; do
  [[ ! -e plain/$f ]] || { echo "FAIL: the unscored run wrote $f"; exit 1; }
done
compared=0
while IFS= read -r f; do
  cmp "plain/$f" "scored/$f" || { echo "FAIL: $f differs between the unscored and the scored run"; exit 1; }
  compared=$((compared + 1))
done < <(cd plain && find inputs noisy denoised -type f | sort)
[[ $compared -ge 30 ]] || { echo "FAIL: only $compared frame files compared"; exit 1; }
echo "$compared frame files identical with and without scoring"

# The experiment's memory plan holds the metric's frames (2000 frames: they dominate the plan).
if "$fovrt" experiment exp.toml --set run.frames=2000 --memory-budget 64MiB --set output.dir=budget > /dev/null 2> budget.err; then
  echo "FAIL: the budget passed"; exit 1
fi
grep -q "largest buffers: eye[01].vdp" budget.err || { cat budget.err; echo "FAIL: the budget does not name the metric's frames"; exit 1; }
echo "1 passed, 0 failed"
