// The floor of an à-trous iteration on the Vulkan device in use (`fovrt bench --denoisers`): the
// real svgf_atrous_pair dispatch (both channels, 2×2 blocks) on synthetic planes, timed as the
// denoisers run it and with every edge-stopping weight 1 (specialization constant
// FOVRT_SPEC_ATROUS_UNIT_WEIGHTS: the same fetches, sums and stores, none of the weight
// arithmetic). Printed against the pass's bytes-moved bound, the pair tells whether what separates
// the pass from the bandwidth bound is data movement or the weights — measured, not assumed.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/math.h"
#include "vk/allocator.h"
#include "vk/pipeline.h"
#include "vk/recorder.h"

namespace fovrt {

class VulkanContext;

// Synthetic inputs of one à-trous dispatch: guide (normal, depth; depth −1 = background),
// depth gradient, and two illumination + variance planes. Edges, a depth ramp and background
// pixels, so every weight term is live.
struct AtrousProbeImage {
    int width = 0, height = 0;
    std::vector<vec4> guide, illum0, illum1;
    std::vector<vec2> depthGradient;
};
AtrousProbeImage MakeAtrousProbeImage(int width, int height, uint32_t seed);

struct AtrousProbeRun {
    std::vector<vec4> out0, out1;  // illumination + variance of both channels
    double ms = 0.0;               // best of `runs` (GPU timestamps; wall clock without them)
};

// One svgf_atrous_pair dispatch at `step` (not the step-1 variant), as the denoisers record it:
// the image uploaded and both pipelines (as run, unit weights) built once, then run at will.
class AtrousProbe {
public:
    AtrousProbe(VulkanContext& context, const AtrousProbeImage& image, int step);
    AtrousProbeRun Run(bool unitWeights, int runs = 1);

private:
    VulkanContext& context_;
    int width_, height_, step_;
    Buffer guide_, depthGradient_, history_, staging_;
    std::array<Buffer, 2> in_, out_;
    std::array<ComputePipeline, 2> pipelines_;  // [unitWeights]
    std::array<VkDescriptorSet, 2> sets_{};
    TimestampPool timestamps_;
};

struct AtrousFloor {
    int width = 0, height = 0, step = 2;
    double fullMs = 0.0;         // the pass as the denoisers run it
    double unitWeightsMs = 0.0;  // every edge-stopping weight 1
    double bytesPerPixel = 0.0;  // its byte model (denoise/bench/pass_bytes.h, svgf "atrous1")
};
AtrousFloor MeasureAtrousFloor(VulkanContext& context, int width, int height, int runs = 3);

}  // namespace fovrt
