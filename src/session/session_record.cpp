// Session recordings: the JSON Lines writer and the streaming, validating reader (format and
// guarantees in session_record.h).
//
// Lines are built as nlohmann::ordered_json (so a frame reads "frame", "time_s", "head", ... in
// that order) and parsed back as nlohmann::json. Each field is read by one small parser that
// knows its dotted key, so a missing or mistyped field names itself ("eyes[1].fov.left"); the
// value checks (finite, unit quaternion, FOV order, sizes, order of frames and gaze samples) are
// one function, CheckFrame, that the writer runs before writing and the reader after parsing.
#include "session/session_record.h"

#include <fcntl.h>
#include <unistd.h>

#include <bit>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <initializer_list>
#include <limits>
#include <numbers>

#include <fmt/format.h>

#include "core/error.h"

namespace fovrt {
namespace {

constexpr size_t kMaxLineBytes = size_t(16) << 20;  // a frame line is ~1 KiB; 16 MiB = corrupt
constexpr int kMaxEyeSize = 16384;                   // as camera.width / camera.height
constexpr double kUnitTolerance = 1e-3;              // |‖q‖ − 1| for quaternions and gaze

using OrderedJson = nlohmann::ordered_json;

// ---- writing ----------------------------------------------------------------------------------

// The JSON number for a float that reads back as the same float: the float's shortest decimal
// when a double-precision reader (nlohmann uses strtod) turns it back into this float, else the
// exact double of the float (always exact, only longer). Decimal -> double -> float rounds twice,
// which for a rare decimal near a float midpoint could land on the other float; hence the check.
double JsonFloat(float value) {
    const std::string shortest = fmt::format("{}", value);
    const double parsed = std::strtod(shortest.c_str(), nullptr);
    if (std::bit_cast<uint32_t>(float(parsed)) == std::bit_cast<uint32_t>(value)) return parsed;
    return double(value);
}

OrderedJson JsonVec3(const vec3& v) {
    return OrderedJson::array({JsonFloat(v.x), JsonFloat(v.y), JsonFloat(v.z)});
}

OrderedJson JsonPose(const Pose& pose) {
    const quat& q = pose.orientation;
    return OrderedJson{{"position", JsonVec3(pose.position)},
                       {"orientation_xyzw",
                        OrderedJson::array({JsonFloat(q.x), JsonFloat(q.y), JsonFloat(q.z), JsonFloat(q.w)})}};
}

OrderedJson JsonEye(const EyeCamera& eye) {
    OrderedJson json = JsonPose(eye.pose());
    const Fov& fov = eye.fov();
    json["fov"] = {{"left", JsonFloat(fov.angleLeft)},
                   {"right", JsonFloat(fov.angleRight)},
                   {"up", JsonFloat(fov.angleUp)},
                   {"down", JsonFloat(fov.angleDown)}};
    json["width"] = eye.width();
    json["height"] = eye.height();
    return json;
}

OrderedJson JsonGaze(const GazeSample& gaze) {
    return OrderedJson{{"time_s", gaze.timeSeconds}, {"direction", JsonVec3(gaze.direction)}, {"valid", gaze.valid}};
}

std::string UtcNow() {
    const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
    std::tm utc{};
    gmtime_r(&now, &utc);
    char text[32];
    std::strftime(text, sizeof(text), "%Y-%m-%dT%H:%M:%SZ", &utc);
    return text;
}

// ---- checks shared by writer and reader -------------------------------------------------------

// A field with a bad value: its message names the key. Caught where the file and line are known.
struct BadField {
    std::string message;
};

[[noreturn]] void Bad(std::string message) { throw BadField{std::move(message)}; }

void CheckFinite(const std::string& key, std::initializer_list<double> values) {
    for (double v : values)
        if (!std::isfinite(v)) Bad(fmt::format("{} is not finite", key));
}

void CheckPose(const std::string& key, const Pose& pose) {
    const vec3& p = pose.position;
    const quat& q = pose.orientation;
    CheckFinite(key + ".position", {p.x, p.y, p.z});
    CheckFinite(key + ".orientation_xyzw", {q.x, q.y, q.z, q.w});
    const double norm = std::sqrt(double(q.x) * q.x + double(q.y) * q.y + double(q.z) * q.z + double(q.w) * q.w);
    if (!(std::abs(norm - 1.0) <= kUnitTolerance))
        Bad(fmt::format("{}.orientation_xyzw is not a unit quaternion (norm {})", key, norm));
}

void CheckGaze(const std::string& key, const GazeSample& gaze) {
    const vec3& d = gaze.direction;
    CheckFinite(key + ".time_s", {gaze.timeSeconds});
    CheckFinite(key + ".direction", {d.x, d.y, d.z});
    const double norm = std::sqrt(double(d.x) * d.x + double(d.y) * d.y + double(d.z) * d.z);
    // A valid sample is a unit direction; an invalid one (blink, tracker loss) only finite.
    if (gaze.valid && !(std::abs(norm - 1.0) <= kUnitTolerance))
        Bad(fmt::format("{}.direction is not a unit vector (length {})", key, norm));
}

void CheckEye(const std::string& key, const EyeCamera& eye) {
    CheckPose(key, eye.pose());
    const Fov& fov = eye.fov();
    const std::pair<const char*, float> angles[] = {
        {"left", fov.angleLeft}, {"right", fov.angleRight}, {"up", fov.angleUp}, {"down", fov.angleDown}};
    for (const auto& [name, angle] : angles)
        if (!(std::abs(angle) < 0.5 * std::numbers::pi))
            Bad(fmt::format("{}.fov.{} = {} rad is outside (-pi/2, pi/2)", key, name, angle));
    if (!(fov.angleLeft < fov.angleRight)) Bad(fmt::format("{}.fov: left must be < right", key));
    if (!(fov.angleDown < fov.angleUp)) Bad(fmt::format("{}.fov: down must be < up", key));
    if (eye.width() < 1 || eye.width() > kMaxEyeSize)
        Bad(fmt::format("{}.width = {} is outside [1, {}]", key, eye.width(), kMaxEyeSize));
    if (eye.height() < 1 || eye.height() > kMaxEyeSize)
        Bad(fmt::format("{}.height = {} is outside [1, {}]", key, eye.height(), kMaxEyeSize));
}

// Every value check of one frame; `previous` is the frame index before it, if any.
void CheckFrame(const FrameRequest& request, const Pose& head, std::span<const GazeSample> samples,
                std::optional<uint32_t> previous) {
    if (previous && request.frame <= *previous)
        Bad(fmt::format("frame {} does not follow frame {} (frame indices must increase)", request.frame,
                        *previous));
    CheckFinite("time_s", {request.timeSeconds});
    CheckPose("head", head);
    for (size_t eye = 0; eye < 2; ++eye) CheckEye(fmt::format("eyes[{}]", eye), request.eyes[eye]);
    CheckGaze("gaze", request.EyeGaze());
    if (request.trueGaze) CheckGaze("tracked_gaze", request.gaze);
    for (size_t i = 0; i < samples.size(); ++i) {
        CheckGaze(fmt::format("gaze_samples[{}]", i), samples[i]);
        if (i > 0 && samples[i].timeSeconds < samples[i - 1].timeSeconds)
            Bad(fmt::format("gaze_samples[{}].time_s = {} is before gaze_samples[{}].time_s = {}", i,
                            samples[i].timeSeconds, i - 1, samples[i - 1].timeSeconds));
    }
}

// ---- parsing ----------------------------------------------------------------------------------

// An object's members, each looked up by name; unknown members are refused.
class Object {
public:
    Object(const nlohmann::json& json, std::string key) : json_(json), key_(std::move(key)) {
        if (!json_.is_object()) Bad(fmt::format("{} is not an object", Name()));
    }
    void Only(std::initializer_list<const char*> names) const {
        for (const auto& [member, value] : json_.items()) {
            bool known = false;
            for (const char* name : names) known = known || member == name;
            if (!known) Bad(fmt::format("unknown key {}", Child(member)));
        }
    }
    const nlohmann::json& At(const char* member) const {
        auto it = json_.find(member);
        if (it == json_.end()) Bad(fmt::format("missing key {}", Child(member)));
        return *it;
    }
    std::string Child(const std::string& member) const { return key_.empty() ? member : key_ + "." + member; }

