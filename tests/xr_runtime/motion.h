// The test runtime's simulated headset: scripted head motion, the two eyes' poses and asymmetric
// FOVs, and the scripted eye gaze, all pure functions of XrTime. Header-only so the runtime's tests
// can compute the values the runtime must report (README.md documents the same formulas).
// Time base: s = XrTime / 1e9, XrTime being CLOCK_MONOTONIC nanoseconds (the runtime's clock).
#pragma once

#include <cmath>
#include <cstdint>

#ifndef GLM_ENABLE_EXPERIMENTAL
#define GLM_ENABLE_EXPERIMENTAL  // glm/gtx/quaternion.hpp: glm::rotation
#endif
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtx/quaternion.hpp>

namespace fovrt::xrrt {

constexpr double kTwoPi = 6.283185307179586;
constexpr float kIpdMeters = 0.063f;
constexpr float kEyeHeightMeters = 1.6f;

struct Pose {
    glm::quat orientation{1.0f, 0.0f, 0.0f, 0.0f};  // glm order: w, x, y, z
    glm::vec3 position{0.0f};
};

inline Pose Compose(const Pose& a, const Pose& b) {
    return {glm::normalize(a.orientation * b.orientation), a.position + a.orientation * b.position};
}

inline Pose Inverse(const Pose& p) {
    glm::quat inv = glm::conjugate(p.orientation);
    return {inv, -(inv * p.position)};
}

inline double Seconds(int64_t xrTime) { return double(xrTime) * 1e-9; }

// Head in STAGE (= LOCAL) space: standing eye height plus slow sinusoids (a few cm, periods of
// 5-13 s) and a slow yaw of up to 0.25 rad with a little pitch, so that poses move every frame.
inline Pose HeadPose(int64_t xrTime) {
    double s = Seconds(xrTime);
    auto wave = [s](double amplitude, double period, double phase = 0.0) {
        return float(amplitude * std::sin(kTwoPi * s / period + phase));
    };
    Pose head;
    head.position = glm::vec3(wave(0.10, 7.0), kEyeHeightMeters + wave(0.03, 5.0),
                              wave(0.05, 11.0, 1.0));
    glm::quat yaw = glm::angleAxis(wave(0.25, 13.0), glm::vec3(0, 1, 0));
    glm::quat pitch = glm::angleAxis(wave(0.05, 6.0, 0.5), glm::vec3(1, 0, 0));
    head.orientation = glm::normalize(yaw * pitch);
    return head;
}

// Eye 0 = left, 1 = right: the head pose moved IPD/2 along the head's own x axis.
inline Pose EyeFromHead(int eye) {
    Pose offset;
    offset.position = glm::vec3(eye == 0 ? -0.5f * kIpdMeters : 0.5f * kIpdMeters, 0.0f, 0.0f);
    return offset;
}

struct Fov {
    float angleLeft, angleRight, angleUp, angleDown;  // radians, as XrFovf
};

// Asymmetric like a real HMD: each eye sees further outwards (temporal) than inwards (nasal).
inline Fov EyeFov(int eye) {
    if (eye == 0) return {-0.95f, 0.80f, 0.85f, -0.90f};
    return {-0.80f, 0.95f, 0.85f, -0.90f};
}

// Gaze direction in VIEW space from tangent-space coordinates: normalize(tx, ty, -1).
inline glm::vec3 GazeFromTangent(float tx, float ty) {
    return glm::normalize(glm::vec3(tx, ty, -1.0f));
}

// The scripted gaze: a slow Lissajous, at most 12 deg horizontally and 9 deg vertically from the
// view axis (under 15 deg in all).
inline glm::vec3 ScriptedGaze(int64_t xrTime) {
    double s = Seconds(xrTime);
    float tx = float(std::tan(12.0 * kTwoPi / 360.0) * std::sin(kTwoPi * s / 3.7));
    float ty = float(std::tan(9.0 * kTwoPi / 360.0) * std::sin(kTwoPi * s / 5.3 + 0.6));
    return GazeFromTangent(tx, ty);
}

// The gaze pose's orientation: the shortest-arc rotation taking -Z onto the gaze direction (no
// roll), so orientation * (0,0,-1) == direction.
inline glm::quat GazeOrientation(const glm::vec3& direction) {
    return glm::rotation(glm::vec3(0.0f, 0.0f, -1.0f), glm::normalize(direction));
}

}  // namespace fovrt::xrrt
