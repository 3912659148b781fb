#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
// asvgf_gradient_atrous — one iteration of the joint-bilateral reconstruction of (δ, Δ) at
// stratum resolution (A-SVGF §3, SPEC §4). Mirrors AsvgfGradientAtrousRef.
// Purpose: 3×3 box kernel at step 2^i strata; weights w_z·w_n·w_l of SVGF on the stratum guide
//   (offsets in pixels = 3·step·k), as one exp2 (common/edge_stopping.glsl); w_l scaled by
//   σ_l·std of the guide luminance over the 3×3 strata (asvgf_stratum_sigma); empty strata enter
//   as 0; centre weight 1.
// Reads:  (δ, Δ), stratum guide (asvgf_gradient_gather), σ_l·std.  Writes: (δ, Δ) filtered.
#include "shared_constants.h"
#include "push_constants.h"
#include "common/two_history_constants.glsl"
#include "common/asvgf.glsl"
#include "common/access.glsl"
#include "common/edge_stopping.glsl"

layout(local_size_x = FOVRT_WORKGROUP_X, local_size_y = FOVRT_WORKGROUP_Y) in;

FOVRT_DECLARE_BINDINGS(ASVGF_ATROUS_BINDING_LIST)  // shaders/bindings/asvgf_gradient_atrous.h

FOVRT_PUSH_CONSTANTS(FOVRT_PUSH_ASVGF_ATROUS);  // shaders/push_constants.h

bool inside(ivec2 s) { return all(greaterThanEqual(s, ivec2(0))) && all(lessThan(s, pc.grid)); }

void main() {
    ivec2 s = ivec2(gl_GlobalInvocationID.xy);
    if (!inside(s)) return;
    int k = s.y * pc.grid.x + s.x;
    vec4 gp = FETCH4(guide_geometry, k);
    vec2 centre = FETCH2(grad_in, k);
    vec2 result = centre;
    if (!GUIDE_IS_BACKGROUND(gp)) {
        vec4 lp = FETCH4(guide_luminance, k);  // luminance, depth gradient
        float inv_l_den = 1.0 / (FETCH1(sigma_l, k) + FOVRT_ATROUS_LUMINANCE_EPSILON);
        vec2 acc = centre;  // the centre has weight 1
        float wsum = 1.0;
        [[unroll]] for (int ky = -1; ky <= 1; ++ky)
            [[unroll]] for (int kx = -1; kx <= 1; ++kx) {
                if (kx == 0 && ky == 0) continue;
                ivec2 t = s + ivec2(kx, ky) * pc.step;
                if (!inside(t)) continue;
                int kt = t.y * pc.grid.x + t.x;
                vec4 gq = FETCH4(guide_geometry, kt);
                if (GUIDE_IS_BACKGROUND(gq)) continue;
                vec2 offset_pixels = vec2(kx, ky) * float(pc.step * ASVGF_STRATUM_SIZE);
                float w = geometry_weight(gp.w, gq.w, lp.yz, offset_pixels, pc.sigma_depth, gp.xyz, gq.xyz,
                                          pc.sigma_normal,
                                          abs(lp.x - FETCH1(guide_luminance, kt)) * inv_l_den);
                acc += w * FETCH2(grad_in, kt);
                wsum += w;
            }
        result = acc / wsum;
    }
    grad_out[k] = result;
}
