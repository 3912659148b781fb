#!/usr/bin/env bash
# End-to-end checks of the fovrt executable (run by ctest as app_cli): `run` writes a multi-layer
# EXR per frame and eye plus a complete manifest; bad input gives one clear error line naming the
# file/key and a non-zero exit, and leaves no manifest behind.
# Usage: cli_check.sh FOVRT WORK_DIR IMAGE_PROBE
set -uo pipefail
. "$(dirname "${BASH_SOURCE[0]}")/tools/skip.sh"
fovrt=$1; work=$2; probe=$3
src=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
rm -rf "$work"; mkdir -p "$work"; cd "$work"
passed=0; failed=0
ok() { echo "ok: $1"; passed=$((passed + 1)); }
bad() { echo "FAIL: $1"; failed=$((failed + 1)); }

# expect_error NAME PATTERN ARGS...: non-zero exit, exactly one stderr line matching PATTERN.
expect_error() {
  local name=$1 pattern=$2; shift 2
  if "$fovrt" "$@" >stdout.txt 2>stderr.txt; then bad "$name: exited 0"; return; fi
  local lines; lines=$(grep -c . stderr.txt)
  if [[ $lines -eq 1 ]] && grep -q -- "$pattern" stderr.txt; then ok "$name: $(cat stderr.txt)"
  else bad "$name: expected one line matching '$pattern', got: $(cat stderr.txt)"; fi
}

