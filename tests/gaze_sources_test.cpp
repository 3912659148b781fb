// Gaze sources: Lissajous positions (thesis formula), angle conventions, gaze pixels, traces.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "gaze/sources.h"
#include "test_support.h"

using namespace fovrt;
namespace fs = std::filesystem;

namespace {

// The thesis formula: centre + sin(2π t (0.4, 0.5) + (π/2, 0)) ⊙ (640, 360) on 1280×720.
vec2 ThesisPixel(double t) {
    return vec2(640.0 + 640.0 * std::sin(2.0 * M_PI * t * 0.4 + M_PI / 2.0),
                360.0 + 360.0 * std::sin(2.0 * M_PI * t * 0.5));
}

std::vector<GazeTraceSample> Parse(const std::string& text) {
    std::istringstream in(text);
    return ParseGazeTraceCsv(in, "trace.csv");
}

}  // namespace

TEST_CASE("Lissajous matches the thesis formula at t = 0, 0.625 s, 1.25 s", "[gaze]") {
    Fov fov = Fov::FromHorizontal(Radians(90.0f), 16.0f / 9.0f);
    GazeParams params;  // defaults = thesis
    auto source = CreateGazeSource(params, fov);
    CHECK(source->Name() == "lissajous");
    auto* lissajous = dynamic_cast<LissajousGaze*>(source.get());
    REQUIRE(lissajous);

    // Closed-form values: t=0 -> (1280, 360); t=0.625 -> (640, 360+360 sin(5π/8)); t=1.25 -> (0, 360+360 sin(5π/4)).
    CHECK(ThesisPixel(0.0).x == Approx(1280.0));
    CHECK(ThesisPixel(0.625).x == Approx(640.0).margin(1e-3));
    CHECK(ThesisPixel(1.25).x == Approx(0.0).margin(1e-3));
    CHECK(ThesisPixel(1.25).y == Approx(360.0 - 360.0 * std::sqrt(0.5)));

    EyeCamera eye1280(Pose(), fov, 1280, 720);
    EyeCamera eye640(Pose(), fov, 640, 360);
    for (double t : {0.0, 0.625, 1.25, 3.3}) {
        vec2 expected = ThesisPixel(t);
        vec2 curve = lissajous->CurveAt(t);
        CHECK(curve.x == Approx(expected.x).margin(1e-3));
        CHECK(curve.y == Approx(expected.y).margin(1e-3));
        GazeSample s = source->At(t);
        CHECK(s.valid);
        CHECK(s.timeSeconds == t);
        CHECK(glm::length(s.direction) == Approx(1.0f));
        // Back through the eye cameras: the same pixel at 1280×720, half of it at 640×360.
        vec2 p = GazePixel(eye1280, s.direction);
        CHECK(p.x == Approx(expected.x).margin(0.05));
        CHECK(p.y == Approx(expected.y).margin(0.05));
        vec2 q = GazePixel(eye640, s.direction);
        CHECK(q.x == Approx(expected.x / 2).margin(0.05));
        CHECK(q.y == Approx(expected.y / 2).margin(0.05));
    }
    // t = 0 is at the right edge of the image: yaw = +45° for a 90° horizontal FOV; pitch 0.
    vec2 angles = GazeAnglesFromDirection(source->At(0.0).direction);
    CHECK(angles.x == Approx(45.0f).margin(1e-3));
    CHECK(angles.y == Approx(0.0f).margin(1e-3));
}

