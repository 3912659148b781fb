#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
// asvgf_stratum_sigma — the w_l scale of A-SVGF's gradient reconstruction (SPEC §4): σ_l times the
// standard deviation of the guide luminance over the valid strata of the 3×3 neighbourhood. It
// does not depend on the à-trous step, so it is computed once per frame rather than in every
// iteration (as AsvgfGradientAtrousRef does inline). 0 where the stratum's guide is background.
// Reads:  stratum guide (geometry: background test; luminance).  Writes: σ_l·std per stratum.
#include "shared_constants.h"
#include "push_constants.h"
#include "common/two_history_constants.glsl"
#include "common/access.glsl"

layout(local_size_x = FOVRT_WORKGROUP_X, local_size_y = FOVRT_WORKGROUP_Y) in;

FOVRT_DECLARE_BINDINGS(ASVGF_SIGMA_BINDING_LIST)  // shaders/bindings/asvgf_stratum_sigma.h

FOVRT_PUSH_CONSTANTS(FOVRT_PUSH_ASVGF_SIGMA);  // shaders/push_constants.h

void main() {
    ivec2 s = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(s, pc.grid))) return;
    float sum = 0.0, sum2 = 0.0, cnt = 0.0;
    [[unroll]] for (int dy = -1; dy <= 1; ++dy)
        [[unroll]] for (int dx = -1; dx <= 1; ++dx) {
            ivec2 t = s + ivec2(dx, dy);
            if (!in_image(t, pc.grid)) continue;
            int kt = t.y * pc.grid.x + t.x;
            if (GUIDE_IS_BACKGROUND(FETCH4(guide_geometry, kt))) continue;
            float l = FETCH1(guide_luminance, kt);
            sum += l;
            sum2 += l * l;
            cnt += 1.0;
        }
    float mean = sum / max(cnt, 1.0);
    sigma_out[s.y * pc.grid.x + s.x] = pc.sigma_luminance * sqrt(max(0.0, sum2 / max(cnt, 1.0) - mean * mean));
}
