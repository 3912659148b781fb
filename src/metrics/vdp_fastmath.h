// exp2 and log2 in float for the metric's per-pixel loops (CSF lookup, masking, pooling): plain
// arithmetic, selects and bit operations, no library calls, so GCC vectorises a loop that calls
// them with baseline SSE2 (libm's exp2f/log2f are calls it cannot vectorise). The selects are
// if-converted only without trapping math: the metric's sources are compiled with
// -fno-trapping-math -fno-math-errno (src/metrics/CMakeLists.txt). Accuracy (tests/
// metrics_vdp_fastmath_test.cpp): log2 within 2e-7 on normal floats (absolute; relative beyond
// ±1), exp2 within 3e-7 relative on [−126, 127]; the metric's JOD moves by at most 1e-6 against
// libm's (tests/metrics_fovvideovdp_test.cpp holds it to 1e-4).
#pragma once

#include <algorithm>
#include <bit>
#include <cstdint>
#include <limits>

// The metric's per-pixel row functions are compiled twice, for baseline x86-64 (SSE2) and for
// AVX2 (twice the vector width), and the loader picks one by the CPU it runs on: the binary stays
// generic (no -march). Not FMA: the AVX2 clone computes the same floats as the SSE2 one, so a
// score is the same on every x86-64.
// Sanitized builds keep the baseline alone: the loader runs a clone's resolver (an ifunc) while it
// relocates, before the sanitizer's runtime is set up, and an instrumented resolver crashes there.
#if defined(__SANITIZE_THREAD__) || defined(__SANITIZE_ADDRESS__)
#define FOVRT_VDP_ROW_CLONES
#else
#define FOVRT_VDP_ROW_CLONES [[gnu::target_clones("avx2", "default")]]
#endif

namespace fovrt {

// log2 x for x > 0; −∞ for x below the smallest normal float (0 included: "no signal").
inline float VdpFastLog2(float x) {
    const uint32_t bits = std::bit_cast<uint32_t>(x);
    // x = 2^e · m with m in [√½, √2): the series below converges fastest around m = 1.
    const uint32_t shifted = bits + (0x3f800000u - 0x3f3504f3u);  // moves m ≥ √2 into the next octave
    const int e = int(shifted >> 23) - 127;
    const float m = std::bit_cast<float>((shifted & 0x007fffffu) + 0x3f3504f3u);
    // log2 m = (2/ln 2)·atanh(t), t = (m − 1)/(m + 1), |t| ≤ 0.1716: odd series to t⁹.
    const float t = (m - 1.0f) / (m + 1.0f), t2 = t * t;
    const float series = t * (2.8853900817779268f +
                              t2 * (0.9617966939259756f +
                                    t2 * (0.5770780163555854f + t2 * (0.4121985831111324f + t2 * 0.3205988979753252f))));
    return x >= std::numeric_limits<float>::min() ? float(e) + series : -std::numeric_limits<float>::infinity();
}

// 2^x; 0 below −126.5 (−∞ included), x clamped at 127 above.
inline float VdpFastExp2(float x) {
    // Clamped to [−127, 127]: n = −127 gives the scale's exponent field 0, the float 0.
    const float c = std::min(std::max(x, -127.0f), 127.0f);
    // Round to nearest by the float's own rounding: adding 1.5·2²³ leaves no fraction bits.
    constexpr float kRound = 12582912.0f;
    const float n = (c + kRound) - kRound;
    const float f = c - n;  // in [−½, ½]
    // 2^f = e^(f ln 2): Taylor series to degree 7 (remainder < 6e-9 on [−½, ½]).
    const float p = 1.0f + f * (0.6931471805599453f +
                         f * (0.2402265069591007f +
                              f * (0.05550410866482158f +
                                   f * (0.009618129107628477f +
                                        f * (0.0013333558146428443f +
                                             f * (0.00015403530393381608f + f * 1.525273380405984e-05f))))));
    const float scale = std::bit_cast<float>(uint32_t(int32_t(n) + 127) << 23);
    return p * scale;
}

}  // namespace fovrt