    double Number(const char* member) const {
        const nlohmann::json& value = At(member);
        if (!value.is_number()) Bad(fmt::format("{} is not a number", Child(member)));
        return value.get<double>();
    }
    float Float(const char* member) const { return float(Number(member)); }
    int64_t Integer(const char* member, int64_t lo, int64_t hi) const {
        const nlohmann::json& value = At(member);
        if (value.is_number_unsigned() && value.get<uint64_t>() > uint64_t(hi))
            Bad(fmt::format("{} = {} is outside [{}, {}]", Child(member), value.get<uint64_t>(), lo, hi));
        if (!value.is_number_integer()) Bad(fmt::format("{} is not an integer", Child(member)));
        const int64_t v = value.get<int64_t>();
        if (v < lo || v > hi) Bad(fmt::format("{} = {} is outside [{}, {}]", Child(member), v, lo, hi));
        return v;
    }
    bool Bool(const char* member) const {
        const nlohmann::json& value = At(member);
        if (!value.is_boolean()) Bad(fmt::format("{} is not true or false", Child(member)));
        return value.get<bool>();
    }
    template <size_t N>
    std::array<float, N> Floats(const char* member) const {
        const nlohmann::json& value = At(member);
        if (!value.is_array() || value.size() != N) Bad(fmt::format("{} is not an array of {} numbers", Child(member), N));
        std::array<float, N> out{};
        for (size_t i = 0; i < N; ++i) {
            if (!value[i].is_number()) Bad(fmt::format("{}[{}] is not a number", Child(member), i));
            out[i] = float(value[i].get<double>());
        }
        return out;
    }

private:
    std::string Name() const { return key_.empty() ? "the line" : key_; }

