// FovVideoVDP (src/metrics/fovvideovdp.h) against its reference implementation, stage by stage and
// end to end, and the behaviour the paper shows (Fig. 1: the same distortion is less visible away
// from the fixation).
//
// The golden cases, their inputs and their provenance: tests/vdp_golden_cases.h.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <iomanip>
#include <limits>
#include <tuple>
#include <vector>

#include "metrics/fovvideovdp.h"
#include "metrics/vdp_csf.h"
#include "metrics/vdp_masking.h"
#include "metrics/vdp_pyramid.h"
#include "metrics/vdp_temporal.h"
#include "vdp_golden_cases.h"

using namespace fovrt;
using namespace fovrt::vdp_test;

TEST_CASE("FovVideoVDP gives the reference implementation's JOD within 0.01 on every golden case", "[vdp]") {
    for (const GoldenCase& c : GoldenCases()) {
        const VdpResult r = ScoreCase(c);
        INFO(c.name << ": fovrt " << std::fixed << std::setprecision(6) << r.jod << ", reference " << c.jod
                    << ", difference " << r.jod - c.jod);
        CHECK(std::abs(r.jod - c.jod) < 0.01);
    }
}

TEST_CASE("the vectorised metric keeps the scalar metric's JOD within 1e-4 on every golden case", "[vdp]") {
    // fovrt's JOD (overall, sustained only, transient only) with libm's exp2/log2 and the CSF
    // axes searched node by node, as the metric computed them before its per-pixel loops were
    // vectorised (vdp_fastmath.h); in the order of GoldenCases().
    const double kScalar[][3] = {
        {9.579290, 9.579290, 10.0}, {9.683994, 9.683994, 10.0}, {9.719753, 9.719753, 10.0},
        {8.067161, 8.067161, 10.0}, {8.943840, 8.943840, 10.0}, {9.119418, 9.119418, 10.0},
        {9.649903, 9.649903, 10.0}, {9.298559, 9.895559, 9.366742}, {9.481324, 9.921554, 9.532526},
        {8.553170, 9.984194, 8.557576}, {8.898003, 9.638957, 9.106398}, {8.312611, 8.683931, 9.506962},
        {9.375161, 9.796758, 9.483961}, {8.754870, 9.540660, 9.102666},
    };
    REQUIRE(GoldenCases().size() == std::size(kScalar));
    for (size_t i = 0; i < GoldenCases().size(); ++i) {
        const VdpResult r = ScoreCase(GoldenCases()[i]);
        INFO(GoldenCases()[i].name << std::fixed << std::setprecision(6) << ": " << r.jod << " " << r.jodSustained
                                   << " " << r.jodTransient);
        CHECK(std::abs(r.jod - kScalar[i][0]) < 1e-4);
        CHECK(std::abs(r.jodSustained - kScalar[i][1]) < 1e-4);
        CHECK(std::abs(r.jodTransient - kScalar[i][2]) < 1e-4);
    }
}

TEST_CASE("a sequence read and scored in chunks gives Score's result on the whole sequence, bit for bit", "[vdp]") {
    // Every video golden case (moving fixations, 60 fps filters reaching 15 frames back, HDR) and
    // a still, with difference maps, in chunks of 1 frame up to longer than the sequence (0: as
    // many as the threads).
    for (const GoldenCase& c : GoldenCases()) {
        if (c.frames == 1 && c.name != GoldenCases()[1].name) continue;
        const Frames frames = MakeFrames(c);
        const VdpPhotometry photometry = PhotometryOf(c);
        VdpOptions options = OptionsOf(c);
        options.diffMaps = true;
        const FovVideoVdp vdp(GeometryOf(c));
        const VdpResult whole = ScoreCase(c, true);
        for (const int chunk : {0, 1, 7, 16, 1000}) {
            int asked = 0;  // frames are asked for once each, in order
            auto read = [&](int f, Plane<float>& test, Plane<float>& reference) {
                CHECK(f == asked++);
                test = VdpLuminance(frames.test[size_t(f)], photometry);
                reference = VdpLuminance(frames.reference[size_t(f)], photometry);
            };
            const VdpResult r = vdp.ScoreSequence(c.frames, read, c.fps, options, chunk);
            INFO(c.name << ", chunks of " << chunk);
            CHECK(asked == c.frames);
            CHECK(r.frames == whole.frames);
            CHECK(r.q == whole.q);
            CHECK(r.jod == whole.jod);
            CHECK(r.jodSustained == whole.jodSustained);
            CHECK(r.jodTransient == whole.jodTransient);
            REQUIRE(r.diffMaps.size() == whole.diffMaps.size());
            for (size_t f = 0; f < r.diffMaps.size(); ++f) CHECK(r.diffMaps[f].vector() == whole.diffMaps[f].vector());
        }
    }
}

