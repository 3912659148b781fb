#include "denoise/reference/svgf_ref.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

#include <glm/gtc/packing.hpp>
#include <tbb/parallel_for.h>

#include "shaders/common/edge_stopping_weights.glsl"
#include "shaders/shared_constants.h"

namespace fovrt {

namespace {

constexpr float kAtrousKernel[5] = {1.0f / 16, 1.0f / 4, 3.0f / 8, 1.0f / 4, 1.0f / 16};

float Gauss3(int dx, int dy) { return (dx == 0 ? 0.5f : 0.25f) * (dy == 0 ? 0.5f : 0.25f); }

// Rows in parallel; every pixel is independent, so results equal the serial loop.
template <typename F>
void ForEachRow(int height, F&& f) {
    tbb::parallel_for(0, height, [&](int y) { f(y); });
}

bool Consistent(int qx, int qy, int width, int height, float z, const vec3& n, uint32_t id, float dz,
                const SvgfGeometry& prev) {
    if (qx < 0 || qy < 0 || qx >= width || qy >= height) return false;
    size_t j = size_t(qy) * size_t(width) + size_t(qx);
    if (prev.objectId[j] != id) return false;
    if (std::abs(prev.depth[j] - z) / (dz + float(FOVRT_REPROJECT_DEPTH_EPSILON)) >
        float(FOVRT_REPROJECT_DEPTH_TOLERANCE))
        return false;
    return glm::dot(prev.normal[j], n) >= float(FOVRT_REPROJECT_NORMAL_COS);
}

}  // namespace

void SvgfGeometryPlanes::Allocate(int width, int height) {
    depth.Resize(width, height, std::numeric_limits<float>::infinity());
    normal.Resize(width, height, vec3(0.0f));
    objectId.Resize(width, height, kNoObject);
}

void SvgfGeometryPlanes::CopyFrom(const FrameInputs& f) {
    depth = f.linearDepth;
    normal = f.normal;
    objectId = f.objectId;
}

void SvgfHistory::Allocate(int width, int height, bool weighted) {
    color.Resize(width, height, vec3(0.0f));
    moments.Resize(width, height, vec2(0.0f));
    length.Resize(width, height, 0.0f);
    if (weighted)
        weight.Resize(width, height, 0.0f);
    else
        weight = Plane<float>();
}

ReprojectionTaps FindReprojectionTaps(vec2 prevPixel, int width, int height, float depth,
                                      const vec3& normal, uint32_t objectId, float dz,
                                      const SvgfGeometry& prev) {
    ReprojectionTaps taps;
    if (objectId == kNoObject) return taps;
    // Off-screen (and NaN, which fails every comparison) before any float → int conversion.
    if (!(prevPixel.x > -1.0f && prevPixel.y > -1.0f && prevPixel.x < float(width) + 1.0f &&
          prevPixel.y < float(height) + 1.0f))
        return taps;
    vec2 pos = prevPixel - 0.5f;
    ivec2 base(int(std::floor(pos.x)), int(std::floor(pos.y)));
    vec2 f = pos - vec2(base);
    const float bilinear[4] = {(1 - f.x) * (1 - f.y), f.x * (1 - f.y), (1 - f.x) * f.y, f.x * f.y};
    float sum = 0.0f;
    for (int t = 0; t < 4; ++t) {
        int qx = base.x + (t & 1), qy = base.y + (t >> 1);
        if (bilinear[t] > 0.0f && Consistent(qx, qy, width, height, depth, normal, objectId, dz, prev)) {
            taps.index[size_t(taps.count)] = qy * width + qx;
            taps.weight[size_t(taps.count)] = bilinear[t];
            sum += bilinear[t];
            ++taps.count;
        }
    }
    if (sum >= float(FOVRT_REPROJECT_MIN_WEIGHT)) {
        for (int t = 0; t < taps.count; ++t) taps.weight[size_t(t)] /= sum;
        return taps;
    }
    taps.count = 0;
    taps.box = true;
    ivec2 nearest(int(std::floor(prevPixel.x)), int(std::floor(prevPixel.y)));
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            int qx = nearest.x + dx, qy = nearest.y + dy;
            if (Consistent(qx, qy, width, height, depth, normal, objectId, dz, prev)) {
                taps.index[size_t(taps.count)] = qy * width + qx;
                taps.weight[size_t(taps.count)] = 1.0f;
                ++taps.count;
            }
        }
    for (int t = 0; t < taps.count; ++t) taps.weight[size_t(t)] = 1.0f / float(taps.count);
    return taps;
}

