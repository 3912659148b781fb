// Temporal stability of RAE weights (issue #14, SPEC §12), measured: the temporal error (mean
// |lum_t − lum_{t−1}| of eye 0 over frames 2..n−1) of each RAE variant with its recurrent state
// carried and with the state reset before every frame, on one scene and spp mode, optionally per
// frame; and each channel's mean colour with the state against a reference's (svgf beside it as
// the measure's control). app_rae_temporal_test asserts both for the committed weights; this tool
// measures other scenes, lengths and weight files (training/README.md).
// Usage: rae_temporal_probe [options]
//   --frames N (8)  --scene NAME (cornell)  --width W (96)  --height H (64)  --first F (0)
//   --foveated (the default disc instead of uniform 1 spp)  --per-frame (one line per frame)
//   --weights rae.raew  --weights-spp rae-spp.raew (default: the committed weights)
//   --reference-spp N (64): the reference whose mean colour the output's is compared with
//   --balance: rae+balance and rae+spp+balance instead of rae and rae-spp
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "rae_temporal.h"

using namespace fovrt;
using fovrt::test::RaeTemporalError;

int main(int argc, char** argv) {
    test::RaeTemporalSetup p;
    p.frames = 8;
    bool perFrame = false;
    bool balance = false;  // the variants with the `balance` mechanism (rae+balance, rae+spp+balance)
    int referenceSpp = 64;
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
        else if (arg == "--per-frame") perFrame = true;
        else if (arg == "--weights") p.weights.weights = value();
        else if (arg == "--weights-spp") p.weights.weightsSpp = value();
        else if (arg == "--reference-spp") referenceSpp = std::atoi(value());
        else if (arg == "--balance") balance = true;
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
        const vec3 reference = test::RaeTemporalSeries::MeanOverFrames(test::RaeReferenceMeanColour(p, referenceSpp));
        const vec3 control = RaeTemporalError(p, "svgf", false).MeanColour() / reference;
        std::printf("svgf     mean colour / the %d-spp reference's: R %.3f G %.3f B %.3f (the measure's control)\n",
                    referenceSpp, control.x, control.y, control.z);
        for (const std::string& variant : balance ? std::vector<std::string>{"rae+balance", "rae+spp+balance"}
                                                 : std::vector<std::string>{"rae", "rae-spp"}) {
            const auto carried = RaeTemporalError(p, variant, false);
            const auto reset = RaeTemporalError(p, variant, true);
            if (perFrame)
                for (int i = 1; i < p.frames; ++i)
                    std::printf("  %-8s frame %3d temporal state %.5f reset %.5f   mean lum state %.4f reset %.4f\n",
                                variant.c_str(), i, carried.temporal[size_t(i)], reset.temporal[size_t(i)],
                                carried.meanLum[size_t(i)], reset.meanLum[size_t(i)]);
            const double c = carried.Mean(), r = reset.Mean();
            std::printf("%-8s temporal error with state %.5f, reset every frame %.5f (ratio %.3f): %s\n", variant.c_str(), c,
                        r, c / r, c < r ? "the state lowers it" : "the state does NOT lower it");
            const vec3 mean = carried.MeanColour();
            std::printf("%-8s mean colour / the %d-spp reference's: R %.3f G %.3f B %.3f\n", variant.c_str(), referenceSpp,
                        mean.x / reference.x, mean.y / reference.y, mean.z / reference.z);
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "rae_temporal_probe: %s\n", e.what());
        return 1;
    }
}