namespace {

// A still 160×90 frame pair whose test has `noise` in the box [x0, x1) × [y0, y1) (whole frame
// when x1 = 0), in cd/m² on the 100 cd/m² sRGB display.
std::pair<Plane<float>, Plane<float>> NoisyStill(double noise, int x0 = 0, int y0 = 0, int x1 = 0, int y1 = 0) {
    GoldenCase c{.name = "behaviour", .seed = 7};
    const Frames f = MakeFrames(c);
    Plane<float> test = f.test[0];
    for (int y = 0; y < c.h; ++y)
        for (int x = 0; x < c.w; ++x)
            if (x1 == 0 || (x >= x0 && x < x1 && y >= y0 && y < y1))
                test(x, y) = float(std::clamp(double(test(x, y)) + noise * NoiseAt(7, 0, x, y), 0.0, 1.0));
    const VdpPhotometry photometry = PhotometryOf(c);
    return {VdpLuminance(test, photometry), VdpLuminance(f.reference[0], photometry)};
}

}  // namespace

TEST_CASE("identical sequences score exactly 10 JOD, foveated or not, with zero difference maps", "[vdp]") {
    GoldenCase still{.name = "identical"};
    GoldenCase video{.name = "identical video", .w = 96, .h = 72, .frames = 8, .fps = 30, .vx = 1.0};
    for (const GoldenCase& c : {still, video})
        for (bool foveated : {false, true}) {
            const Frames f = MakeFrames(c);
            std::vector<Plane<float>> ref;
            for (const Plane<float>& p : f.reference) ref.push_back(VdpLuminance(p, PhotometryOf(c)));
            VdpOptions o;
            o.foveated = foveated;
            o.diffMaps = true;
            const VdpResult r = FovVideoVdp(GeometryOf(c)).Score(ref, ref, c.fps, o);
            CHECK(r.jod == 10.0);
            CHECK(r.jodSustained == 10.0);
            CHECK(r.jodTransient == 10.0);
            for (const Plane<float>& m : r.diffMaps)
                for (float v : m.vector()) REQUIRE(v == 0.0f);
        }
}

TEST_CASE("more noise never raises JOD", "[vdp]") {
    const FovVideoVdp vdp(VdpGeometry::FromPixelsPerDegree(20));
    double previous = 10.0;
    for (double amplitude : {0.005, 0.01, 0.02, 0.04, 0.08, 0.16}) {
        auto [test, ref] = NoisyStill(amplitude);
        const double jod = vdp.Score({test}, {ref}, 0).jod;
        INFO("noise " << amplitude << ": " << jod << " JOD, previous " << previous);
        CHECK(jod < previous);
        previous = jod;
    }
}

TEST_CASE("the same noise is less visible away from the fixation (paper Fig. 1)", "[vdp]") {
    const FovVideoVdp vdp(VdpGeometry::FromPixelsPerDegree(20));
    auto [test, ref] = NoisyStill(0.1, 16, 16, 40, 40);
    auto scoreAt = [&](float x, float y) {
        VdpOptions o;
        o.foveated = true;
        o.fixations = {{x, y}};
        return vdp.Score({test}, {ref}, 0, o).jod;
    };
    const double atPatch = scoreAt(28, 28), near = scoreAt(80, 45), far = scoreAt(150, 80);
    INFO("fixation on the patch " << atPatch << ", 3 deg away " << near << ", 6.5 deg away " << far);
    CHECK(atPatch < near);
    CHECK(near < far);
    // The non-foveated metric sees the patch as if fixated everywhere: at most as good as fixated.
    CHECK(vdp.Score({test}, {ref}, 0).jod <= atPatch + 1e-9);
}

TEST_CASE("the same flicker is less visible away from the fixation", "[vdp]") {
    const GoldenCase c{.name = "flicker patch", .w = 96, .h = 72, .frames = 15, .fps = 30, .flickerHz = 10,
                       .flickerAmp = 0.05, .box = {8, 8, 24, 24}};
    const Frames f = MakeFrames(c);
    std::vector<Plane<float>> test, ref;
    for (const Plane<float>& p : f.test) test.push_back(VdpLuminance(p, PhotometryOf(c)));
    for (const Plane<float>& p : f.reference) ref.push_back(VdpLuminance(p, PhotometryOf(c)));
    const FovVideoVdp vdp(GeometryOf(c));
    auto scoreAt = [&](float x, float y) {
        VdpOptions o;
        o.foveated = true;
        o.fixations = {{x, y}};
        return vdp.Score(test, ref, c.fps, o);
    };
    const VdpResult at = scoreAt(16, 16), away = scoreAt(88, 64);
    INFO("fixation on the flicker " << at.jod << " (transient alone " << at.jodTransient << "), away " << away.jod
                                    << " (" << away.jodTransient << ")");
    CHECK(at.jod < away.jod);
    CHECK(at.jodTransient < away.jodTransient);
    CHECK(at.jodTransient < 10.0);
}

