// Motion vectors (camera and rigid object motion) and stereo disparity.
#include <cmath>

#include "render/probes.h"
#include "render_test_scenes.h"
#include "test_support.h"

using namespace fovrt;
using namespace fovrt::test;

namespace {

constexpr int kW = 64, kH = 48;

// A wall at z = -wallZ (instance 0) and a small quad floating at z = -quadZ (instance 1), which
// moves by `motion` per frame.
Scene WallScene(float wallZ, float quadZ, const vec3& motion) {
    Scene s;
    s.name = "wall";
    Material m;
    m.baseColor = vec3(0.5f);
    s.materials.push_back(m);
    Mesh wall, quad;
    AddQuad(wall, vec3(0, 0, -wallZ), vec3(20, 0, 0), vec3(0, 20, 0), 0);
    AddQuad(quad, vec3(0, 0, -quadZ), vec3(0.1f, 0, 0), vec3(0, 0.1f, 0), 0);
    s.meshes = {wall, quad};
    s.instances.push_back(Instance{"wall", 0, {}, false});
    TransformKey k0, k1;
    k1.time = 1.0f / s.frameRate;
    k1.pose.position = motion;
    s.instances.push_back(Instance{"quad", 1, {k0, k1}, false});
    Light l;
    l.position = vec3(0, 1, 0);
    s.lights.push_back(l);
    s.cameraPath.push_back(CameraKey{});
    return s;
}

}  // namespace

TEST_CASE("camera motion: prevPixel is the surface point seen by the previous camera", "[render]") {
    Scene scene = WallScene(4.0f, 2.0f, vec3(0.0f));
    auto renderer = CreateRenderer(scene, RenderSettings{});
    Pose pose;
    Pose prevPose;
    prevPose.position = vec3(-0.05f, 0.02f, 0.1f);
    prevPose.orientation = glm::angleAxis(Radians(1.5f), vec3(0, 1, 0));
    EyeCamera camera = MakeCamera(pose, kW, kH), prevCamera = MakeCamera(prevPose, kW, kH);
    FrameInputs out;
    renderer->RenderEye(0, camera, prevCamera, Plane<uint16_t>(kW, kH, 1), out);
    int checked = 0;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            REQUIRE(out.objectId(x, y) != kNoObject);
            // The hit point from this frame's ray, projected with last frame's camera.
            vec3 dir = camera.WorldDirection(vec2(x + 0.5f, y + 0.5f));
            float z = out.objectId(x, y) == 0 ? 4.0f : 2.0f;
            vec3 world = camera.Position() + dir * (z / -dir.z);
            auto expected = prevCamera.Project(world);
            REQUIRE(expected);
            CHECK(out.prevPixel(x, y).x == Approx(expected->pixel.x).margin(0.01));
            CHECK(out.prevPixel(x, y).y == Approx(expected->pixel.y).margin(0.01));
            CHECK(out.linearDepth(x, y) == Approx(z).epsilon(1e-4));
            ++checked;
        }
    CHECK(checked == kW * kH);
}

TEST_CASE("pure camera translation shifts a fronto-parallel wall by f * t / z", "[render]") {
    Scene scene = WallScene(4.0f, 100.0f, vec3(0.0f));  // quad behind the wall: only the wall shows
    auto renderer = CreateRenderer(scene, RenderSettings{});
    Pose prevPose;
    prevPose.position = vec3(0.08f, 0.0f, 0.0f);
    EyeCamera camera = MakeCamera(Pose{}, kW, kH, 70.0f), prevCamera = MakeCamera(prevPose, kW, kH, 70.0f);
    FrameInputs out;
    renderer->RenderEye(0, camera, prevCamera, Plane<uint16_t>(kW, kH, 1), out);
    float focalPx = 0.5f * kW / std::tan(Radians(35.0f));
    float shift = focalPx * 0.08f / 4.0f;  // the camera moved right: the wall moves left on screen
    for (int y = 0; y < kH; y += 7)
        for (int x = 0; x < kW; x += 5) {
            CHECK(out.prevPixel(x, y).x == Approx(x + 0.5f - shift).margin(0.01));
            CHECK(out.prevPixel(x, y).y == Approx(y + 0.5f).margin(0.01));
            // Fronto-parallel plane: depth constant, zero gradient.
            CHECK(std::abs(out.depthGradient(x, y).x) < 1e-4f);
        }
}

