// The live views (src/live/views.h): each view has the eye's size and the range it promises,
// false colour maps the ends of its range to the ramp's ends, "error" exists only with a
// reference (zero error is the ramp's dark end), "vdp" (FovVideoVDP's map) is zero for a frame
// against itself and weighs noise at the gaze above the same noise far from it, and a denoiser's
// debug views are offered.
#include <catch2/catch.hpp>

#include <algorithm>

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
        CHECK(built == (name != "error" && name != "vdp"));
        if (!built) continue;
        CHECK(view.rgb.width() == w);
        CHECK(view.rgb.height() == h);
        CHECK(view.hdr == (name == "denoised" || name == "noisy"));
    }
    ViewImage sppView;
    REQUIRE(BuildView("spp", sources, sppView));
    CHECK(sppView.rgb(3, 2) == FalseColour(16.0f, 1.0f, 16.0f));
    CHECK(sppView.rgb(0, 0) == FalseColour(1.0f, 1.0f, 16.0f));
    spp(3, 2) = 40;  // a raised foveation.spp_cap: the scale reaches the map's largest
    REQUIRE(BuildView("spp", sources, sppView));
    CHECK(sppView.rgb(3, 2) == FalseColour(40.0f, 1.0f, 40.0f));
    CHECK(sppView.rgb(0, 0) == FalseColour(1.0f, 1.0f, 40.0f));
    CHECK(sppView.legend == "spp map: 1 (dark) .. 40 (yellow)");
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

namespace {

// The metric's display for the view tests: 12 pixels per degree, 100 cd/m² white.
VdpViewStream TestVdpStream() {
    VdpExperimentDisplay display;
    display.name = "test";
    display.geometry = VdpGeometry::FromPixelsPerDegree(12.0);
    display.photometry.eotf = VdpEotf::Linear;
    return VdpViewStream(display, 0.0f, 30.0);
}

// Grey 0.25 with uniform noise of amplitude 0.1 in the 16×16 square centred on `centre`.
Plane<vec3> NoisePatch(int w, int h, vec2 centre) {
    Plane<vec3> image(w, h, vec3(0.25f));
    uint32_t state = 7;
    for (int y = int(centre.y) - 8; y < int(centre.y) + 8; ++y)
        for (int x = int(centre.x) - 8; x < int(centre.x) + 8; ++x) {
            state = state * 1664525u + 1013904223u;
            image(x, y) += vec3(0.1f * (float(state >> 8) / float(1u << 24) - 0.5f));
        }
    return image;
}

double SumOver(const Plane<float>& map, vec2 centre) {
    double sum = 0.0;
    for (int y = int(centre.y) - 8; y < int(centre.y) + 8; ++y)
        for (int x = int(centre.x) - 8; x < int(centre.x) + 8; ++x) sum += map(x, y);
    return sum;
}

}  // namespace

TEST_CASE("vdp view: needs a reference and a stream; a frame against itself is all zero", "[live][vdp]") {
    const int w = 64, h = 48;
    const FrameInputs in = Inputs(w, h);
    Plane<uint16_t> spp(w, h, 1);
    const Plane<vec3> denoised = NoisePatch(w, h, vec2(32, 24));
    VdpViewStream vdp = TestVdpStream();
    ViewSources sources{&in, &spp, &denoised, nullptr, nullptr, &vdp, vec2(32, 24)};
    ViewImage view;
    CHECK_FALSE(BuildView("vdp", sources, view));  // no reference
    sources.reference = &denoised;
    sources.vdp = nullptr;
    CHECK_FALSE(BuildView("vdp", sources, view));  // no stream
    sources.vdp = &vdp;
    for (int frame = 0; frame < 3; ++frame) {
        REQUIRE(BuildView("vdp", sources, view));
        CHECK_FALSE(view.hdr);
        REQUIRE(view.rgb.width() == w);
        const vec3 zero = FalseColour(kVdpViewLog10Min, kVdpViewLog10Min, kVdpViewLog10Max);
        size_t other = 0;
        for (size_t i = 0; i < view.rgb.size(); ++i) other += view.rgb[i] == zero ? 0 : 1;
        CHECK(other == 0);
    }
    const Plane<float> map = VdpViewMap(vdp, denoised, denoised, vec2(32, 24));
    CHECK(std::all_of(map.vector().begin(), map.vector().end(), [](float v) { return v == 0.0f; }));
}

TEST_CASE("vdp view: the same noise shows more difference at the gaze than far from it", "[live][vdp]") {
    const int w = 160, h = 64;
    const vec2 patch(24, 32), far(136, 32);  // 112 px apart: 9.3° at 12 px/deg
    const Plane<vec3> reference(w, h, vec3(0.25f));
    const Plane<vec3> noisy = NoisePatch(w, h, patch);
    VdpViewStream atPatch = TestVdpStream(), away = TestVdpStream();
    Plane<float> fixated, peripheral;
    for (int frame = 0; frame < 4; ++frame) {  // the temporal channels across frames
        fixated = VdpViewMap(atPatch, noisy, reference, patch);
        peripheral = VdpViewMap(away, noisy, reference, far);
    }
    const double foveal = SumOver(fixated, patch), eccentric = SumOver(peripheral, patch);
    INFO("JOD loss summed over the patch: fixated " << foveal << ", 9.3 deg away " << eccentric);
    CHECK(eccentric > 0.0);
    CHECK(foveal > 1.5 * eccentric);
    // Outside the patch (and its pyramid's reach) nothing differs.
    CHECK(fixated(w - 4, 4) == Approx(0.0f).margin(1e-6));
}
