// The RAE's Vulkan host (denoise/vulkan/rae_vk.h) against the C++ reference (rae_net.h): every
// layer's tensor (encoder convs, recurrent blocks, pools, decoder convs with their upsampled
// concatenation, output) and the end-to-end output over three frames with the hidden state
// carried, in fp32 (1e-4 relative) and fp16 activation storage (2e-2 relative); a camera cut
// resets the device state like the reference's.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "core/rng.h"
#include "denoise/rae_weights.h"
#include "denoise/reference/rae_cpu.h"
#include "denoise/reference/rae_features.h"
#include "denoise/reference/rae_net.h"
#include "denoise/vulkan/rae_vk.h"
#include "denoise_rae_support.h"
#include "test_support.h"
#include "vk_test_support.h"

using namespace fovrt;
using fovrt::test::RelativeError;
using fovrt::test::TestContext;

namespace {

DenoiserParams GoldenParams(Precision precision) {
    DenoiserParams p;
    p.rae.weights = (test::SourceDir() / "tests/data/rae/golden.raew").string();
    p.precision = precision;
    return p;
}

// A 37×21 frame of random direct light over a flat grey surface facing the camera, with per-pixel
// sample counts 1 + x mod 8; with `emptyPhase` ≥ 0, 3 of every 4 pixels have no path sample (the
// one with (x + y + phase) mod 4 = 0 keeps it: a moving 1/4 mask).
FrameInputs RandomFlatFrame(Pcg32& rng, int emptyPhase = -1) {
    FrameInputs f;
    f.Allocate(37, 21);
    for (int y = 0; y < 21; ++y)
        for (int x = 0; x < 37; ++x) {
            f.direct(x, y) = vec3(rng.NextFloat(), rng.NextFloat(), rng.NextFloat());
            f.albedo(x, y) = vec3(0.7f);
            f.normal(x, y) = vec3(0, 0, 1);
            f.linearDepth(x, y) = 2.0f;
            f.objectId(x, y) = 0;
            f.sampleCount(x, y) = uint16_t(1 + x % 8);
            if (emptyPhase >= 0 && (x + y + emptyPhase) % 4 != 0) f.sampleCount(x, y) = 0, f.direct(x, y) = vec3(0.0f);
        }
    return f;
}

Tensor RandomInput(const RaeWeights& w, int width, int height, uint64_t seed) {
    Tensor x(w.inChannels, height, width);
    Pcg32 rng(seed);
    for (float& v : x.data) v = rng.NextFloat() * 2.0f - 0.5f;
    return x;
}

// The reference's tensors of one frame, by layout name (the same sequence as RaeForward).
std::map<std::string, Tensor> ReferenceLayers(const RaeWeights& w, const Tensor& in, RaeState& state) {
    std::map<std::string, Tensor> t;
    const int L = w.Levels();
    const RaeConvOrder order{L};
    const bool fresh = state.hidden.size() != size_t(L + 1);
    const Tensor* cur = &in;
    std::vector<Tensor> hidden(size_t(L + 1));
    for (int l = 0; l <= L; ++l) {
        const std::string p = l < L ? "rae.enc" + std::to_string(l) : "rae.bottleneck";
        Tensor &x = t[p + ".x"], &a = t[p + ".a"], &tt = t[p + ".t"];
        RaeConv3x3(w.convs[size_t(l < L ? order.Encoder(l) : order.Bottleneck())], *cur, nullptr, true, x);
        RaeConv3x3(w.convs[size_t(order.Recurrent(l, 0))], x, nullptr, true, a);
        Tensor zeros(a.c, a.h, a.w);
        RaeConv3x3(w.convs[size_t(order.Recurrent(l, 1))], a, fresh ? &zeros : &state.hidden[size_t(l)], true, tt);
        RaeConv3x3(w.convs[size_t(order.Recurrent(l, 2))], tt, nullptr, true, hidden[size_t(l)]);
        t["rae.hidden" + std::to_string(l)] = hidden[size_t(l)];
        if (l < L) {
            RaeMaxPool2x2(hidden[size_t(l)], t[p + ".pool"]);
            cur = &t[p + ".pool"];
        }
    }
    const Tensor* below = &hidden[size_t(L)];
    for (int l = L - 1; l >= 0; --l) {
        const std::string p = "rae.dec" + std::to_string(l);
        Tensor up;
        RaeUpsample2x2(*below, up);
        RaeConv3x3(w.convs[size_t(order.Decoder(l, 0))], up, &hidden[size_t(l)], true, t[p + ".a"]);
        RaeConv3x3(w.convs[size_t(order.Decoder(l, 1))], t[p + ".a"], nullptr, true, t[p + ".b"]);
        below = &t[p + ".b"];
    }
    RaeConv3x3(w.convs[size_t(order.Output())], *below, nullptr, false, t["rae.output"]);
    state.hidden = hidden;
    return t;
}

}  // namespace

