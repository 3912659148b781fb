// Sample masks (densities below one sample per pixel): the closed forms of their coverage, every
// pixel reached within ⌈1/d⌉ frames, the models' masked maps, and the ray budget met over a
// window of frames when the periphery is masked.
#include <algorithm>
#include <cmath>
#include <optional>
#include <set>
#include <string>

#include "foveation/sample_mask.h"
#include "foveation/spp_model.h"
#include "gaze/gaze_source.h"
#include "test_support.h"

using namespace fovrt;

namespace {

const float kDensities[] = {kMinSpp, 0.1f, 0.25f, 0.3f, 0.5f, 2.0f / 3.0f, 0.75f, 0.9f};

double Phase(int x, int y) { return (double(BayerRank8(x, y)) + 0.5) / 64.0; }

// Frames t0 .. t0 + frames - 1 in which pixel (x, y) of density d is traced.
int Count(float d, int x, int y, uint32_t t0, int frames) {
    int count = 0;
    for (int t = 0; t < frames; ++t) count += SampleMaskSelects(d, x, y, t0 + uint32_t(t));
    return count;
}

EyeCamera Camera(int w, int h) { return EyeCamera(Pose(), Fov::FromHorizontal(Radians(100.0f), float(w) / h), w, h); }

}  // namespace

TEST_CASE("The mask's phases: each 8x8 tile holds every rank once", "[foveation]") {
    std::set<uint32_t> ranks;
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) {
            ranks.insert(BayerRank8(x, y));
            CHECK(BayerRank8(x + 8, y + 16) == BayerRank8(x, y));
        }
    CHECK(ranks.size() == 64);
    CHECK(*ranks.rbegin() == 63);
    // The recursive 2x2 matrix [[0, 2], [3, 1]]: consecutive ranks lie far apart.
    CHECK(BayerRank8(0, 0) == 0);
    CHECK(BayerRank8(4, 4) == 1);
}

TEST_CASE("Mask coverage: the closed form per window, every pixel within ceil(1/d) frames", "[foveation]") {
    for (float d : kDensities) {
        const int bound = int(std::ceil(1.0 / double(d)));
        for (uint32_t t0 : {0u, 5u, 1000u, 123457u})
            for (int y = 0; y < 16; ++y)
                for (int x = 0; x < 16; ++x) {
                    INFO("d " << d << " pixel " << x << "," << y << " from frame " << t0);
                    // Over T frames: ⌊φ + d(t0+T)⌋ − ⌊φ + d·t0⌋, so ⌊dT⌋ or ⌈dT⌉.
                    for (int frames : {bound, 7, 16, 64}) {
                        const int count = Count(d, x, y, t0, frames);
                        const double phi = Phase(x, y);
                        CHECK(count == int(std::floor(phi + double(d) * (t0 + frames)) -
                                           std::floor(phi + double(d) * t0)));
                        CHECK(count >= int(std::floor(double(d) * frames)));
                        CHECK(count <= int(std::ceil(double(d) * frames)));
                    }
                    REQUIRE(Count(d, x, y, t0, bound) >= 1);  // reached within ⌈1/d⌉ frames
                }
    }
}