small=(--set camera.width=48 --set camera.height=32 --set run.frames=2)
if "$fovrt" run "${small[@]}" --set output.dir=run1 --set denoise.device=cpu >/dev/null 2>err.txt; then
  n=$(ls run1/inputs/*.exr 2>/dev/null | wc -l)
  [[ $n -eq 4 ]] && ok "run wrote 4 FrameInputs EXRs" || bad "run wrote $n EXRs, expected 4"
  grep -q '"complete": true' run1/manifest.json && ok "run manifest complete" || bad "manifest"
  # denoise.precision = auto (the default) is fp32 for the C++ reference; the manifest says so.
  grep -q '"denoise_storage": "fp32"' run1/manifest.json && ok "run manifest: auto storage resolved" ||
    bad "manifest lacks denoise_storage fp32"
  ls run1/inputs/*.tmp-* >/dev/null 2>&1 && bad "temp files left behind" || ok "no temp files"
else
  bad "run failed: $(cat err.txt)"
fi

# Record and replay: `run --record` writes a session recording; `run --replay` re-renders it with
# bit-identical noisy and denoised images; frames.jsonl has one line per frame; a truncated or
# corrupt recording and a config change that alters the frames are one-line errors.
if "$fovrt" run "${small[@]}" --set output.dir=rec1 --set denoise.device=cpu --record rec.jsonl >/dev/null 2>err.txt &&
   "$fovrt" run --replay rec.jsonl --set output.dir=replay1 >/dev/null 2>err.txt; then
  [[ $(wc -l < rec.jsonl) -eq 3 ]] && ok "recording: header + 2 frames" || bad "recording has $(wc -l < rec.jsonl) lines"
  for d in rec1 replay1; do
    [[ $(wc -l < $d/frames.jsonl) -eq 2 ]] && ok "$d/frames.jsonl: one line per frame" || bad "$d/frames.jsonl lines"
    grep -q '"records": "frames.jsonl"' $d/manifest.json && ok "$d manifest points at frames.jsonl" || bad "$d manifest"
  done
  same=1
  for f in rec1/noisy/*.png rec1/denoised/svgf/*.png rec1/inputs/*.exr; do cmp -s "$f" "${f/rec1/replay1}" || same=0; done
  [[ $same -eq 1 ]] && ok "replay: bit-identical inputs, noisy and denoised images" || bad "replay differs from the run"
  grep -q '"replay"' replay1/manifest.json && ok "replay manifest names the recording" || bad "replay manifest"
else
  bad "record/replay failed: $(cat err.txt)"
fi
head -c -40 rec.jsonl > truncated.jsonl
sed '3s/"fov":{/"fov_typo":{/' rec.jsonl > corrupt.jsonl
expect_error "truncated recording" "truncated.jsonl: line 3 (after frame 0): truncated line" run --replay truncated.jsonl --set output.dir=e10
expect_error "corrupt recording" "corrupt.jsonl: line 3 (frame 1): unknown key eyes\[0\].fov_typo" run --replay corrupt.jsonl --set output.dir=e11
expect_error "missing recording" "no_such.jsonl: cannot open" run --replay no_such.jsonl --set output.dir=e12
expect_error "replay refuses warm-up frames" "rec.jsonl: replay: run.warmup_frames = 2 differs from the recording's 0: a replay renders the recorded frames only" run --replay rec.jsonl --set run.warmup_frames=2 --set run.first_frame=2 --set output.dir=e14
expect_error "record refuses warm-up frames" "--record: run.warmup_frames = 2" run "${small[@]}" --set run.first_frame=2 --set run.warmup_frames=2 --set output.dir=e15 --record rec_warm.jsonl
expect_error "replay refuses a changed spp model" "rec.jsonl: replay: foveation.model = \"uniform\" differs" run --replay rec.jsonl --set foveation.model=uniform --set output.dir=e13
# experiment --replay: the recording's scene and frames, the file's variants and reference.
printf '[reference]\nspp = 4\ncache_dir = "refcache"\n[output]\ndir = "exp1"\n[experiment]\nscenes = ["room"]\nvariants = ["svgf"]\n' > exp.toml
if "$fovrt" experiment exp.toml --replay rec.jsonl >/dev/null 2>err.txt; then
  [[ -f exp1/manifest.json && -f exp1/frames-cornell.csv ]] && grep -q '"replay"' exp1/manifest.json &&
    ok "experiment --replay renders the recording's scene" || bad "experiment --replay outputs: $(ls exp1)"
  grep -q "experiment.scenes is ignored" err.txt && ok "experiment --replay notes the ignored scenes" || bad "no note: $(cat err.txt)"
else
  bad "experiment --replay failed: $(cat err.txt)"
fi
expect_error "experiment replay truncated" "truncated.jsonl: line 3" experiment exp.toml --replay truncated.jsonl --set output.dir=e14

# output.write_debug_views: one EXR per denoiser, frame and eye with a layer per debug view it
# offers (denoise/debug_views.h), each inside its valid range.
if "$fovrt" run "${small[@]}" --set output.dir=debug1 --set denoise.device=cpu --set output.write_debug_views=true \
    --set 'denoise.denoisers=["two-history-stable", "svgf"]' >/dev/null 2>err.txt; then
  layers=$("$probe" exr-channels debug1/denoised/two-history-stable/f00001_left.debug.exr)
  names=$(echo "$layers" | cut -d' ' -f1 | tr '\n' ' ')
  [[ $names == "historyLength historySamples historyU historyW p q stableLum t variance " ]] &&
    ok "debug views EXR: two-history-stable's 9 layers" || bad "debug views EXR layers: '$names'"
  echo "$layers" | awk '$1 ~ /^(p|q|t)$/ && ($2 < 0 || $3 > 1) {bad = 1} /nonfinite/ {bad = 1} END {exit bad}' &&
    ok "debug views EXR: p, q, t in [0, 1], all finite" || bad "debug views EXR values: $layers"
  [[ $("$probe" exr-channels debug1/denoised/svgf/f00000_right.debug.exr | cut -d' ' -f1) == historyLength ]] &&
    ok "debug views EXR: svgf's one layer" || bad "debug views EXR: svgf's layers"
  [[ $(ls debug1/denoised/*/*.debug.exr | wc -l) -eq 8 ]] && ok "debug views EXR: one per denoiser, frame and eye" ||
    bad "debug views EXR: $(ls debug1/denoised/*/*.debug.exr | wc -l) files, expected 8"
else
  bad "run --set output.write_debug_views=true failed: $(cat err.txt)"
fi

