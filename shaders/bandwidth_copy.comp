#version 460
#extension GL_GOOGLE_include_directive : require
// bandwidth_copy — streaming copy of a large buffer, timed by `fovrt bench --denoisers` to give
// the device's own bandwidth bound of the passes (src/vk/bandwidth.h).
// Purpose: the same access layer and dispatch shape as the image passes (64×1 workgroups, one
//   element per invocation, i = y·W + x): mode 0 reads an rgba32f uniform texel buffer
//   (common/access.glsl), mode 1 reads std430 vec4; both write std430 vec4.
// Reads:  source (vec4 per element).  Writes: destination (vec4 per element).
#include "shared_constants.h"
#include "common/access.glsl"

layout(local_size_x = FOVRT_WORKGROUP_X, local_size_y = FOVRT_WORKGROUP_Y) in;

PLANE(BANDWIDTH_B_TEXEL_IN, src_texel);  // rgba32f
layout(std430, binding = BANDWIDTH_B_STORAGE_IN) readonly buffer Src { vec4 src[]; };
layout(std430, binding = BANDWIDTH_B_OUT) writeonly buffer Dst { vec4 dst[]; };

// Mirrors BandwidthPush in src/vk/bandwidth.cpp.
layout(push_constant) uniform Push {
    ivec2 size;  // elements as rows × columns
    uint mode;   // 0: texel-buffer read, 1: std430 read
} pc;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, pc.size))) return;
    int i = p.y * pc.size.x + p.x;
    dst[i] = pc.mode == 0u ? FETCH4(src_texel, i) : src[i];
}
