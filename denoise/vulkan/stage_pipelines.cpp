#include "denoise/vulkan/stage_pipelines.h"

#include <span>
#include <vector>

#include "denoise/vulkan/svgf_texel_formats.h"

namespace fovrt {

namespace {

template <size_t N>
std::vector<VkFormat> AsVector(const std::array<VkFormat, N>& formats) {
    return {formats.begin(), formats.end()};
}

// The descriptor formats of the one-channel or the pair layout of `shader`.
std::vector<VkFormat> LayoutFormats(StageShader shader, bool pair, Precision precision) {
#define FOVRT_STAGE_SHADER_FORMATS(id, stem, list, pairList)                                        \
    case StageShader::id:                                                                          \
        return pair ? AsVector(FOVRT_TEXEL_FORMATS(pairList, precision)) : AsVector(FOVRT_TEXEL_FORMATS(list, precision));
    switch (shader) { FOVRT_STAGE_SHADERS(FOVRT_STAGE_SHADER_FORMATS) }
#undef FOVRT_STAGE_SHADER_FORMATS
    return {};
}

}  // namespace

ComputePipeline MakeStagePipeline(VulkanContext& context, const PipelineKey& key, uint32_t pushBytes,
                                  uint32_t maxSets) {
    const std::vector<VkFormat> formats =
        LayoutFormats(key.shader, key.pair, key.fp16 ? Precision::Fp16 : Precision::Fp32);
    const uint32_t bindings = uint32_t(BindingCount(key));
    return ComputePipeline(context, ShaderVariantName(key), bindings, pushBytes, maxSets,
                           std::span<const VkFormat>(formats).first(bindings),
                           std::span<const int32_t>(key.spec.values).first(key.spec.count));
}

}  // namespace fovrt
