#version 460
#extension GL_GOOGLE_include_directive : require
// asvgf_gradient_atrous — one iteration of the joint-bilateral reconstruction of (δ, Δ) at
// stratum resolution (A-SVGF §3, SPEC §4). Mirrors AsvgfGradientAtrousRef.
// Purpose: 3×3 box kernel at step 2^i strata; weights w_z·w_n·w_l of SVGF on the guide pixels
//   (offsets in pixels = 3·step·k); w_l scaled by σ_l times the 3×3-strata standard deviation of
//   the guide luminance; empty strata enter as 0; centre weight 1.
// Reads:  (δ, Δ), guide pixels, geometry, depth gradient, inputs for the noisy colour luminance.
// Writes: (δ, Δ) filtered.
#include "shared_constants.h"
#include "common/two_history_constants.glsl"
#include "common/asvgf.glsl"
#include "common/packing.glsl"
#include "common/access.glsl"
#include "common/luminance.glsl"
#include "common/edge_stopping.glsl"

layout(local_size_x = FOVRT_WORKGROUP_X, local_size_y = FOVRT_WORKGROUP_Y) in;

// Read-only planes: uniform texel buffers (common/access.glsl; formats in two_history_vk.cpp).
PLANE(ASVGF_ATROUS_B_GRAD_IN, grad_in);        // rg32f
IPLANE(ASVGF_ATROUS_B_GUIDE, guide);           // r32i (pixel index of each stratum's sample)
PLANE(ASVGF_ATROUS_B_DEPTH, depth);            // r32f
PLANE(ASVGF_ATROUS_B_NORMAL, normal);          // rgb32f
UPLANE(ASVGF_ATROUS_B_OBJECT, object_id);      // r32ui
PLANE(ASVGF_ATROUS_B_DEPTH_GRAD, depth_grad);  // rg32f
PLANE(ASVGF_ATROUS_B_DIRECT, direct);          // rgb32f
PLANE(ASVGF_ATROUS_B_INDIRECT, indirect);      // rgb32f
PLANE(ASVGF_ATROUS_B_ALBEDO, albedo);          // rgb32f
PLANE(ASVGF_ATROUS_B_EMISSION, emission);      // rgb32f
layout(std430, binding = ASVGF_ATROUS_B_GRAD_OUT) writeonly buffer GradOut { vec2 grad_out[]; };

layout(push_constant) uniform Push {
    ivec2 size;
    ivec2 grid;
    int step;
    float sigma_depth;
    float sigma_normal;
    float sigma_luminance;
} pc;

// Luminance of the noisy colour albedo·(direct + indirect) + emission at pixel j.
float guide_luminance(int j) {
    return luminance(FETCH3(albedo, j) * (FETCH3(direct, j) + FETCH3(indirect, j)) + FETCH3(emission, j));
}

bool inside(ivec2 s) { return all(greaterThanEqual(s, ivec2(0))) && all(lessThan(s, pc.grid)); }

void main() {
    ivec2 s = ivec2(gl_GlobalInvocationID.xy);
    if (!inside(s)) return;
    int k = s.y * pc.grid.x + s.x;
    int gp = FETCH1(guide, k);
    if (FETCH1(object_id, gp) == FOVRT_NO_OBJECT) {
        grad_out[k] = FETCH2(grad_in, k);
        return;
    }
    float sum = 0.0, sum2 = 0.0, cnt = 0.0;
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            ivec2 t = s + ivec2(dx, dy);
            if (!inside(t)) continue;
            int gq = FETCH1(guide, t.y * pc.grid.x + t.x);
            if (FETCH1(object_id, gq) == FOVRT_NO_OBJECT) continue;
            float l = guide_luminance(gq);
            sum += l;
            sum2 += l * l;
            cnt += 1.0;
        }
    float mean = sum / cnt;
    float sigma_l_std = pc.sigma_luminance * sqrt(max(0.0, sum2 / cnt - mean * mean));
    float zp = FETCH1(depth, gp);
    vec3 np = FETCH3(normal, gp);
    vec2 dzp = FETCH2(depth_grad, gp);
    float lp = guide_luminance(gp);
    vec2 acc = vec2(0.0);
    float wsum = 0.0;
    for (int ky = -1; ky <= 1; ++ky)
        for (int kx = -1; kx <= 1; ++kx) {
            ivec2 t = s + ivec2(kx, ky) * pc.step;
            if (!inside(t)) continue;
            int kt = t.y * pc.grid.x + t.x;
            int gq = FETCH1(guide, kt);
            if (FETCH1(object_id, gq) == FOVRT_NO_OBJECT) continue;
            float w = 1.0;
            if (kx != 0 || ky != 0) {
                vec2 offset_pixels = vec2(kx, ky) * float(pc.step * ASVGF_STRATUM_SIZE);
                w = depth_weight(zp, FETCH1(depth, gq), dzp, offset_pixels, pc.sigma_depth) *
                    normal_weight(np, FETCH3(normal, gq), pc.sigma_normal) *
                    luminance_weight(lp, guide_luminance(gq), sigma_l_std);
            }
            acc += w * FETCH2(grad_in, kt);
            wsum += w;
        }
    grad_out[k] = acc / wsum;
}
