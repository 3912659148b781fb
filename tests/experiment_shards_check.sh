#!/usr/bin/env bash
# Sharded experiments (issue #15), run by ctest as app_experiment_shards: the quick thesis
# experiment on cornell with 2 seeds, split into 3 shards run one after another, merges into
# CSVs, summary and table byte-identical to the single run; a killed shard leaves nothing that
# looks finished and the merge names it; rerunning just that shard completes the set; shards of
# another experiment are refused; two processes writing the same reference key at once leave one
# valid entry; the cluster jobs run under GNU parallel (when installed) with the same result.
# Usage: experiment_shards_check.sh FOVRT SOURCE_DIR IMAGE_PROBE WORK_DIR
set -uo pipefail
. "$(dirname "${BASH_SOURCE[0]}")/tools/skip.sh"
fovrt=$(realpath "$1"); src=$(realpath "$2"); probe=$(realpath "$3"); work=$(realpath -m "$4")
rm -rf "$work"; mkdir -p "$work"; cd "$work"
passed=0; failed=0
ok() { echo "ok: $1"; passed=$((passed + 1)); }
bad() { echo "FAIL: $1"; failed=$((failed + 1)); }
preset=$src/presets/thesis-foveated.toml
args=(--quick --scene cornell --seeds 2 --set run.frames=4 --set reference.cache_dir="\"$work/cache\"")

t0=$(date +%s.%N)
"$fovrt" experiment "$preset" "${args[@]}" --set output.dir=single > single.txt 2>single.err \
  || bad "single run: $(tail -2 single.err)"
t1=$(date +%s.%N)
echo "single run: $(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.1f", b - a }') s"
for i in 0 1 2; do
  "$fovrt" experiment "$preset" "${args[@]}" --set output.dir=sharded --shard $i/3 >/dev/null 2>shard$i.err \
    || bad "shard $i/3: $(tail -2 shard$i.err)"
done
[[ -f sharded/shards/shard-0-of-3/part.json && ! -e sharded/manifest.json ]] \
  && ok "3 shards wrote their parts (and no experiment outputs)" || bad "shard parts: $(ls sharded sharded/shards 2>&1)"
"$fovrt" experiment "$preset" "${args[@]}" --set output.dir=sharded --merge > merged.txt 2>merge.err \
  || bad "merge: $(tail -2 merge.err)"
cmp single/frames-cornell.csv sharded/frames-cornell.csv && ok "merged CSV byte-identical to the single run ($(grep -c . single/frames-cornell.csv) lines)" \
  || bad "merged CSV differs"
cmp single/summary.json sharded/summary.json && ok "summary.json identical" || bad "summary.json differs"
diff <(grep -v "HTML report" single.txt) <(grep -v "HTML report" merged.txt) >/dev/null && ok "stdout table identical" \
  || bad "table differs: $(diff <(grep -v 'HTML report' single.txt) <(grep -v 'HTML report' merged.txt) | head -4)"
imgs() { grep -o '<img' "$1" | wc -l; }
[[ -f sharded/report.html && $(imgs single/report.html) -eq $(imgs sharded/report.html) && $(imgs single/report.html) -gt 0 ]] \
  && ok "merged report has the single run's $(imgs single/report.html) images" \
  || bad "report images: single $(imgs single/report.html), merged $(imgs sharded/report.html 2>/dev/null)"
grep -q '"merged_shards": true' sharded/manifest.json && ok "the manifest says it was merged" || bad "manifest"

# A shard killed mid-run: nothing that looks finished; the merge names it; a rerun completes.
rm -rf sharded/shards/shard-1-of-3 sharded/manifest.json
# (killed once its first denoised frame is on disk: mid-run, whatever the machine's speed)
rm -rf sharded/cornell
"$fovrt" experiment "$preset" "${args[@]}" --set output.dir=sharded --shard 1/3 --set output.write_exr=true \
  >/dev/null 2>kill.err &
pid=$!
end=$((SECONDS + 600))
until compgen -G "sharded/cornell/*/*.exr" >/dev/null || ! kill -0 $pid 2>/dev/null || ((SECONDS > end)); do sleep 0.1; done
kill -9 $pid 2>/dev/null; wait $pid 2>/dev/null
[[ ! -e sharded/shards/shard-1-of-3 ]] && ok "killed shard left no part" || bad "killed shard left $(ls sharded/shards)"
if "$fovrt" experiment "$preset" "${args[@]}" --set output.dir=sharded --merge >/dev/null 2>incomplete.err; then
  bad "merge of an incomplete set succeeded"
elif [[ $(grep -c . incomplete.err) -eq 1 ]] && grep -q "missing 1/3" incomplete.err; then ok "$(cat incomplete.err)"
else bad "incomplete merge: $(cat incomplete.err)"; fi
"$fovrt" experiment "$preset" "${args[@]}" --set output.dir=sharded --shard 1/3 >/dev/null 2>rerun.err \
  && "$fovrt" experiment "$preset" "${args[@]}" --set output.dir=sharded --merge >/dev/null 2>>rerun.err \
  && cmp -s single/frames-cornell.csv sharded/frames-cornell.csv && ok "rerunning shard 1/3 completes the set (CSV identical)" \
  || bad "rerun: $(tail -2 rerun.err)"
# Parts of another experiment (another seed list) are refused.
if "$fovrt" experiment "$preset" --quick --scene cornell --seeds 3 --set run.frames=4 \
     --set reference.cache_dir="\"$work/cache\"" --set output.dir=sharded --merge >/dev/null 2>other.err; then
  bad "merged parts of another experiment"
