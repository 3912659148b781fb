#!/usr/bin/env bash
# The sanitizer builds (docs/sanitizers.md). Usage: scripts/sanitize.sh [address|thread]...
#   address: ASan+UBSan build in build-asan/, runs the whole ctest suite.
#   thread:  TSan build in build-tsan/, runs the tests where fovrt's own threads meet: the live
#            loop, the preview window and the OpenXR session (ctest -R "$tsan_tests"); builds
#            only what those tests run.
# With no argument, both. Suppressions for the uninstrumented system libraries are in
# scripts/sanitizers/; each entry says why it is not fovrt's bug.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
supp=$root/scripts/sanitizers
jobs=${FOVRT_SANITIZE_JOBS:-$(nproc)}
generator=(); command -v ninja >/dev/null && generator=(-G Ninja)
launcher=(); command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)

tsan_tests='^(live_|preview_|xr_)'

build() {  # build <dir> <address|thread> [targets]
  # -O1 -g: file and line in every report; -O1 keeps the instrumented tests fast enough to run
  # the whole suite (the sanitizers' own recommendation).
  cmake -S . -B "$1" "${generator[@]}" "${launcher[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g -DNDEBUG" -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g -DNDEBUG" \
    -DFOVRT_SANITIZE="$2" >/dev/null
  local start=$SECONDS
  cmake --build "$1" -j"$jobs" ${3:+--target $3}
  echo "== $2: built in $((SECONDS - start)) s"
}

run_address() {
  build build-asan address
  # halt_on_error/abort: the first report fails the test that produced it. detect_leaks on, with
  # the Vulkan driver's and loader's one-time allocations suppressed (asan-leaks.supp).
  ASAN_OPTIONS="detect_leaks=1:halt_on_error=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1:check_initialization_order=1" \
  LSAN_OPTIONS="suppressions=$supp/lsan.supp:print_suppressions=0" \
  UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1:suppressions=$supp/ubsan.supp" \
    ctest --test-dir build-asan --output-on-failure -j"$jobs"
}

run_thread() {
  # The tests' executables, and what the shell tests run: fovrt, image_probe, the test XR runtime.
  local targets="fovrt image_probe fovrt_test_xr_runtime"
  for source in tests/*_test.cpp; do
    name=$(basename "$source" .cpp)
    [[ $name =~ $tsan_tests ]] && targets+=" $name"
  done
  build build-tsan thread "$targets"
  TSAN_OPTIONS="halt_on_error=1:second_deadlock_stack=1:suppressions=$supp/tsan.supp:print_suppressions=0" \
    ctest --test-dir build-tsan --output-on-failure -j"$jobs" -R "$tsan_tests"
}

kinds=("$@"); [[ ${#kinds[@]} -gt 0 ]] || kinds=(address thread)
for kind in "${kinds[@]}"; do
  case $kind in
    address|thread) echo "== $kind"; SECONDS=0; "run_$kind"; echo "== $kind: ${SECONDS} s" ;;
    *) echo "scripts/sanitize.sh: unknown sanitizer '$kind' (expected address or thread)" >&2; exit 2 ;;
  esac
done
