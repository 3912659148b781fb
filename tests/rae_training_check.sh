#!/usr/bin/env bash
# CI smoke test of the RAE's training code (training/): a tiny `fovrt dataset` (cornell, 64×64,
# 8 frames, 16-spp references), 40 steps of train.py on one fixed batch (small widths, 32² crops)
# must lower the loss, and the exported .raew must reproduce PyTorch's outputs in the C++
# reference (tests/tools/rae_check, 1e-4 relative) for both input sets (with and without the
# sample-count channel). Fine-tuning from the export (--init) with the committed weights' options
# runs on a dataset with a second noise realisation, every sequence a camera stop that takes it.
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
  "$py" "$src/training/train.py" --data "$work/data" --out "$out-ft" --widths 4,6,8 $spp --init "$out/rae.raew" \
    --frame-weight-floor 1 --temporal-weight 1 --stops 1,2,4 --schedule-offset 50 \
    --steps 2 --batch 2 --crop 32 --ramp 5 --log-every 2 --threads 2 >"$out-ft.log"
  grep -q "2 noise realisation(s) each" "$out-ft.log" || { echo "FAIL: no extra noise realisation"; exit 1; }
  [ -s "$out-ft/rae.raew" ] || { echo "FAIL: fine-tuning wrote no weights"; exit 1; }
done
echo "rae training check: ok"
