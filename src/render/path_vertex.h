// A path vertex as the integrator (render/integrator.h) and next-event estimation
// (render/light_sampler.h) read it: the surface and material at a hit, and what depends only on
// the direction the path arrives from.
#pragma once

#include <new>
#include <type_traits>

#include "render/bsdf.h"
#include "render/embree_scene.h"

namespace fovrt {

// Material parameters resolved at one surface point (textures applied).
struct ShadingPoint {
    SurfaceHit hit;
    BsdfParams bsdf;
    vec3 albedo;    // demodulation albedo
    vec3 emission;  // emitted radiance (scaled by the instance's switch), towards the front side
    bool emissionTwoSided = false;
};

// A path vertex with everything that depends only on the incoming direction, computed once
// (for the primary vertex: once per pixel, not per sample).
struct PathVertex {
    // Left uninitialised: a vertex is built in place (Resolve, InitVertex), never copied, since
    // copying ~200 bytes through the stack stalled store forwarding on every bounce.
    PathVertex() {}
    ShadingPoint p;
    vec3 ng;      // geometric normal on the side the path arrives from
    Frame frame;  // around the shading normal, bent so that wo stays above it
    BsdfWo wo;    // local outgoing direction and its BSDF terms
    vec3 origin;  // offset origin for rays leaving the surface
};

// The radiance p emits towards w (any length): none from the back of a one-sided emitter.
inline vec3 EmissionToward(const ShadingPoint& p, const vec3& w) {
    return p.emissionTwoSided || glm::dot(p.hit.geomNormal, w) > 0.0f ? p.emission : vec3(0.0f);
}

// Uninitialised room for one T, built in place by Emplace() when needed and never destroyed (T
// must be trivially destructible). Not std::optional: GCC zero-fills an optional's whole storage
// when it is constructed (192 bytes per path vertex, 2.3 KB for a group of eight path lanes).
template <typename T>
union RawSlot {
    static_assert(std::is_trivially_destructible_v<T>);
    RawSlot() {}
    T& Emplace() { return *new (&value) T(); }
    T value;
};

}  // namespace fovrt
