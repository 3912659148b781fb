#!/usr/bin/env bash
# The README's first-command output cannot go stale: runs what scripts/quickstart.sh runs,
# `fovrt experiment presets/quickstart.toml`, in a fresh folder (output and reference cache there,
# via the preset's own relative paths), and compares its stdout line for line with the block
# between the README's `quickstart-output` markers. The numbers are deterministic (same config and
# seeds give the same values), so nothing is masked. When the table changes on purpose (a new
# column, a new metric), the failure prints the new output to paste into the README.
# Usage: readme_quickstart_check.sh FOVRT SOURCE_DIR WORK_DIR
set -euo pipefail
fovrt=$1; src=$2; work=$3
readme=$src/README.md
rm -rf "$work"; mkdir -p "$work"; cd "$work"
# The block: the fenced lines between the markers, without the fences.
awk '/<!-- quickstart-output:begin -->/{on=1; next} /<!-- quickstart-output:end -->/{on=0} on' "$readme" |
  sed '/^```/d' > expected.txt
[[ -s expected.txt ]] || { echo "FAIL: $readme has no quickstart-output block"; exit 1; }
# As a new user runs it from the repository root: out/quickstart and cache/reference, relative.
mkdir -p presets && cp "$src/presets/quickstart.toml" presets/
"$fovrt" experiment presets/quickstart.toml > actual.txt
if ! diff -u expected.txt actual.txt; then
  echo
  echo "FAIL: the output of 'fovrt experiment presets/quickstart.toml' differs from README.md's block"
  echo "(diff above: - README, + now). If the change is intended, update the README block"
  echo "between <!-- quickstart-output:begin --> and <!-- quickstart-output:end --> to:"
  echo '```'
  cat actual.txt
  echo '```'
  exit 1
fi
echo "README quickstart output: identical ($(wc -l < actual.txt) lines)"
