#!/usr/bin/env bash
# The HTML report in a real browser (ctest app_report_browser): a small experiment on the built-in
# Cornell box (2 seeds, 2 variants, a gaze trace with a saccade and a blink so that every kind of
# plot mark is drawn) writes a report; scripts/report-check.sh loads it offline in headless
# Chromium and fails on any console error or figure that did not draw. A copy of the report with
# one image broken and a script error must then fail the same check (the check can fail), and so
# must a copy whose summary table is wider than a 1400-pixel page. The report's other elements
# (full frames with exposure, difference and metric maps, per-seed table, time) are checked too.
# Usage: report_browser_check.sh FOVRT SOURCE_DIR WORK_DIR
set -euo pipefail
fovrt=$1; src=$2; work=$3
rm -rf "$work"; mkdir -p "$work"; cd "$work"

# Rows every 33 ms: a 13° jump between 66 and 100 ms (a saccade, ~400°/s) and a blink (NaN rows).
printf 'n,x,y\n0,0,0\n33,1,0\n66,2,0\n100,15,3\n133,15.5,3\n166,NaN,NaN\n200,NaN,NaN\n233,16,3\n266,16,2\n300,16,2\n333,16,2\n' > trace.csv
cat > exp.toml <<'EOF'
[camera]
width = 64
height = 36
[run]
frames = 10
[foveation]
radius_px = 300
[gaze]
source = "trace"
trace_path = "trace.csv"
[denoise]
device = "cpu"
[reference]
spp = 8
cache_dir = "cache"
[output]
dir = "out"
[experiment]
scenes = ["cornell"]
variants = ["svgf", "two-history"]
seeds = [1, 2]
EOF
"$fovrt" experiment exp.toml > table.txt 2> err.txt || { cat err.txt; echo "FAIL: experiment failed"; exit 1; }
grep -q "HTML report: out/report.html" table.txt || { cat table.txt; echo "FAIL: no report path printed"; exit 1; }
grep -q "saccade" out/report.html || { echo "FAIL: the trace's saccade is not marked"; exit 1; }
grep -q ">blink<" out/report.html || { echo "FAIL: the trace's blink is not marked"; exit 1; }

bash "$src/scripts/report-check.sh" out/report.html dom.html
# What a researcher reads in the page: the full frames painted at the slider's exposure
# (reference, noisy, both variants), each variant against the baseline, the metric's maps, the
# per-seed table, the experiment's time.
painted=$(grep -o '<canvas[^>]*data-painted="1"' dom.html | wc -l)
[[ $painted -eq 4 ]] || { echo "FAIL: $painted of 4 full frames painted"; exit 1; }
grep -q 'class="exposure"' out/report.html || { echo "FAIL: no exposure slider"; exit 1; }
grep -q 'alt="two-history vs svgf"' out/report.html || { echo "FAIL: no difference map to the baseline"; exit 1; }
grep -q 'alt="two-history FovVideoVDP map"' out/report.html || { echo "FAIL: no FovVideoVDP map"; exit 1; }
grep -q '<h3>Per seed' out/report.html || { echo "FAIL: no per-seed table"; exit 1; }
grep -Eq '<td>time</td><td>[0-9.]+ s wall, [0-9.]+ s CPU' out/report.html || { echo "FAIL: no run time"; exit 1; }
echo "report elements: frames painted, exposure, difference and metric maps, per-seed table, time"

# The summary must fit a 1400-pixel page: the same report with an overwide summary must fail.
python3 - <<'PY'
s = open("out/report.html").read()
s = s.replace('<table class="summary">', '<table class="summary" style="min-width:2000px">', 1)
open("wide.html", "w").write(s)
PY
if bash "$src/scripts/report-check.sh" wide.html wide-dom.html 2> wide.txt; then
  echo "FAIL: a summary wider than the page passed the check"; exit 1
fi
grep -q "wider than the page" wide.txt || { cat wide.txt; echo "FAIL: the wide summary was not reported"; exit 1; }
echo "negative control: a summary wider than a 1400-pixel page fails the check"

# The negative control: a broken image and a script error must fail the check.
python3 - <<'EOF'
s = open("out/report.html").read()
s = s.replace("data:image/png;base64,iVBOR", "data:image/png;base64,AAAAA", 1)
s = s.replace("</body>", "<script>undefinedFunction();</script></body>")
open("broken.html", "w").write(s)
EOF
if bash "$src/scripts/report-check.sh" broken.html broken-dom.html 2> broken.txt; then
  echo "FAIL: a report with a broken image and a script error passed the check"; exit 1
fi
grep -q "did not draw" broken.txt || { cat broken.txt; echo "FAIL: the broken image was not reported"; exit 1; }
grep -q "undefinedFunction" broken.txt || { cat broken.txt; echo "FAIL: the script error was not reported"; exit 1; }
echo "negative control: a broken image and a script error fail the check"
echo "1 passed, 0 failed"
