// Time-varying scene state: keyframe interpolation (key times, midpoints, clamping, looping),
// camera paths, light paths and switching, emissive-instance switching, texture lookup.
#include <cmath>

#include "scene/scene.h"
#include "test_support.h"

using namespace fovrt;

namespace {

TransformKey Key(float time, vec3 translate, float yDegrees = 0.0f, vec3 scale = vec3(1.0f)) {
    TransformKey k;
    k.time = time;
    k.pose.position = translate;
    k.pose.orientation = glm::angleAxis(Radians(yDegrees), vec3(0, 1, 0));
    k.scale = scale;
    return k;
}

vec3 Apply(const mat4& m, const vec3& p) { return vec3(m * vec4(p, 1.0f)); }

void CheckVec(const vec3& got, const vec3& want, float eps = 1e-5f) {
    INFO("got (" << got.x << ", " << got.y << ", " << got.z << ") want (" << want.x << ", " << want.y
                 << ", " << want.z << ")");
    CHECK(glm::length(got - want) < eps);
}

}  // namespace

TEST_CASE("instance keys: exact at key times, linear/slerp between, clamped outside", "[scene]") {
    Instance instance;
    CheckVec(Apply(instance.WorldFromObjectAt(3.0f), vec3(1, 2, 3)), vec3(1, 2, 3));  // no keys: identity
    instance.keys = {Key(1.0f, vec3(0, 0, 0), 0.0f, vec3(1.0f)), Key(3.0f, vec3(4, 2, 0), 90.0f, vec3(3.0f))};
    const vec3 p(1, 0, 0);
    CheckVec(Apply(instance.WorldFromObjectAt(1.0f), p), vec3(1, 0, 0));
    // t = 3: scale 3, rotate 90 deg about y ((1,0,0) -> (0,0,-1)), translate (4, 2, 0).
    CheckVec(Apply(instance.WorldFromObjectAt(3.0f), p), vec3(4, 2, -3));
    // Midpoint: translate (2, 1, 0), 45 deg, scale 2.
    float c = std::cos(Radians(45.0f));
    CheckVec(Apply(instance.WorldFromObjectAt(2.0f), p), vec3(2 + 2 * c, 1, -2 * c));
    // A quarter of the way: 22.5 deg, scale 1.5, translate (1, 0.5, 0).
    float a = Radians(22.5f);
    CheckVec(Apply(instance.WorldFromObjectAt(1.5f), p), vec3(1 + 1.5f * std::cos(a), 0.5f, -1.5f * std::sin(a)));
    // Clamped before the first and after the last key.
    CheckVec(Apply(instance.WorldFromObjectAt(-5.0f), p), vec3(1, 0, 0));
    CheckVec(Apply(instance.WorldFromObjectAt(100.0f), p), vec3(4, 2, -3));
}

TEST_CASE("looping keys repeat with the last key time as period", "[scene]") {
    Instance instance;
    instance.keys = {Key(0.0f, vec3(0, 0, 0)), Key(2.0f, vec3(2, 0, 0)), Key(4.0f, vec3(0, 0, 0))};
    instance.loop = true;
    CheckVec(Apply(instance.WorldFromObjectAt(1.0f), vec3(0.0f)), vec3(1, 0, 0));
    CheckVec(Apply(instance.WorldFromObjectAt(5.0f), vec3(0.0f)), vec3(1, 0, 0));
    CheckVec(Apply(instance.WorldFromObjectAt(7.0f), vec3(0.0f)), vec3(1, 0, 0));  // 3 -> descending
    CheckVec(Apply(instance.WorldFromObjectAt(-1.0f), vec3(0.0f)), vec3(1, 0, 0));
    CheckVec(Apply(instance.WorldFromObjectAt(4.5f), vec3(0.0f)), vec3(0.5f, 0, 0));
    instance.loop = false;
    CheckVec(Apply(instance.WorldFromObjectAt(5.0f), vec3(0.0f)), vec3(0, 0, 0));
}