# A scene given by path is labelled by its `name`: the CSV and EXRs go under output.dir in a
# folder named "cornell" (never a folder named after the path, never outside output.dir), and the
# manifest's config names the scene rendered, with the path as the scene's source.
printf '[reference]\nspp = 2\ncache_dir = "refcache"\n[camera]\nwidth = 32\nheight = 24\n[run]\nframes = 1\n[output]\ndir = "exp2"\nwrite_exr = true\n[experiment]\nscenes = ["room"]\nvariants = ["svgf"]\n' > exp2.toml
scene_file="$src/scenes/cornell.toml"
if "$fovrt" experiment exp2.toml --scene "$scene_file" >/dev/null 2>err.txt; then
  [[ -f exp2/frames-cornell.csv ]] && ok "scene by path: exp2/frames-cornell.csv" || bad "scene by path: CSV not at exp2/frames-cornell.csv: $(find exp2 -name '*.csv')"
  [[ -f exp2/cornell/svgf/f00000_left.exr ]] && ok "scene by path: EXRs under exp2/cornell" || bad "scene by path: EXRs at $(find exp2 -name '*.exr' | head -1)"
  [[ -e "$scene_file/svgf" || -e "exp2/frames-$scene_file.csv" ]] && bad "scene by path: wrote under a folder named after the path" || ok "scene by path: nothing named after the path"
  grep -q '"scene": "cornell"' exp2/manifest.json && grep -q "\"source\": \"$scene_file\"" exp2/manifest.json &&
    ok "scene by path: manifest labels it cornell with its source" || bad "scene by path: manifest scene record"
  python3 -c 'import json,sys; m=json.load(open("exp2/manifest.json")); sys.exit(m["config"]["scene"]["name"] != sys.argv[1])' "$scene_file" &&
    ok "scene by path: manifest config names the scene rendered" || bad "scene by path: manifest config.scene.name is not $scene_file"
  grep -q '"cornell"' exp2/summary.json && ! grep -q "$scene_file" exp2/summary.json && ok "scene by path: summary labels it cornell" || bad "scene by path: summary label"
else
  bad "experiment --scene PATH failed: $(cat err.txt)"
fi
rm -rf "$scene_file/svgf" 2>/dev/null; rmdir "$scene_file" 2>/dev/null
# run --set scene.name=PATH: the manifest's scene is labelled by name, the path is its source.
if "$fovrt" run "${small[@]}" --set run.frames=1 --set "scene.name=$scene_file" --set output.dir=run2 --set denoise.device=cpu \
    --set output.write_exr=true >/dev/null 2>err.txt; then
  python3 -c 'import json,sys; m=json.load(open("run2/manifest.json")); sys.exit(not (m["scene"]["name"] == "cornell" and m["scene"]["source"] == sys.argv[1] and m["config"]["scene"]["name"] == sys.argv[1]))' "$scene_file" &&
    ok "run scene by path: manifest scene cornell, source the path" || bad "run scene by path: manifest scene"
  [[ -f run2/denoised/svgf/$(ls run2/denoised/svgf | grep -m1 exr) ]] && ok "run scene by path: EXRs under output.dir" || bad "run scene by path: no EXR under run2"
else
  bad "run --set scene.name=PATH failed: $(cat err.txt)"
fi

# A blink (NaN rows of a trace; frames 1..3 here) is counted in the manifest and marked in
# frames.jsonl with how it was rendered (gaze.blink).
printf 'n,x,y\n0,0,0\n33,1,0\n66,NaN,NaN\n100,NaN,NaN\n133,5,1\n166,6,1\n' > blink.csv
if "$fovrt" run "${small[@]}" --set run.frames=5 --set gaze.source=trace --set gaze.trace_path=blink.csv --set gaze.blink=uniform \
    --set output.dir=blink1 --set denoise.device=cpu >/dev/null 2>err.txt; then
  python3 -c 'import json,sys; m=json.load(open("blink1/manifest.json")); sys.exit(not (m["counters"]["blink_frames"] == 3 and m["config"]["gaze"]["blink"] == "uniform"))' &&
    ok "blink: manifest counts 3 blink frames" || bad "blink: manifest counters.blink_frames"
  [[ $(grep -c '"blink":"uniform"' blink1/frames.jsonl) -eq 3 ]] && ok "blink: frames.jsonl marks the blink frames" || bad "blink: frames.jsonl"
else
  bad "blink run failed: $(cat err.txt)"
fi
expect_error "unknown gaze.blink" "gaze.blink.*did you mean 'hold'" run --set gaze.blink=hld --set output.dir=e19

# A headset recording's "no sample" rows (dir (0,0,1), ori (0,0,0); 55-66 ms: frame 2 at 30 fps) are
# blinks in frames.jsonl; a 100 ms tracker records the true gaze beside the tracked one.
printf 'time,ori_x,ori_y,ori_z,dir_x,dir_y,dir_z\n5.000,0.01,0,0,0.1,0,0.994987\n5.044,0.01,0,0,0.1,0,0.994987\n5.055,0,0,0,0,0,1\n5.066,0,0,0,0,0,1\n5.077,0.01,0,0,0.1,0,0.994987\n5.2,0.01,0,0,0.1,0,0.994987\n' > rec.csv
if "$fovrt" run "${small[@]}" --set run.frames=4 --set run.fps=30 --set gaze.source=recording --set gaze.recording_path=rec.csv \
    --set gaze.tracker_latency_ms=100 --set output.dir=rec1 --set denoise.device=cpu >/dev/null 2>err.txt; then
  [[ $(grep -c '"true_blink":true' rec1/frames.jsonl) -eq 1 && $(grep -c '"true_gaze_head"' rec1/frames.jsonl) -eq 4 ]] &&
    ok "recording: frames.jsonl marks its blink and the true gaze" || bad "recording: frames.jsonl"
