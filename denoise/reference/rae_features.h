// What the recurrent denoising autoencoder sees of a frame and how its output becomes a colour
// (Chaitanya et al. 2017, §3.2 and §4.4). One definition for `fovrt dataset` (training files), the
// C++ reference and the Vulkan host, so training and inference read identical inputs.
//
// Feature channels (kRaeFeatureChannels, in this order; the .raew header says how many a network
// reads: 7, or 8 with the sample-count extension):
//   0-2  direct + indirect illumination, demodulated by albedo (FrameInputs already is), linear HDR;
//        NaN/Inf and negatives → 0. The network sees it raised to γ (RaeNetworkInput). A surface
//        pixel without a path sample (sampleCount 0: a periphery below 1 spp) is filled from its
//        sampled neighbours (RaeFillEmptyPixels) rather than seen black.
//   3-4  view-space shading normal x, y (camera.View()); 0 for background
//   5    depth d/(d + 1), d = linear depth in metres; 1 for background
//   6    roughness (FrameInputs::roughness)
//   7    log2(max(sample count, 1))/4: 0 at 1 spp, 1 at 16 spp (the foveated extension); a filled
//        empty pixel reads what the pixels it was filled from read: its colour is their mean, at
//        least as converged as they are. Read as one sample instead, rae-spp takes the mask's
//        pattern for noise: on a still box scene under a moving quarter mask, relMSE 0.21 against
//        0.068 this way (tests/app_zero_samples_convergence_test.cpp).
// Frames are zero-padded at the right and bottom to multiples of 2^L; the output is cropped.
#pragma once

#include <cstdint>
#include <vector>

#include "core/frame_inputs.h"
#include "core/image.h"
#include "denoise/reference/rae_net.h"

namespace fovrt {

inline constexpr int kRaeFeatureChannels = 8;

// The raw features of `in` (colour linear) at W×H (no padding): the dataset's input planes.
void RaeFeatures(const FrameInputs& in, Tensor& features);
// Push-pull hole filling (Gortler et al. 1996, the Lumigraph's pull-push) of channels 0-2 and 7
// of a W×H `features`: each pixel marked in `fill` takes the mean of the pixels marked in `known`
// within the smallest enclosing aligned 2^k × 2^k block that holds any (pull: each coarser level
// averages its known 2×2 children, weighted by how many known pixels each stands for; push: a
// pixel with none takes its parent's value). Every other pixel is left as it is; with no known
// pixel at all the filled ones become 0. The network has no notion of an empty pixel: it gets a
// spatial estimate from the neighbours, as the SVGF family's spatial filter gives one.
void RaeFillEmptyPixels(const std::vector<uint8_t>& known, const std::vector<uint8_t>& fill, Tensor& features);
// The `balance` mechanism's per-channel gains: g_c = m̄ / m_c, m_c the mean of colour channel c of
// `features` over the frame and m̄ the mean of the three, so that g · colour is grey on average; 1
// for a channel holding under 1e-4 of m̄ (no light to balance) and for a black frame. The network
// runs on g · colour, and its output is divided by g again (RaeRemodulate): a global colour cast
// (an orange light) passes through it unchanged instead of being pulled towards the grey that most
// training illumination is.
vec3 RaeBalanceGains(const Tensor& features);
// The network's input: the first weights.inChannels channels of `features`, colour times `gains`
// raised to γ, zero-padded to multiples of 2^L.
void RaeNetworkInput(const Tensor& features, const RaeWeights& weights, Tensor& input,
                     vec3 gains = vec3(1.0f));
// The training target of a reference image: (reference − emission) / albedo where a surface was
// hit (albedo ≥ 1e-3), 0 for background; 3 × H × W, linear.
void RaeTarget(const FrameInputs& in, const Plane<vec3>& reference, Tensor& target);
// The colour: albedo · max(y, 0)^(1/γ) / gains + emission of the network's output `y` (padded
// size; the top-left W×H is read), `gains` those the input was multiplied by.
void RaeRemodulate(const FrameInputs& in, const Tensor& y, float gamma, Plane<vec3>& output,
                   vec3 gains = vec3(1.0f));

}  // namespace fovrt
