#include "denoise/vulkan/stage_pipelines.h"

#include <span>
#include <vector>

#include "denoise/vulkan/svgf_texel_formats.h"

namespace fovrt {

ComputePipeline MakeStagePipeline(VulkanContext& context, const PipelineKey& key, uint32_t pushBytes,
                                  uint32_t maxSets) {
    const std::vector<VkFormat> formats =
        StageTexelFormats(key.shader, key.pair, key.fp16 ? Precision::Fp16 : Precision::Fp32);
    const uint32_t bindings = uint32_t(BindingCount(key));
    return ComputePipeline(context, ShaderVariantName(key), bindings, pushBytes, maxSets,
                           std::span<const VkFormat>(formats).first(bindings),
                           std::span<const int32_t>(key.spec.values).first(key.spec.count));
}

}  // namespace fovrt
