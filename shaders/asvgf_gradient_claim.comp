#version 460
#extension GL_GOOGLE_include_directive : require
// asvgf_gradient_claim — one gradient sample per stratum (SPEC §4: "at most one per current
// stratum, first wins"). Mirrors the selection in AsvgfScatterGradientsRef.
// Purpose: each valid sample (stratum inside the grid, pixel on screen, finite luminances)
//   atomicMin's its index into its stratum's slot: the lowest index wins, deterministically.
// Reads:  gradient samples.  Writes: claim slots (cleared to 0xFFFFFFFF by the host).
#include "push_constants.h"
#include "common/two_history_constants.glsl"
#include "common/asvgf.glsl"

layout(local_size_x = FOVRT_WORKGROUP_1D) in;

FOVRT_DECLARE_BINDINGS(ASVGF_CLAIM_BINDING_LIST)  // shaders/bindings/asvgf_gradient_claim.h

FOVRT_PUSH_CONSTANTS(FOVRT_PUSH_ASVGF_SAMPLES);  // shaders/push_constants.h

void main() {
    uint k = gl_GlobalInvocationID.x;
    if (k >= pc.count) return;
    GradientSample s = samples[k];
    if (any(lessThan(s.stratum, ivec2(0))) || any(greaterThanEqual(s.stratum, pc.grid))) return;
    if (any(lessThan(s.pixel, ivec2(0))) || any(greaterThanEqual(s.pixel, pc.size))) return;
    if (isnan(s.new_luminance) || isinf(s.new_luminance) || isnan(s.old_luminance) || isinf(s.old_luminance))
        return;
    atomicMin(claim[s.stratum.y * pc.grid.x + s.stratum.x], k);
}
