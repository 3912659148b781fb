// The C++ references run their stages row-parallel (TBB): on one thread and on several they must
// give bit-identical images and identical sample counters, frame after frame (histories included).
#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include <tbb/global_control.h>

#include "denoise/reference/asvgf_ref.h"
#include "denoise/denoiser_factory.h"
#include "denoise_svgf_scenes.h"
#include "test_support.h"

using namespace fovrt;

namespace {

// RandomFrame plus gradient samples (first-wins duplicates included) and a few NaN / negative
// inputs, so every stage and both counters have work.
FrameInputs ThreadsFrame(int w, int h, uint32_t frame) {
    FrameInputs f = test::RandomFrame(w, h, 11, frame);
    std::mt19937 rng(500 + frame);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const ivec2 grid = StratumGridSize(w, h);
    for (int sy = 0; sy < grid.y; ++sy)
        for (int sx = 0; sx < grid.x; ++sx)
            for (int k = u(rng) < 0.3f ? 0 : (u(rng) < 0.2f ? 2 : 1); k > 0; --k) {
                GradientSample s;
                s.stratum = ivec2(sx, sy);
                s.pixel = glm::min(ivec2(sx * kGradientStratumSize, sy * kGradientStratumSize) + 1,
                                   ivec2(w - 1, h - 1));
                s.prevPixel = s.pixel;
                s.newLuminance = 4.0f * u(rng);
                s.oldLuminance = u(rng) < 0.5f ? s.newLuminance : 4.0f * u(rng);
                f.gradientSamples.push_back(s);
            }
    for (int i = 0; i < 40; ++i) {
        const int x = int(u(rng) * float(w)) % w, y = int(u(rng) * float(h)) % h;
        f.direct(x, y) = i % 2 ? vec3(std::numeric_limits<float>::quiet_NaN()) : vec3(-1.0f, 0.5f, 0.5f);
    }
    return f;
}

struct Run {
    std::vector<Plane<vec3>> outputs;
    DenoiseStats stats;
};

Run Denoise(const std::string& name, const DenoiserParams& params, int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
    auto denoiser = CreateDenoiser(name, "cpu", params);
    Run run;
    for (uint32_t frame = 0; frame < 4; ++frame) {
        run.outputs.emplace_back();
        denoiser->Denoise(ThreadsFrame(72, 40, frame), run.outputs.back());
    }
    run.stats = denoiser->Stats();
    return run;
}

}  // namespace

TEST_CASE("asvgf and two-history references: one thread and many give the same bits", "[asvgf][two_history]") {
    for (const char* name :
         {"asvgf", "two-history", "two-history-asvgf", "asvgf-antilag", "two-history-stable", "two-history-stable-firefly",
          "two-history-stable-antilag", "two-history-asvgf-stable-antilag", "two-history-clamp",
          "two-history-stable-clamp"})
        for (bool combined : {false, true}) {
            CAPTURE(name, combined);
            DenoiserParams params;
            params.svgf.filterCombined = combined;
            const Run serial = Denoise(name, params, 1);
            const Run parallel = Denoise(name, params, 4);
            CHECK(serial.stats.nonFiniteSamples > 0);
            CHECK(serial.stats.negativeSamples > 0);
            CHECK(parallel.stats.nonFiniteSamples == serial.stats.nonFiniteSamples);
            CHECK(parallel.stats.negativeSamples == serial.stats.negativeSamples);
            REQUIRE(parallel.outputs.size() == serial.outputs.size());
            for (size_t f = 0; f < serial.outputs.size(); ++f) {
                const Plane<vec3>& a = serial.outputs[f];
                const Plane<vec3>& b = parallel.outputs[f];
                REQUIRE(a.size() == b.size());
                CHECK(std::memcmp(a.data(), b.data(), a.size() * sizeof(vec3)) == 0);
            }
        }
}
