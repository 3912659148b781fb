#include "camera.h"

#include <cmath>

#include "check.h"

namespace fovrt {

Fov Fov::FromHorizontal(float horizontalRadians, float aspect) {
    float tanX = std::tan(0.5f * horizontalRadians);
    float tanY = tanX / aspect;
    return Fov{-0.5f * horizontalRadians, 0.5f * horizontalRadians, std::atan(tanY),
               -std::atan(tanY)};
}

mat4 Pose::WorldFromLocal() const {
    mat4 m = glm::mat4_cast(orientation);
    m[3] = vec4(position, 1.0f);
    return m;
}

Pose Pose::LookAt(const vec3& eye, const vec3& target, const vec3& up) {
    // glm::lookAt gives eye-from-world; invert its rotation to get world-from-eye.
    mat4 view = glm::lookAt(eye, target, up);
    Pose pose;
    pose.orientation = glm::normalize(glm::quat_cast(glm::transpose(mat3(view))));
    pose.position = eye;
    return pose;
}

Pose Pose::Lerp(const Pose& a, const Pose& b, float t) {
    return Pose{glm::slerp(a.orientation, b.orientation, t), glm::mix(a.position, b.position, t)};
}

EyeCamera::EyeCamera(const Pose& pose, const Fov& fov, int width, int height)
    : pose_(pose), fov_(fov), width_(width), height_(height) {
    FOVRT_CHECK_OP(width, >, 0);
    FOVRT_CHECK_OP(height, >, 0);
    view_ = glm::inverse(pose.WorldFromLocal());
    tanLeft_ = std::tan(fov.angleLeft);
    tanRight_ = std::tan(fov.angleRight);
    tanUp_ = std::tan(fov.angleUp);
    tanDown_ = std::tan(fov.angleDown);
}

mat4 EyeCamera::ProjectionMatrix(float zNear, float zFar) const {
    // Off-axis perspective (the OpenXR asymmetric frustum), GL clip conventions.
    float l = tanLeft_ * zNear, r = tanRight_ * zNear, t = tanUp_ * zNear, b = tanDown_ * zNear;
    return glm::frustum(l, r, b, t, zNear, zFar);
}

vec3 EyeCamera::EyeDirection(const vec2& pixel) const {
    float u = pixel.x / float(width_);
    float v = pixel.y / float(height_);
    float tx = tanLeft_ + u * (tanRight_ - tanLeft_);
    float ty = tanUp_ + v * (tanDown_ - tanUp_);
    return glm::normalize(vec3(tx, ty, -1.0f));
}

vec3 EyeCamera::WorldDirection(const vec2& pixel) const {
    return glm::normalize(pose_.orientation * EyeDirection(pixel));
}

vec2 EyeCamera::PixelOfEyeDirection(const vec3& eyeDir) const {
    float tx = eyeDir.x / -eyeDir.z;
    float ty = eyeDir.y / -eyeDir.z;
    float u = (tx - tanLeft_) / (tanRight_ - tanLeft_);
    float v = (ty - tanUp_) / (tanDown_ - tanUp_);
    return vec2(u * float(width_), v * float(height_));
}

std::optional<Projection> EyeCamera::Project(const vec3& world) const {
    vec3 e = vec3(view_ * vec4(world, 1.0f));
    if (e.z >= -1e-6f) return std::nullopt;
    return Projection{PixelOfEyeDirection(e), -e.z};
}

float EyeCamera::LinearDepth(const vec3& world) const {
    return -(view_ * vec4(world, 1.0f)).z;
}

float EyeCamera::PixelsPerDegree() const {
    float horizontalDegrees = Degrees(fov_.angleRight - fov_.angleLeft);
    return float(width_) / horizontalDegrees;
}

EyeCamera StereoRig::Eye(int eye) const {
    FOVRT_CHECK(eye == 0 || eye == 1);
    float offset = (eye == 0 ? -0.5f : 0.5f) * ipd;
    Pose pose = head;
    pose.position = head.position + head.orientation * vec3(offset, 0.0f, 0.0f);
    return EyeCamera(pose, fov[eye], width, height);
}

}  // namespace fovrt
