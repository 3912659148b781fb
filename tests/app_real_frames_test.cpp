// Every denoiser on real rendered frames (built-in Cornell box with Lissajous-foveated spp):
// the Vulkan output must match the plain C++ reference frame after frame, and no output may
// contain NaN/Inf. Random-input tests live in tests/denoise_*; this one catches what only real
// frames contain (background pixels with infinite depth, real motion, foveated sample counts,
// A-SVGF gradient samples from the renderer).
#include <algorithm>
#include <cmath>

#include "config/config.h"
#include "denoise/denoiser_factory.h"
#include "denoise/variants.h"
#include "pipeline/frame_pipeline.h"
#include "test_support.h"
#include "vk/context.h"
#include "denoiser_match_support.h"

using namespace fovrt;

namespace {

RunConfig SmallCornell() {
    RunConfig config = DefaultConfig();
    config.scene.name = "cornell";
    config.camera.width = 72;  // not a multiple of the workgroup size on purpose
    config.camera.height = 44;
    config.foveation.radiusPx = 60.0f;  // 60 px at 320 wide -> a 13.5 px foveal disc at 72 px
    config.foveation.radiusReferenceWidth = 320;
    config.denoise.denoisers = {"asvgf"};  // makes the renderer emit gradient samples
    return config;
}

}  // namespace

TEST_CASE("vulkan denoisers match the C++ reference on real rendered frames", "[vulkan]") {
    if (!VulkanContext::Available()) FOVRT_SKIP("no Vulkan device; GPU-vs-reference check not run");
    const std::vector<StereoFrame> frames = test::RenderFourFrames(SmallCornell());
    const std::vector<const FrameInputs*> leftEye = test::LeftEyeInputs(frames);
    for (const std::string& name : DenoiserNames())
        DYNAMIC_SECTION(name) { test::CheckVulkanMatchesReference(name, leftEye); }
    CHECK(test::TestContext()->validationErrors() == 0);
}

TEST_CASE("reference denoisers keep real frames finite and close to the noisy mean", "[app]") {
    RunConfig config = SmallCornell();
    FramePipeline pipeline(config);
    StereoFrame frame;
    for (const std::string& name : DenoiserNames()) {
        auto denoiser = CreateDenoiser(name, "cpu", ParamsForDenoiser(name, DenoiserParams{}));
        Plane<vec3> out;
        double noisySum = 0.0, outSum = 0.0;
        for (int f = 0; f < 3; ++f) {
            pipeline.Render(uint32_t(f), frame);
            denoiser->Denoise(frame.eyes[0].inputs, out);
        }
        const FrameInputs& in = frame.eyes[0].inputs;
        for (int y = 0; y < in.height(); ++y)
            for (int x = 0; x < in.width(); ++x) {
                REQUIRE(IsFinite(out(x, y)));
                noisySum += Luminance(in.NoisyColor(x, y));
                outSum += Luminance(out(x, y));
            }
        INFO(name << ": mean luminance noisy " << noisySum << " denoised " << outSum);
        // A filter redistributes energy; it must not lose or invent much of it. The RAE is a
        // regression, not a filter: the committed quarter-width networks (L1 in γ = 0.2 space,
        // which pulls towards the median, fine-tuned for temporal stability) come out 10 % darker
        // here (rae and rae-spp; the step-1400 weights 6 % darker and 2 % brighter), and darker
        // on larger views (training/README.md); 30 % still catches a broken network or feature.
        const bool network = FindDenoiserVariant(name).family == DenoiserFamily::Rae;
        CHECK(outSum == Approx(noisySum).epsilon(network ? 0.30 : 0.15));
    }
}
