# Sourced by the shell tests: a check that cannot run here is reported as a skip, never as a pass.
# ctest shows a test that exits with FOVRT_TEST_SKIP_CODE as skipped (its SKIP_RETURN_CODE,
# tests/CMakeLists.txt, which also sets the variable; 77 when a script is run by hand). With
# FOVRT_REQUIRE_ALL=1 (.ci/run: CI installs every dependency) a skip is a failure.
fovrt_skip_code=${FOVRT_TEST_SKIP_CODE:-77}
fovrt_skipped=0

# skip_all WHY: the whole test cannot run here; exits.
skip_all() {
  if [[ ${FOVRT_REQUIRE_ALL:-} == 1 ]]; then
    echo "FAIL: not run, and FOVRT_REQUIRE_ALL=1 makes that a failure: $1"; exit 1
  fi
  echo "SKIP: $1"; exit "$fovrt_skip_code"
}

# skip_part WHY: one part of the test cannot run here; the rest goes on. Under FOVRT_REQUIRE_ALL=1
# it counts as a failure through the script's own bad().
skip_part() {
  if [[ ${FOVRT_REQUIRE_ALL:-} == 1 ]]; then
    bad "not run, and FOVRT_REQUIRE_ALL=1 makes that a failure: $1"
  else
    echo "SKIP: $1"; fovrt_skipped=$((fovrt_skipped + 1))
  fi
}

# finish FAILED: the script's exit: failure if any check failed, else skipped if a part was, else 0.
finish() {
  if [[ $1 -ne 0 ]]; then exit 1; fi
  if [[ $fovrt_skipped -ne 0 ]]; then echo "($fovrt_skipped part(s) skipped)"; exit "$fovrt_skip_code"; fi
  exit 0
}