else
  bad "recording run failed: $(cat err.txt)"
fi
printf 'time,dir_x,dir_y,dir_z\n0,0,0,1\n0.011,0.5,0,0.5\n' > bad_rec.csv
expect_error "non-unit recording row" "bad_rec.csv:3" run --set gaze.source=recording --set gaze.recording_path=bad_rec.csv --set output.dir=e20
expect_error "prediction without a tracker rate" "gaze.prediction" run --set gaze.prediction=cv --set output.dir=e21

echo 'name = "broken"' > broken.toml
echo '[camera]' >> broken.toml
echo 'position = [0, 1, "x"]' >> broken.toml
printf 'n,x,y\n0,1,2\n10,abc,3\n' > bad_trace.csv
expect_error "missing scene file" "no_such_scene.toml" run --set scene.name=no_such_scene.toml --set output.dir=e1
expect_error "corrupt scene file" "broken.toml" run --set scene.name=broken.toml --set output.dir=e2
expect_error "unknown config key" "camera.widht" run --set camera.widht=3 --set output.dir=e3
expect_error "zero resolution" "camera.width" run --set camera.width=0 --set output.dir=e4
expect_error "negative spp" "foveation.spp_inside" run --set foveation.spp_inside=-2 --set output.dir=e5
expect_error "garbage trace row" "bad_trace.csv:3" run --set gaze.source=trace --set gaze.trace_path=bad_trace.csv --set output.dir=e6
expect_error "unknown device" "denoise.device\|device" run "${small[@]}" --set denoise.device=7 --set output.dir=e7
expect_error "unknown denoiser" "denoise.denoisers.*unknown denoiser 'svgf-typo' (did you mean 'svgf'?" run "${small[@]}" --set 'denoise.denoisers=["svgf-typo"]' --set output.dir=e8
expect_error "unknown scene names the nearest" "scene 'cornel'.*did you mean 'cornell'?" run --set scene.name=cornel --set output.dir=e15
expect_error "unknown key names the nearest" "camera.widht.*did you mean 'camera.width'?" run --set camera.widht=3 --set output.dir=e16
expect_error "unknown enum value names the nearest" "foveation.model.*did you mean 'acuity'?" run --set foveation.model=acuty --set output.dir=e17
expect_error "bad render.demodulation names the key" "render.demodulation.*'brfd' is not one of albedo, brdf" run --set render.demodulation=brfd --set output.dir=e31
# An output folder that cannot be written (a file in its path) is one line naming the key and the
# path; so is a reference cache that cannot be, and before any rendering.
touch afile
expect_error "unwritable output.dir" "config key 'output.dir': cannot write to 'afile/sub'" run "${small[@]}" --set output.dir=afile/sub
expect_error "unwritable reference.cache_dir" "config key 'reference.cache_dir': cannot write to 'afile/c'" experiment exp2.toml --set reference.cache_dir=afile/c --set output.dir=e18
# Seeds: bad --seeds / experiment.seeds / experiment.baseline are one line naming the option or key.
expect_error "bad --seeds" "^fovrt: error: --seeds abc: 'abc' is not a non-negative integer" experiment exp2.toml --seeds abc --set output.dir=e19
expect_error "zero --seeds" "^fovrt: error: --seeds 0: the count must be in \[1, 1000\]" experiment exp2.toml --seeds 0 --set output.dir=e20
expect_error "repeated --seeds" "--seeds 1,1: seed 1 is listed twice" experiment exp2.toml --seeds 1,1 --set output.dir=e21
sed 's/^variants = .*/&\nseeds = [1, "two"]/' exp2.toml > exp3.toml
expect_error "bad experiment.seeds" "exp3.toml:[0-9]*: experiment.seeds must hold only integers" experiment exp3.toml --set output.dir=e22
sed 's/^variants = .*/&\nbaseline = "svgff"/' exp2.toml > exp4.toml
expect_error "unknown experiment.baseline" "experiment.baseline 'svgff' is not in experiment.variants (did you mean 'svgf'?)" experiment exp4.toml --set output.dir=e23
expect_error "--seeds with --replay" "--seeds and --replay exclude each other" experiment exp.toml --replay rec.jsonl --seeds 2 --set output.dir=e24
expect_error "unwritable reference.cache_dir (reference)" "config key 'reference.cache_dir': cannot write to 'afile/c'" reference "${small[@]}" --set reference.cache_dir=afile/c
# A run that fails leaves no output folder it created, and keeps one that was there before.
mkdir -p pre
expect_error "failing run in an existing dir" "no_such_scene.toml" run --set scene.name=no_such_scene.toml --set output.dir=pre/deeper/out
[[ -d pre && ! -e pre/deeper ]] && ok "failed run: removed the folders it created, kept pre/" || bad "failed run: pre/ missing or pre/deeper left behind"
expect_error "memory budget" "budget" run "${small[@]}" --memory-budget 1KiB --set output.dir=e9
expect_error "reference memory budget" "budget" reference "${small[@]}" --memory-budget 1KiB
# The denoiser bench at a small size: every denoiser has a per-pass byte model and a bound.
if "$fovrt" bench --denoisers --width 64 --height 48 --frames 1 >bench.txt 2>err.txt; then
  for name in svgf svgf-weighted asvgf two-history two-history-asvgf asvgf-antilag two-history-asvgf-antilag two-history-stable two-history-stable-firefly two-history-stable-antilag two-history-asvgf-stable-antilag two-history-clamp two-history-stable-clamp two-history-hysteresis two-history-stable-hysteresis two-history-asvgf-stable-hysteresis; do
    grep -q "^$name \[" bench.txt && ok "bench times $name" || bad "bench lacks $name"
  done
  grep -q "no per-pass byte model" bench.txt && bad "bench: a denoiser lacks a byte model" || ok "bench: byte models"
  grep -q "host memcpy .* GB/s" bench.txt && ok "bench: memcpy bandwidth" || bad "bench: no memcpy bandwidth"
  if grep -q "Vulkan device: none" bench.txt || grep -q "device streaming copy .* GB/s" bench.txt; then
    ok "bench: device bandwidth"
  else
    bad "bench: no device streaming-copy bandwidth"
  fi
