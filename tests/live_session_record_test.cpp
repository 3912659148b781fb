// Session recordings (session/session_record.h): a written recording reads back bit-identical (free
// poses, asymmetric FOVs, gaze samples, true and tracked gaze, any finite float; a recording
// without tracked gaze reads as rendered with its true gaze), stays readable after every line (a
// killed session), and a truncated or corrupt one is refused with one line naming the file, the
// line and the frame.
#include <unistd.h>

#include <bit>
#include <cstring>
#include <fstream>
#include <functional>
#include <limits>
#include <sstream>

#include "core/error.h"
#include "core/rng.h"
#include "gaze_test_support.h"
#include "session/session_record.h"
#include "test_support.h"

using namespace fovrt;
namespace fs = std::filesystem;

namespace {

fs::path TempDir() { return test::ScratchDir("fovrt-session-test"); }

// Any finite float (all exponents, subnormals and signed zeros included).
float AnyFiniteFloat(Pcg32& rng) {
    while (true) {
        const float f = std::bit_cast<float>(rng.Next());
        if (std::isfinite(f)) return f;
    }
}

double AnyFiniteDouble(Pcg32& rng) {
    while (true) {
        const double d = std::bit_cast<double>((uint64_t(rng.Next()) << 32) | rng.Next());
        if (std::isfinite(d)) return d;
    }
}

float Uniform(Pcg32& rng, float lo, float hi) { return lo + (hi - lo) * rng.NextFloat(); }

quat RandomRotation(Pcg32& rng) {
    vec4 v;
    do v = vec4(Uniform(rng, -1, 1), Uniform(rng, -1, 1), Uniform(rng, -1, 1), Uniform(rng, -1, 1));
    while (glm::length(v) < 0.1f);
    v = glm::normalize(v);
    return quat(v.w, v.x, v.y, v.z);
}

vec3 RandomDirection(Pcg32& rng) {
    vec3 v;
    do v = vec3(Uniform(rng, -1, 1), Uniform(rng, -1, 1), Uniform(rng, -1, 1));
    while (glm::length(v) < 0.1f);
    return glm::normalize(v);
}

// A frame off any scene path: free head and eye poses, asymmetric FOVs, a burst of gaze samples.
RecordedFrame RandomFrame(Pcg32& rng, uint32_t frame) {
    RecordedFrame out;
    out.request.frame = frame;
    out.request.timeSeconds = rng.NextBounded(4) == 0 ? AnyFiniteDouble(rng) : frame / 90.0 + 1e-7 * rng.NextFloat();
    out.head = Pose{RandomRotation(rng), vec3(AnyFiniteFloat(rng), Uniform(rng, -5, 5), AnyFiniteFloat(rng))};
    for (EyeCamera& eye : out.request.eyes) {
        Fov fov{-Uniform(rng, 0.05f, 1.5f), Uniform(rng, 0.05f, 1.5f), Uniform(rng, 0.05f, 1.5f),
                -Uniform(rng, 0.05f, 1.5f)};
        Pose pose{RandomRotation(rng), vec3(AnyFiniteFloat(rng), AnyFiniteFloat(rng), Uniform(rng, -1, 1))};
        eye = EyeCamera(pose, fov, 1 + int(rng.NextBounded(4000)), 1 + int(rng.NextBounded(3000)));
    }
    const int samples = int(rng.NextBounded(5));
    double t = out.request.timeSeconds;
    for (int i = 0; i < samples; ++i) {
        t += 1e-3 * rng.NextFloat();
        out.gazeSamples.push_back(GazeSample{t, RandomDirection(rng), rng.NextBounded(8) != 0});
    }
    out.request.gaze = out.gazeSamples.empty() ? GazeSample{t, RandomDirection(rng), true} : out.gazeSamples.back();
    if (rng.NextBounded(6) == 0) out.request.gaze = GazeSample{t, vec3(0.0f), false};  // tracker lost
    if (rng.NextBounded(3) == 0) {  // a tracker model: the spp maps followed another gaze
        out.request.trueGaze = out.request.gaze;
        out.request.gaze = GazeSample{t, RandomDirection(rng), rng.NextBounded(8) != 0};
    }
    return out;
}

template <class T>
bool SameBits(const T& a, const T& b) {
    return std::memcmp(&a, &b, sizeof(T)) == 0;
}

bool SamePose(const Pose& a, const Pose& b) {
    return SameBits(a.position, b.position) && SameBits(a.orientation, b.orientation);
}

bool SameEye(const EyeCamera& a, const EyeCamera& b) {
    return SamePose(a.pose(), b.pose()) && SameBits(a.fov(), b.fov()) && a.width() == b.width() &&
           a.height() == b.height() && SameBits(a.View(), b.View()) &&
           SameBits(a.ProjectionMatrix(), b.ProjectionMatrix());
}

bool SameFrame(const RecordedFrame& a, const RecordedFrame& b) {
    if (a.request.frame != b.request.frame || !SameBits(a.request.timeSeconds, b.request.timeSeconds)) return false;
    if (!SamePose(a.head, b.head) || !test::SameGazeBits(a.request.gaze, b.request.gaze)) return false;
    if (a.request.trueGaze.has_value() != b.request.trueGaze.has_value()) return false;
    if (a.request.trueGaze && !test::SameGazeBits(*a.request.trueGaze, *b.request.trueGaze)) return false;
    for (size_t eye = 0; eye < 2; ++eye)
        if (!SameEye(a.request.eyes[eye], b.request.eyes[eye])) return false;
    if (a.gazeSamples.size() != b.gazeSamples.size()) return false;
    for (size_t i = 0; i < a.gazeSamples.size(); ++i)
        if (!test::SameGazeBits(a.gazeSamples[i], b.gazeSamples[i])) return false;
    return true;
}

const nlohmann::json kConfig = {{"scene", {{"name", "cornell"}}}, {"camera", {{"width", 32}, {"height", 18}}}};

// Writes `count` random frames (indices 0, 1, 2, ...) and returns them.
std::vector<RecordedFrame> WriteRandom(const fs::path& path, int count, uint64_t seed) {
    Pcg32 rng(seed);
    std::vector<RecordedFrame> frames;
    SessionRecorder recorder(path, kConfig, {{"build", {{"fovrt", "test"}}}});
    for (int f = 0; f < count; ++f) {
        frames.push_back(RandomFrame(rng, uint32_t(f)));
        recorder.Append(frames.back());
    }
    recorder.Close();
    return frames;
}

std::vector<std::string> Lines(const fs::path& path) {
    std::ifstream in(path);
    std::vector<std::string> lines;
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
}

void WriteLines(const fs::path& path, const std::vector<std::string>& lines) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    for (const std::string& line : lines) out << line << '\n';
}

