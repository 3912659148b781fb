// Temporal stability of the committed RAE weights (issue #14, SPEC §12), a measurement rather than
// a test: on a static view of `cornell` (96×64, uniform 1 spp) where only the Monte Carlo noise
// changes between frames, the temporal error (SVGF §5.4: mean |lum_t − lum_{t−1}| over frames
// 2..n−1 of eye 0) of each RAE variant with its recurrent state carried and with the state reset
// before every frame. The paper's claim is that the first is lower; the README reports whether
// the committed weights make it true (they did not: it is a ctest again once they do).
// Usage: rae_temporal_probe [frames = 8 [rae.raew [rae-spp.raew]]] (default: the committed weights)
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "app/frame_pipeline.h"
#include "app_test_configs.h"
#include "denoise/reference/rae_cpu.h"

using namespace fovrt;

namespace {

float Lum(const vec3& c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

// Frame 0 has no predecessor, and frame 1 still carries the reset of frame 0 in both runs.
double TemporalError(const std::string& variant, bool resetEveryFrame, int frames, const RaeParams& weights) {
    RunConfig config = test::SmallCornellConfig();
    config.denoise.params.rae = weights;
    config.camera.width = 96;
    config.camera.height = 64;
    config.foveation.model = "uniform";
    config.foveation.uniformSpp = 1;
    FramePipeline pipeline(config);
    RaeReferenceDenoiser denoiser(variant, ParamsForVariant(FindDenoiserVariant(variant), config.denoise.params));
    StereoFrame frame;
    Plane<vec3> out, prev;
    double sum = 0.0;
    int counted = 0;
    for (int i = 0; i < frames; ++i) {
        pipeline.Render(uint32_t(i), frame);
        if (resetEveryFrame) denoiser.Reset();
        denoiser.Denoise(frame.eyes[0].inputs, out);
        if (i >= 2) {
            double e = 0.0;
            for (size_t p = 0; p < out.size(); ++p) e += std::abs(Lum(out[p]) - Lum(prev[p]));
            sum += e / double(out.size());
            ++counted;
        }
        prev = out;
    }
    return sum / counted;
}

}  // namespace

int main(int argc, char** argv) {
    const int frames = argc > 1 ? std::atoi(argv[1]) : 8;
    if (frames < 3) {
        std::fprintf(stderr, "rae_temporal_probe: frames must be >= 3 (got '%s')\n", argv[1]);
        return 2;
    }
    RaeParams weights;
    if (argc > 2) weights.weights = argv[2];
    if (argc > 3) weights.weightsSpp = argv[3];
    try {
        for (const char* variant : {"rae", "rae-spp"}) {
            const double carried = TemporalError(variant, false, frames, weights);
            const double reset = TemporalError(variant, true, frames, weights);
            std::printf("%-8s temporal error with state %.5f, reset every frame %.5f: %s\n", variant, carried, reset,
                        carried < reset ? "the state lowers it" : "the state does NOT lower it");
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "rae_temporal_probe: %s\n", e.what());
        return 1;
    }
}