else
  bad "bench --denoisers failed: $(cat err.txt)"
fi
# One denoiser, no reference, fp16 histories.
if "$fovrt" bench --denoisers --denoiser two-history --no-reference --precision fp16 --width 64 --height 48 \
    --frames 1 >bench1.txt 2>err.txt; then
  grep -q "^two-history \[" bench1.txt && ! grep -q "^svgf \[\|\[cpu\]" bench1.txt && ok "bench --denoiser selects" ||
    bad "bench --denoiser ran other denoisers or the reference"
else
  bad "bench --denoiser failed: $(cat err.txt)"
fi
# The Embree comparison at a small size, in 2 rounds: a ratio per round and the pooled one (the
# numbers are timings, not checked; the shared Cornell OBJ and embree-tools are needed).
if "$fovrt" bench --scene none --width 64 --height 36 --compare-rounds 2 >cmp.txt 2>err.txt; then
  if grep -q "^  skipped:" cmp.txt; then
    skip_part "bench: the Embree comparison ($(grep "^  skipped:" cmp.txt | sed 's/^  skipped: //'))"
  else
    grep -Eq "per CPU-second \(rounds, per CPU-second: [0-9.]+ / [0-9.]+\)$" cmp.txt \
      && grep -q "2 round(s), each fovrt's 2 frames then Embree's run pair" cmp.txt \
      && ok "bench: the Embree comparison in 2 rounds" || bad "bench comparison: $(grep -E 'ratio|round' cmp.txt)"
  fi
else
  bad "bench comparison failed: $(cat err.txt)"
fi
expect_error "unknown bench denoiser" "svgf-typo" bench --denoisers --denoiser svgf-typo
expect_error "bad bench precision" "fp8" bench --denoisers --precision fp8
expect_error "unknown denoiser names the nearest" "did you mean 'two-history'" memory --width 64 --height 64 --denoiser two-histroy
expect_error "bad precision" "expected fp32 or fp16" memory --width 64 --height 64 --denoiser svgf --precision fp8
# --scored-frames adds FovVideoVDP's frames (4 bytes per pixel and frame, the reference's and each
# variant's, per eye) to the plan and to the budget.
if "$fovrt" memory --width 64 --height 64 --eyes 1 --denoiser svgf --scored-frames 10 >mem.txt 2>err.txt; then
  grep -q "eye0.vdp.svgf_luminance *163840 bytes" mem.txt && grep -q "total 327680 bytes" mem.txt && ! grep -q "eye1.vdp" mem.txt &&
    ok "memory --scored-frames lists the metric's frames of one eye" || bad "memory --scored-frames: $(tail -4 mem.txt)"
