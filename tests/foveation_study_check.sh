#!/usr/bin/env bash
# The foveation study's quick form end to end (presets/foveation-study.toml --quick), run by ctest
# as app_foveation_study: two sampling designs at three budgets on the room, every point a whole
# experiment; the rays-saved table printed with a value and its interval; curves.csv with one row
# per (design, budget, seed) and the measured rays equal to each budget; summary.json's rays saved
# matching the table; `fovrt rays-saved` on the run's folder, and with a second run's, giving the
# same table; the report's JOD-against-rays plot; two shards and a merge give the same curves and
# summary as the single run.
# Usage: foveation_study_check.sh FOVRT SOURCE_DIR WORK_DIR
set -uo pipefail
. "$(dirname "${BASH_SOURCE[0]}")/tools/skip.sh"
fovrt=$(realpath "$1"); src=$(realpath "$2"); work=$(realpath -m "$3")
rm -rf "$work"; mkdir -p "$work"; cd "$work"
passed=0; failed=0
ok() { echo "ok: $1"; passed=$((passed + 1)); }
bad() { echo "FAIL: $1"; failed=$((failed + 1)); }
preset=$src/presets/foveation-study.toml
args=(--quick --set reference.cache_dir="\"$work/cache\"")

"$fovrt" experiment "$preset" "${args[@]}" --set output.dir=single > single.txt 2> single.err \
  || bad "quick study: $(tail -2 single.err)"
cat single.txt
grep -q "Rays saved at equal perceived quality against 'uniform'" single.txt && ok "the rays-saved table is printed" \
  || bad "no rays-saved table"
# room svgf-weighted perceptual 1.10× [1.05, 1.15] ...: a ratio with an interval
grep -Eq '^  room +svgf-weighted +perceptual +[0-9]+\.[0-9]+× \[[0-9]+\.[0-9]+, [0-9]+\.[0-9]+\]' single.txt \
  && ok "rays saved for perceptual has a value and an interval" || bad "no rays-saved value: $(grep room single.txt)"

rows=$(($(wc -l < single/curves.csv) - 1))
[[ $rows -eq 12 ]] && ok "curves.csv: 12 rows (2 designs × 3 budgets × 2 seeds)" || bad "curves.csv rows: $rows"
# Measured rays: the budget, met by every design (the budget model meets it within a few samples).
python3 - single/curves.csv <<'PY' && ok "measured traced spp equals each budget" || bad "measured spp off the budget"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
off = [(r["design"], r["budget_spp"], r["traced_spp_whole"]) for r in rows
       if abs(float(r["traced_spp_whole"]) - float(r["budget_spp"])) > 0.01 * float(r["budget_spp"])]
sys.exit(1 if off or not rows else 0)
PY
# Below 1 spp a pixel without a path sample gets a guide ray: uniform at 0.5 spp leaves half the
# pixels to guides each frame; from 1 spp on uniform sampling has none.
python3 - single/curves.csv <<'PY' && ok "guide rays counted apart: 0.5 per pixel for uniform at 0.5 spp, none at 1 spp" || bad "guide rays"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
u = {r["budget_spp"]: float(r["guide_rays_whole"]) for r in rows if r["design"] == "uniform"}
p = [float(r["guide_rays_whole"]) for r in rows if r["design"] == "perceptual" and r["budget_spp"] == "0.5"]
sys.exit(0 if abs(u["0.5"] - 0.5) < 0.01 and u["1"] == 0 and u["2"] == 0 and p and min(p) > 0.3 else 1)
PY
# At 1 spp the disc, scaled to the budget, samples uniformly: the same inputs, so the same scores,
# foveal ones included (every design is scored in the experiment's own fovea, not its own).
"$fovrt" experiment "$preset" "${args[@]}" --set output.dir=fovea --set 'experiment.quick.experiment.budgets=[1]' \
  --set 'experiment.designs.disc.budgets=[1]' --set 'experiment.quick.experiment.run_designs=["uniform", "disc"]' \
  > fovea.txt 2> fovea.err || bad "uniform and disc at 1 spp: $(tail -2 fovea.err)"
