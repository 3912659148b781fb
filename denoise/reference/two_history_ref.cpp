#include "denoise/reference/two_history_ref.h"

#include <algorithm>
#include <atomic>
#include <cmath>

#include <tbb/parallel_for.h>

#include "denoise/reference/two_history_math.h"
#include "shaders/common/two_history_constants.glsl"
#include "shaders/shared_constants.h"

namespace fovrt {

void TwoHistoryState::Allocate(int width, int height, int channels, bool twoHistory,
                               bool withGradient, ivec2 window) {
    const ivec2 held = twoHistory ? (window.x > 0 ? window : ivec2(width, height)) : ivec2(0);
    for (int c = 0; c < 2; ++c) {
        const bool used = c < channels;
        iu[size_t(c)].Resize(used ? width : 0, used ? height : 0, vec3(0.0f));
        iw[size_t(c)].Resize(used ? held.x : 0, used ? held.y : 0, vec3(0.0f));
        moments[size_t(c)].Resize(used ? width : 0, used ? height : 0, vec2(0.0f));
    }
    wu.Resize(width, height, 0.0f);
    ww.Resize(held.x, held.y, 0.0f);
    powerSums.Resize(held.x, held.y, vec3(0.0f));
    gradient.Resize(withGradient ? width : 0, withGradient ? height : 0, 0.0f);
}

void TwoHistoryReprojectRef(const std::array<const Plane<vec3>*, 2>& colors, int channels,
                            const Plane<vec3>* color2, const FrameInputs& frame,
                            const SvgfGeometry& prevGeometry, bool hasPrev,
                            const TwoHistoryState& prev, TwoHistoryState& cur,
                            const Plane<float>* alphaMap, std::array<Plane<vec4>, 2>& illumU,
                            std::array<Plane<vec4>, 2>& illumW,
                            const TwoHistoryReprojectOptions& options, DenoiseStats& stats) {
    const int w = frame.width(), h = frame.height();
    const Precision prec = options.precision;
    const bool two = options.twoHistory;
    const bool withGradient = two && options.gradient;
    const HistoryWindow win = options.window.OrWhole(w, h), prevWin = options.prevWindow.OrWhole(w, h);
    FOVRT_CHECK(!two || (win.size == prevWin.size && cur.ww.width() == win.size.x && cur.ww.height() == win.size.y));
    // A windowed plane's value over the taps, each at its place in the previous window.
    auto gatherWindow = [&](const auto& plane, const ReprojectionTaps& taps) {
        std::decay_t<decltype(plane[0])> sum{};
        for (int t = 0; t < taps.count; ++t) {
            const int j = taps.index[size_t(t)];
            sum += taps.weight[size_t(t)] * plane[size_t(prevWin.Index(j % w, j / w))];
        }
        return sum;
    };
    auto tapsInPrevWindow = [&](const ReprojectionTaps& taps) {
        for (int t = 0; t < taps.count; ++t) {
            const int j = taps.index[size_t(t)];
            if (taps.weight[size_t(t)] > 0.0f && prevWin.Index(j % w, j / w) < 0) return false;
        }
        return true;
    };
    for (int c = 0; c < channels; ++c) {
        illumU[size_t(c)].Resize(w, h);
        if (two) illumW[size_t(c)].Resize(w, h);
    }
    // Firefly variants: the largest sample luminance of channel c among (x, y)'s in-image 8 neighbours.
    auto neighbourMaxLuminance = [&](size_t c, int x, int y) {
        float m = 0.0f;
        for (int d = 0; d < 9; ++d) {
            const int qx = x + d % 3 - 1, qy = y + d / 3 - 1;
            if (d == 4 || qx < 0 || qy < 0 || qx >= w || qy >= h) continue;
            const size_t j = size_t(qy) * size_t(w) + size_t(qx);
            vec3 raw = (*colors[c])[j];
            if (channels == 1 && color2) raw += (*color2)[j];
            m = std::max(m, FireflyNeighbourLuminance(raw));
        }
        return m;
    };
    // Rows in parallel: pixels are independent; the sample counters are integers, so per-row
    // counts summed in any order equal the serial count.
    std::atomic<uint64_t> nonFinite{0}, negative{0};
    tbb::parallel_for(0, h, [&](int y) {
        DenoiseStats rowStats;
        for (int x = 0; x < w; ++x) {
            const size_t i = size_t(y) * size_t(w) + size_t(x);
            const ReprojectionTaps taps =
                hasPrev ? FindReprojectionTaps(frame, prevGeometry, x, y) : ReprojectionTaps{};
            const bool success = taps.count > 0;
            // The two-history variants weigh by the sample count; A-SVGF's own history reads it
            // only with zeroSamples, to keep a pixel without a path sample (else n = 1).
            const float n = ReprojectionSampleCount(frame, i, two, options.zeroSamples);

            // wi: this pixel in the window (−1 outside); weightedHeld: its weighted history can be
            // gathered (else it restarts: W_w = S_k = 0, I_w from the reprojected I_u).
            const int wi = two ? win.Index(x, y) : -1;
            const bool weightedHeld = success && wi >= 0 && tapsInPrevWindow(taps);
            TwoHistoryWeights wPrev;
            if (success) {
                wPrev.wu = GatherTaps(prev.wu, taps);
                if (weightedHeld) {
                    wPrev.ww = gatherWindow(prev.ww, taps);
                    const vec3 s = gatherWindow(prev.powerSums, taps);
                    wPrev.sMinus1 = s.x, wPrev.s0 = s.y, wPrev.s1 = s.z;
                }
            }
            float alpha = alphaMap ? (*alphaMap)[i] : options.alpha;
            float alphaM = alphaMap ? (*alphaMap)[i] : options.alphaMoments;
            if (options.antilag) {
                const float a = (*alphaMap)[i];
                alpha = AntilagAlpha(a, options.alpha, wPrev.wu, options.antilagPower);
                alphaM = glm::mix(options.alphaMoments, 1.0f, a);
            }
            // β = 0 on disocclusion: every sum restarts from this frame's sample.
            const float beta = success ? TwoHistoryDecay(alpha, wPrev.wu) : 0.0f;
            // No path sample (n = 0): every history stays as reprojected, W_u included; where
            // there is none (W_u,prev = 0) the pixel holds nothing.
            const bool sampled = n > 0.0f, held = sampled || wPrev.wu > 0.0f;
            const TwoHistoryWeights wNew = sampled ? AccumulateWeights(wPrev, beta, n) : wPrev;
            const float am = success ? std::max(alphaM, 1.0f / wNew.wu) : 1.0f;

            vec3 xSum(0.0f), iuPrevSum(0.0f);
            for (int c = 0; c < channels; ++c) {
                const size_t ch = size_t(c);
                vec3 raw = (*colors[ch])[i];
                if (channels == 1 && color2) raw += (*color2)[i];
                vec3 xc = SanitizeIllumination(raw, rowStats);
                const vec3 iuPrev = success ? GatherTaps(prev.iu[ch], taps) : xc;
                const vec2 mGathered = success ? GatherTaps(prev.moments[ch], taps) : vec2(0.0f);
                if (options.suppressFireflies && success && wPrev.wu >= float(FOVRT_FIREFLY_MIN_HISTORY))
                    xc = SuppressFirefly(xc, Luminance(xc), mGathered, options.fireflySigma,
                                         neighbourMaxLuminance(ch, x, y));
                const float l = Luminance(xc);
                const vec2 mPrev = success ? mGathered : vec2(l, l * l);
                const vec3 iu = !sampled ? (held ? iuPrev : vec3(0.0f)) : AccumulateUnweighted(iuPrev, xc, wNew.wu);
                const vec2 m = !sampled ? (held ? mPrev : vec2(0.0f)) : glm::mix(mPrev, vec2(l, l * l), am);
                const float var = std::max(0.0f, m.y - m.x * m.x);
                cur.moments[ch][i] = QuantizeHistory(m, prec);
                illumU[ch][i] = held ? vec4(iu, var) : NothingHeld();
                if (options.writeColorHistory) cur.iu[ch][i] = QuantizeHistory(iu, prec);
                if (two && wi >= 0) {
                    const vec3 iwPrev = weightedHeld ? gatherWindow(prev.iw[ch], taps) : success ? iuPrev : xc;
                    const vec3 iw = !sampled ? (held ? iwPrev : vec3(0.0f)) : AccumulateWeighted(iwPrev, xc, n, wNew.ww);
                    illumW[ch][i] = held ? vec4(iw, var) : NothingHeld();
                    if (options.writeColorHistory) cur.iw[ch][size_t(wi)] = QuantizeHistory(iw, prec);
                } else if (two) {  // outside the window: the unweighted history's
                    illumW[ch][i] = illumU[ch][i];
                }
                xSum += xc;
                iuPrevSum += iuPrev;
            }
            cur.wu[i] = QuantizeHistory(wNew.wu, prec);
            if (two && wi >= 0) {
                cur.ww[size_t(wi)] = QuantizeHistory(wNew.ww, prec);
                cur.powerSums[size_t(wi)] = QuantizeHistory(vec3(wNew.sMinus1, wNew.s0, wNew.s1), prec);
            }
            if (withGradient) {
                const float gPrev = success ? GatherTaps(prev.gradient, taps) : 0.0f;
                cur.gradient[i] = QuantizeHistory(
                    sampled ? AccumulateGradient(gPrev, LuminanceGradient(xSum, iuPrevSum), 0.0f,
                                                 options.gradientBeta, success)
                            : gPrev,  // no sample, no new gradient
                    prec);
            }
        }
        nonFinite += rowStats.nonFiniteSamples;
        negative += rowStats.negativeSamples;
    });
    stats.nonFiniteSamples += nonFinite;
    stats.negativeSamples += negative;
}

template <typename T>
T FilterTwoHistoryGradient(const Plane<T>& gradient, const FrameInputs& frame,
                           const SvgfParams& svgf, int x, int y) {
    static constexpr float kKernel[5] = {1.0f / 16, 1.0f / 4, 3.0f / 8, 1.0f / 4, 1.0f / 16};
    const float zp = frame.linearDepth(x, y);
    const vec3 np = frame.normal(x, y);
    const vec2 gp = frame.depthGradient(x, y);
    T sum{};
    float wsum = 0.0f;
    for (int ky = -2; ky <= 2; ++ky)
        for (int kx = -2; kx <= 2; ++kx) {
            const int qx = x + kx, qy = y + ky;
            if (!gradient.InBounds(qx, qy) || frame.objectId(qx, qy) == kNoObject) continue;
            float wgt = kKernel[kx + 2] * kKernel[ky + 2];
            if (kx != 0 || ky != 0)
                wgt *= DepthWeight(zp, frame.linearDepth(qx, qy), gp, vec2(kx, ky),
                                   svgf.sigmaDepth) *
                       NormalWeight(np, frame.normal(qx, qy), svgf.sigmaNormal);
            sum += wgt * gradient(qx, qy);
            wsum += wgt;
        }
    return sum / wsum;
}

template float FilterTwoHistoryGradient(const Plane<float>&, const FrameInputs&, const SvgfParams&,
                                        int, int);
template vec3 FilterTwoHistoryGradient(const Plane<vec3>&, const FrameInputs&, const SvgfParams&,
                                       int, int);

void TwoHistoryGradientRef(const Plane<float>& gradient, const std::array<Plane<vec4>, 2>& illumU,
                           int channels, const FrameInputs& frame, const SvgfParams& svgf,
                           float qScale, Plane<float>& qOut) {
    const int w = frame.width(), h = frame.height();
    qOut.Resize(w, h, 0.0f);
    tbb::parallel_for(0, h, [&](int y) {
        for (int x = 0; x < w; ++x) {
            if (frame.objectId(x, y) == kNoObject) continue;
            float var = 0.0f;
            for (int c = 0; c < channels; ++c) var += illumU[size_t(c)](x, y).a;
            qOut(x, y) = TwoHistoryGradientBlend(
                FilterTwoHistoryGradient(gradient, frame, svgf, x, y), var, qScale);
        }
    });
}

void NeighbourhoodMeanSigma(const Plane<vec4>& plane, int x, int y, vec3& mean, vec3& sigma) {
    vec3 sum(0.0f), sumSq(0.0f);
    float count = 0.0f;
    for (int d = 0; d < 9; ++d) {
        const int qx = x + d % 3 - 1, qy = y + d / 3 - 1;
        if (qx < 0 || qy < 0 || qx >= plane.width() || qy >= plane.height()) continue;
        const vec3 c = vec3(plane(qx, qy));
        sum += c;
        sumSq += c * c;
        count += 1.0f;
    }
    mean = sum / count;
    sigma = glm::sqrt(glm::max(sumSq / count - mean * mean, vec3(0.0f)));
}

void TwoHistoryBlendRef(const Plane<vec4>& illumU, const Plane<vec4>& illumW,
                        const Plane<float>& wu, const Plane<float>& ww,
                        const Plane<vec3>& powerSums, const Plane<float>& q, Plane<vec4>& out,
                        const TwoHistoryClampOptions& clamp, const Plane<float>* heldChoice,
                        const HistoryWindow& window) {
    const int width = illumU.width();
    const HistoryWindow win = window.OrWhole(width, illumU.height());
    out.Resize(illumU.width(), illumU.height());
    tbb::parallel_for(0, illumU.height(), [&](int y) {
        for (int x = 0; x < width; ++x) {
            const size_t i = size_t(y) * size_t(width) + size_t(x);
            const int wi = win.Index(x, y);
            if (wi < 0) {  // no weighted history here: the unweighted one, as it is
                out[i] = illumU[i];
                continue;
            }
            if (clamp.enabled) {
                vec3 mean, sigma;
                NeighbourhoodMeanSigma(illumW, x, y, mean, sigma);
                out[i] = TwoHistoryClampBlend(illumU[i], illumW[i], mean, sigma, clamp.sigma, q[i]);
                continue;
            }
            const float p = heldChoice ? (*heldChoice)[i]
                                       : TwoHistoryOptimalBlend(StoredTwoHistoryWeights(wu[i], ww[size_t(wi)], powerSums[size_t(wi)]));
            const float t = TwoHistoryFinalBlend(p, q[i]);
            out[i] = glm::mix(illumW[i], illumU[i], t);
        }
    });
}

}  // namespace fovrt
