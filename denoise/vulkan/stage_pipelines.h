// The Vulkan pipeline of a planned dispatch (denoise/pass_plan.h PipelineKey): the shader variant
// from the embedded registry, the descriptor layout of its binding list (denoise/stage_shaders.h;
// uniform texel buffers where the list says so, history planes in their 16-bit format in fp16)
// and its specialization constants.
#pragma once

#include <cstdint>

#include "denoise/pass_plan.h"
#include "vk/context.h"
#include "vk/pipeline.h"

namespace fovrt {

// `pushBytes` of push constants; up to `maxSets` descriptor sets.
ComputePipeline MakeStagePipeline(VulkanContext& context, const PipelineKey& key, uint32_t pushBytes,
                                  uint32_t maxSets);

}  // namespace fovrt
