// Eye cameras and the stereo head model.
//
// Conventions (OpenXR/GL): eye space is right-handed, +X right, +Y up, looking down -Z.
// Pixels: (0,0) is the top-left corner, +y goes down, pixel (x, y) has its centre at
// (x + 0.5, y + 0.5). Linear depth is the distance along the view axis (-z_eye), in metres.
// A field of view is four angles as in XrFovf: left and down are usually negative.
#pragma once

#include <optional>

#include "math.h"

namespace fovrt {

struct Fov {
    float angleLeft = Radians(-45.0f);
    float angleRight = Radians(45.0f);
    float angleUp = Radians(45.0f);
    float angleDown = Radians(-45.0f);

    // Symmetric FOV from a horizontal angle and an aspect ratio (width / height).
    static Fov FromHorizontal(float horizontalRadians, float aspect);
};

struct Pose {
    quat orientation = quat(1.0f, 0.0f, 0.0f, 0.0f);  // world-from-local rotation
    vec3 position = vec3(0.0f);

    mat4 WorldFromLocal() const;
    // A pose at `eye` looking at `target` with the given up vector.
    static Pose LookAt(const vec3& eye, const vec3& target, const vec3& up = vec3(0, 1, 0));
    static Pose Lerp(const Pose& a, const Pose& b, float t);  // slerp on orientation
};

// Where a world point lands on an eye's image.
struct Projection {
    vec2 pixel;         // continuous pixel coordinates (centre of pixel x is x + 0.5)
    float linearDepth;  // -z_eye, > 0 in front of the eye
};

class EyeCamera {
public:
    EyeCamera() = default;
    EyeCamera(const Pose& pose, const Fov& fov, int width, int height);

    const Pose& pose() const { return pose_; }
    const Fov& fov() const { return fov_; }
    int width() const { return width_; }
    int height() const { return height_; }
    vec3 Position() const { return pose_.position; }

    mat4 View() const { return view_; }            // eye-from-world
    mat4 ProjectionMatrix(float zNear = 0.01f, float zFar = 1000.0f) const;  // GL clip, y up
    mat4 ViewProjection() const { return ProjectionMatrix() * view_; }

    // Unit direction, in eye space, through a continuous pixel position.
    vec3 EyeDirection(const vec2& pixel) const;
    // Unit direction, in world space, through a continuous pixel position.
    vec3 WorldDirection(const vec2& pixel) const;
    // Continuous pixel position of an eye-space direction (any z < 0).
    vec2 PixelOfEyeDirection(const vec3& eyeDir) const;
    // Projects a world point; nullopt behind the eye.
    std::optional<Projection> Project(const vec3& world) const;
    // Linear depth of a world point (-z_eye).
    float LinearDepth(const vec3& world) const;

    // Pixels per degree at the image centre (horizontal), for FLIP and reports.
    float PixelsPerDegree() const;

private:
    Pose pose_;
    Fov fov_;
    int width_ = 0;
    int height_ = 0;
    mat4 view_ = mat4(1.0f);
    float tanLeft_ = -1, tanRight_ = 1, tanUp_ = 1, tanDown_ = -1;
};

// Head pose + IPD -> two eye cameras. Eye 0 is left, eye 1 is right.
struct StereoRig {
    Pose head;
    float ipd = 0.063f;  // metres
    Fov fov[2];
    int width = 1280;    // per eye
    int height = 720;

    EyeCamera Eye(int eye) const;
};

}  // namespace fovrt
