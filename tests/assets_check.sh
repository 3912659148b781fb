#!/usr/bin/env bash
# scripts/fetch-assets.sh --verify (never a download): the copies in ../shared match
# scripts/assets.manifest; a copy with one byte changed is named and fails; a folder with only
# some of the assets says which presets still run. curl and wget on the PATH are stand-ins that
# fail the test if the script calls them.
# Usage: assets_check.sh SOURCE_DIR WORK_DIR
set -euo pipefail
src=$1; work=$2
shared=$src/../shared
if [[ ! -d $shared/scenes || ! -d $shared/gaze ]]; then
  echo "skipped: ../shared is absent (nothing to verify)"
  exit 77
fi
rm -rf "$work"; mkdir -p "$work/bin"; cd "$work"
for tool in curl wget; do
  printf '#!/bin/sh\necho "FAIL: fetch-assets.sh --verify called %s" >&2\nexit 99\n' "$tool" > "$work/bin/$tool"
  chmod +x "$work/bin/$tool"
done
export PATH=$work/bin:$PATH
fetch=$src/scripts/fetch-assets.sh

# The folder the presets and tests read.
bash "$fetch" --verify

# A partial copy (the gaze recordings and the Cornell box) with one byte of a recording changed.
copy=$work/shared
mkdir -p "$copy/scenes"
cp -r "$shared/gaze" "$copy/"
cp -r "$shared/scenes/cornell-box" "$copy/scenes/"
chmod -R u+w "$copy"
rc=0; bash "$fetch" --verify --dir "$copy" > partial.txt 2>&1 || rc=$?
cat partial.txt
[[ $rc == 3 ]] || { echo "FAIL: an intact partial copy exited $rc, not 3 (files absent)"; exit 1; }
grep -q '^presets that run without them: .*quickstart' partial.txt ||
  { echo "FAIL: quickstart (built-in Cornell box) not listed as running without the assets"; exit 1; }
grep -q '^presets that stop .*thesis-foveated' partial.txt ||
  { echo "FAIL: thesis-foveated (Veach Ajar) not listed as needing the assets"; exit 1; }

printf '0' | dd of="$copy/gaze/vr-office-p14.csv" bs=1 seek=100 conv=notrunc status=none
rc=0; bash "$fetch" --verify --dir "$copy" > corrupt.txt 2>&1 || rc=$?
cat corrupt.txt
[[ $rc == 1 ]] || { echo "FAIL: a corrupted copy exited $rc, not 1"; exit 1; }
grep -q "^MISMATCH .*gaze/vr-office-p14.csv" corrupt.txt ||
  { echo "FAIL: the corrupted file is not named"; exit 1; }
[[ $(grep -c '^MISMATCH' corrupt.txt) == 1 ]] || { echo "FAIL: an intact file reported as a mismatch"; exit 1; }
echo "assets: ../shared verified; a changed byte and absent files reported"