ReprojectionTaps FindReprojectionTaps(const FrameInputs& cur, const SvgfGeometry& prev, int x, int y) {
    vec2 g = cur.depthGradient(x, y);
    return FindReprojectionTaps(cur.prevPixel(x, y), cur.width(), cur.height(), cur.linearDepth(x, y),
                                cur.normal(x, y), cur.objectId(x, y),
                                std::max(std::abs(g.x), std::abs(g.y)), prev);
}

vec3 SanitizeIllumination(const vec3& c, DenoiseStats& stats) {
    if (!IsFinite(c)) {
        ++stats.nonFiniteSamples;
        return vec3(0.0f);
    }
    if (c.x < 0.0f || c.y < 0.0f || c.z < 0.0f) {
        ++stats.negativeSamples;
        return glm::max(c, vec3(0.0f));
    }
    return c;
}

float ReprojectionSampleCount(const FrameInputs& frame, size_t i, bool weighs, bool zeroAware) {
    if (weighs) return float(frame.sampleCount[i]);
    return zeroAware && frame.sampleCount[i] == 0 ? 0.0f : 1.0f;
}

vec4 NothingHeld() { return vec4(0.0f, 0.0f, 0.0f, float(FOVRT_EMPTY_VARIANCE)); }
bool HoldsNothing(const vec4& illumination) { return illumination.a < 0.0f; }

float QuantizeHistory(float v, Precision precision) {
    if (precision == Precision::Fp32) return v;
    constexpr float kMax = float(FOVRT_HALF_SATURATION);
    return glm::unpackHalf1x16(glm::packHalf1x16(std::clamp(v, -kMax, kMax)));
}
vec2 QuantizeHistory(const vec2& v, Precision p) { return {QuantizeHistory(v.x, p), QuantizeHistory(v.y, p)}; }
vec3 QuantizeHistory(const vec3& v, Precision p) {
    return {QuantizeHistory(v.x, p), QuantizeHistory(v.y, p), QuantizeHistory(v.z, p)};
}
vec4 QuantizeHistory(const vec4& v, Precision p) { return {QuantizeHistory(vec3(v), p), QuantizeHistory(v.w, p)}; }

// The shaders' functions (shaders/common/edge_stopping_weights.glsl, one text for both languages).
float DepthWeight(float zp, float zq, const vec2& depthGrad, const vec2& offset, float sigmaDepth) {
    return glsl::depth_weight(zp, zq, depthGrad, offset, sigmaDepth);
}

float NormalWeight(const vec3& np, const vec3& nq, float sigmaNormal) {
    return glsl::normal_weight_pow(np, nq, sigmaNormal);
}

float LuminanceWeight(float lp, float lq, float sigmaLStd) {
    return glsl::luminance_weight(lp, lq, sigmaLStd);
}