TEST_CASE("difference maps are largest where the difference is", "[vdp]") {
    auto [test, ref] = NoisyStill(0.1, 16, 16, 40, 40);
    VdpOptions o;
    o.diffMaps = true;
    const VdpResult r = FovVideoVdp(VdpGeometry::FromPixelsPerDegree(20)).Score({test}, {ref}, 0, o);
    REQUIRE(r.diffMaps.size() == 1);
    const Plane<float>& m = r.diffMaps[0];
    REQUIRE((m.width() == 160 && m.height() == 90));
    double inside = 0, outside = 0;
    for (int y = 0; y < 90; ++y)
        for (int x = 0; x < 160; ++x) {
            REQUIRE(m(x, y) >= 0.0f);
            (x >= 16 && x < 40 && y >= 16 && y < 40 ? inside : outside) += m(x, y);
        }
    CHECK(inside / (24 * 24) > 20 * outside / (160 * 90 - 24 * 24));
}

TEST_CASE("display geometry: pixels per degree from a FOV, a monitor or a profile", "[vdp]") {
    CHECK(VdpGeometry::FromPixelsPerDegree(20).PixelsPerDegree() == Approx(20).epsilon(1e-12));
    // A 1280-wide eye image over 100° horizontally: 1 / (2 atan(tan 50° / 1280)) in degrees ≈ 9.4
    // at the centre (not 12.8: a flat image spends more pixels per degree off-centre).
    const double ppd = VdpGeometry::FromHorizontalFov(1280, 100).PixelsPerDegree();
    CHECK(ppd == Approx(1.0 / (2.0 * std::atan(std::tan(50.0 * kPiD / 180) / 1280) * 180 / kPiD)));
    // 24-inch 1920×1080 at 0.6 m: 0.2767 mm pixels, ≈ 37.8 ppd.
    CHECK(FindVdpDisplay("monitor-24-fhd").geometry.PixelsPerDegree() == Approx(37.84).margin(0.01));
    CHECK(FindVdpDisplay("headset-25").geometry.PixelsPerDegree() == Approx(25));
    CHECK(FindVdpDisplay("headset-25").photometry.peak == 100);
    CHECK_THROWS_WITH(FindVdpDisplay("vive"), Catch::Contains("unknown display profile 'vive'"));
    // Off-centre pixels of a flat screen subtend less: ppd grows as 1/cos² of the angle.
    const VdpGeometry g = VdpGeometry::FromPixelsPerDegree(20);
    const double c30 = std::cos(30 * kPiD / 180);
    CHECK(g.ResolutionMagnification(30) == Approx(1 / (c30 * c30)).epsilon(2e-3));
    // The reference's form, (tan(a + δ) − tan a) / tan δ with δ half a central pixel, at 5 to
    // 60 ppd and angles out to the 89.9° cap (short of its pole at a + δ = 90°).
    for (double ppd : {5.0, 20.0, 60.0}) {
        const VdpGeometry geo = VdpGeometry::FromPixelsPerDegree(ppd);
        const double delta = 0.5 / ppd * kPiD / 180;
        for (double a : {0.0, 1.0, 12.5, 30.0, 55.0, 80.0, 89.0, 89.9, 95.0}) {
            if (std::min(a, 89.9) + 0.5 / ppd >= 89.99) continue;
            const double r = std::min(a, 89.9) * kPiD / 180;
            INFO("ppd " << ppd << ", angle " << a);
            CHECK(geo.ResolutionMagnification(a) ==
                  Approx((std::tan(r + delta) - std::tan(r)) / std::tan(delta)).epsilon(1e-7));
        }
    }
}

TEST_CASE("photometry: sRGB, linear and absolute values to cd/m², clamped to the display's range", "[vdp]") {
    const VdpPhotometry srgb{100.0, 0.1, VdpEotf::Srgb}, linear{100.0, 0.1, VdpEotf::Linear},
        absolute{1000.0, 0.005, VdpEotf::Absolute};
    CHECK(srgb.Luminance(1.0f) == Approx(100.0));
    CHECK(srgb.Luminance(0.0f) == Approx(0.1));
    CHECK(srgb.Luminance(0.5f) == Approx(99.9 * std::pow((0.5 + 0.055) / 1.055, 2.4) + 0.1).epsilon(1e-6));
    CHECK(linear.Luminance(0.25f) == Approx(99.9 * 0.25 + 0.1));
    CHECK(linear.Luminance(3.0f) == Approx(100.0));
    CHECK(absolute.Luminance(250.0f) == 250.0f);
    CHECK(absolute.Luminance(5000.0f) == 1000.0f);
    CHECK(absolute.Luminance(std::numeric_limits<float>::quiet_NaN()) == 0.005f);
    CHECK(srgb.Luminance(std::numeric_limits<float>::infinity()) == Approx(100.0));
    CHECK(VdpBlackLevel(200.0, 1000.0, 250.0) == Approx(0.2 + 250.0 / kPiD * 0.005));
}

