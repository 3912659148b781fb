// The settings each denoiser reads (VariantSettings, declared per family and mechanism in
// denoise/variants.cpp; printed by `fovrt info --denoiser`, listed in docs/denoisers.md) are the
// ones that change its output: every composition of the SVGF and two-history families runs two
// short sequences on the C++ reference with its defaults, then once per setting with that setting
// moved to another value of its range. The sequences: random frames (every pixel changes: A-SVGF's
// gradient saturates, its anti-lag engages), a static noisy view with moving sample counts (small
// gradients: SVGF's alpha and the firefly clamp engage), and the same with moderate A-SVGF
// gradients (the stabilisation's change threshold engages on lambda). A listed setting must change the output somewhere; an
// unlisted one must leave it bit for bit. So a list cannot claim a setting the passes ignore, nor
// miss one they read.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstring>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "denoise/denoiser_factory.h"
#include "denoise/gradient_strata.h"
#include "denoise/variants.h"
#include "denoise_svgf_scenes.h"
#include "denoise_two_history_scene.h"

using namespace fovrt;

namespace {

// The value each numeric setting is moved to: far enough from its default to matter on 32×32
// random frames (in its range; a new setting without a row here fails the test).
const std::map<std::string, double> kMovedTo = {
    {"denoise.svgf.alpha_color", 0.6},
    {"denoise.svgf.alpha_moments", 0.6},
    {"denoise.svgf.atrous_iterations", 2},
    {"denoise.svgf.feedback_iteration", 0},
    {"denoise.svgf.sigma_depth", 0.05},
    {"denoise.svgf.sigma_normal", 4},
    {"denoise.svgf.sigma_luminance", 0.5},
    {"denoise.svgf.variance_history_threshold", 1},
    {"denoise.svgf.filter_combined", 1},
    {"denoise.asvgf.alpha", 0.5},
    {"denoise.asvgf.gradient_iterations", 1},
    {"denoise.asvgf.antilag_gain", 8},
    {"denoise.asvgf.antilag_power", 1},
    {"denoise.two_history.gradient_beta", 0.2},
    {"denoise.two_history.q_scale", 20},
    {"denoise.two_history.firefly_sigma", 0},
    {"denoise.two_history.clamp_sigma", 0.01},
    {"denoise.two_history.choice_rate", 1},
    {"denoise.two_history.choice_band", 0},
    {"denoise.two_history.window", 0.5},
    {"denoise.two_history_stable.alpha", 0.9},
    {"denoise.two_history_stable.sigma_scale", 0.1},
    {"denoise.two_history_stable.antilag_q", 0.95},
};

DenoiserParams WithSetting(const std::string& key, double value) {
    DenoiserParams params;
    bool found = false;
    ForEachDenoiserParam(params, [&](const ParamInfo& info, auto& field) {
        if (key != info.key) return;
        using T = std::decay_t<decltype(field)>;
        if constexpr (std::is_same_v<T, bool>) field = value != 0.0;
        else field = T(value);
        found = true;
    });
    REQUIRE(found);
    return params;
}

// The outputs of three sequences, a camera cut before each: five random 32×32 frames (sample
// counts, gradient samples, motion); six frames of a static noisy view whose pattern's contrast
// rises by a tenth a frame and whose 4-spp columns move; the same with A-SVGF gradient samples that
// triple every other stratum's shading (lambda 2/3 there). The gaze in the top-left quarter, where
// a window of half each side sits.
std::vector<Plane<vec3>> Outputs(const std::string& name, const DenoiserParams& params) {
    std::unique_ptr<Denoiser> denoiser = CreateDenoiser(name, "cpu", params);
    std::vector<Plane<vec3>> out(17);
    std::mt19937 rng(5);
    for (uint32_t frame = 0; frame < out.size(); ++frame) {
        FrameInputs f;
        if (frame < 5) {
            f = test::RandomTwoHistoryFrame(32, 32, frame);
        } else {
            const int t = (int(frame) - 5) % 6;
            const bool gradients = frame >= 11;
            test::NoisyFrame(f, 32, 32, uint32_t(t), 1.0f, [&](int x, int) { return (x / 4 + t) % 3 == 0 ? 4 : 1; },
                             rng, 1.0f + 0.1f * float(t));
            f.cameraCut = t == 0;
            const ivec2 grid = StratumGridSize(32, 32);
            for (int sy = 0; sy < grid.y && gradients && t > 0; ++sy)
                for (int sx = 0; sx < grid.x; ++sx) {
                    const ivec2 p(sx * kGradientStratumSize, sy * kGradientStratumSize);
                    f.gradientSamples.push_back({ivec2(sx, sy), p, p, (sx + sy + t) % 2 ? 3.0f : 1.0f, 1.0f});
                }
        }
        f.gazePixel = vec2(8.0f, 9.0f);
        denoiser->Denoise(f, out[frame]);
    }
    return out;
}

bool Same(const std::vector<Plane<vec3>>& a, const std::vector<Plane<vec3>>& b) {
    for (size_t i = 0; i < a.size(); ++i)
        if (a[i].bytes() != b[i].bytes() || std::memcmp(a[i].data(), b[i].data(), a[i].bytes()) != 0) return false;
    return true;
}

}  // namespace