    const nlohmann::json& json_;
    std::string key_;
};

vec3 ParseVec3(const Object& object, const char* member) {
    const auto v = object.Floats<3>(member);
    return vec3(v[0], v[1], v[2]);
}

Pose ParsePose(const Object& object) {
    Pose pose;
    pose.position = ParseVec3(object, "position");
    const auto q = object.Floats<4>("orientation_xyzw");
    pose.orientation = quat(q[3], q[0], q[1], q[2]);  // glm: quat(w, x, y, z)
    return pose;
}

EyeCamera ParseEye(const nlohmann::json& json, const std::string& key) {
    const Object eye(json, key);
    eye.Only({"position", "orientation_xyzw", "fov", "width", "height"});
    const Object fovObject(eye.At("fov"), eye.Child("fov"));
    fovObject.Only({"left", "right", "up", "down"});
    Fov fov;
    fov.angleLeft = fovObject.Float("left");
    fov.angleRight = fovObject.Float("right");
    fov.angleUp = fovObject.Float("up");
    fov.angleDown = fovObject.Float("down");
    const Pose pose = ParsePose(eye);
    const int width = int(eye.Integer("width", 1, kMaxEyeSize));
    const int height = int(eye.Integer("height", 1, kMaxEyeSize));
    return EyeCamera(pose, fov, width, height);
}

GazeSample ParseGaze(const nlohmann::json& json, const std::string& key) {
    const Object object(json, key);
    object.Only({"time_s", "direction", "valid"});
    GazeSample gaze;
    gaze.timeSeconds = object.Number("time_s");
    gaze.direction = ParseVec3(object, "direction");
    gaze.valid = object.Bool("valid");
    return gaze;
}

void ParseFrame(const nlohmann::json& json, RecordedFrame& out) {
    const Object root(json, "");
    root.Only({"frame", "time_s", "head", "eyes", "gaze", "tracked_gaze", "gaze_samples"});
    out.request.frame = uint32_t(root.Integer("frame", 0, std::numeric_limits<uint32_t>::max()));
    out.request.timeSeconds = root.Number("time_s");
    const Object head(root.At("head"), "head");
    head.Only({"position", "orientation_xyzw"});
    out.head = ParsePose(head);
    const nlohmann::json& eyes = root.At("eyes");
    if (!eyes.is_array() || eyes.size() != 2) Bad("eyes is not an array of 2 eyes (left, right)");
    for (size_t eye = 0; eye < 2; ++eye) out.request.eyes[eye] = ParseEye(eyes[eye], fmt::format("eyes[{}]", eye));
    // "gaze" is where the eye was; "tracked_gaze", when there, what the spp maps followed.
    out.request.gaze = ParseGaze(root.At("gaze"), "gaze");
    out.request.trueGaze.reset();
    if (json.contains("tracked_gaze")) {
        out.request.trueGaze = out.request.gaze;
        out.request.gaze = ParseGaze(json.at("tracked_gaze"), "tracked_gaze");
    }
    const nlohmann::json& samples = root.At("gaze_samples");
    if (!samples.is_array()) Bad("gaze_samples is not an array");
    out.gazeSamples.clear();
    for (size_t i = 0; i < samples.size(); ++i)
        out.gazeSamples.push_back(ParseGaze(samples[i], fmt::format("gaze_samples[{}]", i)));
}

}  // namespace

// ---- SessionRecorder --------------------------------------------------------------------------

SessionRecorder::SessionRecorder(const std::filesystem::path& path, const nlohmann::json& config,
                                 const nlohmann::json& extra)
    : path_(path) {
    if (!config.is_object()) Fail("{}: the session config must be a JSON object", path_.string());
    if (!extra.is_object()) Fail("{}: the extra header members must be a JSON object", path_.string());
    OrderedJson header;
    header["format"] = kSessionFormat;
    header["version"] = kSessionVersion;
    header["created_utc"] = UtcNow();
    header["config"] = config;
    for (const auto& [key, value] : extra.items()) {
        if (header.contains(key)) Fail("{}: header member '{}' is reserved", path_.string(), key);
        header[key] = value;
    }
    std::string line;
    try {
        line = header.dump() + "\n";
    } catch (const nlohmann::json::exception& e) {
        Fail("{}: the header cannot be written as JSON: {}", path_.string(), e.what());
    }
    std::error_code ignored;
    if (path_.has_parent_path()) std::filesystem::create_directories(path_.parent_path(), ignored);
    fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_APPEND | O_CLOEXEC, 0644);
    if (fd_ < 0) Fail("{}: cannot create the session recording: {}", path_.string(), std::strerror(errno));
    WriteLine(line);
}

