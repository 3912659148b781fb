// LocalBandContrast: the content's local contrast in the noise's frequency band, what the
// perceptual model's content term reads as the metric's masking signal (spp_model.h).
#include <algorithm>
#include <cmath>

#include "foveation/spp_model.h"

namespace fovrt {
namespace {

// One separable pass of the 5-tap binomial [1 4 6 4 1] / 16 with its taps `step` pixels apart
// (à trous), edges clamped.
Plane<float> BinomialBlur(const Plane<float>& in, int step) {
    static constexpr float kTaps[5] = {1.0f / 16, 4.0f / 16, 6.0f / 16, 4.0f / 16, 1.0f / 16};
    const int w = in.width(), h = in.height();
    Plane<float> rows(w, h), out(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            float sum = 0.0f;
            for (int k = -2; k <= 2; ++k) sum += kTaps[k + 2] * in(std::clamp(x + k * step, 0, w - 1), y);
            rows(x, y) = sum;
        }
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            float sum = 0.0f;
            for (int k = -2; k <= 2; ++k) sum += kTaps[k + 2] * rows(x, std::clamp(y + k * step, 0, h - 1));
            out(x, y) = sum;
        }
    return out;
}

}  // namespace

Plane<float> LocalBandContrast(const Plane<float>& luminance, double cyclesPerPixel) {
    // Level j of the pyramid (G_j − G_j+1, G_j+1 = G_j blurred with taps 2^j apart) peaks near
    // 0.5 / 2^j cycles per pixel: the level nearest the noise's frequency.
    const int level = std::clamp(int(std::lround(std::log2(0.5 / std::max(cyclesPerPixel, 1e-3)))), 0, 6);
    Plane<float> fine = luminance;
    for (int j = 0; j < level; ++j) fine = BinomialBlur(fine, 1 << j);
    const Plane<float> coarse = BinomialBlur(fine, 1 << level);
    // Weber contrast, as the metric's pyramid takes it, squared: its energy, averaged over the
    // next scale so that the term follows the band's envelope, not its zero crossings.
    Plane<float> energy(luminance.width(), luminance.height());
    for (size_t i = 0; i < energy.size(); ++i) {
        const float c = coarse[i] > 0.0f ? (fine[i] - coarse[i]) / coarse[i] : 0.0f;
        energy[i] = c * c;
    }
    energy = BinomialBlur(energy, 1 << (level + 1));
    for (float& e : energy.vector()) e = std::sqrt(std::max(e, 0.0f));
    return energy;
}

}  // namespace fovrt
