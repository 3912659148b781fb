#!/usr/bin/env bash
# Headset benchmark: `fovrt xr` against the test OpenXR runtime (tests/xr_runtime, built with the
# tests) at its recommended size (320×240 per eye unless FOVRT_TEST_XR_SIZE says otherwise), with
# Debian's core validation layer on. Per scene × denoiser: fovrt's own end-of-session summary, the
# mean frame-time split from <output.dir>/xr/frames.jsonl, and the layer's error count.
# Usage: scripts/bench-xr.sh [BUILD_DIR] [FRAMES]
set -euo pipefail
build=${1:-build}
frames=${2:-60}
fovrt=$build/src/app/fovrt
envsh=$build/tests/xr_runtime/xr_test_env.sh
[[ -x $fovrt ]] || { echo "$0: error: $fovrt is not built (bash scripts/build.sh)" >&2; exit 1; }
[[ -f $envsh ]] || { echo "$0: error: $envsh is missing (build with the tests: bash scripts/test.sh)" >&2; exit 1; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
# shellcheck disable=SC1090
. "$envsh" "$out/core-validation.txt"
"$fovrt" info | sed -n 's/^machine  */machine: /p'   # CPU model, CPUs, vector extensions
echo "runtime: fovrt test runtime, ${FOVRT_TEST_XR_SIZE:-320x240} per eye, ${FOVRT_TEST_XR_HZ:-90} Hz"
for mode in sync async; do
 for scene in cornell veach-ajar; do
  for denoiser in svgf two-history; do
    [[ $mode == async && $scene != cornell ]] && continue
    rm -rf "$out/run"
    line=$("$fovrt" xr --frames "$frames" --set scene.name="$scene" --set "denoise.denoisers=[\"$denoiser\"]" \
      --set output.dir="$out/run" $([[ $mode == async ]] && echo --async) 2>&1 | grep 'frames in' || true)
    split=$(python3 - "$out/run/xr/frames.jsonl" <<'PY'
import json, sys
rows = [json.loads(l)["ms"] for l in open(sys.argv[1])][10:]  # after the first 10 frames (pipelines, caches)
keys = ["wait_begin_frame", "spp", "trace", "denoise", "write_eyes", "end_frame"]
m = json.load(open(sys.argv[1].replace("frames.jsonl", "manifest.json")))
rate = m["frames"]["ended"] / m["timing"]["seconds"]
print("mean ms over frames 11+: " + ", ".join(f"{k} {sum(r[k] for r in rows) / len(rows):.1f}" for k in keys)
      + f"; {rate:.1f} xrEndFrame/s, {m['frames']['with_layer']} of {m['frames']['ended']} with a layer")
PY
)
    printf '%-6s %-10s %-12s %s\n%-30s %s\n' "$mode" "$scene" "$denoiser" "${line#fovrt xr: }" "" "$split"
  done
 done
done
echo "core validation errors: $(fovrt_xr_validation_errors)"
