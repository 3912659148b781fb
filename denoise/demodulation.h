// The shared demodulation step (Zhuang et al. §4.3: "we treat the original methods as a black
// box, and only change the inputs and the outputs of the filtering ... and change the demodulation
// from the diffuse albedo to F_β"). A FrameInputs carries direct / indirect divided by one factor
// (FrameInputs::demodulation, Modulation()) and the factor planes (albedo; fbeta when asked for); every
// denoiser remodulates by Modulation(). A variant named "<name>+brdf" / "<name>+albedo"
// (denoise/variants.h) re-divides the frame's illumination by the factor it asks for before the
// filter sees it, so one render feeds both kinds of variant.
#pragma once

#include <memory>

#include "core/frame_inputs.h"
#include "denoise/denoiser.h"

namespace fovrt {

// `in` with direct and indirect divided by `want`'s factor instead of in.demodulation's:
// illum · from / to per channel (pixels whose target factor is 0, the background, keep theirs;
// fovrt::Error when a surface pixel has none: a frame rendered without the F_β plane).
// Returns `in` itself, copying nothing, when it already is; otherwise fills and returns `scratch`
// (every other plane and field copied unchanged).
const FrameInputs& Redemodulate(const FrameInputs& in, Demodulation want, FrameInputs& scratch);

// Wraps a denoiser so that it filters illumination demodulated by `want` (the hosts themselves
// only ever remodulate by the frame's Modulation()). Name() is `name` (with its suffix).
std::unique_ptr<Denoiser> WithDemodulation(std::unique_ptr<Denoiser> inner, Demodulation want,
                                           std::string name);

}  // namespace fovrt