TEST_CASE("camera path and head pose", "[scene]") {
    Scene scene;
    scene.cameraPath = {CameraKey{0.0f, Pose::LookAt(vec3(0, 0, 0), vec3(0, 0, -1))},
                        CameraKey{2.0f, Pose::LookAt(vec3(2, 0, 0), vec3(3, 0, 0))}};
    Pose mid = scene.HeadAt(1.0f);
    CheckVec(mid.position, vec3(1, 0, 0));
    // Forward turns from -z to +x: halfway it points along (1, 0, -1)/sqrt(2).
    CheckVec(mid.orientation * vec3(0, 0, -1), glm::normalize(vec3(1, 0, -1)));
    CheckVec(scene.HeadAt(-1.0f).position, vec3(0, 0, 0));
    CheckVec(scene.HeadAt(9.0f).orientation * vec3(0, 0, -1), vec3(1, 0, 0));
    CheckVec(scene.StateAt(1.0f).head.position, vec3(1, 0, 0));
    scene.cameraLoop = true;
    CheckVec(scene.HeadAt(3.0f).position, vec3(1, 0, 0));
}

TEST_CASE("switching schedules", "[scene]") {
    CHECK(SwitchedOn(0.0f, 0.0f, 0.0f, 0.0f));  // period 0: always on
    CHECK(SwitchedOn(0.5f, 1.0f, 0.7f, 0.0f));
    CHECK_FALSE(SwitchedOn(0.8f, 1.0f, 0.7f, 0.0f));
    CHECK(SwitchedOn(1.1f, 1.0f, 0.7f, 0.0f));
    CHECK_FALSE(SwitchedOn(-0.2f, 1.0f, 0.7f, 0.0f));  // phase 0.8
    // Offset shifts the schedule: on for [0.25, 0.95) within each second.
    CHECK_FALSE(SwitchedOn(0.1f, 1.0f, 0.7f, 0.25f));
    CHECK(SwitchedOn(0.3f, 1.0f, 0.7f, 0.25f));
    CHECK_FALSE(SwitchedOn(0.97f, 1.0f, 0.7f, 0.25f));
}

TEST_CASE("light paths, aiming and switching in StateAt", "[scene]") {
    Scene scene;
    Light spot;
    spot.type = LightType::Spot;
    spot.color = vec3(1, 0.5f, 0.25f);
    spot.intensity = 4.0f;
    spot.path = {Key(0.0f, vec3(-1, 2, 0)), Key(2.0f, vec3(1, 2, 0))};
    spot.aimAtTarget = true;
    spot.target = vec3(0, 0, 0);
    spot.spotInner = Radians(10.0f);
    spot.spotOuter = Radians(20.0f);
    spot.switchPeriod = 1.0f;
    spot.switchOnDuration = 0.5f;
    scene.lights.push_back(spot);

    SceneState s = scene.StateAt(1.0f);
    REQUIRE(s.lights.size() == 1);
    CheckVec(s.lights[0].position, vec3(0, 2, 0));
    CheckVec(s.lights[0].direction, vec3(0, -1, 0));
    CheckVec(s.lights[0].radiantIntensity, vec3(4, 2, 1));
    CHECK(s.lights[0].cosInner == Approx(std::cos(Radians(10.0f))));
    CHECK(s.lights[0].cosOuter == Approx(std::cos(Radians(20.0f))));
    SceneState off = scene.StateAt(1.75f);
    CheckVec(off.lights[0].radiantIntensity, vec3(0.0f));
    CheckVec(off.lights[0].position, vec3(0.75f, 2, 0));
    CheckVec(off.lights[0].direction, glm::normalize(vec3(-0.75f, -2, 0)));
}