TEST_CASE("a denoiser's settings are exactly those that change its output", "[denoise][variants]") {
    std::vector<std::string> numeric;
    for (const std::string& key : DenoiserSettingKeys())
        if (key.rfind("denoise.rae.", 0) != 0) numeric.push_back(key);
    for (const std::string& key : numeric) {
        INFO(key);
        REQUIRE(kMovedTo.count(key) == 1);
    }
    size_t compositions = 0;
    for (const std::string& name : DenoiserCompositions()) {
        const DenoiserVariant& variant = FindDenoiserVariant(name);
        if (variant.family == DenoiserFamily::Rae) continue;
        ++compositions;
        const std::vector<std::string> reads = VariantSettings(variant);
        const std::vector<Plane<vec3>> base = Outputs(name, DenoiserParams{});
        for (const std::string& key : numeric) {
            const bool listed = std::find(reads.begin(), reads.end(), key) != reads.end();
            const bool changed = !Same(Outputs(name, WithSetting(key, kMovedTo.at(key))), base);
            INFO(name << ": " << key << (listed ? " is listed but leaves the output as it was"
                                                : " is not listed but changes the output"));
            CHECK(changed == listed);
        }
    }
    CHECK(compositions > 50);
}

// stabilize-antilag's change weight never exceeds what the stabilisation takes already where A-SVGF's
// lambda is q (MechanismRules): with asvgf a composition's output is the one without it, bit for bit.
TEST_CASE("stabilize-antilag changes nothing with asvgf", "[denoise][variants]") {
    size_t compared = 0;
    for (const std::string& name : DenoiserCompositions()) {
        const std::string with = "+stabilize-antilag";
        if (name.find("+asvgf") == std::string::npos || name.find(with) == std::string::npos) continue;
        std::string without = name;
        without.erase(without.find(with), with.size());
        INFO(name << " against " << without);
        CHECK(Same(Outputs(name, DenoiserParams{}), Outputs(without, DenoiserParams{})));
        ++compared;
    }
    CHECK(compared >= 8);
    // Without A-SVGF's gradient it does change the output (and reads antilag_q).
    CHECK(!Same(Outputs("two-history+stabilize+stabilize-antilag", DenoiserParams{}),
                Outputs("two-history+stabilize", DenoiserParams{})));
}

TEST_CASE("the RAE reads its weights: rae+spp the sample-count network's", "[denoise][variants]") {
    auto reads = [](const char* name) { return VariantSettings(FindDenoiserVariant(name)); };
    CHECK(reads("rae") == std::vector<std::string>{"denoise.rae.weights"});
    CHECK(reads("rae-spp") == std::vector<std::string>{"denoise.rae.weights_spp"});
}
