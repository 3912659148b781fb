#!/usr/bin/env bash
# scripts/fetch-assets.sh --verify: the copies in ../shared match scripts/assets.manifest; a copy
# with one byte changed is named and fails; a folder with only some of the assets says which
# presets still run. Nothing is downloaded: under --verify, curl and wget are stand-ins that fail
# if called; the download mode runs against a stand-in curl that serves ../shared's files.
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

# Download mode, with a stand-in curl that serves each manifest URL from ../shared: the absent
# files arrive and verify, the derived ones (no public copy) are named; a download with a changed
# byte is refused and not moved into place.
mkdir -p serve
cat > serve/curl <<EOF
#!/usr/bin/env bash
out=""; url=""
while [[ \$# -gt 0 ]]; do
  case \$1 in -o) out=\$2; shift 2 ;; --retry) shift 2 ;; -*) shift ;; *) url=\$1; shift ;; esac
done
path=\$(awk -v u="\$url" '\$3 == u {print \$2}' "$src/scripts/assets.manifest")
[[ -n \$path ]] || exit 22
cat "$shared/\$path" > "\$out"
[[ -z \${CORRUPT:-} ]] || printf 'x' >> "\$out"
EOF
chmod +x serve/curl
rc=0; PATH=$work/serve:$PATH bash "$fetch" --dir "$work/fetched" > fetched.txt 2>&1 || rc=$?
cat fetched.txt
[[ $rc == 3 ]] || { echo "FAIL: a download into an empty folder exited $rc, not 3 (derived files absent)"; exit 1; }
grep -q '^absent scenes/veach-ajar/veach-ajar.obj: derived' fetched.txt ||
  { echo "FAIL: the derived veach-ajar.obj is not named as absent"; exit 1; }
rc=0; bash "$fetch" --verify --dir "$work/fetched" > refetched.txt 2>&1 || rc=$?
grep -q '^2 of .* files absent' refetched.txt ||
  { echo "FAIL: after the download, not exactly the 2 derived files are absent: $(cat refetched.txt)"; exit 1; }
rm "$work/fetched/gaze/vr-kitchen-p15.csv"
rc=0; CORRUPT=1 PATH=$work/serve:$PATH bash "$fetch" --dir "$work/fetched" > bad-download.txt 2>&1 || rc=$?
cat bad-download.txt
[[ $rc == 1 ]] || { echo "FAIL: a download with the wrong hash exited $rc, not 1"; exit 1; }
grep -q '^MISMATCH gaze/vr-kitchen-p15.csv: the download' bad-download.txt ||
  { echo "FAIL: the bad download is not named"; exit 1; }
[[ ! -e $work/fetched/gaze/vr-kitchen-p15.csv ]] || { echo "FAIL: the bad download was moved into place"; exit 1; }
echo "assets: ../shared verified; a changed byte and absent files reported; downloads checked"
