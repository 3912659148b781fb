#include "render/embree_rays.h"

#include <bit>
#include <cstddef>
#include <cstdint>
#include <limits>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

#include "core/check.h"

namespace fovrt {
namespace {

// may_alias: RTCRay's float and unsigned fields are written through these.
using Float4 = float __attribute__((vector_size(16), may_alias));
using Uint4 = uint32_t __attribute__((vector_size(16), may_alias));
static_assert(offsetof(RTCRay, tnear) == 12 && offsetof(RTCRay, time) == 28 && offsetof(RTCRay, flags) == 44,
              "InitRay writes RTCRay as three 16-byte groups");

void InitRayPacket8Lanes(const vec3& o, const vec3* dirs, const bool* valid, int* mask, RTCRayHit8& rh) {
    for (int i = 0; i < 8; ++i) {
        mask[i] = valid[i] ? -1 : 0;
        rh.ray.org_x[i] = o.x;
        rh.ray.org_y[i] = o.y;
        rh.ray.org_z[i] = o.z;
        rh.ray.tnear[i] = 0.0f;
        rh.ray.dir_x[i] = dirs[i].x;
        rh.ray.dir_y[i] = dirs[i].y;
        rh.ray.dir_z[i] = dirs[i].z;
        rh.ray.time[i] = 0.0f;
        rh.ray.tfar[i] = std::numeric_limits<float>::infinity();
        rh.ray.mask[i] = 0xFFFFFFFFu;
        rh.ray.id[i] = unsigned(i);
        rh.ray.flags[i] = 0;
        rh.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
    }
}

#if defined(__x86_64__)
[[gnu::target("avx")]] void InitRayPacket8Avx(const vec3& o, const vec3* dirs, const bool* valid, int* mask,
                                              RTCRayHit8& rh) {
    const __m256 zero = _mm256_setzero_ps();
    const __m256i none = _mm256_set1_epi32(int(RTC_INVALID_GEOMETRY_ID));
    // valid[i] (0 or 1) read byte by byte, as the caller has just written them, then negated.
    const __m128i z = _mm_setzero_si128();
    const __m128i lo = _mm_sub_epi32(z, _mm_setr_epi32(valid[0], valid[1], valid[2], valid[3]));
    const __m128i hi = _mm_sub_epi32(z, _mm_setr_epi32(valid[4], valid[5], valid[6], valid[7]));
    _mm256_store_si256(reinterpret_cast<__m256i*>(mask), _mm256_set_m128i(hi, lo));
    _mm256_store_ps(rh.ray.org_x, _mm256_set1_ps(o.x));
    _mm256_store_ps(rh.ray.org_y, _mm256_set1_ps(o.y));
    _mm256_store_ps(rh.ray.org_z, _mm256_set1_ps(o.z));
    _mm256_store_ps(rh.ray.tnear, zero);
    float* dirFields[3] = {rh.ray.dir_x, rh.ray.dir_y, rh.ray.dir_z};
    for (int c = 0; c < 3; ++c)
        _mm256_store_ps(dirFields[c], _mm256_setr_ps(dirs[0][c], dirs[1][c], dirs[2][c], dirs[3][c], dirs[4][c],
                                                     dirs[5][c], dirs[6][c], dirs[7][c]));
    _mm256_store_ps(rh.ray.time, zero);
    _mm256_store_ps(rh.ray.tfar, _mm256_set1_ps(std::numeric_limits<float>::infinity()));
    _mm256_store_si256(reinterpret_cast<__m256i*>(rh.ray.mask), _mm256_set1_epi32(-1));
    _mm256_store_si256(reinterpret_cast<__m256i*>(rh.ray.id), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7));
    _mm256_store_si256(reinterpret_cast<__m256i*>(rh.ray.flags), _mm256_setzero_si256());
    _mm256_store_si256(reinterpret_cast<__m256i*>(rh.hit.geomID), none);
    _mm256_store_si256(reinterpret_cast<__m256i*>(rh.hit.instID[0]), none);
}
#endif

}  // namespace

void InitRay(RTCRay& ray, const vec3& o, const vec3& d, float tFar) {
    // Stored through vector lvalues, not memcpy: GCC may lower a memcpy of a vector into two
    // 8-byte stores (it did where two InitRay calls shared a tail), which undoes the point.
    auto* groups = reinterpret_cast<Float4*>(&ray.org_x);
    groups[0] = Float4{o.x, o.y, o.z, 0.0f};
    groups[1] = Float4{d.x, d.y, d.z, 0.0f};
    *reinterpret_cast<Uint4*>(&ray.tfar) = Uint4{std::bit_cast<uint32_t>(tFar), 0xFFFFFFFFu, 0u, 0u};
}

bool CpuHasAvx() {
#if defined(__x86_64__)
    static const bool avx = __builtin_cpu_supports("avx");
    return avx;
#else
    return false;
#endif
}

void InitRayPacket8(const vec3& o, const vec3* dirs, const bool* valid, int* mask, RTCRayHit8& rh,
                    PacketWrites writes) {
    if (writes == PacketWrites::Auto) writes = CpuHasAvx() ? PacketWrites::Avx : PacketWrites::Lanes;
#if defined(__x86_64__)
    if (writes == PacketWrites::Avx) {
        FOVRT_CHECK(CpuHasAvx());
        InitRayPacket8Avx(o, dirs, valid, mask, rh);
        return;
    }
#else
    FOVRT_CHECK(writes == PacketWrites::Lanes);
#endif
    InitRayPacket8Lanes(o, dirs, valid, mask, rh);
}

}  // namespace fovrt
