// gaze.blink: a trace's NaN rows are blinks. "hold" foveates on the last valid direction (the
// spp map stays foveated); "uniform" renders the blink frames with a uniform spp map at the
// foveated map's mean (the same rays, spread evenly). Frames with a valid sample are untouched.
#include <cmath>
#include <fstream>

#include "app_test_configs.h"
#include "config/config.h"
#include "core/error.h"
#include "pipeline/frame_pipeline.h"
#include "test_support.h"

using namespace fovrt;
namespace fs = std::filesystem;

namespace {

// Trace rows every 33 ms; rows 66 and 100 ms are a blink, so frames 1..3 (33.3, 66.7, 100 ms at
// 30 fps) have an invalid bracketing sample and frames 0 and 4 do not.
fs::path WriteBlinkTrace(const fs::path& dir) {
    const fs::path path = dir / "blink.csv";
    std::ofstream(path) << "n,x,y\n0,0,0\n33,1,0\n66,NaN,NaN\n100,NaN,NaN\n133,5,1\n166,6,1\n";
    return path;
}

RunConfig SmallCornell(const fs::path& trace, const std::string& blink) {
    RunConfig config = test::SmallCornellConfig();
    config.gaze.source = "trace";
    config.gaze.tracePath = trace.string();
    config.gaze.blink = blink;
    return config;
}

bool IsUniform(const Plane<uint16_t>& map) {
    for (size_t p = 0; p < map.size(); ++p)
        if (map[p] != map[0]) return false;
    return true;
}

uint64_t Total(const Plane<uint16_t>& map) {
    uint64_t total = 0;
    for (size_t p = 0; p < map.size(); ++p) total += map[p];
    return total;
}

}  // namespace

TEST_CASE("gaze.blink: hold keeps the foveated map, uniform spreads its mean during a blink", "[app][gaze]") {
    const fs::path dir = test::ScratchDir("fovrt-blink-test");
    const fs::path trace = WriteBlinkTrace(dir);
    FramePipeline hold(SmallCornell(trace, "hold"));
    FramePipeline uniform(SmallCornell(trace, "uniform"));
    StereoFrame held, even;
    for (uint32_t f = 0; f < 5; ++f) {
        INFO("frame " << f);
        hold.Render(hold.RequestAt(f), held);
        uniform.Render(uniform.RequestAt(f), even);
        const bool blink = f >= 1 && f <= 3;
        CHECK(held.gaze.valid == !blink);
        CHECK(even.gaze.valid == !blink);
        for (int eye = 0; eye < 2; ++eye) {
            const Plane<uint16_t>& heldMap = held.eyes[size_t(eye)].sppMap;
            const Plane<uint16_t>& evenMap = even.eyes[size_t(eye)].sppMap;
            CHECK(!IsUniform(heldMap));  // hold: foveated on the last valid direction
            CHECK(IsUniform(evenMap) == blink);
            CHECK(even.eyes[size_t(eye)].uniformForBlink == blink);
            CHECK(!held.eyes[size_t(eye)].uniformForBlink);
            if (blink) {
                // The foveated map's rays, spread evenly (the mean rounded to a whole spp).
                const double n = double(evenMap.size());
                CHECK(std::abs(double(Total(evenMap)) - double(Total(heldMap))) <= n / 2.0);
            } else {
                CHECK(Total(evenMap) == Total(heldMap));
            }
        }
    }
}

TEST_CASE("gaze.blink: only hold and uniform, named in the error", "[app][gaze]") {
    RunConfig config = DefaultConfig();
    config.gaze.blink = "close";
    CHECK_THROWS_WITH(ValidateGazeParams(config.gaze), Catch::Contains("gaze.blink"));
}
