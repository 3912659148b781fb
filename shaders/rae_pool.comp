#version 460
#extension GL_GOOGLE_include_directive : require
// rae_pool — 2×2 max-pool of one tensor of the recurrent denoising autoencoder (SPEC §12; C++
// reference RaeMaxPool2x2 in denoise/reference/rae_net.cpp).
// Reads:  act (channels planes of 2·size at src_offset).  Writes: act (channels planes of size at
// dst_offset). Workgroups along x cover tiles_x × channels.
#include "shared_constants.h"
#include "push_constants.h"
#include "common/packing.glsl"

layout(local_size_x = RAE_WORKGROUP, local_size_y = RAE_WORKGROUP) in;

FOVRT_DECLARE_BINDINGS(RAE_POOL_BINDING_LIST)  // shaders/bindings/rae.h

FOVRT_PUSH_CONSTANTS(FOVRT_PUSH_RAE_POOL);  // shaders/push_constants.h

void main() {
    const int tile = int(gl_WorkGroupID.x) % pc.tiles_x;
    const int c = int(gl_WorkGroupID.x) / pc.tiles_x;
    const ivec2 p = ivec2(tile * RAE_WORKGROUP + int(gl_LocalInvocationID.x), int(gl_GlobalInvocationID.y));
    if (any(greaterThanEqual(p, pc.size)) || c >= pc.channels) return;
    const int srcW = pc.size.x * 2;
    const uint src = pc.src_offset + uint(c * srcW * pc.size.y * 2) + uint(2 * p.y * srcW + 2 * p.x);
    const float m = max(max(float(act[src]), float(act[src + 1u])),
                        max(float(act[src + uint(srcW)]), float(act[src + uint(srcW) + 1u])));
    act[pc.dst_offset + uint(c * pc.size.x * pc.size.y + p.y * pc.size.x + p.x)] = hfloat(m);
}
