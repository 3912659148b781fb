// The SVGF schedule facts every backend, the memory plan and the byte model share: which à-trous
// iteration feeds the colour history back, and which ping-pong plane ends up holding the filtered
// illumination. One definition each, so the Vulkan hosts, the C++ references and the bench agree.
#pragma once

#include <algorithm>

#include "denoise/params.h"

namespace fovrt {

// The 1-based à-trous iteration whose output becomes the colour history; 0 = the unfiltered
// temporal accumulation is fed back (also when there is no à-trous iteration). The two-history
// family blends its two histories after iteration 1, so a later feedback would feed the blend
// back: it feeds back iteration 1 at the latest (Tu 2024, slide "Why Not Blend Earlier").
inline int FeedbackIteration(const SvgfParams& p, bool twoHistory) {
    if (p.atrousIterations <= 0 || p.feedbackIteration <= 0) return 0;
    return std::min(p.feedbackIteration, twoHistory ? 1 : p.atrousIterations);
}

// Index (0 or 1) of the illumination ping-pong plane ("illum0"/"illum1") that holds the filtered
// illumination after `atrousIterations` iterations: the reprojection writes plane 0, the
// variance estimate plane 1, à-trous iteration i reads plane (i+1)&1 and writes plane i&1.
inline int FilteredIlluminationPlane(int atrousIterations) {
    return atrousIterations == 0 ? 1 : (atrousIterations - 1) & 1;
}

}  // namespace fovrt
