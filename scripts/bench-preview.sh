#!/usr/bin/env bash
# Live preview benchmark: frames per second and gaze-to-photon latency of `fovrt preview` under
# Xvfb, per scene × per-eye resolution × denoiser. Each line is the preview's own end-of-session
# summary (src/live/live_stats.h) after FRAMES frames with Lissajous gaze.
# Usage: scripts/bench-preview.sh [BUILD_DIR] [FRAMES]
set -euo pipefail
build=${1:-build}
frames=${2:-60}
fovrt=$build/src/app/fovrt
[[ -x $fovrt ]] || { echo "$0: error: $fovrt is not built (bash scripts/build.sh)" >&2; exit 1; }
command -v xvfb-run >/dev/null || { echo "$0: error: xvfb-run is missing (scripts/install-deps.sh)" >&2; exit 1; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
"$fovrt" info | sed -n 's/^machine  */machine: /p'   # CPU model, CPUs, vector extensions
for scene in cornell veach-ajar; do
  for size in 320x180 640x360; do
    for denoiser in svgf two-history; do
      w=${size%x*}; h=${size#*x}
      line=$(xvfb-run -a -s "-screen 0 1920x1080x24" "$fovrt" preview --frames "$frames" \
        --set scene.name="$scene" --set camera.width="$w" --set camera.height="$h" \
        --set "denoise.denoisers=[\"$denoiser\"]" --set output.dir="$out" 2>&1 | grep 'frames in' || true)
      printf '%-10s %-8s %-12s %s\n' "$scene" "$size" "$denoiser" "${line#fovrt preview: }"
    done
  done
done
