#version 460
#extension GL_GOOGLE_include_directive : require
// svgf_pack_guide — packs this frame's edge-stopping guide for the spatial filters
// (svgf_filter_moments, svgf_atrous): vec4(normal, depth), depth replaced by −1 on background
// pixels (object id kNoObject; visible surfaces have linear depth > 0). One rgba32f fetch per tap
// instead of three (depth, normal, object id): on lavapipe the filters are bound by fetch count.
// Reads:  depth, normal, object id (this frame).
// Writes: guide (vec4).
#include "shared_constants.h"
#include "push_constants.h"
#include "common/access.glsl"

layout(local_size_x = FOVRT_WORKGROUP_X, local_size_y = FOVRT_WORKGROUP_Y) in;

FOVRT_DECLARE_BINDINGS(SVGF_GUIDE_BINDING_LIST)  // shaders/bindings/svgf_pack_guide.h

FOVRT_PUSH_CONSTANTS(FOVRT_PUSH_IMAGE_SIZE);  // shaders/push_constants.h

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, pc.size))) return;
    int i = p.y * pc.size.x + p.x;
    bool background = FETCH_OBJECT(object_id, i) == FOVRT_NO_OBJECT;
    guide_out[i] = vec4(FETCH_NORMAL(normal, i), background ? -1.0 : FETCH_DEPTH(depth, i));
}
