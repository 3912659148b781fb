// EXR/PNG I/O: bit-exact FrameInputs round trip, RGB round trip, atomic writes, error messages.
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>

#include "core/error.h"
#include "core/rng.h"
#include "io/exr.h"
#include "io/png.h"
#include "render/visibility_buffer.h"
#include "test_support.h"

using namespace fovrt;
namespace fs = std::filesystem;

namespace {

fs::path TempDir(const char* name) {
    fs::path dir = fs::temp_directory_path() / fmt::format("fovrt_io_test_{}_{}", name, ::getpid());
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

template <typename T>
bool BitEqual(const Plane<T>& a, const Plane<T>& b) {
    return a.width() == b.width() && a.height() == b.height() &&
           std::memcmp(a.data(), b.data(), a.bytes()) == 0;
}

float RandomFloat(Pcg32& rng) { return (rng.NextFloat() - 0.5f) * 1000.0f * rng.NextFloat(); }

// Random FrameInputs, and a random renderer visibility buffer in `vis` (its extra EXR layers).
FrameInputs RandomInputs(int w, int h, VisibilityBuffer& vis) {
    Pcg32 rng(42);
    FrameInputs fi;
    fi.Allocate(w, h);
    vis.Allocate(w, h);
    fi.eye = 1;
    fi.frameIndex = 0xFFFFFFF0u;  // does not fit a signed int: must still round-trip
    fi.timeSeconds = 1.0 / 3.0;
    fi.cameraCut = true;
    fi.camera = EyeCamera(Pose::LookAt(vec3(1, 2, 3), vec3(0, 1, 0)), Fov{-0.8f, 0.7f, 0.6f, -0.5f}, w, h);
    fi.prevCamera = EyeCamera(Pose::LookAt(vec3(1.1f, 2, 3), vec3(0, 1, 0)), Fov{-0.8f, 0.7f, 0.6f, -0.5f}, w, h);
    for (size_t i = 0; i < fi.direct.size(); ++i) {
        auto v3 = [&] { return vec3(RandomFloat(rng), RandomFloat(rng), RandomFloat(rng)); };
        auto v2 = [&] { return vec2(RandomFloat(rng), RandomFloat(rng)); };
        fi.direct[i] = v3();
        fi.indirect[i] = v3();
        fi.albedo[i] = v3();
        fi.emission[i] = v3();
        fi.normal[i] = v3();
        fi.linearDepth[i] = i % 7 == 0 ? std::numeric_limits<float>::infinity() : RandomFloat(rng);
        fi.depthGradient[i] = v2();
        fi.objectId[i] = i % 5 == 0 ? kNoObject : rng.Next();
        fi.prevPixel[i] = v2();
        vis.primitiveId[i] = rng.Next();
        vis.barycentrics[i] = v2();
        vis.worldPosition[i] = v3();
        fi.sampleCount[i] = uint16_t(1 + rng.NextBounded(16));
        vis.seed[i] = rng.Next();
    }
    fi.direct[3] = vec3(1e-40f, -0.0f, std::numeric_limits<float>::max());  // denormal, -0, max
    fi.gradientSamples.push_back(GradientSample{ivec2(1, 2), ivec2(4, 7), ivec2(3, 8), 0.25f, 1e-7f});
    fi.gradientSamples.push_back(GradientSample{ivec2(20, 0), ivec2(61, 2), ivec2(60, 1), 3.5f, 100.0f});
    fi.gazePixel = vec2(17.25f, -3.5f);
    return fi;
}

}  // namespace

TEST_CASE("FrameInputs round-trip through EXR bit-exactly", "[io]") {
    const int w = 64, h = 48;
    VisibilityBuffer vis;
    FrameInputs fi = RandomInputs(w, h, vis);
    Plane<uint16_t> spp(w, h);
    for (size_t i = 0; i < spp.size(); ++i) spp[i] = uint16_t(1 + i % 16);
    fs::path dir = TempDir("frame");
    fs::path path = dir / "frame.exr";
    WriteFrameInputsExr(path, fi, spp, PlaneLayers(vis));
    REQUIRE(fs::exists(path));

    Plane<uint16_t> sppBack;
    FrameInputs back = ReadFrameInputsExr(path, &sppBack);
    CHECK(BitEqual(fi.direct, back.direct));
    CHECK(BitEqual(fi.indirect, back.indirect));
    CHECK(BitEqual(fi.albedo, back.albedo));
    CHECK(BitEqual(fi.emission, back.emission));
    CHECK(BitEqual(fi.normal, back.normal));
    CHECK(BitEqual(fi.linearDepth, back.linearDepth));
    CHECK(BitEqual(fi.depthGradient, back.depthGradient));
    CHECK(BitEqual(fi.objectId, back.objectId));
    CHECK(BitEqual(fi.prevPixel, back.prevPixel));
    CHECK(BitEqual(fi.sampleCount, back.sampleCount));
    VisibilityBuffer visBack;
    ReadPlaneLayers(ReadExr(path), visBack);
    CHECK(BitEqual(vis.primitiveId, visBack.primitiveId));
    CHECK(BitEqual(vis.barycentrics, visBack.barycentrics));
    CHECK(BitEqual(vis.worldPosition, visBack.worldPosition));
    CHECK(BitEqual(vis.seed, visBack.seed));
    CHECK(BitEqual(spp, sppBack));
    CHECK(back.eye == 1);
    CHECK(back.frameIndex == 0xFFFFFFF0u);
    CHECK(back.timeSeconds == fi.timeSeconds);
    CHECK(back.cameraCut);
    CHECK(back.camera.width() == w);
    CHECK(back.camera.View() == fi.camera.View());
    CHECK(back.prevCamera.ViewProjection() == fi.prevCamera.ViewProjection());
    REQUIRE(back.gradientSamples.size() == 2);
    CHECK(back.gradientSamples[1].pixel == ivec2(61, 2));
    CHECK(back.gradientSamples[1].prevPixel == ivec2(60, 1));
    CHECK(back.gradientSamples[0].oldLuminance == 1e-7f);
    REQUIRE(back.gazePixel.has_value());
    CHECK(*back.gazePixel == vec2(17.25f, -3.5f));
    // A frame without a gaze (a dump from before it was recorded) reads back without one.
    fi.gazePixel.reset();
    WriteFrameInputsExr(dir / "nogaze.exr", fi, spp, PlaneLayers(vis));
    CHECK(!ReadFrameInputsExr(dir / "nogaze.exr").gazePixel.has_value());

    // Every plane name is a layer in the file, with the documented channel names.
    ExrImage image = ReadExr(path);
    CHECK(image.Has("direct.R"));
    CHECK(image.Has("normal.Z"));
    CHECK(image.Has("barycentrics.V"));
    CHECK(image.channels.at("objectId").isUint);
    CHECK(image.channels.at("spp").isUint);
    CHECK(image.channels.at("sampleCount").isUint);
    std::vector<std::string> names = FrameInputs::PlaneNames();
    vis.VisitPlanes([&](const PlaneSpec& spec, const auto&) { names.push_back(spec.name); });
    for (const std::string& name : names) {
        bool found = false;
        for (const auto& [channel, data] : image.channels)
            found = found || channel == name || channel.rfind(name + ".", 0) == 0;
        CHECK(found);
    }
    fs::remove_all(dir);
}

TEST_CASE("RGB EXR round trip, half storage and layers", "[io]") {
    fs::path dir = TempDir("rgb");
    Plane<vec3> img(16, 8);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 16; ++x) img(x, y) = vec3(x * 0.1f, y * 0.37f, 1.0f / (1 + x + y));
    WriteRgbExr(dir / "a.exr", img);
    CHECK(BitEqual(img, ReadRgbExr(dir / "a.exr")));

