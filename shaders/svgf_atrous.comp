#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
// svgf_atrous — one edge-avoiding à-trous wavelet iteration (paper §4.3, SPEC §3).
// Purpose: 5×5 kernel h⊗h at step 2^i with w = w_z·w_n·w_l; w_l uses the 3×3 Gaussian-prefiltered
//   variance of the centre; colour = Σ h w c / Σ h w, variance = Σ h² w² Var / (Σ h w)².
//   On the feedback iteration the filtered colour is also written as the colour history.
// Reads:  illumination + variance (vec4), guide (normal, depth, background), depth gradient.
// Writes: illumination + variance (vec4); colour history when write_history != 0.
#include "shared_constants.h"
#include "common/packing.glsl"
#include "common/access.glsl"
#include "common/luminance.glsl"
#include "common/edge_stopping.glsl"

layout(local_size_x = FOVRT_WORKGROUP_X, local_size_y = FOVRT_WORKGROUP_Y) in;

// Read-only planes: uniform texel buffers (common/access.glsl; formats in denoise/svgf_texel_formats.h).
PLANE(SVGF_ATROUS_B_ILLUM_IN, illum_in);       // rgba32f
PLANE(SVGF_ATROUS_B_GUIDE, guide);             // rgba32f (normal, depth; svgf_pack_guide)
PLANE(SVGF_ATROUS_B_DEPTH_GRAD, depth_grad);   // rg32f
layout(std430, binding = SVGF_ATROUS_B_ILLUM_OUT) writeonly buffer IllumOut { vec4 illum_out[]; };
layout(std430, binding = SVGF_ATROUS_B_HIST_COLOR) writeonly buffer HistColor { hfloat hist_color[]; };

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
    vec4 center = FETCH4(illum_in, i);
    vec4 result = center;
    vec4 gc = FETCH4(guide, i);
    if (!GUIDE_IS_BACKGROUND(gc)) {
        // 3×3 Gaussian of the variance, only to steer w_l.
        float var_sum = 0.0, var_w = 0.0;
        [[unroll]] for (int dy = -1; dy <= 1; ++dy)
            [[unroll]] for (int dx = -1; dx <= 1; ++dx) {
                ivec2 q = p + ivec2(dx, dy);
                if (!inside(q)) continue;
                int j = q.y * pc.size.x + q.x;
                if (GUIDE_IS_BACKGROUND(FETCH4(guide, j))) continue;
                float g = gauss3(dx, dy);
                var_sum += g * FETCH4(illum_in, j).a;
                var_w += g;
            }
        float sigma_l_std = pc.sigma_luminance * sqrt(max(0.0, var_sum / var_w));
        float zp = gc.w;
        vec3 np = gc.xyz;
        vec2 gp = FETCH2(depth_grad, i);
        float lp = luminance(center.rgb);
        float inv_l_den = 1.0 / (sigma_l_std + FOVRT_ATROUS_LUMINANCE_EPSILON);
        float sum_w = 0.0;
        vec3 sum_c = vec3(0.0);
        float sum_v = 0.0;
        [[unroll]] for (int ky = -2; ky <= 2; ++ky) {
            [[unroll]] for (int kx = -2; kx <= 2; ++kx) {
                ivec2 off = ivec2(kx, ky) * pc.step;
                ivec2 q = p + off;
                if (!inside(q)) continue;
                int j = q.y * pc.size.x + q.x;
                vec4 gq = FETCH4(guide, j);
                if (GUIDE_IS_BACKGROUND(gq)) continue;
                vec4 cq = FETCH4(illum_in, j);
                float h = kAtrousKernel[kx + 2] * kAtrousKernel[ky + 2];
                float w = (kx == 0 && ky == 0)
                              ? 1.0
                              : geometry_weight(zp, gq.w, gp, vec2(off), pc.sigma_depth, np, gq.xyz,
                                                pc.sigma_normal, abs(lp - luminance(cq.rgb)) * inv_l_den);
                float hw = h * w;
                sum_w += hw;
                sum_c += hw * cq.rgb;
                sum_v += hw * hw * cq.a;
            }
        }
        result = vec4(sum_c / sum_w, sum_v / (sum_w * sum_w));
    }
    illum_out[i] = result;
    if (pc.write_history != 0u) STORE3(hist_color, i, to_history(result.rgb), hfloat);
}