python3 - fovea/curves.csv <<'PY' && ok "at 1 spp disc scores exactly as uniform, fovea included" || bad "disc at 1 spp differs from uniform"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
u = {r["seed"]: r for r in rows if r["design"] == "uniform"}
d = {r["seed"]: r for r in rows if r["design"] == "disc"}
cols = ["jod", "relmse_whole", "relmse_fovea", "flicker_fovea", "traced_spp_fovea"]
sys.exit(0 if u and u.keys() == d.keys() and all(u[k][c] == d[k][c] for k in u for c in cols) else 1)
PY
# Sweeps that ran apart (fovrt rays-saved): the study's own folder gives the table it printed; with
# the second run's uniform and disc at 1 spp gathered beside it, perceptual's row is unchanged.
table() { awk '/^Rays saved at equal perceived quality/ {on = 1; next} on && /^  / {print; next} on {exit}' "$1"; }
"$fovrt" rays-saved single > apart.txt 2> apart.err || bad "rays-saved of the single run: $(tail -1 apart.err)"
diff <(table single.txt) <(table apart.txt) > /dev/null && [[ -n $(table apart.txt) ]] \
  && ok "rays-saved of the run's folder prints the run's own table" || bad "rays-saved table differs: $(cat apart.txt)"
row() { grep -E '^  room +svgf-weighted +perceptual ' "$1" | head -1 | tr -s ' '; }
"$fovrt" rays-saved single fovea > apart2.txt 2> apart2.err || bad "rays-saved of two runs: $(tail -1 apart2.err)"
[[ -n $(row apart.txt) && "$(row apart.txt)" == "$(row apart2.txt)" ]] && grep -Eq '^  room +svgf-weighted +disc ' apart2.txt \
  && ok "a second run's points gathered beside it: perceptual's row unchanged, disc listed" \
  || bad "two runs: '$(row apart.txt)' against '$(row apart2.txt)'"
# One gaze window pooled is the run itself; --design takes one name, so the folder after it stays a run.
"$fovrt" rays-saved --pool-gaze --design perceptual single > pooled.txt 2> pooled.err \
  || bad "rays-saved --pool-gaze of the single run: $(tail -1 pooled.err)"
[[ -n $(row apart.txt) && "$(row apart.txt)" == "$(row pooled.txt)" ]] && ! grep -q "gaze windows pooled" pooled.txt \
  && ok "--pool-gaze over one window: perceptual's row unchanged" || bad "pooled: '$(row pooled.txt)'"
"$fovrt" rays-saved single --anchor nope > /dev/null 2> apart3.err && bad "rays-saved ran with an unknown anchor" \
  || { grep -q "no run holds the anchor design 'nope'" apart3.err && ok "an unknown anchor is refused: $(tail -1 apart3.err)" \
       || bad "anchor message: $(tail -1 apart3.err)"; }
python3 - single/summary.json single.txt <<'PY' && ok "summary.json's rays saved is the table's" || bad "summary.json rays saved"
import json, re, sys
s = json.load(open(sys.argv[1]))
r = s["designs"]["perceptual"]["rays_saved"]["room"]["svgf-weighted"]
shown = re.search(r"perceptual +([0-9.]+)× \[([0-9.]+), ([0-9.]+)\]", open(sys.argv[2]).read())
ok = s["anchor_design"] == "uniform" and r["lower"] <= r["value"] <= r["upper"] and shown \
     and all(abs(float(shown.group(i + 1)) - v) < 0.006 for i, v in enumerate([r["value"], r["lower"], r["upper"]]))
ok = ok and set(s["designs"]["uniform"]["points"][0]["traced_spp"]["room"]) == {"whole", "fovea", "periphery"}
f = s["designs"]["perceptual"]["rays_saved_fovea"]["room"]["svgf-weighted"]  # at equal foveal relMSE
ok = ok and f["value"] is not None and f["lower"] <= f["value"] <= f["upper"]
sys.exit(0 if ok else 1)
PY
# --json: the same comparison unrounded, equal to the sweep's own summary.json (to curves.csv's 9 digits).
"$fovrt" rays-saved single --json apart.json > apart4.txt 2> apart4.err || bad "rays-saved --json: $(tail -1 apart4.err)"
python3 - single/summary.json apart.json <<'PY' && ok "rays-saved --json: the run's rays saved, JOD gain and points, unrounded" \
  || bad "rays-saved --json differs from summary.json"
