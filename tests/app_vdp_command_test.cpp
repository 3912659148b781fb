// `fovrt vdp` (src/app/cmd_vdp.cpp) on frames written to disk: golden cases of the metric
// (tests/vdp_golden_cases.h, values from the reference implementation) written as float EXRs of
// their display-encoded values give the reference's JOD through the command; a PNG sequence gives
// what the library gives on the same 8-bit values; bad input is one error naming the file.
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <tuple>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "app/commands.h"
#include "core/error.h"
#include "io/exr.h"
#include "io/png.h"
#include "metrics/fovvideovdp.h"
#include "test_support.h"
#include "vdp_golden_cases.h"

using namespace fovrt;
using namespace fovrt::vdp_test;
namespace fs = std::filesystem;

namespace {

// Runs `fovrt vdp ARGS... --json out.json` and returns the JSON.
nlohmann::json RunVdp(std::vector<std::string> args, const fs::path& dir) {
    const fs::path json = dir / "out.json";
    fs::remove(json);
    CLI::App app;
    RegisterVdpCommand(app);
    args.insert(args.begin(), "vdp");
    args.push_back("--json");
    args.push_back(json.string());
    std::vector<const char*> argv = {"fovrt"};
    for (const std::string& a : args) argv.push_back(a.c_str());
    app.parse(int(argv.size()), argv.data());
    std::ifstream in(json);
    return nlohmann::json::parse(in);
}

Plane<vec3> Grey(const Plane<float>& p) {
    Plane<vec3> out(p.width(), p.height());
    for (size_t i = 0; i < p.size(); ++i) out[i] = vec3(p[i]);
    return out;
}

// Writes each frame of a case as dir/{test,reference}/frame_NNNN.exr (R = G = B = the value).
void WriteCaseExrs(const GoldenCase& c, const fs::path& dir) {
    const Frames f = MakeFrames(c);
    for (const char* side : {"test", "reference"}) fs::create_directories(dir / side);
    for (int i = 0; i < c.frames; ++i) {
        WriteRgbExr(dir / "test" / fmt::format("frame_{:04d}.exr", i), Grey(f.test[size_t(i)]));
        WriteRgbExr(dir / "reference" / fmt::format("frame_{:04d}.exr", i), Grey(f.reference[size_t(i)]));
    }
}

}  // namespace

TEST_CASE("fovrt vdp on EXR frames gives the reference implementation's JOD (still and gaze-tracked video)", "[vdp]") {
    const fs::path dir = test::ScratchDir("fovrt-vdp-command");
    {
        const GoldenCase& c = CaseNamed("still, noise, 20 ppd");
        WriteCaseExrs(c, dir / "still");
        const nlohmann::json j = RunVdp({(dir / "still/test/frame_0000.exr").string(),
                                         (dir / "still/reference/frame_0000.exr").string(), "--ppd", "20",
                                         "--peak", "100", "--black", "0.1", "--eotf", "srgb"},
                                        dir);
        INFO("fovrt vdp " << j["jod"].get<double>() << ", reference " << c.jod);
        CHECK(std::abs(j["jod"].get<double>() - c.jod) < 0.01);
        CHECK(j["foveated"] == false);
    }
    {
        const GoldenCase& c = CaseNamed("video, dynamic noise, 20 ppd, foveated");
        WriteCaseExrs(c, dir / "video");
        std::ofstream gaze(dir / "gaze.csv");
        gaze << "frame,x,y\n";
        for (int f = 0; f < c.frames; ++f) gaze << f << "," << c.fx0 << "," << c.fy0 << "\n";
        gaze.close();
        const nlohmann::json j = RunVdp({(dir / "video/test").string(), (dir / "video/reference").string(), "--fps",
                                         "30", "--ppd", "20", "--peak", "100", "--black", "0.1", "--eotf", "srgb",
                                         "--gaze", (dir / "gaze.csv").string(), "--diff-maps", (dir / "maps").string()},
                                        dir);
        INFO("fovrt vdp " << j["jod"].get<double>() << ", reference " << c.jod);
        CHECK(std::abs(j["jod"].get<double>() - c.jod) < 0.01);
        CHECK(j["frames"] == 30);
        CHECK(j["foveated"] == true);
        CHECK(j["jod_sustained"].get<double>() < 10.0);
        const ExrImage map = ReadExr(dir / "maps/vdp_diff_0029.exr");
        CHECK((map.width == c.w && map.height == c.h));
        const std::vector<float>& loss = map.Floats("jod_loss");
        CHECK(*std::min_element(loss.begin(), loss.end()) >= 0.0f);
        CHECK(*std::max_element(loss.begin(), loss.end()) > 0.0f);
    }
}

