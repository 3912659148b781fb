// The recurrent denoising autoencoder's C++ reference (denoise/reference/rae_net.h): each layer
// against closed forms, the whole network against PyTorch's golden outputs (training/
// make_golden.py: a seeded 3-level network, two frames, hidden state carried) to 1e-4 relative,
// the weight file's checks, and the recurrence (frame 1 reaches frame 3; a camera cut resets).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>

#include "core/error.h"
#include "core/rng.h"
#include "denoise/denoiser_factory.h"
#include "denoise/memory_plan.h"
#include "denoise/rae_weights.h"
#include "denoise/reference/rae_cpu.h"
#include "denoise/reference/rae_features.h"
#include "denoise/reference/rae_net.h"
#include "io/npy.h"
#include "denoise_rae_support.h"
#include "test_support.h"

using namespace fovrt;
using fovrt::test::RelativeError;

namespace {

std::filesystem::path Golden(const char* file) { return test::SourceDir() / "tests/data/rae" / file; }

Tensor Frame(const NpyArray& a, int t) {
    REQUIRE(a.shape.size() == 4);
    Tensor x(int(a.shape[1]), int(a.shape[2]), int(a.shape[3]));
    std::copy_n(a.data.begin() + std::ptrdiff_t(size_t(t) * x.data.size()), x.data.size(), x.data.begin());
    return x;
}

RaeConv Conv(int out, int in, float bias = 0.0f) {
    RaeConv c;
    c.out = out;
    c.in = in;
    c.weight.assign(size_t(out) * in * 9, 0.0f);
    c.bias.assign(size_t(out), bias);
    return c;
}

// A W×H frame of random surfaces (every pixel hit) for the denoiser-level tests.
FrameInputs RandomFrame(int w, int h, uint64_t seed) {
    FrameInputs f;
    f.Allocate(w, h);
    Pcg32 rng(seed);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            f.direct(x, y) = vec3(rng.NextFloat(), rng.NextFloat(), rng.NextFloat()) * 2.0f;
            f.indirect(x, y) = vec3(rng.NextFloat(), rng.NextFloat(), rng.NextFloat());
            f.albedo(x, y) = vec3(0.5f, 0.6f, 0.7f);
            f.normal(x, y) = glm::normalize(vec3(rng.NextFloat() - 0.5f, rng.NextFloat() - 0.5f, 1.0f));
            f.linearDepth(x, y) = 1.0f + rng.NextFloat();
            f.objectId(x, y) = 1;
            f.roughness(x, y) = 0.5f;
            f.sampleCount(x, y) = uint16_t(1 + (x + y) % 8);
        }
    return f;
}

DenoiserParams GoldenParams() {
    DenoiserParams p;
    p.rae.weights = Golden("golden.raew").string();
    p.rae.weightsSpp = p.rae.weights;
    return p;
}

}  // namespace

TEST_CASE("rae conv: zero padding, bias, leaky ReLU 0.1, concatenation order", "[rae]") {
    // A centre tap of 1 on input channel 1 (the second tensor's first channel): out = that plane.
    Tensor a(1, 3, 4), b(1, 3, 4);
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 4; ++x) {
            a.At(0, y, x) = 100.0f;
            b.At(0, y, x) = float(y * 4 + x) - 5.0f;
        }
    RaeConv c = Conv(1, 2, 0.5f);
    c.weight[9 + 4] = 1.0f;
    Tensor out;
    RaeConv3x3(c, a, &b, true, out);
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 4; ++x) {
            const float v = b.At(0, y, x) + 0.5f;
            CHECK(out.At(0, y, x) == Approx(v > 0 ? v : 0.1f * v));
        }
    // All nine taps of 1 on a plane of ones: the count of in-image neighbours (zero padding).
    RaeConv box = Conv(1, 1);
    std::fill(box.weight.begin(), box.weight.end(), 1.0f);
    Tensor ones(1, 3, 4);
    std::fill(ones.data.begin(), ones.data.end(), 1.0f);
    RaeConv3x3(box, ones, nullptr, false, out);
    CHECK(out.At(0, 0, 0) == 4.0f);
    CHECK(out.At(0, 0, 1) == 6.0f);
    CHECK(out.At(0, 1, 1) == 9.0f);
    CHECK(out.At(0, 2, 3) == 4.0f);
    // Linear output: negatives pass unscaled.
    RaeConv neg = Conv(1, 1, -2.0f);
    RaeConv3x3(neg, ones, nullptr, false, out);
    CHECK(out.At(0, 1, 1) == -2.0f);
}