    WriteRgbExr(dir / "h.exr", img, ExrStorage::Half);
    Plane<vec3> half = ReadRgbExr(dir / "h.exr");
    float maxRel = 0;
    for (size_t i = 0; i < img.size(); ++i)
        for (int c = 0; c < 3; ++c)
            maxRel = std::max(maxRel, std::abs(half[i][c] - img[i][c]) / std::max(img[i][c], 1e-3f));
    CHECK(maxRel < 1e-3f);  // half has 11 significant bits
    CHECK(maxRel > 0.0f);   // and it really was stored as half

    // Generic layers: a named RGB layer is found with ReadRgbExr(path, layer).
    Plane<float> depth(16, 8, 2.5f);
    WriteExrLayers(dir / "l.exr", 16, 8,
                   {ExrLayer::FromPlane("denoised", img), ExrLayer::FromPlane("depth", depth)});
    CHECK(BitEqual(img, ReadRgbExr(dir / "l.exr", "denoised")));
    CHECK(ReadExr(dir / "l.exr").Floats("depth")[5] == 2.5f);
    fs::remove_all(dir);
}

TEST_CASE("EXR read errors name the file", "[io]") {
    fs::path dir = TempDir("err");
    fs::path missing = dir / "missing.exr";
    CHECK_THROWS_WITH(ReadExr(missing), Catch::Contains("missing.exr"));
    fs::path corrupt = dir / "corrupt.exr";
    {
        std::ofstream out(corrupt, std::ios::binary);
        out << "v/1\x01garbage that is not an EXR file";
    }
    CHECK_THROWS_AS(ReadExr(corrupt), Error);
    CHECK_THROWS_WITH(ReadExr(corrupt), Catch::Contains("corrupt.exr"));

    // Truncated file: a valid header with most pixel data cut off.
    Plane<vec3> img(64, 64, vec3(1, 2, 3));
    WriteRgbExr(dir / "full.exr", img);
    fs::path truncated = dir / "truncated.exr";
    fs::copy_file(dir / "full.exr", truncated);
    fs::resize_file(truncated, fs::file_size(truncated) / 2);
    CHECK_THROWS_WITH(ReadRgbExr(truncated), Catch::Contains("truncated.exr"));

    // An RGB EXR is not a FrameInputs dump; a missing channel is named.
    CHECK_THROWS_WITH(ReadFrameInputsExr(dir / "full.exr"), Catch::Contains("full.exr"));
    CHECK_THROWS_WITH(ReadRgbExr(dir / "full.exr", "direct"), Catch::Contains("direct.R"));
    fs::remove_all(dir);
}

