#!/usr/bin/env bash
# CI smoke test of the RAE's training code (training/): a tiny `fovrt dataset` (cornell, 64×64,
# 8 frames, 16-spp references), 40 steps of train.py on one fixed batch (small widths, 32² crops)
# must lower the loss, and the exported .raew must reproduce PyTorch's outputs in the C++
# reference (tests/tools/rae_check, 1e-4 relative) for both input sets (with and without the
# sample-count channel). Fine-tuning from the export (--init) with the committed weights' options
# runs on a dataset with a second noise realisation, every sequence a camera stop that takes it,
# together with a dataset of a procedural room (training/procedural_scenes.py: the same seed writes
# the same files; `fovrt dataset` takes the scene by path, refuses two scenes of one name before it
# writes anything, and with --gaze-per-scene gives each scene its own Lissajous path).
# Exit 77 (skipped) without Debian's python3-torch.
# Usage: rae_training_check.sh FOVRT RAE_CHECK SOURCE_DIR WORK_DIR
set -euo pipefail
. "$(dirname "${BASH_SOURCE[0]}")/tools/skip.sh"
fovrt=$1 check=$2 src=$3 work=$4
py=/usr/bin/python3
[ -x "$py" ] || py=python3
if ! "$py" -c "import torch, numpy" 2>/dev/null; then
  skip_all "python3-torch / python3-numpy not installed (scripts/install-deps.sh installs them)"
fi
rm -rf "$work" && mkdir -p "$work"
"$fovrt" dataset --out "$work/data" --scenes cornell --eval "" --no-uniform --noise-realisations 2 \
  --set camera.width=64 --set camera.height=64 --set run.frames=8 --set reference.spp=16 \
  --set reference.cache_dir="\"$work/cache\"" --set foveation.radius_px=100 >/dev/null
# The block-energy term (train.energy_loss) in closed form: 0 for the target itself and for any
# rearrangement of pixels inside a block (where the paper's per-pixel L1 is not 0); doubling the
# linear light of every pixel costs each block m^γ (2^γ − 1).
"$py" - "$src/training" <<'PY'
import sys
sys.path.insert(0, sys.argv[1])
import torch, train, rae_net
g = rae_net.GAMMA
t = torch.rand(1, 2, 3, 16, 16) + 0.1
assert train.energy_loss(t, t).item() < 1e-6
flipped = t.flip(-1).view(1, 2, 3, 16, 2, 8).flip(-2).reshape(1, 2, 3, 16, 16)  # mirror inside 8-wide blocks
assert train.energy_loss(flipped, t).item() < 1e-5 and (flipped - t).abs().mean().item() > 0.05
m = torch.nn.functional.avg_pool2d((t ** (1 / g)).flatten(0, 1), 8) + 1e-6
expected = (m ** g * (2 ** g - 1)).mean().item()
got = train.energy_loss(t * 2 ** g, t, fw=torch.ones(7)).item()  # equal frame weights: a plain mean
assert abs(got - expected) < 1e-4 * expected, (got, expected)
print(f"energy_loss: closed forms hold ({got:.6f} = {expected:.6f})")
PY
# Procedural rooms: deterministic per seed, loadable, a dataset of their own.
"$py" "$src/training/procedural_scenes.py" --out "$work/proc-a" --seeds 1-2 >/dev/null
"$py" "$src/training/procedural_scenes.py" --out "$work/proc-b" --seeds 1-2 >/dev/null
diff -r "$work/proc-a" "$work/proc-b" >/dev/null || { echo "FAIL: procedural scenes differ for one seed"; exit 1; }
room="$work/proc-a/proc-0001/scene.toml"
"$fovrt" dataset --out "$work/proc" --scenes "$room" --eval "" --no-uniform --noise-realisations 2 \
  --set camera.width=64 --set camera.height=64 --set run.frames=8 --set reference.spp=4 \
  --set reference.cache_dir="\"$work/cache\"" >/dev/null
grep -q '"name": "proc-0001_disc_left"' "$work/proc/manifest.json" || { echo "FAIL: no procedural sequence"; exit 1; }
if "$fovrt" dataset --out "$work/twice" --scenes "$room,$room" --eval "" --no-uniform --set camera.width=64 \
    --set camera.height=64 --set run.frames=8 --set reference.spp=4 --set reference.cache_dir="\"$work/cache\"" \
    2>"$work/twice.err"; then
  echo "FAIL: two scenes of one name accepted"; exit 1
fi
grep -q "named 'proc-0001' like scene" "$work/twice.err" || { cat "$work/twice.err"; exit 1; }
# ... before anything is rendered or written: the folder is not even made.
[ ! -e "$work/twice" ] || { echo "FAIL: the refused dataset left $work/twice behind"; exit 1; }
# --gaze-per-scene: each scene its own Lissajous path, drawn from its name: the same for both
# eyes and on a second run, different between scenes, within the documented ranges of the config's.
for run in 1 2; do
  "$fovrt" dataset --out "$work/gaze$run" --scenes "$room,box" --eval "" --no-uniform --gaze-per-scene \
    --set camera.width=32 --set camera.height=32 --set run.frames=2 --set reference.spp=2 \
    --set reference.cache_dir="\"$work/cache\"" >/dev/null
