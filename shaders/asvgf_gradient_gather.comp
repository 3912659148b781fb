#version 460
#extension GL_GOOGLE_include_directive : require
// asvgf_gradient_gather — per stratum (δ, Δ) = (f_i − f_{i−1}, max(f_i, f_{i−1})) of the claimed
// sample (0 when empty) and the guide pixel: the sample's pixel, else the stratum's centre.
// Mirrors AsvgfScatterGradientsRef.
// Reads:  gradient samples, claim slots.  Writes: (δ, Δ) per stratum, guide pixel index.
#include "common/two_history_constants.glsl"
#include "common/asvgf.glsl"
#include "shared_constants.h"

layout(local_size_x = FOVRT_WORKGROUP_X, local_size_y = FOVRT_WORKGROUP_Y) in;

layout(std430, binding = ASVGF_GATHER_B_SAMPLES) readonly buffer Samples { GradientSample samples[]; };
layout(std430, binding = ASVGF_GATHER_B_CLAIM) readonly buffer Claim { uint claim[]; };
layout(std430, binding = ASVGF_GATHER_B_GRAD) writeonly buffer Grad { vec2 grad[]; };
layout(std430, binding = ASVGF_GATHER_B_GUIDE) writeonly buffer Guide { int guide[]; };

layout(push_constant) uniform Push {
    ivec2 size;
    ivec2 grid;
    uint count;
} pc;

void main() {
    ivec2 s = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(s, pc.grid))) return;
    int k = s.y * pc.grid.x + s.x;
    uint c = claim[k];
    if (c == 0xFFFFFFFFu) {
        ivec2 centre = min(s * ASVGF_STRATUM_SIZE + 1, pc.size - 1);
        grad[k] = vec2(0.0);
        guide[k] = centre.y * pc.size.x + centre.x;
        return;
    }
    GradientSample g = samples[c];
    float f_new = max(g.new_luminance, 0.0), f_old = max(g.old_luminance, 0.0);
    grad[k] = vec2(f_new - f_old, max(f_new, f_old));
    guide[k] = g.pixel.y * pc.size.x + g.pixel.x;
}
