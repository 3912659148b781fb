// SVGF on the CPU: the C++ reference stages (svgf_ref.h) composed into a Denoiser, one call per
// stage as in the paper: reproject → filter moments → à-trous ×N (feedback of iteration k) →
// modulate. Also the fallback backend when no Vulkan device exists. Handles "svgf" and
// "svgf-weighted" (params.svgf.weightBySampleCount).
#pragma once

#include <chrono>
#include <string>
#include <vector>

#include "denoise/denoiser.h"
#include "denoise/reference/svgf_ref.h"

namespace fovrt {

class SvgfReferenceDenoiser : public Denoiser {
public:
    SvgfReferenceDenoiser(std::string name, const DenoiserParams& params);
    std::string Name() const override { return name_; }
    std::string Backend() const override { return "cpu"; }
    void Reset() override;
    // New parameters: drops every history through Reset().
    void SetParams(const DenoiserParams& params);
    void Denoise(const FrameInputs& inputs, Plane<vec3>& output) override;
    std::vector<PassTiming> LastTimings() const override { return timings_; }
    DenoiseStats Stats() const override { return stats_; }

    // Read access for tests and composed denoisers: this frame's history of channel c (after
    // Denoise), and the last à-trous output.
    const SvgfHistory& CurrentHistory(size_t channel) const { return channels_[channel].hist[parity_ ^ 1]; }
    const Plane<vec4>& Filtered(size_t channel) const { return channels_[channel].filtered; }
    // Ping-pong planes: after Denoise, illum 0 holds the reprojection (no à-trous) or the last
    // even à-trous iteration; illum 1 the filtered moments or the last odd iteration.
    const Plane<vec4>& Illum(size_t channel, int k) const { return channels_[channel].illum[k]; }
    size_t ChannelCount() const { return channels_.size(); }

private:
    bool ReadDebugPlane(DebugViewId view, Plane<float>& out) override;

    struct Channel {
        SvgfHistory hist[2];  // A/B: hist[parity] is written this frame
        Plane<vec4> illum[2];
        Plane<vec4> filtered;
    };
    void Allocate(int width, int height);

    std::string name_;
    DenoiserParams params_;
    int width_ = 0, height_ = 0;
    int parity_ = 0;
    bool hasFrame_ = false;  // a Denoise() since construction, Reset() or a resize (debug views)
    SvgfGeometryPlanes prevGeometry_;
    std::vector<Channel> channels_;
    std::vector<PassTiming> timings_;
    DenoiseStats stats_;
};

}  // namespace fovrt
