#!/usr/bin/env bash
# Renders a fovrt HTML report to a PNG with headless Chromium (for CI artefacts and docs).
# Usage: scripts/report-screenshot.sh REPORT.html OUT.png [WIDTH HEIGHT]
# Exits 0 with a "skipped" message when Chromium is not installed (it is not a build dependency).
set -euo pipefail

if [[ $# -lt 2 ]]; then
  echo "usage: $0 REPORT.html OUT.png [WIDTH HEIGHT]" >&2
  exit 2
fi
report=$1
out=$2
width=${3:-1400}
height=${4:-4000}

if [[ ! -f "$report" ]]; then
  echo "$0: error: report '$report' does not exist" >&2
  exit 1
fi

browser=""
for candidate in chromium chromium-browser google-chrome; do
  if command -v "$candidate" >/dev/null 2>&1; then
    browser=$candidate
    break
  fi
done
if [[ -z "$browser" ]]; then
  echo "skipped: chromium absent (apt-get install chromium)"
  exit 0
fi

abs_report=$(cd "$(dirname "$report")" && pwd)/$(basename "$report")
mkdir -p "$(dirname "$out")"
abs_out=$(cd "$(dirname "$out")" && pwd)/$(basename "$out")
# A private profile dir keeps runs independent; --no-sandbox is needed as root in containers.
profile=$(mktemp -d)
trap 'rm -rf "$profile"' EXIT
"$browser" --headless --disable-gpu --no-sandbox --hide-scrollbars --user-data-dir="$profile" \
  --window-size="${width},${height}" --screenshot="$abs_out" "file://$abs_report" >/dev/null 2>&1
if [[ ! -s "$abs_out" ]]; then
  echo "$0: error: $browser wrote no screenshot to $abs_out" >&2
  exit 1
fi
echo "wrote $abs_out"
