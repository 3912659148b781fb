// The compute shaders of the SVGF-family passes, one row each: the stem shaders/CMakeLists.txt
// compiles (shaders/<stem>.comp) and its binding lists (shaders/bindings/<stem>.h) for one
// channel and for the "_pair" variant (the same list where the shader has no pair variant). The
// pass plan names shaders by these ids; the Vulkan host expands the lists into descriptor
// layouts (denoise/vulkan/stage_pipelines.h). Macros and an enum only: no Vulkan here.
#pragma once

#include <cstdint>

#include "shaders/common/two_history_constants.glsl"
#include "shaders/shared_constants.h"

namespace fovrt {

// X(id, stem, one-channel binding list, pair binding list)
#define FOVRT_STAGE_SHADERS(X)                                                                   \
    X(PackGuide, "svgf_pack_guide", SVGF_GUIDE_BINDING_LIST, SVGF_GUIDE_BINDING_LIST)            \
    X(SvgfReproject, "svgf_reproject", SVGF_REPROJECT_BINDING_LIST,                              \
      SVGF_REPROJECT_PAIR_ALL_BINDING_LIST)                                                      \
    X(MomentsClassify, "svgf_moments_classify", SVGF_CLASSIFY_BINDING_LIST,                      \
      SVGF_CLASSIFY_BINDING_LIST)                                                                \
    X(FilterMoments, "svgf_filter_moments", SVGF_MOMENTS_BINDING_LIST, SVGF_MOMENTS_BINDING_LIST) \
    X(Atrous, "svgf_atrous", SVGF_ATROUS_BINDING_LIST, SVGF_ATROUS_PAIR_ALL_BINDING_LIST)        \
    X(Modulate, "svgf_modulate", SVGF_MODULATE_BINDING_LIST, SVGF_MODULATE_BINDING_LIST)         \
    X(TwoHistoryReproject, "two_history_reproject", TH_REPROJECT_BINDING_LIST,                   \
      TH_REPROJECT_PAIR_ALL_BINDING_LIST)                                                        \
    X(TwoHistoryGradient, "two_history_gradient", TH_GRADIENT_BINDING_LIST,                      \
      TH_GRADIENT_BINDING_LIST)                                                                  \
    X(TwoHistoryChoice, "two_history_choice", TH_CHOICE_BINDING_LIST, TH_CHOICE_BINDING_LIST)    \
    X(TwoHistoryBlend, "two_history_blend", TH_BLEND_BINDING_LIST, TH_BLEND_BINDING_LIST)        \
    X(TwoHistoryStabilize, "two_history_stabilize", TH_STABILIZE_BINDING_LIST,                   \
      TH_STABILIZE_BINDING_LIST)                                                                 \
    X(AsvgfClaim, "asvgf_gradient_claim", ASVGF_CLAIM_BINDING_LIST, ASVGF_CLAIM_BINDING_LIST)    \
    X(AsvgfGather, "asvgf_gradient_gather", ASVGF_GATHER_BINDING_LIST, ASVGF_GATHER_BINDING_LIST) \
    X(AsvgfSigma, "asvgf_stratum_sigma", ASVGF_SIGMA_BINDING_LIST, ASVGF_SIGMA_BINDING_LIST)     \
    X(AsvgfAtrous, "asvgf_gradient_atrous", ASVGF_ATROUS_BINDING_LIST, ASVGF_ATROUS_BINDING_LIST) \
    X(AsvgfAlpha, "asvgf_alpha", ASVGF_ALPHA_BINDING_LIST, ASVGF_ALPHA_BINDING_LIST)

#define FOVRT_STAGE_SHADER_ID(id, stem, list, pairList) id,
enum class StageShader : uint8_t { FOVRT_STAGE_SHADERS(FOVRT_STAGE_SHADER_ID) };
#undef FOVRT_STAGE_SHADER_ID

}  // namespace fovrt
