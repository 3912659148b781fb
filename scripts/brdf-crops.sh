#!/usr/bin/env bash
# The picture of the detailed surface in docs/experiments.md: foveal crops of brdf-detail's metal
# panel, reference | svgf | svgf+brdf | two-history | two-history+brdf, from the fovea crops of
# one `fovrt experiment` report (presets/brdf-demodulation.toml at 640×360, 30 frames, 256-spp
# references, the gaze held on the panel so that the fovea is where the detail is). The report
# gives each crop's rectangle; this script cuts the centre of it and enlarges it with netpbm
# (nearest neighbour, so the cells stay sharp). Needs python3 (stdlib only) and netpbm.
# Usage: scripts/brdf-crops.sh [--no-run] [OUT_PNG]   (default docs/brdf-detail-crops.png)
#   --no-run: reuse the last run's report (out/brdf-crops/report.html)
set -euo pipefail
cd "$(dirname "$0")/.."
fovrt=${FOVRT:-build/src/app/fovrt}
rerun=1
if [ "${1:-}" = "--no-run" ]; then rerun=0; shift; fi
out_png=${1:-docs/brdf-detail-crops.png}
run=out/brdf-crops
side=100   # pixels cut from the centre of each fovea crop (200 × 200 at 640 wide)
scale=2    # enlargement

# Gaze 4.6° left and 2.1° up of the head's axis: the metal panel's centre at 640×360.
[ $rerun = 0 ] || nice -n 5 "$fovrt" experiment presets/brdf-demodulation.toml --scene brdf-detail \
  --set camera.width=640 --set camera.height=360 --set run.frames=30 --set reference.spp=256 \
  --set 'gaze.source="static"' --set gaze.yaw_deg=-4.6 --set gaze.pitch_deg=2.1 \
  --set "output.dir=\"$run\"" --set 'reference.cache_dir="out/ref-cache"' >/dev/null

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# The report's fovea crops (base64 PNGs after the "Fovea crops" heading), one file per image.
python3 - "$run/report.html" "$tmp" <<'EOF'
import base64, re, sys
html = open(sys.argv[1], encoding="utf-8").read()
head = re.search(r"<h3>(Fovea crops[^<]*)</h3>", html)
print(head.group(1))
section = html[head.end():html.index("</div>", head.end())]
for alt, data in re.findall(r'<img alt="([^"]*)"[^>]*src="data:image/png;base64,([^"]*)"', section):
    open(f"{sys.argv[2]}/{alt.replace('+', '_')}.png", "wb").write(base64.b64decode(data))
EOF
pngtopnm "$tmp/reference.png" > "$tmp/size.ppm"
crop=$(pnmfile "$tmp/size.ppm" | awk '{print $4}')  # the fovea crop's side
parts=()
for name in reference svgf svgf_brdf two-history two-history_brdf; do
  pngtopnm "$tmp/$name.png" | pnmcut -left $(((crop - side) / 2)) -top $(((crop - side) / 2)) \
    -width $side -height $side | pamenlarge $scale | pnmpad -white -right 6 > "$tmp/$name.ppm"
  parts+=("$tmp/$name.ppm")
done
mkdir -p "$(dirname "$out_png")"
pnmcat -lr "${parts[@]}" | pnmtopng -compression 9 > "$out_png"
echo "wrote $out_png ($(stat -c %s "$out_png") bytes): centre ${side}×${side} of each crop, ×$scale"
