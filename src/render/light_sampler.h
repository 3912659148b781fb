// Lights and their sampling (as pbrt-v4's lightsamplers plus the integrator's SampleLd): the
// power distribution over emissive triangles, rebuilt per frame, and next-event estimation (NEE)
// with its MIS weights.
// - Area lights are one-sided, as in pbrt and Mitsuba: an emissive triangle emits only to the side
//   of its geometric normal (SurfaceHit::geomNormal: the winding's, or the authored normals' where
//   a mesh has them), both sides when its material is Material::emissionTwoSided. Seen from behind
//   it is black for every estimator alike: camera rays, BSDF-sampled hits and NEE (pdf 0).
// - Emissive triangles are sampled in proportion to their power (world area * luminance of the
//   emitted radiance * sides, times the instance's emission scale), then uniformly in area: a
//   two-sided triangle emits twice the flux of a one-sided one (pbrt's DiffuseAreaLight::Phi), and
//   scenes with one-sided lights only are sampled exactly as when every light was two-sided.
// - Point/spot/directional lights are all sampled at every vertex (one shadow ray each). At the
//   primary vertex that part does not depend on the sample, so the integrator traces it once per
//   pixel and reuses it for the pixel's n samples (DeterministicLights).
// Functions are declared inline as the tracer's in-class members were (GCC inlines by that hint).
// The shadow rays go through `Rays` (render/path_tracer.cpp: EmbreeScene or the probes' recorder).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "render/embree_scene.h"
#include "render/path_vertex.h"
#include "render/ray_counts.h"
#include "render/sampler.h"
#include "scene/scene.h"

namespace fovrt {

// The luminance by which lights are picked (per unit area): a two-sided emitter sends twice the
// flux of a one-sided one (pbrt's DiffuseAreaLight). The distribution and LightSampler::Pdf must
// agree on it, so both call this.
inline float SelectionLuminance(const vec3& emission, bool twoSided) {
    return Luminance(emission) * (twoSided ? 2.0f : 1.0f);
}

// MIS power heuristic (beta = 2) of a strategy with pdf a against one with pdf b.
inline float PowerHeuristic(float a, float b) { return a * a / (a * a + b * b); }

// An emissive triangle as NEE samples it in the current frame: world corner p0 and edges
// (p1 - p0, p2 - p0), unit geometric normal (SurfaceHit's at the centroid: the front side)
// and emitted radiance with the instance's emission scale. Built per frame, so a light
// sample costs no surface reconstruction.
struct Emitter {
    vec3 p0, e1, e2, normal, emission;
    bool twoSided;
};

// The point/spot/directional-light part of NEE at the primary vertex: it does not depend on the
// sample (same origin, same light direction), so it is computed and traced once per pixel and
// reused by all n samples (bit-identical: the same sum in the same order).
struct DeterministicLights {
    vec3 sum = vec3(0.0f);
    uint64_t shadowTests = 0;
};

class LightSampler {
public:
    // Finds the scene's emissive triangles (their power follows the frame: Build).
    explicit LightSampler(const Scene& scene);

    // The emitter table and power distribution of the frame `embree` was last updated to.
    void Build(const Scene& scene, const EmbreeScene& embree);

    bool HasEmitters() const { return power_ > 0.0f; }

    // Solid-angle pdf with which NEE picks a point on an emitter seen at distance t along wi
    // (from the receiver): 0 when the receiver is behind a one-sided emitter, which NEE then
    // skips and a BSDF-sampled hit sees black, so MIS weights stay consistent.
    float Pdf(const vec3& emission, const vec3& geomNormal, bool twoSided, float t, const vec3& wi) const {
        float lum = SelectionLuminance(emission, twoSided);
        float cosL = -glm::dot(geomNormal, wi);
        if (twoSided) cosL = std::abs(cosL);
        if (power_ <= 0.0f || lum <= 0.0f || cosL <= 0.0f) return 0.0f;
        return lum / power_ * t * t / cosL;
    }

    // Point/spot/directional lights at one vertex (one shadow ray each): the sample-independent
    // first part of Sample.
    template <typename Rays>
    DeterministicLights SampleDeterministic(const Rays& rays, const std::vector<LightState>& lights,
                                            const PathVertex& v) const;