TEST_CASE("rae max-pool 2x2 and nearest upsample 2x2", "[rae]") {
    Tensor x(2, 4, 4);
    for (size_t i = 0; i < x.data.size(); ++i) x.data[i] = float((i * 7) % 13) - 6.0f;
    Tensor p, u;
    RaeMaxPool2x2(x, p);
    REQUIRE((p.c == 2 && p.h == 2 && p.w == 2));
    for (int c = 0; c < 2; ++c)
        for (int y = 0; y < 2; ++y)
            for (int xx = 0; xx < 2; ++xx)
                CHECK(p.At(c, y, xx) == std::max({x.At(c, 2 * y, 2 * xx), x.At(c, 2 * y, 2 * xx + 1),
                                                  x.At(c, 2 * y + 1, 2 * xx), x.At(c, 2 * y + 1, 2 * xx + 1)}));
    RaeUpsample2x2(p, u);
    REQUIRE((u.h == 4 && u.w == 4));
    for (int y = 0; y < 4; ++y)
        for (int xx = 0; xx < 4; ++xx) CHECK(u.At(1, y, xx) == p.At(1, y / 2, xx / 2));
}

TEST_CASE("rae reference matches PyTorch on two frames to 1e-4 relative (golden files)", "[rae]") {
    const RaeWeights w = LoadRaeWeights(Golden("golden.raew"));
    CHECK(w.Levels() == 3);
    CHECK(w.inChannels == 8);
    CHECK(w.sampleCount);
    CHECK(w.Parameters() == 11555);  // make_golden.py prints PyTorch's count
    const NpyArray in = ReadNpy(Golden("golden_input.npy"));
    const NpyArray expected = ReadNpy(Golden("golden_output.npy"));
    RaeState state;
    for (int t = 0; t < 2; ++t) {
        Tensor y;
        RaeForward(w, Frame(in, t), state, y);
        INFO("frame " << t);
        CHECK(RelativeError(y, Frame(expected, t)) < 1e-4);
    }
    CHECK(state.hidden.size() == 4);
    CHECK(state.Bytes() == RaeHiddenStateBytes(w, 40, 24));
}

TEST_CASE("rae weight files: a bad magic, truncation and trailing bytes are named errors", "[rae]") {
    std::ifstream f(Golden("golden.raew"), std::ios::binary);
    std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    CHECK_NOTHROW(ParseRaeWeights(bytes, "golden"));
    auto bad = bytes;
    bad[0] = 'X';
    CHECK_THROWS_WITH(ParseRaeWeights(bad, "x.raew"), Catch::Contains("magic"));
    bad = bytes;
    bad.resize(bytes.size() - 3);
    CHECK_THROWS_WITH(ParseRaeWeights(bad, "x.raew"), Catch::Contains("truncated"));
    bad = bytes;
    bad.push_back(0);
    CHECK_THROWS_WITH(ParseRaeWeights(bad, "x.raew"), Catch::Contains("trailing"));
    // Round trip through SaveRaeWeights.
    const RaeWeights w = ParseRaeWeights(bytes, "golden");
    const auto path = test::ScratchDir("rae-test") / "copy.raew";
    SaveRaeWeights(path, w);
    std::ifstream g(path, std::ios::binary);
    std::vector<uint8_t> copy((std::istreambuf_iterator<char>(g)), std::istreambuf_iterator<char>());
    CHECK(copy == bytes);
}

TEST_CASE("npy files round-trip", "[rae]") {
    NpyArray a;
    a.shape = {2, 3, 5};
    for (int i = 0; i < 30; ++i) a.data.push_back(float(i) * 0.5f - 3.0f);
    const auto path = test::ScratchDir("rae-test") / "a.npy";
    WriteNpy(path, a);
    const NpyArray b = ReadNpy(path);
    CHECK(b.shape == a.shape);
    CHECK(b.data == a.data);
}

