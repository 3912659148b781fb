#!/usr/bin/env bash
# Acceptance check of `fovrt experiment presets/thesis-foveated.toml --quick` (run by ctest as
# app_experiment_quick): the table shows every variant, the CSVs, summary JSON, HTML report and
# manifest exist, a second run with the same config and seed gives byte-identical CSVs, and the
# report loads in headless Chromium with no console error and every figure drawn
# (scripts/report-check.sh; Chromium is installed by scripts/install-deps.sh).
# Usage: experiment_quick_check.sh FOVRT SOURCE_DIR WORK_DIR
set -euo pipefail
. "$(dirname "${BASH_SOURCE[0]}")/tools/skip.sh"
fovrt=$1; src=$2; work=$3
if [[ ! -d "$src/../shared/scenes/veach-ajar" && -z "${FOVRT_SHARED_SCENES:-}" ]]; then
  skip_all "../shared/scenes is absent (the thesis preset renders Veach Ajar)"
fi
rm -rf "$work"; mkdir -p "$work"; cd "$work"
# Two of the preset's three seeds: every multi-seed path runs, in two thirds of the CI time.
run() { "$fovrt" experiment "$src/presets/thesis-foveated.toml" --quick --seeds 2 \
          --set output.dir="$1" --set reference.cache_dir=cache; }
run out > table.txt
cat table.txt
for variant in svgf svgf-weighted two-history asvgf two-history-asvgf; do
  for scene in cornell veach-ajar; do
    awk -v s="$scene" -v v="$variant" '$1=="Scene"{cur=$2; sub(/:$/, "", cur)} cur==s && $1==v{found=1} END{exit !found}' \
      table.txt || { echo "FAIL: variant $variant missing from the $scene table"; exit 1; }
  done
done
for f in out/frames-cornell.csv out/frames-veach-ajar.csv out/summary.json out/report.html out/manifest.json; do
  [[ -s "$f" ]] || { echo "FAIL: $f missing or empty"; exit 1; }
done
grep -q '"complete": true' out/manifest.json || { echo "FAIL: manifest not marked complete"; exit 1; }
grep -q "Scene cornell: 2 seeds (1, 2)" table.txt || { echo "FAIL: the table does not state the seeds"; exit 1; }
grep -q '"ci_low"' out/summary.json || { echo "FAIL: summary.json has no intervals"; exit 1; }
grep -q "HTML report: out/report.html" table.txt || { echo "FAIL: the report path is not printed"; exit 1; }
run out2 > /dev/null
cmp out/frames-cornell.csv out2/frames-cornell.csv
cmp out/frames-veach-ajar.csv out2/frames-veach-ajar.csv
echo "identical CSVs on rerun: yes"
bash "$src/scripts/report-check.sh" out/report.html
echo "1 passed, 0 failed"
