// Session recordings (SPEC §11): a live session written frame by frame, so that it can be
// re-rendered headless with the same cameras, gaze and spp maps (`fovrt run --replay`,
// `fovrt experiment --replay`). No dependency on the app: the caller passes the resolved config
// as JSON, and the app turns it back into a RunConfig.
//
// Format: JSON Lines, UTF-8, every line one JSON object ending in '\n'.
//   Line 1, the header:
//     {"format": "fovrt-session", "version": 1, "created_utc": "2024-05-01T12:00:00Z",
//      "config": {...the resolved config...}, ...the caller's extra members ("build", "scene")}
//   Every further line, one frame, in the order rendered (frame indices strictly increasing):
//     {"frame": 5, "time_s": 0.16666666666666666,
//      "head": {"position": [x, y, z], "orientation_xyzw": [x, y, z, w]},
//      "eyes": [{"position": [x, y, z], "orientation_xyzw": [x, y, z, w],
//                "fov": {"left": l, "right": r, "up": u, "down": d}, "width": 640, "height": 360},
//               {...the right eye...}],
//      "gaze": {"time_s": t, "direction": [x, y, z], "valid": true},
//      "tracked_gaze": {"time_s": t, "direction": [x, y, z], "valid": true},   (optional)
//      "gaze_samples": [{"time_s": t, "direction": [x, y, z], "valid": true}, ...]}
//   Units: metres, radians, seconds. Poses are world-from-local (core/camera.h); the quaternion is
//   in OpenXR's x, y, z, w order; FOV angles as XrFovf (left and down usually negative). `gaze` is
//   the true gaze of the frame (where the eye was: FrameRequest::EyeGaze()), `tracked_gaze` what
//   a modelled eye tracker reported of it (gaze/tracker.h), which the spp maps followed — present
//   only when the session ran a tracker model (FrameRequest::trueGaze set); without it the frame
//   was rendered with `gaze` (every recording made before the field existed reads so).
//   `gaze_samples` are every true sample taken since the previous frame, oldest first (a live
//   window samples the mouse or tracker more often than it renders; may be empty). Gaze
//   directions are in head space.
//
// Exactness: every number reads back bit-identical. Doubles are written as the shortest decimal
// that round-trips; floats as the shortest decimal of the float when a double-precision reader
// gives the same float back (checked on write), else as the exact double of the float.
//
// Crash safety: the recorder writes each line with one write(2) on an O_APPEND descriptor and
// keeps nothing in memory, so a session that is closed, crashes or is killed at any moment leaves
// complete lines only: a readable recording of the frames so far. (No fsync per frame: a power
// cut may lose the frames the kernel had not written back.)
//
// Validation: the reader checks every field of every line (types, count, finite values, unit
// quaternions, FOV order and range, sizes, frame order) and throws fovrt::Error with one line
// naming the file, the line and the frame, e.g.
//   "rec.jsonl: line 7 (frame 5): missing key eyes[1].fov"
//   "rec.jsonl: line 7 (after frame 4): truncated line (no newline at the end of the file)"
// (frame = the line's own frame index when it can be read, else the frame before it). The writer
// applies the same value checks before writing, so it never writes a line the reader refuses.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/camera.h"
#include "pipeline/frame_request.h"

namespace fovrt {

inline constexpr const char* kSessionFormat = "fovrt-session";
inline constexpr int kSessionVersion = 1;

// One recorded frame: what it was rendered from, the head pose the eyes came from, and every gaze
// sample taken since the previous frame.
struct RecordedFrame {
    FrameRequest request;
    Pose head;
    std::vector<GazeSample> gazeSamples;  // true samples, oldest first; request.gaze is the one rendered with
};

// Writes a recording. Move-only; the destructor closes the file.
class SessionRecorder {
public:
    // Creates (or truncates) `path` and writes the header. `config`: the resolved config, a JSON
    // object (required); `extra`: further header members (e.g. "build", "scene"), an object whose
    // keys must not be format, version, created_utc or config. Throws fovrt::Error naming the
    // file.
    SessionRecorder(const std::filesystem::path& path, const nlohmann::json& config,
                    const nlohmann::json& extra = nlohmann::json::object());
    SessionRecorder(SessionRecorder&& other) noexcept;
    SessionRecorder& operator=(SessionRecorder&& other) noexcept;
    SessionRecorder(const SessionRecorder&) = delete;
    SessionRecorder& operator=(const SessionRecorder&) = delete;
    ~SessionRecorder();

    // Appends one frame as one line. Throws fovrt::Error (naming the file, the frame and the
    // field) for a value the reader would refuse (non-finite, not a unit quaternion, FOV out of
    // order, frame index not after the previous one) and for a failed write.
    void Append(const FrameRequest& request, const Pose& head,
                std::span<const GazeSample> gazeSamples);
    void Append(const RecordedFrame& frame) { Append(frame.request, frame.head, frame.gazeSamples); }
    // Closes the file (flushing it to disk); Append afterwards is an error. Idempotent.
    void Close();

    const std::filesystem::path& Path() const { return path_; }
    size_t FramesWritten() const { return frames_; }

private:
    void WriteLine(const std::string& line);

    std::filesystem::path path_;
    int fd_ = -1;
    size_t frames_ = 0;
    std::optional<uint32_t> lastFrame_;
};

// Reads a recording one frame at a time (memory stays flat however long it is).
class SessionReader {
public:
    // Opens `path` and reads and checks the header (format, version, config object). Throws
    // fovrt::Error naming the file.
    explicit SessionReader(const std::filesystem::path& path);
    SessionReader(SessionReader&&) noexcept;
    SessionReader& operator=(SessionReader&&) noexcept;
    ~SessionReader();

    const nlohmann::json& Header() const { return header_; }
    const nlohmann::json& Config() const { return header_.at("config"); }

    // Reads and checks the next frame into `out`; false at the end of the file. Throws
    // fovrt::Error naming the file, the line and the frame.
    bool Next(RecordedFrame& out);

    const std::filesystem::path& Path() const { return path_; }
    size_t FramesRead() const { return frames_; }

private:
    bool ReadLine();  // into line_; false at the end of the file
    [[noreturn]] void FailAtLine(const std::string& frame, const std::string& message) const;

    std::filesystem::path path_;
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> file_;
    nlohmann::json header_;
    std::string line_;
    size_t lineNumber_ = 0;
    size_t frames_ = 0;
    std::optional<uint32_t> lastFrame_;
};

// Reads and checks every frame of a recording once (streaming): for a job that needs the count
// before it starts, and to refuse a corrupt recording before writing any output.
struct SessionSummary {
    size_t frames = 0;
    uint32_t firstFrame = 0;
    uint32_t lastFrame = 0;
};
SessionSummary ScanSession(const std::filesystem::path& path);

}  // namespace fovrt
