// What a mechanism's row (kMechanisms, denoise/variants.cpp) declares of its plan fragment: which
// passes of its own it adds to its family's frame, and the slot of the frame where they run. The
// fragments are written with the plan's toolkit (denoise/mechanism_passes.h); this header names
// them only, so that the rows stay below the plan. A mechanism that switches a mode of a family
// pass (weighted, firefly, clamp, anti-lag's reprojection bit) adds no pass: the family pass sets
// the mode and its stage carries it to the reference.
#pragma once

#include <cstdint>

namespace fovrt {

// Where a mechanism's passes join the family's frame (PlanSvgfFamily).
enum class FrameSlot : uint8_t {
    BeforeGuide,    // after the upload, before the guide: reads this frame's inputs (A-SVGF's gradient)
    AfterVariance,  // after the variance estimate, before the blend and à-trous (the EMA gradient's q)
    BeforeBlend,    // just before the two-history blend (the held choice it reads)
    AfterFilter,    // after the last à-trous iteration, before modulation (stabilisation)
};

// A mechanism's own passes, one plan fragment each (denoise/mechanism_passes.h).
enum class MechanismPass : uint8_t { None, AsvgfGradient, EmaGradient, HeldChoice, Stabilize };

struct MechanismPasses {
    FrameSlot slot = FrameSlot::BeforeGuide;
    MechanismPass pass = MechanismPass::None;  // None: the mechanism adds no pass of its own
};

}  // namespace fovrt