TEST_CASE("room scene: flickering lamp, rotating crate, sweeping spot", "[scene]") {
    Scene room = LoadScene(ResolveSceneName("room"));
    size_t lamp = room.emissionSwitches.at(0).instance;
    CHECK(room.StateAt(0.5f).emissionScale[lamp] == 1.0f);
    CHECK(room.StateAt(0.8f).emissionScale[lamp] == 0.0f);
    CHECK(room.StateAt(1.1f).emissionScale[lamp] == 1.0f);
    CHECK(room.StateAt(0.8f).emissionScale[0] == 1.0f);  // the room itself never switches
    // Crate: translate (1.4, 0, -1.2), scale 0.5, rotation 0 -> 120 deg over 2 s: 60 deg at t = 1.
    size_t crate = 3;
    REQUIRE(room.instances[crate].name == "crate");
    float a = Radians(60.0f);
    vec3 expect = vec3(1.4f, 0, -1.2f) + 0.5f * vec3(std::cos(a), 0, -std::sin(a));
    CheckVec(Apply(room.StateAt(1.0f).worldFromObject[crate], vec3(1, 0, 0)), expect);
    // Loop period 6 s: t = 7 is t = 1.
    CheckVec(Apply(room.StateAt(7.0f).worldFromObject[crate], vec3(1, 0, 0)), expect);
    // Spot sweeps x from -1.5 to 1.5 over 3 s; the blinking point light is off in [1.5, 2).
    CheckVec(room.StateAt(1.5f).lights[0].position, vec3(0, 2.3f, 0.5f));
    CHECK(room.StateAt(1.0f).lights[1].radiantIntensity.b > 0.0f);
    CheckVec(room.StateAt(1.75f).lights[1].radiantIntensity, vec3(0.0f));
    // Camera dolly: halfway at t = 3.
    CheckVec(room.HeadAt(3.0f).position, vec3(0, 1.6f, 2.2f));
}

TEST_CASE("pillars move sideways and come back", "[scene]") {
    Scene pillars = LoadScene(ResolveSceneName("pillars"));
    size_t p = 4;  // pillar2: x from -0.75 to 0.75 and back, 4 s loop
    REQUIRE(pillars.instances[p].name == "pillar2");
    CheckVec(Apply(pillars.StateAt(0.0f).worldFromObject[p], vec3(0.0f)), vec3(-0.75f, 0, -1));
    CheckVec(Apply(pillars.StateAt(1.0f).worldFromObject[p], vec3(0.0f)), vec3(0, 0, -1));
    CheckVec(Apply(pillars.StateAt(3.0f).worldFromObject[p], vec3(0.0f)), vec3(0, 0, -1));
    CheckVec(Apply(pillars.StateAt(5.0f).worldFromObject[p], vec3(0.0f)), vec3(0, 0, -1));
    // Scale (0.25, 2, 0.25): the top of the unit cube is 2 m high.
    CheckVec(Apply(pillars.StateAt(2.0f).worldFromObject[p], vec3(0.5f, 1, 0)), vec3(0.875f, 2, -1));
    // A frame index maps to time = frame / frameRate.
    CHECK(pillars.frameRate == 30.0f);
}

TEST_CASE("texture sampling: bilinear with wrap, top-left origin", "[scene]") {
    Texture t;
    t.width = 2;
    t.height = 2;
    // Row 0 (top): 0, 1; row 1: 2, 3.
    t.texels = {vec4(0.0f), vec4(1.0f), vec4(2.0f), vec4(3.0f)};
    CHECK(t.Sample(vec2(0.25f, 0.25f)).x == Approx(0.0f));  // texel centres
    CHECK(t.Sample(vec2(0.75f, 0.25f)).x == Approx(1.0f));
    CHECK(t.Sample(vec2(0.25f, 0.75f)).x == Approx(2.0f));
    CHECK(t.Sample(vec2(0.5f, 0.5f)).x == Approx(1.5f));    // average of all four
    CHECK(t.Sample(vec2(0.5f, 0.25f)).x == Approx(0.5f));
    // Wrap: u = 0 lies halfway between the last and the first column.
    CHECK(t.Sample(vec2(0.0f, 0.25f)).x == Approx(0.5f));
    CHECK(t.Sample(vec2(1.25f, 0.25f)).x == Approx(0.0f));
    CHECK(t.Sample(vec2(-0.75f, 0.75f)).x == Approx(2.0f));
    CHECK(t.Sample(vec2(0.25f, 0.0f)).x == Approx(1.0f));   // between rows 1 and 0
    CHECK(t.Sample(vec2(0.375f, 0.25f)).x == Approx(0.25f));
    Texture empty;
    CHECK(empty.Sample(vec2(0.3f)).x == 1.0f);
}
