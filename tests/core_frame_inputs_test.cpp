// FrameInputs' plane list: fields, Allocate's neutral values, Bytes, PlaneNames and ForEachPlane
// all come from FOVRT_FRAME_INPUT_PLANES and agree with each other.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/frame_inputs.h"
#include "test_support.h"

using namespace fovrt;

TEST_CASE("Allocate gives every plane its size and neutral (background) value", "[core]") {
    FrameInputs f;
    f.gradientSamples.push_back(GradientSample{});
    f.Allocate(5, 3);
    CHECK(f.gradientSamples.empty());
    f.VisitPlanes([&](const PlaneSpec& spec, const auto& plane) {
        INFO(spec.name);
        CHECK(plane.width() == 5);
        CHECK(plane.height() == 3);
    });
    CHECK(f.direct(4, 2) == vec3(0.0f));
    CHECK(f.normal(0, 0) == vec3(0.0f));
    CHECK(std::isinf(f.linearDepth(2, 1)));
    CHECK(f.objectId(1, 1) == kNoObject);
    CHECK(f.prevPixel(3, 0) == vec2(0.0f));
    CHECK(f.sampleCount(0, 2) == 1);
}

TEST_CASE("ForEachPlane, PlaneNames and Bytes describe the same planes", "[core]") {
    FrameInputs f;
    f.Allocate(7, 4);
    std::vector<std::string> names;
    size_t bytes = 0;
    f.ForEachPlane([&](const PlaneBytes& p) {
        INFO(p.name);
        names.push_back(p.name);
        CHECK(p.bytes == p.elementSize * 7 * 4);
        bytes += p.bytes;
    });
    CHECK(names == FrameInputs::PlaneNames());
    CHECK(names.front() == "direct");
    CHECK(f.Bytes() == bytes);
    // 6 RGB planes (direct, indirect, albedo, fbeta, emission, normal), depth, depth gradient,
    // object id, motion, sample count, roughness.
    CHECK(bytes == size_t(7 * 4) * (6 * 12 + 4 + 8 + 4 + 8 + 2 + 4));
    f.gradientSamples.resize(3);
    CHECK(f.Bytes() == bytes + 3 * sizeof(GradientSample));
    // The data pointers are the planes' own, with their element sizes.
    f.ForEachPlane([&](const PlaneBytes& p) {
        const std::string name = p.name;
        if (name == "linearDepth") CHECK((p.data == f.linearDepth.data() && p.elementSize == 4));
        if (name == "sampleCount") CHECK((p.data == f.sampleCount.data() && p.elementSize == 2));
    });
}

TEST_CASE("the renderer's visibility buffer is not part of FrameInputs", "[core]") {
    for (const char* name : {"primitiveId", "barycentrics", "worldPosition", "seed"}) {
        INFO(name);
        const std::vector<std::string>& names = FrameInputs::PlaneNames();
        CHECK(std::find(names.begin(), names.end(), name) == names.end());
    }
}