TEST_CASE("rae on Vulkan matches the C++ reference layer by layer and end to end", "[vulkan][rae]") {
    if (!VulkanContext::Available()) FOVRT_SKIP("no Vulkan device");
    for (Precision precision : {Precision::Fp32, Precision::Fp16}) {
        if (precision == Precision::Fp16 && !TestContext()->supports16BitStorage()) continue;
        const double tolerance = precision == Precision::Fp32 ? 1e-4 : 2e-2;
        INFO((precision == Precision::Fp32 ? "fp32" : "fp16"));
        RaeVulkanDenoiser vk("rae-spp", TestContext(), GoldenParams(precision));
        const RaeWeights& w = vk.Weights();
        RaeState state;
        for (int frame = 0; frame < 3; ++frame) {
            const Tensor in = RandomInput(w, 40, 24, 7 + uint64_t(frame));
            const std::map<std::string, Tensor> expected = ReferenceLayers(w, in, state);
            Tensor out;
            vk.Forward(in, out);
            INFO("frame " << frame);
            CHECK(RelativeError(out, expected.at("rae.output")) < tolerance);
            for (const auto& [name, tensor] : expected) {
                INFO(name);
                Tensor got;
                vk.ReadTensor(name, got);
                CHECK(RelativeError(got, tensor) < tolerance);
            }
            // The reference's own forward agrees with the layer-by-layer sequence.
            if (frame == 0) {
                RaeState s;
                Tensor y;
                RaeForward(w, in, s, y);
                CHECK(RelativeError(y, expected.at("rae.output")) == 0.0);
            }
        }
    }
    CHECK(TestContext()->validationErrors() == 0);
}

TEST_CASE("rae on Vulkan: denoised frames follow the reference, and a camera cut resets", "[vulkan][rae]") {
    if (!VulkanContext::Available()) FOVRT_SKIP("no Vulkan device");
    const Precision precision = GENERATE(Precision::Fp32, Precision::Fp16);  // fp16: activations stored as half
    DenoiserParams p = GoldenParams(precision);
    p.rae.balance = GENERATE(false, true);  // with the `balance` mechanism's gains too
    const bool empty = GENERATE(false, true);  // 3 of 4 pixels without a path sample
    INFO("fp16 " << (precision == Precision::Fp16) << ", balance " << p.rae.balance << ", empty pixels " << empty);
    RaeVulkanDenoiser vk("rae-spp", TestContext(), p);
    RaeReferenceDenoiser ref("rae-spp", p);
    Pcg32 rng(3);
    for (int frame = 0; frame < 4; ++frame) {
        FrameInputs f = RandomFlatFrame(rng, empty ? frame : -1);
        f.cameraCut = frame == 2;
        Plane<vec3> a, b;
        vk.Denoise(f, a);
        ref.Denoise(f, b);
        CHECK(std::all_of(a.data(), a.data() + a.size(),
                          [](vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }));
        double err = 0.0, scale = 0.0;
        for (size_t i = 0; i < a.size(); ++i) {
            err = std::max(err, double(glm::length(a[i] - b[i])));
            scale = std::max(scale, double(glm::length(b[i])));
        }
        INFO("frame " << frame);
        CHECK(err / scale < (precision == Precision::Fp16 ? 2e-2 : 1e-4));
    }
    std::vector<std::string> passes;
    for (const PassTiming& t : vk.LastTimings()) passes.push_back(t.pass);
    CHECK(passes == std::vector<std::string>{"rae_features", "upload", "rae_encoder", "rae_decoder", "download",
                                             "rae_remodulate"});
}

// The staging ring (vk/transfer_ring.h): frames streamed through a ring far smaller than their
// input and output give the bytes of frames submitted at once, fp32 and fp16 activations.
TEST_CASE("rae on Vulkan: a frame streamed through a small staging ring equals one submit", "[vulkan][rae]") {
    if (!VulkanContext::Available()) FOVRT_SKIP("no Vulkan device");
    for (Precision precision : {Precision::Fp32, Precision::Fp16}) {
        if (precision == Precision::Fp16 && !TestContext()->supports16BitStorage()) continue;
        INFO((precision == Precision::Fp16 ? "fp16" : "fp32"));
        const DenoiserParams whole = GoldenParams(precision);
        DenoiserParams streamed = whole;
        streamed.transferRingBytes = 1000;
        RaeVulkanDenoiser a("rae-spp", TestContext(), whole), b("rae-spp", TestContext(), streamed);
        Pcg32 rng(5);
        for (int frame = 0; frame < 3; ++frame) {
            const FrameInputs f = RandomFlatFrame(rng);
            Plane<vec3> outA, outB;
            a.Denoise(f, outA);
            b.Denoise(f, outB);
            REQUIRE(outA.size() == outB.size());
            CHECK(std::equal(outA.data(), outA.data() + outA.size(), outB.data()));
        }
    }
}
