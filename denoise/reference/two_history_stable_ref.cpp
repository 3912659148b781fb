#include "denoise/reference/two_history_stable_ref.h"

#include <cmath>

#include <tbb/parallel_for.h>

#include "shaders/shared_constants.h"

namespace fovrt {

void TwoHistoryStabilizeRef(const Plane<vec4>& filtered, const FrameInputs& frame, const SvgfGeometry& prevGeometry,
                            bool hasPrev, const Plane<float>& prevStable, const Plane<float>& wu,
                            const TwoHistoryStableParams& params, Precision precision, Plane<float>& curStable,
                            Plane<vec4>& out, const Plane<float>* q) {
    const int w = frame.width(), h = frame.height();
    out.Resize(w, h);
    curStable.Resize(w, h, 0.0f);
    tbb::parallel_for(0, h, [&](int y) {
        for (int x = 0; x < w; ++x) {
            const vec4 c = filtered(x, y);
            const float l = Luminance(vec3(c));
            // 3×3 luminance moments over object pixels.
            float sum = 0.0f, sum2 = 0.0f, count = 0.0f;
            for (int k = 0; k < 9; ++k) {
                const int qx = x + k % 3 - 1, qy = y + k / 3 - 1;
                if (!filtered.InBounds(qx, qy) || frame.objectId(qx, qy) == kNoObject) continue;
                const float lq = Luminance(vec3(filtered(qx, qy)));
                sum += lq;
                sum2 += lq * lq;
                count += 1.0f;
            }
            const float mean = count > 0.0f ? sum / count : l;
            const float spread = count > 0.0f ? std::max(0.0f, sum2 / count - mean * mean) : 0.0f;
            const float sigma = std::sqrt(spread + std::max(c.a, 0.0f));
            float ls = l;
            if (hasPrev) {
                // Bilinear taps only: where they all fail the stabilisation restarts (no 3×3 fallback).
                const ReprojectionTaps taps = FindReprojectionTaps(frame, prevGeometry, x, y);
                if (taps.count > 0 && !taps.box)
                    ls = StabilizedLuminance(
                        GatherTaps(prevStable, taps), l, mean, sigma, params.sigmaScale,
                        StabilizationWeight(params.alpha, wu(x, y),
                                            q ? StabilizationChangeWeight((*q)(x, y), params.antilagQ) : 0.0f));
            }
            curStable(x, y) = QuantizeHistory(ls, precision);
            out(x, y) = vec4(StabilizedColor(vec3(c), l, ls), c.a);
        }
    });
}

}  // namespace fovrt
