#version 460
#extension GL_GOOGLE_include_directive : require
// two_history_blend — the variance-optimal, gradient-guided blend of the two histories after
// à-trous iteration 1 (SPEC §5). Mirrors TwoHistoryBlendRef.
// Purpose: p from (W_u, W_w, S_k); t = p + q − pq; out = lerp((I_w, Var_w), (I_u, Var_u), t).
// Reads:  filtered (I_u, Var) and (I_w, Var), W_u, W_w, power sums, q.
// Writes: the blend, in place over (I_u, Var) (the input of the remaining iterations).
#include "shared_constants.h"
#include "common/two_history_constants.glsl"
#include "common/packing.glsl"
#include "common/two_history.glsl"

layout(local_size_x = FOVRT_WORKGROUP_X, local_size_y = FOVRT_WORKGROUP_Y) in;

layout(std430, binding = TH_BLEND_B_ILLUM_U) buffer IllumU { vec4 illum_u[]; };
layout(std430, binding = TH_BLEND_B_ILLUM_W) readonly buffer IllumW { vec4 illum_w[]; };
layout(std430, binding = TH_BLEND_B_WU) readonly buffer Wu { hfloat wu[]; };
layout(std430, binding = TH_BLEND_B_WW) readonly buffer Ww { hfloat ww[]; };
layout(std430, binding = TH_BLEND_B_S) readonly buffer S { hfloat s[]; };
layout(std430, binding = TH_BLEND_B_Q) readonly buffer Q { float q[]; };

layout(push_constant) uniform Push {
    ivec2 size;
} pc;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, pc.size))) return;
    int i = p.y * pc.size.x + p.x;
    float pb = two_history_optimal_blend(float(wu[i]), float(ww[i]), LOAD3(s, i));
    float t = pb + q[i] - pb * q[i];
    illum_u[i] = mix(illum_w[i], illum_u[i], t);
}
