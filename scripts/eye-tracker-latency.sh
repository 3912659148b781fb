#!/usr/bin/env bash
# The eye-tracker latency study (docs/eye-tracking.md): presets/eye-tracker-latency.toml for every
# headset recording × tracker latency × predictor, one `fovrt experiment` per point (--set), then
# scripts/eye_tracker_latency_collate.py writes latency-study.csv, latency-study.svg (foveal relMSE,
# JOD, fovea-to-gaze distance and miss rate against latency, one line per predictor) and the
# report latency-study.html (the plot, then per recording its plot and table).
#
# Usage: scripts/eye-tracker-latency.sh [--quick] [--seeds N|LIST] [--out DIR] [--fovrt PATH]
#                                       [--recordings "a.csv b.csv"] [--latencies "0 10 ..."]
#                                       [--predictions "none cv landing"] [-- extra fovrt options]
# Recordings default to every ../shared/gaze/*.csv. A point already complete (its manifest.json
# exists) is not run again, so an interrupted study resumes. Seeds may run as separate studies
# (--out DIR3 -- --set 'experiment.seeds=[3]'; --seeds N is a count: seeds 1..N) and be collated
# together, each seed once: python3 scripts/eye_tracker_latency_collate.py DIR1 DIR3 --markdown
set -euo pipefail
cd "$(dirname "$0")/.."

fovrt=build/src/app/fovrt
out=out/eye-tracker-latency-study
quick=()
seeds=()
recordings=(../shared/gaze/*.csv)
latencies=(0 10 20 40 80 150)
predictions=(none cv landing)
extra=()
while [[ $# -gt 0 ]]; do
  case "$1" in
    --quick) quick=(--quick); shift ;;
    --seeds) seeds=(--seeds "$2"); shift 2 ;;
    --out) out=$2; shift 2 ;;
    --fovrt) fovrt=$2; shift 2 ;;
    --recordings) read -r -a recordings <<<"$2"; shift 2 ;;
    --latencies) read -r -a latencies <<<"$2"; shift 2 ;;
    --predictions) read -r -a predictions <<<"$2"; shift 2 ;;
    --) shift; extra=("$@"); break ;;
    *) echo "eye-tracker-latency.sh: unknown option '$1'" >&2; exit 2 ;;
  esac
done
[[ -x $fovrt ]] || { echo "eye-tracker-latency.sh: no fovrt at '$fovrt' (build it, or --fovrt PATH)" >&2; exit 1; }
for r in "${recordings[@]}"; do
  [[ -f $r ]] || { echo "eye-tracker-latency.sh: recording '$r' not found (../shared/gaze absent?)" >&2; exit 1; }
done

mkdir -p "$out/runs"
for r in "${recordings[@]}"; do
  name=$(basename "$r" .csv)
  for latency in "${latencies[@]}"; do
    for prediction in "${predictions[@]}"; do
      dir="$out/runs/$name/latency-$latency/$prediction"
      [[ -f $dir/manifest.json ]] && continue
      echo "== $name, latency $latency ms, prediction $prediction" >&2
      mkdir -p "$(dirname "$dir")"
      "$fovrt" experiment presets/eye-tracker-latency.toml "${quick[@]}" "${seeds[@]}" \
        --set "gaze.recording_path=$r" --set "gaze.tracker_latency_ms=$latency" \
        --set "gaze.prediction=$prediction" --set "output.dir=$dir" --set output.report=false \
        "${extra[@]}" >"$dir.log" 2>&1 || { echo "failed: see $dir.log" >&2; exit 1; }
    done
  done
done
python3 scripts/eye_tracker_latency_collate.py "$out"
