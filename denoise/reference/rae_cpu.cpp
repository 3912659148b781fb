#include "denoise/reference/rae_cpu.h"

#include <chrono>

#include "core/cpu_time.h"
#include "core/error.h"
#include "denoise/reference/rae_features.h"

namespace fovrt {
RaeReferenceDenoiser::RaeReferenceDenoiser(std::string name, const DenoiserParams& params)
    : name_(std::move(name)), weights_(SharedRaeWeights(params)), balance_(params.rae.balance) {}

void RaeReferenceDenoiser::Denoise(const FrameInputs& inputs, Plane<vec3>& output) {
    auto start = std::chrono::steady_clock::now();
    if (inputs.cameraCut) state_ = {};
    Tensor features, input, y;
    RaeFeatures(inputs, features);
    const vec3 gains = balance_ ? RaeBalanceGains(features) : vec3(1.0f);
    RaeNetworkInput(features, *weights_, input, gains);
    const double featureMs = MsSince(start);
    start = std::chrono::steady_clock::now();
    double encoderMs = 0.0, decoderMs = 0.0;
    RaeForward(*weights_, input, state_, y, &encoderMs, &decoderMs);
    start = std::chrono::steady_clock::now();
    RaeRemodulate(inputs, y, weights_->gamma, output, gains);
    timings_ = {{"rae_features", featureMs},
                {"rae_encoder", encoderMs},
                {"rae_decoder", decoderMs},
                {"rae_remodulate", MsSince(start)}};
}

}  // namespace fovrt
