#include "denoise/reference/asvgf_ref.h"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>

#include "denoise/reference/svgf_ref.h"

namespace fovrt {

int AsvgfScatterGradientsRef(const FrameInputs& frame, Plane<vec2>& gradient,
                             Plane<StratumGuide>& guide) {
    const int w = frame.width(), h = frame.height();
    const ivec2 grid = StratumGridSize(w, h);
    gradient.Resize(grid.x, grid.y, vec2(0.0f));
    guide.Resize(grid.x, grid.y);
    Plane<uint8_t> filled(grid.x, grid.y, uint8_t(0));
    auto guideAt = [&](ivec2 p) {
        StratumGuide g;
        g.depth = frame.linearDepth(p.x, p.y);
        g.normal = frame.normal(p.x, p.y);
        g.depthGradient = frame.depthGradient(p.x, p.y);
        g.luminance = Luminance(frame.NoisyColor(p.x, p.y));
        g.objectId = frame.objectId(p.x, p.y);
        return g;
    };
    int count = 0;
    // First sample wins, as the shader's compare-and-swap on the stratum slot.
    for (const GradientSample& s : frame.gradientSamples) {
        if (!gradient.InBounds(s.stratum.x, s.stratum.y) ||
            !frame.direct.InBounds(s.pixel.x, s.pixel.y))
            continue;
        if (filled(s.stratum.x, s.stratum.y)) continue;
        if (!std::isfinite(s.newLuminance) || !std::isfinite(s.oldLuminance)) continue;
        filled(s.stratum.x, s.stratum.y) = 1;
        const float fNew = std::max(s.newLuminance, 0.0f), fOld = std::max(s.oldLuminance, 0.0f);
        gradient(s.stratum.x, s.stratum.y) = vec2(fNew - fOld, std::max(fNew, fOld));
        guide(s.stratum.x, s.stratum.y) = guideAt(s.pixel);
        ++count;
    }
    // Rows in parallel from here on: every stratum / pixel is independent (results equal serial).
    tbb::parallel_for(0, grid.y, [&](int sy) {
        for (int sx = 0; sx < grid.x; ++sx) {
            if (filled(sx, sy)) continue;
            const ivec2 centre(std::min(sx * kGradientStratumSize + 1, w - 1),
                               std::min(sy * kGradientStratumSize + 1, h - 1));
            guide(sx, sy) = guideAt(centre);
        }
    });
    return count;
}

void AsvgfGradientAtrousRef(const Plane<vec2>& in, const Plane<StratumGuide>& guide, int iteration,
                            Plane<vec2>& out, const SvgfParams& svgf) {
    const int gw = in.width(), gh = in.height();
    out.Resize(gw, gh, vec2(0.0f));
    const int step = 1 << iteration;
    tbb::parallel_for(0, gh, [&](int sy) {
        for (int sx = 0; sx < gw; ++sx) {
            const StratumGuide& gp = guide(sx, sy);
            if (gp.objectId == kNoObject) {
                out(sx, sy) = in(sx, sy);
                continue;
            }
            // Standard deviation of the guide luminance over the 3×3 strata: scales w_l.
            float sum = 0, sum2 = 0, cnt = 0;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    if (!guide.InBounds(sx + dx, sy + dy)) continue;
                    const StratumGuide& gq = guide(sx + dx, sy + dy);
                    if (gq.objectId == kNoObject) continue;
                    sum += gq.luminance;
                    sum2 += gq.luminance * gq.luminance;
                    cnt += 1;
                }
            const float mean = sum / cnt;
            const float sigmaLStd =
                svgf.sigmaLuminance * std::sqrt(std::max(0.0f, sum2 / cnt - mean * mean));
            vec2 acc(0.0f);
            float wsum = 0.0f;
            for (int ky = -1; ky <= 1; ++ky)
                for (int kx = -1; kx <= 1; ++kx) {
                    const int qx = sx + kx * step, qy = sy + ky * step;
                    if (!in.InBounds(qx, qy)) continue;
                    const StratumGuide& gq = guide(qx, qy);
                    if (gq.objectId == kNoObject) continue;
                    float wgt = 1.0f;
                    if (kx != 0 || ky != 0) {
                        const vec2 offsetPixels = vec2(kx, ky) * float(step * kGradientStratumSize);
                        wgt = DepthWeight(gp.depth, gq.depth, gp.depthGradient, offsetPixels,
                                          svgf.sigmaDepth) *
                              NormalWeight(gp.normal, gq.normal, svgf.sigmaNormal) *
                              LuminanceWeight(gp.luminance, gq.luminance, sigmaLStd);
                    }
                    acc += wgt * in(qx, qy);
                    wsum += wgt;
                }
            out(sx, sy) = acc / wsum;  // the centre has weight 1
        }
    });
}

void AsvgfAlphaRef(const Plane<vec2>& reconstructed, int width, int height, float alpha,
                   Plane<float>& alphaOut, Plane<float>& lambdaOut, std::optional<float> antilagGain) {
    const int gw = reconstructed.width(), gh = reconstructed.height();
    Plane<float> lambdaS(gw, gh, 0.0f);
    tbb::parallel_for(0, gh, [&](int sy) {
        for (int sx = 0; sx < gw; ++sx) {
            const vec2 d = reconstructed(sx, sy);
            lambdaS(sx, sy) = d.y > 1e-6f ? std::min(1.0f, std::abs(d.x) / d.y) : 0.0f;
        }
    });
    alphaOut.Resize(width, height, alpha);
    lambdaOut.Resize(width, height, 0.0f);
    tbb::parallel_for(0, height, [&](int y) {
        for (int x = 0; x < width; ++x) {
            const int sx = x / kGradientStratumSize, sy = y / kGradientStratumSize;
            float lambda = 0.0f;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx)
                    if (lambdaS.InBounds(sx + dx, sy + dy))
                        lambda = std::max(lambda, lambdaS(sx + dx, sy + dy));
            // α is monotonic in λ, so the max of α is the α of the max λ.
            lambdaOut(x, y) = lambda;
            alphaOut(x, y) = antilagGain ? std::clamp(*antilagGain * lambda, 0.0f, 1.0f)
                                         : (1.0f - lambda) * alpha + lambda;
        }
    });
}

void AsvgfTemporalAlphaRef(const FrameInputs& frame, const AsvgfParams& params,
                           const SvgfParams& svgf, Plane<float>& alphaOut, Plane<float>& lambdaOut,
                           Plane<vec2>* reconstructed) {
    Plane<vec2> a, b;
    Plane<StratumGuide> guide;
    AsvgfScatterGradientsRef(frame, a, guide);
    for (int i = 0; i < params.gradientIterations; ++i) {
        AsvgfGradientAtrousRef(a, guide, i, b, svgf);
        std::swap(a, b);
    }
    AsvgfAlphaRef(a, frame.width(), frame.height(), params.alpha, alphaOut, lambdaOut);
    if (reconstructed) *reconstructed = std::move(a);
}

}  // namespace fovrt