else
  bad "memory --scored-frames failed: $(cat err.txt)"
fi
expect_error "memory --window out of range" "denoise.two_history.window: 0 is out of range (0, 1]" memory --width 64 --height 64 --window 0
# --window keeps two-history's weighted history (40 B/pixel in fp16) in a quarter of the image.
if "$fovrt" memory --width 64 --height 64 --eyes 1 --denoiser two-history --precision fp16 --window 0.5 >mem.txt 2>err.txt; then
  grep -q "weighted history in a window of 0.5 per side" mem.txt && grep -q "^wweight.A  *2048 " mem.txt &&
    grep -q "^history total  *303104  *74.00" mem.txt &&
    ok "memory --window sizes the weighted planes by the window" || bad "memory --window: $(head -3 mem.txt; grep total mem.txt)"
else
  bad "memory --window failed: $(cat err.txt)"
fi
expect_error "the metric's frames count against the budget" "vdp.*luminance" memory --width 64 --height 64 --denoiser svgf \
  --scored-frames 1000 --memory-budget 4MiB
# info lists every denoiser variant of the table with its summary.
"$fovrt" info >info.txt 2>err.txt && [[ $(grep -c "^denoiser " info.txt) -eq 18 ]] &&
  grep -q "^denoiser  *two-history-asvgf  *two-history SVGF" info.txt && ok "info lists the denoisers" ||
  bad "info: $(cat info.txt err.txt)"
# config --keys: one line per key from the settings tables (key, default, allowed, meaning).
"$fovrt" config --keys >keys.txt 2>err.txt && grep -q "^denoise.svgf.alpha_color  *0.2  *(0, 1] " keys.txt &&
  grep -q "^denoise.precision  *auto  *fp32|fp16|auto " keys.txt &&
  grep -q "^foveation.radius_deg  *0.0  *\[0, 180) " keys.txt &&
  grep -q "^foveation.model  *disc  *disc|linear|acuity|uniform|perceptual " keys.txt &&
  grep -q "^gaze.tracker_rate_hz  *0.0  *\[0, 10000\] " keys.txt && ok "config --keys" || bad "config --keys: $(cat keys.txt err.txt)"
# A run renders the experiment's noisy inputs when it lists the same variants: A-SVGF's gradient
# samples re-shade one pixel per 3×3 stratum with the previous frame's seed, so from frame 1 on the
# inputs depend on whether a listed variant needs them. The experiment's denoised EXRs stand for
# its inputs (it writes no FrameInputs): the C++ reference denoiser is deterministic.
printf '[camera]\nwidth = 48\nheight = 32\n[run]\nframes = 3\n[denoise]\ndevice = "cpu"\n[reference]\nspp = 2\ncache_dir = "refcache"\n[output]\nwrite_exr = true\nreport = false\n[experiment]\nscenes = ["cornell"]\nvariants = ["svgf", "asvgf"]\n' > exp5.toml
same_run=(--set camera.width=48 --set camera.height=32 --set run.frames=3 --set denoise.device=cpu
          --set scene.name=cornell --set output.write_exr=true --set output.write_png=false)
if "$fovrt" experiment exp5.toml --set output.dir=x-exp >/dev/null 2>err.txt &&
   "$fovrt" run "${same_run[@]}" --set 'denoise.denoisers=["svgf", "asvgf"]' --set output.dir=x-both >/dev/null 2>>err.txt &&
   "$fovrt" run "${same_run[@]}" --set 'denoise.denoisers=["svgf"]' --set output.dir=x-svgf >/dev/null 2>>err.txt; then
  n=0; same=0
  for v in svgf asvgf; do for f in 0 1 2; do for eye in left right; do
    n=$((n + 1)); cmp -s x-exp/cornell/$v/f0000${f}_$eye.exr x-both/denoised/$v/f0000${f}_$eye.exr && same=$((same + 1))
  done; done; done
  [[ $n -eq 12 && $same -eq 12 ]] && ok "run with the experiment's variants reproduces its frames: $same of $n denoised EXRs identical" \
    || bad "run with the experiment's variants: $same of $n denoised EXRs identical"
  cmp -s x-svgf/inputs/f00000_left.exr x-both/inputs/f00000_left.exr && ok "frame 0 inputs equal without A-SVGF's gradient samples" \
    || bad "frame 0 inputs differ with and without gradient samples"
  if ! cmp -s x-svgf/inputs/f00001_left.exr x-both/inputs/f00001_left.exr &&
     ! cmp -s x-svgf/denoised/svgf/f00001_left.exr x-exp/cornell/svgf/f00001_left.exr; then
    ok "without asvgf listed, frame 1 inputs (and svgf's output) differ from the experiment's: the documented condition"
  else bad "frame 1 inputs do not depend on the gradient samples: the documented condition is wrong"; fi