TEST_CASE("integer codes through VdpCodeLuminance's tables equal VdpLuminance of their values bit for bit",
          "[vdp]") {
    // Every code of both bit depths, on each EOTF, grey (1 and 2 channels) and RGB (3 and 4): the
    // value a reader of floats would see (code·(65535/(2^b−1)) / 65535) through VdpLuminance.
    const VdpPhotometry photometries[] = {
        {100.0, 0.1, VdpEotf::Srgb}, {200.0, 0.6, VdpEotf::Linear}, {1000.0, 0.005, VdpEotf::Absolute}};
    for (const VdpPhotometry& photometry : photometries)
        for (const int bits : {8, 16}) {
            const uint32_t codes = 1u << bits, widen = 65535u / (codes - 1u);
            const int w = 256, h = int(codes) / w;
            auto value = [&](uint32_t c) { return float(c * widen) / 65535.0f; };
            for (const int channels : {1, 2, 3, 4}) {
                // Pixel i: code i on R (and grey), rotated codes on G and B, alpha the largest code.
                std::vector<uint16_t> c16(size_t(codes) * size_t(channels));
                Plane<vec3> rgb(w, h);
                for (uint32_t i = 0; i < codes; ++i) {
                    const uint32_t g = (i * 7919u) % codes, b = (i * 104729u + 13u) % codes;
                    const uint32_t pixel[4] = {i, channels < 3 ? codes - 1 : g, b, codes - 1};
                    for (int k = 0; k < channels; ++k)
                        c16[size_t(i) * size_t(channels) + size_t(k)] = uint16_t(pixel[k]);
                    rgb[i] = channels < 3 ? vec3(value(i)) : vec3(value(i), value(g), value(b));
                }
                const VdpCodeLuminance table(photometry, bits);
                Plane<float> looked;
                if (bits == 8) {
                    const std::vector<uint8_t> c8(c16.begin(), c16.end());
                    table.Image(c8.data(), w, h, channels, looked);
                } else {
                    table.Image(c16.data(), w, h, channels, looked);
                }
                const Plane<float> computed = VdpLuminance(rgb, photometry);
                size_t differing = 0;
                for (size_t i = 0; i < computed.size(); ++i) differing += looked[i] != computed[i];
                INFO(bits << "-bit, " << channels << " channel(s), EOTF " << int(photometry.eotf));
                CHECK(differing == 0);
            }
        }
}

TEST_CASE("the CSF table reproduces the model at its nodes and interpolates between", "[vdp]") {
    const VdpCsfTable table(5.0, -1.5, 0.604562);
    // Nodes: ρ = 2^(−4 + 10 i/31), L = 10^(−3 + 7 j/31), e = (√120 k/31)².
    for (auto [i, j, k] : {std::tuple{10, 15, 0}, {20, 25, 5}, {25, 8, 12}}) {
        const float rho = float(std::pow(10.0, std::log10(0.0625) + (std::log10(64.0) - std::log10(0.0625)) * i / 31));
        const float lum = float(std::pow(10.0, -3.0 + 7.0 * j / 31));
        const float ecc = float(std::pow(std::sqrt(120.0) * k / 31, 2.0));
        CHECK(table.Sensitivity(rho, lum, ecc) == Approx(VdpCsfModel(rho, 5.0, lum, ecc, -1.5, 0.604562)).epsilon(1e-4));
    }
    // Sensitivity falls with eccentricity and at high frequency.
    CHECK(table.Sensitivity(4, 50, 20) < table.Sensitivity(4, 50, 0));
    CHECK(table.Sensitivity(30, 50, 0) < table.Sensitivity(4, 50, 0));
    // The luminance slice equals the 3D lookup.
    const auto slice = table.Slice(3.3f, 0.0f);
    for (float lum : {0.2f, 7.0f, 95.0f}) CHECK(table.Sensitivity(slice, lum) == Approx(table.Sensitivity(3.3f, lum, 0.0f)).epsilon(1e-5));
}

