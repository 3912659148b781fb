// The bench's à-trous floor probe (denoise/bench/atrous_probe.h): its unit-weight mode must be the plain
// à-trous kernel — Σ h c / Σ h and Σ h² Var / (Σ h)² over the taps inside the image and off the
// background, background pixels passed through — so that the "every weight 1" timing it reports
// is the same dispatch minus the weight arithmetic; and the full mode must be a different one.
#include <cmath>

#include "denoise/bench/atrous_probe.h"
#include "test_support.h"
#include "vk_test_support.h"

using namespace fovrt;

namespace {
const float kH[5] = {1.0f / 16, 1.0f / 4, 3.0f / 8, 1.0f / 4, 1.0f / 16};

vec4 PlainAtrous(const AtrousProbeImage& im, const std::vector<vec4>& illum, int x, int y, int step) {
    const size_t i = size_t(y) * size_t(im.width) + size_t(x);
    if (im.guide[i].w < 0.0f) return illum[i];
    vec3 sumC(0.0f);
    float sumV = 0.0f, sumW = 0.0f;
    for (int ky = -2; ky <= 2; ++ky)
        for (int kx = -2; kx <= 2; ++kx) {
            const int qx = x + kx * step, qy = y + ky * step;
            if (qx < 0 || qy < 0 || qx >= im.width || qy >= im.height) continue;
            const size_t j = size_t(qy) * size_t(im.width) + size_t(qx);
            if (im.guide[j].w < 0.0f) continue;
            const float h = kH[kx + 2] * kH[ky + 2];
            sumC += h * vec3(illum[j]);
            sumV += h * h * illum[j].w;
            sumW += h;
        }
    return vec4(sumC / sumW, sumV / (sumW * sumW));
}
}  // namespace

TEST_CASE("a-trous floor probe: unit weights are the plain a-trous kernel", "[vulkan][svgf]") {
    if (!VulkanContext::Available()) FOVRT_SKIP("no Vulkan device");
    VulkanContext& c = *test::TestContext();
    // Odd size: 2×2 blocks with partners outside the image at the right and bottom edges.
    const AtrousProbeImage im = MakeAtrousProbeImage(67, 45, 3);
    for (int step : {2, 4}) {
        AtrousProbe probe(c, im, step);
        const AtrousProbeRun unit = probe.Run(true);
        const AtrousProbeRun full = probe.Run(false);
        double maxErr = 0.0, maxFullDiff = 0.0;
        for (int y = 0; y < im.height; ++y)
            for (int x = 0; x < im.width; ++x) {
                const size_t i = size_t(y) * size_t(im.width) + size_t(x);
                for (int ch = 0; ch < 2; ++ch) {
                    const std::vector<vec4>& in = ch ? im.illum1 : im.illum0;
                    const vec4 got = (ch ? unit.out1 : unit.out0)[i];
                    const vec4 want = PlainAtrous(im, in, x, y, step);
                    const vec4 fullGot = (ch ? full.out1 : full.out0)[i];
                    for (int k = 0; k < 4; ++k) {
                        maxErr = std::max(maxErr, double(std::abs(got[k] - want[k]) / (1.0f + std::abs(want[k]))));
                        maxFullDiff = std::max(maxFullDiff, double(std::abs(fullGot[k] - got[k])));
                    }
                }
            }
        INFO("step " << step << ": unit weights vs plain kernel max rel error " << maxErr
                     << ", full vs unit max difference " << maxFullDiff);
        CHECK(maxErr < 1e-5);
        CHECK(maxFullDiff > 0.05);  // the edge-stopping weights change the result
        CHECK(std::isfinite(unit.ms));
    }
    const AtrousFloor f = MeasureAtrousFloor(c, 64, 32, 1);
    CHECK(f.bytesPerPixel == 88.0);  // illumination in + out for two channels, guide, depth gradient
    CHECK(f.fullMs > 0.0);
    CHECK(f.unitWeightsMs > 0.0);
    CHECK(c.allocator().LiveBytes() == 0);
    CHECK(c.validationErrors() == 0);
}
