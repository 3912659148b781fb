// main() of every Catch2 test executable: Catch2's own, then a skip (test_skip.h) turned into
// ctest's skip status when nothing failed.
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

#include "test_skip.h"

int main(int argc, char* argv[]) {
    const int failures = Catch::Session().run(argc, argv);
    // Catch2 returns the failure count: never let one that equals the skip code read as a skip.
    if (failures != 0) return failures == FOVRT_TEST_SKIP_CODE ? 1 : failures;
    return fovrt::test::SkippedTestCases() > 0 ? FOVRT_TEST_SKIP_CODE : 0;
}
