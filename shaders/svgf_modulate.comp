#version 460
#extension GL_GOOGLE_include_directive : require
// svgf_modulate — remodulation (paper §4, SPEC §2): out = albedo · (direct + indirect) + emission.
// Reads:  filtered illumination of each channel (vec4; one when combined: specialization constant
//         FOVRT_SPEC_MODULATE_COMBINED), albedo (the frame's modulation factor, input.modulation:
//         the albedo, or F_β under brdf demodulation), emission — uniform texel buffers (common/access.glsl).
// Writes: HDR colour (float[3N]).
#include "shared_constants.h"
#include "push_constants.h"
#include "common/packing.glsl"
#include "common/access.glsl"

layout(local_size_x = FOVRT_WORKGROUP_X, local_size_y = FOVRT_WORKGROUP_Y) in;
layout(constant_id = FOVRT_SPEC_MODULATE_COMBINED) const bool kCombined = false;

FOVRT_DECLARE_BINDINGS(SVGF_MODULATE_BINDING_LIST)  // shaders/bindings/svgf_modulate.h

FOVRT_PUSH_CONSTANTS(FOVRT_PUSH_IMAGE_SIZE);  // shaders/push_constants.h

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, pc.size))) return;
    int i = p.y * pc.size.x + p.x;
    vec3 illum = FETCH3(illum0, i);
    if (!kCombined) illum += FETCH3(illum1, i);
    STORE3(color_out, i, FETCH3(albedo, i) * illum + FETCH3(emission, i), float);
}
