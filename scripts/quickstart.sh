#!/usr/bin/env bash
# README command 1: install dependencies, build, and run the quickstart experiment on the built-in
# Cornell box (presets/quickstart.toml): SVGF vs two-history SVGF over 3 seeds, ending in the
# foveal/peripheral error table with 95 % intervals and the path of its HTML report. fovrt is
# installed to /usr/local (bin/fovrt on the PATH, its scenes and weights in share/fovrt).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
cmake --install build > /dev/null
fovrt experiment presets/quickstart.toml
