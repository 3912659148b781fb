// C++ reference of the SVGF stages (Schied et al. 2017, §4): one scalar function per stage with the
// same inputs and outputs as its shader (shaders/svgf_*.comp). Also the CPU fallback backend.
// Other denoisers (svgf-weighted, two-history, A-SVGF) compose these stages; their signatures are
// stable. Loops are plain scalar code, rows in parallel with TBB (identical results to serial).
#pragma once

#include <array>
#include <cstdint>

#include "core/frame_inputs.h"
#include "core/image.h"
#include "core/math.h"
#include "denoise/denoiser.h"
#include "denoise/history_window.h"
#include "denoise/params.h"

namespace fovrt {

// The geometry planes the SVGF tests and edge-stopping weights read, for one frame.
struct SvgfGeometry {
    const Plane<float>& depth;
    const Plane<vec3>& normal;
    const Plane<uint32_t>& objectId;
};
inline SvgfGeometry GeometryOf(const FrameInputs& f) { return {f.linearDepth, f.normal, f.objectId}; }

// Owned copy of a frame's geometry (the previous frame's, kept as history).
struct SvgfGeometryPlanes {
    Plane<float> depth;
    Plane<vec3> normal;
    Plane<uint32_t> objectId;
    void Allocate(int width, int height);  // background everywhere: nothing reprojects
    void CopyFrom(const FrameInputs& f);
    SvgfGeometry View() const { return {depth, normal, objectId}; }
};

// One channel's persistent SVGF state: one side of an A/B pair.
struct SvgfHistory {
    Plane<vec3> color;    // colour fed back (filtered after à-trous iteration k)
    Plane<vec2> moments;  // (E[l], E[l²]) of luminance
    Plane<float> length;  // history length in frames (interpolated on reprojection)
    Plane<float> weight;  // total weight W (weighted mode only; empty otherwise)
    void Allocate(int width, int height, bool weighted);
};

// Back-projection taps (Schied et al. 2017, §4.1; thresholds of Falcor's SVGFPass): 2×2 bilinear
// with per-tap consistency tests (object id, |z_prev − z|/(dz + 0.01) ≤ 10, dot(n_prev, n) ≥ 0.9),
// weights renormalised; if none is valid, every valid pixel of the 3×3 block around the nearest
// previous pixel, equal weights; else none.
struct ReprojectionTaps {
    int count = 0;
    bool box = false;               // from the 3×3 fallback (no bilinear tap was valid)
    std::array<int, 9> index{};    // previous-frame pixel index y·W + x
    std::array<float, 9> weight{};  // sum 1 when count > 0
};
ReprojectionTaps FindReprojectionTaps(vec2 prevPixel, int width, int height, float depth,
                                      const vec3& normal, uint32_t objectId, float dz,
                                      const SvgfGeometry& prev);
// Taps of pixel (x, y) of the current frame.
ReprojectionTaps FindReprojectionTaps(const FrameInputs& cur, const SvgfGeometry& prev, int x, int y);

template <typename T>
T GatherTaps(const Plane<T>& plane, const ReprojectionTaps& taps) {
    T sum{};
    for (int t = 0; t < taps.count; ++t) sum += taps.weight[size_t(t)] * plane[size_t(taps.index[size_t(t)])];
    return sum;
}

// NaN/Inf pixel → 0 (counted non-finite); negative components → 0 (counted negative).
vec3 SanitizeIllumination(const vec3& c, DenoiseStats& stats);

// The path-sample count n pixel i is accumulated with (REPROJ_SAMPLE_COUNT,
// shaders/common/reprojection.glsl): frame.sampleCount where the stage weighs by it; 0 or 1 where
// it only keeps pixels without a sample (`zeroAware`: DenoiserParams::sampleCountsMayBeZero), so
// a sampled pixel's arithmetic is the one without counts; else 1. n = 0 keeps the history.
float ReprojectionSampleCount(const FrameInputs& frame, size_t i, bool weighs, bool zeroAware);

// The (illumination, variance) of a pixel that holds nothing: no path sample this frame and no
// history (FOVRT_EMPTY_VARIANCE); the spatial passes give it weight 0 so its neighbours fill it.
vec4 NothingHeld();
bool HoldsNothing(const vec4& illumination);

// Rounds a value as the history storage of `precision` would (fp16 round trip, saturating).
float QuantizeHistory(float v, Precision precision);
vec2 QuantizeHistory(const vec2& v, Precision precision);
vec3 QuantizeHistory(const vec3& v, Precision precision);
vec4 QuantizeHistory(const vec4& v, Precision precision);

// Edge-stopping weights: the shaders' functions (shaders/common/edge_stopping_weights.glsl, one text
// for GLSL and C++).
float DepthWeight(float zp, float zq, const vec2& depthGrad, const vec2& offset, float sigmaDepth);
float NormalWeight(const vec3& np, const vec3& nq, float sigmaNormal);
float LuminanceWeight(float lp, float lq, float sigmaLStd);

struct SvgfReprojectOptions {
    float alphaColor = 0.2f;
    float alphaMoments = 0.2f;
    bool weighted = false;         // svgf-weighted: W ← (1−α)W + n, C += n(x − C)/W
    bool zeroSamples = false;      // unweighted: a pixel with n = 0 keeps its history (ZERO_SAMPLES)
    bool writeColorHistory = true; // false when an à-trous iteration feeds back the colour
    Precision precision = Precision::Fp32;
};

// Stage svgf_reproject. `color2` (may be null) is added to `color` (combined filtering).
// Writes histCur.moments/length (/weight), histCur.color when writeColorHistory, and illumOut =
// (accumulated colour, temporal variance).
void SvgfReprojectRef(const Plane<vec3>& color, const Plane<vec3>* color2, const FrameInputs& cur,
                      const SvgfGeometry& prev, const SvgfHistory& histPrev, SvgfHistory& histCur,
                      Plane<vec4>& illumOut, const SvgfReprojectOptions& options, DenoiseStats& stats);

// Stage svgf_filter_moments: 7×7 spatial variance where length < threshold.
void SvgfFilterMomentsRef(const Plane<vec4>& illumIn, const SvgfGeometry& geometry,
                          const Plane<vec2>& depthGradient, const Plane<vec2>& moments,
                          const Plane<float>& length, Plane<vec4>& illumOut, const SvgfParams& params);

// Stage svgf_atrous, one iteration with step 2^iteration. When historyColor is non-null the
// filtered colour is also written there (the feedback iteration), quantised to `precision`.
// historyColor, when given, holds `historyWindow` (denoise/history_window.h; size 0: the image).
void SvgfAtrousRef(const Plane<vec4>& illumIn, const SvgfGeometry& geometry,
                   const Plane<vec2>& depthGradient, int iteration, Plane<vec4>& illumOut,
                   Plane<vec3>* historyColor, const SvgfParams& params,
                   Precision precision = Precision::Fp32, const HistoryWindow& historyWindow = {});

// Stage svgf_modulate: out = albedo·(illum0 + illum1) + emission; illum1 null when combined.
void SvgfModulateRef(const Plane<vec4>& illum0, const Plane<vec4>* illum1, const Plane<vec3>& albedo,
                     const Plane<vec3>& emission, Plane<vec3>& out);

}  // namespace fovrt
