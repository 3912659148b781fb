#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
// svgf_atrous — one edge-avoiding à-trous wavelet iteration (paper §4.3, SPEC §3).
// Purpose: 5×5 kernel h⊗h at step 2^i with w = w_z·w_n·w_l; w_l uses the 3×3 Gaussian-prefiltered
//   variance of the centre; colour = Σ h w c / Σ h w, variance = Σ h² w² Var / (Σ h w)².
//   On the feedback iteration (specialization constant FOVRT_SPEC_ATROUS_WRITE_HISTORY) the filtered
//   colour is also written as the colour history, at its window's index (pc.hist_size0/1 at
//   pc.hist_origin0/1: the image, or two-history's weighted history window). A pixel that holds nothing (HOLDS_NOTHING: no
//   sample, no history) has weight 0 as a tap, its own included, and as a centre no w_l: its
//   neighbours fill it; with none that holds anything it stays as it is.
// Channels: FOVRT_CHANNELS (1: "svgf_atrous", 2: "svgf_atrous_pair") illumination planes filtered
//   by one dispatch (direct + indirect, or the unweighted + weighted history of two-history). The
//   per-tap guide fetch, background test, depth gradient and w_z·w_n exponent are shared; each
//   channel keeps its own w_l and variance, so every channel gets exactly the 1-channel result.
//   A compile-time count, not a run-time flag: lavapipe executes both sides of every branch.
// Blocks: one invocation filters a 2×2 block of pixels at stride 2^i (see main), fetching the
//   6×6 tap lattice they share once: per pixel 9 (guide + channels) tap fetches instead of 25.
//   FOVRT_ATROUS_STEP1 ("…_step1", iteration 0 only): the four 3×3 variance windows are one 4×4
//   block, 4 fetches per pixel instead of 9. The host dispatches AtrousBlockGroups (denoise/vulkan/svgf_layout.h).
// Reads:  per channel illumination + variance (vec4); guide (normal, depth, background), depth gradient.
// Writes: per channel illumination + variance (vec4); colour history when kWriteHistory.
#include "shared_constants.h"
#include "push_constants.h"
#include "common/packing.glsl"
#include "common/access.glsl"
#include "common/luminance.glsl"
#include "common/edge_stopping.glsl"
#include "common/history_window.glsl"

#ifndef FOVRT_CHANNELS
#define FOVRT_CHANNELS 1
#endif
#define NCH FOVRT_CHANNELS

layout(local_size_x = FOVRT_WORKGROUP_X, local_size_y = FOVRT_WORKGROUP_Y) in;
layout(constant_id = FOVRT_SPEC_ATROUS_WRITE_HISTORY) const bool kWriteHistory = false;
layout(constant_id = FOVRT_SPEC_ATROUS_UNIT_WEIGHTS) const bool kUnitWeights = false;  // bench probe only

FOVRT_DECLARE_BINDINGS(SVGF_ATROUS_BINDING_LIST)  // shaders/bindings/svgf_atrous.h
#if NCH == 2
FOVRT_DECLARE_BINDINGS(SVGF_ATROUS_PAIR_BINDING_LIST)
#define FETCH_ILLUM(v, j) v[0] = FETCH4(illum_in0, j); v[1] = FETCH4(illum_in1, j)
#elif NCH == 1
#define FETCH_ILLUM(v, j) v[0] = FETCH4(illum_in0, j)
#else
#error "FOVRT_CHANNELS must be 1 or 2"
#endif

FOVRT_PUSH_CONSTANTS(FOVRT_PUSH_SVGF_ATROUS);  // shaders/push_constants.h

bool inside(ivec2 q) { return in_image(q, pc.size); }

// 2×2 pixel blocks at stride s = step: one invocation filters P_k = base + s·(k & 1, k >> 1),
// k = 0..3, where base has bit i (s = 2^i) of x and y cleared. The 5×5 windows of the four pixels
// cover a 6×6 lattice of stride s, so each lattice texel (guide + channels) is fetched once for
// four pixels: 36 instead of 100 tap fetches. Per pixel the maths and the summation order (rows,
// then columns) are those of the 1-pixel filter and of SvgfAtrousRef. Blocks per axis:
// (n / 2s)·s + min(n mod 2s, s) (AtrousBlockGroups). FOVRT_ATROUS_BLOCK_Y = 1 (shared_constants.h)
// gives 2×1 blocks (pairs along x, a 6×5 lattice), measured slower on lavapipe (denoise/svgf.md).
#define BY FOVRT_ATROUS_BLOCK_Y     // block rows (1: 2×1 blocks, pairs along x)
#define BK (2 * BY)                  // pixels per block
int block_base(int b, int s) { return ((b / s) * 2 * s) + (b % s); }

