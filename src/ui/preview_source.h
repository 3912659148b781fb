// PreviewFrameSource: the desktop preview's FrameSource. The head pose is the scene's camera path
// or a free-flying camera (WASD + right-drag); the gaze is the mouse pointer over an eye image or
// the configured synthetic source (Lissajous, trace, static). The window thread feeds the pointer
// and the fly camera; the render thread takes one request per frame.
#pragma once

#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "config/config.h"
#include "live/frame_source.h"
#include "pipeline/frame_pipeline.h"

namespace fovrt {

// A free-flying head: position plus yaw (about +Y) and pitch (about the rotated +X), radians.
struct FlyCamera {
    vec3 position = vec3(0.0f);
    float yaw = 0.0f;
    float pitch = 0.0f;

    Pose ToPose() const;
    static FlyCamera FromPose(const Pose& pose);
    // Moves by `local` metres in the head's own frame (+X right, +Y up, -Z forward).
    void Move(const vec3& local);
    void Turn(float dYaw, float dPitch);  // pitch clamped short of straight up/down
};

class PreviewFrameSource : public FrameSource {
public:
    explicit PreviewFrameSource(const RunConfig& config);
    // The pipeline gives the scene's camera path and the rig (FOV, IPD, resolution).
    void Bind(const FramePipeline& pipeline);

    // Gaze: "mouse" or a synthetic source with the configured gaze.* parameters ("lissajous",
    // "static", and "trace" when gaze.trace_path is set). Unknown names: fovrt::Error.
    std::vector<std::string> GazeSourceNames() const;
    void SetGazeSource(const std::string& name);
    std::string GazeSourceName() const;
    bool MouseGaze() const { return GazeSourceName() == "mouse"; }
    // The synthetic sources' parameters (gaze.* keys); a change rebuilds the running source.
    GazeParams SyntheticParams() const;
    void SetSyntheticParams(const GazeParams& params);  // fovrt::Error names a bad gaze.* key
    // The synthetic source G toggles to from the mouse (the configured one, else lissajous).
    std::string SyntheticDefault() const;
    // The pointer's gaze, head space, polled at `takenAt` (the window polls it every iteration).
    void SetPointerGaze(const vec3& directionHead, LiveClock::time_point takenAt);

    // Head: the scene's camera path (nullopt) or a free camera.
    void SetFreeHead(std::optional<FlyCamera> camera);
    std::optional<FlyCamera> FreeHead() const;
    // The head pose a frame at `sceneTime` would use now (to start a fly camera where the path is).
    Pose HeadAt(double sceneTime) const;
    // The eyes of the latest request (the window maps the pointer through them).
    std::array<EyeCamera, 2> LatestEyes() const;

    SourcedFrame Next(uint32_t frame, double sceneTime) override;

private:
    const FramePipeline* pipeline_ = nullptr;
    GazeParams gazeParams_;
    Fov referenceFov_;
    std::unique_ptr<GazeSource> synthetic_;
    mutable std::mutex mutex_;
    LiveClock::time_point start_;  // the mouse's clock starts with the session
    std::string gazeSource_;
    TimedGaze pointer_;
    std::vector<TimedGaze> pointerSamples_;  // since the previous frame
    std::optional<FlyCamera> free_;
    std::array<EyeCamera, 2> latestEyes_;
};

}  // namespace fovrt
