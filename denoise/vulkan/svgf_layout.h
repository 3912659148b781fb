// Dispatch sizes of the Vulkan hosts: workgroups over an image and over the 2×2 blocks of an
// à-trous iteration. Push-constant blocks: shaders/push_constants.h (declared once for GLSL and
// C++); specialization constants: the pass plan (denoise/svgf_family_plan.h).
#pragma once

#include <algorithm>
#include <cstdint>

#include "core/math.h"
#include "denoise/svgf_family_plan.h"
#include "shaders/push_constants.h"
#include "shaders/shared_constants.h"

namespace fovrt {

// Workgroups covering a W×H image.
inline uvec2 DispatchGroups(int width, int height) {
    return uvec2((width + FOVRT_WORKGROUP_X - 1) / FOVRT_WORKGROUP_X,
                 (height + FOVRT_WORKGROUP_Y - 1) / FOVRT_WORKGROUP_Y);
}

// Blocks per axis of `n` pixels at stride `step`: pixels pair up (x, x + step) inside each run of
// 2·step, and a last partial run of r pixels has min(r, step) blocks (partners past the edge).
inline int AtrousBlocks(int n, int step) { return n / (2 * step) * step + std::min(n % (2 * step), step); }

// Workgroups of an à-trous dispatch at `step` (one invocation per 2×2 block: shaders/svgf_atrous.comp).
inline uvec2 AtrousBlockGroups(int width, int height, int step) {
    return DispatchGroups(AtrousBlocks(width, step), FOVRT_ATROUS_BLOCK_Y == 2 ? AtrousBlocks(height, step) : height);
}

}  // namespace fovrt