// Reads every frame; returns the error message ("" when the file reads to the end).
std::string ReadAll(const fs::path& path, size_t* framesRead = nullptr) {
    try {
        SessionReader reader(path);
        RecordedFrame frame;
        while (reader.Next(frame)) {
            if (framesRead) ++*framesRead;
        }
        return "";
    } catch (const Error& e) {
        return e.what();
    }
}

}  // namespace

TEST_CASE("a recording reads back bit-identical frames: free poses, asymmetric FOVs, gaze bursts", "[live]") {
    const fs::path path = TempDir() / "roundtrip.jsonl";
    const std::vector<RecordedFrame> written = WriteRandom(path, 400, 20261124);

    SessionReader reader(path);
    CHECK(reader.Header()["format"] == "fovrt-session");
    CHECK(reader.Header()["version"] == 1);
    CHECK(reader.Config() == kConfig);
    CHECK(reader.Header()["build"]["fovrt"] == "test");
    RecordedFrame frame;
    size_t n = 0;
    while (reader.Next(frame)) {
        REQUIRE(n < written.size());
        INFO("frame " << n);
        REQUIRE(SameFrame(frame, written[n]));
        ++n;
    }
    CHECK(n == written.size());
    CHECK(reader.FramesRead() == written.size());
    const SessionSummary summary = ScanSession(path);
    CHECK(summary.frames == written.size());
    CHECK(summary.firstFrame == 0);
    CHECK(summary.lastFrame == written.size() - 1);
}

