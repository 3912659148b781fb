#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
// bandwidth_copy — streaming copy of a large buffer, timed by `fovrt bench --denoisers` to give
// the device's own bandwidth bound of the passes, and its exp2 throughput (src/vk/bandwidth.h).
// Purpose: the same access layer and dispatch shape as the image passes (64×1 workgroups, one
//   element per invocation, i = y·W + x). The mode is a specialization constant, not a push
//   constant: lavapipe evaluates both sides of a run-time select, so a run-time mode would time
//   both loads in every mode.
//   Mode 0 reads an rgba32f uniform texel buffer (common/access.glsl), mode 1 reads std430 vec4;
//   both write std430 vec4. Mode 2 is mode 0 plus BANDWIDTH_EXP2_PER_ELEMENT independent exp2 per
//   element (the transcendental of every edge-stopping weight): the ALU side of the passes.
// Reads:  source (vec4 per element).  Writes: destination (vec4 per element).
#include "shared_constants.h"
#include "push_constants.h"
#include "common/access.glsl"

layout(local_size_x = FOVRT_WORKGROUP_X, local_size_y = FOVRT_WORKGROUP_Y) in;
layout(constant_id = 0) const uint kMode = 0u;

FOVRT_DECLARE_BINDINGS(BANDWIDTH_BINDING_LIST)  // shaders/bindings/bandwidth_copy.h

FOVRT_PUSH_CONSTANTS(FOVRT_PUSH_BANDWIDTH);  // shaders/push_constants.h

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, pc.size))) return;
    int i = p.y * pc.size.x + p.x;
    vec4 v = kMode == 1u ? src[i] : FETCH4(src_texel, i);
    if (kMode == 2u) {
        // Four independent accumulators, exponents in [−8, 0): no overflow, no constant folding.
        vec4 acc = vec4(0.0);
        [[unroll]] for (int k = 0; k < BANDWIDTH_EXP2_PER_ELEMENT / 4; ++k)
            acc += exp2(-v * float(k + 1) * (8.0 / float(BANDWIDTH_EXP2_PER_ELEMENT / 4)));
        v = acc;
    }
    dst[i] = v;
}