TEST_CASE("rae recurrence: frame 1 changes frame 3's output; a camera cut resets the state", "[rae]") {
    const DenoiserParams p = GoldenParams();
    const int w = 37, h = 21;  // not multiples of 8: the padding path
    std::vector<FrameInputs> frames;
    for (int i = 0; i < 3; ++i) frames.push_back(RandomFrame(w, h, 100 + uint64_t(i)));
    FrameInputs changed = RandomFrame(w, h, 999);

    auto run = [&](const std::vector<FrameInputs>& seq) {
        RaeReferenceDenoiser d("rae-spp", p);
        Plane<vec3> out;
        for (const FrameInputs& f : seq) d.Denoise(f, out);
        return out;
    };
    const Plane<vec3> base = run(frames);
    std::vector<FrameInputs> other = frames;
    other[0] = changed;
    const Plane<vec3> perturbed = run(other);
    double diff = 0.0;
    for (size_t i = 0; i < base.size(); ++i) diff = std::max(diff, double(glm::length(base[i] - perturbed[i])));
    CHECK(diff > 1e-4);  // frame 1 reached frame 3 through the hidden state

    // A cut on frame 3: its output is the fresh network's on frame 3 alone.
    std::vector<FrameInputs> cut = other;
    cut[2].cameraCut = true;
    const Plane<vec3> afterCut = run(cut);
    const Plane<vec3> fresh = run({frames[2]});
    for (size_t i = 0; i < fresh.size(); ++i) REQUIRE(afterCut[i] == fresh[i]);

    // Background pixels come out as their emission exactly (albedo 0).
    FrameInputs bg = frames[0];
    bg.objectId(3, 4) = kNoObject;
    bg.albedo(3, 4) = vec3(0.0f);
    bg.emission(3, 4) = vec3(0.25f, 0.5f, 1.0f);
    RaeReferenceDenoiser d("rae-spp", p);
    Plane<vec3> out;
    d.Denoise(bg, out);
    CHECK(out(3, 4) == vec3(0.25f, 0.5f, 1.0f));
    CHECK(d.LastTimings().size() == 4);
}

// The `balance` mechanism: gains that make the frame's mean illumination grey, in closed form, and
// undone exactly on the output, so that a network passing its colour input through returns it.
TEST_CASE("rae balance: grey gains in closed form, undone on the output", "[rae]") {
    const int w = 4, h = 2;
    Tensor f(kRaeFeatureChannels, h, w);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            // Channel means 2, 1 and 0.5 (each pixel pair averages to them).
            const float k = (x % 2 == 0) ? 1.5f : 0.5f;
            f.At(0, y, x) = 2.0f * k;
            f.At(1, y, x) = 1.0f * k;
            f.At(2, y, x) = 0.5f * k;
        }
    const vec3 g = RaeBalanceGains(f);
    const float mean = 3.5f / 3.0f;
    CHECK(g.x == Approx(mean / 2.0f));
    CHECK(g.y == Approx(mean / 1.0f));
    CHECK(g.z == Approx(mean / 0.5f));

    // No light in a channel (below 1e-4 of the mean) or in the frame: that gain stays 1.
    Tensor dark = f;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) dark.At(2, y, x) = 0.0f;
    CHECK(RaeBalanceGains(dark).z == 1.0f);
    CHECK(RaeBalanceGains(Tensor(kRaeFeatureChannels, h, w)) == vec3(1.0f));

    // The network's input is the balanced colour raised to γ; its output divided by the gains: a
    // network that returns its colour input gives back albedo · colour + emission for any gains.
    const FrameInputs frame = RandomFrame(w, h, 7);
    Tensor features;
    RaeFeatures(frame, features);
    const RaeWeights weights = LoadRaeWeights(Golden("golden.raew"));
    const vec3 gains = RaeBalanceGains(features);
    Tensor input;
    RaeNetworkInput(features, weights, input, gains);
    CHECK(input.At(0, 1, 2) == Approx(std::pow(features.At(0, 1, 2) * gains.x, weights.gamma)));
    Plane<vec3> out;
    RaeRemodulate(frame, input, weights.gamma, out, gains);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const vec3 expected = frame.albedo(x, y) * (frame.direct(x, y) + frame.indirect(x, y));
            for (int c = 0; c < 3; ++c) CHECK(out(x, y)[c] == Approx(expected[c]).epsilon(1e-4));
        }
}

