#!/usr/bin/env bash
# No silent wrong results (run by ctest as app_integrity): corrupted shard rows and reference-cache
# entries are refused or re-rendered by content, never used; a merge names every bad or missing
# shard at once; one writer per output folder; an earlier run's outputs are moved aside, never
# left beside a new manifest; SIGINT / SIGTERM stop with one line, no temporaries and no manifest;
# an unwritable output.dir gives the system's reason; a full disk (a file-size limit, a small tmpfs)
# leaves nothing of the failed command's; shards rendered from different contents of a scene are
# refused by --merge; a rerun moves aside exactly what the previous command wrote, each earlier run
# into a folder of its own (a killed one marked partial); the filesystem root and $HOME are refused.
# Every wait is for an event (a line in frames.jsonl, a process's exit), never a fixed time.
# Usage: integrity_check.sh FOVRT WORK_DIR
set -uo pipefail
. "$(dirname "${BASH_SOURCE[0]}")/tools/skip.sh"
fovrt=$(realpath "$1"); work=$(realpath -m "$2"); scenes=$(realpath "$(dirname "$0")/../scenes")
rm -rf "$work"; mkdir -p "$work"; cd "$work"
passed=0; failed=0
ok() { echo "ok: $1"; passed=$((passed + 1)); }
bad() { echo "FAIL: $1"; failed=$((failed + 1)); }
# one_line FILE PATTERN: FILE holds exactly one non-empty line and it matches PATTERN.
one_line() { [[ $(grep -c . "$1") -eq 1 ]] && grep -q -- "$2" "$1"; }
# flip FILE OFFSET: inverts 8 bytes of FILE at OFFSET in place.
flip() {
  python3 - "$1" "$2" <<'PY'
import sys
path, offset = sys.argv[1], int(sys.argv[2])
data = bytearray(open(path, 'rb').read())
for i in range(offset, offset + 8): data[i] ^= 0xFF
open(path, 'wb').write(data)
PY
}

small=(--set camera.width=48 --set camera.height=32 --set denoise.device=cpu)

