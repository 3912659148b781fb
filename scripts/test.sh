#!/usr/bin/env bash
# README command 2: install dependencies, build, run every test with ctest.
# --sanitize: the same dependencies, then the ASan+UBSan and TSan builds (scripts/sanitize.sh,
# docs/sanitizers.md) instead of the Release build.
set -euo pipefail
cd "$(dirname "$0")/.."
case ${1:-} in
  "") ;;
  --sanitize) bash scripts/install-deps.sh; exec bash scripts/sanitize.sh ;;
  *) echo "scripts/test.sh: unknown argument '$1' (expected none or --sanitize)" >&2; exit 2 ;;
esac
bash scripts/install-deps.sh
bash scripts/build.sh
ctest --test-dir build --output-on-failure -j"$(nproc)"