// A surface pixel without a path sample (a periphery below 1 spp) is filled from its sampled
// neighbours before the network sees it: the mean of the known pixels of the smallest aligned
// 2^k block that holds any.
TEST_CASE("rae empty pixels: push-pull fill in closed form", "[rae]") {
    const int w = 8, h = 4;
    // Sampled pixels hold 1, 2, 4 or 8 samples, by column.
    auto count = [](int x, int) { return uint16_t(1u << (x % 4)); };
    auto countFeature = [](int x, int) { return float(x % 4) * 0.25f; };
    auto frame = [&](auto known, auto colour) {
        FrameInputs f;
        f.Allocate(w, h);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                f.objectId(x, y) = 0;
                f.albedo(x, y) = vec3(0.5f);
                f.normal(x, y) = vec3(0, 0, 1);
                f.linearDepth(x, y) = 1.0f;
                f.sampleCount(x, y) = known(x, y) ? count(x, y) : 0;
                f.direct(x, y) = known(x, y) ? colour(x, y) : vec3(0.0f);
            }
        return f;
    };
    auto ramp = [](int x, int y) { return vec3(float(1 + x + 10 * y), 2.0f, 0.5f * float(x)); };
    Tensor t;

    // One sampled pixel per 2×2 block: each empty pixel takes its block's colour and sample count;
    // the sampled ones keep theirs bit for bit.
    auto corner = [](int x, int y) { return x % 2 == 0 && y % 2 == 0; };
    RaeFeatures(frame(corner, ramp), t);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const vec3 expected = ramp(x - x % 2, y - y % 2);
            for (int c = 0; c < 3; ++c) CHECK(t.At(c, y, x) == expected[c]);
            CHECK(t.At(7, y, x) == countFeature(x - x % 2, y - y % 2));
        }

    // An empty 2×2 block takes the mean of the known pixels of its 4×4 block; an empty 4×4 block
    // that of the whole 8×4 frame's known pixels.
    auto holes = [](int x, int y) { return !(x < 2 && y < 2) && x < 4; };  // the right 4×4 empty too
    RaeFeatures(frame(holes, ramp), t);
    vec3 block(0.0f);
    float blockCount = 0.0f;
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x)
            if (holes(x, y)) {
                block += ramp(x, y) / 12.0f;
                blockCount += countFeature(x, y) / 12.0f;
            }
    for (int c = 0; c < 3; ++c) {
        CHECK(t.At(c, 0, 0) == Approx(block[c]));  // the empty top-left block
        CHECK(t.At(c, 1, 1) == Approx(block[c]));
        CHECK(t.At(c, 3, 7) == Approx(block[c]));  // the right half: the frame's only known pixels are that 4×4's
        CHECK(t.At(c, 2, 2) == ramp(2, 2)[c]);
    }
    CHECK(t.At(7, 0, 0) == Approx(blockCount));
    CHECK(t.At(7, 3, 7) == Approx(blockCount));
    CHECK(t.At(7, 2, 3) == countFeature(3, 2));

    // A constant image stays constant wherever it is sampled; the background is neither filled nor
    // read (its "illumination" here is large and must not leak).
    FrameInputs f = frame([](int x, int y) { return (x + y) % 3 == 0; }, [](int, int) { return vec3(0.3f, 0.6f, 0.9f); });
    f.objectId(7, 3) = kNoObject;
    f.sampleCount(7, 3) = 1;
    f.direct(7, 3) = vec3(100.0f);
    f.objectId(6, 3) = kNoObject;  // an empty background pixel stays 0
    f.sampleCount(6, 3) = 0;
    f.direct(6, 3) = vec3(0.0f);
    RaeFeatures(f, t);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            if (f.objectId(x, y) == kNoObject) continue;
            CHECK(t.At(0, y, x) == Approx(0.3f));
            CHECK(t.At(2, y, x) == Approx(0.9f));
        }
    CHECK(t.At(0, 3, 6) == 0.0f);
    CHECK(t.At(0, 3, 7) == 100.0f);

    // No sample anywhere: every pixel 0, nothing non-finite.
    RaeFeatures(frame([](int, int) { return false; }, ramp), t);
    CHECK(std::all_of(t.data.begin(), t.data.end(), [](float v) { return std::isfinite(v); }));
    for (int c = 0; c < 3; ++c) CHECK(t.At(c, 2, 5) == 0.0f);
}

TEST_CASE("rae memory plan counts the hidden state as history", "[rae]") {
    const DenoiserParams p = GoldenParams();
    const RaeWeights& w = *SharedRaeWeights(p);
    size_t hidden = 0;
    for (const BufferPlan& b : PlanRaeMemory(37, 21, p))
        if (b.history) hidden += b.bytes;
    // An A/B pair per level (the previous state is read while the new one is written).
    CHECK(hidden == 2 * RaeHiddenStateBytes(w, 40, 24));
    // 4·(4·40·24 + 6·20·12 + 8·10·6 + 8·5·3)
    CHECK(RaeHiddenStateBytes(w, 40, 24) == size_t(4 * (4 * 960 + 6 * 240 + 8 * 60 + 8 * 15)));
}