SessionRecorder::SessionRecorder(SessionRecorder&& other) noexcept
    : path_(std::move(other.path_)), fd_(std::exchange(other.fd_, -1)), frames_(other.frames_),
      lastFrame_(other.lastFrame_) {}

SessionRecorder& SessionRecorder::operator=(SessionRecorder&& other) noexcept {
    if (this != &other) {
        if (fd_ >= 0) ::close(fd_);
        path_ = std::move(other.path_);
        fd_ = std::exchange(other.fd_, -1);
        frames_ = other.frames_;
        lastFrame_ = other.lastFrame_;
    }
    return *this;
}

SessionRecorder::~SessionRecorder() {
    if (fd_ >= 0) ::close(fd_);  // every line is already written; nothing to flush
}

void SessionRecorder::Append(const FrameRequest& request, const Pose& head,
                             std::span<const GazeSample> gazeSamples) {
    if (fd_ < 0) Fail("{}: the session recording is closed", path_.string());
    try {
        CheckFrame(request, head, gazeSamples, lastFrame_);
    } catch (const BadField& bad) {
        Fail("{}: frame {}: {}", path_.string(), request.frame, bad.message);
    }
    OrderedJson line;
    line["frame"] = request.frame;
    line["time_s"] = request.timeSeconds;
    line["head"] = JsonPose(head);
    line["eyes"] = OrderedJson::array({JsonEye(request.eyes[0]), JsonEye(request.eyes[1])});
    line["gaze"] = JsonGaze(request.EyeGaze());
    if (request.trueGaze) line["tracked_gaze"] = JsonGaze(request.gaze);
    OrderedJson samples = OrderedJson::array();
    for (const GazeSample& sample : gazeSamples) samples.push_back(JsonGaze(sample));
    line["gaze_samples"] = std::move(samples);
    WriteLine(line.dump() + "\n");
    lastFrame_ = request.frame;
    ++frames_;
}

void SessionRecorder::WriteLine(const std::string& line) {
    ssize_t written;
    do {
        written = ::write(fd_, line.data(), line.size());
    } while (written < 0 && errno == EINTR);
    if (written < 0) Fail("{}: cannot write: {}", path_.string(), std::strerror(errno));
    if (size_t(written) != line.size())
        Fail("{}: short write ({} of {} bytes; disk full?)", path_.string(), written, line.size());
}

void SessionRecorder::Close() {
    if (fd_ < 0) return;
    const int fd = std::exchange(fd_, -1);
    const bool synced = ::fsync(fd) == 0;
    const int syncErrno = errno;
    if (::close(fd) != 0) Fail("{}: cannot close: {}", path_.string(), std::strerror(errno));
    if (!synced && syncErrno != EINVAL) Fail("{}: cannot flush to disk: {}", path_.string(), std::strerror(syncErrno));
}

// ---- SessionReader ----------------------------------------------------------------------------

namespace {

// nlohmann's message without its "[json.exception.out_of_range.406] " prefix.
std::string JsonProblem(const nlohmann::json::exception& e) {
    std::string message = e.what();
    if (message.rfind("[json.exception.", 0) == 0 && message.find("] ") != std::string::npos)
        message = message.substr(message.find("] ") + 2);
    return message;
}

}  // namespace

