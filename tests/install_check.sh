#!/usr/bin/env bash
# `cmake --install` into a temporary prefix: <prefix>/bin/fovrt runs (`fovrt info`) and reads the
# data it ships from <prefix>/share/fovrt, not from the source tree: a one-frame run of the
# built-in Cornell box names the installed scene file in its manifest, and still does after the
# prefix is moved.
# Usage: install_check.sh BUILD_DIR WORK_DIR
set -euo pipefail
build=$1; work=$2
rm -rf "$work"; mkdir -p "$work"; cd "$work"
cmake --install "$build" --prefix "$work/prefix" > install.txt
fail() { echo "FAIL: $1"; exit 1; }
[[ -x prefix/bin/fovrt ]] || fail "no executable at <prefix>/bin/fovrt"
prefix/bin/fovrt info > info.txt || fail "installed 'fovrt info' exited non-zero"
grep -q '^fovrt ' info.txt || fail "'fovrt info' prints no version line: $(head -n 3 info.txt)"

# run PREFIX: one small frame of the built-in Cornell box on the C++ reference denoisers.
run() {
  "$1/bin/fovrt" run --set scene.name=cornell --set camera.width=32 --set camera.height=18 \
    --set run.frames=1 --set denoise.device=cpu --set output.dir="run-$(basename "$1")" > /dev/null
  grep -q "\"$1/share/fovrt/scenes/cornell.toml\"" "run-$(basename "$1")/manifest.json" ||
    fail "the run from $1 did not read $1/share/fovrt/scenes/cornell.toml: $(grep -o '"[^"]*cornell.toml"' \
      "run-$(basename "$1")/manifest.json" | head -n 1)"
}
run "$work/prefix"
mv prefix moved
run "$work/moved"
echo "install: fovrt runs from the prefix with the prefix's data ($(wc -l < install.txt) install lines)"
