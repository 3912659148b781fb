#version 460
#extension GL_GOOGLE_include_directive : require
// svgf_reproject — SVGF temporal accumulation (paper §4.1, SPEC §3), one illumination channel.
// Purpose: sanitise the noisy demodulated illumination (NaN/Inf/negative → 0, counted), back-project
//   the previous history with the tested 2×2 bilinear taps (3×3 fallback, else disocclusion), and
//   blend: C' = lerp(C_prev, C, α_c) with α_c = max(α, 1/length) — or, in weighted mode (svgf-weighted,
//   SPEC §5), W ← (1−α)·W_prev + n, C' = C_prev + n·(C − C_prev)/W. Moments (l, l²) use
//   α_m = max(α_m, 1/length). History length is interpolated from the valid taps, +1, capped.
// Reads:  colour in (+ second channel when combined), depth/normal/object of both frames, depth
//         gradient, previous pixel, sample counts (weighted), previous colour/moments/length/weight.
// Writes: this frame's moments/length/weight (and colour history when no à-trous feedback),
//         illumination + temporal variance (vec4), sanitising counters.
#include "shared_constants.h"
#include "common/packing.glsl"
#include "common/access.glsl"
#include "common/luminance.glsl"
#include "common/reprojection.glsl"

layout(local_size_x = FOVRT_WORKGROUP_X, local_size_y = FOVRT_WORKGROUP_Y) in;

// Read-only planes: uniform texel buffers (common/access.glsl; formats in denoise/svgf_texel_formats.h),
// except the fp16 colour history (RGB16F texel buffers are not widely supported) and the sample counts.
PLANE(SVGF_REPROJECT_B_COLOR_IN, color_in);            // rgb32f
PLANE(SVGF_REPROJECT_B_COLOR_IN2, color_in2);          // rgb32f
PLANE(SVGF_REPROJECT_B_DEPTH, depth);                  // r32f
PLANE(SVGF_REPROJECT_B_NORMAL, normal);                // rgb32f
UPLANE(SVGF_REPROJECT_B_OBJECT, object_id);            // r32ui
PLANE(SVGF_REPROJECT_B_PREV_DEPTH, prev_depth);        // r32f
PLANE(SVGF_REPROJECT_B_PREV_NORMAL, prev_normal);      // rgb32f
UPLANE(SVGF_REPROJECT_B_PREV_OBJECT, prev_object);     // r32ui
PLANE(SVGF_REPROJECT_B_DEPTH_GRAD, depth_grad);        // rg32f
PLANE(SVGF_REPROJECT_B_PREV_PIXEL, prev_pixel);        // rg32f
layout(std430, binding = SVGF_REPROJECT_B_SAMPLE_COUNT) readonly buffer SampleCount { uint sample_count[]; };
#ifdef FOVRT_FP16
layout(std430, binding = SVGF_REPROJECT_B_PREV_COLOR) readonly buffer PrevColor { hfloat hist_prev_color[]; };
#define PREV_COLOR_LOAD LOAD3
#else
PLANE(SVGF_REPROJECT_B_PREV_COLOR, hist_prev_color);   // rgb32f
#define PREV_COLOR_LOAD FETCH3
#endif
PLANE(SVGF_REPROJECT_B_PREV_MOMENTS, hist_prev_moments);  // rg32f / rg16f
PLANE(SVGF_REPROJECT_B_PREV_LENGTH, hist_prev_length);    // r32f / r16f
PLANE(SVGF_REPROJECT_B_PREV_WEIGHT, hist_prev_weight);    // r32f / r16f
layout(std430, binding = SVGF_REPROJECT_B_CUR_COLOR) writeonly buffer CurColor { hfloat hist_color[]; };
layout(std430, binding = SVGF_REPROJECT_B_CUR_MOMENTS) writeonly buffer CurMoments { hfloat hist_moments[]; };
layout(std430, binding = SVGF_REPROJECT_B_CUR_LENGTH) writeonly buffer CurLength { hfloat hist_length[]; };
layout(std430, binding = SVGF_REPROJECT_B_CUR_WEIGHT) writeonly buffer CurWeight { hfloat hist_weight[]; };
layout(std430, binding = SVGF_REPROJECT_B_ILLUM_OUT) writeonly buffer IllumOut { vec4 illum_out[]; };
layout(std430, binding = SVGF_REPROJECT_B_STATS) buffer Stats { uint stats[]; };