else bad "run/experiment comparison failed: $(tail -2 err.txt)"; fi
# --set experiment.KEY is read like the file's key; an unknown one is refused naming the --set.
expect_error "--set experiment.bogus" "^fovrt: error: --set experiment.bogus=1: unknown key experiment.bogus (did you mean" experiment exp2.toml --set experiment.bogus=1 --set output.dir=e30
expect_error "--set experiment.variants is read" "--set experiment.variants=\[\"svgff\"\]: experiment.variants: unknown denoiser 'svgff'" experiment exp2.toml --set 'experiment.variants=["svgff"]' --set output.dir=e31
# A value that is not UTF-8 is refused before anything is rendered, naming the key.
expect_error "non-UTF-8 --set value" "^fovrt: error: --set output.dir: the value is not valid UTF-8" run "${small[@]}" --set output.dir=$'e32-\xff'
# A directory given as a gaze trace is named as one.
mkdir -p traces
expect_error "gaze trace is a directory" "traces: is a directory, not a gaze trace (CSV)" run "${small[@]}" --set gaze.source=trace --set gaze.trace_path=traces --set output.dir=e33
# Budgets are checked before anything large is allocated, on the whole run's memory plan: under
# a 1 GiB address-space limit, a 16384² run with a 2 GiB budget is refused by the budget (had it
# allocated first, it would have died of the limit). Without a budget, running out of memory is
# one line naming the resolution and the bytes the run asked for.
# AddressSanitizer reserves terabytes of address space for its shadow memory, so an ASan build
# (scripts/sanitize.sh) cannot start under the limit: there the budget cases run without it and
# the out-of-memory case is skipped.
# (ldd's whole output is matched: piped to `grep -q`, ldd fails writing after grep exits, and
# pipefail then hides libasan in some runs.)
asan=false; [[ $(ldd "$fovrt" 2>/dev/null) == *libasan* ]] && asan=true
real_fovrt=$fovrt
if ! $asan; then
  printf '#!/usr/bin/env bash\nulimit -v 1048576\nexec "%s" "$@"\n' "$(realpath "$fovrt")" > limited-fovrt
  chmod +x limited-fovrt
  fovrt=./limited-fovrt
fi
huge=(--set camera.width=16384 --set camera.height=16384 --set run.frames=1 --set denoise.device=cpu)
expect_error "budget before allocation (run)" "^fovrt: error: --memory-budget 2147483648 bytes exceeded: run needs" run "${huge[@]}" --memory-budget 2GiB --set output.dir=e34
expect_error "budget before allocation (experiment)" "^fovrt: error: --memory-budget 2147483648 bytes exceeded: experiment needs" experiment exp2.toml "${huge[@]}" --memory-budget 2GiB --set output.dir=e35
expect_error "budget before allocation (reference)" "^fovrt: error: --memory-budget 1073741824 bytes exceeded: reference needs" reference "${huge[@]}" --memory-budget 1GiB --set reference.cache_dir=e36c
# (the run's own start line comes first: the error is the one line after it)
if $asan; then echo "skip: out of memory (run): an ASan build cannot run under an address-space limit"
elif "$fovrt" run "${huge[@]}" --set output.dir=e37 >stdout.txt 2>stderr.txt; then bad "out of memory (run): exited 0"
elif [[ $(grep -c "error" stderr.txt) -eq 1 ]] &&
     tail -1 stderr.txt | grep -q "^fovrt: error: out of memory: fovrt run at 16384x16384 per eye asked for [0-9]* bytes"; then
  ok "out of memory (run): $(tail -1 stderr.txt)"
else bad "out of memory (run): $(cat stderr.txt)"; fi
fovrt=$real_fovrt
[[ -e e37/manifest.json ]] && bad "e37 has a manifest after running out of memory"

