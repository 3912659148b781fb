// The perceptual spp model with the metric's own contrast sensitivity (FovVideoVDP's CSF with its
// cortical magnification): the map falls monotonically with eccentricity on a headset-like eye,
// follows the CSF's ratio S(e) / S(0), and under a ray budget meets it; its content term reads the
// metric's masking and, in the frame pipeline, the previous frame's albedo.
#include <cmath>

#include "config/config.h"
#include "metrics/vdp_csf.h"
#include "metrics/vdp_params.h"
#include "pipeline/eye_sensitivity.h"
#include "pipeline/frame_pipeline.h"
#include "pipeline/metric_display.h"
#include "test_support.h"

using namespace fovrt;

TEST_CASE("The metric's CSF is what the perceptual model reads", "[foveation]") {
    const ContrastSensitivity s = MetricContrastSensitivity();
    const VdpParams params;
    for (double e : {0.0, 5.0, 30.0})
        CHECK(s(3.2, 50.0, e) == VdpCsfModel(3.2, 0.0, 50.0, e, params.csfSigma, params.kCm));
    // Cortical magnification: the same grating is harder to see off-axis.
    CHECK(s(3.2, 50.0, 20.0) < 0.5 * s(3.2, 50.0, 0.0));
}

TEST_CASE("Perceptual with the metric's CSF: falls monotonically with eccentricity, meets a budget",
          "[foveation]") {
    // 90° wide: 7.1 ppd, so the noise (half of Nyquist, 1.8 cpd) lies above the CSF's peak (about
    // 1 cpd) and S falls from the gaze on (below the peak the model holds it flat, see models.cpp).
    const int w = 640, h = 180;
    const EyeCamera cam(Pose(), Fov::FromHorizontal(Radians(90.0f), float(w) / h), w, h);
    FoveationParams p;
    p.model = "perceptual";
    p.sppMin = kMinSpp;
    auto model = CreateSppModel(p, MetricContrastSensitivity());
    Plane<float> density;
    model->GenerateDensity(cam, vec3(0, 0, -1), 0, density);
    const double rho = 0.5 * 0.5 * cam.PixelsPerDegree();
    const ContrastSensitivity s = MetricContrastSensitivity();
    float previous = 1e9f;
    for (int x = w / 2; x < w; ++x) {  // the centre row, outward
        REQUIRE(density(x, h / 2) <= previous);
        previous = density(x, h / 2);
        const vec3 ray = cam.EyeDirection(vec2(x + 0.5f, h / 2 + 0.5f));
        const double e = Degrees(std::acos(double(-ray.z)));
        const double expected = std::max(8.0 * s(rho, 50.0, e) / s(rho, 50.0, 0.0), double(kMinSpp));
        REQUIRE(density(x, h / 2) == Approx(expected).epsilon(1e-2));
    }
    CHECK(density(w / 2, h / 2) > 7.9f);
    CHECK(previous < 2.0f);  // 45° out

    p.sppFloor = kMinSpp;
    p.rayBudget = int64_t(w) * h / 2;  // 0.5 spp
    model = CreateSppModel(p, MetricContrastSensitivity());
    int64_t total = 0;
    Plane<uint16_t> spp;
    for (uint32_t t = 0; t < 16; ++t) {
        model->Generate(cam, vec3(0, 0, -1), t, spp);
        for (size_t i = 0; i < spp.size(); ++i) total += spp[i];
    }
    CHECK(std::abs(double(total) - 16.0 * double(p.rayBudget)) <= 0.01 * 16.0 * double(p.rayBudget));
}

TEST_CASE("The content term and the metric's pooling read the metric's constants", "[foveation]") {
    const ContrastMasking m = MetricContrastMasking();
    const VdpParams params;
    CHECK(m.sensitivityGain == Approx(std::pow(10.0, params.sensitivityCorrection / 20.0)));
    CHECK(m.k == Approx(std::pow(10.0, params.maskC)));
    CHECK(m.q == params.maskQSustained);
    CHECK(m.p == params.maskP);
    CHECK(m.beta == params.beta);
}

namespace {

// `scene` at 96×54 under the perceptual map at a budget of 1 spp, the periphery free to go below it.
RunConfig PerceptualAtOneSpp(const char* scene) {
    RunConfig config = DefaultConfig();
    config.scene.name = scene;
    config.camera.width = 96;
    config.camera.height = 54;
    config.denoise.device = "cpu";
    config.foveation.model = "perceptual";
    config.foveation.sppMin = kMinSpp;
    config.foveation.sppFloor = kMinSpp;
    config.foveation.rayBudget = 96 * 54;
    return config;
}

// Frame 0 has no previous frame: with the term, the map without it, on both eyes.
void CheckFirstFrameIsPlain(FramePipeline& term, FramePipeline& plain, StereoFrame& a, StereoFrame& b) {
    plain.Render(plain.RequestAt(0), a);
    term.Render(term.RequestAt(0), b);
    for (int eye = 0; eye < 2; ++eye) CHECK(a.eyes[size_t(eye)].sppMap.vector() == b.eyes[size_t(eye)].sppMap.vector());
}

// A term switched off for frame `frame` and on again (the live panel): what was held from before
// is not read, so frame + 1 is the map without the term, as `plain` renders it.
void CheckOffAndOnReadsNothingOld(FramePipeline& term, FramePipeline& plain, const FoveationParams& on,
                                  const FoveationParams& off, uint32_t frame) {
    StereoFrame a, b;
    term.SetFoveation(off);
    term.Render(term.RequestAt(frame), b);
    term.SetFoveation(on);
    term.Render(term.RequestAt(frame + 1), b);
    plain.Render(plain.RequestAt(frame), a);
    plain.Render(plain.RequestAt(frame + 1), a);
    CHECK(a.eyes[0].sppMap.vector() == b.eyes[0].sppMap.vector());
}

}  // namespace