TEST_CASE("temporal filters: sustained sums to 1, transient is its scaled derivative, 250 ms long", "[vdp]") {
    CHECK(VdpTemporalFilterLength(30) == 8);
    CHECK(VdpTemporalFilterLength(60) == 15);
    CHECK(VdpTemporalFilterLength(90) == 23);
    const VdpTemporalFilters f = MakeVdpTemporalFilters(30, VdpParams{});
    double sum = 0;
    for (float v : f.sustained) sum += v;
    CHECK(sum == Approx(1.0).epsilon(1e-6));
    const double dt = 8.0 / 30 / 7;  // linspace(0, 8/30, 8)
    for (size_t i = 0; i + 1 < f.sustained.size(); ++i)
        CHECK(f.transient[i] == Approx(kVdpTransientGain * (f.sustained[i + 1] - f.sustained[i]) / dt).epsilon(1e-4));
    CHECK(f.transient.back() == 0.0f);
}

namespace {

// The 5-tap reduce and expand of one row, tap by tap with every bounds test (the form
// VdpGaussReduce and VdpGaussExpand take at the edges; inside they skip the tests).
constexpr float kTap[5] = {0.25f - 0.4f / 2.0f, 0.25f, 0.4f, 0.25f, 0.25f - 0.4f / 2.0f};

std::vector<float> ReduceRowTapByTap(const std::vector<float>& in, bool oddRule) {
    const int n = int(in.size()), m = (n + 1) / 2;
    std::vector<float> out(size_t(m), 0.0f);
    for (int i = 0; i < m; ++i)
        for (int k = 0; k < 5; ++k)
            if (const int j = 2 * i + k - 2; j >= 0 && j < n) out[size_t(i)] += kTap[k] * in[size_t(j)];
    out[0] += in[0] * kTap[1] + in[n > 1 ? 1 : 0] * kTap[0];
    if (oddRule) out[size_t(m - 1)] += in[size_t(n - 1)] * kTap[3] + in[size_t(std::max(n - 2, 0))] * kTap[4];
    else out[size_t(m - 1)] += in[size_t(n - 1)] * kTap[4];
    return out;
}

std::vector<float> ExpandRowTapByTap(const std::vector<float>& in, int n) {
    const int inCount = int(in.size());
    std::vector<int> src(size_t(n) + 4, -1);  // the zero-interleaved, edge-padded signal
    for (int j = 0; 2 + 2 * j < n + 2 && j < inCount; ++j) src[size_t(2 + 2 * j)] = j;
    src[0] = 0;
    src[size_t(n + 4 - 2 + (n % 2))] = inCount - 1;
    std::vector<float> out(size_t(n), 0.0f);
    for (int c = 0; c < n; ++c)
        for (int k = 0; k < 5; ++k)
            if (const int j = src[size_t(c + k)]; j >= 0) out[size_t(c)] += 2.0f * kTap[k] * in[size_t(j)];
    return out;
}

}  // namespace

TEST_CASE("reduce and expand equal their tap-by-tap definition bit for bit along rows of every width", "[vdp]") {
    // Two-row images (reduce) and one-row images (expand) of widths 2 to 41, odd and even, with
    // values that make every tap count; the vertical pass of each, whose code has no fast path,
    // is written out as the pyramid sums it.
    for (int w = 2; w <= 41; ++w) {
        Plane<float> image(w, 2);
        for (int y = 0; y < 2; ++y)
            for (int x = 0; x < w; ++x) image(x, y) = float(1.0 + 0.37 * x + 0.011 * x * x - 0.2 * y);
        // Height 2 → 1 (even: the even end rule): taps 2, 3 inside, then 1, 0 (first row), 4 (last).
        std::vector<float> column(static_cast<size_t>(w));
        for (int x = 0; x < w; ++x) {
            float v = 0.0f;
            v += kTap[2] * image(x, 0);
            v += kTap[3] * image(x, 1);
            v += kTap[1] * image(x, 0);
            v += kTap[0] * image(x, 1);
            v += kTap[4] * image(x, 1);
            column[size_t(x)] = v;
        }
        const Plane<float> reduced = VdpGaussReduce(image);
        const std::vector<float> reducedRow = ReduceRowTapByTap(column, false);
        REQUIRE(reduced.height() == 1);
        for (int x = 0; x < reduced.width(); ++x) {
            INFO("reduce " << w << "x2, x = " << x);
            CHECK(reduced(x, 0) == reducedRow[size_t(x)]);
        }

        Plane<float> half((w + 1) / 2, 1);
        for (int x = 0; x < half.width(); ++x) half(x, 0) = float(0.5 + 0.29 * x - 0.013 * x * x);
        // Height 1 → 1: taps 0, 2 and 4 all read the one row.
        std::vector<float> row(static_cast<size_t>(half.width()));
        for (int x = 0; x < half.width(); ++x) {
            float v = 0.0f;
            for (const int k : {0, 2, 4}) v += 2.0f * kTap[k] * half(x, 0);
            row[size_t(x)] = v;
        }
        const Plane<float> expanded = VdpGaussExpand(half, w, 1);
        const std::vector<float> expandedRow = ExpandRowTapByTap(row, w);
        for (int x = 0; x < w; ++x) {
            INFO("expand to " << w << ", x = " << x);
            CHECK(expanded(x, 0) == expandedRow[size_t(x)]);
        }
    }
}