TEST_CASE("Lissajous in degrees and static gaze", "[gaze]") {
    GazeParams params;
    params.units = "deg";
    params.amplitude = vec2(20.0f, 10.0f);
    params.frequencyHz = vec2(1.0f, 0.25f);
    params.phaseDeg = vec2(0.0f, 90.0f);
    auto source = CreateGazeSource(params, Fov());
    vec2 a = GazeAnglesFromDirection(source->At(0.25).direction);  // sin(π/2) = 1; sin(π/8+π/2)
    CHECK(a.x == Approx(20.0f).margin(1e-3));
    CHECK(a.y == Approx(10.0f * std::cos(M_PI / 8.0)).margin(1e-3));

    GazeParams s;
    s.source = "static";
    s.yawDeg = 10.0f;
    s.pitchDeg = -5.0f;
    auto fixed = CreateGazeSource(s, Fov());
    vec3 d = fixed->At(123.0).direction;
    // Fick: yaw about up, then pitch.
    CHECK(d.x == Approx(std::sin(Radians(10.0f)) * std::cos(Radians(5.0f))));
    CHECK(d.y == Approx(-std::sin(Radians(5.0f))));
    CHECK(d.z == Approx(-std::cos(Radians(10.0f)) * std::cos(Radians(5.0f))));
    vec2 back = GazeAnglesFromDirection(d);
    CHECK(back.x == Approx(10.0f));
    CHECK(back.y == Approx(-5.0f));
    // Right and up on the image: positive yaw -> right of centre, positive pitch -> above.
    EyeCamera eye(Pose(), Fov::FromHorizontal(Radians(90.0f), 1.0f), 100, 100);
    vec2 p = GazePixel(eye, GazeDirectionFromAngles(10.0f, 10.0f));
    CHECK(p.x > 50.0f);
    CHECK(p.y < 50.0f);

    GazeParams bad;
    bad.source = "mouse";
    CHECK_THROWS_WITH(CreateGazeSource(bad, Fov()), Catch::Contains("gaze.source"));
    bad = GazeParams();
    bad.source = "trace";
    CHECK_THROWS_WITH(CreateGazeSource(bad, Fov()), Catch::Contains("gaze.trace_path"));
}

TEST_CASE("Trace: linear interpolation, clamping, invalid samples", "[gaze]") {
    auto samples = Parse(
        "# recorded with a test rig\n"
        "n, x, y, lx\n"
        "0, 0, 0, 1\n"
        "10, 10, -4, 1\n"
        "20, NaN, NaN, 1\n"
        "30, 2, 2, 1\n"
        "\n"
        "40, 4, 6, 1\r\n");
    REQUIRE(samples.size() == 5);
    CHECK(!samples[2].valid);
    TraceGaze trace(samples);
    auto angles = [&](double t) { return GazeAnglesFromDirection(trace.At(t).direction); };
    CHECK(angles(0.005).x == Approx(5.0f).margin(1e-4));   // half-way between rows 1 and 2
    CHECK(angles(0.005).y == Approx(-2.0f).margin(1e-4));
    CHECK(angles(0.0025).x == Approx(2.5f).margin(1e-4));
    CHECK(angles(0.035).x == Approx(3.0f).margin(1e-4));
    CHECK(angles(0.035).y == Approx(4.0f).margin(1e-4));
    CHECK(trace.At(0.035).valid);
    // Clamped outside the trace.
    CHECK(angles(-1.0).x == Approx(0.0f).margin(1e-4));
    CHECK(angles(100.0).x == Approx(4.0f).margin(1e-4));
    CHECK(angles(100.0).y == Approx(6.0f).margin(1e-4));
    // Around the blink: invalid, holding the last valid direction.
    CHECK(!trace.At(0.015).valid);
    CHECK(!trace.At(0.025).valid);
    CHECK(angles(0.025).x == Approx(10.0f).margin(1e-4));
    // A start offset shifts the timeline.
    TraceGaze shifted(samples, 30.0);
    CHECK(GazeAnglesFromDirection(shifted.At(0.005).direction).x == Approx(3.0f).margin(1e-4));
    // Columns in another order, extra columns, time_ms header.
    auto other = Parse("y,foo,X,time_ms\n1,a,2,5\n3,b,4,15\n");
    REQUIRE(other.size() == 2);
    CHECK(other[1].timeMs == 15.0);
    CHECK(other[1].yawDeg == 4.0f);
    CHECK(other[1].pitchDeg == 3.0f);
}

