// Temporal stability of RAE weights (issue #14, SPEC §12), a measurement: on a view of a scene
// (default: the static `cornell` at 96×64, uniform 1 spp) the temporal error (SVGF §5.4: mean
// |lum_t − lum_{t−1}| of eye 0, frames 2..n−1) of each RAE variant with its recurrent state carried
// and with the state reset before every frame. The paper's claim is that the first is lower.
// Usage: rae_temporal_probe [options]
//   --frames N (8)  --scene NAME (cornell)  --width W (96)  --height H (64)  --first F (0)
//   --foveated (the default disc instead of uniform 1 spp)  --per-frame (one line per frame)
//   --weights rae.raew  --weights-spp rae-spp.raew (default: the committed weights)
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "app/frame_pipeline.h"
#include "app_test_configs.h"
#include "denoise/reference/rae_cpu.h"

using namespace fovrt;

namespace {

struct Probe {
    std::string scene = "cornell";
    int width = 96, height = 64, frames = 8, first = 0;
    bool foveated = false, perFrame = false;
    RaeParams weights;
};

float Lum(const vec3& c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

struct Series {
    std::vector<double> temporal;  // [i] = mean |lum_i − lum_{i−1}|, i >= 1 ([0] = 0)
    std::vector<double> meanLum;   // mean output luminance per frame
};

Series Run(const Probe& p, const std::string& variant, bool resetEveryFrame) {
    RunConfig config = test::SmallCornellConfig();
    config.scene.name = p.scene;
    config.denoise.params.rae = p.weights;
    config.camera.width = p.width;
    config.camera.height = p.height;
    if (p.foveated) {
        config.foveation.radiusPx = 200.0f;
        config.foveation.radiusReferenceWidth = 1280;
    } else {
        config.foveation.model = "uniform";
        config.foveation.uniformSpp = 1;
    }
    FramePipeline pipeline(config);
    RaeReferenceDenoiser denoiser(variant, ParamsForVariant(FindDenoiserVariant(variant), config.denoise.params));
    StereoFrame frame;
    Plane<vec3> out, prev;
    Series s;
    for (int i = 0; i < p.frames; ++i) {
        pipeline.Render(uint32_t(p.first + i), frame);
        if (resetEveryFrame) denoiser.Reset();
        denoiser.Denoise(frame.eyes[0].inputs, out);
        double e = 0.0, l = 0.0;
        for (size_t q = 0; q < out.size(); ++q) {
            l += Lum(out[q]);
            if (i > 0) e += std::abs(Lum(out[q]) - Lum(prev[q]));
        }
        s.temporal.push_back(e / double(out.size()));
        s.meanLum.push_back(l / double(out.size()));
        prev = out;
    }
    return s;
}

// Frame 0 has no predecessor, and frame 1 still carries the reset of frame 0 in both runs.
double Mean(const std::vector<double>& v) {
    double sum = 0.0;
    for (size_t i = 2; i < v.size(); ++i) sum += v[i];
    return sum / double(v.size() - 2);
}

}  // namespace

int main(int argc, char** argv) {
    Probe p;
    for (int a = 1; a < argc; ++a) {
        const std::string arg = argv[a];
        auto value = [&]() -> const char* {
            if (a + 1 >= argc) {
                std::fprintf(stderr, "rae_temporal_probe: %s needs a value\n", arg.c_str());
                std::exit(2);
            }
            return argv[++a];
        };
        if (arg == "--frames") p.frames = std::atoi(value());
        else if (arg == "--scene") p.scene = value();
        else if (arg == "--width") p.width = std::atoi(value());
        else if (arg == "--height") p.height = std::atoi(value());
        else if (arg == "--first") p.first = std::atoi(value());
        else if (arg == "--foveated") p.foveated = true;
        else if (arg == "--per-frame") p.perFrame = true;
        else if (arg == "--weights") p.weights.weights = value();
        else if (arg == "--weights-spp") p.weights.weightsSpp = value();
        else {
            std::fprintf(stderr, "rae_temporal_probe: unknown argument '%s'\n", arg.c_str());
            return 2;
        }
    }
    if (p.frames < 3) {
        std::fprintf(stderr, "rae_temporal_probe: --frames must be >= 3\n");
        return 2;
    }
    try {
        std::printf("%s %dx%d %s, frames %d..%d\n", p.scene.c_str(), p.width, p.height,
                    p.foveated ? "foveated disc" : "uniform 1 spp", p.first, p.first + p.frames - 1);
        for (const char* variant : {"rae", "rae-spp"}) {
            const Series carried = Run(p, variant, false);
            const Series reset = Run(p, variant, true);
            if (p.perFrame)
                for (int i = 1; i < p.frames; ++i)
                    std::printf("  %-8s frame %3d temporal state %.5f reset %.5f   mean lum state %.4f reset %.4f\n",
                                variant, i, carried.temporal[size_t(i)], reset.temporal[size_t(i)],
                                carried.meanLum[size_t(i)], reset.meanLum[size_t(i)]);
            const double c = Mean(carried.temporal), r = Mean(reset.temporal);
            std::printf("%-8s temporal error with state %.5f, reset every frame %.5f (ratio %.3f): %s\n", variant, c,
                        r, c / r, c < r ? "the state lowers it" : "the state does NOT lower it");
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "rae_temporal_probe: %s\n", e.what());
        return 1;
    }
}
