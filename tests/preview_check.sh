#!/usr/bin/env bash
# The desktop preview, for real, under Xvfb (run by ctest as preview_window): frames presented with
# zero Vulkan validation messages; the X server's own screenshot of the window equals the app's
# readback of its swapchain image and shows scene content in both eye halves; the pointer moves the
# gaze (the spp map's bright disc follows it); the overlay toggle changes pixels; a key press
# switches the denoiser (logged, histories reset); a recorded session replays headless to
# bit-identical spp maps and noisy inputs; a tracker latency makes the spp map's gaze (+) lag the
# pointer's true gaze (x), recorded frame by frame; no display is one clear line.
# Usage: preview_check.sh FOVRT IMAGE_PROBE WORK_DIR
set -uo pipefail
. "$(dirname "${BASH_SOURCE[0]}")/tools/skip.sh"
fovrt=$(realpath "$1"); probe=$(realpath "$2"); work=$(realpath -m "$3")
for tool in xvfb-run xdotool xwd xwdtopnm pnmtopng; do
  if ! command -v $tool >/dev/null; then
    skip_all "$tool is missing (scripts/install-deps.sh installs xvfb, xdotool, x11-apps, netpbm)"
  fi
done
if [[ -z "${FOVRT_IN_XVFB:-}" ]]; then
  rm -rf "$work"; mkdir -p "$work"
  # (-noreset: the server would reset, pointer and all, whenever its last client leaves.)
  # No display at all: one line pointing to `fovrt run`, non-zero exit.
  if env -u DISPLAY -u WAYLAND_DISPLAY "$fovrt" preview --frames 1 >/dev/null 2>"$work/nodisplay.txt"; then
    echo "FAIL: preview without a display exited 0"; exit 1
  fi
  if [[ $(grep -c . "$work/nodisplay.txt") -eq 1 ]] && grep -q "fovrt run" "$work/nodisplay.txt"; then
    echo "ok: no display: $(cat "$work/nodisplay.txt")"
  else
    echo "FAIL: no display: expected one line naming fovrt run, got: $(cat "$work/nodisplay.txt")"; exit 1
  fi
  exec env FOVRT_IN_XVFB=1 xvfb-run -a -s "-screen 0 1280x720x24 -noreset" bash "$0" "$@"
fi

cd "$work"
passed=0; failed=0
ok() { echo "ok: $1"; passed=$((passed + 1)); }
bad() { echo "FAIL: $1"; failed=$((failed + 1)); }
# Small eyes in a small window: 160×90 per eye, letterboxed 320×180 into each half of 640×360.
small=(--window 640x360 --no-panel --set camera.width=160 --set camera.height=90 --set scene.name=cornell
       --set run.seed=7)
# Every wait below ends on the event it checks (a file, a log line, a recorded pose, the X server's
# pixels), polled; the deadline only bounds a hang, so a loaded machine takes longer, never fails.
deadline_s=300
until_ok() {  # until_ok CMD...: polls CMD until it succeeds; fails after deadline_s seconds
  local end=$((SECONDS + deadline_s))
  until "$@"; do ((SECONDS < end)) || return 1; sleep 0.1; done
}
alive() { kill -0 "$1" 2>/dev/null; }
wait_for() {  # wait_for FILE PID: until FILE exists (0) or PID is gone (1)
  until_ok eval "[[ -s $1 ]] || ! alive $2" && [[ -s $1 ]]
}
preview_window() { timeout "$deadline_s" xdotool search --sync --name "fovrt preview" | head -1; }
screenshot_root() { xwd -root -silent | xwdtopnm 2>/dev/null | pnmtopng > "$1"; }

# 1. Frames presented, validation clean; the X server's pixels = the app's swapchain readback.
# (--linger keeps the last frame up until Escape, once the X server shows it.)
FOVRT_VK_VALIDATION=1 "$fovrt" preview "${small[@]}" --set gaze.source=static --frames 5 \
  --screenshot app.png --linger $deadline_s 2>err1.txt &
