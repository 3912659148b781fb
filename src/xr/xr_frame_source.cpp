#include "xr/xr_frame_source.h"

#include <cmath>

#include "core/error.h"

namespace fovrt {

Pose Compose(const Pose& a, const Pose& b) {
    Pose out;
    out.orientation = glm::normalize(a.orientation * b.orientation);
    out.position = a.position + a.orientation * b.position;
    return out;
}

Pose Inverse(const Pose& a) {
    Pose out;
    out.orientation = glm::conjugate(a.orientation);
    out.position = -(out.orientation * a.position);
    return out;
}

namespace {

// The head's position and heading (rotation about +Y only): recentring keeps the user's pitch
// and roll, as a headset's "recentre" does.
Pose PositionAndHeading(const Pose& head) {
    const vec3 forward = head.orientation * vec3(0, 0, -1);
    const float yaw = std::atan2(-forward.x, -forward.z);
    Pose out;
    out.orientation = glm::angleAxis(yaw, vec3(0, 1, 0));
    out.position = head.position;
    return out;
}

}  // namespace

XrFrameSource::XrFrameSource(const RunConfig& config, bool followPath) : config_(config), followPath_(followPath) {
    // No mouse in a headset: a mouse-gaze config falls back to the static gaze.
    if (config_.gaze.source == "mouse") config_.gaze.source = "static";
    fallbackName_ = config_.gaze.source;
}

void XrFrameSource::Set(const std::array<XrEyeView, 2>& views, const Pose& headLocal, double sceneTime,
                        std::optional<vec3> trackedGaze, LiveClock::time_point gazeTakenAt) {
    std::lock_guard<std::mutex> lock(mutex_);
    views_ = views;
    headLocal_ = headLocal;
    sceneTime_ = sceneTime;
    trackedGaze_ = trackedGaze;
    gazeTakenAt_ = gazeTakenAt;
    if (!recentre_) recentre_ = PositionAndHeading(headLocal);
}

Pose XrFrameSource::WorldFromLocal(double sceneTime) const {
    const Pose anchor = pipeline_->RigAtTime(followPath_ ? sceneTime : 0.0).head;
    return Compose(anchor, Inverse(*recentre_));
}

bool XrFrameSource::HasViews() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return recentre_.has_value();
}

std::optional<XrFrameSource::Issued> XrFrameSource::IssuedFrame(uint32_t frame) const {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto& slot = issued_[frame % issued_.size()];
    if (slot && slot->frame == frame) return slot;
    return std::nullopt;
}

std::map<std::string, uint64_t> XrFrameSource::FramesPerGazeSource() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return framesPerSource_;
}

std::string XrFrameSource::LastGazeSource() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return lastSource_;
}

SourcedFrame XrFrameSource::Next(uint32_t frame, double) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!pipeline_ || !recentre_) Fail("XrFrameSource: Next before Bind and Set");
    SourcedFrame out;
    out.request.frame = frame;
    out.request.timeSeconds = sceneTime_;
    const Pose world = WorldFromLocal(sceneTime_);
    out.head = Compose(world, headLocal_);
    for (int eye = 0; eye < 2; ++eye)
        out.request.eyes[size_t(eye)] = EyeCamera(Compose(world, views_[size_t(eye)].pose), views_[size_t(eye)].fov,
                                                  config_.camera.width, config_.camera.height);
    if (trackedGaze_) {
        out.request.gaze.direction = *trackedGaze_;
        out.request.gaze.timeSeconds = sceneTime_;
        out.request.gaze.valid = true;
        lastSource_ = "eye-tracker";
    } else {
        // The synthetic sources map pixels through a reference camera: the left eye's FOV.
        if (!fallback_) fallback_ = CreateGazeSource(config_.gaze, views_[0].fov);
        out.request.gaze = fallback_->At(sceneTime_);
        lastSource_ = fallbackName_;
    }
    out.gazeTakenAt = gazeTakenAt_;
    out.gazeSamples = {TimedGaze{out.request.gaze, gazeTakenAt_}};
    ++framesPerSource_[lastSource_];
    issued_[frame % issued_.size()] = Issued{frame, views_, lastSource_};
    return out;
}

}  // namespace fovrt
