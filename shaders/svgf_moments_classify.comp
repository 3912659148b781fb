#version 460
#extension GL_GOOGLE_include_directive : require
// svgf_moments_classify — lists the pixels whose variance svgf_filter_moments must estimate
// spatially (not background, history length < threshold; paper §4.2, Falcor) and counts the
// workgroups of its indirect dispatch. In the steady state the list is (nearly) empty.
// Reads:  guide (background test), this frame's history length.
// Writes: list of pixel indices, (groups x, 1, 1, count) — zeroed by the host before.
#include "shared_constants.h"
#include "push_constants.h"
#include "common/packing.glsl"
#include "common/access.glsl"
FOVRT_DECLARE_BINDINGS(SVGF_CLASSIFY_BINDING_LIST)  // shaders/bindings/svgf_moments_classify.h
#define PIXEL_LIST_B_ARGS SVGF_CLASSIFY_B_ARGS
#define PIXEL_LIST_B_LIST SVGF_CLASSIFY_B_LIST
#include "common/pixel_list.glsl"

layout(local_size_x = FOVRT_WORKGROUP_X, local_size_y = FOVRT_WORKGROUP_Y) in;

FOVRT_PUSH_CONSTANTS(FOVRT_PUSH_SVGF_CLASSIFY);  // shaders/push_constants.h

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, pc.size))) return;
    int i = p.y * pc.size.x + p.x;
    if (GUIDE_IS_BACKGROUND(FETCH4(guide, i)) || !(FETCH1(hist_length, i) < pc.threshold)) return;
    pixel_list_append(i);
}
