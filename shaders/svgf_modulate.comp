#version 460
#extension GL_GOOGLE_include_directive : require
// svgf_modulate — remodulation (paper §4, SPEC §2): out = albedo · (direct + indirect) + emission.
// Reads:  filtered illumination of each channel (vec4; one when combined), albedo, emission.
// Writes: HDR colour (float[3N]).
#include "shared_constants.h"
#include "common/packing.glsl"

layout(local_size_x = FOVRT_WORKGROUP_X, local_size_y = FOVRT_WORKGROUP_Y) in;

layout(std430, binding = SVGF_MODULATE_B_ILLUM0) readonly buffer Illum0 { vec4 illum0[]; };
layout(std430, binding = SVGF_MODULATE_B_ILLUM1) readonly buffer Illum1 { vec4 illum1[]; };
layout(std430, binding = SVGF_MODULATE_B_ALBEDO) readonly buffer Albedo { float albedo[]; };
layout(std430, binding = SVGF_MODULATE_B_EMISSION) readonly buffer Emission { float emission[]; };
layout(std430, binding = SVGF_MODULATE_B_OUT) writeonly buffer Out { float color_out[]; };

// Mirrors SvgfModulatePush in denoise/svgf_layout.h.
layout(push_constant) uniform Push {
    ivec2 size;
    uint combined;
} pc;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, pc.size))) return;
    int i = p.y * pc.size.x + p.x;
    vec3 illum = illum0[i].rgb;
    if (pc.combined == 0u) illum += illum1[i].rgb;
    STORE3(color_out, i, LOAD3(albedo, i) * illum + LOAD3(emission, i), float);
}