void main() {
    ivec2 b = ivec2(gl_GlobalInvocationID.xy);
    const int s = pc.step;
#if BY == 2
    ivec2 base = ivec2(block_base(b.x, s), block_base(b.y, s));
#else
    ivec2 base = ivec2(block_base(b.x, s), b.y);
#endif
    if (!inside(base)) return;  // the group round-up past the last block
    ivec2 pix[BK];
    bool valid[BK];
    [[unroll]] for (int k = 0; k < BK; ++k) {
        pix[k] = base + ivec2(k & 1, k >> 1) * s;
        valid[k] = inside(pix[k]);
    }
    // Centre texels: captured by the variance prefilter below (the centre is one of its taps).
    // Pixels outside the image keep a background guide, so they are never filtered or stored.
    vec4 gc[BK], center[BK][NCH];
    float var_sum[BK][NCH], var_w[BK];
    [[unroll]] for (int k = 0; k < BK; ++k) {
        gc[k] = vec4(0.0, 0.0, 0.0, -1.0);
        var_w[k] = 0.0;
        [[unroll]] for (int c = 0; c < NCH; ++c) {
            center[k][c] = vec4(0.0);
            var_sum[k][c] = 0.0;
        }
    }
    // 3×3 Gaussian of the variance (always step 1), only to steer w_l.
#if FOVRT_ATROUS_STEP1
    // s = 1: the four 3×3 windows are one 4×4 block (16 fetches instead of 36).
    [[unroll]] for (int vy = 0; vy < 2 + BY; ++vy)
        [[unroll]] for (int vx = 0; vx < 4; ++vx) {
            ivec2 q = base + ivec2(vx - 1, vy - 1);
            const bool q_inside = inside(q);
            int j = clamped_index(q, pc.size);
            vec4 gq = FETCH4(guide, j);
            vec4 v[NCH];
            FETCH_ILLUM(v, j);
            const bool use = q_inside && !GUIDE_IS_BACKGROUND(gq) && !HOLDS_NOTHING(v[0]);
            [[unroll]] for (int k = 0; k < BK; ++k) {
                const int dx = vx - 1 - (k & 1), dy = vy - 1 - (k >> 1);
                if (dx < -1 || dx > 1 || dy < -1 || dy > 1) continue;  // compile-time
                if (dx == 0 && dy == 0) {
                    gc[k] = q_inside ? gq : gc[k];
                    center[k] = v;  // only read where gc[k] is not background
                }
                float g = use ? gauss3(dx, dy) : 0.0;
                [[unroll]] for (int c = 0; c < NCH; ++c) var_sum[k][c] += g * v[c].a;
                var_w[k] += g;
            }
        }
#else
    // s ≥ 2: the four 3×3 windows do not share a row and a column at once; fetch each.
    [[unroll]] for (int k = 0; k < BK; ++k)
        [[unroll]] for (int dy = -1; dy <= 1; ++dy)
            [[unroll]] for (int dx = -1; dx <= 1; ++dx) {
                ivec2 q = pix[k] + ivec2(dx, dy);
                const bool q_inside = inside(q);
                int j = clamped_index(q, pc.size);
                vec4 gq = FETCH4(guide, j);
                vec4 v[NCH];
                FETCH_ILLUM(v, j);
                if (dx == 0 && dy == 0) {
                    gc[k] = q_inside ? gq : gc[k];
                    center[k] = v;  // only read where gc[k] is not background
                }
                float g = q_inside && !GUIDE_IS_BACKGROUND(gq) && !HOLDS_NOTHING(v[0]) ? gauss3(dx, dy) : 0.0;
                [[unroll]] for (int c = 0; c < NCH; ++c) var_sum[k][c] += g * v[c].a;
                var_w[k] += g;
            }
#endif
    bool filtered[BK];
    vec2 gp[BK];
    float lp[BK][NCH], inv_l_den[BK][NCH], sum_w[BK][NCH], sum_v[BK][NCH];
    vec3 sum_c[BK][NCH];
    [[unroll]] for (int k = 0; k < BK; ++k) {
        filtered[k] = !GUIDE_IS_BACKGROUND(gc[k]);
        gp[k] = valid[k] ? FETCH2(depth_grad, pix[k].y * pc.size.x + pix[k].x) : vec2(0.0);
        [[unroll]] for (int c = 0; c < NCH; ++c) {
            float sigma_l_std = pc.sigma_luminance * sqrt(max(0.0, var_w[k] > 0.0 ? var_sum[k][c] / var_w[k] : 0.0));
            lp[k][c] = luminance(center[k][c].rgb);
            // A centre that holds nothing has no luminance to stop at.
            inv_l_den[k][c] = HOLDS_NOTHING(center[k][0]) ? 0.0 : 1.0 / (sigma_l_std + FOVRT_ATROUS_LUMINANCE_EPSILON);
            sum_w[k][c] = 0.0;
            sum_c[k][c] = vec3(0.0);
            sum_v[k][c] = 0.0;
        }
    }
    // The 6×6 lattice row by row; lattice (lx, ly) is tap (lx − 2 − ax, ly − 2 − ay) of pixel
    // (ax, ay) = (k & 1, k >> 1) when that lies in [−2, 2]² (resolved at compile time).
    [[unroll]] for (int ly = 0; ly < 4 + BY; ++ly) {
        [[unroll]] for (int lx = 0; lx < 6; ++lx) {
            ivec2 q = base + ivec2(lx - 2, ly - 2) * s;
            int j = clamped_index(q, pc.size);
            vec4 gq = FETCH4(guide, j);
            vec4 cq[NCH];
            FETCH_ILLUM(cq, j);
            const bool use = inside(q) && !GUIDE_IS_BACKGROUND(gq) && !HOLDS_NOTHING(cq[0]);
            [[unroll]] for (int k = 0; k < BK; ++k) {
                const int kx = lx - 2 - (k & 1), ky = ly - 2 - (k >> 1);
                if (kx < -2 || kx > 2 || ky < -2 || ky > 2) continue;  // compile-time
                float h = kAtrousKernel[kx + 2] * kAtrousKernel[ky + 2];
                ivec2 off = ivec2(kx, ky) * s;
                // Geometric part of the exponent, once for all channels.
                const bool centre = kx == 0 && ky == 0;
                float depth_term = centre ? 0.0 : geometry_depth_term(gc[k].w, gq.w, gp[k], vec2(off), pc.sigma_depth);
                float normal_log2 = centre ? 0.0 : geometry_normal_log2(gc[k].xyz, gq.xyz, pc.sigma_normal);
                float normal_factor = centre ? 1.0 : geometry_normal_factor(gc[k].xyz, gq.xyz);
                [[unroll]] for (int c = 0; c < NCH; ++c) {
                    float w = centre ? 1.0
                                     : geometry_weight_from_terms(depth_term, normal_log2, normal_factor,
                                                                  abs(lp[k][c] - luminance(cq[c].rgb)) * inv_l_den[k][c]);
                    w = use ? (kUnitWeights ? 1.0 : w) : 0.0;
                    float hw = h * w;
                    sum_w[k][c] += hw;
                    sum_c[k][c] += hw * cq[c].rgb;
                    sum_v[k][c] += hw * hw * cq[c].a;
                }
            }
        }
    }
    [[unroll]] for (int k = 0; k < BK; ++k) {
        if (!valid[k]) continue;
        int i = pix[k].y * pc.size.x + pix[k].x;
        vec4 result[NCH];
        [[unroll]] for (int c = 0; c < NCH; ++c)
            result[c] = filtered[k] && sum_w[k][c] > 0.0
                            ? vec4(sum_c[k][c] / sum_w[k][c], sum_v[k][c] / (sum_w[k][c] * sum_w[k][c]))
                            : center[k][c];
        illum_out0[i] = TO_ILLUM(result[0]);
        int h0 = window_index(pix[k], pc.hist_origin0, pc.hist_size0);
        if (kWriteHistory && h0 >= 0) STORE3(hist_color0, h0, to_history(result[0].rgb), hfloat);
#if NCH == 2
        illum_out1[i] = TO_ILLUM(result[1]);
        int h1 = window_index(pix[k], pc.hist_origin1, pc.hist_size1);
        if (kWriteHistory && h1 >= 0) STORE3(hist_color1, h1, to_history(result[1].rgb), hfloat);
#endif
    }
}