pid=$!
if wait_for app.png $pid; then
  shown() { screenshot_root root.png; [[ $("$probe" diff app.png root.png) == "max=0 "* ]] || ! alive $pid; }
  until_ok shown
  if alive $pid; then
    win=$(preview_window)
    timeout 30 xdotool windowfocus --sync "$win" key Escape || kill $pid
  fi
  wait $pid; rc=$?
  [[ $rc -eq 0 ]] && ok "5 frames presented, exit 0" || bad "exit $rc: $(tail -3 err1.txt)"
  if grep -q "vulkan validation" err1.txt; then bad "validation messages: $(grep -m3 'vulkan validation' err1.txt)"
  elif grep -q "0 Vulkan validation errors, 0 warnings" err1.txt; then ok "zero Vulkan validation messages"
  else bad "validation was not on: $(tail -2 err1.txt)"; fi
  diff=$("$probe" diff app.png root.png)
  [[ $diff == "max=0 "* ]] && ok "X screenshot equals the swapchain readback ($diff)" || bad "screenshot differs: $diff"
  for half in "0 90 320 270" "320 90 640 270"; do
    std=$("$probe" stats app.png $half | sed 's/.*std=//')
    awk -v s="$std" 'BEGIN { exit !(s > 10) }' && ok "eye half ($half) shows scene content (luma std $std)" \
      || bad "eye half ($half) looks empty (luma std $std)"
  done
else
  wait $pid; bad "no screenshot: $(tail -3 err1.txt)"
fi

# 2. The pointer is the gaze: the spp map's bright disc follows it.
for pos in "160 180" "110 200"; do
  set -- $pos
  # (the first fake motion after the server starts can be lost: move until the pointer is there)
  pointer_at() { xdotool mousemove "$1" "$2"; [[ $(xdotool getmouselocation) == "x:$1 y:$2 "* ]]; }
  until_ok pointer_at "$1" "$2" || bad "the pointer did not reach ($1, $2)"
  if "$fovrt" preview "${small[@]}" --set gaze.source=mouse --view spp --no-overlay --frames 3 \
       --screenshot spp.png 2>err2.txt; then
    c=$("$probe" centroid spp.png 0 90 320 270)
    if awk -v c="$c" -v x="$1" -v y="$2" 'BEGIN { split(c, p, " "); exit !((p[1]-x)^2 + (p[2]-y)^2 < 36) }'; then
      ok "pointer at ($1, $2): spp disc centred at ($c)"
    else bad "pointer at ($1, $2): spp disc centred at ($c)"; fi
  else bad "mouse gaze run failed: $(tail -2 err2.txt)"; fi
done

