// The plan fragments of the mechanisms with passes of their own (named by their rows:
// denoise/mechanism_slots.h), written with the plan's toolkit: each writes its passes, every
// pass with its reference stage and its Vulkan commands (mechanism_passes.cpp; A-SVGF's gradient
// in asvgf_plan.cpp).
#pragma once

#include "denoise/mechanism_slots.h"

namespace fovrt::plan {

class Writer;
struct Family;
struct FrameCursor;

using PlanFragment = void (*)(Writer&, const Family&, FrameCursor&);

void AsvgfGradient(Writer& w, const Family& f, FrameCursor& cursor);
void EmaGradient(Writer& w, const Family& f, FrameCursor& cursor);
void HeldChoice(Writer& w, const Family& f, FrameCursor& cursor);
void Stabilize(Writer& w, const Family& f, FrameCursor& cursor);

// The fragment that writes `pass` (not None).
PlanFragment FragmentOf(MechanismPass pass);

}  // namespace fovrt::plan
