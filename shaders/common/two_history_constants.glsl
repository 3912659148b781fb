// Bindings and push-constant flags of the two-history and A-SVGF shaders (shaders/two_history_*.comp,
// shaders/asvgf_*.comp). Macros only: included by GLSL and by C++ (the pass plan, denoise/stage_shaders.h).
#ifndef FOVRT_TWO_HISTORY_CONSTANTS_GLSL
#define FOVRT_TWO_HISTORY_CONSTANTS_GLSL

// 1-D passes (one invocation per gradient sample).
#define FOVRT_WORKGROUP_1D 64

// two_history_reproject: one channel (combined: direct + indirect); two_history_reproject_pair:
// both channels in one dispatch (direct at the base bindings, indirect at COLOR_IN2,
// PREV_IU_OTHER and the *2 bindings), with the taps and the per-pixel state (W_u, W_w, S_k, g)
// once per pixel (g: one float, the signed luminance of the gradient over both channels;
// two-history only, GRADIENT flag). Lavapipe allows 32 storage buffers per stage: the pair
// layout has 25 in fp16.
// two_history_reproject's bindings: shaders/bindings/two_history_reproject.h.

// Mode bits of two_history_reproject, fixed per pipeline (specialization constant
// FOVRT_SPEC_REPROJECT_FLAGS); whether a previous frame exists is a push constant.
#define TH_REPROJECT_FLAG_TWO_HISTORY 1u   // accumulate I_w, W_w, S_k
#define TH_REPROJECT_FLAG_COMBINED 2u      // this channel = direct + indirect
#define TH_REPROJECT_FLAG_ALPHA_MAP 4u     // α from the per-pixel map
#define TH_REPROJECT_FLAG_WRITE_COLOR 8u   // feed back the unfiltered accumulation
#define TH_REPROJECT_FLAG_GRADIENT 16u     // accumulate g (two-history; not two-history-asvgf)
#define TH_REPROJECT_FLAG_ANTILAG 32u      // the map holds the anti-lag factor a (ALPHA_MAP too)
#define TH_REPROJECT_FLAG_FIREFLY 64u      // clamp a sample above μ + kσ and its neighbours (firefly variants)
#define TH_REPROJECT_FLAG_ZERO_SAMPLES 128u // one history (asvgf): read n only for n = 0 (maps below 1 spp)

// Firefly suppression clamps a sample only where the reprojected moments span this many frames of
// history (W_u,prev): younger moments do not yet estimate the pixel's spread (SVGF's own threshold
// for trusting the temporal variance is 4 frames as well).
#define FOVRT_FIREFLY_MIN_HISTORY 4.0

// Two-history's blend factor p where V(p) is linear (the denominator a − 2b + c of
// TwoHistoryOptimalBlend lost in rounding): the smaller end V(0) = a or V(1) = c wins, and ends within
// this fraction of a + c are a tie, p = 1 (I_u), on the host and the device alike. Every sample count
// of the history equal gives a = b = c (I_w = I_u), which rounding (a few 1e-7 of a + c in fp32)
// would otherwise split between p = 0 and 1; the band stays below the 1e-5 of V that p may lose.
#define FOVRT_TWO_HISTORY_TIE 4e-6

// two_history_stabilize: below this luminance the stabilised colour is shifted (c + L_s − L)
// instead of scaled (c·L_s/L), which would amplify the noise of a near-black pixel's hue.
#define FOVRT_STABLE_LUMINANCE_FLOOR 1e-4


// ---- Bindings declared once (shaders/bindings.h) of the two-history and A-SVGF passes.
#include "../bindings.h"
#include "../bindings/asvgf_alpha.h"
#include "../bindings/asvgf_gradient_atrous.h"
#include "../bindings/asvgf_gradient_claim.h"
#include "../bindings/asvgf_gradient_gather.h"
#include "../bindings/asvgf_stratum_sigma.h"
#include "../bindings/two_history_blend.h"
#include "../bindings/two_history_choice.h"
#include "../bindings/two_history_gradient.h"
#include "../bindings/two_history_reproject.h"
#include "../bindings/two_history_stabilize.h"
#ifdef __cplusplus
FOVRT_PASS_BINDINGS(TH_REPROJECT)  // one channel ("two_history_reproject")
FOVRT_PAIR_BINDINGS(TH_REPROJECT)  // "two_history_reproject_pair"
FOVRT_PASS_BINDINGS(TH_GRADIENT)
FOVRT_PASS_BINDINGS(TH_BLEND)
FOVRT_PASS_BINDINGS(TH_CHOICE)
FOVRT_PASS_BINDINGS(TH_STABILIZE)
FOVRT_PASS_BINDINGS(ASVGF_CLAIM)
FOVRT_PASS_BINDINGS(ASVGF_GATHER)
FOVRT_PASS_BINDINGS(ASVGF_SIGMA)
FOVRT_PASS_BINDINGS(ASVGF_ATROUS)
FOVRT_PASS_BINDINGS(ASVGF_ALPHA)
#endif

#endif
