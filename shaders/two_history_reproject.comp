#version 460
#extension GL_GOOGLE_include_directive : require
// two_history_reproject — temporal accumulation of the unweighted and the sample-count-weighted
// histories (SPEC §5; A-SVGF's per-pixel α, SPEC §4), one channel per dispatch. Mirrors
// TwoHistoryReprojectRef.
// Purpose: sanitise the illumination (NaN/Inf → 0, negative → 0, counted); back-project every
//   history with SVGF's tested taps (common/reprojection.glsl); β = min(1, (1/α − 1)/W_u,prev)
//   (0 on disocclusion); W_u ← βW_u + 1, W_w ← βW_w + n, S_k ← β²S_k + n^k; I_u += (x − I_u)/W_u,
//   I_w += n(x − I_w)/W_w; moments with max(α_m, 1/W_u); g ← β_g g + (1 − β_g)·lum(Σx − ΣI_u,prev)
//   over both channels (SHARED dispatch with the GRADIENT flag; g is one float, the signed
//   luminance of the gradient).
// Reads:  illumination, geometry of both frames, depth gradient, previous pixel, sample counts,
//         per-pixel α (A-SVGF), previous histories.
// Writes: this frame's histories (moments, W_u into the channel's length; W_w, S, g when SHARED;
//         colours when no à-trous iteration feeds back), (I_u, Var) and (I_w, Var), counters.
#include "shared_constants.h"
#include "common/two_history_constants.glsl"
#include "common/packing.glsl"
#include "common/access.glsl"
#include "common/luminance.glsl"
#include "common/reprojection.glsl"
#include "common/two_history.glsl"

layout(local_size_x = FOVRT_WORKGROUP_X, local_size_y = FOVRT_WORKGROUP_Y) in;

// Read-only planes: uniform texel buffers (common/access.glsl; formats in two_history_vk.cpp),
// except the fp16 RGB histories (RGB16F texel buffers are rarely supported), sample counts and α.
PLANE(TH_REPROJECT_B_COLOR, color);                // rgb32f
PLANE(TH_REPROJECT_B_COLOR_OTHER, color_other);    // rgb32f
PLANE(TH_REPROJECT_B_DEPTH, depth);                // r32f
PLANE(TH_REPROJECT_B_NORMAL, normal);              // rgb32f
UPLANE(TH_REPROJECT_B_OBJECT, object_id);          // r32ui
PLANE(TH_REPROJECT_B_PREV_DEPTH, prev_depth);      // r32f
PLANE(TH_REPROJECT_B_PREV_NORMAL, prev_normal);    // rgb32f
UPLANE(TH_REPROJECT_B_PREV_OBJECT, prev_object);   // r32ui
PLANE(TH_REPROJECT_B_DEPTH_GRAD, depth_grad);      // rg32f
PLANE(TH_REPROJECT_B_PREV_PIXEL, prev_pixel);      // rg32f
layout(std430, binding = TH_REPROJECT_B_SAMPLE_COUNT) readonly buffer SampleCount { uint sample_count[]; };
layout(std430, binding = TH_REPROJECT_B_ALPHA) readonly buffer AlphaMap { float alpha_map[]; };
#ifdef FOVRT_FP16
layout(std430, binding = TH_REPROJECT_B_PREV_IU) readonly buffer PrevIu { hfloat prev_iu[]; };
layout(std430, binding = TH_REPROJECT_B_PREV_IU_OTHER) readonly buffer PrevIuOther { hfloat prev_iu_other[]; };
layout(std430, binding = TH_REPROJECT_B_PREV_IW) readonly buffer PrevIw { hfloat prev_iw[]; };
layout(std430, binding = TH_REPROJECT_B_PREV_S) readonly buffer PrevS { hfloat prev_s[]; };
#define HIST3_LOAD LOAD3
#else
PLANE(TH_REPROJECT_B_PREV_IU, prev_iu);            // rgb32f
PLANE(TH_REPROJECT_B_PREV_IU_OTHER, prev_iu_other);
PLANE(TH_REPROJECT_B_PREV_IW, prev_iw);
PLANE(TH_REPROJECT_B_PREV_S, prev_s);
#define HIST3_LOAD FETCH3
#endif
PLANE(TH_REPROJECT_B_PREV_G, prev_g);              // r32f / r16f (luminance gradient)
PLANE(TH_REPROJECT_B_PREV_M, prev_m);              // rg32f / rg16f
PLANE(TH_REPROJECT_B_PREV_WU, prev_wu);            // r32f / r16f
PLANE(TH_REPROJECT_B_PREV_WW, prev_ww);            // r32f / r16f
layout(std430, binding = TH_REPROJECT_B_CUR_IU) writeonly buffer CurIu { hfloat cur_iu[]; };
layout(std430, binding = TH_REPROJECT_B_CUR_IW) writeonly buffer CurIw { hfloat cur_iw[]; };
layout(std430, binding = TH_REPROJECT_B_CUR_M) writeonly buffer CurM { hfloat cur_m[]; };
layout(std430, binding = TH_REPROJECT_B_CUR_WU) writeonly buffer CurWu { hfloat cur_wu[]; };
layout(std430, binding = TH_REPROJECT_B_CUR_WW) writeonly buffer CurWw { hfloat cur_ww[]; };
layout(std430, binding = TH_REPROJECT_B_CUR_S) writeonly buffer CurS { hfloat cur_s[]; };
layout(std430, binding = TH_REPROJECT_B_CUR_G) writeonly buffer CurG { hfloat cur_g[]; };
layout(std430, binding = TH_REPROJECT_B_ILLUM_U) writeonly buffer IllumU { vec4 illum_u[]; };
layout(std430, binding = TH_REPROJECT_B_ILLUM_W) writeonly buffer IllumW { vec4 illum_w[]; };
layout(std430, binding = TH_REPROJECT_B_STATS) buffer Stats { uint stats[]; };

