// Constants of the display pass (shaders/display_compose.comp, src/display/display_pass.h and its C++
// reference src/display/display_compose.h). Macros only: included by GLSL and by C++.
#ifndef FOVRT_DISPLAY_CONSTANTS_GLSL
#define FOVRT_DISPLAY_CONSTANTS_GLSL

// Push-constant flags (FOVRT_PUSH_DISPLAY_COMPOSE's `flags`).
#define DISPLAY_FLAG_BGRA 1u          // bytes B,G,R,A (B8G8R8A8_*); else R,G,B,A (R8G8B8A8_*)
#define DISPLAY_FLAG_REINHARD 2u      // tone curve x/(1+x) instead of the clamp (Tonemap::Reinhard)
#define DISPLAY_FLAG_SIDE_BY_SIDE 4u  // slot 1 (the right eye at origin1) is shown
#define DISPLAY_FLAG_SLOT0_RIGHT 8u   // slot 0 shows the right eye (layout: the right eye alone)
#define DISPLAY_FLAG_MARK0 16u        // draw the gaze marker and fovea outline in slot 0
#define DISPLAY_FLAG_MARK1 32u        // … in slot 1
#define DISPLAY_FLAG_TRUE0 64u        // with MARK0: the true gaze's marker in slot 0 (a modelled tracker)
#define DISPLAY_FLAG_TRUE1 128u       // … in slot 1

// Overlay geometry in output pixels × FOVRT_DISPLAY_SUBPIXELS (fixed point, so that the shader
// and the C++ reference decide every overlay pixel with the same integer arithmetic).
#define FOVRT_DISPLAY_SUBPIXELS 8
// A pixel is on a line when its centre lies within this of it: 0.75 px, lines 1–2 px wide.
#define FOVRT_DISPLAY_LINE_HALF_WIDTH 6
// The gaze marker: a cross whose arms reach 6 px from the gaze point.
#define FOVRT_DISPLAY_MARKER_ARM 48
// The true gaze's marker: a diagonal cross (×) of the same reach, so it reads apart from the
// tracked gaze's + without colour; a pixel is on it when |dx − dy| ≤ this (0.71 px from a diagonal).
#define FOVRT_DISPLAY_DIAGONAL_HALF_WIDTH 8
// Caps that keep the integer arithmetic in range: gaze within ±2^20 subpixels (±131072 px), the
// fovea radius up to 4000 px (2·(r + w)² < 2^32).
#define FOVRT_DISPLAY_MAX_COORD 1048576
#define FOVRT_DISPLAY_MAX_RADIUS 32000

// Colours, already sRGB-encoded bytes 0xRRGGBB (drawn as is, not through the display transform).
#define FOVRT_DISPLAY_BACKGROUND_RGB 0x202020u  // letterbox bars and empty slots: dark grey
#define FOVRT_DISPLAY_GAZE_RGB 0x20FF40u        // gaze marker (the gaze the spp map follows): green
#define FOVRT_DISPLAY_TRUE_GAZE_RGB 0x30D0FFu   // true gaze marker (where the eye is): light blue
#define FOVRT_DISPLAY_FOVEA_RGB 0xFF40FFu       // fovea outline: magenta

// ---- Bindings declared once (shaders/bindings.h).
#include "../bindings.h"
#include "../bindings/display_compose.h"
#ifdef __cplusplus
FOVRT_PASS_BINDINGS(DISPLAY_COMPOSE)
#endif

#endif
