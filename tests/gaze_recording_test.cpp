// Headset gaze recordings (gaze/recording.h): columns by name, the headset frame converted to
// fovrt's head space, the Vive's invalid rows as blinks, errors naming file:line, and the real
// recordings in ../shared/gaze.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/error.h"
#include "gaze/recording.h"
#include "test_support.h"

using namespace fovrt;
namespace fs = std::filesystem;

namespace {

std::vector<GazeTraceSample> Parse(const std::string& text) {
    std::istringstream in(text);
    return ParseGazeRecordingCsv(in, "rec.csv");
}

std::string ErrorOf(const std::string& text) {
    try {
        Parse(text);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST_CASE("recording: headset frame (+z ahead, +x right, +y up) to yaw right / pitch up", "[gaze]") {
    // 10° right: (sin 10°, 0, cos 10°); 5° up: (0, sin 5°, cos 5°). Columns in any order, extras ignored.
    const double s10 = std::sin(10.0 * M_PI / 180.0), c10 = std::cos(10.0 * M_PI / 180.0);
    const double s5 = std::sin(5.0 * M_PI / 180.0), c5 = std::cos(5.0 * M_PI / 180.0);
    std::ostringstream text;
    text.precision(9);
    text << "Dir_Z,time,dir_x,extra,dir_y,ori_x,ori_y,ori_z\n"
         << c10 << ",20.5," << s10 << ",a,0,0.01,0,0\n"
         << c5 << ",20.511,0,b," << s5 << ",0.01,0,0\n"
         << "1,20.522,0,c,0,0,0,0\n"  // the Vive's "no sample" row
         << "," << "20.533,,d,,0,0,0\n";  // empty direction
    const auto samples = Parse(text.str());
    REQUIRE(samples.size() == 4);
    CHECK(samples[0].timeMs == 0.0);
    CHECK(samples[1].timeMs == Approx(11.0).margin(1e-9));
    CHECK(samples[0].valid);
    CHECK(samples[0].yawDeg == Approx(10.0f).margin(1e-4));
    CHECK(samples[0].pitchDeg == Approx(0.0f).margin(1e-4));
    CHECK(samples[1].yawDeg == Approx(0.0f).margin(1e-4));
    CHECK(samples[1].pitchDeg == Approx(5.0f).margin(1e-4));
    CHECK(!samples[2].valid);
    CHECK(!samples[3].valid);
    // Head space: right is +x, ahead is -z (GazeDirectionFromAngles' convention).
    const vec3 head = HeadDirectionFromHeadset(vec3(float(s10), 0.0f, float(c10)));
    CHECK(head.x > 0.0f);
    CHECK(head.z < 0.0f);
}

TEST_CASE("recording: straight ahead with a real origin is a valid sample", "[gaze]") {
    const auto samples = Parse("time,ori_x,ori_y,ori_z,dir_x,dir_y,dir_z\n0,0.01,0,-0.02,0,0,1\n");
    REQUIRE(samples.size() == 1);
    CHECK(samples[0].valid);
    CHECK(samples[0].yawDeg == 0.0f);
}

TEST_CASE("recording: a UTF-8 byte-order mark before the header is skipped", "[gaze]") {
    // Spreadsheets save CSV with one; the header's first name would otherwise read "\xEF\xBB\xBFtime".
    const auto samples = Parse("\xEF\xBB\xBFtime,dir_x,dir_y,dir_z\n0,0,0,1\n0.1,0,0.0871557,0.9961947\n");
    REQUIRE(samples.size() == 2);
    CHECK(samples[1].timeMs == Approx(100.0));
    CHECK(samples[1].pitchDeg == Approx(5.0f).margin(1e-3));
}

TEST_CASE("recording: bad files give one line naming file:line", "[gaze]") {
    const std::string header = "time,dir_x,dir_y,dir_z\n";
    struct Case {
        std::string text, expected;
    };
    const std::vector<Case> cases = {
        {"time,x,y\n0,1,2\n", "rec.csv:1: gaze recording header must name columns time"},
        {header + "0,0,0,1\nabc,0,0,1\n", "rec.csv:3: time 'abc' is not a finite number"},
        {header + "1,0,0,1\n0.5,0,0,1\n", "rec.csv:3: time 0.5 s goes backwards"},
        {header + "0,0.5,0,0.5\n", "rec.csv:2: gaze direction (0.5, 0, 0.5) is not a unit vector"},
        {header + "0,0,0,-1\n", "rec.csv:2: gaze direction (0, 0, -1) does not point ahead"},
        {header + "0,x,0,1\n", "rec.csv:2: dir_x 'x' is not a finite number"},
        {header + "0,0,0\n", "rec.csv:2: expected at least 4 comma-separated fields, got 3"},
        {header + "0,0,0,1\n", "rec.csv: gaze recording has no valid sample"},
        {header, "rec.csv: gaze recording has a header but no samples"},
        {"", "rec.csv: empty gaze recording"},
        // Which of two dir_x columns is the gaze? Reading the first would be a guess.
        {"time,dir_x,dir_y,dir_z,DIR_X\n0,0,0,1,0.5\n", "rec.csv:1: column 'dir_x' appears twice (fields 2 and 5)"},
        {"\ntime,dir_x,dir_y,dir_z,time\n0,0,0,1,3\n", "rec.csv:2: column 'time' appears twice (fields 1 and 5)"},
    };
    for (const Case& c : cases) {
        INFO(c.text);
        const std::string message = ErrorOf(c.text);
        CHECK(message.rfind(c.expected, 0) == 0);
        CHECK(message.find('\n') == std::string::npos);
    }
    CHECK_THROWS_WITH(LoadGazeRecordingCsv("/nonexistent/rec.csv"), Catch::Contains("/nonexistent/rec.csv"));
}

TEST_CASE("recording: the three headset recordings in ../shared/gaze load; invalid rows play as blinks", "[gaze]") {
    const fs::path dir = test::SharedGaze();
    if (dir.empty()) FOVRT_SKIP("../shared/gaze is absent; real-recording test not run");
    struct Expected {
        const char* file;
        size_t rows;
        double durationS;
    };
    // Rows and durations from ../shared/gaze/README.md.
    for (const Expected& e : {Expected{"vr-kitchen-p10.csv", 3941, 44.2}, Expected{"vr-kitchen-p15.csv", 1631, 18.5},
                              Expected{"vr-office-p14.csv", 1459, 16.7}}) {
        INFO(e.file);
        const auto samples = LoadGazeRecordingCsv(dir / e.file);
        CHECK(samples.size() == e.rows);
        CHECK(samples.back().timeMs / 1000.0 == Approx(e.durationS).margin(0.1));
        std::vector<float> eccentricity;
        size_t invalid = 0;
        for (const GazeTraceSample& s : samples) {
            if (!s.valid) {
                ++invalid;
                continue;
            }
            const vec3 d = GazeDirectionFromAngles(s.yawDeg, s.pitchDeg);
            eccentricity.push_back(Degrees(std::acos(std::clamp(-d.z, -1.0f, 1.0f))));
        }
        // README: 0–7 % invalid rows, median angle from straight ahead 8–15° (measured over the
        // valid rows here: 7.8° for vr-office-p14, so the lower bound is 7°).
        CHECK(double(invalid) / double(samples.size()) <= 0.07);
        std::nth_element(eccentricity.begin(), eccentricity.begin() + long(eccentricity.size() / 2), eccentricity.end());
        const float median = eccentricity[eccentricity.size() / 2];
        CHECK(median >= 7.0f);
        CHECK(median <= 15.0f);
        // Played as a trace: every invalid row's time gives an invalid (blink) sample.
        const TraceGaze gaze(samples);
        for (const GazeTraceSample& s : samples)
            if (!s.valid) REQUIRE(!gaze.At(s.timeMs / 1000.0).valid);
    }
}
