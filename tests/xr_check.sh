#!/usr/bin/env bash
# `fovrt xr` against fovrt's test OpenXR runtime (tests/xr_runtime), loaded by Debian's real loader
# through XR_RUNTIME_JSON, with Debian's core validation layer on (run by ctest as xr_session):
# the exact session state sequence and N frames ended with a clean exit; swapchains at the
# recommended size; the eyes IPD apart and moving; each eye's image as the runtime read it back
# equals fovrt's own output for that eye; eye gaze on: the spp map's disc sits where the scripted
# gaze looks; gaze off: the fallback is used and reported; Ctrl-C and a runtime-initiated exit end
# cleanly; session and instance loss, and every bad input, give one line and a non-zero exit with
# no recording left behind; a recorded session replays headless to identical spp maps and noisy
# inputs and to the images the headset was sent; --mirror shows the headset's frames in a window
# under Xvfb; a tracker latency records each frame's true and tracked gaze, and the replay renders
# with both. Zero core validation errors.
# Usage: xr_check.sh FOVRT IMAGE_PROBE XR_TEST_ENV_SH WORK_DIR
set -uo pipefail
. "$(dirname "${BASH_SOURCE[0]}")/tools/skip.sh"
fovrt=$(realpath "$1"); probe=$(realpath "$2"); envsh=$(realpath "$3"); work=$(realpath -m "$4")
for tool in python3; do
  command -v $tool >/dev/null || skip_all "$tool is missing (scripts/install-deps.sh installs it)"
done
if ! vulkaninfo --summary >/dev/null 2>&1; then skip_all "no Vulkan device"; fi
rm -rf "$work"; mkdir -p "$work"; cd "$work"
# shellcheck disable=SC1090
. "$envsh" "$work/core-validation.txt"
[[ -n "${XR_ENABLE_API_LAYERS:-}" ]] || { echo "FAIL: the core validation layer is not set up"; exit 1; }
passed=0; failed=0
ok() { echo "ok: $1"; passed=$((passed + 1)); }
bad() { echo "FAIL: $1"; failed=$((failed + 1)); }
json() { python3 -c "import json,sys; d=json.load(open(sys.argv[1])); print(eval(sys.argv[2]))" "$@"; }
small=(--set scene.name=cornell --set run.seed=7 --set denoise.denoisers='["svgf"]')
export FOVRT_TEST_XR_SIZE=160x120

# 1. A clean session: 4 frames rendered and submitted, exit through xrRequestExitSession.
FOVRT_VK_VALIDATION=1 FOVRT_TEST_XR_DUMP=rt1 "$fovrt" xr "${small[@]}" --set output.dir=s1 --frames 4 --write-frames \
  --write-inputs --record rec.jsonl >out1.txt 2>err1.txt
rc=$?
[[ $rc -eq 0 ]] && ok "4 frames, exit 0" || bad "exit $rc: $(tail -3 err1.txt)"
grep -q "fovrt xr: 0 Vulkan validation errors, 0 warnings" err1.txt && ok "zero Vulkan validation messages" \
  || bad "Vulkan validation: $(grep -m3 -i 'vulkan validation' err1.txt)"
expected="IDLE READY SYNCHRONIZED VISIBLE FOCUSED VISIBLE SYNCHRONIZED STOPPING IDLE EXITING"
runtime_states=$(sed 's/^XR_SESSION_STATE_//' rt1/states.txt 2>/dev/null | tr '\n' ' ' | sed 's/ $//')
app_states=$(json s1/xr/manifest.json "' '.join(d['session_states'])" 2>/dev/null)
[[ "$runtime_states" == "$expected" ]] && ok "runtime's states: $runtime_states" \
  || bad "runtime's states: '$runtime_states' (expected '$expected')"