// Mirrors SvgfReprojectPush in denoise/svgf_layout.h.
layout(push_constant) uniform Push {
    ivec2 size;
    float alpha_color;
    float alpha_moments;
    uint flags;  // SVGF_REPROJECT_FLAG_*
} pc;

#define SVGF_REPROJECT_FLAG_WEIGHTED 1u
#define SVGF_REPROJECT_FLAG_COMBINED 2u
#define SVGF_REPROJECT_FLAG_WRITE_COLOR 4u

float reproj_prev_depth(int i) { return FETCH1(prev_depth, i); }
vec3 reproj_prev_normal(int i) { return FETCH3(prev_normal, i); }
uint reproj_prev_object(int i) { return FETCH1(prev_object, i); }

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, pc.size))) return;
    int i = p.y * pc.size.x + p.x;

    // Sanitise: a non-finite pixel becomes 0; negative components are clamped to 0.
    vec3 c = FETCH3(color_in, i);
    if ((pc.flags & SVGF_REPROJECT_FLAG_COMBINED) != 0u) c += FETCH3(color_in2, i);
    if (any(isnan(c)) || any(isinf(c))) {
        c = vec3(0.0);
        atomicAdd(stats[0], 1u);
    } else if (any(lessThan(c, vec3(0.0)))) {
        c = max(c, vec3(0.0));
        atomicAdd(stats[1], 1u);
    }
    float l = luminance(c);
    vec2 m = vec2(l, l * l);

    uint id = FETCH1(object_id, i);
    vec2 dzv = FETCH2(depth_grad, i);
    ReprojTaps taps = find_reprojection_taps(FETCH2(prev_pixel, i), pc.size, FETCH1(depth, i), FETCH3(normal, i),
                                             id, max(abs(dzv.x), abs(dzv.y)));
    vec3 c_prev = vec3(0.0);
    vec2 m_prev = vec2(0.0);
    float len_prev = 0.0;
    float w_prev = 0.0;
    bool weighted = (pc.flags & SVGF_REPROJECT_FLAG_WEIGHTED) != 0u;
    REPROJ_GATHER(hist_prev_color, taps, pc.size, PREV_COLOR_LOAD, vec3(0.0), c_prev);
    REPROJ_GATHER(hist_prev_moments, taps, pc.size, FETCH2, vec2(0.0), m_prev);
    REPROJ_GATHER(hist_prev_length, taps, pc.size, FETCH1, 0.0, len_prev);
    if (weighted) REPROJ_GATHER(hist_prev_weight, taps, pc.size, FETCH1, 0.0, w_prev);
    bool success = taps.count > 0;
    float len = success ? min(len_prev + 1.0, FOVRT_MAX_HISTORY_LENGTH) : 1.0;

    vec3 c_acc;
    if (weighted) {
        float n = float(max(LOAD_U16(sample_count, i), 1u));
        float total = (success ? (1.0 - pc.alpha_color) * w_prev : 0.0) + n;
        c_acc = success ? c_prev + (n / total) * (c - c_prev) : c;
        hist_weight[i] = hfloat(to_history(total));
    } else {
        float a = success ? max(pc.alpha_color, 1.0 / len) : 1.0;
        c_acc = mix(c_prev, c, a);
    }
    float am = success ? max(pc.alpha_moments, 1.0 / len) : 1.0;
    vec2 m_acc = mix(m_prev, m, am);

    STORE2(hist_moments, i, to_history(m_acc), hfloat);
    hist_length[i] = hfloat(len);
    if ((pc.flags & SVGF_REPROJECT_FLAG_WRITE_COLOR) != 0u) STORE3(hist_color, i, to_history(c_acc), hfloat);
    float variance = max(0.0, m_acc.y - m_acc.x * m_acc.x);
    illum_out[i] = vec4(c_acc, variance);
}
