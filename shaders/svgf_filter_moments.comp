#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
// svgf_filter_moments — spatial variance estimate where the temporal one is unreliable
// (paper §4.2, SPEC §3, Falcor SVGFFilterMoments).
// Purpose: where history length < threshold, replace illumination and variance by a 7×7 bilateral
//   estimate (weights w_z·w_n): illum = Σw c / Σw, variance = max(0, m2 − m1²) of Σw m / Σw,
//   boosted by threshold / length for the first frames. Elsewhere pass through. A pixel that holds
//   nothing (HOLDS_NOTHING) is no neighbour, and one listed itself takes its neighbours' estimate.
// Dispatch: indirect, one invocation per pixel listed by svgf_moments_classify (not background,
//   length < threshold); the host copies the input to the output for every other pixel first.
// Reads:  illumination + variance (vec4), guide (normal, depth, background), depth gradient,
//         this frame's moments and history length.
// Writes: illumination + variance (vec4).
#include "shared_constants.h"
#include "push_constants.h"
#include "common/packing.glsl"
#include "common/access.glsl"
#include "common/edge_stopping.glsl"
FOVRT_DECLARE_BINDINGS(SVGF_MOMENTS_BINDING_LIST)  // shaders/bindings/svgf_filter_moments.h
#define PIXEL_LIST_B_ARGS SVGF_MOMENTS_B_ARGS
#define PIXEL_LIST_B_LIST SVGF_MOMENTS_B_LIST
#include "common/pixel_list.glsl"

layout(local_size_x = FOVRT_SPATIAL_LIST_GROUP) in;

FOVRT_PUSH_CONSTANTS(FOVRT_PUSH_SVGF_FILTER_MOMENTS);  // shaders/push_constants.h

void filter_pixel(int i) {
    ivec2 p = ivec2(i % pc.size.x, i / pc.size.x);
    float len = FETCH1(hist_length, i);
    vec4 gc = FETCH4(guide, i);
    float zp = gc.w;
    vec3 np = gc.xyz;
    vec2 gp = FETCH2(depth_grad, i);
    float sum_w = 0.0;
    vec3 sum_c = vec3(0.0);
    vec2 sum_m = vec2(0.0);
    [[unroll]] for (int dy = -FOVRT_MOMENTS_RADIUS; dy <= FOVRT_MOMENTS_RADIUS; ++dy) {
        [[unroll]] for (int dx = -FOVRT_MOMENTS_RADIUS; dx <= FOVRT_MOMENTS_RADIUS; ++dx) {
            ivec2 q = p + ivec2(dx, dy);
            if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, pc.size))) continue;
            int j = q.y * pc.size.x + q.x;
            vec4 gq = FETCH4(guide, j);
            vec4 cq = FETCH4(illum_in, j);
            if (GUIDE_IS_BACKGROUND(gq) || HOLDS_NOTHING(cq)) continue;
            float w = geometry_weight(zp, gq.w, gp, vec2(dx, dy), pc.sigma_depth, np, gq.xyz,
                                      pc.sigma_normal, 0.0);
            sum_w += w;
            sum_c += w * cq.rgb;
            sum_m += w * FETCH2(moments, j);
        }
    }
    // The centre has weight 1, so sum_w ≥ 1, unless it holds nothing: then its neighbours fill it,
    // and where none holds anything it stays as it is.
    if (sum_w == 0.0) {
        illum_out[i] = hvec4(FETCH4(illum_in, i));
        return;
    }
    vec2 m = sum_m / sum_w;
    float variance = max(0.0, m.y - m.x * m.x) * (pc.threshold / max(len, 1.0));
    illum_out[i] = TO_ILLUM(vec4(sum_c / sum_w, variance));
}

void main() {
    uint k;
    if (pixel_list_entry(k)) filter_pixel(pixel_list_at(k));
}
