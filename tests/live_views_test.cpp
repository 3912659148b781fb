// The live views (src/live/views.h): each view has the eye's size and the range it promises,
// false colour maps the ends of its range to the ramp's ends, "error" exists only with a
// reference (zero error is the ramp's dark end), and a denoiser's debug views are offered.
#include <catch2/catch.hpp>

#include "denoise/denoiser_factory.h"
#include "live/views.h"

using namespace fovrt;

namespace {

FrameInputs Inputs(int w, int h) {
    FrameInputs in;
    in.Allocate(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            in.direct(x, y) = vec3(0.5f);
            in.albedo(x, y) = vec3(0.8f, 0.4f, 0.2f);
            in.normal(x, y) = vec3(0, 0, 1);
            in.linearDepth(x, y) = 1.0f + float(x);
            in.objectId(x, y) = 0;
            in.prevPixel(x, y) = vec2(x + 0.5f, y + 0.5f);
        }
    return in;
}

}  // namespace

TEST_CASE("false colour maps its range onto the ramp's ends; non-finite is black", "[live]") {
    const vec3 lo = FalseColour(0.0f, 0.0f, 1.0f), hi = FalseColour(1.0f, 0.0f, 1.0f);
    CHECK(lo == FalseColour(-5.0f, 0.0f, 1.0f));  // clamped
    CHECK(hi == FalseColour(9.0f, 0.0f, 1.0f));
    CHECK(hi.r + hi.g > lo.r + lo.g + 1.0f);      // dark blue -> yellow
    CHECK(FalseColour(std::nanf(""), 0.0f, 1.0f) == vec3(0.0f));
}

TEST_CASE("every base view has the eye's size; error needs a reference", "[live]") {
    const int w = 8, h = 4;
    const FrameInputs in = Inputs(w, h);
    Plane<uint16_t> spp(w, h, 1);
    spp(3, 2) = 16;
    const Plane<vec3> denoised(w, h, vec3(0.3f));
    ViewSources sources{&in, &spp, &denoised, nullptr, nullptr};
    for (const std::string& name : BaseViewNames()) {
        ViewImage view;
        const bool built = BuildView(name, sources, view);
        CHECK(built == (name != "error"));
        if (!built) continue;
        CHECK(view.rgb.width() == w);
        CHECK(view.rgb.height() == h);
        CHECK(view.hdr == (name == "denoised" || name == "noisy"));
    }
    ViewImage sppView;
    REQUIRE(BuildView("spp", sources, sppView));
    CHECK(sppView.rgb(3, 2) == FalseColour(16.0f, 1.0f, 16.0f));
    CHECK(sppView.rgb(0, 0) == FalseColour(1.0f, 1.0f, 16.0f));
    ViewImage noisy;
    REQUIRE(BuildView("noisy", sources, noisy));
    CHECK(noisy.rgb(0, 0).r == Approx(0.8f * 0.5f));

    const Plane<vec3> reference = denoised;
    sources.reference = &reference;
    ViewImage error;
    REQUIRE(BuildView("error", sources, error));
    CHECK(error.rgb(0, 0) == FalseColour(-4.0f, -4.0f, 0.0f));  // zero error: the dark end
    CHECK_FALSE(BuildView("no-such-view", sources, error));
}

TEST_CASE("a denoiser's debug views are views after its first frame", "[live]") {
    auto denoiser = CreateDenoiser("asvgf", "cpu", ParamsForDenoiser("asvgf", DenoiserParams{}));
    const std::vector<std::string> names = ViewNamesFor(*denoiser);
    REQUIRE(std::find(names.begin(), names.end(), "alpha") != names.end());
    const FrameInputs in = Inputs(8, 4);
    Plane<uint16_t> spp(8, 4, 1);
    Plane<vec3> out;
    ViewSources sources{&in, &spp, &out, nullptr, denoiser.get()};
    ViewImage view;
    CHECK_FALSE(BuildView("alpha", sources, view));  // nothing denoised yet
    denoiser->Denoise(in, out);
    REQUIRE(BuildView("alpha", sources, view));
    CHECK(view.rgb.width() == 8);
    CHECK_FALSE(view.hdr);
}
