#version 460
#extension GL_GOOGLE_include_directive : require
// two_history_reproject — temporal accumulation of the unweighted and the sample-count-weighted
// histories (SPEC §5; A-SVGF's per-pixel α, SPEC §4). Mirrors TwoHistoryReprojectRef.
// Purpose: sanitise the illumination (NaN/Inf → 0, negative → 0, counted); back-project every
//   history with SVGF's tested taps (common/reprojection.glsl); β = min(1, (1/α − 1)/W_u,prev)
//   (0 on disocclusion; ANTILAG: α = antilag_alpha of the map's a, W_u,prev and the base α);
//   FIREFLY: x scaled down to max(μ + kσ of its reprojected moments, its 8 neighbours' largest
//   sample luminance) where W_u,prev ≥ FOVRT_FIREFLY_MIN_HISTORY (suppress_firefly), before it
//   enters any history;
//   W_u ← βW_u + 1, W_w ← βW_w + n, S_k ← β²S_k + n^k; I_u += (x − I_u)/W_u,
//   I_w += n(x − I_w)/W_w; moments with max(α_m, 1/W_u); g ← β_g g + (1 − β_g)·lum(Σx − ΣI_u,prev)
//   over the channels (GRADIENT flag; g is one float, the signed luminance of the gradient).
//   n = 0 (no path sample; TWO_HISTORY, or ZERO_SAMPLES: A-SVGF's one history reading the counts
//   because the spp map may hold zeros): every history stays as reprojected, W_u included;
//   without one the pixel holds nothing (FOVRT_EMPTY_VARIANCE).
// Channels: FOVRT_CHANNELS (1: "two_history_reproject", one channel = direct + indirect summed
//   (combined); 2: "two_history_reproject_pair", direct at the base bindings and indirect at
//   COLOR_IN2 / PREV_IU_OTHER / the *2 bindings). The taps (consistency tests on the previous
//   geometry) and the per-pixel state (W_u, W_w, S, g) are gathered and computed once per pixel;
//   W_u is the same for both channels (as in the reference) and written into each channel's length.
// Window: the weighted history (I_w, W_w, S_k) lives in a window that follows the gaze
//   (pc.win_size at pc.win_origin; at pc.prev_win_origin last frame; common/history_window.glsl).
//   Outside it (I_w, Var) = (I_u, Var) and nothing weighted is stored; a pixel inside whose taps
//   are not all in the previous window restarts its weighted history (W_w = S_k = 0, I_w from the
//   reprojected I_u). A window of the whole image changes nothing.
// Passes: as svgf_reproject — this shader on every pixel with the bilinear taps, listing the pixels
//   whose taps all failed; "…_box" on the listed pixels with the 3×3 fallback taps (indirect).
// Modes: TH_REPROJECT_FLAG_* as the specialization constant FOVRT_SPEC_REPROJECT_FLAGS.
// Reads:  illumination, geometry of both frames, depth gradient, previous pixel, sample counts
//         (TWO_HISTORY, ZERO_SAMPLES), per-pixel α (A-SVGF), previous histories.
// Writes: this frame's histories (per channel moments, W_u into the channel's length, colours
//         when no à-trous iteration feeds back; W_w, S, g once), (I_u, Var) and (I_w, Var), counters,
//         the list.
#include "shared_constants.h"
#include "push_constants.h"
#include "common/two_history_constants.glsl"
#include "common/packing.glsl"
#include "common/access.glsl"
#include "common/luminance.glsl"
#include "common/reprojection.glsl"
#include "common/two_history.glsl"
#include "common/history_window.glsl"

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
const bool kTwo = (kFlags & TH_REPROJECT_FLAG_TWO_HISTORY) != 0u;
const bool kCombined = (kFlags & TH_REPROJECT_FLAG_COMBINED) != 0u;
const bool kAlphaMap = (kFlags & TH_REPROJECT_FLAG_ALPHA_MAP) != 0u;
const bool kWriteColor = (kFlags & TH_REPROJECT_FLAG_WRITE_COLOR) != 0u;
const bool kGradient = (kFlags & TH_REPROJECT_FLAG_GRADIENT) != 0u;
const bool kAntilag = (kFlags & TH_REPROJECT_FLAG_ANTILAG) != 0u;
const bool kFirefly = (kFlags & TH_REPROJECT_FLAG_FIREFLY) != 0u;
const bool kZeroSamples = (kFlags & TH_REPROJECT_FLAG_ZERO_SAMPLES) != 0u;

