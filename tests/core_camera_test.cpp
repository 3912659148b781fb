#include "core/camera.h"

#include "test_support.h"

using namespace fovrt;

TEST_CASE("pixel directions and projection are inverse", "[core]") {
    Fov fov{Radians(-50.0f), Radians(40.0f), Radians(35.0f), Radians(-45.0f)};  // asymmetric
    Pose pose = Pose::LookAt(vec3(1, 2, 3), vec3(0, 1, -2));
    EyeCamera camera(pose, fov, 320, 200);
    for (vec2 pixel : {vec2(0.5f, 0.5f), vec2(160.0f, 100.0f), vec2(319.5f, 17.25f)}) {
        vec3 world = camera.Position() + 3.0f * camera.WorldDirection(pixel);
        auto projected = camera.Project(world);
        REQUIRE(projected.has_value());
        CHECK(projected->pixel.x == Approx(pixel.x).margin(1e-3));
        CHECK(projected->pixel.y == Approx(pixel.y).margin(1e-3));
    }
}

TEST_CASE("fov edges map to image edges", "[core]") {
    Fov fov{Radians(-50.0f), Radians(40.0f), Radians(35.0f), Radians(-45.0f)};
    EyeCamera camera(Pose{}, fov, 100, 80);
    vec3 left = camera.EyeDirection(vec2(0.0f, 40.0f));
    vec3 top = camera.EyeDirection(vec2(50.0f, 0.0f));
    CHECK(std::atan2(left.x, -left.z) == Approx(fov.angleLeft).margin(1e-5));
    CHECK(std::atan2(top.y, -top.z) == Approx(fov.angleUp).margin(1e-5));
}

TEST_CASE("projection matrix agrees with Project()", "[core]") {
    Fov fov{Radians(-50.0f), Radians(40.0f), Radians(35.0f), Radians(-45.0f)};
    EyeCamera camera(Pose::LookAt(vec3(0, 1, 4), vec3(0.2f, 0.9f, 0)), fov, 640, 360);
    vec3 world(0.3f, 0.7f, -0.5f);
    vec4 clip = camera.ViewProjection() * vec4(world, 1.0f);
    vec2 ndc = vec2(clip) / clip.w;
    vec2 pixel((ndc.x * 0.5f + 0.5f) * 640.0f, (0.5f - ndc.y * 0.5f) * 360.0f);
    auto projected = camera.Project(world);
    REQUIRE(projected);
    CHECK(projected->pixel.x == Approx(pixel.x).margin(1e-2));
    CHECK(projected->pixel.y == Approx(pixel.y).margin(1e-2));
    CHECK(projected->linearDepth == Approx(clip.w).epsilon(1e-5));
}

TEST_CASE("stereo rig separates eyes by the IPD along head x", "[core]") {
    StereoRig rig;
    rig.head = Pose::LookAt(vec3(0, 1.6f, 0), vec3(1, 1.6f, 0));  // looking down +X world
    rig.ipd = 0.064f;
    vec3 left = rig.Eye(0).Position(), right = rig.Eye(1).Position();
    CHECK(glm::length(right - left) == Approx(0.064f));
    // Looking down +X with +Y up, right = forward × up = +Z: the right eye sits at larger z.
    CHECK(right.z > left.z);
}
