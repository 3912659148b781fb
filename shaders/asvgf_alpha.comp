#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
// asvgf_alpha — per-pixel temporal weight from the reconstructed gradient (SPEC §4).
// Mirrors AsvgfAlphaRef.
// Purpose: λ(s) = min(1, |δ̂|/Δ̂) (0 where Δ̂ = 0); per pixel λ = max over the 3×3 strata around
//   its stratum; α = (1 − λ)α_base + λ. FOVRT_SPEC_ASVGF_ANTILAG (the anti-lag variants): the α
//   plane holds the anti-lag factor a = clamp(gain·λ, 0, 1), which two_history_reproject turns
//   into α together with the history length.
// Reads:  (δ̂, Δ̂) per stratum.  Writes: α (or a) and λ per pixel.
#include "shared_constants.h"
#include "push_constants.h"
#include "common/two_history_constants.glsl"
#include "common/asvgf.glsl"
#include "common/access.glsl"

layout(local_size_x = FOVRT_WORKGROUP_X, local_size_y = FOVRT_WORKGROUP_Y) in;
layout(constant_id = FOVRT_SPEC_ASVGF_ANTILAG) const bool kAntilag = false;

FOVRT_DECLARE_BINDINGS(ASVGF_ALPHA_BINDING_LIST)  // shaders/bindings/asvgf_alpha.h

FOVRT_PUSH_CONSTANTS(FOVRT_PUSH_ASVGF_ALPHA);  // shaders/push_constants.h

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, pc.size))) return;
    ivec2 s = p / ASVGF_STRATUM_SIZE;
    float lambda = 0.0;
    [[unroll]] for (int dy = -1; dy <= 1; ++dy)
        [[unroll]] for (int dx = -1; dx <= 1; ++dx) {
            ivec2 t = s + ivec2(dx, dy);
            if (any(lessThan(t, ivec2(0))) || any(greaterThanEqual(t, pc.grid))) continue;
            vec2 d = FETCH2(grad, t.y * pc.grid.x + t.x);
            lambda = max(lambda, d.y > 1e-6 ? min(1.0, abs(d.x) / d.y) : 0.0);
        }
    int i = p.y * pc.size.x + p.x;
    lambda_out[i] = lambda;
    alpha_out[i] = kAntilag ? clamp(pc.antilag_gain * lambda, 0.0, 1.0) : (1.0 - lambda) * pc.alpha + lambda;
}
