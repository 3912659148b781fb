// The A-SVGF stratum grid (Schied et al. 2018, §3.3, "Constructing Gradient Samples"): 3×3-pixel
// strata, one forward-projected gradient sample kept per stratum. Shared by the renderer's sample
// layout, the references, the Vulkan passes and the memory plan.
#pragma once

#include <cstddef>

#include "core/frame_inputs.h"
#include "core/math.h"

namespace fovrt {

// Stratum grid of a W×H image: ceil(W/3) × ceil(H/3).
inline ivec2 StratumGridSize(int width, int height) {
    return ivec2((width + kGradientStratumSize - 1) / kGradientStratumSize,
                 (height + kGradientStratumSize - 1) / kGradientStratumSize);
}

// Capacity of the gradient-sample upload: two per stratum.
inline size_t GradientSampleCapacity(int width, int height) {
    const ivec2 g = StratumGridSize(width, height);
    return 2 * size_t(g.x) * size_t(g.y);
}

}  // namespace fovrt
