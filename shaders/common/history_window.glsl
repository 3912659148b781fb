// The weighted history's window (two-history, denoise.two_history.window), written once for GLSL
// and C++ (shared_language.glsl): the weighted history (I_w, W_w, S_k) is kept only for a
// rectangle of `size` pixels at `origin` that follows the gaze; its planes hold that rectangle row
// by row. A window of the whole image (origin 0, size = the image) indexes as the image does.
#ifndef FOVRT_HISTORY_WINDOW_GLSL
#define FOVRT_HISTORY_WINDOW_GLSL
#include "shared_language.glsl"

FOVRT_GLSL_BEGIN

// Index of image pixel p in the window's planes; −1 outside the window.
FOVRT_SHARED_FN int window_index(ivec2 p, ivec2 origin, ivec2 size) {
    ivec2 w = p - origin;
    if (w.x < 0 || w.y < 0 || w.x >= size.x || w.y >= size.y) return -1;
    return w.y * size.x + w.x;
}

FOVRT_GLSL_END

#endif