    // Next-event estimation at one vertex: the point/spot/directional lights and one emitter
    // picked by sel.x. `mis`: weight the emitter sample against BSDF sampling. `cached`: the
    // vertex's SampleDeterministic() computed earlier (its shadow tests are counted again here,
    // as reused).
    // Always inlined (into Integrator::Advance), as when it was a member of one tracer class:
    // as a call, +1.2 % instructions on the 1-spp Cornell box (callgrind).
    template <typename Rays>
    [[gnu::always_inline]] vec3 Sample(const Rays& rays, const std::vector<LightState>& lights, const PathVertex& v,
                const PathSampler& sampler, int vertex, const vec2& sel, bool mis, RayCounts& counts,
                const DeterministicLights* cached = nullptr) const;

private:
    struct EmissiveTriangle {
        uint32_t instance, primitive;
    };
    std::vector<EmissiveTriangle> emissive_;
    std::vector<Emitter> emitters_;  // per emissive_ entry, current frame
    std::vector<float> cdf_;
    float power_ = 0.0f;
};

template <typename Rays>
inline DeterministicLights LightSampler::SampleDeterministic(const Rays& rays,
                                                             const std::vector<LightState>& lights,
                                                             const PathVertex& v) const {
    constexpr float kInf = std::numeric_limits<float>::infinity();
    const ShadingPoint& p = v.p;
    const vec3& ng = v.ng;
    const vec3& origin = v.origin;
    DeterministicLights out;
    vec3& result = out.sum;
    for (const LightState& light : lights) {
        if (light.radiantIntensity == vec3(0.0f)) continue;
        vec3 wi;
        float tFar;
        vec3 li;
        if (light.type == LightType::Directional) {
            wi = -glm::normalize(light.direction);
            tFar = kInf;
            li = light.radiantIntensity;
        } else {
            vec3 d = light.position - p.hit.position;
            float dist2 = glm::dot(d, d);
            if (!(dist2 > 0.0f)) continue;
            float dist = std::sqrt(dist2);
            wi = d / dist;
            tFar = dist * (1.0f - 1e-4f);
            li = light.radiantIntensity / dist2;
            if (light.type == LightType::Spot) {
                float c = glm::dot(-wi, glm::normalize(light.direction));
                float x = std::clamp((c - light.cosOuter) / std::max(light.cosInner - light.cosOuter, 1e-6f), 0.0f, 1.0f);
                li *= x * x * (3.0f - 2.0f * x);
                if (x <= 0.0f) continue;
            }
        }
        if (glm::dot(wi, ng) <= 0.0f) continue;
        BsdfEval e = EvalBsdf(p.bsdf, v.wo, v.frame.ToLocal(wi));
        if (e.fCos == vec3(0.0f)) continue;
        ++out.shadowTests;
        if (rays.Occluded(origin, wi, tFar)) continue;
        result += e.fCos * li;
    }
    return out;
}

template <typename Rays>
[[gnu::always_inline]] inline vec3 LightSampler::Sample(const Rays& rays, const std::vector<LightState>& lights, const PathVertex& v,
                                 const PathSampler& sampler, int vertex, const vec2& sel, bool mis,
                                 RayCounts& counts, const DeterministicLights* cached) const {
    const ShadingPoint& p = v.p;
    const vec3& ng = v.ng;
    const vec3& origin = v.origin;
    vec3 result(0.0f);
    if (cached) {
        result = cached->sum;
        counts.shadow += cached->shadowTests;
        counts.shadowReused += cached->shadowTests;
    } else {
        DeterministicLights fresh = SampleDeterministic(rays, lights, v);
        result = fresh.sum;
        counts.shadow += fresh.shadowTests;
    }
    if (power_ > 0.0f) {
        size_t index = size_t(std::upper_bound(cdf_.begin(), cdf_.end(), sel.x * power_) - cdf_.begin());
        index = std::min(index, emissive_.size() - 1);
        vec2 u = sampler.LightPoint(vertex);
        float su = std::sqrt(u.x);
        const Emitter& light = emitters_[index];
        vec2 b(su * (1.0f - u.y), su * u.y);
        vec3 lightPosition = light.p0 + b.x * light.e1 + b.y * light.e2;  // as SurfaceAt
        const vec3& emission = light.emission;
        vec3 d = lightPosition - p.hit.position;
        float dist2 = glm::dot(d, d);
        if (dist2 > 0.0f) {
            float dist = std::sqrt(dist2);
            vec3 wi = d / dist;
            float pdf = Pdf(emission, light.normal, light.twoSided, dist, wi);
            if (pdf > 0.0f && glm::dot(wi, ng) > 0.0f) {
                BsdfEval e = EvalBsdf(p.bsdf, v.wo, v.frame.ToLocal(wi));
                if (e.fCos != vec3(0.0f)) {
                    ++counts.shadow;
                    // The ray leaves the offset origin, so it meets the light's plane short
                    // of dist by offset / cos: near a light at grazing angles that exceeds the
                    // 1e-3 margin and the light shadowed itself (a ceiling 2 cm above one).
                    float tPlane = glm::dot(light.normal, lightPosition - origin) / glm::dot(light.normal, wi);
                    if (!rays.Occluded(origin, wi, std::min(dist, tPlane) * (1.0f - 1e-3f))) {
                        float weight = mis ? PowerHeuristic(pdf, e.pdf) : 1.0f;
                        result += e.fCos * emission * (weight / pdf);
                    }
                }
            }
        }
    }
    return result;
}

}  // namespace fovrt