TEST_CASE("Mask density: the mean over frames and over each frame's pixels is d", "[foveation]") {
    for (float d : kDensities) {
        INFO("d " << d);
        // Over time: exactly ⌊φ + dL⌋ samples in L frames from frame 0, so within 1/L of d.
        const int frames = 4096;
        CHECK(std::abs(double(Count(d, 3, 5, 0, frames)) / frames - double(d)) <= 1.0 / frames);
        // In one frame: the pixels whose phase lies in an interval of length d, ⌊64d⌋ or ⌈64d⌉ of
        // every 8×8 tile.
        for (uint32_t t : {0u, 1u, 2u, 77u}) {
            int traced = 0;
            for (int y = 0; y < 32; ++y)
                for (int x = 0; x < 32; ++x) traced += SampleMaskSelects(d, x, y, t);
            CHECK(std::abs(double(traced) / (32 * 32) - double(d)) <= 1.0 / 64.0);
        }
    }
    // d = 1/16 and 1/4: exactly d in every frame, and the traced pixels change from frame to frame.
    for (float d : {kMinSpp, 0.25f}) {
        std::set<std::vector<bool>> patterns;
        for (uint32_t t = 0; t < uint32_t(std::lround(1.0f / d)); ++t) {
            std::vector<bool> traced;
            for (int y = 0; y < 8; ++y)
                for (int x = 0; x < 8; ++x) traced.push_back(SampleMaskSelects(d, x, y, t));
            CHECK(std::count(traced.begin(), traced.end(), true) == std::lround(64 * d));
            patterns.insert(traced);
        }
        CHECK(patterns.size() == size_t(std::lround(1.0f / d)));
    }
}

TEST_CASE("Models below one spp: uniform 0.5, disc 0.25 outside, linear 6 down to 0.125", "[foveation]") {
    const int w = 64, h = 48;
    const EyeCamera cam = Camera(w, h);
    FoveationParams uniform;
    uniform.model = "uniform";
    uniform.uniformSpp = 0.5f;
    FoveationParams disc;
    disc.sppOutside = 0.25f;
    disc.radiusPx = 400.0f;  // 20 px at 64 wide
    FoveationParams linear;
    linear.model = "linear";
    linear.sppMax = 6;
    linear.sppMin = 0.125f;
    for (const FoveationParams& p : {uniform, disc, linear}) {
        INFO(p.model);
        auto model = CreateSppModel(p);
        Plane<float> density;
        model->GenerateDensity(cam, vec3(0, 0, -1), 0, density);
        // Over 8 frames (⌈1/0.125⌉): every pixel traced; a masked one 1/d-th of the frames.
        std::vector<Plane<uint16_t>> maps(8);
        for (uint32_t t = 0; t < 8; ++t) model->Generate(cam, vec3(0, 0, -1), 40 + t, maps[t]);
        int masked = 0;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const float d = density(x, y);
                int count = 0, total = 0;
                for (const Plane<uint16_t>& spp : maps) {
                    count += spp(x, y) > 0;
                    total += spp(x, y);
                    if (d < 1.0f) REQUIRE(spp(x, y) <= 1);
                    if (d >= 1.0f) REQUIRE(spp(x, y) == std::lround(d));
                }
                REQUIRE(count >= 1);
                if (d < 1.0f) {
                    ++masked;
                    REQUIRE(total == Count(d, x, y, 40, 8));
                }
            }
        CHECK(masked > 0);
    }
    // The closed forms at the model level: uniform 0.5 traces each pixel on every other frame.
    auto model = CreateSppModel(uniform);
    Plane<uint16_t> a, b;
    model->Generate(cam, vec3(0, 0, -1), 10, a);
    model->Generate(cam, vec3(0, 0, -1), 11, b);
    for (size_t i = 0; i < a.size(); ++i) REQUIRE(a[i] + b[i] == 1);
}