[[ "$app_states" == "$expected" ]] && ok "fovrt saw the same states" || bad "fovrt's states: '$app_states'"
python3 - s1/xr/manifest.json rt1/frames.jsonl s1/xr/frames.jsonl <<'PY' && ok "frames, sizes, poses: $(cat summary1.txt)" || bad "frames, sizes, poses: $(cat summary1.txt)"
import json, math, sys
m = json.load(open(sys.argv[1]))
rt = [json.loads(l) for l in open(sys.argv[2])]
app = [json.loads(l) for l in open(sys.argv[3])]
problems = []
f = m["frames"]
if f["rendered"] != 4 or f["with_layer"] != 4: problems.append(f"frames {f}")
if f["ended"] != len(rt): problems.append(f"fovrt ended {f['ended']} frames, the runtime saw {len(rt)}")
sc = m["runtime"]["swapchain"]
if (sc["width"], sc["height"]) != (160, 120): problems.append(f"swapchain {sc}")
layered = [r for r in rt if r["layerCount"] == 1]
if len(layered) != 4: problems.append(f"{len(layered)} frames with a layer")
for r in layered:
    if any(v["swapchainSize"] != [160, 120] or v["imageRect"] != [0, 0, 160, 120] for v in r["views"]):
        problems.append("a view is not the whole recommended-size swapchain")
    a, b = (v["pose"]["position"] for v in r["views"])
    ipd = math.dist(a, b)
    if abs(ipd - 0.063) > 1e-4: problems.append(f"eyes {ipd:.5f} m apart")
    fov = r["views"][0]["fov"]
    if abs(fov[0] + fov[1]) < 1e-3: problems.append(f"left FOV symmetric {fov}")
moved = math.dist(layered[0]["views"][0]["pose"]["position"], layered[-1]["views"][0]["pose"]["position"])
if moved < 1e-4: problems.append("the head did not move")
if [a["display_time_ns"] for a in app] != [r["displayTime"] for r in layered]:
    problems.append("fovrt's frames are not the runtime's layered frames")
open("summary1.txt", "w").write("; ".join(problems) if problems else
    f"{len(rt)} frames ended, 4 with a layer, 160x120 per eye, eyes 0.0630 m apart, head moved {moved*1000:.1f} mm")
