// The row forms FovVideoVDP's per-pixel loops run (src/metrics/vdp_fastmath.h, the CSF table's
// LocateRow/Log2Sensitivity, VdpLog2MaskedDifferenceRow) against the scalar forms they replace:
// libm's exp2/log2, VdpCsfTable::Sensitivity and VdpLog2MaskedDifference.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "metrics/vdp_csf.h"
#include "metrics/vdp_fastmath.h"
#include "metrics/vdp_masking.h"
#include "metrics/vdp_params.h"

using namespace fovrt;

TEST_CASE("VdpFastLog2 is within 2e-7 of log2 (relative beyond ±1) on normal floats, -inf below", "[vdp]") {
    double worst = 0.0;
    // Every octave of the normal range, at mantissas from a fixed-seed generator and at the
    // octave's edges and its √2 split.
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> mantissa(1.0f, 2.0f);
    for (int e = -126; e <= 127; ++e) {
        std::vector<float> ms = {1.0f, std::nextafter(2.0f, 1.0f), float(std::sqrt(2.0)),
                                 std::nextafter(float(std::sqrt(2.0)), 1.0f)};
        for (int i = 0; i < 200; ++i) ms.push_back(mantissa(rng));
        for (float m : ms) {
            const float x = std::ldexp(m, e);
            const double exact = std::log2(double(x));
            worst = std::max(worst, std::abs(double(VdpFastLog2(x)) - exact) / std::max(1.0, std::abs(exact)));
        }
    }
    INFO("worst error " << worst);
    CHECK(worst < 2e-7);
    CHECK(VdpFastLog2(1.0f) == 0.0f);
    CHECK(VdpFastLog2(8.0f) == 3.0f);
    for (float x : {0.0f, -0.0f, std::numeric_limits<float>::denorm_min(), -1.0f})
        CHECK(VdpFastLog2(x) == -std::numeric_limits<float>::infinity());
}

TEST_CASE("VdpFastExp2 is within 3e-7 relative of exp2 on [-126, 127] and 0 far below", "[vdp]") {
    double worst = 0.0;
    for (int i = 0; i <= 253 * 512; ++i) {
        const float x = -126.0f + float(i) / 512.0f + 0.37f / 512.0f;
        if (x > 127.0f) break;
        const double exact = std::exp2(double(x));
        worst = std::max(worst, std::abs(double(VdpFastExp2(x)) - exact) / exact);
    }
    INFO("worst relative error " << worst);
    CHECK(worst < 3e-7);
    CHECK(VdpFastExp2(0.0f) == 1.0f);
    CHECK(VdpFastExp2(10.0f) == 1024.0f);
    CHECK(VdpFastExp2(-127.0f) == 0.0f);
    CHECK(VdpFastExp2(-1000.0f) == 0.0f);
    CHECK(VdpFastExp2(-std::numeric_limits<float>::infinity()) == 0.0f);
}

