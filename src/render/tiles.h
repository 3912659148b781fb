// The work split (as the Embree tutorials' renderTile → parallel_for): fixed 16×16 tiles run in
// parallel, so an image is identical for any thread count; per eye, the visibility buffer of a tile
// (TraceTile), then every entry shaded once (ShadeEntry: from TraceTile when nothing is merged,
// else from ShadeTile after A-SVGF's merge, render/forward_projection.h).
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "core/frame_inputs.h"
#include "render/camera_rays.h"
#include "render/embree_scene.h"
#include "render/integrator.h"
#include "render/ray_counts.h"
#include "render/visibility_buffer.h"

namespace fovrt {

constexpr int kTileSize = 16;  // pixels; fixed so work splits identically for any thread count

// Runs fn(x0, y0, x1, y1, counts) over fixed 16×16 tiles in parallel on `arena`; each tile's
// counters are added to `counters` afterwards.
template <typename Fn>
inline void ForEachTile(tbb::task_arena& arena, RenderCounters& counters, int w, int h, Fn&& fn) {
    int tilesX = (w + kTileSize - 1) / kTileSize, tilesY = (h + kTileSize - 1) / kTileSize;
    arena.execute([&] {
        tbb::parallel_for(0, tilesX * tilesY, [&](int tile) {
            int x0 = (tile % tilesX) * kTileSize, y0 = (tile / tilesX) * kTileSize;
            RayCounts counts;
            fn(x0, y0, std::min(x0 + kTileSize, w), std::min(y0 + kTileSize, h), counts);
            counters.Add(counts);
        });
    });
}

// Per-tile constants of one eye's frame.
struct EyeView {
    int eye;
    uint32_t frame;
    const EyeCamera& camera;
    const EyeCamera& prevCamera;
    const std::vector<InstanceXform>& prevXforms;  // the previous frame's instance transforms
    vec3 eyePos;
    mat3 prevView;
    EyeRays rays;
    EyeView(int e, uint32_t f, const EyeCamera& c, const EyeCamera& prev, const std::vector<InstanceXform>& prevX)
        : eye(e), frame(f), camera(c), prevCamera(prev), prevXforms(prevX), eyePos(c.Position()),
          prevView(mat3(prev.View())), rays(c) {}
};

// Shades visibility-buffer entry (x, y) = s with n samples from `seed` (n = 0: a guide ray, no
// path sample) and fills the remaining G-buffer planes. `dir`: world ray towards s (any length; background: the pixel's unit ray);
// `eyeRay`: the same ray in eye space with z = -1. Always inlined: as a call, the 1-spp
// bench ran 1.6 % more instructions than the single-sweep tracer before the split (callgrind).
template <typename Rays>
[[gnu::always_inline]] inline void ShadeEntry(const Integrator<Rays>& in, const EyeView& view, int x, int y,
                                              const SurfaceSample& s, uint32_t seed, int n, const vec3& dir,
                                              const vec3& eyeRay, FrameInputs& out, VisibilityBuffer& vis,
                                              Plane<float>& luminance, RayCounts& counts) {
    counts.guide += n == 0 ? 1 : 0;  // here, not in TraceTile: a merged gradient sample brings its own n
    if (s.instance == kNoObject) {
        out.emission(x, y) = in.scene().background;
        if (!luminance.empty()) luminance(x, y) = Luminance(in.scene().background);
        vec3 e = view.prevView * dir;
        out.prevPixel(x, y) = e.z < 0.0f ? view.prevCamera.PixelOfEyeDirection(e) : vec2(-1.0f);
        return;
    }
    SurfaceHit hit;
    PixelShade shade = in.ShadePixel(view.eyePos, s, seed, n, counts, &hit);
    vec3 ng = glm::dot(hit.geomNormal, dir) > 0.0f ? -hit.geomNormal : hit.geomNormal;
    vec3 ns = glm::dot(hit.shadingNormal, ng) < 0.0f ? -hit.shadingNormal : hit.shadingNormal;
    float depth = view.camera.LinearDepth(hit.position);
    out.direct(x, y) = shade.direct;
    out.indirect(x, y) = shade.indirect;
    out.albedo(x, y) = shade.albedo;
    out.fbeta(x, y) = shade.fbeta;
    out.emission(x, y) = shade.emission;
    out.normal(x, y) = ns;
    out.linearDepth(x, y) = depth;
    out.depthGradient(x, y) = DepthGradient(view.rays, eyeRay, ng, depth);
    out.roughness(x, y) = shade.roughness;
    vis.worldPosition(x, y) = hit.position;
    vec3 prevWorld = vec3(view.prevXforms[s.instance].worldFromObject * vec4(in.embree().ObjectPosition(s), 1.0f));
    auto prev = view.prevCamera.Project(prevWorld);
    out.prevPixel(x, y) = prev ? prev->pixel : vec2(-1.0f);
    if (!luminance.empty()) luminance(x, y) = Luminance(Remodulate(shade));
}

// Visibility buffer of one tile: primary rays through the pixel centres (8-wide packets along
// the row), the fresh per-pixel seeds and the spp map's sample counts (a pixel the map gives 0
// keeps its primary ray as a guide ray: guide planes filled, no path sample, direct = indirect = 0). `shade`: nothing will
// be merged, so each pixel is shaded right after its packet (one sweep, the rays at hand).
template <typename Rays>
inline void TraceTile(const Integrator<Rays>& in, const EyeView& view, const Plane<uint16_t>& spp, int x0, int y0, int x1,
               int y1, bool shade, FrameInputs& out, VisibilityBuffer& vis, Plane<float>& luminance,
               RayCounts& counts) {
    // Background in every plane first (the planes were sized for overwrite, so they hold the
    // last frame's values): one tile at a time, the writes below then hit cached lines instead
    // of following a whole-frame fill pass through memory.
    out.SetNeutral(x0, y0, x1, y1);
    vis.SetNeutral(x0, y0, x1, y1);
    for (int y = y0; y < y1; ++y) {
        for (int xs = x0; xs < x1; xs += 8) {
            vec3 dirs[8];
            bool valid[8];
            SurfaceSample hits[8];
            float ts[8];
            for (int i = 0; i < 8; ++i) {
                valid[i] = xs + i < x1;
                dirs[i] = view.rays.Direction(xs + i, y);
                counts.primary += valid[i] ? 1 : 0;
            }
            in.rays().Intersect8(view.eyePos, dirs, valid, hits, ts, true);
            for (int i = 0; i < 8 && xs + i < x1; ++i) {
                int x = xs + i;
                uint32_t seed = PixelSeed(in.settings().seed, uint32_t(view.eye), uint32_t(x), uint32_t(y), view.frame);
                int n = spp(x, y);  // 0: the guide planes only (a guide ray), colour 0
                vis.seed(x, y) = seed;
                out.sampleCount(x, y) = uint16_t(n);
                out.objectId(x, y) = hits[i].instance;
                vis.primitiveId(x, y) = hits[i].primitive;
                vis.barycentrics(x, y) = hits[i].barycentrics;
                if (shade)
                    ShadeEntry(in, view, x, y, hits[i], seed, n, dirs[i], view.rays.Eye(x, y), out, vis, luminance,
                               counts);
            }
        }
    }
}

// Shades every visibility-buffer entry of one tile once (after the merge). `merged` marks
// the forward-projected gradient samples: their surface point is not at the pixel centre, so
// view direction and depth gradient use the ray through the point itself.
template <typename Rays>
inline void ShadeTile(const Integrator<Rays>& in, const EyeView& view, const Plane<uint8_t>& merged, int x0, int y0, int x1,
               int y1, FrameInputs& out, VisibilityBuffer& vis, Plane<float>& luminance, RayCounts& counts) {
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
            SurfaceSample s{out.objectId(x, y), vis.primitiveId(x, y), vis.barycentrics(x, y)};
            uint32_t seed = vis.seed(x, y);
            int n = out.sampleCount(x, y);
            if (!merged(x, y)) {
                ShadeEntry(in, view, x, y, s, seed, n, view.rays.Direction(x, y), view.rays.Eye(x, y), out,
                           vis, luminance, counts);
                continue;
            }
            vec3 dir = in.PositionOf(s) - view.eyePos;
            vec3 eyeRay = view.rays.eyeFromWorld * dir;
            eyeRay /= -eyeRay.z;  // in front of the camera (forward projection checked it)
            ShadeEntry(in, view, x, y, s, seed, n, dir, eyeRay, out, vis, luminance, counts);
        }
}

}  // namespace fovrt