TEST_CASE("Content masking in the frame pipeline: the previous frame's albedo moves rays off the texture",
          "[foveation]") {
    // The room's checker floor under the perceptual map at a budget of 1 spp: frame 0 has no
    // previous frame (flat, the map without the term); frame 1 reads frame 0's albedo.
    RunConfig config = PerceptualAtOneSpp("room");
    FramePipeline plain(config);
    config.foveation.contentMasking = true;
    FramePipeline masked(config);
    StereoFrame a, b;
    CheckFirstFrameIsPlain(masked, plain, a, b);

    Plane<float> albedo(96, 54);
    for (size_t i = 0; i < albedo.size(); ++i) albedo[i] = Luminance(b.eyes[0].inputs.albedo[i]);
    const Plane<float> contrast = LocalBandContrast(albedo, 0.25);
    plain.Render(plain.RequestAt(1), a);
    masked.Render(masked.RequestAt(1), b);
    // Over 1 frame the map's total is the budget's within the dither; the textured pixels (band
    // contrast above 5 %) get fewer rays than without the term, the rest more.
    uint64_t texturedPlain = 0, texturedMasked = 0, otherPlain = 0, otherMasked = 0;
    int textured = 0;
    for (size_t i = 0; i < contrast.size(); ++i) {
        const bool busy = contrast[i] > 0.05f;
        textured += busy;
        (busy ? texturedPlain : otherPlain) += a.eyes[0].sppMap[i];
        (busy ? texturedMasked : otherMasked) += b.eyes[0].sppMap[i];
    }
    INFO("textured pixels " << textured << ": " << texturedPlain << " -> " << texturedMasked << " rays; others "
                            << otherPlain << " -> " << otherMasked);
    REQUIRE(textured > 200);
    CHECK(texturedMasked < 0.8 * double(texturedPlain));
    CHECK(otherMasked > otherPlain);

    // Switched off for frame 2 and on again: the albedo held from before is not read.
    FoveationParams off = config.foveation;
    off.contentMasking = false;
    CheckOffAndOnReadsNothingOld(masked, plain, config.foveation, off, 2);
}

TEST_CASE("The noise term in the frame pipeline: the frames as the display shows them, the first frame flat",
          "[foveation]") {
    // Cornell at 1 spp under the perceptual map, shown a stop brighter than the radiance. Frame 0
    // has seen nothing: the map without the term. Frame 1's map is the model's with the noise of
    // frame 0 as the metric's display shows it (its luminance at the PNGs' exposure, clipped at
    // its black and white), texture and object edges not counted as noise.
    RunConfig config = PerceptualAtOneSpp("cornell");
    config.output.exposure = 1.0f;
    FramePipeline plain(config);
    config.foveation.noiseVisibility = true;
    FramePipeline noise(config);
    StereoFrame a, b;
    CheckFirstFrameIsPlain(noise, plain, a, b);

    VisibleNoiseEstimator expected;
    const FrameInputs& in = b.eyes[0].inputs;
    Plane<float> modulation(in.width(), in.height());
    for (size_t i = 0; i < modulation.size(); ++i) modulation[i] = Luminance(in.albedo[i]);
    const VdpPhotometry photometry = ExperimentVdpDisplay(config, in.camera).photometry;
    Plane<vec3> shown = in.NoisyImage();
    for (vec3& c : shown.vector()) c *= 2.0f;  // one stop
    expected.Add(VdpLuminance(shown, photometry), in.sampleCount, {&modulation, &in.objectId});
    REQUIRE(expected.Noise().Valid());

    const FrameRequest next = noise.RequestAt(1);
    noise.Render(next, b);
    plain.Render(plain.RequestAt(1), a);
    Plane<uint16_t> map;
    CreateSppModel(config.foveation, MetricContrastSensitivity(), MetricContrastMasking())
        ->Generate(next.eyes[0], b.eyes[0].gazeEye, 1, map, {nullptr, &expected.Noise()});
    CHECK(b.eyes[0].sppMap.vector() == map.vector());
    CHECK(b.eyes[0].sppMap.vector() != a.eyes[0].sppMap.vector());

    // Switched off for frame 2 and on again: the noise estimated before is not read.
    FoveationParams off = config.foveation;
    off.noiseVisibility = false;
    CheckOffAndOnReadsNothingOld(noise, plain, config.foveation, off, 2);
}