TEST_CASE("true and tracked gaze: both read back; a recording without tracked gaze was rendered with the true one",
          "[live]") {
    const fs::path path = TempDir() / "tracked.jsonl";
    const GazeSample eye{0.25, glm::normalize(vec3(0.3f, -0.1f, -1.0f)), true};
    const GazeSample tracker{0.25, glm::normalize(vec3(0.1f, 0.05f, -1.0f)), true};
    Pcg32 rng(3);
    RecordedFrame tracked = RandomFrame(rng, 0), ideal = RandomFrame(rng, 1);
    tracked.request.gaze = tracker;
    tracked.request.trueGaze = eye;
    ideal.request.gaze = eye;
    ideal.request.trueGaze.reset();
    {
        SessionRecorder recorder(path, kConfig);
        recorder.Append(tracked);
        recorder.Append(ideal);
    }
    const std::vector<std::string> lines = Lines(path);
    REQUIRE(lines.size() == 3);
    // "gaze" is where the eye was, "tracked_gaze" what the spp maps followed; an ideal frame's line
    // is the format as it was before the field existed.
    const nlohmann::json first = nlohmann::json::parse(lines[1]);
    CHECK(first["gaze"]["direction"][0].get<float>() == eye.direction.x);
    CHECK(first["tracked_gaze"]["direction"][0].get<float>() == tracker.direction.x);
    CHECK(lines[2].find("tracked_gaze") == std::string::npos);
    {
        SessionReader reader(path);
        RecordedFrame frame;
        REQUIRE(reader.Next(frame));
        CHECK(SameFrame(frame, tracked));
        REQUIRE(reader.Next(frame));
        CHECK(SameFrame(frame, ideal));
        CHECK(!frame.request.trueGaze);
    }
    // A recording from before the field: the frame was rendered with its one gaze.
    nlohmann::json old = first;
    old.erase("tracked_gaze");
    WriteLines(path, {lines[0], old.dump()});
    SessionReader reader(path);
    RecordedFrame frame;
    REQUIRE(reader.Next(frame));
    CHECK(test::SameGazeBits(frame.request.gaze, eye));
    CHECK(!frame.request.trueGaze);
    CHECK(test::SameGazeBits(frame.request.EyeGaze(), eye));
}

TEST_CASE("every appended frame is on disk at once: a killed session leaves a readable recording", "[live]") {
    const fs::path path = TempDir() / "killed.jsonl";
    Pcg32 rng(7);
    SessionRecorder recorder(path, kConfig);
    CHECK(ScanSession(path).frames == 0);  // the header alone is a valid, empty recording
    for (uint32_t f = 0; f < 5; ++f) {
        recorder.Append(RandomFrame(rng, 10 + 3 * f));  // indices need only increase
        // No Close(): what another process sees now is what a kill would leave.
        const SessionSummary summary = ScanSession(path);
        CHECK(summary.frames == f + 1);
        CHECK(summary.lastFrame == 10 + 3 * f);
    }
}

TEST_CASE("a truncated recording names the file, the line and the frame", "[live]") {
    const fs::path path = TempDir() / "rec.jsonl";
    WriteRandom(path, 6, 11);
    const std::string text = [&] {
        std::ifstream in(path, std::ios::binary);
        std::stringstream s;
        s << in.rdbuf();
        return s.str();
    }();
    // Cut in the middle of line 7 (frame 5): frames 0..4 read, then one error line.
    const size_t line7 = [&] {
        size_t pos = 0;
        for (int i = 0; i < 6; ++i) pos = text.find('\n', pos) + 1;
        return pos;
    }();
    for (size_t cut : {line7 + 1, line7 + 100, text.size() - 1}) {
        fs::resize_file(path, cut);
        size_t read = 0;
        const std::string error = ReadAll(path, &read);
        INFO(error);
        CHECK(read == 5);
        CHECK(error == path.string() + ": line 7 (after frame 4): truncated line (no newline at the end of the file)");
        std::ofstream(path, std::ios::binary | std::ios::trunc) << text;
    }
    // Cut inside the header.
    fs::resize_file(path, 20);
    CHECK(ReadAll(path) == path.string() + ": line 1 (header): truncated line (no newline at the end of the file)");
}

