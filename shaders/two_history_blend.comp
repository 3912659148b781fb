#version 460
#extension GL_GOOGLE_include_directive : require
// two_history_blend — the variance-optimal, gradient-guided blend of the two histories after
// à-trous iteration 1 (SPEC §5). Mirrors TwoHistoryBlendRef.
// Purpose: p from (W_u, W_w, S_k); t = p + q − pq; out = lerp((I_w, Var_w), (I_u, Var_u), t).
// Reads:  filtered (I_u, Var) and (I_w, Var), W_u, W_w, power sums, q.
// Writes: the blend, in place over (I_u, Var) (the input of the remaining iterations).
#include "shared_constants.h"
#include "push_constants.h"
#include "common/two_history_constants.glsl"
#include "common/packing.glsl"
#include "common/access.glsl"
#include "common/two_history.glsl"

layout(local_size_x = FOVRT_WORKGROUP_X, local_size_y = FOVRT_WORKGROUP_Y) in;

FOVRT_DECLARE_BINDINGS(TH_BLEND_BINDING_LIST)  // shaders/bindings/two_history_blend.h
#ifdef FOVRT_FP16
#define LOAD_S(i) LOAD3(s, i)
#else
#define LOAD_S(i) FETCH3(s, i)
#endif

FOVRT_PUSH_CONSTANTS(FOVRT_PUSH_IMAGE_SIZE);  // shaders/push_constants.h

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, pc.size))) return;
    int i = p.y * pc.size.x + p.x;
    float pb = two_history_optimal_blend(FETCH1(wu, i), FETCH1(ww, i), LOAD_S(i));
    float qi = FETCH1(q, i);
    float t = pb + qi - pb * qi;
    illum_u[i] = mix(FETCH4(illum_w, i), illum_u[i], t);
}
