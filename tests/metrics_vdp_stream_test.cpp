// VdpStream (src/metrics/vdp_stream.h), FovVideoVDP one frame at a time: each frame's difference
// map is the one FovVideoVdp::Score gives for that frame of the whole sequence (the golden video
// with moving content and a moving fixation: both temporal channels, the padding before the first
// frame, frames leaving the window), and Reset starts a new sequence. Score's firstScoredFrame,
// which the stream uses, scores only the frames from there on.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "core/error.h"
#include "metrics/vdp_stream.h"
#include "metrics/vdp_temporal.h"
#include "vdp_golden_cases.h"

using namespace fovrt;
using namespace fovrt::vdp_test;

namespace {

const GoldenCase& MovingFixationCase() {
    for (const GoldenCase& c : GoldenCases())
        if (std::string(c.name) == "video, moving content blurred, moving fixation, 25 ppd") return c;
    FAIL("golden case missing");
    return GoldenCases().front();
}

struct Sequence {
    std::vector<Plane<float>> test, reference;
    VdpOptions options;
};

Sequence Luminance(const GoldenCase& c) {
    const Frames frames = MakeFrames(c);
    Sequence s;
    for (const Plane<float>& p : frames.test) s.test.push_back(VdpLuminance(p, PhotometryOf(c)));
    for (const Plane<float>& p : frames.reference) s.reference.push_back(VdpLuminance(p, PhotometryOf(c)));
    s.options = OptionsOf(c);
    s.options.diffMaps = true;
    return s;
}

double MaxAbsDifference(const Plane<float>& a, const Plane<float>& b) {
    REQUIRE(a.width() == b.width());
    REQUIRE(a.height() == b.height());
    double worst = 0.0;
    for (size_t i = 0; i < a.size(); ++i) worst = std::max(worst, double(std::abs(a[i] - b[i])));
    return worst;
}

}  // namespace

TEST_CASE("a stream's map of each frame is Score's map of that frame of the whole sequence", "[vdp]") {
    const GoldenCase& c = MovingFixationCase();
    const Sequence s = Luminance(c);
    const VdpResult whole = FovVideoVdp(GeometryOf(c)).Score(s.test, s.reference, c.fps, s.options);
    REQUIRE(whole.diffMaps.size() == s.test.size());
    VdpStream stream(GeometryOf(c), c.fps);
    double peak = 0.0;
    for (size_t f = 0; f < s.test.size(); ++f) {
        const Plane<float> map = stream.Next(s.test[f], s.reference[f], s.options.fixations[f]);
        for (float v : whole.diffMaps[f].vector()) peak = std::max(peak, double(v));
        INFO("frame " << f);
        CHECK(MaxAbsDifference(map, whole.diffMaps[f]) <= 1e-6);
    }
    CHECK(peak > 1e-4);  // the maps compared are not all zero
    CHECK(stream.Held() == size_t(VdpTemporalFilterLength(c.fps)));
    // After Reset the next frame is a sequence's first again.
    stream.Reset();
    CHECK(stream.Held() == 0);
    const Plane<float> restarted = stream.Next(s.test[5], s.reference[5], s.options.fixations[5]);
    // Score pads before a sequence's first frame with that frame: two copies, the second scored.
    const std::vector<Plane<float>> t5(2, s.test[5]), r5(2, s.reference[5]);
    VdpOptions one = s.options;
    one.fixations.assign(2, s.options.fixations[5]);
    one.firstScoredFrame = 1;
    const VdpResult still = FovVideoVdp(GeometryOf(c)).Score(t5, r5, c.fps, one);
    CHECK(MaxAbsDifference(restarted, still.diffMaps[0]) <= 1e-6);
}

TEST_CASE("firstScoredFrame: the frames before it only feed the temporal filters", "[vdp]") {
    const GoldenCase& c = MovingFixationCase();
    const Sequence s = Luminance(c);
    const FovVideoVdp vdp(GeometryOf(c));
    const VdpResult whole = vdp.Score(s.test, s.reference, c.fps, s.options);
    VdpOptions tail = s.options;
    tail.firstScoredFrame = 20;
    const VdpResult last = vdp.Score(s.test, s.reference, c.fps, tail);
    REQUIRE(last.frames == whole.frames - 20);
    REQUIRE(last.diffMaps.size() == size_t(last.frames));
    for (int f = 0; f < last.frames; ++f)
        for (int ch = 0; ch < last.channels; ++ch)
            for (int b = 0; b < last.bands; ++b) CHECK(last.Q(b, ch, f) == whole.Q(b, ch, f + 20));
    CHECK(MaxAbsDifference(last.diffMaps[0], whole.diffMaps[20]) == 0.0);
    tail.firstScoredFrame = whole.frames;
    CHECK_THROWS_AS(vdp.Score(s.test, s.reference, c.fps, tail), Error);
}
