// Push-constant blocks of every compute pass, declared once for GLSL and C++. Each block is a
// field list FOVRT_PUSH_<PASS>(F) of F(type, name); a shader declares its block with
// FOVRT_PUSH_CONSTANTS(FOVRT_PUSH_<PASS>) and reads pc.<name>; the host fills the struct of the
// same fields (fovrt::<Pass>Push below) by aggregate initialisation, in field order. Types are
// ivec2, int, uint and float only, so the std430 push-constant offsets equal the C++ layout
// (static_asserts at the end pin the sizes). Macros only: included by GLSL and by C++.
#ifndef FOVRT_PUSH_CONSTANTS_H
#define FOVRT_PUSH_CONSTANTS_H

// svgf_reproject (mode bits: specialization constant FOVRT_SPEC_REPROJECT_FLAGS).
// has_prev 0: no previous frame (first frame, reset): nothing reprojects.
#define FOVRT_PUSH_SVGF_REPROJECT(F) F(ivec2, size) F(float, alpha_color) F(float, alpha_moments) F(uint, has_prev)
// svgf_pack_guide, svgf_modulate: the image size alone.
#define FOVRT_PUSH_IMAGE_SIZE(F) F(ivec2, size)
// svgf_moments_classify: threshold = history length below which the spatial estimate is used.
#define FOVRT_PUSH_SVGF_CLASSIFY(F) F(ivec2, size) F(float, threshold)
// svgf_filter_moments
#define FOVRT_PUSH_SVGF_FILTER_MOMENTS(F) \
    F(ivec2, size) F(float, sigma_depth) F(float, sigma_normal) F(float, threshold)
// svgf_atrous: step = 2^iteration; hist_size0/1, hist_origin0/1: the window each side's fed-back
// colour history holds (common/history_window.glsl; the image for all but two-history's I_w).
#define FOVRT_PUSH_SVGF_ATROUS(F)                                                                      \
    F(ivec2, size) F(int, step) F(float, sigma_depth) F(float, sigma_normal) F(float, sigma_luminance) \
    F(ivec2, hist_size0) F(ivec2, hist_origin0) F(ivec2, hist_size1) F(ivec2, hist_origin1)
// two_history_reproject (mode bits: specialization constant FOVRT_SPEC_REPROJECT_FLAGS);
// antilag_power: the ANTILAG flag's history reduction (1 − a)^power; firefly_sigma: the FIREFLY
// flag's k in μ + kσ; win_size, win_origin, prev_win_origin: the weighted history's window this
// frame and the previous one (common/history_window.glsl).
#define FOVRT_PUSH_TWO_HISTORY_REPROJECT(F)                                                          \
    F(ivec2, size) F(float, alpha) F(float, alpha_moments) F(float, gradient_beta) F(uint, has_prev) \
    F(float, antilag_power) F(float, firefly_sigma) F(ivec2, win_size) F(ivec2, win_origin)          \
    F(ivec2, prev_win_origin)
// two_history_blend: clamp_history 1 for the clamp variants (the box of k = clamp_sigma in place of p);
// held_choice 1 for the hysteresis variants (two_history_choice's held choice in place of p);
// win_size, win_origin: the weighted history's window (outside it the blend keeps I_u).
#define FOVRT_PUSH_TWO_HISTORY_BLEND(F)                                                            \
    F(ivec2, size) F(ivec2, win_size) F(ivec2, win_origin) F(float, clamp_sigma) F(uint, clamp_history) \
    F(uint, held_choice)
// two_history_choice: rate, band = choice_rate, choice_band (TwoHistoryParams); the window as the
// blend's (outside it p = 1).
#define FOVRT_PUSH_TWO_HISTORY_CHOICE(F) \
    F(ivec2, size) F(ivec2, win_size) F(ivec2, win_origin) F(float, rate) F(float, band) F(uint, has_prev)
// two_history_gradient
#define FOVRT_PUSH_TWO_HISTORY_GRADIENT(F) \
    F(ivec2, size) F(float, sigma_depth) F(float, sigma_normal) F(float, q_scale) F(uint, two_channels)
