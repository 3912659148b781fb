// How fovrt writes rays for Embree. Embree reads a single ray's (org, tnear) and (dir, time) as
// 16-byte loads (its Vec3fa) and each field of an 8-ray packet as one 32-byte load. A load that
// follows narrower stores to the same bytes cannot be served from the store buffer (store-to-load
// forwarding) and waits until the stores have reached the cache, once per field and ray; written
// here as whole vectors, the loads are served at once (`fovrt bench`'s bare rtcOccluded1 /
// rtcIntersect1 rays +26 to +36 % per second; src/render/PROFILE.md, fifth pass).
#pragma once

#include <embree3/rtcore.h>

#include "core/math.h"

namespace fovrt {

// origin + t dir for t in [0, tFar], time 0, every mask bit, id 0, no flags.
void InitRay(RTCRay& ray, const vec3& origin, const vec3& dir, float tFar);

// How an 8-ray packet is written: one 32-byte AVX store per field where the CPU has AVX (Auto),
// or lane by lane (4- or 8-byte stores). Both write the same bytes.
enum class PacketWrites { Auto, Lanes, Avx };
bool CpuHasAvx();

// Eight rays from `origin` along dirs[i] (t in [0, inf)), mask[i] = -1 where valid[i], else 0;
// hit.geomID and hit.instID[0] cleared to RTC_INVALID_GEOMETRY_ID. mask and rh 32-byte aligned.
void InitRayPacket8(const vec3& origin, const vec3* dirs, const bool* valid, int* mask, RTCRayHit8& rh,
                    PacketWrites writes = PacketWrites::Auto);

}  // namespace fovrt