TEST_CASE("a pyramid decomposed into an earlier frame's planes equals a fresh decomposition", "[vdp]") {
    const Frames still = MakeFrames(CaseNamed("still, noise, 20 ppd"));  // 160×90
    const Frames video = MakeFrames(CaseNamed("video, dynamic noise, 20 ppd"));  // 96×72
    const std::vector<const Plane<float>*> stillImages = {&still.test[0], &still.reference[0]};
    const std::vector<const Plane<float>*> videoImages = {&video.test[4], &video.reference[4], &video.test[5],
                                                          &video.reference[5]};
    const std::vector<const Plane<float>*> swapped = {&still.reference[0], &still.test[0]};
    VdpContrastPyramid reused;
    // Then other content of the same size (every plane stale), smaller with more images and fewer
    // bands, larger again.
    for (const auto& [images, bands] :
         {std::pair{stillImages, 5}, {swapped, 5}, {videoImages, 4}, {stillImages, 5}}) {
        VdpDecompose(images, 1, bands, reused);
        const VdpContrastPyramid fresh = VdpDecompose(images, 1, bands);
        for (int b = 0; b < bands; ++b) {
            CHECK(reused.adaptation[size_t(b)].vector() == fresh.adaptation[size_t(b)].vector());
            for (size_t i = 0; i < images.size(); ++i)
                CHECK(reused.contrast[size_t(b)][i].vector() == fresh.contrast[size_t(b)][i].vector());
        }
    }
}

TEST_CASE("both temporal channels in one pass equal each channel filtered alone, at the start and later", "[vdp]") {
    const GoldenCase& c = CaseNamed("video, HDR cd/m2, moving content with noise");
    const Frames frames = MakeFrames(c);
    const VdpTemporalFilters f = MakeVdpTemporalFilters(c.fps, VdpParams{});
    Plane<float> sustained, transient;  // reused from frame to frame, as the metric does
    for (int frame : {20, 0, 3}) {
        VdpFilterFrameChannels(frames.test, frame, f, sustained, transient);
        CHECK(sustained.vector() == VdpFilterFrame(frames.test, frame, f.sustained).vector());
        CHECK(transient.vector() == VdpFilterFrame(frames.test, frame, f.transient).vector());
    }
}