// two_history_stabilize: alpha = α_s, sigma_scale = k, antilag_q = q0 (TwoHistoryStableParams);
// antilag 1 for two-history-stable-antilag.
#define FOVRT_PUSH_TWO_HISTORY_STABILIZE(F) \
    F(ivec2, size) F(float, alpha) F(float, sigma_scale) F(uint, has_prev) F(float, antilag_q) F(uint, antilag)
// asvgf_gradient_claim, asvgf_gradient_gather: image size, stratum grid, uploaded samples.
#define FOVRT_PUSH_ASVGF_SAMPLES(F) F(ivec2, size) F(ivec2, grid) F(uint, count)
// asvgf_gradient_atrous: step in strata.
#define FOVRT_PUSH_ASVGF_ATROUS(F) \
    F(ivec2, size) F(ivec2, grid) F(int, step) F(float, sigma_depth) F(float, sigma_normal) F(float, sigma_luminance)
// asvgf_stratum_sigma
#define FOVRT_PUSH_ASVGF_SIGMA(F) F(ivec2, grid) F(float, sigma_luminance)
// asvgf_alpha: alpha = the base temporal weight; antilag_gain: a = clamp(gain·λ, 0, 1) with
// FOVRT_SPEC_ASVGF_ANTILAG.
#define FOVRT_PUSH_ASVGF_ALPHA(F) F(ivec2, size) F(ivec2, grid) F(float, alpha) F(float, antilag_gain)
// bandwidth_copy: elements as rows × columns.
#define FOVRT_PUSH_BANDWIDTH(F) F(ivec2, size)
// display_compose (shaders/common/display_constants.glsl; filled by MakeDisplayComposePush in
// src/display/display_compose.h). out_size: output pixels; eye_size: each eye's pixels; extent: the
// letterboxed viewport of every slot shown (0: none); origin0/origin1: where slot 0 (the left eye,
// or the one eye shown) and slot 1 (the right eye, side by side only) start; gaze_s = the gaze
// point and radius_s = the fovea radius, in output pixels × FOVRT_DISPLAY_SUBPIXELS (radius ≤ 0:
// no outline); true_gaze_s = where the eye really is (a modelled tracker's true gaze), likewise;
// step = eye pixels per output pixel (float(eye / extent), rounded once on the host);
// scale = 2^exposure (HDR) or 1 (display data); flags = DISPLAY_FLAG_*.
#define FOVRT_PUSH_DISPLAY_COMPOSE(F)                                                               \
    F(ivec2, out_size) F(ivec2, eye_size) F(ivec2, extent) F(ivec2, origin0) F(ivec2, origin1)          \
    F(ivec2, gaze0) F(ivec2, gaze1) F(ivec2, true_gaze0) F(ivec2, true_gaze1) F(float, step_x)         \
    F(float, step_y) F(int, radius0) F(int, radius1) F(float, scale) F(uint, flags)

// rae_conv (denoise/vulkan/rae_vk.h): output size; channels of input a (upsampled 2×2 nearest by
// addressing when flags & RAE_FLAG_UPSAMPLE_A) and of input b (concatenated after a; 0 = none);
// offsets in elements of the activation buffer and of the weight buffer; tiles_x = workgroups
// along x per output-channel group (the group index rides on gl_WorkGroupID.x).
#define FOVRT_PUSH_RAE_CONV(F)                                                                   \
    F(ivec2, size) F(int, in_a) F(int, in_b) F(int, out_channels) F(uint, a_offset) F(uint, b_offset) \
    F(uint, dst_offset) F(uint, w_offset) F(uint, bias_offset) F(uint, flags) F(int, tiles_x)
// rae_pool: output size, channels, source and destination offsets (elements).
#define FOVRT_PUSH_RAE_POOL(F) F(ivec2, size) F(int, channels) F(uint, src_offset) F(uint, dst_offset) F(int, tiles_x)

#define FOVRT_PUSH_FIELD(type, name) type name;

#ifdef __cplusplus
#include <cstdint>

#include "core/math.h"

