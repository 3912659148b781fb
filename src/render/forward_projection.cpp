#include "render/forward_projection.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/rng.h"
#include "render/renderer.h"

namespace fovrt {
namespace {

constexpr float kGradientDepthTolerance = 0.01f;  // relative depth match for forward projection
constexpr uint32_t kGradientStream = 0x47524144u;   // random pixel per stratum

// A pixel the previous frame gave no path sample has no f_{i-1} to difference against (its
// luminance is its emission alone): the stratum's sample moves to the next pixel, in raster order
// from the drawn one (px, py), that had samples. False when no pixel of the stratum had any.
bool SampledPixelOfStratum(const Plane<uint16_t>& prevCount, int bx, int by, int sizeX, int sizeY, int& px, int& py) {
    const int first = (py - by) * sizeX + (px - bx), cells = sizeX * sizeY;
    for (int k = 0; k < cells; ++k) {
        const int cell = (first + k) % cells;
        const int x = bx + cell % sizeX, y = by + cell / sizeX;
        if (prevCount(x, y) == 0) continue;
        px = x, py = y;
        return true;
    }
    return false;
}

}  // namespace

void MergeGradientSamples(const EmbreeScene& embree, uint32_t runSeed, uint32_t frame, int eye,
                          const EyeCamera& camera, const EyeHistory& history, const VisibilityBuffer& prevVis,
                          FrameInputs& out, VisibilityBuffer& vis, Plane<uint8_t>& merged) {
    int w = camera.width(), h = camera.height();
    int sw = (w + kGradientStratumSize - 1) / kGradientStratumSize;
    int sh = (h + kGradientStratumSize - 1) / kGradientStratumSize;
    std::vector<uint8_t> taken(size_t(sw) * size_t(sh), 0);
    for (int sy = 0; sy < sh; ++sy) {
        for (int sx = 0; sx < sw; ++sx) {
            Pcg32 rng(PixelSeed(HashCombine(runSeed, kGradientStream), uint32_t(eye),
                                uint32_t(sx), uint32_t(sy), frame));
            int bx = sx * kGradientStratumSize, by = sy * kGradientStratumSize;
            const int sizeX = std::min(kGradientStratumSize, w - bx), sizeY = std::min(kGradientStratumSize, h - by);
            int px = bx + int(rng.NextBounded(uint32_t(sizeX)));
            int py = by + int(rng.NextBounded(uint32_t(sizeY)));
            if (!SampledPixelOfStratum(history.sampleCount, bx, by, sizeX, sizeY, px, py)) continue;
            if (history.instance(px, py) == kNoObject) continue;
            SurfaceSample s{history.instance(px, py), prevVis.primitiveId(px, py), prevVis.barycentrics(px, py)};
            auto proj = camera.Project(embree.Surface(s).position);
            if (!proj) continue;
            int cx = int(std::floor(proj->pixel.x)), cy = int(std::floor(proj->pixel.y));
            if (!out.objectId.InBounds(cx, cy) || out.objectId(cx, cy) == kNoObject) continue;
            size_t stratum = size_t(cy / kGradientStratumSize) * size_t(sw) + size_t(cx / kGradientStratumSize);
            if (taken[stratum]) continue;  // first wins; so (cx, cy) still holds its own entry
            SurfaceSample here{out.objectId(cx, cy), vis.primitiveId(cx, cy), vis.barycentrics(cx, cy)};
            bool sameSurface = here.instance == s.instance && here.primitive == s.primitive;
            if (!sameSurface) {
                float depth = camera.LinearDepth(embree.Surface(here).position);
                if (std::abs(depth - proj->linearDepth) > kGradientDepthTolerance * proj->linearDepth)
                    continue;  // occluded in this frame
            }
            taken[stratum] = 1;
            merged(cx, cy) = 1;
            out.objectId(cx, cy) = s.instance;
            vis.primitiveId(cx, cy) = s.primitive;
            vis.barycentrics(cx, cy) = s.barycentrics;
            vis.seed(cx, cy) = prevVis.seed(px, py);
            out.sampleCount(cx, cy) = history.sampleCount(px, py);
            GradientSample g;
            g.stratum = ivec2(cx / kGradientStratumSize, cy / kGradientStratumSize);
            g.pixel = ivec2(cx, cy);
            g.prevPixel = ivec2(px, py);
            g.oldLuminance = history.luminance(px, py);
            g.newLuminance = 0.0f;
            out.gradientSamples.push_back(g);
        }
    }
}

}  // namespace fovrt
