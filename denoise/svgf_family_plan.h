// The pass list of the SVGF family (svgf, svgf-weighted, asvgf, two-history, two-history-asvgf):
// one function per pass kind (svgf_family_plan.cpp; the reprojection in reprojection_plan.cpp,
// A-SVGF's gradient in asvgf_plan.cpp, their toolkit in plan_writer.h), each deciding once which
// planes the pass reads and writes and emitting both the reference's stage and the Vulkan
// commands from that decision. The family's passes set the modes the row's flags ask for; the
// mechanisms with passes of their own join at the slots their rows declare
// (denoise/mechanism_passes.h), never by name here.
#pragma once

#include <cstdint>
#include <vector>

#include "denoise/pass_plan.h"
#include "denoise/variants.h"

namespace fovrt {

// The passes of `variant` (family Svgf or TwoHistory) at W×H; `params` as ParamsForVariant
// gives them.
std::vector<PlannedPass> PlanSvgfFamily(const DenoiserVariant& variant, const DenoiserParams& params,
                                        int width, int height);

// The pipeline of one à-trous dispatch (shaders/svgf_atrous.comp): `pair` channels, the step-1
// variant, writing the colour history (the feedback iteration); `unitWeights` only for the
// bench's floor probe (denoise/bench/atrous_probe.h).
PipelineKey AtrousPipeline(const DenoiserParams& params, bool pair, bool step1, bool writeHistory,
                           bool unitWeights = false);

// Specialization constant FOVRT_SPEC_NORMAL_SQUARINGS of the edge-stopping shaders
// (shaders/common/edge_stopping.glsl): k when σn = 2^k exactly (0 ≤ k ≤ 12), else −1.
int32_t NormalWeightSquarings(float sigmaNormal);

// The plane the two-history blend takes q from: the EMA gradient's q, or A-SVGF's λ̂
// (two-history-asvgf).
PlaneId BlendQPlane(const DenoiserVariant& variant);

}  // namespace fovrt
