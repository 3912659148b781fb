#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
// svgf_reproject — SVGF temporal accumulation (paper §4.1, SPEC §3).
// Purpose: sanitise the noisy demodulated illumination (NaN/Inf/negative → 0, counted), back-project
//   the previous history with the tested 2×2 bilinear taps (3×3 fallback, else disocclusion), and
//   blend: C' = lerp(C_prev, C, α_c) with α_c = max(α, 1/length) — or, in weighted mode (svgf-weighted,
//   SPEC §5), W ← (1−α)·W_prev + n, C' = C_prev + n·(C − C_prev)/W. Moments (l, l²) use
//   α_m = max(α_m, 1/length). History length is interpolated from the valid taps, +1, capped.
//   n = 0 (no path sample; weighted, or ZERO_SAMPLES: the unweighted mode reading the counts
//   because the spp map may hold zeros): the reprojected history is kept as it is (length,
//   weight, moments, colour); without one the pixel holds nothing (length 0, FOVRT_EMPTY_VARIANCE).
// Passes: "svgf_reproject[_pair]" runs on every pixel with the bilinear taps and lists the pixels
//   whose taps all failed (their disocclusion result is written meanwhile); "…_box" runs on the
//   listed pixels only (indirect dispatch) with the 3×3 fallback taps and overwrites their results
//   (common/reprojection.glsl explains why two passes). Sanitising is counted by the first only.
// Channels: FOVRT_CHANNELS (1: one channel, or direct + indirect summed when combined; 2: "_pair",
//   direct = COLOR_IN and indirect = COLOR_IN2 with their own histories at the *2 bindings). The
//   taps (consistency tests on the previous geometry) are found once per pixel for both channels;
//   each channel's arithmetic is the one-channel arithmetic.
// Modes: SVGF_REPROJECT_FLAG_* as the specialization constant FOVRT_SPEC_REPROJECT_FLAGS.
// Reads:  colour in (+ second channel), depth/normal/object of both frames, depth gradient,
//         previous pixel, sample counts (weighted, ZERO_SAMPLES), previous colour/moments/length/weight
//         per channel.
// Writes: per channel this frame's moments/length/weight (and colour history when no à-trous
//         feedback), illumination + temporal variance (vec4); sanitising counters; the list.
#include "shared_constants.h"
#include "push_constants.h"
#include "common/packing.glsl"
#include "common/access.glsl"
#include "common/luminance.glsl"
#include "common/reprojection.glsl"

#ifndef FOVRT_CHANNELS
#define FOVRT_CHANNELS 1
#endif
#define NCH FOVRT_CHANNELS

#if FOVRT_REPROJECT_BOX
layout(local_size_x = FOVRT_SPATIAL_LIST_GROUP) in;
#else
layout(local_size_x = FOVRT_WORKGROUP_X, local_size_y = FOVRT_WORKGROUP_Y) in;
#endif
layout(constant_id = FOVRT_SPEC_REPROJECT_FLAGS) const uint kFlags = 0u;
const bool kWeighted = (kFlags & SVGF_REPROJECT_FLAG_WEIGHTED) != 0u;
const bool kCombined = (kFlags & SVGF_REPROJECT_FLAG_COMBINED) != 0u;
const bool kWriteColor = (kFlags & SVGF_REPROJECT_FLAG_WRITE_COLOR) != 0u;
const bool kZeroSamples = (kFlags & SVGF_REPROJECT_FLAG_ZERO_SAMPLES) != 0u;

FOVRT_DECLARE_BINDINGS(SVGF_REPROJECT_BINDING_LIST)  // shaders/bindings/svgf_reproject.h
#if NCH == 2
FOVRT_DECLARE_BINDINGS(SVGF_REPROJECT_PAIR_BINDING_LIST)
#elif NCH != 1
#error "FOVRT_CHANNELS must be 1 or 2"
#endif
#define PIXEL_LIST_B_ARGS SVGF_REPROJECT_B_LIST_ARGS
#define PIXEL_LIST_B_LIST SVGF_REPROJECT_B_LIST
#include "common/pixel_list.glsl"
// The fp16 colour history is a storage buffer (RGB16F texel buffers are rarely supported).
#ifdef FOVRT_FP16
#define PREV_COLOR_LOAD LOAD3
#else
#define PREV_COLOR_LOAD FETCH3
#endif

FOVRT_PUSH_CONSTANTS(FOVRT_PUSH_SVGF_REPROJECT);  // shaders/push_constants.h

float reproj_prev_depth(int i) { return FETCH_DEPTH(prev_depth, i); }
vec3 reproj_prev_normal(int i) { return FETCH_NORMAL(prev_normal, i); }
uint reproj_prev_object(int i) { return FETCH_OBJECT(prev_object, i); }

// Sanitise: a non-finite pixel becomes 0 (stats[0]); negative components are clamped to 0 (stats[1]).
// Counted by the main pass only: the box pass revisits pixels it has counted.
vec3 sanitise(vec3 c) {
    if (any(isnan(c)) || any(isinf(c))) {
        if (!bool(FOVRT_REPROJECT_BOX)) atomicAdd(stats[0], 1u);
        return vec3(0.0);
    }
    if (any(lessThan(c, vec3(0.0)))) {
        if (!bool(FOVRT_REPROJECT_BOX)) atomicAdd(stats[1], 1u);
        return max(c, vec3(0.0));
    }
    return c;
}

