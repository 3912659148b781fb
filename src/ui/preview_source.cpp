#include "ui/preview_source.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/quaternion.hpp>

namespace fovrt {

Pose FlyCamera::ToPose() const {
    Pose pose;
    pose.position = position;
    pose.orientation = glm::angleAxis(yaw, vec3(0, 1, 0)) * glm::angleAxis(pitch, vec3(1, 0, 0));
    return pose;
}

FlyCamera FlyCamera::FromPose(const Pose& pose) {
    FlyCamera camera;
    camera.position = pose.position;
    const vec3 forward = pose.orientation * vec3(0, 0, -1);
    camera.yaw = std::atan2(-forward.x, -forward.z);
    camera.pitch = std::asin(std::clamp(forward.y, -1.0f, 1.0f));
    return camera;
}

void FlyCamera::Move(const vec3& local) { position += ToPose().orientation * local; }

void FlyCamera::Turn(float dYaw, float dPitch) {
    yaw += dYaw;
    pitch = std::clamp(pitch + dPitch, Radians(-89.0f), Radians(89.0f));
}

PreviewFrameSource::PreviewFrameSource(const RunConfig& config) {
    gazeSource_ = config.gaze.source;
    start_ = pointer_.takenAt = LiveClock::now();
}

void PreviewFrameSource::Bind(const FramePipeline& pipeline) {
    pipeline_ = &pipeline;
    gazeParams_ = pipeline.Config().gaze;
    referenceFov_ = ResolveFov(pipeline.Config(), pipeline.GetScene());
    SetGazeSource(gazeSource_);
    const StereoRig rig = pipeline.RigAtTime(0.0);  // the pointer maps through these until frame 0
    for (int eye = 0; eye < 2; ++eye) latestEyes_[size_t(eye)] = rig.Eye(eye);
}

std::vector<std::string> PreviewFrameSource::GazeSourceNames() const {
    std::vector<std::string> names = {"mouse", "lissajous", "static"};
    if (!gazeParams_.tracePath.empty()) names.push_back("trace");
    return names;
}

void PreviewFrameSource::SetGazeSource(const std::string& name) {
    std::unique_ptr<GazeSource> synthetic;
    if (name != "mouse") {
        GazeParams params = SyntheticParams();
        params.source = name;
        synthetic = CreateGazeSource(params, referenceFov_);  // loads a trace here, not per frame
    }
    std::lock_guard<std::mutex> lock(mutex_);
    gazeSource_ = name;
    if (synthetic) synthetic_ = std::move(synthetic);
}

std::string PreviewFrameSource::GazeSourceName() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return gazeSource_;
}

GazeParams PreviewFrameSource::SyntheticParams() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return gazeParams_;
}

void PreviewFrameSource::SetSyntheticParams(const GazeParams& params) {
    GazeParams checked = params;
    checked.source = "static";
    ValidateGazeParams(checked);
    const std::string name = GazeSourceName();
    {
        std::lock_guard<std::mutex> lock(mutex_);
        gazeParams_ = params;
    }
    SetGazeSource(name);
}

std::string PreviewFrameSource::SyntheticDefault() const {
    return gazeParams_.source == "mouse" ? "lissajous" : gazeParams_.source;
}

void PreviewFrameSource::SetPointerGaze(const vec3& directionHead, LiveClock::time_point takenAt) {
    std::lock_guard<std::mutex> lock(mutex_);
    // Every poll is a sample (latency runs from the newest); recordings keep the movements.
    const bool moved = pointer_.gaze.direction != directionHead;
    pointer_.gaze.direction = directionHead;
    pointer_.gaze.timeSeconds = std::chrono::duration<double>(takenAt - start_).count();
    pointer_.takenAt = takenAt;
    if (moved || pointerSamples_.empty()) pointerSamples_.push_back(pointer_);
}

void PreviewFrameSource::SetFreeHead(std::optional<FlyCamera> camera) {
    std::lock_guard<std::mutex> lock(mutex_);
    free_ = camera;
}

std::optional<FlyCamera> PreviewFrameSource::FreeHead() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return free_;
}

Pose PreviewFrameSource::HeadAt(double sceneTime) const {
    std::lock_guard<std::mutex> lock(mutex_);
    return free_ ? free_->ToPose() : pipeline_->RigAtTime(sceneTime).head;
}

std::array<EyeCamera, 2> PreviewFrameSource::LatestEyes() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return latestEyes_;
}

SourcedFrame PreviewFrameSource::Next(uint32_t frame, double sceneTime) {
    SourcedFrame out;
    out.request.frame = frame;
    out.request.timeSeconds = sceneTime;
    StereoRig rig = pipeline_->RigAtTime(sceneTime);
    std::lock_guard<std::mutex> lock(mutex_);
    if (free_) rig.head = free_->ToPose();
    out.head = rig.head;
    for (int eye = 0; eye < 2; ++eye) out.request.eyes[size_t(eye)] = rig.Eye(eye);
    latestEyes_ = out.request.eyes;
    if (gazeSource_ == "mouse" || !synthetic_) {
        out.request.gaze = pointer_.gaze;
        out.gazeTakenAt = pointer_.takenAt;
        out.gazeSamples = std::move(pointerSamples_);
        pointerSamples_.clear();
    } else {
        out.request.gaze = synthetic_->At(sceneTime);
        out.gazeTakenAt = LiveClock::now();
        out.gazeSamples = {TimedGaze{out.request.gaze, out.gazeTakenAt}};
    }
    return out;
}

}  // namespace fovrt
