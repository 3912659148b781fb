// Temporal error of an RAE variant with its recurrent state carried and with the state reset
// before every frame (issue #14's temporal-stability claim), shared by app_rae_temporal_test and
// tests/tools/rae_temporal_probe. Header only: both link fovrt_app.
#pragma once

#include <string>
#include <vector>

#include "app_test_configs.h"
#include "denoise/denoiser_factory.h"
#include "metrics/image_metrics.h"
#include "pipeline/frame_pipeline.h"

namespace fovrt::test {

struct RaeTemporalSetup {
    std::string scene = "cornell";
    int width = 96, height = 64, frames = 16, first = 0;
    bool foveated = false;  // false: uniform 1 spp; true: the default disc (8 spp inside, 1 outside)
    RaeParams weights;      // default: the committed weights
};

struct RaeTemporalSeries {
    std::vector<double> temporal;  // [i] = mean |lum_i − lum_{i−1}| of eye 0 (SVGF §5.4); [0] = 0
    std::vector<double> meanLum;   // mean output luminance per frame
    std::vector<vec3> meanColour;  // mean output colour per frame
    // Mean over frames 2..n−1: frame 0 has no predecessor, and frame 1 still carries the reset
    // of frame 0 in both runs.
    double Mean() const {
        double sum = 0.0;
        for (size_t i = 2; i < temporal.size(); ++i) sum += temporal[i];
        return sum / double(temporal.size() - 2);
    }
    // The mean colour over the same frames.
    vec3 MeanColour() const { return MeanOverFrames(meanColour); }
    static vec3 MeanOverFrames(const std::vector<vec3>& perFrame) {
        glm::dvec3 sum(0.0);
        for (size_t i = 2; i < perFrame.size(); ++i) sum += glm::dvec3(perFrame[i]);
        return vec3(sum / double(perFrame.size() - 2));
    }
};

inline vec3 MeanColour(const Plane<vec3>& image) {
    glm::dvec3 sum(0.0);
    for (size_t q = 0; q < image.size(); ++q) sum += glm::dvec3(image[q]);
    return vec3(sum / double(image.size()));
}

inline RunConfig RaeTemporalConfig(const RaeTemporalSetup& p) {
    RunConfig config = SmallCornellConfig();
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
    return config;
}

inline RaeTemporalSeries RaeTemporalError(const RaeTemporalSetup& p, const std::string& variant, bool resetEveryFrame) {
    const RunConfig config = RaeTemporalConfig(p);
    FramePipeline pipeline(config);
    // Any denoiser on the C++ reference (svgf is the tests' control for the mean colour).
    const std::unique_ptr<Denoiser> denoiser =
        CreateDenoiser(variant, "cpu", ParamsForDenoiser(variant, config.denoise.params));
    StereoFrame frame;
    Plane<vec3> out, prev;
    RaeTemporalSeries s;
    for (int i = 0; i < p.frames; ++i) {
        pipeline.Render(uint32_t(p.first + i), frame);
        if (resetEveryFrame) denoiser->Reset();
        denoiser->Denoise(frame.eyes[0].inputs, out);
        double l = 0.0;
        for (size_t q = 0; q < out.size(); ++q) l += Luminance(out[q]);
        s.temporal.push_back(i > 0 ? TemporalError(out, prev) : 0.0);  // the experiments' measure
        s.meanLum.push_back(l / double(out.size()));
        s.meanColour.push_back(MeanColour(out));
        prev = out;
    }
    return s;
}

// The mean colour of eye 0's `spp`-sample reference at each frame of `p` (index as the series').
inline std::vector<vec3> RaeReferenceMeanColour(const RaeTemporalSetup& p, int spp) {
    FramePipeline pipeline(RaeTemporalConfig(p));
    std::vector<vec3> means;
    Plane<vec3> reference;
    for (int i = 0; i < p.frames; ++i) {
        const uint32_t frame = uint32_t(p.first + i);
        pipeline.SetFrame(frame);
        pipeline.GetRenderer().RenderReference(0, pipeline.RigAt(frame).Eye(0), spp, frame, reference);
        means.push_back(MeanColour(reference));
    }
    return means;
}

}  // namespace fovrt::test