void SvgfReprojectRef(const Plane<vec3>& color, const Plane<vec3>* color2, const FrameInputs& cur,
                      const SvgfGeometry& prev, const SvgfHistory& histPrev, SvgfHistory& histCur,
                      Plane<vec4>& illumOut, const SvgfReprojectOptions& options, DenoiseStats& stats) {
    const int w = cur.width(), h = cur.height();
    illumOut.Resize(w, h);
    std::atomic<uint64_t> nonFinite{0}, negative{0};
    const Precision prec = options.precision;
    ForEachRow(h, [&](int y) {
        DenoiseStats rowStats;
        for (int x = 0; x < w; ++x) {
            size_t i = size_t(y) * size_t(w) + size_t(x);
            vec3 raw = color[i];
            if (color2) raw += (*color2)[i];
            vec3 c = SanitizeIllumination(raw, rowStats);
            float l = Luminance(c);
            vec2 m(l, l * l);
            ReprojectionTaps taps = FindReprojectionTaps(cur, prev, x, y);
            bool success = taps.count > 0;
            vec3 cPrev = GatherTaps(histPrev.color, taps);
            vec2 mPrev = GatherTaps(histPrev.moments, taps);
            float lenPrev = GatherTaps(histPrev.length, taps);
            float len = success ? std::min(lenPrev + 1.0f, float(FOVRT_MAX_HISTORY_LENGTH)) : 1.0f;
            const float n = ReprojectionSampleCount(cur, i, options.weighted, options.zeroSamples);
            // A pixel without a path sample keeps its reprojected history as it is (no colour
            // enters, the length stays), or holds nothing where it has none.
            if (n == 0.0f) {
                const bool held = success && lenPrev > 0.0f;
                if (options.weighted)
                    histCur.weight[i] = held ? QuantizeHistory(GatherTaps(histPrev.weight, taps), prec) : 0.0f;
                histCur.moments[i] = held ? QuantizeHistory(mPrev, prec) : vec2(0.0f);
                histCur.length[i] = held ? QuantizeHistory(lenPrev, prec) : 0.0f;
                if (options.writeColorHistory) histCur.color[i] = held ? QuantizeHistory(cPrev, prec) : vec3(0.0f);
                illumOut[i] = held ? vec4(cPrev, std::max(0.0f, mPrev.y - mPrev.x * mPrev.x)) : NothingHeld();
                continue;
            }
            vec3 cAcc;
            if (options.weighted) {
                float wPrev = GatherTaps(histPrev.weight, taps);
                float total = (success ? (1.0f - options.alphaColor) * wPrev : 0.0f) + n;
                cAcc = success ? cPrev + (n / total) * (c - cPrev) : c;
                histCur.weight[i] = QuantizeHistory(total, prec);
            } else {
                float a = success ? std::max(options.alphaColor, 1.0f / len) : 1.0f;
                cAcc = glm::mix(cPrev, c, a);
            }
            float am = success ? std::max(options.alphaMoments, 1.0f / len) : 1.0f;
            vec2 mAcc = glm::mix(mPrev, m, am);
            histCur.moments[i] = QuantizeHistory(mAcc, prec);
            histCur.length[i] = QuantizeHistory(len, prec);
            if (options.writeColorHistory) histCur.color[i] = QuantizeHistory(cAcc, prec);
            illumOut[i] = vec4(cAcc, std::max(0.0f, mAcc.y - mAcc.x * mAcc.x));
        }
        nonFinite += rowStats.nonFiniteSamples;
        negative += rowStats.negativeSamples;
    });
    stats.nonFiniteSamples += nonFinite;
    stats.negativeSamples += negative;
}

void SvgfFilterMomentsRef(const Plane<vec4>& illumIn, const SvgfGeometry& geometry,
                          const Plane<vec2>& depthGradient, const Plane<vec2>& moments,
                          const Plane<float>& length, Plane<vec4>& illumOut, const SvgfParams& params) {
    const int w = illumIn.width(), h = illumIn.height();
    illumOut.Resize(w, h);
    const float threshold = float(params.varianceHistoryThreshold);
    ForEachRow(h, [&](int y) {
        for (int x = 0; x < w; ++x) {
            size_t i = size_t(y) * size_t(w) + size_t(x);
            float len = length[i];
            if (geometry.objectId[i] == kNoObject || len >= threshold) {
                illumOut[i] = illumIn[i];
                continue;
            }
            float zp = geometry.depth[i];
            vec3 np = geometry.normal[i];
            vec2 gp = depthGradient[i];
            float sumW = 0.0f;
            vec3 sumC(0.0f);
            vec2 sumM(0.0f);
            for (int dy = -FOVRT_MOMENTS_RADIUS; dy <= FOVRT_MOMENTS_RADIUS; ++dy)
                for (int dx = -FOVRT_MOMENTS_RADIUS; dx <= FOVRT_MOMENTS_RADIUS; ++dx) {
                    int qx = x + dx, qy = y + dy;
                    if (qx < 0 || qy < 0 || qx >= w || qy >= h) continue;
                    size_t j = size_t(qy) * size_t(w) + size_t(qx);
                    if (geometry.objectId[j] == kNoObject || HoldsNothing(illumIn[j])) continue;
                    float wq = DepthWeight(zp, geometry.depth[j], gp, vec2(dx, dy), params.sigmaDepth) *
                               NormalWeight(np, geometry.normal[j], params.sigmaNormal);
                    sumW += wq;
                    sumC += wq * vec3(illumIn[j]);
                    sumM += wq * moments[j];
                }
            if (sumW == 0.0f) {  // holds nothing, and neither does any neighbour
                illumOut[i] = illumIn[i];
                continue;
            }
            vec2 m = sumM / sumW;
            float variance = std::max(0.0f, m.y - m.x * m.x) * (threshold / std::max(len, 1.0f));
            illumOut[i] = vec4(sumC / sumW, variance);
        }
    });
}