TEST_CASE("a corrupt field names the file, the line, the frame and the key", "[live]") {
    const fs::path dir = TempDir();
    const fs::path good = dir / "good.jsonl";
    WriteRandom(good, 6, 12);
    const std::vector<std::string> lines = Lines(good);
    REQUIRE(lines.size() == 7);
    const fs::path path = dir / "rec.jsonl";

    // Line 7 is frame 5: edit its JSON, expect `message`.
    auto expect = [&](const std::function<void(nlohmann::json&)>& edit, const std::string& message) {
        nlohmann::json frame = nlohmann::json::parse(lines[6]);
        edit(frame);
        std::vector<std::string> changed = lines;
        changed[6] = frame.dump();
        WriteLines(path, changed);
        const std::string error = ReadAll(path);
        INFO(error);
        CHECK(error == path.string() + ": line 7 (frame 5): " + message);
        CHECK(error.find('\n') == std::string::npos);
    };
    expect([](nlohmann::json& f) { f["eyes"][1].erase("fov"); }, "missing key eyes[1].fov");
    expect([](nlohmann::json& f) { f["eyes"][0]["fov"].erase("up"); }, "missing key eyes[0].fov.up");
    expect([](nlohmann::json& f) { f["eyes"][0]["fov"]["left"] = "wide"; }, "eyes[0].fov.left is not a number");
    expect([](nlohmann::json& f) { f["eyes"][1]["fov"]["left"] = 0.9; f["eyes"][1]["fov"]["right"] = 0.1; },
           "eyes[1].fov: left must be < right");
    expect([](nlohmann::json& f) { f["eyes"][0]["width"] = 0; }, "eyes[0].width = 0 is outside [1, 16384]");
    expect([](nlohmann::json& f) { f["eyes"][0]["height"] = 2.5; }, "eyes[0].height is not an integer");
    expect([](nlohmann::json& f) { f["head"]["orientation_xyzw"] = {0, 0, 0, 2}; },
           "head.orientation_xyzw is not a unit quaternion (norm 2)");
    expect([](nlohmann::json& f) { f["head"]["position"] = {1, 2}; }, "head.position is not an array of 3 numbers");
    expect([](nlohmann::json& f) { f["eyes"][1]["position"][2] = 1e39; }, "eyes[1].position is not finite");
    expect([](nlohmann::json& f) { f["eyes"] = nlohmann::json::array({f["eyes"][0]}); },
           "eyes is not an array of 2 eyes (left, right)");
    expect([](nlohmann::json& f) { f["gaze"]["valid"] = true; f["gaze"]["direction"] = {0, 0, 0}; },
           "gaze.direction is not a unit vector (length 0)");
    expect([](nlohmann::json& f) {
        f["gaze_samples"] = nlohmann::json::array({nlohmann::json{{"time_s", 1.0}, {"direction", {0, 0, -1}}}});
    }, "missing key gaze_samples[0].valid");
    expect([](nlohmann::json& f) { f["tracked_gaze"] = {{"time_s", 1.0}, {"direction", {0, 0, 0}}, {"valid", true}}; },
           "tracked_gaze.direction is not a unit vector (length 0)");
    expect([](nlohmann::json& f) { f["tracked_gaze"] = 3; }, "tracked_gaze is not an object");
    expect([](nlohmann::json& f) { f["time_s"] = nullptr; }, "time_s is not a number");
    expect([](nlohmann::json& f) { f["exposure"] = 1; }, "unknown key exposure");

    // A line with a readable frame index is named by it; an unreadable one by the frame before it.
    std::vector<std::string> changed = lines;
    nlohmann::json repeated = nlohmann::json::parse(lines[6]);
    repeated["frame"] = 4;
    changed[6] = repeated.dump();
    WriteLines(path, changed);
    CHECK(ReadAll(path) == path.string() + ": line 7 (frame 4): frame 4 does not follow frame 4 (frame indices must increase)");
    changed[6] = "{\"frame\": 5, \"time_s\": ";
    WriteLines(path, changed);
    CHECK(ReadAll(path).rfind(path.string() + ": line 7 (after frame 4): not valid JSON", 0) == 0);
    changed[6] = "";
    WriteLines(path, changed);
    CHECK(ReadAll(path) == path.string() + ": line 7 (after frame 4): empty line");
    // Valid JSON syntax whose number no double holds: one line naming the file and line, not
    // nlohmann's out_of_range exception.
    std::string overflow = lines[6];
    overflow.replace(overflow.find("\"time_s\":") + 9, 0, "1e400,\"x\":");
    changed[6] = overflow;
    WriteLines(path, changed);
    CHECK(ReadAll(path).rfind(path.string() + ": line 7 (after frame 4): not readable JSON: number overflow", 0) == 0);
    WriteLines(path, {R"({"format":"fovrt-session","version":1e400,"config":{}})"});
    CHECK(ReadAll(path).rfind(path.string() + ": line 1: the header is not readable JSON: number overflow", 0) == 0);
}