# 3. The overlay toggle changes a few pixels and nothing else.
"$fovrt" preview "${small[@]}" --set gaze.source=static --frames 2 --screenshot on.png 2>/dev/null
"$fovrt" preview "${small[@]}" --set gaze.source=static --frames 2 --screenshot off.png --no-overlay 2>/dev/null
d=$("$probe" diff on.png off.png)
frac=${d#*differing=}
awk -v f="$frac" 'BEGIN { exit !(f > 0 && f < 0.05) }' && ok "overlay toggle changes $frac of the pixels" \
  || bad "overlay toggle: $d"

# 4. A key switches the denoiser (logged, histories reset); Escape closes the window mid-run
#    with a clean exit and a complete recording.
"$fovrt" preview "${small[@]}" --set gaze.source=static --frames 100000 --record closed.jsonl \
  --stats stats.jsonl --capture-dir captures 2>err4.txt &
pid=$!
head_of() { grep -o '"head":{"position":\[[^]]*\]' closed.jsonl | sed -n "$1"; }
until_ok eval '[[ $(grep -c . stats.jsonl 2>/dev/null) -ge 2 ]]'
win=$(preview_window)
timeout 30 xdotool windowfocus --sync "$win" key 4
until_ok grep -q "denoiser svgf -> two-history" err4.txt
# A frame of the new denoiser has been shown: its passes are in the stats stream.
until_ok eval 'tail -1 stats.jsonl | grep -q blend'
timeout 30 xdotool windowfocus --sync "$win" key F12
until_ok grep -q "saved frame" err4.txt
# Fly forward (leaves the camera path) with W held until a recorded frame has the moved head.
first_head=$(head_of 1p)
timeout 30 xdotool windowfocus --sync "$win" keydown w
until_ok eval '[[ -n $(head_of \$p) && $(head_of \$p) != "$first_head" ]]'
timeout 30 xdotool windowfocus --sync "$win" keyup w
timeout 30 xdotool windowfocus --sync "$win" key Escape || kill $pid
wait $pid; rc=$?
[[ $rc -eq 0 ]] && ok "window closed mid-run: exit 0" || bad "closed mid-run: exit $rc: $(tail -2 err4.txt)"
grep -q "denoiser svgf -> two-history (histories reset)" err4.txt && ok "key 4: $(grep -m1 'histories reset' err4.txt)" \
  || bad "denoiser switch not logged: $(tail -3 err4.txt)"
grep -q '"reproject' stats.jsonl && tail -1 stats.jsonl | grep -q 'blend' && ok "stats stream shows the new denoiser's passes" \
  || bad "passes did not change: $(tail -1 stats.jsonl)"
# cornell's camera path is static: the head stays put until W flies it forward (-Z).
heads=$(grep -o '"head":{"position":\[[^]]*\]' closed.jsonl | sort -u | wc -l)
first=$(head -2 closed.jsonl | tail -1 | grep -o '"head":{"position":\[[^]]*\]')
last=$(tail -1 closed.jsonl | grep -o '"head":{"position":\[[^]]*\]')
[[ $heads -ge 2 && "$first" != "$last" ]] && ok "W flies the camera: head $first -> $last" \
  || bad "W did not move the head ($heads distinct positions; $first -> $last)"
shots=$(ls captures/*_window.png captures/*_left.exr captures/*_right.exr 2>/dev/null | wc -l)
[[ $shots -eq 3 ]] && ok "F12 saved the window PNG and both eyes' FrameInputs + output EXRs" \
  || bad "F12 saved $shots files: $(ls captures 2>&1)"
if "$fovrt" run --replay closed.jsonl --set output.dir=closed-replay --set output.write_png=false 2>err4r.txt; then
  ok "the recording of a closed session replays ($(ls closed-replay/inputs | wc -l) EXRs)"
else bad "recording of a closed session: $(tail -2 err4r.txt)"; fi

# 5. Record in the preview, replay headless: identical spp maps and noisy inputs.
"$fovrt" preview "${small[@]}" --set gaze.source=lissajous --frames 4 --record rec.jsonl --write-inputs \
  --set output.dir=live 2>err5.txt || bad "record run failed: $(tail -2 err5.txt)"
if "$fovrt" run --replay rec.jsonl --set output.dir=replay --set output.write_png=false 2>err5r.txt; then
  n=0; same=0
  for f in live/inputs/*.exr; do
    n=$((n + 1))
    "$probe" exr-equal "$f" "replay/inputs/$(basename "$f")" >/dev/null && same=$((same + 1)) \
      || echo "  $(basename "$f"): $("$probe" exr-equal "$f" "replay/inputs/$(basename "$f")")"
  done
  [[ $n -eq 8 && $same -eq 8 ]] && ok "replay: $same of $n FrameInputs + spp EXRs bit-identical" \
    || bad "replay: $same of $n EXRs identical"
else bad "replay failed: $(tail -2 err5r.txt)"; fi

# 6. A view the denoiser does not have: one line naming it and the views there are.
if "$fovrt" preview "${small[@]}" --frames 1 --view alpha >/dev/null 2>err6.txt; then bad "--view alpha with svgf exited 0"
elif [[ $(grep -c . err6.txt) -eq 1 ]] && grep -q "view alpha: not a view of denoiser svgf" err6.txt; then
  ok "bad view: $(cat err6.txt)"
else bad "bad view: $(cat err6.txt)"; fi

# 7. A tracker latency: the spp map follows the pointer `latency` late. The pointer jumps from A to
#    B; the recording's frames carry true gaze B with tracked gaze A until the latency has passed,
#    then B; F12 in between captures the overlay's x (true gaze) at B and + (tracked gaze) at A.
lag_ms=6000; ax=100; ay=150; bx=220; by=200
until_ok pointer_at $ax $ay || bad "the pointer did not reach ($ax, $ay)"
"$fovrt" preview "${small[@]}" --set gaze.source=mouse --set gaze.tracker_latency_ms=$lag_ms --frames 100000 \
  --record lag.jsonl --stats lag-stats.jsonl --capture-dir lagcap 2>err7.txt &
pid=$!
# lag_frames: one line per recorded frame, "frame true tracked" (directions rounded to 1e-4).
lag_frames() {
  python3 -c "import json, sys
for l in list(open('lag.jsonl'))[1:]:
    f = json.loads(l); d = lambda g: ','.join('%.4f' % v for v in g['direction'])
    print(f['frame'], d(f['gaze']), d(f['tracked_gaze']) if 'tracked_gaze' in f else '-')" 2>/dev/null
}
until_ok eval '[[ $(lag_frames | wc -l) -ge 2 ]] || ! alive $pid'
gaze_a=$(lag_frames | head -1 | cut -d' ' -f2)
until_ok pointer_at $bx $by || bad "the pointer did not reach ($bx, $by)"
# The first frame with the moved true gaze, then until the window has presented it.
moved_frame() { lag_frames | awk -v a="$gaze_a" '$2 != a { print $1; exit }'; }
until_ok eval '[[ -n $(moved_frame) ]] || ! alive $pid'
fb=$(moved_frame)
until_ok eval '[[ $(tail -1 lag-stats.jsonl 2>/dev/null | grep -o "\"frame\":[0-9]*" | cut -d: -f2) -gt ${fb:-0} ]] || ! alive $pid'
win=$(preview_window)
timeout 30 xdotool windowfocus --sync "$win" key F12
until_ok eval 'grep -q "saved frame" err7.txt || ! alive $pid'
# Until the tracked gaze has caught up with the pointer.
until_ok eval '[[ -n $(lag_frames | awk -v a="$gaze_a" "\$2 != a && \$2 == \$3") ]] || ! alive $pid'
timeout 30 xdotool windowfocus --sync "$win" key Escape || kill $pid
wait $pid; rc=$?
[[ $rc -eq 0 ]] && ok "tracker latency: session exit 0" || bad "tracker latency: exit $rc: $(tail -2 err7.txt)"
summary=$(lag_frames | awk -v a="$gaze_a" '
  { n++; if ($3 == "-") untracked++
    state = ($2 == a && $3 == a) ? "A" : ($2 != a && $3 == a) ? "lag" : ($2 == $3) ? "B" : "other"
    count[state]++; if (state != last) order = order (order == "" ? "" : ">") state; last = state }
  END { printf "%d frames: %s (A %d, lag %d, B %d, other %d, untracked %d)", n, order, count["A"], count["lag"],
        count["B"], count["other"], untracked }')
[[ $summary == *": A>lag>B ("*"other 0, untracked 0)" ]] \
  && ok "tracker latency $lag_ms ms: true and tracked gaze per recorded frame: $summary" \
  || bad "tracker latency: recorded frames $summary"
shot=$(ls lagcap/*_window.png 2>/dev/null | head -1)
if [[ -n $shot ]]; then
  number=$(basename "$shot" | sed 's/^frame0*\([0-9]*\)_window.png/\1/')
  shown=$(lag_frames | awk -v f=$((number - 1)) -v a="$gaze_a" '$1 == f { print ($2 != a && $3 == a) ? "lag" : "not lagging" }')
  x=$("$probe" colour "$shot" 30D0FF 0 0 320 360)
  plus=$("$probe" colour "$shot" 20FF40 0 0 320 360)
  near() { awk -v c="$1" -v x="$2" -v y="$3" 'BEGIN { split(c, p, " "); exit !((p[1]-x)^2 + (p[2]-y)^2 < 4) }'; }
  if [[ $shown == lag ]] && near "$x" $bx $by && near "$plus" $ax $ay; then
    ok "F12 during the lag (frame $number): true gaze x at ($x) = pointer, tracked + at ($plus) = where it was"
  else bad "F12 capture of frame $number ($shown): x at ($x), + at ($plus); pointer ($bx, $by), before ($ax, $ay)"; fi
else bad "tracker latency: no F12 capture: $(tail -2 err7.txt)"; fi

echo "preview_check: $passed passed, $failed failed"
finish $failed
