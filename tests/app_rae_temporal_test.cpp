// Issue #14's temporal-stability claim for the committed RAE weights (training/weights/): with the
// recurrent state carried from frame to frame, the temporal error (mean |lum_t − lum_{t−1}| of the
// denoised eye, frames 2..15: the metric of fovrt's experiments) is lower than with the same
// network's state reset before every frame. Static views, where the reference does not change and
// every difference between frames is flicker, at 96×64 per eye over 16 frames: cornell (a training
// scene) with uniform 1 spp and with the foveated disc, and veach-ajar (held out of training, the
// thesis scene) with the foveated disc. Deterministic (seeded tracer, the C++ reference network).
// The claim does not hold everywhere for `rae` (box, suzanne: training/README.md); tests/tools/
// rae_temporal_probe measures any scene, size, length and weight file, per frame. The cases after
// the first hold the output's mean colour to the reference's.
#include <catch2/catch.hpp>

#include <cmath>
#include <tuple>

#include "rae_temporal.h"
#include "test_support.h"

using namespace fovrt;

namespace {
// The state must lower the temporal error by at least 5 %, not by a rounding error.
constexpr double kMargin = 0.95;
// The least share of each channel's light the networks keep on veach-ajar (held out).
constexpr float kHeldOutEnergyFloor = 0.22f;
}  // namespace

TEST_CASE("rae: the recurrent state lowers the temporal error against resetting it every frame", "[app][rae]") {
    const std::string variant = GENERATE(as<std::string>{}, "rae", "rae-spp");
    const auto [scene, foveated] = GENERATE(table<std::string, bool>({{"cornell", false},
                                                                      {"cornell", true},
                                                                      {"veach-ajar", true}}));
    if (scene == "veach-ajar") FOVRT_REQUIRE_SHARED_SCENES();
    test::RaeTemporalSetup setup;
    setup.scene = scene;
    setup.foveated = foveated;
    setup.frames = 16;
    const double carried = test::RaeTemporalError(setup, variant, false).Mean();
    const double reset = test::RaeTemporalError(setup, variant, true).Mean();
    INFO(variant << " on " << scene << (foveated ? " (foveated disc)" : " (uniform 1 spp)")
                 << ": temporal error with state " << carried << ", reset every frame " << reset << ", ratio "
                 << carried / reset);
    CHECK(carried < kMargin * reset);
}

// The mean colour of the denoised frames against the reference's, per channel, over frames 2..15
// with the state carried: a denoiser that keeps the noisy input's energy and hue scores near 1.
// svgf, which redistributes energy without creating or losing much of it, is the control that
// the measure is sound (cornell 0.99; veach-ajar 0.84: at 1 spp a few bright paths carry most of
// that scene's light, and 16 frames at 96×64 do not average them out).
namespace {
vec3 MeanColourRatio(const std::string& scene, bool foveated, const std::string& variant) {
    test::RaeTemporalSetup setup;
    setup.scene = scene;
    setup.foveated = foveated;
    setup.frames = 16;
    const vec3 reference = test::RaeTemporalSeries::MeanOverFrames(test::RaeReferenceMeanColour(setup, 64));
    return test::RaeTemporalError(setup, variant, false).MeanColour() / reference;
}
}  // namespace

TEST_CASE("rae: the mean-colour measure holds svgf to the reference", "[app][rae]") {
    const auto [scene, foveated, tolerance] =
        GENERATE(table<std::string, bool, float>({{"cornell", false, 0.03f}, {"veach-ajar", true, 0.20f}}));
    if (scene == "veach-ajar") FOVRT_REQUIRE_SHARED_SCENES();
    const vec3 ratio = MeanColourRatio(scene, foveated, "svgf");
    INFO("svgf on " << scene << ": mean colour / the reference's: R " << ratio.x << " G " << ratio.y << " B "
                    << ratio.z);
    for (int c = 0; c < 3; ++c) CHECK(std::abs(ratio[c] - 1.0f) < tolerance);
}

// Held out and lit through a door, veach-ajar's 1-spp input is 95 % black. The weights trained
// on four directly lit scenes kept 12-35 % of each channel there (rae 0.12-0.15, rae-spp
// 0.15-0.35); those trained with the procedural rooms too, half of them lit the same way, keep
// rae 0.26-0.29 and rae-spp 0.41-0.63 (training/README.md). Still far from 1: a floor, not a goal.
TEST_CASE("rae: the output keeps veach-ajar's light", "[app][rae]") {
    FOVRT_REQUIRE_SHARED_SCENES();
    const std::string variant = GENERATE(as<std::string>{}, "rae", "rae-spp");
    const vec3 ratio = MeanColourRatio("veach-ajar", true, variant);
    INFO(variant << " on veach-ajar: mean colour / the reference's: R " << ratio.x << " G " << ratio.y << " B "
                 << ratio.z);
    for (int c = 0; c < 3; ++c) CHECK(ratio[c] > kHeldOutEnergyFloor);
}

// Cornell's hue: its light is orange (Ke 17, 12, 4) and the networks pull the illumination
// towards grey (R 0.71-0.80, B up to 1.5 of the reference's), which made the experiments' frames
// grey and their relMSE 27 times svgf's. Not fixed in the networks: this case is expected to fail
// (Catch's [!shouldfail]), and turns red the day the weights meet the bound, so that it becomes a
// plain check. The `balance` mechanism restores the hue around the same networks (the last case).
TEST_CASE("rae: the output keeps cornell's hue (known to fail)", "[app][rae][!shouldfail]") {
    const std::string variant = GENERATE(as<std::string>{}, "rae", "rae-spp");
    const vec3 ratio = MeanColourRatio("cornell", false, variant);
    INFO(variant << " on cornell: mean colour / the reference's: R " << ratio.x << " G " << ratio.y << " B "
                 << ratio.z);
    for (int c = 0; c < 3; ++c) CHECK(std::abs(ratio[c] - 1.0f) < 0.10f);
}

// The `balance` mechanism (RaeBalanceGains) runs the same networks on illumination balanced to grey
// by per-channel gains from the frame's mean and divides their output by the gains again, so
// cornell's orange cast passes through them: the hue (each channel's ratio over the mean of the
// three) within 10 % of the reference's. rae and rae-spp without it (the case above) fail this
// too: R 0.73 / B 1.44 and R 0.79 / G 1.13 of the mean, at the committed weights.
TEST_CASE("rae+balance: the output keeps cornell's hue", "[app][rae]") {
    const std::string variant = GENERATE(as<std::string>{}, "rae+balance", "rae+spp+balance");
    const vec3 ratio = MeanColourRatio("cornell", false, variant);
    const vec3 hue = ratio / ((ratio.x + ratio.y + ratio.z) / 3.0f);
    INFO(variant << " on cornell: mean colour / the reference's: R " << ratio.x << " G " << ratio.y << " B "
                 << ratio.z << "; over their mean: " << hue.x << " " << hue.y << " " << hue.z);
    for (int c = 0; c < 3; ++c) CHECK(std::abs(hue[c] - 1.0f) < 0.10f);
}
