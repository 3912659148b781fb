#!/usr/bin/env bash
# README command 1: install dependencies, build, run the default headless job on a built-in scene.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
./build/src/app/fovrt run