SessionReader::SessionReader(const std::filesystem::path& path)
    : path_(path), file_(std::fopen(path.c_str(), "rb"), &std::fclose) {
    const std::string name = path_.string();
    if (!file_) Fail("{}: cannot open the session recording: {}", name, std::strerror(errno));
    if (std::filesystem::is_directory(path_)) Fail("{}: is a directory, not a session recording", name);
    if (!ReadLine()) Fail("{}: empty file, not a fovrt session recording", name);
    try {
        header_ = nlohmann::json::parse(line_);
    } catch (const nlohmann::json::parse_error&) {
        Fail("{}: line 1: not a fovrt session recording (the header is not JSON)", name);
    } catch (const nlohmann::json::exception& e) {
        // Valid syntax that JSON cannot hold (a number such as 1e400 overflows a double).
        Fail("{}: line 1: the header is not readable JSON: {}", name, JsonProblem(e));
    }
    if (!header_.is_object() || !header_.contains("format") || header_["format"] != kSessionFormat)
        Fail("{}: not a fovrt session recording (line 1 lacks \"format\": \"{}\")", name, kSessionFormat);
    const nlohmann::json& version = header_.contains("version") ? header_["version"] : nlohmann::json();
    if (!version.is_number_integer())
        Fail("{}: line 1: the header's version is missing or not an integer", name);
    if (version.get<int64_t>() != kSessionVersion)
        Fail("{}: session format version {} is not supported (this fovrt reads version {})", name,
             version.get<int64_t>(), kSessionVersion);
    if (!header_.contains("config") || !header_["config"].is_object())
        Fail("{}: line 1: the header has no config object", name);
}

SessionReader::SessionReader(SessionReader&&) noexcept = default;
SessionReader& SessionReader::operator=(SessionReader&&) noexcept = default;
SessionReader::~SessionReader() = default;

// Reads one line (without its '\n') into line_. A last line without '\n' was cut short (the
// recorder ends every line with one), as is one longer than any frame could be.
bool SessionReader::ReadLine() {
    line_.clear();
    std::FILE* file = file_.get();
    bool any = false;
    for (int c = getc_unlocked(file); c != EOF; c = getc_unlocked(file)) {
        any = true;
        if (c == '\n') {
            ++lineNumber_;
            return true;
        }
        line_.push_back(char(c));
        if (line_.size() > kMaxLineBytes) {
            ++lineNumber_;
            FailAtLine(lastFrame_ ? fmt::format("after frame {}", *lastFrame_) : "first frame",
                       fmt::format("line longer than {} MiB (corrupt file?)", kMaxLineBytes >> 20));
        }
    }
    if (std::ferror(file)) Fail("{}: read error after line {}", path_.string(), lineNumber_);
    if (!any) return false;
    ++lineNumber_;
    const std::string where = lastFrame_ ? fmt::format("after frame {}", *lastFrame_)
                              : lineNumber_ == 1 ? "header"
                                                 : "first frame";
    FailAtLine(where, "truncated line (no newline at the end of the file)");
}

void SessionReader::FailAtLine(const std::string& frame, const std::string& message) const {
    Fail("{}: line {} ({}): {}", path_.string(), lineNumber_, frame, message);
}

bool SessionReader::Next(RecordedFrame& out) {
    if (!ReadLine()) return false;
    const std::string before = lastFrame_ ? fmt::format("after frame {}", *lastFrame_) : "first frame";
    if (line_.empty()) FailAtLine(before, "empty line");
    nlohmann::json json;
    try {
        json = nlohmann::json::parse(line_);
    } catch (const nlohmann::json::parse_error& e) {
        FailAtLine(before, fmt::format("not valid JSON (at byte {})", e.byte));
    } catch (const nlohmann::json::exception& e) {
        FailAtLine(before, fmt::format("not readable JSON: {}", JsonProblem(e)));
    }
    // The line's own frame index, when it has one, names the frame in every later message.
    std::string frame = before;
    if (json.is_object() && json.contains("frame") && json["frame"].is_number_unsigned() &&
        json["frame"].get<uint64_t>() <= std::numeric_limits<uint32_t>::max())
        frame = fmt::format("frame {}", json["frame"].get<uint64_t>());
    try {
        ParseFrame(json, out);
        CheckFrame(out.request, out.head, out.gazeSamples, lastFrame_);
    } catch (const BadField& bad) {
        FailAtLine(frame, bad.message);
    }
    lastFrame_ = out.request.frame;
    ++frames_;
    return true;
}

SessionSummary ScanSession(const std::filesystem::path& path) {
    SessionReader reader(path);
    SessionSummary summary;
    RecordedFrame frame;
    while (reader.Next(frame)) {
        if (summary.frames == 0) summary.firstFrame = frame.request.frame;
        summary.lastFrame = frame.request.frame;
        ++summary.frames;
    }
    return summary;
}

}  // namespace fovrt
