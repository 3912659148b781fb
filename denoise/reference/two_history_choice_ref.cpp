#include "denoise/reference/two_history_choice_ref.h"

#include <tbb/parallel_for.h>

#include "denoise/reference/two_history_math.h"

namespace fovrt {

void TwoHistoryChoiceRef(const FrameInputs& frame, const SvgfGeometry& prevGeometry, bool hasPrev,
                         const Plane<float>& prevChoice, const Plane<float>& wu, const Plane<float>& ww,
                         const Plane<vec3>& powerSums, const TwoHistoryParams& params, Precision precision,
                         Plane<float>& curChoice, const HistoryWindow& window) {
    const int w = frame.width(), h = frame.height();
    const HistoryWindow win = window.OrWhole(w, h);
    curChoice.Resize(w, h, 0.0f);
    tbb::parallel_for(0, h, [&](int y) {
        for (int x = 0; x < w; ++x) {
            const int wi = win.Index(x, y);
            const float p = wi < 0 ? 1.0f
                                   : TwoHistoryOptimalBlend(StoredTwoHistoryWeights(wu(x, y), ww[size_t(wi)],
                                                                                    powerSums[size_t(wi)]));
            float held = p;
            if (hasPrev && wu(x, y) > 1.0f) {
                // Bilinear taps only: where they all fail the choice restarts (no 3×3 fallback).
                const ReprojectionTaps taps = FindReprojectionTaps(frame, prevGeometry, x, y);
                if (taps.count > 0 && !taps.box)
                    held = HystereticChoice(GatherTaps(prevChoice, taps), p, params.choiceRate, params.choiceBand);
            }
            curChoice(x, y) = QuantizeHistory(held, precision);
        }
    });
}

}  // namespace fovrt
