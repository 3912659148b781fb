// XrFrameSource: the headset's FrameSource. Each frame the session hands it what it located at
// the predicted display time — both eyes' poses and asymmetric FOVs, the head, the eye tracker's
// gaze when there is one — and the render stage turns that into a FrameRequest:
//   world-from-eye = anchor · recentre⁻¹ · LOCAL-from-eye
// where the anchor is the scene camera's pose (at the start, or riding the camera path with
// follow_path) and the recentre is the first head pose's position and heading, so the user
// starts where the scene's camera stands, looking where it looks.
// Without an active eye gaze sample the configured gaze source (gaze.*) gives the gaze, and each
// frame is counted under the source that gave it.
// Thread-safe: the session thread calls Set, the render thread Next (xr --async).
#pragma once

#include <array>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "config/config.h"
#include "live/frame_source.h"
#include "pipeline/frame_pipeline.h"
#include "xr/xr_session.h"

namespace fovrt {

class XrFrameSource : public FrameSource {
public:
    XrFrameSource(const RunConfig& config, bool followPath);
    void Bind(const FramePipeline& pipeline) { pipeline_ = &pipeline; }

    // What the next frame renders: the eyes and head (LOCAL space) at the display time, the scene
    // time, and the tracker's gaze (head space) or nullopt for the fallback.
    void Set(const std::array<XrEyeView, 2>& views, const Pose& headLocal, double sceneTime,
             std::optional<vec3> trackedGaze, LiveClock::time_point gazeTakenAt);

    SourcedFrame Next(uint32_t frame, double sceneTime) override;

    // Whether Set has been called (the render thread may start asking).
    bool HasViews() const;

    // What Next gave for `frame`, in the headset's terms (the last few frames are kept): the LOCAL
    // views the projection layer must carry, and the gaze's source.
    struct Issued {
        uint32_t frame = 0;
        std::array<XrEyeView, 2> views{};
        std::string gazeSource;
    };
    std::optional<Issued> IssuedFrame(uint32_t frame) const;

    // Frames per gaze source ("eye-tracker" or the fallback's name).
    std::map<std::string, uint64_t> FramesPerGazeSource() const;
    std::string FallbackName() const { return fallbackName_; }
    std::string LastGazeSource() const;

private:
    Pose WorldFromLocal(double sceneTime) const;

    RunConfig config_;
    bool followPath_;
    const FramePipeline* pipeline_ = nullptr;
    std::string fallbackName_;
    std::unique_ptr<GazeSource> fallback_;
    std::optional<Pose> recentre_;
    std::array<XrEyeView, 2> views_{};
    Pose headLocal_;
    double sceneTime_ = 0.0;
    std::optional<vec3> trackedGaze_;
    LiveClock::time_point gazeTakenAt_;
    std::map<std::string, uint64_t> framesPerSource_;
    std::string lastSource_;
    std::array<std::optional<Issued>, 8> issued_;  // ring, by frame index
    mutable std::mutex mutex_;
};

// Pose algebra used by the mapping (a·b applies b first; Inverse(a)·a = identity).
Pose Compose(const Pose& a, const Pose& b);
Pose Inverse(const Pose& a);

}  // namespace fovrt
