// Layouts shared by the SVGF shaders and the host: push-constant blocks (mirrored in each
// shaders/svgf_*.comp) and the storage format of every plane (see shaders/common/packing.glsl).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "core/math.h"
#include "denoise/params.h"
#include "shaders/shared_constants.h"

namespace fovrt {

// svgf_reproject's mode bits (SVGF_REPROJECT_FLAG_*) are a specialization constant.
struct SvgfReprojectPush {
    ivec2 size;
    float alphaColor;
    float alphaMoments;
    uint32_t hasPrev;  // 0: no previous frame (first frame, reset): nothing reprojects
};
static_assert(sizeof(SvgfReprojectPush) == 20);

struct SvgfFilterMomentsPush {
    ivec2 size;
    float sigmaDepth;
    float sigmaNormal;
    float threshold;
};
static_assert(sizeof(SvgfFilterMomentsPush) == 20);

struct SvgfClassifyPush {
    ivec2 size;
    float threshold;
};
static_assert(sizeof(SvgfClassifyPush) == 12);

struct SvgfAtrousPush {
    ivec2 size;
    int32_t step;
    float sigmaDepth;
    float sigmaNormal;
    float sigmaLuminance;
};
static_assert(sizeof(SvgfAtrousPush) == 24);

struct SvgfModulatePush {  // combined: specialization constant FOVRT_SPEC_MODULATE_COMBINED
    ivec2 size;
};
static_assert(sizeof(SvgfModulatePush) == 8);

// Bytes per element of a history plane scalar.
inline size_t HistoryScalarBytes(Precision p) { return p == Precision::Fp16 ? 2 : 4; }

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
