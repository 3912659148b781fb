#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
// svgf_atrous — one edge-avoiding à-trous wavelet iteration (paper §4.3, SPEC §3).
// Purpose: 5×5 kernel h⊗h at step 2^i with w = w_z·w_n·w_l; w_l uses the 3×3 Gaussian-prefiltered
//   variance of the centre; colour = Σ h w c / Σ h w, variance = Σ h² w² Var / (Σ h w)².
//   On the feedback iteration the filtered colour is also written as the colour history.
// Channels: FOVRT_CHANNELS (1: "svgf_atrous", 2: "svgf_atrous_pair") illumination planes filtered
//   by one dispatch (direct + indirect, or the unweighted + weighted history of two-history). The
//   per-tap guide fetch, background test, depth gradient and w_z·w_n exponent are shared; each
//   channel keeps its own w_l and variance, so every channel gets exactly the 1-channel result.
//   A compile-time count, not a run-time flag: lavapipe executes both sides of every branch.
// Reads:  per channel illumination + variance (vec4); guide (normal, depth, background), depth gradient.
// Writes: per channel illumination + variance (vec4); colour history when write_history != 0.
#include "shared_constants.h"
#include "common/packing.glsl"
#include "common/access.glsl"
#include "common/luminance.glsl"
#include "common/edge_stopping.glsl"

#ifndef FOVRT_CHANNELS
#define FOVRT_CHANNELS 1
#endif
#define NCH FOVRT_CHANNELS

layout(local_size_x = FOVRT_WORKGROUP_X, local_size_y = FOVRT_WORKGROUP_Y) in;

// Read-only planes: uniform texel buffers (common/access.glsl; formats in denoise/svgf_texel_formats.h).
PLANE(SVGF_ATROUS_B_GUIDE, guide);             // rgba32f (normal, depth; svgf_pack_guide)
PLANE(SVGF_ATROUS_B_DEPTH_GRAD, depth_grad);   // rg32f
PLANE(SVGF_ATROUS_B_ILLUM_IN, illum_in0);      // rgba32f
layout(std430, binding = SVGF_ATROUS_B_ILLUM_OUT) writeonly buffer IllumOut0 { vec4 illum_out0[]; };
layout(std430, binding = SVGF_ATROUS_B_HIST_COLOR) writeonly buffer HistColor0 { hfloat hist_color0[]; };
#if NCH == 2
PLANE(SVGF_ATROUS_B_ILLUM_IN2, illum_in1);
layout(std430, binding = SVGF_ATROUS_B_ILLUM_OUT2) writeonly buffer IllumOut1 { vec4 illum_out1[]; };
layout(std430, binding = SVGF_ATROUS_B_HIST_COLOR2) writeonly buffer HistColor1 { hfloat hist_color1[]; };
#define FETCH_ILLUM(v, j) v[0] = FETCH4(illum_in0, j); v[1] = FETCH4(illum_in1, j)
#elif NCH == 1
#define FETCH_ILLUM(v, j) v[0] = FETCH4(illum_in0, j)
#else
#error "FOVRT_CHANNELS must be 1 or 2"
#endif

// Mirrors SvgfAtrousPush in denoise/svgf_layout.h.
layout(push_constant) uniform Push {
    ivec2 size;
    int step;
    float sigma_depth;
    float sigma_normal;
    float sigma_luminance;
    uint write_history;
} pc;

bool inside(ivec2 q) { return all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, pc.size)); }

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (!inside(p)) return;
    int i = p.y * pc.size.x + p.x;
    vec4 center[NCH];
    FETCH_ILLUM(center, i);
    vec4 result[NCH] = center;
    vec4 gc = FETCH4(guide, i);
    if (!GUIDE_IS_BACKGROUND(gc)) {
        // 3×3 Gaussian of the variance, only to steer w_l.
        float var_sum[NCH], var_w = 0.0;
        [[unroll]] for (int c = 0; c < NCH; ++c) var_sum[c] = 0.0;
        [[unroll]] for (int dy = -1; dy <= 1; ++dy)
            [[unroll]] for (int dx = -1; dx <= 1; ++dx) {
                ivec2 q = p + ivec2(dx, dy);
                if (!inside(q)) continue;
                int j = q.y * pc.size.x + q.x;
                if (GUIDE_IS_BACKGROUND(FETCH4(guide, j))) continue;
                float g = gauss3(dx, dy);
                vec4 v[NCH];
                FETCH_ILLUM(v, j);
                [[unroll]] for (int c = 0; c < NCH; ++c) var_sum[c] += g * v[c].a;
                var_w += g;
            }
        float zp = gc.w;
        vec3 np = gc.xyz;
        vec2 gp = FETCH2(depth_grad, i);
        float lp[NCH], inv_l_den[NCH], sum_w[NCH], sum_v[NCH];
        vec3 sum_c[NCH];
        [[unroll]] for (int c = 0; c < NCH; ++c) {
            float sigma_l_std = pc.sigma_luminance * sqrt(max(0.0, var_sum[c] / var_w));
            lp[c] = luminance(center[c].rgb);
            inv_l_den[c] = 1.0 / (sigma_l_std + FOVRT_ATROUS_LUMINANCE_EPSILON);
            sum_w[c] = 0.0;
            sum_c[c] = vec3(0.0);
            sum_v[c] = 0.0;
        }
        [[unroll]] for (int ky = -2; ky <= 2; ++ky) {
            [[unroll]] for (int kx = -2; kx <= 2; ++kx) {
                ivec2 off = ivec2(kx, ky) * pc.step;
                ivec2 q = p + off;
                if (!inside(q)) continue;
                int j = q.y * pc.size.x + q.x;
                vec4 gq = FETCH4(guide, j);
                if (GUIDE_IS_BACKGROUND(gq)) continue;
                vec4 cq[NCH];
                FETCH_ILLUM(cq, j);
                float h = kAtrousKernel[kx + 2] * kAtrousKernel[ky + 2];
                // Geometric part of the exponent, once for all channels (kx, ky are unrolled
                // constants: the centre test is resolved at compile time).
                bool centre = kx == 0 && ky == 0;
                float depth_term = centre ? 0.0 : geometry_depth_term(zp, gq.w, gp, vec2(off), pc.sigma_depth);
                float normal_log2 = centre ? 0.0 : geometry_normal_log2(np, gq.xyz, pc.sigma_normal);
                [[unroll]] for (int c = 0; c < NCH; ++c) {
                    float w = centre ? 1.0
                                     : geometry_weight_from_terms(depth_term, normal_log2,
                                                                  abs(lp[c] - luminance(cq[c].rgb)) * inv_l_den[c]);
                    float hw = h * w;
                    sum_w[c] += hw;
                    sum_c[c] += hw * cq[c].rgb;
                    sum_v[c] += hw * hw * cq[c].a;
                }
            }
        }
        [[unroll]] for (int c = 0; c < NCH; ++c)
            result[c] = vec4(sum_c[c] / sum_w[c], sum_v[c] / (sum_w[c] * sum_w[c]));
    }
    illum_out0[i] = result[0];
    if (pc.write_history != 0u) STORE3(hist_color0, i, to_history(result[0].rgb), hfloat);
#if NCH == 2
    illum_out1[i] = result[1];
    if (pc.write_history != 0u) STORE3(hist_color1, i, to_history(result[1].rgb), hfloat);
#endif
}
