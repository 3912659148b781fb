#!/usr/bin/env bash
# Checks a fovrt HTML report in a real browser: loads it offline in headless Chromium (every host
# name resolves to nothing, so a CDN reference cannot load), lets its scripts run, dumps the DOM
# and fails on
#   - a script error or console message (the report's check script records window errors and
#     console.error in <html data-errors>; Chromium logs every console message as CONSOLE),
#   - any image, SVG figure or full-frame canvas that did not draw (the check script marks each
#     data-drawn="1" or "0" once the page has loaded; every <img>/<svg>/<canvas> of the file must
#     come back "1"),
#   - a page whose check never ran (no data-report-check="ok" on <body>),
#   - a summary table wider than the page in a 1400-pixel-wide window (the page's script notes it
#     as an error).
# Usage: scripts/report-check.sh REPORT.html [DOM_OUT.html]
# Exit 0 and "report-check: ok (N figures drawn)" on success; 1 with one line per problem.
set -euo pipefail

if [[ $# -lt 1 ]]; then
  echo "usage: $0 REPORT.html [DOM_OUT.html]" >&2
  exit 2
fi
report=$1
[[ -f "$report" ]] || { echo "report-check: error: '$report' does not exist" >&2; exit 1; }

browser=""
for candidate in chromium chromium-browser google-chrome; do
  if command -v "$candidate" >/dev/null 2>&1; then browser=$candidate; break; fi
done
if [[ -z "$browser" ]]; then
  echo "report-check: error: chromium is not installed (bash scripts/install-deps.sh installs it)" >&2
  exit 1
fi

abs_report=$(cd "$(dirname "$report")" && pwd)/$(basename "$report")
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
dom=${2:-$tmp/dom.html}
# --no-sandbox: root in a container; a private profile keeps runs independent; the virtual time
# budget lets the load event and the check script run before the DOM is dumped.
if ! timeout 120 "$browser" --headless --no-sandbox --disable-gpu --user-data-dir="$tmp/profile" --window-size=1400,1000 \
    --host-resolver-rules="MAP * ~NOTFOUND" --virtual-time-budget=10000 \
    --enable-logging=stderr --v=0 --dump-dom "file://$abs_report" >"$dom" 2>"$tmp/stderr"; then
  echo "report-check: error: $browser failed on $report: $(tail -3 "$tmp/stderr")" >&2
  exit 1
fi

problems=0
fail() { echo "report-check: FAIL: $*" >&2; problems=$((problems + 1)); }
figures=$( (grep -o "<img\|<svg\|<canvas" "$abs_report" || true) | wc -l)
drawn=$( (grep -o 'data-drawn="1"' "$dom" || true) | wc -l)
undrawn=$( (grep -o 'data-drawn="0"' "$dom" || true) | wc -l)
[[ "$figures" -gt 0 ]] || fail "$report has no figures"
[[ "$undrawn" -eq 0 ]] || fail "$undrawn figure(s) did not draw: $(grep -o '<[a-z]*[^>]*data-drawn="0"' "$dom" | cut -c1-120 | head -3)"
[[ "$drawn" -eq "$figures" ]] || fail "$drawn of $figures figures drew"
if grep -q 'data-errors=' "$dom"; then fail "script errors: $(grep -o 'data-errors="[^"]*"' "$dom" | head -1 | cut -c1-300)"; fi
if grep -q ':CONSOLE' "$tmp/stderr"; then fail "console output: $(grep ':CONSOLE' "$tmp/stderr" | head -3)"; fi
grep -q 'data-report-check="ok"' "$dom" || fail "the page's check did not report ok ($(grep -o 'data-report-check="[a-z]*"' "$dom" || echo 'it never ran'))"
if [[ $problems -gt 0 ]]; then exit 1; fi
echo "report-check: ok ($drawn figures drawn, no console errors) $report"
