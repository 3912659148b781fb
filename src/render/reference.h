// The high-spp reference (Renderer::RenderReference): every pixel's primary ray through its
// centre, shaded with `spp` samples by the same integrator as the noisy frames, from the
// reference's own seed (decorrelated from the noisy frames' by kReferenceStream).
#pragma once

#include <cstdint>
#include <limits>

#include <tbb/task_arena.h>

#include "core/camera.h"
#include "core/check.h"
#include "core/image.h"
#include "core/rng.h"
#include "render/integrator.h"
#include "render/ray_counts.h"
#include "render/tiles.h"

namespace fovrt {

constexpr uint32_t kReferenceStream = 0x52454631u;  // decorrelates reference seeds from noisy ones

template <typename Rays>
inline void RenderReference(const Integrator<Rays>& in, tbb::task_arena& arena, RenderCounters& counters, int eye,
                     const EyeCamera& camera, int spp, uint32_t seed, Plane<vec3>& out) {
    constexpr float kInf = std::numeric_limits<float>::infinity();
    FOVRT_CHECK_OP(spp, >=, 1);
    int w = camera.width(), h = camera.height();
    out.Resize(w, h, vec3(0.0f));
    const uint32_t referenceSeed = HashCombine(seed, kReferenceStream);
    ForEachTile(arena, counters, w, h, [&](int x0, int y0, int x1, int y1, RayCounts& counts) {
        for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x) {
                vec3 dir = camera.WorldDirection(vec2(x + 0.5f, y + 0.5f));
                SurfaceSample s;
                float t;
                ++counts.primary;
                if (!in.rays().Intersect(camera.Position(), dir, kInf, s, t, true)) {
                    out(x, y) = in.scene().background;
                    continue;
                }
                const uint32_t pixelSeed = PixelSeed(referenceSeed, uint32_t(eye), uint32_t(x), uint32_t(y), 0u);
                out(x, y) = in.ShadePixel(camera.Position(), s, pixelSeed, spp, counts).radiance;
            }
    });
}

}  // namespace fovrt