TEST_CASE("Trace errors name the file and line", "[gaze]") {
    CHECK_THROWS_WITH(Parse("n,x,y\n0,1,2\n5,abc,2\n"), Catch::Contains("trace.csv:3") && Catch::Contains("abc"));
    CHECK_THROWS_WITH(Parse("n,x,y\n0,1,2\n\n10,1\n"), Catch::Contains("trace.csv:4"));
    CHECK_THROWS_WITH(Parse("n,x,y\n10,1,2\n5,1,2\n"), Catch::Contains("trace.csv:3") && Catch::Contains("backwards"));
    CHECK_THROWS_WITH(Parse("t,x,y\n0,1,2\n"), Catch::Contains("trace.csv:1") && Catch::Contains("header"));
    CHECK_THROWS_WITH(Parse("n,x,y\n0,95,2\n"), Catch::Contains("trace.csv:2") && Catch::Contains("range"));
    CHECK_THROWS_WITH(Parse("n,x,y\n0,inf,2\n"), Catch::Contains("trace.csv:2"));
    CHECK_THROWS_WITH(Parse("n,x,y\nnan,1,2\n"), Catch::Contains("trace.csv:2"));
    CHECK_THROWS_WITH(Parse("n,x,y\n0,1.5x,2\n"), Catch::Contains("trace.csv:2"));
    CHECK_THROWS_WITH(Parse("n,x,y\n"), Catch::Contains("no samples"));
    CHECK_THROWS_WITH(Parse(""), Catch::Contains("trace.csv"));
    CHECK_THROWS_WITH(Parse("n,x,y\n0,nan,nan\n"), Catch::Contains("no valid sample"));
    // A column named twice (or both time columns): reading the first would be a guess.
    CHECK_THROWS_WITH(Parse("n,x,y,x\n0,1,2,3\n"),
                      Catch::Contains("trace.csv:1: column 'x' appears twice (fields 2 and 4)"));
    CHECK_THROWS_WITH(Parse("# rig\ntime_ms,x,y,n\n0,1,2,3\n"),
                      Catch::Contains("trace.csv:2: gaze trace header names both n and time_ms"));
    // A UTF-8 byte-order mark (spreadsheets write one) is skipped, not read into the first name.
    auto marked = Parse("\xEF\xBB\xBFn,x,y\n0,1,2\n");
    REQUIRE(marked.size() == 1);
    CHECK(marked[0].yawDeg == 1.0f);

    // Through the factory, from a file: the message carries the path.
    fs::path dir = fs::temp_directory_path() / fmt::format("fovrt_gaze_test_{}", ::getpid());
    fs::create_directories(dir);
    {
        std::ofstream out(dir / "bad.csv");
        out << "n,x,y\n0,0,0\n8,0,zz\n";
    }
    GazeParams p;
    p.source = "trace";
    p.tracePath = (dir / "bad.csv").string();
    CHECK_THROWS_WITH(CreateGazeSource(p, Fov()), Catch::Contains("bad.csv:3"));
    p.tracePath = (dir / "missing.csv").string();
    CHECK_THROWS_WITH(CreateGazeSource(p, Fov()), Catch::Contains("missing.csv"));
    // A directory opens as a stream that reads nothing: say what it is, not "empty gaze trace".
    fs::create_directories(dir / "traces");
    p.tracePath = (dir / "traces").string();
    CHECK_THROWS_WITH(CreateGazeSource(p, Fov()), Catch::Equals((dir / "traces").string() +
                                                                ": is a directory, not a gaze trace (CSV)"));
    {
        std::ofstream out(dir / "good.csv");
        out << "n,x,y\n100,0,0\n200,10,0\n";
    }
    p.tracePath = (dir / "good.csv").string();
    auto source = CreateGazeSource(p, Fov());
    CHECK(source->Name() == "trace");
    CHECK(GazeAnglesFromDirection(source->At(0.05).direction).x == Approx(5.0f).margin(1e-4));
    fs::remove_all(dir);
}