TEST_CASE("the CSF table's row lookup gives the scalar lookup's sensitivity in and beyond the table", "[vdp]") {
    const VdpCsfTable table(5.0, -1.5, 0.604562);
    // Values inside the axes, at their ends, on nodes and outside (clamped to the table).
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::vector<float> rho, lum, ecc;
    for (int i = 0; i < 3000; ++i) {
        rho.push_back(std::exp2(-5.0f + 12.0f * u(rng)));
        lum.push_back(std::pow(10.0f, -4.0f + 9.0f * u(rng)));
        ecc.push_back(130.0f * u(rng) * u(rng));
    }
    for (float r : {0.0625f, 64.0f, 1.0f, 0.01f}) rho.push_back(r), lum.push_back(0.001f), ecc.push_back(0.0f);
    for (float l : {0.001f, 1e4f, 1.0f, 1e5f}) rho.push_back(4.0f), lum.push_back(l), ecc.push_back(120.0f);
    const size_t n = rho.size();
    VdpCsfAxisRow rhoRow, lumRow, eccRow;
    table.LocateRow(VdpCsfTable::AxisName::Rho, rho.data(), n, rhoRow);
    table.LocateRow(VdpCsfTable::AxisName::Luminance, lum.data(), n, lumRow);
    table.LocateRow(VdpCsfTable::AxisName::Eccentricity, ecc.data(), n, eccRow);
    std::vector<float> log2S(n);
    table.Log2Sensitivity(rhoRow, lumRow, eccRow, n, log2S.data());
    double worst = 0.0;
    for (size_t i = 0; i < n; ++i)
        worst = std::max(worst,
                         std::abs(double(log2S[i]) - std::log2(double(table.Sensitivity(rho[i], lum[i], ecc[i])))));
    // The row form reads the axes as exactly uniform grids; the float grid's rounding moves the
    // fraction by ~1e-6, which the steepest cells (high ρ, sensitivity near the 1e-4 floor) turn
    // into 2e-5 in log2 S.
    INFO("worst log2 difference " << worst);
    CHECK(worst < 3e-5);

    // The slice form (one ρ and e per band, the non-foveated metric).
    const VdpCsfTable::LuminanceSlice slice = table.Slice(3.3f, 0.0f);
    table.Log2Sensitivity(slice, lumRow, n, log2S.data());
    worst = 0.0;
    for (size_t i = 0; i < n; ++i)
        worst = std::max(worst, std::abs(double(log2S[i]) - std::log2(double(table.Sensitivity(slice, lum[i])))));
    INFO("worst log2 difference, slice " << worst);
    CHECK(worst < 1e-5);
}

TEST_CASE("the masking row gives log2 D to 2e-5, -inf where T = R, and no overflow under strong masking", "[vdp]") {
    const VdpParams prm;
    const float p = float(prm.maskP), log2Gain = float(prm.maskC * std::log2(10.0));
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    std::vector<float> t, r, s;
    for (int i = 0; i < 4000; ++i) {
        t.push_back(2.0f * u(rng));
        r.push_back(i % 7 == 0 ? t.back() : 2.0f * u(rng));
        s.push_back(std::exp2(2.0f + 11.0f * (u(rng) + 1.0f) / 2.0f));
    }
    // Contrasts at the pyramid's clamp (2·1000) with a sensitivity that makes q·log2 M exceed 128,
    // where 2^(q·log2 M) overflows a float.
    t.push_back(2000.0f), r.push_back(1999.0f), s.push_back(524288.0f);
    const size_t n = t.size();
    std::vector<float> log2S(n), log2D(n);
    for (size_t i = 0; i < n; ++i) log2S[i] = std::log2(s[i]);
    for (float q : {float(prm.maskQSustained), float(prm.maskQTransient)}) {
        VdpLog2MaskedDifferenceRow(t.data(), r.data(), log2S.data(), n, p, q, log2Gain, log2D.data());
        double worst = 0.0;
        for (size_t i = 0; i < n; ++i) {
            if (t[i] == r[i]) {
                CHECK(log2D[i] == -std::numeric_limits<float>::infinity());
                continue;
            }
            // D = min(|T−R|^p / (1 + M^q), 10⁴) in double, log2(1 + 2^y) without overflow.
            const double y = q * (double(log2Gain) + std::log2(std::min(std::abs(double(t[i])), std::abs(double(r[i])))) +
                                  double(log2S[i]));
            const double expected = std::min(p * std::log2(std::abs(double(t[i]) - double(r[i])) * double(s[i])) -
                                                 (std::max(y, 0.0) + std::log2(1.0 + std::exp2(-std::abs(y)))),
                                             std::log2(1e4));
            worst = std::max(worst, std::abs(double(log2D[i]) - expected));
            if (std::isfinite(VdpLog2MaskedDifference(t[i], r[i], s[i], p, q, log2Gain)))
                CHECK(std::abs(log2D[i] - VdpLog2MaskedDifference(t[i], r[i], s[i], p, q, log2Gain)) < 2e-5f);
        }
        INFO("q " << q << ": worst log2 difference " << worst);
        CHECK(worst < 2e-5);
    }
}
