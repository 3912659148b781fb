#include "denoise/reference/rae_cpu.h"

#include <chrono>

#include "core/cpu_time.h"
#include "core/error.h"
#include "denoise/reference/rae_features.h"

namespace fovrt {
RaeReferenceDenoiser::RaeReferenceDenoiser(std::string name, const DenoiserParams& params)
    : name_(std::move(name)), weights_(SharedRaeWeights(params)) {}

void RaeReferenceDenoiser::Denoise(const FrameInputs& inputs, Plane<vec3>& output) {
    auto start = std::chrono::steady_clock::now();
    if (inputs.cameraCut) state_ = {};
    Tensor features, input, y;
    RaeFeatures(inputs, features);
    RaeNetworkInput(features, *weights_, input);
    const double featureMs = MsSince(start);
    start = std::chrono::steady_clock::now();
    double encoderMs = 0.0, decoderMs = 0.0;
    RaeForward(*weights_, input, state_, y, &encoderMs, &decoderMs);
    start = std::chrono::steady_clock::now();
    RaeRemodulate(inputs, y, weights_->gamma, output);
    timings_ = {{"rae_features", featureMs},
                {"rae_encoder", encoderMs},
                {"rae_decoder", decoderMs},
                {"rae_remodulate", MsSince(start)}};
}

}  // namespace fovrt
