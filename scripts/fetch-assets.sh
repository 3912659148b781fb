#!/usr/bin/env bash
# The assets outside the repository: the scenes and eye-tracking recordings that some presets and
# tests read from ../shared (beside the checkout). scripts/assets.manifest lists each file with its
# SHA-256 and public source. This script checks every copy present against its hash and, unless
# --verify is given, downloads each missing file (curl or wget), checks it and moves it into place.
# Builds and tests never download (the test assets_verify runs it with --verify, and its download
# mode against a stand-in curl).
# Usage: scripts/fetch-assets.sh [--verify] [--dir DIR]   (DIR default: ../shared beside the checkout)
# Exit: 0 every file present and matching; 1 a copy (or a download) does not match its hash, or a
#       download failed; 2 a bad option; 3 some files are absent (those present match).
# It ends by naming the presets that run without the absent files and the tests that skip.
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
manifest=$repo/scripts/assets.manifest
dir=$repo/../shared
verify_only=0
while [[ $# -gt 0 ]]; do
  case $1 in
    --verify) verify_only=1; shift ;;
    --dir) [[ $# -ge 2 ]] || { echo "fetch-assets.sh: --dir needs a folder" >&2; exit 2; }
           dir=$2; shift 2 ;;
    *) echo "fetch-assets.sh: unknown option '$1' (usage: fetch-assets.sh [--verify] [--dir DIR])" >&2; exit 2 ;;
  esac
done

sha256() { sha256sum "$1" | cut -d' ' -f1; }
download() {  # URL FILE
  if command -v curl >/dev/null 2>&1; then curl -fsSL --retry 2 -o "$2" "$1"
  elif command -v wget >/dev/null 2>&1; then wget -q -O "$2" "$1"
  else echo "fetch-assets.sh: neither curl nor wget is installed" >&2; return 1; fi
}

total=0; bad=0; absent=()
while read -r hash path source; do
  [[ -z $hash || $hash == \#* ]] && continue
  total=$((total + 1))
  file=$dir/$path
  if [[ -f $file ]]; then
    if [[ $(sha256 "$file") != "$hash" ]]; then
      echo "MISMATCH $file: its SHA-256 is not the one in scripts/assets.manifest (a corrupted or different copy)"
      bad=$((bad + 1))
    fi
    continue
  fi
  if [[ $verify_only == 1 ]]; then absent+=("$path"); continue; fi
  if [[ $source == derived ]]; then
    echo "absent $path: derived from the files beside it, with no public copy; copy it from an existing ../shared"
    absent+=("$path"); continue
  fi
  echo "downloading $path"
  mkdir -p "$(dirname "$file")"
  if ! download "$source" "$file.part"; then
    echo "FAILED $path: could not download $source"
    rm -f "$file.part"; bad=$((bad + 1)); continue
  fi
  if [[ $(sha256 "$file.part") != "$hash" ]]; then
    echo "MISMATCH $path: the download from $source does not have the manifest's SHA-256 (kept as $file.part)"
    bad=$((bad + 1)); continue
  fi
  mv "$file.part" "$file"
done < "$manifest"

if [[ ${#absent[@]} -gt 0 ]]; then
  # Grouped by asset folder (gaze, scenes/<name>): a scene needs its whole folder.
  groups_of() { printf '%s\n' "$@" | awk -F/ '{print ($1 == "gaze") ? "gaze" : $1 "/" $2}'; }
  echo "${#absent[@]} of $total files absent from $dir: $(groups_of "${absent[@]}" | uniq -c |
    awk '{printf "%s%s (%d files)", (NR > 1 ? ", " : ""), $2, $1}')"
  # What still runs: a scene file under scenes/ needs the shared folder it names; a preset needs
  # the scenes it lists and any recording under gaze/.
  missing_groups=$(groups_of "${absent[@]}" | sort -u)
  needs=()  # "scene-name group" pairs
  for scene in "$repo"/scenes/*.toml; do
    group=$(sed -n 's|.*shared/\(scenes/[^/"]*\)/.*|\1|p' "$scene" | head -n1)
    [[ -n $group ]] && needs+=("$(basename "$scene" .toml) $group")
  done
  runs=(); stops=()
  for preset in "$repo"/presets/*.toml; do
    name=$(basename "$preset" .toml); blocked=0
    for group in $missing_groups; do
      if [[ $group == gaze ]]; then grep -q 'shared/gaze/' "$preset" && blocked=1
      else
        for pair in "${needs[@]}"; do
          [[ ${pair#* } == "$group" ]] && grep -q "\"${pair%% *}\"" "$preset" && blocked=1
        done
      fi
    done
    if [[ $blocked == 1 ]]; then stops+=("$name"); else runs+=("$name"); fi
  done
  echo "presets that run without them: ${runs[*]:-none}"
  echo "presets that stop with one line naming the absent file: ${stops[*]:-none}"
  echo "tests that skip with a message without them: $(grep -lE 'FOVRT_REQUIRE_SHARED_SCENES|SharedScenes\(\)|SharedGaze\(\)|shared/(gaze|scenes)' \
    "$repo"/tests/*.cpp "$repo"/tests/*.sh | xargs -n1 basename | tr '\n' ' ')"
fi
if [[ $bad -gt 0 ]]; then
  echo "fetch-assets.sh: $bad of $total files do not match scripts/assets.manifest" >&2
  exit 1
fi
[[ ${#absent[@]} -gt 0 ]] && exit 3
echo "fetch-assets.sh: all $total files in $dir match scripts/assets.manifest"