namespace {

// Values inside the reference at one frame (gen_stages.py beside the generator, same commit):
// per band, at three pixels of the band, the contrast of each image (test, reference [, transient
// test, transient reference]) with the band gain, the adaptation luminance, the sensitivity of each
// channel after the sensitivity correction; and Q per band × channel at that frame.
struct StageSample {
    int band, x, y;
    double adaptation;
    double contrast[4];
    double sensitivity[2];
};
struct StageGolden {
    const char* caseName;
    int frame;
    double rho[5];
    std::vector<StageSample> samples;
    double q[5][2];
};

const StageGolden kStillStages = {
    "still, noise, 20 ppd, foveated near a corner", 0, {10, 3.228, 1.614, 0.807, 0.4035},
    {
        {0, 40, 30, 9.04689789, {-0.462258279, -0.411428154, 0, 0}, {25.8669701, 0}},
        {0, 80, 45, 21.8917141, {-0.284957141, -0.161598682, 0, 0}, {23.6260586, 0}},
        {0, 120, 60, 26.9669132, {-0.279070884, -0.200865462, 0, 0}, {17.7011013, 0}},
        {1, 20, 15, 16.0525494, {-1.11834502, -1.10110939, 0, 0}, {265.447845, 0}},
        {1, 40, 22, 19.2555084, {0.251031548, 0.242772579, 0, 0}, {209.696732, 0}},
        {1, 60, 30, 29.6337948, {-0.255385041, -0.300807327, 0, 0}, {183.215683, 0}},
        {2, 10, 7, 17.4221992, {-0.841286123, -0.847279727, 0, 0}, {571.348572, 0}},
        {2, 20, 11, 20.0967445, {-0.0280932486, -0.0450051539, 0, 0}, {491.588684, 0}},
        {2, 30, 15, 24.1495228, {0.460926741, 0.465625614, 0, 0}, {433.941101, 0}},
        {3, 5, 4, 20.7787323, {0.096675247, 0.0936359689, 0, 0}, {796.909302, 0}},
        {3, 10, 6, 20.7168999, {-0.0350380465, -0.0477917567, 0, 0}, {759.388367, 0}},
        {3, 15, 8, 20.7503166, {-0.0920230672, -0.0813895091, 0, 0}, {716.174561, 0}},
        {4, 2, 2, 20.9241676, {-0.0150553901, -0.013794166, 0, 0}, {699.616638, 0}},
        {4, 5, 3, 20.7775307, {-0.00447554979, -0.00953732617, 0, 0}, {768.696716, 0}},
        {4, 7, 4, 21.1238861, {-0.045102302, -0.0383665897, 0, 0}, {792.379211, 0}},
    },
    {{5.55044031, 0}, {53.8045998, 0}, {29.8189774, 0}, {19.5449982, 0}, {15.4724207, 0}}};
const StageGolden kVideoStages = {
    "video, moving content blurred, moving fixation, 25 ppd", 5, {12.5, 4.035, 2.0175, 1.00875, 0.504375},
    {
        {0, 24, 24, 30.5761471, {-0.0434769355, -0.0750605091, -0.0321174003, -0.0752626136}, {40.0191422, 29.7567806}},
        {0, 48, 36, 6.53387785, {-0.298536301, -0.376776278, 0.345582485, 0.446328938}, {14.8939571, 11.0298824}},
        {0, 72, 48, 17.9377537, {0.0194259174, -0.302194983, -0.0425977483, -0.0491113402}, {17.7895336, 13.2004242}},
        {1, 12, 12, 31.3047161, {0.00128985581, -0.0975906029, -0.0494861379, -0.0998345837}, {294.994141, 306.983673}},
        {1, 24, 18, 12.1317148, {-0.909668863, -1.09737945, 0.650856137, 0.879190564}, {195.64505, 189.19693}},
        {1, 36, 24, 18.1227417, {0.0124908229, 0.00421910733, -0.0691573545, -0.0982093066}, {181.040802, 165.493439}},
        {2, 6, 6, 25.5915298, {0.535008907, 0.491971284, -0.110835634, -0.0986014605}, {580.024536, 1011.01837}},
        {2, 12, 9, 18.2904072, {-0.815856755, -0.927225709, -0.000371039612, 0.0380964205}, {499.362091, 774.604553}},
        {2, 18, 12, 19.9553623, {-0.192372143, -0.219337568, -0.0120290313, -0.00807056762}, {452.021057, 636.668335}},
        {3, 3, 3, 20.8349705, {0.691008627, 0.710846364, -0.174047455, -0.172199771}, {793.172363, 2646.71289}},
        {3, 6, 4, 20.7573986, {-0.0651650727, -0.0542874075, -0.013614106, -0.0208270531}, {769.704773, 2275.28418}},
        {3, 9, 6, 23.4240379, {-0.307321221, -0.337690234, 0.00362850446, 0.00270002964}, {738.343872, 1931.00317}},
        {4, 1, 1, 22.1372223, {-0.128876612, -0.118259422, 0.024093898, 0.0259661097}, {689.28302, 5177.3833}},
        {4, 3, 2, 24.6387959, {-0.301728517, -0.317302495, -0.00239385059, -0.0030006913}, {744.500061, 4478.07666}},
        {4, 4, 3, 27.879694, {-0.479940295, -0.508089483, -0.00490642805, -0.00644783536}, {760.576721, 4123.45068}},
    },
    {{35.5801849, 13.8513012}, {595.019958, 378.265808}, {807.021179, 858.836792}, {210.885132, 272.065491}, {0.931518734, 5.02837801}}};

// Relative agreement, with an absolute floor for values that float32 cancellation leaves near 0.
bool Agrees(double ours, double theirs, double rel = 1e-3, double floor = 1e-4) {
    return std::abs(ours - theirs) <= rel * std::max(std::abs(theirs), floor);
}

void CheckStages(const StageGolden& g) {
    const GoldenCase& c = CaseNamed(g.caseName);
    const Frames frames = MakeFrames(c);
    const VdpPhotometry photometry = PhotometryOf(c);
    std::vector<Plane<float>> test, ref;
    for (const Plane<float>& p : frames.test) test.push_back(VdpLuminance(p, photometry));
    for (const Plane<float>& p : frames.reference) ref.push_back(VdpLuminance(p, photometry));
    const FovVideoVdp vdp(GeometryOf(c));
    const VdpGeometry& geo = vdp.geometry();
    const int channels = c.frames > 1 ? 2 : 1;

    // Band frequencies.
    const std::vector<double> rho = VdpBandFrequencies(c.w, c.h, geo.PixelsPerDegree());
    REQUIRE(VdpBandCount(c.w, c.h, geo.PixelsPerDegree()) == 5);
    for (int b = 0; b < 5; ++b) CHECK(Agrees(rho[size_t(b)], g.rho[b], 1e-6));

    // Band contrasts and adaptation luminance.
    std::vector<Plane<float>> images;
    if (channels == 2) {
        const VdpTemporalFilters f = MakeVdpTemporalFilters(c.fps, vdp.params());
        for (const auto* taps : {&f.sustained, &f.transient}) {
            images.push_back(VdpFilterFrame(test, g.frame, *taps));
            images.push_back(VdpFilterFrame(ref, g.frame, *taps));
        }
    } else {
        images = {test[0], ref[0]};
    }
    std::vector<const Plane<float>*> inputs;
    for (const Plane<float>& p : images) inputs.push_back(&p);
    const VdpContrastPyramid pyr = VdpDecompose(inputs, 1, 5);
    const VdpOptions options = OptionsOf(c);
    const VdpFixation fix = options.fixations.size() == 1 ? options.fixations[0] : options.fixations[size_t(g.frame)];
    const glm::dvec2 gaze = geo.ViewDirection(fix.x + 0.5, fix.y + 0.5, c.w, c.h, c.w, c.h);
    for (const StageSample& s : g.samples) {
        const Plane<float>& adapt = pyr.adaptation[size_t(s.band)];
        INFO("band " << s.band << " pixel " << s.x << "," << s.y);
        CHECK(Agrees(adapt(s.x, s.y), s.adaptation));
        for (int i = 0; i < 2 * channels; ++i) {
            INFO("image " << i << ": " << pyr.contrast[size_t(s.band)][size_t(i)](s.x, s.y) << " vs " << s.contrast[i]);
            CHECK(Agrees(pyr.contrast[size_t(s.band)][size_t(i)](s.x, s.y), s.contrast[i]));
        }
        // Sensitivity at the pixel's eccentricity and magnified frequency.
        const glm::dvec2 dir = geo.ViewDirection(s.x + 0.5, s.y + 0.5, adapt.width(), adapt.height(), c.w, c.h);
        const double ecc = glm::length(dir - gaze);
        const double band = rho[size_t(s.band)] * geo.ResolutionMagnification(glm::length(dir));
        for (int ch = 0; ch < channels; ++ch) {
            const double sens = vdp.Sensitivity(ch, float(band), adapt(s.x, s.y), float(ecc));
            INFO("channel " << ch << ": S " << sens << " vs " << s.sensitivity[ch]);
            CHECK(Agrees(sens, s.sensitivity[ch]));
        }
    }

    // Per-band, per-channel quality at the frame.
    const VdpResult r = vdp.Score(test, ref, c.fps, options);
    for (int b = 0; b < 5; ++b)
        for (int ch = 0; ch < channels; ++ch) {
            INFO("Q band " << b << " channel " << ch << ": " << r.Q(b, ch, g.frame) << " vs " << g.q[b][ch]);
            CHECK(Agrees(r.Q(b, ch, g.frame), g.q[b][ch]));
        }
}

}  // namespace

