// PathTracer: the tracer behind Renderer, as a class template over the object its ray calls go
// through — EmbreeScene itself (CreateRenderer, path_tracer.cpp) or a RecordingScene over it
// (CreateProbeRenderer, probe_renderer.cpp). Internal to the render library. Per eye (RenderEye):
// the visibility buffer (TraceTile, into the eye's VisibilityBuffer, which the tracer keeps;
// FrameInputs gets only what denoisers read), with A-SVGF gradient samples the forward-projected
// previous surface samples merged into it (MergeGradientSamples), then every entry shaded once
// (ShadeEntry, from TraceTile when nothing is merged, else from ShadeTile).
// - An spp-map entry of 0 traces the pixel's primary ray only (a guide ray, RenderStats::guideRays):
//   its guide planes are filled, direct and indirect are 0, sampleCount is 0.
// - Static instances (at most one transform key) are flattened into the top-level BVH.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include <tbb/task_arena.h>

#include "core/check.h"
#include "render/embree_scene.h"
#include "render/forward_projection.h"
#include "render/integrator.h"
#include "render/ray_counts.h"
#include "render/reference.h"
#include "render/renderer.h"
#include "render/tiles.h"

namespace fovrt {

// `Rays`: what the ray calls go through (EmbreeScene itself, or a RecordingScene over it);
// `Interface`: Renderer or ProbeRenderer.
template <typename Rays, typename Interface>
class PathTracer : public Interface {
public:
    PathTracer(const Scene& scene, const RenderSettings& settings)
        : integrator_(scene, settings),
          arena_(settings.threads > 0 ? settings.threads : tbb::task_arena::automatic) {
        SetFrame(0);
    }

    using Interface::SetFrame;
    void SetFrame(uint32_t frame, float timeSeconds) override {
        if (hasFrame_ && frame == frame_) return;
        if (hasFrame_) prevXforms_ = integrator_.embree().xforms();
        frame_ = frame;
        integrator_.SetState(integrator_.scene().StateAt(timeSeconds));
        if (!hasFrame_) prevXforms_ = integrator_.embree().xforms();
        hasFrame_ = true;
    }

    const SceneState& State() const override { return integrator_.state(); }
    void SetGradientSamples(bool on) override { integrator_.SetGradientSamples(on); }
    void SetFbetaPlane(bool on) override { integrator_.SetFbetaPlane(on); }
    const Scene& GetScene() const override { return integrator_.scene(); }

    void RenderEye(int eye, const EyeCamera& camera, const EyeCamera& prevCamera,
                   const Plane<uint16_t>& spp, FrameInputs& out) override {
        FOVRT_CHECK(eye == 0 || eye == 1);
        const RenderSettings& settings = integrator_.settings();
        int w = camera.width(), h = camera.height();
        FOVRT_CHECK_OP(spp.width(), ==, w);
        FOVRT_CHECK_OP(spp.height(), ==, h);
        bool cut = out.cameraCut;
        out.AllocateForOverwrite(w, h);  // TraceTile sets every pixel of every plane
        out.eye = eye;
        out.frameIndex = frame_;
        out.timeSeconds = integrator_.state().time;
        out.camera = camera;
        out.prevCamera = prevCamera;
        out.demodulation = settings.demodulation;
        // The noisy luminance only feeds A-SVGF's gradient samples (this frame's and the history's).
        Plane<float> luminance;
        if (settings.gradientSamples) luminance.Resize(w, h, 0.0f);

        EyeHistory& history = history_[eye];
        EyeVisibility& visibility = visibility_[eye];
        if (settings.gradientSamples) visibility.latest = 1 - visibility.latest;  // last frame's is now Previous()
        VisibilityBuffer& vis = visibility.Latest();
        vis.AllocateForOverwrite(w, h);
        bool merge = settings.gradientSamples && history.valid && !cut && history.frame + 1 == frame_ &&
                     history.instance.width() == w && history.instance.height() == h;
        const EyeView view(eye, frame_, camera, prevCamera, prevXforms_);
        // Nothing to merge: visibility and shading in one sweep.
        ForEachTile(arena_, counters_, w, h, [&](int x0, int y0, int x1, int y1, RayCounts& counts) {
            TraceTile(integrator_, view, spp, x0, y0, x1, y1, !merge, out, vis, luminance, counts);
        });
        if (merge) {
            // A-SVGF (paper §3): the forward-projected previous surface samples and seeds merged
            // into the new visibility buffer, then every entry shaded once.
            Plane<uint8_t> merged(w, h, uint8_t(0));
            MergeGradientSamples(integrator_.embree(), settings.seed, frame_, eye, camera, history,
                                 visibility.Previous(), out, vis, merged);
            ForEachTile(arena_, counters_, w, h, [&](int x0, int y0, int x1, int y1, RayCounts& counts) {
                ShadeTile(integrator_, view, merged, x0, y0, x1, y1, out, vis, luminance, counts);
            });
            // f_i(G→, ξ_{i−1}) is the merged pixel's own shading.
            for (GradientSample& g : out.gradientSamples) g.newLuminance = luminance(g.pixel.x, g.pixel.y);
        }

        if (!settings.gradientSamples) return;  // the history only feeds gradient samples
        history.valid = true;
        history.frame = frame_;
        history.instance = out.objectId;
        history.sampleCount = out.sampleCount;
        history.luminance = std::move(luminance);
    }

    void RenderReference(int eye, const EyeCamera& camera, int spp, uint32_t seed, Plane<vec3>& out) override {
        fovrt::RenderReference(integrator_, arena_, counters_, eye, camera, spp, seed, out);
    }

    const VisibilityBuffer& Visibility(int eye) const override {
        FOVRT_CHECK(eye == 0 || eye == 1);
        return visibility_[eye].Latest();
    }

    RenderStats Stats() const override { return counters_.Stats(); }
    void ResetStats() override { counters_.Reset(); }

    void Restart(uint32_t seed) override {
        integrator_.SetSeed(seed);
        counters_.Reset();
        for (int eye = 0; eye < 2; ++eye) {
            history_[eye] = EyeHistory{};
            visibility_[eye] = EyeVisibility{};
        }
        hasFrame_ = false;
        SetFrame(0);  // as the constructor: frame 0's state is also the first previous frame's
    }

protected:
    Integrator<Rays> integrator_;
    mutable tbb::task_arena arena_;
    mutable RenderCounters counters_;
    bool hasFrame_ = false;
    uint32_t frame_ = 0;
    std::vector<InstanceXform> prevXforms_;  // the previous frame's (motion vectors)
    EyeHistory history_[2];
    EyeVisibility visibility_[2];
};

}  // namespace fovrt