namespace fovrt {
// The C++ type of each GLSL type a block may hold.
#define FOVRT_PUSH_CPP_TYPE_ivec2 ivec2
#define FOVRT_PUSH_CPP_TYPE_int int32_t
#define FOVRT_PUSH_CPP_TYPE_uint uint32_t
#define FOVRT_PUSH_CPP_TYPE_float float
#define FOVRT_DECLARE_PUSH(Name, LIST)         \
    struct Name {                              \
        LIST(FOVRT_PUSH_FIELD_QUALIFIED)       \
    }
#define FOVRT_PUSH_FIELD_QUALIFIED(type, name) FOVRT_PUSH_CPP_TYPE_##type name;
FOVRT_DECLARE_PUSH(SvgfReprojectPush, FOVRT_PUSH_SVGF_REPROJECT);
FOVRT_DECLARE_PUSH(ImageSizePush, FOVRT_PUSH_IMAGE_SIZE);
FOVRT_DECLARE_PUSH(SvgfClassifyPush, FOVRT_PUSH_SVGF_CLASSIFY);
FOVRT_DECLARE_PUSH(SvgfFilterMomentsPush, FOVRT_PUSH_SVGF_FILTER_MOMENTS);
FOVRT_DECLARE_PUSH(SvgfAtrousPush, FOVRT_PUSH_SVGF_ATROUS);
FOVRT_DECLARE_PUSH(TwoHistoryReprojectPush, FOVRT_PUSH_TWO_HISTORY_REPROJECT);
FOVRT_DECLARE_PUSH(TwoHistoryBlendPush, FOVRT_PUSH_TWO_HISTORY_BLEND);
FOVRT_DECLARE_PUSH(TwoHistoryChoicePush, FOVRT_PUSH_TWO_HISTORY_CHOICE);
FOVRT_DECLARE_PUSH(TwoHistoryGradientPush, FOVRT_PUSH_TWO_HISTORY_GRADIENT);
FOVRT_DECLARE_PUSH(TwoHistoryStabilizePush, FOVRT_PUSH_TWO_HISTORY_STABILIZE);
FOVRT_DECLARE_PUSH(AsvgfSamplesPush, FOVRT_PUSH_ASVGF_SAMPLES);
FOVRT_DECLARE_PUSH(AsvgfAtrousPush, FOVRT_PUSH_ASVGF_ATROUS);
FOVRT_DECLARE_PUSH(AsvgfSigmaPush, FOVRT_PUSH_ASVGF_SIGMA);
FOVRT_DECLARE_PUSH(AsvgfAlphaPush, FOVRT_PUSH_ASVGF_ALPHA);
FOVRT_DECLARE_PUSH(BandwidthPush, FOVRT_PUSH_BANDWIDTH);
FOVRT_DECLARE_PUSH(DisplayComposePush, FOVRT_PUSH_DISPLAY_COMPOSE);
FOVRT_DECLARE_PUSH(RaeConvPush, FOVRT_PUSH_RAE_CONV);
FOVRT_DECLARE_PUSH(RaePoolPush, FOVRT_PUSH_RAE_POOL);
#undef FOVRT_DECLARE_PUSH
#undef FOVRT_PUSH_FIELD_QUALIFIED
// Every ivec2 at an 8-byte-aligned offset, 4-byte scalars between: no padding on either side.
static_assert(sizeof(SvgfReprojectPush) == 20 && sizeof(ImageSizePush) == 8 && sizeof(SvgfClassifyPush) == 12 &&
              sizeof(SvgfFilterMomentsPush) == 20 && sizeof(SvgfAtrousPush) == 56 &&
              sizeof(TwoHistoryReprojectPush) == 56 && sizeof(TwoHistoryBlendPush) == 36 &&
              sizeof(TwoHistoryChoicePush) == 36 &&
              sizeof(TwoHistoryGradientPush) == 24 &&
              sizeof(TwoHistoryStabilizePush) == 28 &&
              sizeof(AsvgfSamplesPush) == 20 && sizeof(AsvgfAtrousPush) == 32 && sizeof(AsvgfSigmaPush) == 12 &&
              sizeof(AsvgfAlphaPush) == 24 && sizeof(BandwidthPush) == 8);
// Seven ivec2 first, then the scalars: 80 bytes, within the 128 every device allows.
static_assert(sizeof(DisplayComposePush) == 96);
static_assert(sizeof(RaeConvPush) == 48 && sizeof(RaePoolPush) == 24);
}  // namespace fovrt
#else
// GLSL: the block every shader reads as `pc`.
#define FOVRT_PUSH_CONSTANTS(LIST) layout(push_constant) uniform Push { LIST(FOVRT_PUSH_FIELD) } pc
#endif

#endif
