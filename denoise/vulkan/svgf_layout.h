// Dispatch helpers shared by the Vulkan hosts: workgroup counts and the edge-stopping
// specialization constants. Push-constant blocks: shaders/push_constants.h (declared once for GLSL and C++).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "core/math.h"
#include "denoise/params.h"
#include "shaders/push_constants.h"
#include "shaders/shared_constants.h"

namespace fovrt {

// Workgroups covering a W×H image.
inline uvec2 DispatchGroups(int width, int height) {
    return uvec2((width + FOVRT_WORKGROUP_X - 1) / FOVRT_WORKGROUP_X,
                 (height + FOVRT_WORKGROUP_Y - 1) / FOVRT_WORKGROUP_Y);
}

// Specialization constants of the edge-stopping shaders (shaders/common/edge_stopping.glsl), by
// constant_id: FOVRT_SPEC_NORMAL_SQUARINGS = k when σn = 2^k exactly (0 ≤ k ≤ 12), else −1.
inline int32_t NormalWeightSquarings(float sigmaNormal) {
    for (int k = 0; k <= FOVRT_MAX_NORMAL_SQUARINGS; ++k)
        if (sigmaNormal == float(1 << k)) return k;
    return -1;
}
inline std::array<int32_t, 1> EdgeStoppingSpecialization(const SvgfParams& p) {
    static_assert(FOVRT_SPEC_NORMAL_SQUARINGS == 0);
    return {NormalWeightSquarings(p.sigmaNormal)};
}

}  // namespace fovrt
