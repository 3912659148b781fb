#include "metrics/vdp_temporal.h"

#include <algorithm>
#include <cmath>

#include "metrics/vdp_fastmath.h"

namespace fovrt {

int VdpTemporalFilterLength(double fps) { return int(std::ceil(250.0 / (1000.0 / fps))); }

VdpTemporalFilters MakeVdpTemporalFilters(double fps, const VdpParams& params) {
    const int n = VdpTemporalFilterLength(fps);
    std::vector<double> t(static_cast<size_t>(n)), s(static_cast<size_t>(n));
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {
        t[size_t(i)] = n > 1 ? double(n) / fps * i / (n - 1) : 0.0;
        const double d = std::log(t[size_t(i)] + 1e-4) - std::log(params.sustainedBeta);
        s[size_t(i)] = std::exp(-d * d / (2.0 * params.sustainedSigma * params.sustainedSigma));
        sum += s[size_t(i)];
    }
    VdpTemporalFilters f;
    f.sustained.resize(size_t(n));
    f.transient.assign(size_t(n), 0.0f);
    for (int i = 0; i < n; ++i) f.sustained[size_t(i)] = float(s[size_t(i)] / sum);
    for (int i = 0; i + 1 < n; ++i)
        f.transient[size_t(i)] = float(kVdpTransientGain * (s[size_t(i + 1)] - s[size_t(i)]) / sum / (t[1] - t[0]));
    return f;
}

Plane<float> VdpFilterFrame(const std::vector<Plane<float>>& frames, int frame, const std::vector<float>& taps) {
    Plane<float> out(frames[0].width(), frames[0].height(), 0.0f);
    for (size_t k = 0; k < taps.size(); ++k) {
        const Plane<float>& src = frames[size_t(std::max(frame - int(k), 0))];
        const float g = taps[k];
        for (size_t p = 0; p < out.size(); ++p) out[p] += g * src[p];
    }
    return out;
}

FOVRT_VDP_ROW_CLONES
void VdpFilterFrameChannels(const std::vector<Plane<float>>& frames, int frame, const VdpTemporalFilters& filters,
                            Plane<float>& sustained, Plane<float>& transient) {
    const int w = frames[0].width(), h = frames[0].height();
    // Written in place: the metric passes the planes of an earlier frame, whose memory is reused.
    sustained.ResizeForOverwrite(w, h);
    transient.ResizeForOverwrite(w, h);
    // Row by row, so the taps' rows and the two outputs stay in cache; per pixel the taps are
    // summed in VdpFilterFrame's order, the first tap's product standing for 0 + it.
    for (int y = 0; y < h; ++y) {
        float* s = &sustained(0, y);
        float* t = &transient(0, y);
        for (size_t k = 0; k < filters.sustained.size(); ++k) {
            const float* src = &frames[size_t(std::max(frame - int(k), 0))](0, y);
            const float gs = filters.sustained[k], gt = filters.transient[k];
            if (k == 0) {
                for (int x = 0; x < w; ++x) s[x] = gs * src[x], t[x] = gt * src[x];
                continue;
            }
            for (int x = 0; x < w; ++x) {
                s[x] += gs * src[x];
                t[x] += gt * src[x];
            }
        }
    }
}

}  // namespace fovrt