TEST_CASE("stage by stage on a still: band frequencies, contrasts, sensitivities and Q within 1e-3", "[vdp]") {
    CheckStages(kStillStages);
}

TEST_CASE("stage by stage on a video frame with both temporal channels and a moving fixation", "[vdp]") {
    CheckStages(kVideoStages);
}

TEST_CASE("masking: the pooled log2 form equals D = |T-R|^p / (1 + (10^c min(|T|,|R|))^q), clamped at 1e4", "[vdp]") {
    const VdpParams prm;
    const float p = float(prm.maskP), q = float(prm.maskQSustained), gain = float(std::pow(10.0, prm.maskC));
    const float log2Gain = float(prm.maskC * std::log2(10.0));
    for (auto [t, r, s] : {std::tuple{0.3f, 0.25f, 40.0f}, {-0.01f, 0.02f, 300.0f}, {1.5f, -2.0f, 800.0f},
                           {0.001f, 0.0f, 20.0f}}) {
        const float d = VdpMaskedDifference(t, r, 1.0f / s, p, q, gain);
        CHECK(std::exp2(VdpLog2MaskedDifference(t, r, s, p, q, log2Gain)) == Approx(d).epsilon(1e-5));
    }
    CHECK(VdpMaskedDifference(50.0f, 0.0f, 0.001f, p, q, gain) == 1e4f);
    CHECK(std::exp2(VdpLog2MaskedDifference(50.0f, 0.0f, 1000.0f, p, q, log2Gain)) == Approx(1e4f));
    CHECK(std::isinf(VdpLog2MaskedDifference(0.2f, 0.2f, 100.0f, p, q, log2Gain)));
}