// Mirrors TwoHistoryReprojectPush in denoise/two_history_vk.cpp.
layout(push_constant) uniform Push {
    ivec2 size;
    float alpha;
    float alpha_moments;
    float gradient_beta;
    uint flags;  // TH_REPROJECT_FLAG_*
} pc;

float reproj_prev_depth(int i) { return FETCH1(prev_depth, i); }
vec3 reproj_prev_normal(int i) { return FETCH3(prev_normal, i); }
uint reproj_prev_object(int i) { return FETCH1(prev_object, i); }

// NaN/Inf → 0, negative components → 0; counted only when `count` (each channel once).
vec3 sanitize(vec3 c, bool count) {
    if (any(isnan(c)) || any(isinf(c))) {
        if (count) atomicAdd(stats[0], 1u);
        return vec3(0.0);
    }
    if (any(lessThan(c, vec3(0.0)))) {
        if (count) atomicAdd(stats[1], 1u);
        return max(c, vec3(0.0));
    }
    return c;
}

// Bilinear gather of one history plane over the taps (GLSL cannot pass buffer arrays).
#define GATHER1(arr, taps, out_) REPROJ_GATHER(arr, taps, pc.size, FETCH1, 0.0, out_)
#define GATHER2(arr, taps, out_) REPROJ_GATHER(arr, taps, pc.size, FETCH2, vec2(0.0), out_)
#define GATHER3(arr, taps, out_) REPROJ_GATHER(arr, taps, pc.size, HIST3_LOAD, vec3(0.0), out_)

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, pc.size))) return;
    int i = p.y * pc.size.x + p.x;
    bool two = (pc.flags & TH_REPROJECT_FLAG_TWO_HISTORY) != 0u;
    bool combined = (pc.flags & TH_REPROJECT_FLAG_COMBINED) != 0u;
    bool shared_state = (pc.flags & TH_REPROJECT_FLAG_SHARED) != 0u;
    bool write_color = (pc.flags & TH_REPROJECT_FLAG_WRITE_COLOR) != 0u;

    ReprojTaps taps;
    taps.count = 0;
    if ((pc.flags & TH_REPROJECT_FLAG_HAS_PREV) != 0u) {
        vec2 dzv = FETCH2(depth_grad, i);
        taps = find_reprojection_taps(FETCH2(prev_pixel, i), pc.size, FETCH1(depth, i), FETCH3(normal, i),
                                      FETCH1(object_id, i),
                                      max(abs(dzv.x), abs(dzv.y)));
    }
    bool success = taps.count > 0;
    float n = float(max(LOAD_U16(sample_count, i), 1u));
    bool alpha_map_on = (pc.flags & TH_REPROJECT_FLAG_ALPHA_MAP) != 0u;
    float alpha = alpha_map_on ? alpha_map[i] : pc.alpha;
    float alpha_m = alpha_map_on ? alpha_map[i] : pc.alpha_moments;

    float wu_prev = 0.0, ww_prev = 0.0;
    vec3 s_prev = vec3(0.0);
    if (success) {
        GATHER1(prev_wu, taps, wu_prev);
        if (two) {
            GATHER1(prev_ww, taps, ww_prev);
            GATHER3(prev_s, taps, s_prev);
        }
    }
    float beta = success ? two_history_decay(alpha, wu_prev) : 0.0;
    float wu = beta * wu_prev + 1.0;
    float ww = beta * ww_prev + n;
    vec3 s = beta * beta * s_prev + vec3(1.0 / n, 1.0, n);
    float am = success ? max(alpha_m, 1.0 / wu) : 1.0;

    vec3 raw = FETCH3(color, i);
    if (combined) raw += FETCH3(color_other, i);
    vec3 x = sanitize(raw, true);
    float l = luminance(x);
    vec3 iu_prev = x, iw_prev = x;
    vec2 m_prev = vec2(l, l * l);
    if (success) {
        GATHER3(prev_iu, taps, iu_prev);
        GATHER2(prev_m, taps, m_prev);
        if (two) GATHER3(prev_iw, taps, iw_prev);
    }
    vec3 iu = iu_prev + (x - iu_prev) * (1.0 / wu);
    vec2 m = mix(m_prev, vec2(l, l * l), am);
    float variance = max(0.0, m.y - m.x * m.x);
    STORE2(cur_m, i, to_history(m), hfloat);
    cur_wu[i] = hfloat(to_history(wu));
    illum_u[i] = vec4(iu, variance);
    if (write_color) STORE3(cur_iu, i, to_history(iu), hfloat);
    if (two) {
        vec3 iw = iw_prev + (x - iw_prev) * (n / ww);
        illum_w[i] = vec4(iw, variance);
        if (write_color) STORE3(cur_iw, i, to_history(iw), hfloat);
    }
    if (two && shared_state) {
        cur_ww[i] = hfloat(to_history(ww));
        STORE3(cur_s, i, to_history(s), hfloat);
        if ((pc.flags & TH_REPROJECT_FLAG_GRADIENT) != 0u) {
            vec3 x_sum = x, iu_prev_sum = iu_prev;
            if ((pc.flags & TH_REPROJECT_FLAG_OTHER) != 0u) {
                vec3 xo = sanitize(FETCH3(color_other, i), false);
                vec3 iuo = xo;
                if (success) GATHER3(prev_iu_other, taps, iuo);
                x_sum += xo;
                iu_prev_sum += iuo;
            }
            float g_prev = 0.0;
            if (success) GATHER1(prev_g, taps, g_prev);
            float g = success ? g_prev * pc.gradient_beta +
                                    luminance(x_sum - iu_prev_sum) * (1.0 - pc.gradient_beta)
                              : 0.0;
            cur_g[i] = hfloat(to_history(g));
        }
    }
}
