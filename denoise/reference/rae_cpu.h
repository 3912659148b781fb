// RaeReferenceDenoiser: the `rae` variant on the CPU (Chaitanya et al. 2017) — FrameInputs →
// features → RaeForward → remodulated colour, with one eye's hidden state kept between frames and
// dropped on Reset() and on camera cuts. The Vulkan host (denoise/vulkan/rae_vk.*) is held to it.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "denoise/denoiser.h"
#include "denoise/reference/rae_net.h"

namespace fovrt {

class RaeReferenceDenoiser : public Denoiser {
public:
    RaeReferenceDenoiser(std::string name, const DenoiserParams& params);
    std::string Name() const override { return name_; }
    std::string Backend() const override { return "cpu"; }
    void Reset() override { state_ = {}; }
    void Denoise(const FrameInputs& inputs, Plane<vec3>& output) override;
    std::vector<PassTiming> LastTimings() const override { return timings_; }
    DenoiseStats Stats() const override { return {}; }

    const RaeWeights& Weights() const { return *weights_; }
    const RaeState& State() const { return state_; }

private:
    bool ReadDebugPlane(DebugViewId, Plane<float>&) override { return false; }

    std::string name_;
    std::shared_ptr<const RaeWeights> weights_;
    bool balance_;  // the `balance` mechanism (RaeBalanceGains)
    RaeState state_;
    std::vector<PassTiming> timings_;
};

}  // namespace fovrt