# --- Shard rows carry their key and a checksum; a merge checks every part before using any ---
cat > exp.toml <<'TOML'
[camera]
width = 48
height = 32
[run]
frames = 2
[reference]
spp = 16
[denoise]
device = "cpu"
[experiment]
scenes = ["cornell"]
variants = ["svgf", "two-history"]
TOML
ex=(--set reference.cache_dir=\"$work/cache\" --set output.dir=\"$work/sharded\")
for i in 0 1 2; do
  "$fovrt" experiment exp.toml "${ex[@]}" --shard $i/3 >/dev/null 2>shard$i.err || bad "shard $i/3: $(tail -1 shard$i.err)"
done
cp -a sharded/shards pristine
restore() { rm -rf sharded/shards; cp -a pristine sharded/shards; }
merge() { "$fovrt" experiment exp.toml "${ex[@]}" --merge >merge.out 2>merge.err; }
merge && ok "intact shards merge" || bad "intact merge: $(cat merge.err)"
cp sharded/frames-cornell.csv intact.csv

rows=sharded/shards/shard-1-of-3/rows.tsv
flip $rows $(( $(head -1 $rows | wc -c) + 40 ))
if merge; then bad "merge of a byte-flipped rows.tsv exited 0 (CSV $(cmp -s intact.csv sharded/frames-cornell.csv && echo same || echo changed))"
elif one_line merge.err "shard-1-of-3: rows.tsv: checksum mismatch"; then ok "8 flipped bytes: $(cat merge.err)"
else bad "flipped bytes: $(cat merge.err)"; fi
restore

rows=sharded/shards/shard-0-of-3/rows.tsv
python3 - $rows <<'PY'
import re, sys
path = sys.argv[1]
lines = open(path).read().split('\n')
fields = lines[1].split('\t')
fields[7] = re.sub(r'[0-8]', lambda m: str(int(m.group()) + 1), fields[7], count=1)  # one digit up
lines[1] = '\t'.join(fields)
open(path, 'w').write('\n'.join(lines))
PY
if merge; then bad "merge of an edited digit exited 0"
elif one_line merge.err "shard-0-of-3: rows.tsv: checksum mismatch"; then ok "one digit edited: refused"
else bad "edited digit: $(cat merge.err)"; fi

# shard 0 still edited; shard 2 gone as well: both named in the one line.
rm -rf sharded/shards/shard-2-of-3
if merge; then bad "merge with a missing shard exited 0"
elif one_line merge.err "missing 2/3" && grep -q "shard-0-of-3: rows.tsv" merge.err; then ok "a bad and a missing shard, both named: $(cat merge.err)"
else bad "bad + missing: $(cat merge.err)"; fi
restore

rm sharded/shards/shard-1-of-3/part.json
if merge; then bad "merge without part.json exited 0"
elif one_line merge.err "shard-1-of-3: missing part.json"; then ok "deleted part.json: 'missing part.json'"
else bad "deleted part.json: $(cat merge.err)"; fi
restore

cp sharded/shards/shard-0-of-3/rows.tsv sharded/shards/shard-1-of-3/rows.tsv
if merge; then bad "merge with shard 0's rows in shard 1 exited 0"
elif one_line merge.err "shard-1-of-3: rows.tsv was made for experiment [0-9a-f]* shard-0-of-3"; then ok "shard 0's rows in shard 1 refused"
else bad "swapped rows: $(cat merge.err)"; fi
restore

sed -i 's/"eye_frames": \([0-9]\)/"eye_frames": 9\1/' sharded/shards/shard-1-of-3/part.json
if merge; then bad "merge of an edited part.json exited 0"
elif one_line merge.err "shard-1-of-3: part.json: checksum mismatch"; then ok "edited part.json refused"
else bad "edited part.json: $(cat merge.err)"; fi
restore
merge && cmp -s intact.csv sharded/frames-cornell.csv && ok "restored shards merge to the same CSV" \
  || bad "restored merge: $(cat merge.err)"

# --- Shards rendered from different contents of their scene: eye 0 before a Kd edit, eye 1 after ---
mkdir scene; cp "$scenes"/{cornell.toml,cornell_room.obj,cornell_room.mtl,cube.obj,cube.mtl} scene/
sed "s|^scenes = .*|scenes = [\"$work/scene/cornell.toml\"]|; s|^variants = .*|variants = [\"svgf\"]|" exp.toml >mixed.toml
mx=(--set reference.cache_dir=\"$work/cache\" --set output.dir=\"$work/mixed\")
"$fovrt" experiment mixed.toml "${mx[@]}" --shard 0/2 >/dev/null 2>mixed.err || bad "mixed shard 0/2: $(tail -1 mixed.err)"
sed -i '0,/^Kd .*/s//Kd 0.9 0.2 0.2/' scene/cornell_room.mtl
"$fovrt" experiment mixed.toml "${mx[@]}" --shard 1/2 >/dev/null 2>mixed.err || bad "mixed shard 1/2: $(tail -1 mixed.err)"
if "$fovrt" experiment mixed.toml "${mx[@]}" --merge >/dev/null 2>mixed.err; then bad "merge of shards of two scene contents exited 0"
elif one_line mixed.err "scene 'cornell' (.*scene/cornell.toml) changed between shard-0-of-2 and shard-1-of-2: files that differ: cornell_room.mtl (" \
     && [[ ! -e mixed/manifest.json ]]; then ok "shards of two scene contents refused: $(cut -c1-220 mixed.err)..."
else bad "shards of two scene contents: $(cat mixed.err)"; fi

# --- Reference-cache entries carry their key and a pixel checksum ---
ref=(--set scene.name=cornell --set camera.width=48 --set camera.height=32 --set run.frames=1 --set reference.spp=16
     --set reference.cache_dir=\"$work/refs\")
"$fovrt" reference "${ref[@]}" >/dev/null 2>ref.err || bad "reference: $(cat ref.err)"
eye0=$(ls refs/*-e0-*.exr); eye1=$(ls refs/*-e1-*.exr)
cp "$eye0" eye0.exr
cp "$eye1" "$eye0"
if "$fovrt" reference "${ref[@]}" >ref.out 2>ref.err && grep -q "^rendered .*-e0-" ref.out \
   && grep -q "^cached .*-e1-" ref.out && cmp -s eye0.exr "$eye0" \
   && [[ $(grep -c "reference cache entry" ref.err) -eq 1 ]] && grep -q "holds the entry of key .*rendering it again" ref.err; then
  ok "eye 1's entry copied over eye 0's: re-rendered, equal to the original ($(grep 'reference cache' ref.err))"
else bad "swapped entry: $(cat ref.out ref.err)"; fi
flip "$eye0" $(( $(stat -c %s "$eye0") / 2 ))
if "$fovrt" reference "${ref[@]}" >ref.out 2>ref.err && grep -q "^rendered .*-e0-" ref.out && cmp -s eye0.exr "$eye0" \
   && [[ $(grep -c "reference cache entry" ref.err) -eq 1 ]] && grep -q "rendering it again" ref.err; then
  ok "byte-flipped entry: re-rendered ($(grep 'reference cache' ref.err | cut -c1-160))"
else bad "flipped entry: $(cat ref.out ref.err)"; fi

# --- One writer per output folder; an earlier run's outputs are moved aside ---
"$fovrt" run "${small[@]}" --set run.frames=3 --set output.dir=out >/dev/null 2>run.err || bad "run: $(cat run.err)"
echo "mine" > out/notes.txt; echo "mine" > out/inputs/mydata.txt
"$fovrt" run "${small[@]}" --set run.frames=1 --set output.dir=out >/dev/null 2>run.err || bad "rerun: $(cat run.err)"
first=(out/previous-run-*)
[[ ${#first[@]} -eq 1 && $(ls out/inputs | wc -l) -eq 3 && $(ls "${first[0]}"/inputs | wc -l) -eq 6 && -f out/notes.txt \
   && -f out/inputs/mydata.txt && $(grep -c . out/frames.jsonl) -eq 1 ]] && grep -q "moved the earlier outputs" run.err \
  && ok "a 1-frame rerun over 3 frames: 2 EXRs beside its manifest, the earlier 6 in ${first[0]#out/}/, notes.txt and inputs/mydata.txt untouched" \
  || bad "stale outputs: $(ls out out/inputs) $(cat run.err)"
"$fovrt" run "${small[@]}" --set run.frames=1 --set output.dir=out >/dev/null 2>run.err || bad "third run: $(cat run.err)"
runs=(out/previous-run-*)
[[ ${#runs[@]} -eq 2 && $(cat out/inputs/mydata.txt) == mine && $(ls "${first[0]}"/inputs | wc -l) -eq 6 ]] \
  && ok "a third run: both earlier runs kept apart, inputs/mydata.txt still in place" \
  || bad "third run: $(ls out out/inputs) $(cat run.err)"

# The lock held by another process (flock(1) here, holding it until we release it).
exec 9>out/.fovrt.lock
flock 9; echo "pid 4242 on testhost, started 2026-01-01 00:00:00 UTC: fovrt run (held by the test)" >&9
if "$fovrt" run "${small[@]}" --set run.frames=1 --set output.dir=out >/dev/null 2>lock.err; then bad "run into a locked folder exited 0"
elif one_line lock.err "in use by another fovrt (pid 4242 on testhost"; then ok "locked folder: $(cat lock.err)"
else bad "locked folder: $(cat lock.err)"; fi
exec 9>&-

# --- Interrupts: a long run, interrupted once its first frame is written ---
# start_run DIR: a run far longer than the test; waits until its first frame is in frames.jsonl.
start_run() {
  "$fovrt" run "${small[@]}" --set run.frames=100000 --set output.dir="$1" >/dev/null 2>"$1.err" &
  pid=$!
  until [[ -s $1/frames.jsonl ]] || ! kill -0 $pid 2>/dev/null; do sleep 0.05; done
}
for sig in INT TERM; do
  start_run int$sig
  if [[ $sig == INT ]]; then  # a second writer while the first holds the folder
    if "$fovrt" run "${small[@]}" --set run.frames=1 --set output.dir=int$sig >/dev/null 2>second.err; then bad "second writer exited 0"
    elif one_line second.err "in use by another fovrt (pid $pid "; then ok "second writer refused: $(cut -c1-150 second.err)..."
    else bad "second writer: $(cat second.err)"; fi
  fi
  kill -$sig $pid; wait $pid; rc=$?
  want=$([[ $sig == INT ]] && echo 130 || echo 143)
  tmp=$(find int$sig -name '*.tmp-*' | wc -l)
  last=$(tail -1 int$sig.err)
  if [[ $rc -eq $want && $tmp -eq 0 && ! -e int$sig/manifest.json && $(grep -c interrupted int$sig.err) -eq 1 ]] \
     && [[ $last =~ ^fovrt:\ interrupted\ by\ SIG$sig:\ [0-9]+\ of\ 100000\ frames\ written\ in\ .*\;\ no\ manifest$ ]]; then
    ok "SIG$sig: exit $rc, no temporaries, no manifest: $last"
  else bad "SIG$sig: exit $rc (want $want), $tmp temporaries, manifest $(ls int$sig/manifest.json 2>&1), stderr: $(cat int$sig.err)"; fi
done

# `reference` on an animated scene (a new entry every frame), interrupted after its first entry.
"$fovrt" reference --set scene.name=pillars --set camera.width=48 --set camera.height=32 --set run.frames=100000 \
  --set reference.spp=4 --set reference.cache_dir=\"refsINT\" >/dev/null 2>refsINT.err &
pid=$!
until compgen -G "refsINT/*.exr" >/dev/null || ! kill -0 $pid 2>/dev/null; do sleep 0.05; done
kill -INT $pid; wait $pid; rc=$?
last=$(tail -1 refsINT.err)
if [[ $rc -eq 130 && $(find refsINT -name '*.tmp-*' | wc -l) -eq 0 && $(grep -c . refsINT.err) -eq 1 ]] \
   && [[ $last =~ ^fovrt:\ interrupted\ by\ SIGINT:\ [0-9]+\ rendered,\ 0\ cached\ in\ refsINT\;\ every\ entry\ there\ is\ complete$ ]]; then
  ok "reference, SIGINT: exit 130, no temporaries: $last"
else bad "reference SIGINT: exit $rc, $(find refsINT -name '*.tmp-*' | wc -l) temporaries: $(cat refsINT.err)"; fi

# A complete run, a run killed (SIGKILL) after its first frame, a third run: the first and the
# killed one each kept in a folder of their own, the killed one named partial.
"$fovrt" run "${small[@]}" --set run.frames=1 --set output.dir=k9 >/dev/null 2>k9.err || bad "run before the kill: $(cat k9.err)"
"$fovrt" run "${small[@]}" --set run.frames=100000 --set output.dir=k9 >/dev/null 2>k9.err &
pid=$!
# until its own first frame: the first run's frames.jsonl moved aside and a new one written since,
# so the kill never lands in the move itself
first_frame_written() { compgen -G 'k9/previous-run-*/frames.jsonl' >/dev/null && [[ -s k9/frames.jsonl ]]; }
for _ in $(seq 100000); do first_frame_written || ! kill -0 $pid 2>/dev/null && break; sleep 0.05; done  # polls the event
kill -KILL $pid; wait $pid 2>/dev/null
"$fovrt" run "${small[@]}" --set run.frames=1 --set output.dir=k9 >/dev/null 2>k9.err || bad "run after the kill: $(cat k9.err)"
complete=(k9/previous-run-*[0-9]Z); partial=(k9/previous-run-*-partial)
if [[ ${#complete[@]} -eq 1 && -f ${complete[0]}/manifest.json && ${#partial[@]} -eq 1 && -s ${partial[0]}/frames.jsonl \
      && ! -e ${partial[0]}/manifest.json && -f k9/manifest.json && $(grep -c . k9/frames.jsonl) -eq 1 ]]; then
  ok "complete, killed, rerun: ${complete[0]#k9/}/ and ${partial[0]#k9/}/ kept, the rerun's outputs at the top"
else bad "killed run: $(ls k9) $(cat k9.err)"; fi

# An experiment of room, then one of cornell, into one folder: room's CSVs move aside with the rest.
for scene in room cornell; do
  "$fovrt" experiment exp.toml --scene $scene --set experiment.variants='["svgf"]' --set run.frames=1 \
    --set reference.cache_dir=\"$work/cache\" --set output.dir=\"$work/scenes\" >/dev/null 2>scenes.err \
    || bad "experiment --scene $scene: $(tail -1 scenes.err)"
done
if [[ -f scenes/gaze-cornell.csv && ! -e scenes/gaze-room.csv && ! -e scenes/frames-room.csv ]] && compgen -G "scenes/previous-run-*/gaze-room.csv" >/dev/null; then
  ok "experiment --scene room, then --scene cornell: gaze-room.csv moved aside with room's outputs"
else bad "stale scene CSVs: $(ls scenes)"; fi

# --- Unwritable folders and a full disk ---
if "$fovrt" run "${small[@]}" --set run.frames=1 --set output.dir=/proc/x >/dev/null 2>proc.err; then bad "output.dir=/proc/x exited 0"
elif one_line proc.err "cannot write to '/proc/x'" && ! grep -q Success proc.err; then ok "$(cat proc.err)"
else bad "/proc/x: $(cat proc.err)"; fi
# The filesystem root and the home folder: refused in one line, before anything is written. As
# root a regression would write into / itself, so there only app_output_dir_test checks the root.
if [[ $(id -u) -eq 0 ]]; then echo "skipped: output.dir=/ (running as root)"
elif "$fovrt" run "${small[@]}" --set run.frames=1 --set output.dir=/ >/dev/null 2>root.err; then bad "output.dir=/ exited 0"
elif one_line root.err "config key 'output.dir': '/' is the filesystem root"; then ok "$(cat root.err)"
else bad "output.dir=/: $(cat root.err)"; fi
mkdir home
if HOME=$work/home "$fovrt" run "${small[@]}" --set run.frames=1 --set output.dir=\"$work/home\" >/dev/null 2>home.err; then
  bad "output.dir=\$HOME exited 0"
elif one_line home.err "is the home folder (\$HOME)" && [[ -z $(ls -A home) ]]; then ok "$(cat home.err)"
else bad "output.dir=\$HOME: $(cat home.err); left $(ls -A home)"; fi
# RLIMIT_FSIZE 0 (SIGXFSZ ignored): every write to a file fails with EFBIG, as on a full disk.
# (stderr goes through a pipe, which the limit does not cover.)
err=$( (trap '' XFSZ; ulimit -f 0; exec "$fovrt" run "${small[@]}" --set run.frames=1 --set output.dir=full/out 2>&1 >/dev/null) )
rc=$?
if [[ $rc -eq 0 ]]; then bad "a run with no space exited 0"
elif [[ ! -e full && $(grep -c "error" <<<"$err") -eq 1 ]] && tail -1 <<<"$err" | grep -q "File too large"; then
  ok "no space: nothing left ($(tail -1 <<<"$err" | cut -c1-100)...)"
else bad "no space: exit $rc, left $(find full 2>&1 | head -5); $err"; fi

# A real full disk: a small tmpfs, mounted in a private mount namespace (unshare: as root, or as a
# user where user namespaces are allowed; skipped with a message where neither works). Each case
# leaves the folder's listing (disk.ls), stderr (disk.err) and exit status (disk.rc) outside it.
# on_full_disk SIZE SETUP COMMAND: SETUP, then COMMAND, run in $work with the tmpfs at disk/.
on_full_disk() {
  rm -rf disk disk.ls disk.err disk.rc; mkdir disk
  unshare -rm bash -c 'mount -t tmpfs -o size=$1 tmpfs disk || exit 99; eval "$2"; eval "$3" >/dev/null 2>disk.err
                       echo $? >disk.rc; (cd disk && find . -mindepth 1 | sort) >disk.ls' _ "$@" 2>/dev/null
}
if ! on_full_disk 64k true true; then
  skip_part "full-disk probes (cannot mount a tmpfs in a private mount namespace: not root, no user namespaces)"
else
  # 64 KiB: the first frame's second EXR finds the disk full.
  on_full_disk 64k true "'$fovrt' run ${small[*]} --set run.frames=1 --set output.dir=disk/out"
  if [[ $(cat disk.rc) -eq 0 ]]; then bad "a run on a full disk exited 0"
  elif [[ ! -s disk.ls && $(grep -c "error" disk.err) -eq 1 ]] && tail -1 disk.err | grep -q "No space left on device"; then
    ok "full disk, new folder: nothing left ($(tail -1 disk.err | cut -c1-90)...)"
  else bad "full disk, new folder: exit $(cat disk.rc), left $(head -5 disk.ls | tr '\n' ' '); $(cat disk.err)"; fi
  # A folder holding an earlier complete run and a file of the user's: the new run's frames fill
  # the disk; the earlier run stays whole in previous-run/, the new run leaves nothing at the top.
  on_full_disk 300k "'$fovrt' run ${small[*]} --set run.frames=1 --set output.dir=disk >/dev/null 2>&1; echo mine >disk/notes.txt" \
    "'$fovrt' run ${small[*]} --set run.frames=8 --set output.dir=disk"
  # (the failed run's ledger, saying it left nothing, stays where the disk had room for it)
  top=$(grep -v '^\./previous-run-[^/]*/\|^\./\.fovrt-outputs\.json$' disk.ls | sed 's|^\./previous-run-.*|./previous-run-*|' | tr '\n' ' ')
  if [[ $(cat disk.rc) -eq 0 ]]; then bad "a run filling the disk exited 0"
  elif [[ $top == "./.fovrt.lock ./notes.txt ./previous-run-* " ]] &&
       grep -q '^\./previous-run-[0-9TZ]*/manifest.json$' disk.ls &&
       [[ $(grep -c "error" disk.err) -eq 1 ]] && tail -1 disk.err | grep -q "No space left on device"; then
    ok "disk full during a run in a folder that existed: only the lock, the user's file and previous-run-*/ left ($(tail -1 disk.err | cut -c1-80)...)"
  else bad "disk full in an existing folder: exit $(cat disk.rc), top: $top; $(cat disk.err)"; fi
fi

echo "$passed passed, $failed failed"
finish $failed
