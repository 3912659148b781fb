// The recurrent denoising autoencoder (Chaitanya et al. 2017, §4.1–4.2): its weights as the
// training code exports them (.raew, layout documented in training/rae_net.py), and the C++
// reference of inference that the Vulkan host (denoise/vulkan/rae_vk.*) and PyTorch are held to.
//
// Per frame, with C = conv 3×3 (zero padding) + leaky ReLU 0.1 and R(I, h) = C(C([C(I), h])):
//   encoder l = 0..L-1:  x = C(x); h_l = R_l(x, h_l'); x = maxpool2×2(h_l)
//   bottleneck:          x = C(x); h_L = R_L(x, h_L'); x = h_L
//   decoder l = L-1..0:  x = C(C([upsample2×2(x), h_l]))
//   output:              conv 3×3 → 3 channels, linear
// Concatenations are in PyTorch's channel order ([first, second]); frame sizes must be multiples
// of 2^L (the denoiser pads). The hidden state h_0..h_L is RaeState.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "denoise/rae_weights.h"

namespace fovrt {

// A C×H×W float tensor (one frame, batch 1), channel-major like PyTorch's NCHW.
struct Tensor {
    int c = 0, h = 0, w = 0;
    std::vector<float> data;

    Tensor() = default;
    Tensor(int channels, int height, int width)
        : c(channels), h(height), w(width), data(size_t(channels) * height * width, 0.0f) {}
    float* Channel(int i) { return data.data() + size_t(i) * h * w; }
    const float* Channel(int i) const { return data.data() + size_t(i) * h * w; }
    float& At(int ch, int y, int x) { return data[(size_t(ch) * h + y) * w + x]; }
    float At(int ch, int y, int x) const { return data[(size_t(ch) * h + y) * w + x]; }
    size_t Bytes() const { return data.size() * sizeof(float); }
};

// The recurrent state of one eye: h_0..h_L (empty tensors = zeros, the state after a reset).
struct RaeState {
    std::vector<Tensor> hidden;
    bool Empty() const { return hidden.empty(); }
    size_t Bytes() const;
};

// ---- Layers (the C++ reference each Vulkan shader is tested against) ----
// out = act(conv3×3(in) + bias), zero padding 1; act = leaky ReLU 0.1 when `leaky`.
// `in` may be the concatenation [a, b] given as two tensors (b may be null: a only).
void RaeConv3x3(const RaeConv& conv, const Tensor& a, const Tensor* b, bool leaky, Tensor& out);
void RaeMaxPool2x2(const Tensor& in, Tensor& out);
void RaeUpsample2x2(const Tensor& in, Tensor& out);

// One frame through the network: `in` (weights.inChannels × H × W, H and W multiples of 2^L,
// colour already raised to γ) → `out` (3 × H × W, γ space). `state` is read (empty: zeros) and
// replaced by this frame's hidden state. `encoderMs` / `decoderMs` (optional): wall-clock split
// (encoder + bottleneck, decoder + output conv).
void RaeForward(const RaeWeights& weights, const Tensor& in, RaeState& state, Tensor& out,
                double* encoderMs = nullptr, double* decoderMs = nullptr);

}  // namespace fovrt
