// The bilinear reprojection of a pass's own one-float history (two_history_stabilize,
// two_history_choice). Include after the bindings: the shader binds this frame's and the previous
// frame's geometry as depth, normal, object_id, prev_depth, prev_normal, prev_object, depth_grad
// and prev_pixel (slot order checked in denoise/svgf_family_plan.cpp). Bilinear taps only: where
// every tap fails (count 0) the history restarts, without the 3×3 fallback, as in the C++
// references (FindReprojectionTaps with `!taps.box`).
#ifndef FOVRT_OWN_HISTORY_REPROJECTION_GLSL
#define FOVRT_OWN_HISTORY_REPROJECTION_GLSL
#include "common/reprojection.glsl"

float reproj_prev_depth(int i) { return FETCH_DEPTH(prev_depth, i); }
vec3 reproj_prev_normal(int i) { return FETCH_NORMAL(prev_normal, i); }
uint reproj_prev_object(int i) { return FETCH_OBJECT(prev_object, i); }

// The taps of pixel i (= p.y·size.x + p.x) into the previous frame; gather with REPROJ_GATHER.
ReprojTaps own_history_taps(int i, ivec2 size) {
    vec2 dzv = FETCH2(depth_grad, i);
    return find_reprojection_taps(FETCH2(prev_pixel, i), size, FETCH_DEPTH(depth, i), FETCH_NORMAL(normal, i),
                                  FETCH_OBJECT(object_id, i), max(abs(dzv.x), abs(dzv.y)));
}

#endif