import json, math, sys
s, j = json.load(open(sys.argv[1])), json.load(open(sys.argv[2]))
def same(a, b):  # equal but for the 9 significant digits curves.csv keeps
    if isinstance(a, dict): return isinstance(b, dict) and a.keys() == b.keys() and all(same(a[k], b[k]) for k in a)
    if isinstance(a, list): return isinstance(b, list) and len(a) == len(b) and all(map(same, a, b))
    if isinstance(a, float) and isinstance(b, (int, float)): return math.isclose(a, b, rel_tol=1e-7, abs_tol=1e-6)
    return a == b
c = [c for c in j["comparisons"] if (c["scene"], c["variant"], c["design"]) == ("room", "svgf-weighted", "perceptual")][0]
d = s["designs"]["perceptual"]
ok = j["anchor_design"] == "uniform" and j["method"] == s["method"] and j["bootstrap_unit"] == "seed" and [u["seed"] for u in c["units"]] == s["seeds"]
ok = ok and all(same(c[k], d[k]["room"]["svgf-weighted"]) for k in ("rays_saved", "jod_gain", "rays_saved_fovea"))
ok = ok and same([p["rays_saved_here"] for p in c["points"]], [p["scores"]["room"]["svgf-weighted"]["rays_saved_here"] for p in d["points"]])
ok = ok and same([p["traced_spp"] for p in c["points"]], [p["traced_spp"]["room"]["whole"] for p in d["points"]])
ok = ok and c["rays_saved"]["value"] is not None and "lower" in c["rays_saved"]
sys.exit(0 if ok else 1)
PY
"$fovrt" rays-saved single --json apart.txt/apart.json > /dev/null 2> apart5.err && bad "rays-saved --json under a file ran" \
  || { [[ $(wc -l < apart5.err) -eq 1 ]] && grep -q "\-\-json apart.txt/apart.json" apart5.err && ! ls apart.txt?* > /dev/null 2>&1 \
         && ok "--json under a file: one line naming it, nothing left: $(cat apart5.err)" || bad "--json failure: $(cat apart5.err)"; }
grep -q "room · svgf-weighted: JOD against rays" single/report.html && [[ $(grep -o "<circle" single/report.html | wc -l) -ge 6 ]] \
  && ok "the report plots JOD against rays, a marker per point" || bad "report plot"
if command -v chromium > /dev/null 2>&1 || command -v chromium-browser > /dev/null 2>&1; then
  bash "$src/scripts/report-check.sh" single/report.html dom.html 2> browser.err \
    && ok "the sweep's report draws every figure in headless Chromium" || bad "browser check: $(tail -3 browser.err)"
else
  skip_part "chromium is not installed: the sweep's report was not opened in a browser"
fi
[[ -f single/designs/perceptual-b2/summary.json && -f single/designs/uniform-b0.5/frames-room.csv ]] \
  && ok "every point's own outputs under designs/" || bad "point outputs: $(ls single/designs)"

for i in 0 1; do
  "$fovrt" experiment "$preset" "${args[@]}" --set output.dir=sharded --shard $i/2 > /dev/null 2> shard$i.err \
    || bad "shard $i/2: $(tail -2 shard$i.err)"
done
"$fovrt" experiment "$preset" "${args[@]}" --set output.dir=sharded --merge > merged.txt 2> merge.err \
  || bad "merge: $(tail -2 merge.err)"
cmp single/curves.csv sharded/curves.csv && cmp single/summary.json sharded/summary.json \
  && ok "two shards and a merge: curves.csv and summary.json identical to the single run" || bad "merged sweep differs"
diff <(grep -v "HTML report" single.txt) <(grep -v "HTML report" merged.txt) > /dev/null && ok "merged table identical" \
  || bad "merged table differs"

# Refusals name the design and key.
"$fovrt" experiment "$preset" "${args[@]}" --set output.dir=bad --set experiment.designs.disc.render.spp=3 \
  > /dev/null 2> bad.err && bad "a design with a render key ran" \
  || { grep -q "experiment.designs.disc.render.spp" bad.err && ok "a design's foreign key is refused: $(tail -1 bad.err)" \
       || bad "foreign key message: $(tail -1 bad.err)"; }
"$fovrt" experiment "$preset" "${args[@]}" --set output.dir=bad --set foveation.spp_max=8 \
  > /dev/null 2> bad.err && bad "--set of a design's key ran" \
  || { grep -q "experiment.designs.perceptual" bad.err && ok "--set of a design's key is refused" || bad "set message: $(tail -1 bad.err)"; }

echo "passed $passed, failed $failed"
finish "$failed"