void SvgfAtrousRef(const Plane<vec4>& illumIn, const SvgfGeometry& geometry,
                   const Plane<vec2>& depthGradient, int iteration, Plane<vec4>& illumOut,
                   Plane<vec3>* historyColor, const SvgfParams& params, Precision precision,
                   const HistoryWindow& historyWindow) {
    const int w = illumIn.width(), h = illumIn.height();
    const HistoryWindow held = historyWindow.OrWhole(w, h);
    const int step = 1 << iteration;
    illumOut.Resize(w, h);
    auto inside = [&](int x, int y) { return x >= 0 && y >= 0 && x < w && y < h; };
    ForEachRow(h, [&](int y) {
        for (int x = 0; x < w; ++x) {
            size_t i = size_t(y) * size_t(w) + size_t(x);
            vec4 center = illumIn[i];
            vec4 result = center;
            if (geometry.objectId[i] != kNoObject) {
                // A pixel that holds nothing has weight 0 everywhere (its neighbours fill it) and,
                // with no luminance of its own, no luminance edge-stopping.
                const bool empty = HoldsNothing(center);
                float varSum = 0.0f, varW = 0.0f;
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx) {
                        if (!inside(x + dx, y + dy)) continue;
                        size_t j = i + size_t(ptrdiff_t(dy) * w + dx);
                        if (geometry.objectId[j] == kNoObject || HoldsNothing(illumIn[j])) continue;
                        float g = Gauss3(dx, dy);
                        varSum += g * illumIn[j].a;
                        varW += g;
                    }
                float sigmaLStd = params.sigmaLuminance * std::sqrt(std::max(0.0f, varW > 0.0f ? varSum / varW : 0.0f));
                float zp = geometry.depth[i];
                vec3 np = geometry.normal[i];
                vec2 gp = depthGradient[i];
                float lp = Luminance(vec3(center));
                float sumW = 0.0f, sumV = 0.0f;
                vec3 sumC(0.0f);
                for (int ky = -2; ky <= 2; ++ky)
                    for (int kx = -2; kx <= 2; ++kx) {
                        int qx = x + kx * step, qy = y + ky * step;
                        if (!inside(qx, qy)) continue;
                        size_t j = size_t(qy) * size_t(w) + size_t(qx);
                        if (geometry.objectId[j] == kNoObject || HoldsNothing(illumIn[j])) continue;
                        vec4 cq = illumIn[j];
                        float hk = kAtrousKernel[kx + 2] * kAtrousKernel[ky + 2];
                        float wq = (kx == 0 && ky == 0)
                                       ? 1.0f
                                       : DepthWeight(zp, geometry.depth[j], gp,
                                                     vec2(kx * step, ky * step), params.sigmaDepth) *
                                             NormalWeight(np, geometry.normal[j], params.sigmaNormal) *
                                             (empty ? 1.0f : LuminanceWeight(lp, Luminance(vec3(cq)), sigmaLStd));
                        float hw = hk * wq;
                        sumW += hw;
                        sumC += hw * vec3(cq);
                        sumV += hw * hw * cq.a;
                    }
                if (sumW > 0.0f) result = vec4(sumC / sumW, sumV / (sumW * sumW));
            }
            illumOut[i] = result;
            if (const int hi = held.Index(x, y); historyColor && hi >= 0)
                (*historyColor)[size_t(hi)] = QuantizeHistory(vec3(result), precision);
        }
    });
}

void SvgfModulateRef(const Plane<vec4>& illum0, const Plane<vec4>* illum1, const Plane<vec3>& albedo,
                     const Plane<vec3>& emission, Plane<vec3>& out) {
    const int w = illum0.width(), h = illum0.height();
    out.Resize(w, h);
    ForEachRow(h, [&](int y) {
        for (int x = 0; x < w; ++x) {
            size_t i = size_t(y) * size_t(w) + size_t(x);
            vec3 illum = vec3(illum0[i]);
            if (illum1) illum += vec3((*illum1)[i]);
            out[i] = albedo[i] * illum + emission[i];
        }
    });
}

}  // namespace fovrt