TEST_CASE("object motion: prevPixel follows the previous object transform", "[render]") {
    const vec3 motion(0.1f, -0.05f, 0.0f);
    Scene scene = WallScene(4.0f, 2.0f, motion);
    auto renderer = CreateProbeRenderer(scene, RenderSettings{});  // WorldPosition: a probe
    EyeCamera camera = MakeCamera(Pose{}, kW, kH, 70.0f);
    renderer->SetFrame(0);
    renderer->SetFrame(1);
    FrameInputs out;
    renderer->RenderEye(0, camera, camera, Plane<uint16_t>(kW, kH, 1), out);
    const VisibilityBuffer& vis = renderer->Visibility(0);
    float focalPx = 0.5f * kW / std::tan(Radians(35.0f));
    int quadPixels = 0;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            vec2 centre(x + 0.5f, y + 0.5f);
            if (out.objectId(x, y) == 1u) {
                ++quadPixels;
                // The quad moved by `motion` since the last frame; screen y points down.
                CHECK(out.prevPixel(x, y).x == Approx(centre.x - focalPx * motion.x / 2.0f).margin(0.01));
                CHECK(out.prevPixel(x, y).y == Approx(centre.y + focalPx * motion.y / 2.0f).margin(0.01));
                CHECK(vis.worldPosition(x, y).x == Approx(renderer->WorldPosition(
                    SurfaceSample{1u, vis.primitiveId(x, y), vis.barycentrics(x, y)}).x));
            } else {
                REQUIRE(out.objectId(x, y) == 0u);
                CHECK(out.prevPixel(x, y).x == Approx(centre.x).margin(0.01));
                CHECK(out.prevPixel(x, y).y == Approx(centre.y).margin(0.01));
            }
        }
    CHECK(quadPixels >= 12);
}

TEST_CASE("stereo: a point at known depth shows the disparity IPD and FOV predict", "[render]") {
    const float depth = 1.5f;
    Scene scene = WallScene(50.0f, depth, vec3(0.0f));
    auto renderer = CreateRenderer(scene, RenderSettings{});
    StereoRig rig;
    rig.width = 256;
    rig.height = 128;
    rig.ipd = 0.063f;
    rig.fov[0] = rig.fov[1] = Fov::FromHorizontal(Radians(90.0f), 2.0f);
    float centroid[2];
    for (int eye = 0; eye < 2; ++eye) {
        EyeCamera camera = rig.Eye(eye);
        FrameInputs out;
        renderer->RenderEye(eye, camera, camera, Plane<uint16_t>(rig.width, rig.height, 1), out);
        // Sub-pixel position of the world point x = 0 on the quad: fit world x against the pixel
        // centre along the middle row (linear on a fronto-parallel plane) and solve for 0.
        double n = 0, sx = 0, sw = 0, sxx = 0, sxw = 0;
        int y = rig.height / 2;
        for (int x = 0; x < rig.width; ++x)
            if (out.objectId(x, y) == 1u) {
                double px = x + 0.5, wx = renderer->Visibility(eye).worldPosition(x, y).x;
                n += 1;
                sx += px;
                sw += wx;
                sxx += px * px;
                sxw += px * wx;
            }
        REQUIRE(n > 10);
        double slope = (n * sxw - sx * sw) / (n * sxx - sx * sx);
        double intercept = (sw - slope * sx) / n;
        centroid[eye] = float(-intercept / slope);
    }
    float focalPx = 0.5f * rig.width / std::tan(Radians(45.0f));
    float expected = focalPx * rig.ipd / depth;  // the left eye sees the point further right
    INFO("left " << centroid[0] << " right " << centroid[1] << " expected disparity " << expected);
    CHECK(centroid[0] - centroid[1] == Approx(expected).margin(0.35));
    CHECK(centroid[0] == Approx(rig.width / 2.0f + expected / 2.0f).margin(0.35));
}

TEST_CASE("depth gradient matches the linear depth of neighbouring pixels on a tilted plane", "[render]") {
    Scene scene;
    scene.name = "floor";
    scene.materials.push_back(Material{});
    Mesh floor;
    AddQuad(floor, vec3(0, -1, 0), vec3(0, 0, 50), vec3(50, 0, 0), 0);
    scene.meshes.push_back(floor);
    scene.instances.push_back(Instance{"floor", 0, {}, false});
    scene.cameraPath.push_back(CameraKey{});
    auto renderer = CreateRenderer(scene, RenderSettings{});
    Pose pose;
    pose.orientation = glm::angleAxis(Radians(-30.0f), vec3(1, 0, 0)) * glm::angleAxis(Radians(10.0f), vec3(0, 1, 0));
    EyeCamera camera = MakeCamera(pose, kW, kH, 70.0f);
    FrameInputs out;
    renderer->RenderEye(0, camera, camera, Plane<uint16_t>(kW, kH, 1), out);
    int checked = 0;
    for (int y = 1; y < kH - 1; ++y)
        for (int x = 1; x < kW - 1; ++x) {
            if (out.objectId(x, y) != 0u || out.objectId(x + 1, y) != 0u || out.objectId(x - 1, y) != 0u ||
                out.objectId(x, y + 1) != 0u || out.objectId(x, y - 1) != 0u)
                continue;
            float gx = 0.5f * (out.linearDepth(x + 1, y) - out.linearDepth(x - 1, y));
            float gy = 0.5f * (out.linearDepth(x, y + 1) - out.linearDepth(x, y - 1));
            vec2 g = out.depthGradient(x, y);
            float d = out.linearDepth(x, y);
            // On a plane depth = c / L(x) with L linear in the pixel, so the derivative g and the
            // central difference gc obey g = gc (1 - (g / d)^2) exactly.
            CHECK(g.x == Approx(gx * (1.0f - (g.x / d) * (g.x / d))).epsilon(0.005).margin(1e-4));
            CHECK(g.y == Approx(gy * (1.0f - (g.y / d) * (g.y / d))).epsilon(0.005).margin(1e-4));
            ++checked;
        }
    CHECK(checked > kW * kH / 4);
}