sys.exit(1 if problems else 0)
PY
# Each eye's released image, read back by the runtime, equals fovrt's own output byte for byte
# (--write-frames writes the bytes the device composed for the swapchain image, so this checks the
# copy into the image, its layout and byte order, the release and the frame it belongs to).
same=0; n=0; worst=""
while read -r frame disp; do
  ppmframe=$(python3 -c "import json,sys
for l in open('rt1/frames.jsonl'):
    r=json.loads(l)
    if r['displayTime']==int(sys.argv[1]): print('%05d' % r['frame'])" "$disp")
  for eye in 0 1; do
    n=$((n + 1))
    png=s1/xr/frames/$(printf 'f%05d' "$frame")_$([[ $eye == 0 ]] && echo left || echo right).png
    d=$("$probe" diff "rt1/frame_${ppmframe}_eye${eye}.ppm" "$png" 2>&1)
    [[ $d == "max=0 "* ]] && same=$((same + 1)) || worst="$worst [$frame/$eye: $d]"
  done
done < <(python3 -c "import json
for l in open('s1/xr/frames.jsonl'):
    r=json.loads(l); print(r['frame'], r['display_time_ns'])")
[[ $n -eq 8 && $same -eq 8 ]] && ok "the runtime's read-back of all 8 eye images equals fovrt's output, byte for byte" \
  || bad "read-back vs fovrt output: $same of $n equal;$worst"
# Gaze off (the runtime supports the extension, no tracker delivers): the fallback, reported.
g=$(json s1/xr/manifest.json "d['gaze_source_frames']")
[[ "$g" == "{'lissajous': 4}" ]] && ok "gaze off: fallback frames $g" || bad "gaze off: $g"
[[ $(grep -c "eye gaze action is not active" err1.txt) -eq 1 ]] && ok "gaze off: one warning line" \
  || bad "gaze off warning: $(grep -c 'not active' err1.txt) lines"

# 1b. --async: the live loop renders on its own thread; every display slot submits the newest
#     finished frame with the poses it was traced from, and its read-back equals fovrt's output.
FOVRT_TEST_XR_DUMP=rta "$fovrt" xr "${small[@]}" --set output.dir=sa --frames 3 --async --write-frames 2>erra.txt
rc=$?
if [[ $rc -eq 0 ]] && python3 - rta/frames.jsonl sa/xr/frames.jsonl sa/xr/frames "$probe" <<'PY' > summarya.txt; then
import json, math, subprocess, sys
rt = [json.loads(l) for l in open(sys.argv[1])]
app = [json.loads(l) for l in open(sys.argv[2])]
problems = []
by_time = {a["display_time_ns"]: a for a in app}
current = None
layered = 0
for r in rt:
    if r["displayTime"] in by_time:
        current = by_time[r["displayTime"]]
        for eye, name in ((0, "left"), (1, "right")):
            d = subprocess.run([sys.argv[4], "diff", f"rta/{r['views'][eye]['ppm']}",
                                f"{sys.argv[3]}/f{current['frame']:05d}_{name}.png"], capture_output=True, text=True).stdout
            if not d.startswith("max=0 "): problems.append(f"frame {current['frame']} eye {eye}: {d.strip()}")
    if r["layerCount"] == 0: continue
    layered += 1
    if current is None: problems.append(f"runtime frame {r['frame']} has a layer before any fovrt frame"); continue
    for eye in (0, 1):
        if math.dist(r["views"][eye]["pose"]["position"], current["eyes"][eye]["local"]["position"]) > 1e-6:
            problems.append(f"runtime frame {r['frame']} eye {eye}: pose is not fovrt frame {current['frame']}'s")
if len(app) != 3: problems.append(f"{len(app)} frames submitted")
print("; ".join(problems[:4]) if problems else f"{len(rt)} frames ended, {layered} with a layer, 3 fovrt frames, each layer with its frame's poses, read-backs equal fovrt's output byte for byte")
sys.exit(1 if problems else 0)
PY
  ok "--async: $(cat summarya.txt)"
else bad "--async: exit $rc: $(cat summarya.txt 2>/dev/null) $(tail -2 erra.txt)"; fi

# 2. Record -> replay headless: identical spp maps and noisy inputs; and the headless denoised
#    PNGs (the C++ display transform) are what the headset was sent (the device's), up to the
#    transform's documented 1 LSB in a rare byte (shaders/common/display_transform.glsl).
if "$fovrt" run --replay rec.jsonl --set output.dir=replay 2>err2.txt; then
  n=0; same=0
  for f in s1/inputs/*.exr; do
    n=$((n + 1))
    "$probe" exr-equal "$f" "replay/inputs/$(basename "$f")" >/dev/null && same=$((same + 1))
  done
  [[ $n -eq 8 && $same -eq 8 ]] && ok "replay: $same of $n FrameInputs + spp EXRs bit-identical" \
    || bad "replay: $same of $n identical"
  n=0; close=0; worst=""
  for f in s1/xr/frames/*.png; do
    n=$((n + 1))
    d=$("$probe" diff "$f" "replay/denoised/svgf/$(basename "$f")" 2>&1)
    [[ $d =~ ^max=([0-9]+)\ differing=([0-9.]+) ]] && ((BASH_REMATCH[1] <= 1)) \
      && python3 -c "import sys; sys.exit(float(sys.argv[1]) > 1e-3)" "${BASH_REMATCH[2]}" \
      && close=$((close + 1)) || worst="$worst [$(basename "$f"): $d]"
  done
  [[ $n -eq 8 && $close -eq 8 ]] && ok "replay: the headset's 8 eye images are the headless run's denoised PNGs (at most 1 LSB in 0.1 % of pixels)" \
    || bad "replay vs headset images: $close of $n within 1 LSB;$worst"
else bad "replay failed: $(tail -2 err2.txt)"; fi

# 3. Eye gaze on: the spp map's disc follows the scripted gaze (two fixed directions).
for g in "0.25,-0.15" "-0.3,0.2"; do
  rm -rf rt3 s3
  FOVRT_TEST_XR_GAZE=on FOVRT_TEST_XR_GAZE_FIXED=$g FOVRT_TEST_XR_DUMP=rt3 "$fovrt" xr "${small[@]}" \
    --set output.dir=s3 --frames 3 --view spp 2>err3.txt || { bad "gaze on ($g): $(tail -2 err3.txt)"; continue; }
  src=$(json s3/xr/manifest.json "d['gaze_source_frames']")
  last=$(ls rt3/frame_*_eye0.ppm | tail -1)
  c=$("$probe" centroid "$last" 0 0 160 120)
  python3 - "$g" "$c" rt3/frames.jsonl <<'PY' && ok "gaze on at tangent ($g): frames $src, spp disc at ($c)" \
    || bad "gaze on at tangent ($g): frames $src, spp disc at ($c)"
import json, sys
tx, ty = map(float, sys.argv[1].split(","))
cx, cy = map(float, sys.argv[2].split())
r = [json.loads(l) for l in open(sys.argv[3]) if json.loads(l)["layerCount"]][-1]
import math
l, rr, u, d = (math.tan(a) for a in r["views"][0]["fov"])
ex, ey = (tx - l) / (rr - l) * 160, (u - ty) / (u - d) * 120
sys.exit(0 if (cx - ex) ** 2 + (cy - ey) ** 2 < 5 ** 2 else 1)
PY
  # Inputs flow only while FOCUSED: a first frame rendered while VISIBLE takes the fallback.
  python3 - s3/xr/frames.jsonl <<'PY' || bad "gaze on ($g): frames by source $src"
import json, sys
sources = [json.loads(l)["gaze_source"] for l in open(sys.argv[1])]
sys.exit(0 if sources[-2:] == ["eye-tracker"] * 2 else 1)
PY
  grep -q "not active" err3.txt && bad "gaze on ($g): warned that the action is not active"
done

# 4. Ctrl-C: xrRequestExitSession, the states walk down to EXITING, exit 0.
FOVRT_TEST_XR_DUMP=rt4 "$fovrt" xr "${small[@]}" --set output.dir=s4 2>err4.txt &
pid=$!
for _ in $(seq 1 600); do [[ $(grep -c . s4/xr/frames.jsonl 2>/dev/null) -ge 2 ]] && break; sleep 0.1; done
kill -INT $pid; wait $pid; rc=$?
[[ $rc -eq 0 && $(tail -1 rt4/states.txt) == *EXITING ]] && ok "Ctrl-C: exit 0 after $(json s4/xr/manifest.json "d['frames']['rendered']") frames, ended in EXITING" \
  || bad "Ctrl-C: exit $rc, last state $(tail -1 rt4/states.txt 2>/dev/null): $(tail -2 err4.txt)"

# 5. The runtime ends the session itself (the user quit): STOPPING -> clean exit.
FOVRT_TEST_XR_EXIT_AFTER=5 FOVRT_TEST_XR_DUMP=rt5 "$fovrt" xr "${small[@]}" --set output.dir=s5 2>err5.txt
rc=$?
[[ $rc -eq 0 && $(tail -1 rt5/states.txt) == *EXITING ]] && ok "runtime-initiated exit: exit 0" \
  || bad "runtime-initiated exit: exit $rc: $(tail -2 err5.txt)"

# 6. Session loss and instance loss: one line, non-zero exit, the recording holds whole frames.
for kind in LOSS INSTANCE_LOSS; do
  rm -f lost.jsonl
  env FOVRT_TEST_XR_${kind}_AFTER=3 "$fovrt" xr "${small[@]}" --set output.dir=s6 --record lost.jsonl \
    >/dev/null 2>err6.txt
  rc=$?
  line=$(grep "^fovrt: error" err6.txt)
  if [[ $rc -ne 0 && $(grep -c "^fovrt: error" err6.txt) -eq 1 && $line == *lost* || $rc -ne 0 && $line == *"went away"* ]] &&
     "$fovrt" run --replay lost.jsonl --set output.dir=s6r --set output.write_png=false --set output.write_inputs=false 2>/dev/null; then
    ok "$kind: exit $rc, '$line', recording replays ($(($(grep -c . lost.jsonl) - 1)) frames)"
  else bad "$kind: exit $rc: $(tail -2 err6.txt)"; fi
done

# 7. Bad input: one line, non-zero exit, no recording.
bad_args=()  # fovrt xr options of the next check_bad
check_bad() {  # check_bad NAME EXPECTED_SUBSTRING ENV...
  local name=$1 want=$2; shift 2
  rm -f badrec.jsonl
  env "$@" "$fovrt" xr "${small[@]}" --set output.dir=s7 --frames 1 --record badrec.jsonl "${bad_args[@]}" \
    >/dev/null 2>err7.txt
  local rc=$?
  # (the core validation layer announces itself on stderr when an instance is created: not fovrt's)
  sed -i '/^Core Validation output type/d' err7.txt
  if [[ $rc -ne 0 && $(grep -c . err7.txt) -eq 1 && $(cat err7.txt) == *"$want"* && ! -e badrec.jsonl ]]; then
    ok "$name: $(cat err7.txt)"
  else bad "$name: exit $rc, recording $([[ -e badrec.jsonl ]] && echo left || echo absent): $(head -c 600 err7.txt)"; fi
}
echo '{"file_format_version": "1.0.0", "runtime": ' > broken.json
check_bad "no runtime" "no OpenXR runtime" -u XR_RUNTIME_JSON XDG_CONFIG_DIRS=/nonexistent XDG_CONFIG_HOME=/nonexistent
check_bad "missing XR_RUNTIME_JSON" "no such file" XR_RUNTIME_JSON=$work/absent.json
check_bad "corrupt XR_RUNTIME_JSON" "not valid JSON" XR_RUNTIME_JSON=$work/broken.json
check_bad "no enable2" "XR_KHR_vulkan_enable2" FOVRT_TEST_XR_NO_ENABLE2=1
check_bad "no HMD" "no head-mounted display" FOVRT_TEST_XR_NO_HMD=1
check_bad "form factor" "does not support the head-mounted display" FOVRT_TEST_XR_FORM_FACTOR_UNSUPPORTED=1
# A view the denoiser does not offer: refused with the views it does offer, as `fovrt preview` does.
bad_args=(--view lambda)
check_bad "unknown --view" "--view lambda: not a view of denoiser svgf (views: denoised, noisy, spp,"
bad_args=()

# 8. --mirror: the window shows the headset's frames (Xvfb). In an ASan build (scripts/sanitize.sh)
# this case runs without leak checking: LeakSanitizer reports 112 bytes in 2 callocs made by a
# library unloaded before exit (it cannot name it), seen only with the mirror window
# (docs/sanitizers.md); memory errors are still checked. ldd's whole output is matched, not piped
# to `grep -q`: grep exits at the match, ldd then fails writing the rest (EPIPE), and pipefail
# made the test take an ASan build for a plain one in some runs.
mirror_env=(); [[ $(ldd "$fovrt" 2>/dev/null) == *libasan* ]] && mirror_env=(env "ASAN_OPTIONS=${ASAN_OPTIONS:-}:detect_leaks=0")
if command -v xvfb-run >/dev/null; then
  if xvfb-run -a -s "-screen 0 1280x720x24" "${mirror_env[@]}" "$fovrt" xr "${small[@]}" --set output.dir=s8 --frames 3 --mirror \
       --window 640x360 --screenshot mirror.png 2>err8.txt; then
    std=$("$probe" stats mirror.png 400 90 640 270 | sed 's/.*std=//')
    awk -v s="$std" 'BEGIN { exit !(s > 10) }' && ok "--mirror: the window shows the right eye's frame (luma std $std)" \
      || bad "--mirror: the right eye's half looks empty (luma std $std)"
  else bad "--mirror: $(tail -2 err8.txt)"; fi
else skip_part "--mirror (no xvfb-run)"; fi

# 9. A tracker model over the headset's eye gaze (200 ms latency): the recording holds every
#    frame's true gaze and the tracked gaze its spp map followed — an earlier frame's true gaze,
#    never its own — and a headless replay renders with both as recorded.
FOVRT_TEST_XR_GAZE=on "$fovrt" xr "${small[@]}" --set output.dir=s9 --frames 5 --set gaze.tracker_latency_ms=200 \
  --record tracked.jsonl 2>err9.txt
rc=$?
if [[ $rc -eq 0 ]] && "$fovrt" run --replay tracked.jsonl --set output.dir=s9r --set output.write_png=false \
     --set output.write_inputs=false 2>err9r.txt; then
  python3 - tracked.jsonl s9r/frames.jsonl s9/xr/frames.jsonl <<'PY' > summary9.txt && ok "tracker model: $(cat summary9.txt)" || bad "tracker model: $(cat summary9.txt)"
import json, sys
rec = [json.loads(l) for l in list(open(sys.argv[1]))[1:]]
replayed = {r["frame"]: r for r in map(json.loads, open(sys.argv[2]))}
logged = {r["frame"]: r for r in map(json.loads, open(sys.argv[3]))}
problems = []
if len(rec) != 5: problems.append(f"{len(rec)} frames recorded")
# The tracker reports a sample through its (yaw, pitch) angles: equal to float rounding.
same = lambda a, b: max(abs(x - y) for x, y in zip(a, b)) < 1e-5
seen = []
for k, f in enumerate(rec):
    if "tracked_gaze" not in f: problems.append(f"frame {f['frame']}: no tracked_gaze"); continue
    true, tracked = f["gaze"]["direction"], f["tracked_gaze"]["direction"]
    seen.append(true)
    if k == 0 and not same(tracked, true): problems.append("frame 0: the first sample is not the tracked gaze")
    if k > 0 and (same(tracked, true) or not any(same(tracked, s) for s in seen[:-1])):
        problems.append(f"frame {f['frame']}: tracked gaze is not an earlier frame's true gaze")
    r = replayed.get(f["frame"])
    if not r or any(abs(a - b) > 1e-6 for a, b in zip(r["gaze_head"] + r.get("true_gaze_head", [9] * 3), tracked + true)):
        problems.append(f"frame {f['frame']}: the replay's gaze_head/true_gaze_head differ from the recording")
    l = logged.get(f["frame"])
    if not l or any(abs(a - b) > 1e-6 for a, b in zip(l["gaze_direction"] + l.get("true_gaze_direction", [9] * 3), tracked + true)):
        problems.append(f"frame {f['frame']}: frames.jsonl's gaze_direction/true_gaze_direction differ from the recording")
sources = [l["gaze_source"] for l in logged.values()]
print("; ".join(problems[:4]) if problems else
      f"{len(rec)} frames ({', '.join(sources)}) recorded with true and tracked gaze, each tracked gaze an earlier "
      "frame's true gaze; the replay renders with both")
sys.exit(1 if problems else 0)
PY
else bad "tracker model: exit $rc: $(tail -2 err9.txt) $(tail -2 err9r.txt 2>/dev/null)"; fi

# Core validation saw every call above.
errors=$(fovrt_xr_validation_errors)
# The layer announces itself at xrCreateInstance (so it was loaded); its report file is the
# authority (Debian's 1.0.20 layer sends nothing to a debug-utils messenger).
grep -q "Core Validation output type" out1.txt err1.txt && ok "the core validation layer was loaded" \
  || bad "the core validation layer did not load"
[[ $errors -eq 0 ]] && ok "core validation: 0 errors" || bad "core validation: $errors errors: $(grep -m3 VALID_ERROR core-validation.txt)"
echo "$passed passed, $failed failed"
finish $failed
