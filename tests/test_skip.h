// Skipping a test case, reported as a skip and not as a pass. Catch2 v2 has no skipped state: a
// skipping test case (FOVRT_SKIP, test_support.h) is counted here, and the executable's main
// (catch_main.cpp) then exits with FOVRT_TEST_SKIP_CODE when no test case failed, which ctest
// reports as skipped (SKIP_RETURN_CODE, tests/CMakeLists.txt).
#pragma once

#include <atomic>
#include <cstdlib>
#include <cstring>

namespace fovrt::test {

inline std::atomic<int>& SkippedTestCases() {
    static std::atomic<int> count{0};
    return count;
}

// FOVRT_REQUIRE_ALL=1 (.ci/run, where every dependency is installed): a skip is a failure.
inline bool SkipsAreFailures() {
    const char* value = std::getenv("FOVRT_REQUIRE_ALL");
    return value && std::strcmp(value, "1") == 0;
}

}  // namespace fovrt::test