// Gathers channel k's previous history over the taps into c_prev[k], m_prev[k], len_prev[k], w_prev[k].
#define GATHER_HISTORY(k)                                                                       \
    do {                                                                                        \
        REPROJ_GATHER(hist_prev_color##k, taps, pc.size, PREV_COLOR_LOAD, vec3(0.0), c_prev[k]); \
        REPROJ_GATHER(hist_prev_moments##k, taps, pc.size, FETCH2, vec2(0.0), m_prev[k]);        \
        REPROJ_GATHER(hist_prev_length##k, taps, pc.size, FETCH1, 0.0, len_prev[k]);             \
        w_prev[k] = 0.0;                                                                        \
        if (kWeighted) REPROJ_GATHER(hist_prev_weight##k, taps, pc.size, FETCH1, 0.0, w_prev[k]); \
    } while (false)

// Writes channel k's accumulated history and illumination.
#define WRITE_HISTORY(k)                                                                                     \
    do {                                                                                                     \
        if (kWeighted) hist_weight##k[i] = hfloat(to_history(total[k]));                                     \
        STORE2(hist_moments##k, i, to_history(m_acc[k]), hfloat);                                            \
        hist_length##k[i] = hfloat(len[k]);                                                                  \
        if (kWriteColor) STORE3(hist_color##k, i, to_history(c_acc[k]), hfloat);                             \
        illum_out##k[i] = TO_ILLUM(n == 0.0 && len[k] == 0.0                                                  \
                                       ? vec4(vec3(0.0), FOVRT_EMPTY_VARIANCE)                               \
                                       : vec4(c_acc[k], max(0.0, m_acc[k].y - m_acc[k].x * m_acc[k].x)));    \
    } while (false)

// Accumulates pixel i with this pass's taps; true when the main pass found no bilinear tap on an
// on-screen object pixel (the box pass decides it).
bool reproject_pixel(int i) {
    vec3 c[NCH];
#if NCH == 2
    c[0] = sanitise(FETCH3(color_in, i));
    c[1] = sanitise(FETCH3(color_in2, i));
#else
    c[0] = FETCH3(color_in, i);
    if (kCombined) c[0] += FETCH3(color_in2, i);
    c[0] = sanitise(c[0]);
#endif

    ReprojTaps taps;
    taps.count = 0;
    taps.needs_box = false;
    if (pc.has_prev != 0u) {
        vec2 dzv = FETCH2(depth_grad, i);
        taps = find_reprojection_taps(FETCH2(prev_pixel, i), pc.size, FETCH_DEPTH(depth, i), FETCH_NORMAL(normal, i),
                                      FETCH_OBJECT(object_id, i), max(abs(dzv.x), abs(dzv.y)));
    }
    vec3 c_prev[NCH];
    vec2 m_prev[NCH];
    float len_prev[NCH], w_prev[NCH];
    GATHER_HISTORY(0);
#if NCH == 2
    GATHER_HISTORY(1);
#endif
    bool success = taps.count > 0;
    float n = REPROJ_SAMPLE_COUNT(sample_count, i, kWeighted, kZeroSamples);

    vec3 c_acc[NCH];
    vec2 m_acc[NCH];
    float len[NCH], total[NCH];
    [[unroll]] for (int k = 0; k < NCH; ++k) {
        float l = luminance(c[k]);
        vec2 m = vec2(l, l * l);
        if (n == 0.0) {  // no path sample: the reprojected history as it is, or nothing
            bool held = success && len_prev[k] > 0.0;
            total[k] = held ? w_prev[k] : 0.0;
            c_acc[k] = held ? c_prev[k] : vec3(0.0);
            m_acc[k] = held ? m_prev[k] : vec2(0.0);
            len[k] = held ? len_prev[k] : 0.0;
            continue;
        }
        len[k] = success ? min(len_prev[k] + 1.0, FOVRT_MAX_HISTORY_LENGTH) : 1.0;
        if (kWeighted) {
            total[k] = (success ? (1.0 - pc.alpha_color) * w_prev[k] : 0.0) + n;
            c_acc[k] = success ? c_prev[k] + (n / total[k]) * (c[k] - c_prev[k]) : c[k];
        } else {
            total[k] = 0.0;
            float a = success ? max(pc.alpha_color, 1.0 / len[k]) : 1.0;
            c_acc[k] = mix(c_prev[k], c[k], a);
        }
        float am = success ? max(pc.alpha_moments, 1.0 / len[k]) : 1.0;
        m_acc[k] = mix(m_prev[k], m, am);
    }
    WRITE_HISTORY(0);
#if NCH == 2
    WRITE_HISTORY(1);
#endif
    return taps.needs_box;
}

void main() {
#if FOVRT_REPROJECT_BOX
    uint k;
    if (pixel_list_entry(k)) reproject_pixel(pixel_list_at(k));
#else
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, pc.size))) return;
    int i = p.y * pc.size.x + p.x;
    if (reproject_pixel(i)) pixel_list_append(i);
#endif
}
