#version 460
#extension GL_GOOGLE_include_directive : require
// asvgf_gradient_gather — per stratum (δ, Δ) = (f_i − f_{i−1}, max(f_i, f_{i−1})) of the claimed
// sample (0 when empty), and the stratum guide at its guide pixel (the sample's pixel, else the
// stratum's centre): normal, depth (−1 on background), noisy luminance of albedo·(direct +
// indirect) + emission, depth gradient. Mirrors AsvgfScatterGradientsRef.
// Reads:  gradient samples, claim slots, this frame's geometry and noisy colour at the guide pixel.
// Writes: (δ, Δ) per stratum, the stratum guide (two vec4 planes).
#include "shared_constants.h"
#include "push_constants.h"
#include "common/two_history_constants.glsl"
#include "common/asvgf.glsl"
#include "common/access.glsl"
#include "common/luminance.glsl"

layout(local_size_x = FOVRT_WORKGROUP_X, local_size_y = FOVRT_WORKGROUP_Y) in;

FOVRT_DECLARE_BINDINGS(ASVGF_GATHER_BINDING_LIST)  // shaders/bindings/asvgf_gradient_gather.h

FOVRT_PUSH_CONSTANTS(FOVRT_PUSH_ASVGF_SAMPLES);  // shaders/push_constants.h

void main() {
    ivec2 s = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(s, pc.grid))) return;
    int k = s.y * pc.grid.x + s.x;
    uint c = claim[k];
    int j;
    if (c == 0xFFFFFFFFu) {
        ivec2 centre = min(s * ASVGF_STRATUM_SIZE + 1, pc.size - 1);
        grad[k] = vec2(0.0);
        j = centre.y * pc.size.x + centre.x;
    } else {
        GradientSample g = samples[c];
        float f_new = max(g.new_luminance, 0.0), f_old = max(g.old_luminance, 0.0);
        grad[k] = vec2(f_new - f_old, max(f_new, f_old));
        j = g.pixel.y * pc.size.x + g.pixel.x;
    }
    bool background = FETCH_OBJECT(object_id, j) == FOVRT_NO_OBJECT;
    guide_geometry[k] = vec4(FETCH_NORMAL(normal, j), background ? -1.0 : FETCH_DEPTH(depth, j));
    float l = luminance(FETCH3(albedo, j) * (FETCH3(direct, j) + FETCH3(indirect, j)) + FETCH3(emission, j));
    guide_luminance[k] = vec4(l, FETCH2(depth_grad, j), 0.0);
}
