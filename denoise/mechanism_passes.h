// A mechanism's plan fragment: the passes of its own that it adds to its family's frame, and the
// slot of the frame where they run. A row of kMechanisms (variants.cpp), the mechanism's unit,
// names its fragment; the fragments are written with the plan's toolkit (plan_writer.h) in
// mechanism_passes.cpp, or in a file of their own (asvgf_plan.cpp). A mechanism that only
// switches a mode of a family pass (weighted, firefly, clamp, anti-lag's reprojection bit) has
// none: the family pass sets the mode and its stage carries it to the reference.
#pragma once

#include <cstdint>
#include <vector>

namespace fovrt {

struct DenoiserVariant;  // denoise/variants.h
namespace plan {
class Writer;
struct Family;
struct FrameCursor;
}  // namespace plan

// Where a mechanism's passes join the family's frame (PlanSvgfFamily).
enum class FrameSlot : uint8_t {
    BeforeGuide,    // after the upload, before the guide: reads this frame's inputs (A-SVGF's gradient)
    AfterVariance,  // after the variance estimate, before the blend and à-trous (the EMA gradient's q)
    BeforeBlend,    // just before the two-history blend (the held choice it reads)
    AfterFilter,    // after the last à-trous iteration, before modulation (stabilisation)
};

// Writes the mechanism's passes, each with its reference stage and its Vulkan commands.
using PlanFragment = void (*)(plan::Writer&, const plan::Family&, plan::FrameCursor&);

struct MechanismPasses {
    FrameSlot slot = FrameSlot::BeforeGuide;
    PlanFragment emit = nullptr;  // null: the mechanism adds no pass of its own
};

// A mechanism with passes of its own, for the plan's tests: the row's flag and its fragment.
struct MechanismFragment {
    bool DenoiserVariant::*flag;
    MechanismPasses passes;
};
// Every mechanism with passes of its own, in kMechanisms' (frame) order (variants.cpp).
std::vector<MechanismFragment> MechanismFragments();
// The fragments of the mechanisms `variant` turns on at `slot`, in frame order (variants.cpp).
std::vector<PlanFragment> MechanismFragmentsAt(const DenoiserVariant& variant, FrameSlot slot);

namespace plan {
// The fragments (mechanism_passes.cpp; A-SVGF's gradient in asvgf_plan.cpp).
void AsvgfGradient(Writer& w, const Family& f, FrameCursor& cursor);
void EmaGradient(Writer& w, const Family& f, FrameCursor& cursor);
void HeldChoice(Writer& w, const Family& f, FrameCursor& cursor);
void Stabilize(Writer& w, const Family& f, FrameCursor& cursor);
}  // namespace plan

}  // namespace fovrt