FOVRT_DECLARE_BINDINGS(TH_REPROJECT_BINDING_LIST)  // shaders/bindings/two_history_reproject.h
#if NCH == 2
FOVRT_DECLARE_BINDINGS(TH_REPROJECT_PAIR_BINDING_LIST)
#elif NCH != 1
#error "FOVRT_CHANNELS must be 1 or 2"
#endif
#define PIXEL_LIST_B_ARGS TH_REPROJECT_B_LIST_ARGS
#define PIXEL_LIST_B_LIST TH_REPROJECT_B_LIST
#include "common/pixel_list.glsl"
// fp16 RGB histories are storage buffers (RGB16F texel buffers are rarely supported).
#ifdef FOVRT_FP16
#define HIST3_LOAD LOAD3
#else
#define HIST3_LOAD FETCH3
#endif

FOVRT_PUSH_CONSTANTS(FOVRT_PUSH_TWO_HISTORY_REPROJECT);  // shaders/push_constants.h

float reproj_prev_depth(int i) { return FETCH_DEPTH(prev_depth, i); }
vec3 reproj_prev_normal(int i) { return FETCH_NORMAL(prev_normal, i); }
uint reproj_prev_object(int i) { return FETCH_OBJECT(prev_object, i); }

// NaN/Inf → 0, negative components → 0; counted (each channel once).
// Counted by the main pass only: the box pass revisits pixels it has counted.
vec3 sanitize(vec3 c) {
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

// Bilinear gather of one history plane over the taps (GLSL cannot pass buffer arrays).
#define GATHER1(arr, taps, out_) REPROJ_GATHER(arr, taps, pc.size, FETCH1, 0.0, out_)
#define GATHER2(arr, taps, out_) REPROJ_GATHER(arr, taps, pc.size, FETCH2, vec2(0.0), out_)
#define GATHER3(arr, taps, out_) REPROJ_GATHER(arr, taps, pc.size, HIST3_LOAD, vec3(0.0), out_)

// The previous window's index of tap t; −1 outside it.
int prev_window_tap(ReprojTaps taps, int t) {
    return window_index(reproj_tap_pixel(taps, t), pc.prev_win_origin, pc.win_size);
}
// Whether every valid tap lies in the previous window (its weighted history can be gathered).
bool taps_in_prev_window(ReprojTaps taps) {
    [[unroll]] for (int t = 0; t < REPROJ_SLOTS; ++t)
        if (reproj_tap_weight(taps, t) > 0.0 && prev_window_tap(taps, t) < 0) return false;
    return true;
}
// Bilinear gather of a windowed history plane (every valid tap in the previous window).
#define GATHER_WINDOW(arr, taps, load, zero, out_)                                   \
    do {                                                                           \
        out_ = zero;                                                               \
        [[unroll]] for (int t_ = 0; t_ < REPROJ_SLOTS; ++t_) {                     \
            float w_ = reproj_tap_weight(taps, t_);                                \
            if (w_ > 0.0) out_ += w_ * load(arr, prev_window_tap(taps, t_));         \
        }                                                                          \
    } while (false)

// Channel k's unsanitised input at pixel j (direct + indirect when combined).
vec3 channel_input(int k, int j) {
#if NCH == 2
    return k == 0 ? FETCH3(color_in, j) : FETCH3(color_in2, j);
#else
    vec3 c = FETCH3(color_in, j);
    if (kCombined) c += FETCH3(color_in2, j);
    return c;
#endif
}

// FIREFLY: the largest sample luminance of channel k among pixel i's in-image 8 neighbours.
float neighbour_max_luminance(int k, int i) {
    ivec2 p = ivec2(i % pc.size.x, i / pc.size.x);
    float m = 0.0;
    for (int d = 0; d < 9; ++d) {
        ivec2 q = p + ivec2(d % 3 - 1, d / 3 - 1);
        if (d == 4 || !in_image(q, pc.size)) continue;
        m = max(m, firefly_neighbour_luminance(channel_input(k, q.y * pc.size.x + q.x)));
    }
    return m;
}

// Channel k: gathers its histories, (FIREFLY) clamps x[k] to its moments and neighbours, accumulates x[k] with
// the per-pixel W_u/W_w, writes its histories and illumination; leaves the gathered I_u,prev in
// iu_prev[k] (for g).
#define ACCUMULATE_CHANNEL(k)                                                                  \
    do {                                                                                       \
        iu_prev[k] = x[k];                                                                     \
        vec3 iw_prev_ = x[k];                                                                  \
        vec2 m_prev_ = vec2(0.0);                                                              \
        if (success) {                                                                         \
            GATHER3(prev_iu##k, taps, iu_prev[k]);                                             \
            GATHER2(prev_m##k, taps, m_prev_);                                                 \
            if (w_held) GATHER_WINDOW(prev_iw##k, taps, HIST3_LOAD, vec3(0.0), iw_prev_);      \
            else iw_prev_ = iu_prev[k]; /* a restarted weighted history starts from I_u */     \
            if (kFirefly && wu_prev >= FOVRT_FIREFLY_MIN_HISTORY)                              \
                x[k] = suppress_firefly(x[k], luminance(x[k]), m_prev_, pc.firefly_sigma,      \
                                        neighbour_max_luminance(k, i));                        \
        }                                                                                      \
        float l_ = luminance(x[k]);                                                            \
        if (!success) m_prev_ = vec2(l_, l_ * l_);                                             \
        vec3 iu_ = !sampled ? (held ? iu_prev[k] : vec3(0.0))                                  \
                            : iu_prev[k] + (x[k] - iu_prev[k]) * (1.0 / wu);                   \
        vec2 m_ = !sampled ? (held ? m_prev_ : vec2(0.0)) : mix(m_prev_, vec2(l_, l_ * l_), am); \
        float variance_ = max(0.0, m_.y - m_.x * m_.x);                                        \
        STORE2(cur_m##k, i, to_history(m_), hfloat);                                           \
        if (k == 0) cur_wu##k[i] = hfloat(to_history(wu)); /* one W_u for both channels */   \
        vec4 u4_ = held ? vec4(iu_, variance_) : vec4(vec3(0.0), FOVRT_EMPTY_VARIANCE);           \
        illum_u##k[i] = TO_ILLUM(u4_);                                                         \
        if (kWriteColor) STORE3(cur_iu##k, i, to_history(iu_), hfloat);                        \
        if (kTwo && wi >= 0) {                                                                 \
            vec3 iw_ = !sampled ? (held ? iw_prev_ : vec3(0.0))                                \
                                : iw_prev_ + (x[k] - iw_prev_) * (n / ww);                     \
            illum_w##k[i] = TO_ILLUM(held ? vec4(iw_, variance_) : vec4(vec3(0.0), FOVRT_EMPTY_VARIANCE)); \
            if (kWriteColor) STORE3(cur_iw##k, wi, to_history(iw_), hfloat);                   \
        } else if (kTwo) { /* outside the window: the unweighted history's */                  \
            illum_w##k[i] = TO_ILLUM(u4_);                                                     \
        }                                                                                      \
    } while (false)

// Accumulates pixel i with this pass's taps; true when the main pass found no bilinear tap on an
// on-screen object pixel (the box pass decides it).
bool reproject_pixel(int i) {
    ReprojTaps taps;
    taps.count = 0;
    taps.needs_box = false;
    if (pc.has_prev != 0u) {
        vec2 dzv = FETCH2(depth_grad, i);
        taps = find_reprojection_taps(FETCH2(prev_pixel, i), pc.size, FETCH_DEPTH(depth, i), FETCH_NORMAL(normal, i),
                                      FETCH_OBJECT(object_id, i),
                                      max(abs(dzv.x), abs(dzv.y)));
    }
    bool success = taps.count > 0;
    // The two-history variants weigh by the sample count; A-SVGF's own history reads it only
    // with ZERO_SAMPLES, to keep a pixel without a path sample (else n = 1).
    float n = REPROJ_SAMPLE_COUNT(sample_count, i, kTwo, kZeroSamples);

    // Per-pixel state, once for all channels (W_u from channel 0's length: both channels hold the same).
    // wi: this pixel in the window (−1 outside); w_held: its weighted history can be gathered.
    int wi = kTwo ? window_index(ivec2(i % pc.size.x, i / pc.size.x), pc.win_origin, pc.win_size) : -1;
    bool w_held = success && wi >= 0 && taps_in_prev_window(taps);
    float wu_prev = 0.0, ww_prev = 0.0;
    vec3 s_prev = vec3(0.0);
    if (success) {
        GATHER1(prev_wu0, taps, wu_prev);
        if (w_held) {
            GATHER_WINDOW(prev_ww, taps, FETCH1, 0.0, ww_prev);
            GATHER_WINDOW(prev_s, taps, HIST3_LOAD, vec3(0.0), s_prev);
        }
    }
    float alpha = kAlphaMap ? alpha_map[i] : pc.alpha;
    float alpha_m = kAlphaMap ? alpha_map[i] : pc.alpha_moments;
    if (kAntilag) {  // the map holds a; pc.alpha, pc.alpha_moments are the base weights
        float a = alpha_map[i];
        alpha = antilag_alpha(a, pc.alpha, wu_prev, pc.antilag_power);
        alpha_m = mix(pc.alpha_moments, 1.0, a);
    }
    float beta = success ? two_history_decay(alpha, wu_prev) : 0.0;
    // No path sample (n = 0): every history stays as reprojected, W_u included; where there is
    // none (W_u,prev = 0) the pixel holds nothing.
    bool sampled = n > 0.0, held = sampled || wu_prev > 0.0;
    float wu = sampled ? beta * wu_prev + 1.0 : wu_prev;
    float ww = sampled ? beta * ww_prev + n : ww_prev;
    vec3 s = sampled ? beta * beta * s_prev + vec3(1.0 / n, 1.0, n) : s_prev;
    float am = success ? max(alpha_m, 1.0 / wu) : 1.0;

    vec3 x[NCH], iu_prev[NCH];
    x[0] = sanitize(channel_input(0, i));
#if NCH == 2
    x[1] = sanitize(channel_input(1, i));
#endif
    ACCUMULATE_CHANNEL(0);
#if NCH == 2
    ACCUMULATE_CHANNEL(1);
#endif
    if (kTwo) {
        if (wi >= 0) {
            cur_ww[wi] = hfloat(to_history(ww));
            STORE3(cur_s, wi, to_history(s), hfloat);
        }
        if (kGradient) {
            vec3 x_sum = x[0], iu_prev_sum = iu_prev[0];
#if NCH == 2
            x_sum += x[1];
            iu_prev_sum += iu_prev[1];
#endif
            float g_prev = 0.0;
            if (success) GATHER1(prev_g, taps, g_prev);
            float g = !sampled ? g_prev  // no sample, no new gradient
                      : success ? g_prev * pc.gradient_beta +
                                    luminance(x_sum - iu_prev_sum) * (1.0 - pc.gradient_beta)
                                : 0.0;
            cur_g[i] = hfloat(to_history(g));
        }
    }
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