TEST_CASE("fovrt vdp on a PNG sequence scores its 8-bit values like the library, headset profile", "[vdp]") {
    const fs::path dir = test::ScratchDir("fovrt-vdp-command") / "png";
    const GoldenCase c{.name = "png", .w = 96, .h = 72, .frames = 4, .fps = 30, .seed = 9, .noise = 0.05};
    const Frames f = MakeFrames(c);
    const VdpDisplay& display = FindVdpDisplay("headset-15");
    std::vector<Plane<float>> test, ref;
    for (const char* side : {"test", "ref"}) fs::create_directories(dir / side);
    for (int i = 0; i < c.frames; ++i) {
        for (auto [frame, side, out] : {std::tuple{&f.test[size_t(i)], "test", &test}, {&f.reference[size_t(i)], "ref", &ref}}) {
            std::vector<uint8_t> bytes;
            Plane<float> quantised(c.w, c.h);
            for (size_t p = 0; p < frame->size(); ++p) {
                const uint8_t v = uint8_t(std::lround((*frame)[p] * 255.0f));
                bytes.insert(bytes.end(), {v, v, v});
                quantised[p] = v / 255.0f;
            }
            WriteRgb8Png(dir / side / fmt::format("{:02d}.png", i), c.w, c.h, bytes);
            out->push_back(VdpLuminance(quantised, display.photometry));
        }
    }
    const double expected = FovVideoVdp(display.geometry).Score(test, ref, 30).jod;
    const nlohmann::json j = RunVdp({(dir / "test").string(), (dir / "ref").string(), "--display", "headset-15"}, dir);
    CHECK(j["jod"].get<double>() == Approx(expected).margin(1e-4));
    CHECK(j["eotf"] == "srgb");
    CHECK(j["pixels_per_degree"].get<double>() == Approx(15));
    CHECK(expected < 10.0);
}

TEST_CASE("fovrt vdp: bad input is one error naming the file", "[vdp]") {
    const fs::path dir = test::ScratchDir("fovrt-vdp-command") / "errors";
    const GoldenCase c{.name = "errors", .w = 64, .h = 48, .frames = 2, .fps = 30};
    WriteCaseExrs(c, dir / "two");
    const std::string t = (dir / "two/test").string(), r = (dir / "two/reference").string();
    CHECK_THROWS_WITH(RunVdp({(dir / "missing").string(), r}, dir), Catch::Contains("missing: no such file or folder"));
    CHECK_THROWS_WITH(RunVdp({(dir / "two/test/frame_0000.exr").string(), r}, dir), Catch::Contains("has 1 frames but"));
    std::ofstream(dir / "bad.csv") << "frame,x,y\n0,1,2\n1,oops\n";
    CHECK_THROWS_WITH(RunVdp({t, r, "--gaze", (dir / "bad.csv").string()}, dir), Catch::Contains("bad.csv:3: expected 'frame,x,y'"));
    std::ofstream(dir / "short.csv") << "0,1,2\n";
    CHECK_THROWS_WITH(RunVdp({t, r, "--gaze", (dir / "short.csv").string()}, dir), Catch::Contains("no fixation for frame 1"));
    CHECK_THROWS_WITH(RunVdp({t, r, "--display", "rift"}, dir), Catch::Contains("unknown display profile 'rift'"));
    std::ofstream(dir / "two/test/frame_0001.exr") << "not an exr";
    CHECK_THROWS_WITH(RunVdp({t, r}, dir), Catch::Contains("frame_0001.exr"));
}
