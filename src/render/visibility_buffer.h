// VisibilityBuffer: the path tracer's per-pixel working planes for one eye and frame — which
// surface sample each pixel shades and with which seed. Not part of FrameInputs: no denoiser reads
// them. The renderer keeps one per eye (two with A-SVGF gradient samples, whose forward projection
// reads the previous frame's); Renderer::Visibility(eye) shows the latest. The instance id of each
// entry is FrameInputs::objectId (the denoisers read that one), the sample count
// FrameInputs::sampleCount.
#pragma once

#include <cstdint>

#include "core/frame_inputs.h"
#include "core/plane_list.h"

namespace fovrt {

// X(member, element type, neutral value, EXR channels, doc), as FOVRT_FRAME_INPUT_PLANES.
#define FOVRT_VISIBILITY_PLANES(X)                                                                \
    X(primitiveId, uint32_t, kNoObject, "", "triangle index within the instance's mesh")          \
    X(barycentrics, vec2, vec2(0.0f), "UV", "(u, v) of the hit, Embree convention")               \
    X(worldPosition, vec3, vec3(0.0f), "XYZ",                                                     \
      "primary hit in world space (this frame); 0 for background")                                \
    X(seed, uint32_t, 0u, "",                                                                     \
      "per-pixel RNG seed of this frame (at an A-SVGF gradient pixel the previous frame's)")

struct VisibilityBuffer {
    FOVRT_VISIBILITY_PLANES(FOVRT_PLANE_MEMBER)

    int width() const { return seed.width(); }
    int height() const { return seed.height(); }

    // Every plane at W×H with its neutral value (background everywhere).
    void Allocate(int width, int height) { FOVRT_VISIBILITY_PLANES(FOVRT_PLANE_RESIZE) }
    // As FrameInputs::AllocateForOverwrite / SetNeutral.
    void AllocateForOverwrite(int width, int height) { FOVRT_VISIBILITY_PLANES(FOVRT_PLANE_RESIZE_FOR_OVERWRITE) }
    void SetNeutral(int x0, int y0, int x1, int y1) { FOVRT_VISIBILITY_PLANES(FOVRT_PLANE_SET_NEUTRAL) }
    size_t Bytes() const { return TotalPlaneBytes(*this); }

    // f(const PlaneSpec&, Plane<T>&) per plane, in list order (EXR layers: io/exr.h PlaneLayers).
    template <typename F>
    void VisitPlanes(F&& f) { FOVRT_VISIBILITY_PLANES(FOVRT_PLANE_VISIT) }
    template <typename F>
    void VisitPlanes(F&& f) const { FOVRT_VISIBILITY_PLANES(FOVRT_PLANE_VISIT) }
};

}  // namespace fovrt
