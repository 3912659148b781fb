// The rays fovrt hands to Embree (render/embree_rays.h): every field set to what Embree expects,
// and the packet's AVX writes byte for byte the lane-by-lane ones, whatever the memory held.
#include <cstring>
#include <limits>

#include "core/rng.h"
#include "render/embree_rays.h"
#include "test_support.h"

using namespace fovrt;

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

template <typename T>
void Scribble(T& value, unsigned char byte) {
    std::memset(&value, byte, sizeof value);
}

}  // namespace

TEST_CASE("InitRay sets every field of the ray") {
    for (unsigned char garbage : {0x00, 0xCD, 0xFF}) {
        RTCRay ray;
        Scribble(ray, garbage);
        InitRay(ray, vec3(1.0f, -2.0f, 3.5f), vec3(0.0f, 0.6f, -0.8f), 42.0f);
        CHECK(ray.org_x == 1.0f);
        CHECK(ray.org_y == -2.0f);
        CHECK(ray.org_z == 3.5f);
        CHECK(ray.tnear == 0.0f);
        CHECK(ray.dir_x == 0.0f);
        CHECK(ray.dir_y == 0.6f);
        CHECK(ray.dir_z == -0.8f);
        CHECK(ray.time == 0.0f);
        CHECK(ray.tfar == 42.0f);
        CHECK(ray.mask == 0xFFFFFFFFu);
        CHECK(ray.id == 0u);
        CHECK(ray.flags == 0u);
    }
}

TEST_CASE("InitRayPacket8 writes the same packet lane by lane and with AVX") {
    Pcg32 rng(7);
    for (int pattern : {0xFF, 0x0F, 0x81, 0x01, 0x00, 0xA5}) {
        const vec3 origin(rng.NextFloat() - 0.5f, 2.0f * rng.NextFloat(), -rng.NextFloat());
        vec3 dirs[8];
        bool valid[8];
        for (int i = 0; i < 8; ++i) {
            dirs[i] = vec3(rng.NextFloat() - 0.5f, rng.NextFloat() - 0.5f, -rng.NextFloat());
            valid[i] = (pattern >> i) & 1;
        }
        alignas(32) int maskLanes[8];
        alignas(32) RTCRayHit8 lanes;
        Scribble(maskLanes, 0xCD);
        Scribble(lanes, 0xCD);
        InitRayPacket8(origin, dirs, valid, maskLanes, lanes, PacketWrites::Lanes);
        for (int i = 0; i < 8; ++i) {
            CHECK(maskLanes[i] == (valid[i] ? -1 : 0));
            CHECK(lanes.ray.org_x[i] == origin.x);
            CHECK(lanes.ray.org_y[i] == origin.y);
            CHECK(lanes.ray.org_z[i] == origin.z);
            CHECK(lanes.ray.tnear[i] == 0.0f);
            CHECK(lanes.ray.dir_x[i] == dirs[i].x);
            CHECK(lanes.ray.dir_y[i] == dirs[i].y);
            CHECK(lanes.ray.dir_z[i] == dirs[i].z);
            CHECK(lanes.ray.time[i] == 0.0f);
            CHECK(lanes.ray.tfar[i] == kInf);
            CHECK(lanes.ray.mask[i] == 0xFFFFFFFFu);
            CHECK(lanes.ray.id[i] == unsigned(i));
            CHECK(lanes.ray.flags[i] == 0u);
            CHECK(lanes.hit.geomID[i] == RTC_INVALID_GEOMETRY_ID);
            CHECK(lanes.hit.instID[0][i] == RTC_INVALID_GEOMETRY_ID);
        }
        if (!CpuHasAvx()) {
            WARN("this CPU has no AVX: the AVX packet writes are not checked here");
            continue;
        }
        alignas(32) int maskAvx[8];
        alignas(32) RTCRayHit8 avx;
        Scribble(maskAvx, 0xCD);
        Scribble(avx, 0xCD);
        InitRayPacket8(origin, dirs, valid, maskAvx, avx, PacketWrites::Avx);
        CHECK(std::memcmp(maskAvx, maskLanes, sizeof maskAvx) == 0);
        CHECK(std::memcmp(&avx, &lanes, sizeof avx) == 0);
        // Auto is one of the two.
        alignas(32) int maskAuto[8];
        alignas(32) RTCRayHit8 automatic;
        Scribble(maskAuto, 0xCD);
        Scribble(automatic, 0xCD);
        InitRayPacket8(origin, dirs, valid, maskAuto, automatic);
        CHECK(std::memcmp(&automatic, &lanes, sizeof automatic) == 0);
    }
}