# A trace that ends: a start past its end, or a run longer than it, is refused before rendering
# (gaze.trace_end = "refuse"); "hold" renders the frames past the end on its last row, with a
# warning, and marks them in frames.jsonl. 100 ms of trace: frames 0..3 at 30 fps.
printf 'n,x,y\n0,0,0\n50,5,0\n100,10,0\n' > short.csv
ends=(--set run.fps=30 --set gaze.source=trace --set gaze.trace_path=short.csv --set denoise.device=cpu)
expect_error "run longer than its trace" 'gaze.trace_end = "refuse": frames 0..4 .*need 5 frames of gaze .*has 4' \
  run "${small[@]}" "${ends[@]}" --set run.frames=5 --set output.dir=e40
expect_error "trace_start_ms past the trace" "gaze.trace_start_ms: 500 ms is outside gaze.trace_path '.*short.csv', which lasts 100 ms" \
  run "${small[@]}" "${ends[@]}" --set gaze.trace_start_ms=500 --set output.dir=e41
if "$fovrt" run "${small[@]}" "${ends[@]}" --set run.frames=5 --set gaze.trace_end=hold --set output.dir=held1 \
    >/dev/null 2>err.txt; then
  [[ $(grep -c '"gaze_held":true' held1/frames.jsonl) -eq 1 ]] && grep '"frame":4,' held1/frames.jsonl | grep -q '"gaze_held":true' &&
    grep -q 'frames 4..4 are past the end' err.txt && ok "trace_end hold: frame 4 marked gaze_held, with a warning" ||
    bad "trace_end hold: frames.jsonl or warning: $(cat err.txt)"
else
  bad "trace_end hold run failed: $(cat err.txt)"
fi
# A periphery below 1 spp: the run's denoisers read the sample counts (the manifest says so; run1's
# map never holds 0), and the RAE runs it, its empty pixels filled from their neighbours.
if "$fovrt" run "${small[@]}" --set foveation.spp_outside=0.25 --set output.dir=zero1 --set denoise.device=cpu \
    >/dev/null 2>err.txt; then
  python3 -c 'import json,sys; sys.exit(not (json.load(open("zero1/manifest.json"))["denoise_sample_counts_may_be_zero"] is True and json.load(open("run1/manifest.json"))["denoise_sample_counts_may_be_zero"] is False))' &&
    ok "spp_outside 0.25: the manifest records that sample counts may be zero, run1's that they may not" ||
    bad "manifest denoise_sample_counts_may_be_zero"
else
  bad "run with spp_outside 0.25 failed: $(cat err.txt)"
fi
if "$fovrt" run "${small[@]}" --set 'denoise.denoisers=["rae"]' --set foveation.spp_outside=0.25 \
    --set output.dir=rae-zero1 >/dev/null 2>err.txt; then
  grep -q '"complete": true' rae-zero1/manifest.json && ok "rae below 1 spp: runs to a complete manifest" ||
    bad "rae below 1 spp: manifest incomplete"
else
  bad "rae below 1 spp failed: $(cat err.txt)"
fi
# A scene with no light would score as perfect: refused naming it.
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' > tri.obj
printf 'name = "dark"\n[[mesh]]\nfile = "tri.obj"\n' > dark.toml
expect_error "scene with no light" "scene 'dark' (.*dark.toml): has no light" run "${small[@]}" --set scene.name=dark.toml --set output.dir=e42
# A preset's paths are from its folder: the latency preset finds its recording from any folder.
mkdir -p elsewhere
(cd elsewhere && "$fovrt" config --experiment -c "$src/presets/eye-tracker-latency.toml") > latency.toml 2>err.txt &&
  grep -qx "recording_path = [\"']$(cd "$src/.." && pwd)/shared/gaze/vr-kitchen-p10.csv[\"']" latency.toml &&
  ok "preset paths from the preset's folder" || bad "preset paths: $(grep recording_path latency.toml) $(cat err.txt)"

left=""
for d in e1 e2 e3 e4 e5 e6 e7 e8 e9 e10 e11 e12 e13 e14 e15 e16 e17 e18 e19 e30 e31 e32-$'\xff' e33 e34 e35 e36c e40 e41 e42 e43; do
  [[ -e $d/manifest.json ]] && bad "$d has a manifest after an error"
  [[ -e $d ]] && left="$left $d"
done
ok "no manifest after any error"
[[ -z $left ]] && ok "no output folder left behind by a failed run" || bad "failed runs left output folders:$left"
echo "$passed passed, $failed failed"
finish $failed