TEST_CASE("Writers are atomic: no final file when the writer throws", "[io]") {
    fs::path dir = TempDir("atomic");
    // Two layers producing the same channel name: WriteExrLayers throws before renaming.
    Plane<vec3> img(8, 8, vec3(1));
    CHECK_THROWS_AS(WriteExrLayers(dir / "dup.exr", 8, 8,
                                   {ExrLayer::FromPlane("a", img), ExrLayer::FromPlane("a", img)}),
                    Error);
    CHECK(!fs::exists(dir / "dup.exr"));
    // Target path is a directory: writing fails and leaves neither the file nor a temp file.
    fs::create_directories(dir / "isdir.exr");
    CHECK_THROWS(WriteRgbExr(dir / "isdir.exr", img));
    CHECK(fs::is_directory(dir / "isdir.exr"));
    int entries = 0;
    for (auto& e : fs::directory_iterator(dir)) entries += e.path().filename().string().find(".tmp-") != std::string::npos;
    CHECK(entries == 0);
    // An existing good file is not clobbered by a failed rewrite.
    WriteRgbExr(dir / "good.exr", img);
    CHECK_THROWS(WriteExrLayers(dir / "good.exr", 8, 8,
                                {ExrLayer::FromPlane("a", img), ExrLayer::FromPlane("a", img)}));
    CHECK(BitEqual(img, ReadRgbExr(dir / "good.exr")));
    fs::remove_all(dir);
}

TEST_CASE("PNG tonemap and encoding", "[io]") {
    Plane<vec3> img(4, 2, vec3(0.0f));
    img(1, 0) = vec3(1.0f, 0.5f, 2.0f);
    img(2, 0) = vec3(std::numeric_limits<float>::quiet_NaN(), -1.0f, 0.0031308f);
    img(3, 0) = vec3(0.25f);
    std::vector<uint8_t> rgb = TonemapToRgb8(img);
    CHECK(rgb[3] == 255);   // 1.0 -> 255
    CHECK(rgb[4] == 188);   // sRGB(0.5) = 0.7354 -> 188
    CHECK(rgb[5] == 255);   // clamp
    CHECK(rgb[6] == 0);     // NaN -> 0
    CHECK(rgb[7] == 0);     // negative -> 0
    CHECK(rgb[8] == 10);    // 12.92 * 0.0031308 * 255 = 10.3
    // Exposure +1 stop doubles: 0.25 -> 0.5.
    CHECK(TonemapToRgb8(img, 1.0f)[9] == 188);
    // Reinhard: 1 -> 0.5.
    CHECK(TonemapToRgb8(img, 0.0f, Tonemap::Reinhard)[3] == 188);

    std::vector<uint8_t> png = EncodePngToMemory(img);
    REQUIRE(png.size() > 8);
    CHECK(png[0] == 0x89);
    CHECK(png[1] == 'P');
    CHECK(png[2] == 'N');
    CHECK(png[3] == 'G');
    fs::path dir = TempDir("png");
    WritePng(dir / "a.png", img);
    CHECK(fs::file_size(dir / "a.png") == png.size());
    fs::remove_all(dir);
}
