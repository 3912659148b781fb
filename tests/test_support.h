// Helpers shared by the tests: locating data, and skipping with a message when it is absent
// (a skip is reported to ctest as one: test_skip.h).
#pragma once

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <unistd.h>

#include <catch2/catch.hpp>

#include "core/image.h"
#include "core/math.h"
#include "core/rng.h"
#include "test_skip.h"

namespace fovrt::test {

inline std::filesystem::path SourceDir() { return FOVRT_SOURCE_DIR; }

// A whole file's bytes (empty when it cannot be read: the test's own checks then fail on it).
inline std::string ReadFile(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

// ../shared/scenes beside the checkout (or $FOVRT_SHARED_SCENES), empty when absent.
inline std::filesystem::path SharedScenes() {
    if (const char* env = std::getenv("FOVRT_SHARED_SCENES")) return env;
    auto dir = SourceDir().parent_path() / "shared" / "scenes";
    return std::filesystem::exists(dir) ? dir : std::filesystem::path();
}

// ../shared/gaze beside the checkout (headset recordings, see its README), empty when absent.
inline std::filesystem::path SharedGaze() {
    auto dir = SourceDir().parent_path() / "shared" / "gaze";
    return std::filesystem::exists(dir) ? dir : std::filesystem::path();
}

// This process's scratch directory under the system temp dir, "<prefix>-<pid>", created on first
// use and removed when the test executable ends (one per executable: prefix is fixed per file).
inline std::filesystem::path ScratchDir(const std::string& prefix) {
    struct Scratch {
        std::filesystem::path dir;
        explicit Scratch(const std::string& p)
            : dir(std::filesystem::temp_directory_path() / (p + "-" + std::to_string(::getpid()))) {
            std::filesystem::create_directories(dir);
        }
        ~Scratch() {
            std::error_code ignored;
            std::filesystem::remove_all(dir, ignored);
        }
    };
    static const Scratch scratch(prefix);
    return scratch.dir;
}

// An HDR test image with uniform random channels in [0, scale).
inline Plane<vec3> RandomImage(int w, int h, uint64_t seed, float scale = 1.0f) {
    Pcg32 rng(seed);
    Plane<vec3> img(w, h);
    for (size_t i = 0; i < img.size(); ++i)
        img[i] = scale * vec3(rng.NextFloat(), rng.NextFloat(), rng.NextFloat());
    return img;
}

}  // namespace fovrt::test

// Ends the test case as skipped (test_skip.h: the executable then exits with ctest's skip status
// unless another test case failed), or as failed under FOVRT_REQUIRE_ALL=1.
#define FOVRT_SKIP(why)                                                                   \
    do {                                                                                  \
        if (::fovrt::test::SkipsAreFailures())                                            \
            FAIL("not run, and FOVRT_REQUIRE_ALL=1 makes that a failure: " << (why));     \
        ++::fovrt::test::SkippedTestCases();                                              \
        WARN("skipped: " << (why));                                                       \
        std::fprintf(stderr, "skipped: %s\n", std::string(why).c_str());                 \
        return;                                                                           \
    } while (0)

#define FOVRT_REQUIRE_SHARED_SCENES()                                            \
    do {                                                                         \
        if (::fovrt::test::SharedScenes().empty())                               \
            FOVRT_SKIP("../shared/scenes is absent; shared-scene test not run"); \
    } while (0)