else grep -q "another experiment" other.err && ok "parts of another experiment refused: $(head -c 120 other.err)" \
  || bad "other experiment: $(cat other.err)"; fi

# Two processes writing the same reference key at once: one valid entry, no temporaries.
ref=(--set scene.name=cornell --set camera.width=96 --set camera.height=54 --set run.frames=1 --set reference.spp=64)
"$fovrt" reference "${ref[@]}" --set reference.cache_dir=solo >/dev/null 2>&1
"$fovrt" reference "${ref[@]}" --set reference.cache_dir=shared >/dev/null 2>race1.err & p1=$!
"$fovrt" reference "${ref[@]}" --set reference.cache_dir=shared >/dev/null 2>race2.err & p2=$!
wait $p1; r1=$?; wait $p2; r2=$?
n=$(ls shared | wc -l); tmp=$(ls -a shared | grep -c tmp)
same=0; for f in solo/*.exr; do "$probe" exr-equal "$f" "shared/$(basename "$f")" >/dev/null && same=$((same + 1)); done
[[ $r1 -eq 0 && $r2 -eq 0 && $n -eq 2 && $tmp -eq 0 && $same -eq 2 ]] \
  && ok "two writers of the same keys: $n entries (one per eye), no temporaries, equal to a solo render" \
  || bad "concurrent writers: exit $r1/$r2, $n entries, $tmp temporaries, $same equal"

# image_probe exr-relmse, as docs/foveation-study.md measures a reference's own noise: 0 against
# itself, above 0 against the reference of another seed, in the whole image and in two discs.
"$fovrt" reference "${ref[@]}" --eye 0 --set reference.seed=2 --set reference.cache_dir=seed2 >/dev/null 2>&1
self=$("$probe" exr-relmse solo/*-e0-*.exr solo/*-e0-*.exr 10 48 27 20 20)
other=$("$probe" exr-relmse seed2/*-e0-*.exr solo/*-e0-*.exr 10 48 27 20 20)
[[ "$self" == $'whole 0\ndiscs 2 radius 10 mean 0' ]] && awk '{ if ($NF <= 0) bad = 1 } END { exit bad }' <<<"$other" \
  && ok "exr-relmse: 0 against itself, $(tr '\n' ' ' <<<"$other")against another seed" \
  || bad "exr-relmse: '$self' / '$other'"

# The cluster jobs on this machine with GNU parallel: the same CSV.
"$fovrt" cluster "$preset" "${args[@]}" --set output.dir=viaparallel --shards 3 --reference-tasks 4 \
  --jobs-dir jobs 2>cluster.err || bad "fovrt cluster: $(cat cluster.err)"
[[ $(grep -c . jobs/references.tasks) -ge 2 && $(grep -c . jobs/experiment.tasks) -eq 3 ]] \
  && grep -q -- "--shard 2/3" jobs/experiment.tasks && grep -q "#SBATCH --array=0-2" jobs/experiment.sbatch \
  && grep -q "dependency=afterok" jobs/submit.sh && ok "fovrt cluster wrote $(grep -c . jobs/references.tasks) reference tasks, 3 shards, sbatch scripts" \
  || bad "jobs dir: $(ls jobs)"
if command -v parallel >/dev/null; then
  if bash jobs/run-parallel.sh 2 >parallel.out 2>&1 && cmp -s single/frames-cornell.csv viaparallel/frames-cornell.csv; then
    ok "run-parallel.sh (GNU parallel): CSV identical to the single run"
  else bad "run-parallel.sh: $(tail -3 parallel.out)"; fi
else skip_part "run-parallel.sh: GNU parallel is not installed (scripts/install-deps.sh installs it)"; fi

# On a real one-node Slurm cluster started here (tests/tools/slurm_cluster.sh): the references as
# one job array, the shards as a second (afterok), the merge last; the same CSV as the single run.
cluster=$work/slurm
if out=$(bash "$src/tests/tools/slurm_cluster.sh" start "$cluster" 2>slurm.err); then
  eval "$out"
  trap 'bash "$src/tests/tools/slurm_cluster.sh" stop "$cluster"' EXIT
  start=$(date +%s.%N)
  if "$fovrt" cluster "$preset" "${args[@]}" --set output.dir=viaslurm --shards 3 --reference-tasks 4 \
       --partition fovrt --time 00:30:00 --cpus-per-task 1 --jobs-dir slurmjobs --submit >submit.out 2>&1; then
    # Until the merge job's manifest is there or the queue is empty (every job ended).
    end=$((SECONDS + 1800))
    until [[ -f viaslurm/manifest.json || -z $(squeue -h 2>/dev/null) ]] || ((SECONDS > end)); do sleep 0.5; done
    end=$(date +%s.%N)
    if cmp -s single/frames-cornell.csv viaslurm/frames-cornell.csv; then
      ok "Slurm: 3 job arrays chained by afterok ($(tail -1 submit.out)) merged to the single run's CSV in $(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.1f", b - a }') s"
    else bad "Slurm: no identical CSV: $(tail -2 submit.out); $(tail -3 slurmjobs/logs/*.out 2>/dev/null | tail -6)"; fi
  else bad "Slurm submit: $(tail -3 submit.out)"; fi
  bash "$src/tests/tools/slurm_cluster.sh" stop "$cluster"; trap - EXIT
  pgrep -f "$cluster/slurm.conf" >/dev/null && bad "Slurm daemons still running" || ok "Slurm daemons stopped"
else
  skip_part "Slurm: the one-node cluster did not start ($(tail -1 slurm.err))"
fi

echo "$passed passed, $failed failed"
finish $failed
