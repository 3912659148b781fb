#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
// two_history_gradient — edge-aware filter of the gradient EMA and the gradient blend factor q
// (SPEC §5). Mirrors TwoHistoryGradientRef.
// Purpose: g' = Σ h(k) w_z w_n g / Σ h(k) w_z w_n over a 5×5 à-trous kernel (step 1, no
//   luminance term: g itself is what is being estimated); q = clamp(S·|g'|/std, 0, 1) with
//   std² = Σ_channels Var of the unweighted history (after the variance estimate). g is the
//   signed luminance of the gradient, one float (denoise/reference/two_history_math.h).
// Reads:  gradient EMA (this frame), (I_u, Var) per channel, the packed guide (normal, depth,
//         background; svgf_pack_guide: one fetch per tap instead of three), depth gradient.
// Writes: q (float per pixel).
#include "shared_constants.h"
#include "push_constants.h"
#include "common/two_history_constants.glsl"
#include "common/packing.glsl"
#include "common/access.glsl"
#include "common/edge_stopping.glsl"
#include "common/two_history.glsl"

layout(local_size_x = FOVRT_WORKGROUP_X, local_size_y = FOVRT_WORKGROUP_Y) in;

FOVRT_DECLARE_BINDINGS(TH_GRADIENT_BINDING_LIST)  // shaders/bindings/two_history_gradient.h

FOVRT_PUSH_CONSTANTS(FOVRT_PUSH_TWO_HISTORY_GRADIENT);  // shaders/push_constants.h

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, pc.size))) return;
    int i = p.y * pc.size.x + p.x;
    vec4 gc = FETCH4(guide, i);
    vec2 gp = FETCH2(depth_grad, i);
    float sum = 0.0;
    float wsum = 0.0;
    // Taps outside the image or on background weigh 0 (no `continue`: common/access.glsl).
    [[unroll]] for (int ky = -2; ky <= 2; ++ky)
        [[unroll]] for (int kx = -2; kx <= 2; ++kx) {
            ivec2 q = p + ivec2(kx, ky);
            int j = clamped_index(q, pc.size);
            vec4 gq = FETCH4(guide, j);
            bool use = in_image(q, pc.size) && !GUIDE_IS_BACKGROUND(gq);
            float w = kAtrousKernel[kx + 2] * kAtrousKernel[ky + 2];
            if (kx != 0 || ky != 0)  // compile-time; w_z·w_n as one exp2, as in svgf_atrous
                w *= geometry_weight(gc.w, gq.w, gp, vec2(kx, ky), pc.sigma_depth, gc.xyz, gq.xyz, pc.sigma_normal, 0.0);
            w = use ? w : 0.0;
            sum += w * FETCH1(gradient, j);
            wsum += w;
        }
    float variance = FETCH4(illum_u0, i).a + (pc.two_channels != 0u ? FETCH4(illum_u1, i).a : 0.0);
    // Background pixels: q = 0 (their sums are 0/0, discarded by the select).
    q_out[i] = GUIDE_IS_BACKGROUND(gc) ? 0.0 : two_history_gradient_blend(sum / wsum, variance, pc.q_scale);
}