done
"$py" - "$work/gaze1/manifest.json" "$work/gaze2/manifest.json" <<'PY'
import json, sys
a, b = (json.load(open(p))["sequences"] for p in sys.argv[1:3])
gaze = {s["name"]: s["gaze"] for s in a}
assert gaze == {s["name"]: s["gaze"] for s in b}, "the per-scene gaze differs between runs"
room, box = gaze["proc-0001_disc_left"], gaze["box_disc_left"]
assert room == gaze["proc-0001_disc_right"] and box == gaze["box_disc_right"], "the eyes' gaze differs"
assert room != box, "two scenes drew one path"
for g in (room, box):  # the config's default path: amplitude (640, 360), frequency (0.4, 0.5) Hz
    for i, (amp, freq) in enumerate(zip((640, 360), (0.4, 0.5))):
        assert 0.5 * amp <= g["amplitude"][i] < amp and 0.6 * freq <= g["frequency_hz"][i] < 1.4 * freq, g
        assert 0 <= g["phase_deg"][i] < 360, g
print("gaze per scene:", room, box)
PY
if "$fovrt" dataset --out "$work/static" --scenes box --eval "" --gaze-per-scene --set 'gaze.source="static"' \
    2>"$work/static.err"; then
  echo "FAIL: --gaze-per-scene accepted a static gaze"; exit 1
fi
grep -q 'gaze.source = "static"' "$work/static.err" || { cat "$work/static.err"; exit 1; }
for spp in "" "--sample-count"; do
  out="$work/run$spp"
  "$py" "$src/training/train.py" --data "$work/data" --out "$out" --widths 4,6,8 $spp \
    --steps 40 --batch 2 --crop 32 --ramp 5 --log-every 5 --ckpt-every 20 --fixed-batch --threads 2 >"$out.log"
  first=$(awk -F, 'NR==2 {print $4}' "$out/train_log.csv")
  last=$(awk -F, 'END {print $4}' "$out/train_log.csv")
  echo "loss ${spp:-(7 inputs)}: first $first, last $last"
  awk -v a="$first" -v b="$last" 'BEGIN { exit !(b < a) }' || { echo "FAIL: loss did not decrease"; exit 1; }
  # Resume: 10 more steps continue from the checkpoint.
  "$py" "$src/training/train.py" --data "$work/data" --out "$out" --widths 4,6,8 $spp \
    --steps 50 --batch 2 --crop 32 --ramp 5 --log-every 5 --fixed-batch --threads 2 --resume >>"$out.log"
  grep -q "resumed at step 40" "$out.log" || { echo "FAIL: no resume"; exit 1; }
  "$py" "$src/training/check_export.py" "$out/rae.raew" "$work/data" "$out/check" --frames 3 --crop 64
  "$check" "$out/rae.raew" "$out/check/input.npy" "$out/check/output.npy"
  "$py" "$src/training/train.py" --data "$work/data" "$work/proc" --out "$out-ft" --widths 4,6,8 $spp --init "$out/rae.raew" \
    --frame-weight-floor 1 --temporal-weight 1 --stops 1,2,4 --schedule-offset 50 \
    --steps 2 --batch 2 --crop 32 --ramp 5 --log-every 2 --threads 2 >"$out-ft.log"
  grep -q "4 train / 0 eval sequences, 2 noise realisation(s) each" "$out-ft.log" ||
    { echo "FAIL: the two datasets were not read together"; exit 1; }
  [ -s "$out-ft/rae.raew" ] || { echo "FAIL: fine-tuning wrote no weights"; exit 1; }
done
# --device: a device this torch cannot use is refused in one line naming it, before anything is
# written (on a machine with CUDA the refusal cannot be provoked and is not checked).
if "$py" -c 'import sys, torch; sys.exit(0 if torch.cuda.is_available() else 1)'; then
  echo "CUDA present: the --device refusal is not checked"
else
  if "$py" "$src/training/train.py" --data "$work/data" --out "$work/cuda" --device cuda 2>"$work/cuda.err"; then
    echo "FAIL: --device cuda accepted without a CUDA device"; exit 1
  fi
  { [ "$(wc -l <"$work/cuda.err")" -eq 1 ] && grep -q -- "--device cuda: .*sees no CUDA device" "$work/cuda.err"; } ||
    { echo "FAIL: the refusal of --device cuda:"; cat "$work/cuda.err"; exit 1; }
  [ ! -e "$work/cuda" ] || { echo "FAIL: a refused --device left $work/cuda"; exit 1; }
fi
echo "rae training check: ok"