TEST_CASE("Ray budget below W*H: met over a window of frames, every pixel within its bound", "[foveation]") {
    const int w = 64, h = 48;
    const int64_t n = int64_t(w) * h;
    const EyeCamera cam = Camera(w, h);
    const vec3 gaze = GazeDirectionFromAngles(10.0f, -5.0f);
    for (const char* name : {"disc", "linear", "acuity", "uniform"})
        for (double perPixel : {0.0625, 0.25, 0.5, 0.8, 1.5}) {
            FoveationParams p;
            p.model = name;
            p.radiusPx = 400.0f;
            p.sppFloor = kMinSpp;
            p.rayBudget = int64_t(std::llround(perPixel * double(n)));
            INFO(name << " budget " << perPixel << " spp");
            auto model = CreateSppModel(p);
            // A static gaze keeps each pixel's target, so each keeps its mask's guarantees.
            const int frames = 32;
            Plane<int> traced(w, h);
            int64_t total = 0;
            Plane<uint16_t> spp;
            for (int t = 0; t < frames; ++t) {
                model->Generate(cam, gaze, uint32_t(t), spp);
                for (int y = 0; y < h; ++y)
                    for (int x = 0; x < w; ++x) {
                        REQUIRE(spp(x, y) <= kMaxSpp);
                        total += spp(x, y);
                        if (t < 16 && spp(x, y) > 0) traced(x, y) = 1;
                    }
            }
            // Every target is at least spp_floor = 1/16: each pixel traced within 16 frames.
            for (size_t i = 0; i < traced.size(); ++i) REQUIRE(traced[i] == 1);
            // The window's total: the budget per frame, within 1 % (masked pixels: each within
            // one sample of d·frames, the phases spread over [0, 1), so the errors mostly cancel).
            const double expected = double(p.rayBudget) * frames;
            CHECK(std::abs(double(total) - expected) <= 0.01 * expected);
        }
}

// ZeroSppKey is read from the keys, never from a map: every config it clears must give maps
// without a 0, and the ones it names (with the key that allows it) must give some.
TEST_CASE("ZeroSppKey names the key that lets the spp map hold 0, and a map without it holds none", "[foveation]") {
    const int w = 64, h = 48;
    const int64_t n = int64_t(w) * h;
    const EyeCamera cam = Camera(w, h);
    struct Case {
        const char* what;
        FoveationParams params;
        std::optional<std::string> key;
    };
    auto with = [](auto set) {
        FoveationParams p;
        p.radiusPx = 400.0f;  // 20 px at 64 wide: a periphery around the disc
        set(p);
        return p;
    };
    const Case cases[] = {
        {"disc 8/1", with([](FoveationParams&) {}), std::nullopt},
        {"disc 8/0.25", with([](FoveationParams& p) { p.sppOutside = 0.25f; }), "foveation.spp_outside = 0.25"},
        {"linear 6..0.125", with([](FoveationParams& p) { p.model = "linear"; p.sppMax = 6; p.sppMin = 0.125f; }),
         "foveation.spp_min = 0.125"},
        {"linear 6..1 with spp_outside 0.25 unused",
         with([](FoveationParams& p) { p.model = "linear"; p.sppMax = 6; p.sppOutside = 0.25f; }), std::nullopt},
        {"acuity down to 0.5", with([](FoveationParams& p) { p.model = "acuity"; p.sppMin = 0.5f; }),
         "foveation.spp_min = 0.5"},
        {"uniform 0.5", with([](FoveationParams& p) { p.model = "uniform"; p.uniformSpp = 0.5f; }),
         "foveation.uniform_spp = 0.5"},
        {"uniform 1 under a budget of 0.5 spp, floor 1/16",
         with([&](FoveationParams& p) { p.model = "uniform"; p.sppFloor = kMinSpp; p.rayBudget = n / 2; }),
         "foveation.spp_floor = 0.0625"},
        {"disc 8/0.25 under a budget of 2 spp, floor 1: the budget lifts the periphery to 1",
         with([&](FoveationParams& p) { p.sppOutside = 0.25f; p.rayBudget = 2 * n; }), std::nullopt},
    };
    for (const Case& c : cases) {
        INFO(c.what);
        CHECK(ZeroSppKey(c.params) == c.key);
        CHECK(MapMayHaveZeroSamples(c.params) == c.key.has_value());
        auto model = CreateSppModel(c.params);
        Plane<uint16_t> spp;
        size_t zeros = 0;
        for (uint32_t t = 0; t < 4; ++t) {
            model->Generate(cam, GazeDirectionFromAngles(10.0f, -5.0f), t, spp);
            zeros += size_t(std::count(spp.data(), spp.data() + spp.size(), uint16_t(0)));
        }
        if (c.key)
            CHECK(zeros > 0);
        else
            CHECK(zeros == 0);
    }
}
