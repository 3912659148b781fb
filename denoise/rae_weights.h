// The recurrent denoising autoencoder's trained weights (Chaitanya et al. 2017) as the training
// code exports them (.raew; layout documented in training/rae_net.py): parsing, the conv order,
// parameter and FLOP counts, hidden-state and memory plans. No inference here
// (denoise/reference/rae_net.h, denoise/vulkan/rae_vk.h), so the memory plan and the bench can read
// a network's shape.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "denoise/params.h"

namespace fovrt {

struct BufferPlan;

// One 3×3 convolution: weight [out][in][3][3] (PyTorch layout), bias [out].
struct RaeConv {
    int out = 0, in = 0;
    std::vector<float> weight;
    std::vector<float> bias;
};

inline constexpr uint32_t kRaeFlagSampleCount = 1;  // input channel 7: log2(spp)/4

struct RaeWeights {
    uint32_t version = 1;
    int inChannels = 7;
    bool sampleCount = false;
    float gamma = 0.2f;
    std::vector<int> widths;     // one per encoder level (L = widths.size())
    std::vector<RaeConv> convs;  // RaeConvOrder's order

    int Levels() const { return int(widths.size()); }
    size_t Parameters() const;
    // 2 × multiply-adds of every conv per full-resolution pixel.
    double FlopsPerPixel() const;
};

// Index of each conv in RaeWeights::convs (the .raew order): encoder l: 4l (feed-forward C),
// 4l+1..4l+3 (R_l: c_in, c_h1, c_h2); bottleneck 4L..4L+3; decoder stage s = 0..L-1 (level
// L-1-s): 4L+4+2s, 4L+5+2s; output 6L+4.
struct RaeConvOrder {
    int levels;
    int Encoder(int l) const { return 4 * l; }
    int Recurrent(int l, int k) const { return 4 * l + 1 + k; }  // l = levels: the bottleneck's
    int Bottleneck() const { return 4 * levels; }
    int Decoder(int level, int k) const { return 4 * levels + 4 + 2 * (levels - 1 - level) + k; }
    int Output() const { return 6 * levels + 4; }
    int Count() const { return 6 * levels + 5; }
};

// Reads a .raew file; fovrt::Error naming the file and what is wrong (magic, version, a conv's
// shape against the widths, truncation, trailing bytes).
RaeWeights LoadRaeWeights(const std::filesystem::path& path);
// The same from bytes in memory (`what` names the source in errors).
RaeWeights ParseRaeWeights(const std::vector<uint8_t>& bytes, const std::string& what);
// Writes `weights` in the same format (tests build seeded networks with it).
void SaveRaeWeights(const std::filesystem::path& path, const RaeWeights& weights);

// Bytes of the hidden state for a (padded) W×H frame: Σ_l w_l·(W/2^l)·(H/2^l)·4 + w_{L-1} at 1/2^L.
size_t RaeHiddenStateBytes(const RaeWeights& weights, int paddedWidth, int paddedHeight);

// The weight file `params.rae.weights` names: as given if it exists, else under the data fovrt
// ships (core/data_dir.h: the installed copy or the source tree), so the committed default works
// from any working directory.
std::filesystem::path ResolveRaeWeightsPath(const DenoiserParams& params);
// Loads it once per path and process (both eyes and every instance share one copy).
std::shared_ptr<const RaeWeights> SharedRaeWeights(const DenoiserParams& params);

// The smallest multiple of 2^levels >= size (frames are zero-padded to it).
inline int RaePaddedSize(int size, int levels) {
    const int m = 1 << levels;
    return (size + m - 1) / m * m;
}

// One tensor of a frame's activations: `channels` planes of width × height floats at `offset`
// (floats) in the one activation buffer the Vulkan host allocates (denoise/vulkan/rae_vk.h).
struct RaeTensorSlot {
    std::string name;  // "rae.input", "rae.enc1.x", "rae.hidden2.A", "rae.dec0.b", "rae.output"
    int channels = 0, width = 0, height = 0;
    size_t offset = 0;  // floats
    bool history = false;  // the hidden state: an A/B pair, one side kept between frames
    size_t Floats() const { return size_t(channels) * size_t(width) * size_t(height); }
};
// Every tensor of one frame at a padded W×H (multiples of 2^L), in network order: input; per
// encoder level l: x (feed-forward conv), a (R's first conv), t (R's second), hidden l A/B (R's
// output), pool (l+1's resolution); the bottleneck as level L (no pool); per decoder level l:
// a, b (its two convs; the first reads the upsampled lower level and hidden l by addressing);
// output (3 channels).
std::vector<RaeTensorSlot> RaeTensorLayout(const RaeWeights& weights, int paddedWidth, int paddedHeight);
// The slot named `name` of a layout (fovrt::Error when absent).
const RaeTensorSlot& FindRaeSlot(const std::vector<RaeTensorSlot>& layout, const std::string& name);

// Every buffer the rae variant holds for one eye at W×H: each tensor of RaeTensorLayout (the
// hidden state's A/B pairs as history; 2 bytes a value with denoise.precision = fp16), the
// weights, and the host-visible staging ring.
std::vector<BufferPlan> PlanRaeMemory(int width, int height, const DenoiserParams& params);
// The staging ring of the rae variant at the padded size: the input's upload and the output's
// download in the activations' storage, each 16-byte aligned, or DenoiserParams::transferRingBytes
// if smaller (vk/transfer_ring.h streams a frame through it).
size_t RaeStagingBytes(const RaeWeights& weights, int paddedWidth, int paddedHeight, const DenoiserParams& params);

}  // namespace fovrt