TEST_CASE("a file that is not a version-1 recording is refused naming the file", "[live]") {
    const fs::path dir = TempDir();
    const fs::path path = dir / "header.jsonl";
    auto headerError = [&](const std::string& header) {
        WriteLines(path, {header});
        return ReadAll(path);
    };
    CHECK(headerError(R"({"format":"fovrt-session","version":2,"config":{}})") ==
          path.string() + ": session format version 2 is not supported (this fovrt reads version 1)");
    CHECK(headerError(R"({"format":"other","version":1,"config":{}})").rfind(path.string() + ": not a fovrt session recording", 0) == 0);
    CHECK(headerError(R"({"format":"fovrt-session","version":1})") == path.string() + ": line 1: the header has no config object");
    CHECK(headerError("frame,x,y").rfind(path.string() + ": line 1: not a fovrt session recording", 0) == 0);
    WriteLines(path, {});
    CHECK(ReadAll(path) == path.string() + ": empty file, not a fovrt session recording");
    CHECK(ReadAll(dir / "missing.jsonl").rfind((dir / "missing.jsonl").string() + ": cannot open", 0) == 0);
}

TEST_CASE("the recorder refuses what the reader would refuse, naming the file and the frame", "[live]") {
    const fs::path path = TempDir() / "refuse.jsonl";
    Pcg32 rng(3);
    SessionRecorder recorder(path, kConfig);
    recorder.Append(RandomFrame(rng, 4));
    RecordedFrame frame = RandomFrame(rng, 4);
    CHECK_THROWS_WITH(recorder.Append(frame),
                      path.string() + ": frame 4: frame 4 does not follow frame 4 (frame indices must increase)");
    frame = RandomFrame(rng, 5);
    frame.head.orientation = quat(0.5f, 0.0f, 0.0f, 0.0f);
    CHECK_THROWS_WITH(recorder.Append(frame),
                      path.string() + ": frame 5: head.orientation_xyzw is not a unit quaternion (norm 0.5)");
    frame = RandomFrame(rng, 5);
    frame.request.timeSeconds = std::numeric_limits<double>::infinity();
    CHECK_THROWS_WITH(recorder.Append(frame), path.string() + ": frame 5: time_s is not finite");
    CHECK_THROWS_WITH(SessionRecorder(path, nlohmann::json::array()),
                      path.string() + ": the session config must be a JSON object");
    CHECK_THROWS_WITH(SessionRecorder(TempDir() / "reserved.jsonl", kConfig, {{"version", 2}}),
                      (TempDir() / "reserved.jsonl").string() + ": header member 'version' is reserved");
    recorder.Close();
    CHECK(ScanSession(path).frames == 1);  // the refused frames left nothing behind
    CHECK_THROWS_WITH(recorder.Append(RandomFrame(rng, 9)), path.string() + ": the session recording is closed");
}
