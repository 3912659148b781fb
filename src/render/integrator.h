// The integrator (as pbrt-v4's integrators): one path sample vertex by vertex (Advance: NEE
// and the BSDF continuation; Land: the bounce ray's hit; Finish: the rest of the path), and
// ShadePixel, the n samples of one primary surface sample. It owns what shading reads: the
// scene, the resolved materials, the Embree scene and the ray calls (`Rays`: EmbreeScene, or the
// probes' RecordingScene), the light sampler and the frame's scene state.
//
// Conventions:
// - Primary visibility is noise-free: one ray through the pixel centre (a merged gradient sample
//   excepted); the n samples all start at that primary surface sample (so a visibility-buffer
//   entry and its seed reproduce them: ProbeRenderer::Shade).
// - maxDepth = path vertices after the camera. Vertex k < maxDepth: next-event estimation (MIS,
//   power heuristic, against BSDF sampling) + a BSDF-sampled continuation whose emitter hits are
//   MIS-weighted. The last vertex only does NEE, with full weight (no continuation ray). So a
//   white furnace with emission Le and albedo a gives Le * sum_{k=0..maxDepth} a^k: k = 0 is the
//   emission seen at the primary hit, k = j the light arriving after j reflections.
// - Lights, one-sided emitters and how they are picked: render/light_sampler.h.
// - "direct" = paths with one reflection (NEE at the primary hit, emitters hit by the first
//   bounce); "indirect" = the rest. Both are divided by the same primary-hit factor
//   (RenderSettings::demodulation): the albedo, or F_β (Zhuang et al. Fig. 3); emission is not.
// - Demodulation albedo = diffuse reflectance + normal-incidence specular reflectance F0,
//   clamped to [1e-3, 1] (per channel), so albedo * (L / albedo) reproduces L also for black
//   dielectrics and metals (whose albedo is then their base colour).
// - F_β = the BSDF's directional albedo at the primary hit's outgoing cosine (the BSDF's own
//   local wo, after the shading-normal bend), from the shared pre-integrated table
//   (render/brdf_table.h), clamped below at 1e-3 only (it may exceed 1 at grazing angles). The
//   albedo plane is always written; the F_β plane under brdf demodulation or when asked
//   (RenderSettings::fbetaPlane, for "+brdf" variants), so that one render feeds both kinds of
//   variant and albedo-only runs skip the lookups (0 in the plane).
// - Samples with a non-finite value are dropped (contribute 0, counted in RenderStats).
// - Throughput (same results as tracing every ray one at a time, bit for bit): the point/spot/
//   directional-light shadow rays of the primary vertex are traced once per pixel and reused by
//   its n samples (RenderStats::shadowRaysReused), and the first bounce rays of up to 8 samples
//   (all leaving the primary vertex) are traced as one rtcIntersect8 packet when n >= 2.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include "core/error.h"
#include "core/frame_inputs.h"
#include "render/brdf_table.h"
#include "render/bsdf.h"
#include "render/embree_scene.h"
#include "render/light_sampler.h"
#include "render/path_vertex.h"
#include "render/ray_counts.h"
#include "render/renderer.h"
#include "render/sampler.h"
#include "scene/scene.h"

namespace fovrt {

constexpr float kMinAlbedo = 1e-3f;  // demodulation guard (Falcor's max(albedo, 1e-3))

// Demodulated result of n samples at one primary surface sample.
// Demodulated result of n samples at one primary surface sample.
struct PixelShade {
    vec3 direct = vec3(0.0f);      // divided by `modulation`
    vec3 indirect = vec3(0.0f);    // divided by `modulation`
    vec3 albedo = vec3(0.0f);
    vec3 fbeta = vec3(0.0f);
    vec3 modulation = vec3(0.0f);  // albedo or fbeta (RenderSettings::demodulation)
    vec3 emission = vec3(0.0f);
    vec3 radiance = vec3(0.0f);  // emission + direct + indirect, not demodulated
    float roughness = 0.0f;      // primary hit's GGX roughness (sqrt alpha): the RAE's input
};

// Uninitialised room for one T, built in place by Emplace() when needed and never destroyed (T

// core's Remodulate, as FrameInputs::NoisyColor uses: re-shaded and stored luminances match bit for bit.
inline vec3 Remodulate(const PixelShade& s) {
    return fovrt::Remodulate(s.modulation, s.direct, s.indirect, s.emission);
}

template <typename Rays>
class Integrator {
public:
    // Fails (one line naming the scene) on a bad maxDepth, material index or texture index.
    Integrator(const Scene& scene, const RenderSettings& settings)
        : scene_(Checked(scene, settings)), settings_(settings), embree_(std::make_unique<EmbreeScene>(scene_)),
          rays_(*embree_), lights_(scene_) {
        for (const Material& m : scene_.materials) {
            ResolvedMaterial r;
            r.textured = m.baseColorTexture >= 0 || m.metallicRoughnessTexture >= 0 || m.roughnessTexture >= 0 ||
                         m.metallicTexture >= 0;
            r.bsdf = MakeBsdfParams(m.baseColor, m.roughness, m.metallic, m.specular);
            r.albedo = glm::clamp(r.bsdf.diffuse + r.bsdf.f0, vec3(kMinAlbedo), vec3(1.0f));
            materials_.push_back(r);
        }
        SetFbetaPlane(settings_.fbetaPlane);
    }

    // Moves the scene to `state`: instance transforms, BVH, emitters.
    void SetState(const SceneState& state) {
        state_ = state;
        embree_->Update(state_);
        lights_.Build(scene_, *embree_);
    }
    void SetGradientSamples(bool on) { settings_.gradientSamples = on; }
    void SetSeed(uint32_t seed) { settings_.seed = seed; }
    void SetFbetaPlane(bool on) {
        settings_.fbetaPlane = on;
        // The table (seconds to build) only once some frame needs F_β.
        if (!fbetaTable_ && (on || settings_.demodulation == Demodulation::Brdf)) fbetaTable_ = &SharedBrdfTable();
    }

    const Scene& scene() const { return scene_; }
    const RenderSettings& settings() const { return settings_; }
    const SceneState& state() const { return state_; }
    const EmbreeScene& embree() const { return *embree_; }
    const Rays& rays() const { return rays_; }
    Rays& rays() { return rays_; }

    // World position of a surface sample in the current frame.
    vec3 PositionOf(const SurfaceSample& sample) const { return embree_->Surface(sample).position; }

    // Whether a vertex reads its selectors: x picks the emitter (only with emissive triangles), y
    // the BSDF lobe (only where a bounce follows and the surface has a specular lobe: with
    // pSpec = 0 every y in [0, 1) picks the diffuse lobe, as 0 does).
    bool ReadsSelectors(bool last, float pSpec) const { return lights_.HasEmitters() || (!last && pSpec > 0.0f); }

    // The vertex's selectors, drawn only when read: every image is unchanged, and the sampler's
    // work halves on Lambert surfaces lit by point lights.
    vec2 Selectors(const PathVertex& v, const PathSampler& sampler, int vertex, bool last) const {
        return ReadsSelectors(last, v.wo.pSpec) ? sampler.Selectors(vertex) : vec2(0.0f);
    }

    // Completes vertex v (v.p resolved) for a path arriving from direction wo.
    void InitVertex(PathVertex& v, const vec3& wo) const {
        const ShadingPoint& p = v.p;
        // Face-forward both normals to the side the path arrives from.
        vec3 ng = glm::dot(p.hit.geomNormal, wo) < 0.0f ? -p.hit.geomNormal : p.hit.geomNormal;
        vec3 ns = glm::dot(p.hit.shadingNormal, ng) < 0.0f ? -p.hit.shadingNormal : p.hit.shadingNormal;
        float cosO = glm::dot(ns, wo);
        if (cosO < 0.01f) ns = glm::normalize(ns + (0.01f - cosO) * wo);  // keep wo above
        Frame frame(ns);
        v.ng = ng;
        v.frame = frame;
        v.wo = PrepareBsdfWo(p.bsdf, frame.ToLocal(wo));
        v.origin = OffsetRayOrigin(p.hit.position, ng);
    }

    // One path sample in flight: the vertex it is at and its next bounce ray.
    struct PathState {
        // User-provided, so that building one in place does not zero the ~300 bytes first.
        PathState() {}
        const PathVertex* v = nullptr;
        RawSlot<PathVertex> storage;
        vec3 throughput = vec3(1.0f);
        int depth = 1;
        BsdfSample bs;  // written by Advance before Land reads it
        vec3 wi;        // likewise
        vec3 direct = vec3(0.0f), indirect = vec3(0.0f);
    };

    // NEE at the path's current vertex and its BSDF continuation. Returns true when a bounce
    // ray st.v->origin + t st.wi is to be traced (then Land), false when the path has ended.
    bool Advance(PathState& st, const PathSampler& sampler, const DeterministicLights& primaryLights,
                 RayCounts& counts) const {
        const PathVertex* v = st.v;
        int vertex = st.depth - 1;
        vec3& target = st.depth == 1 ? st.direct : st.indirect;
        bool last = st.depth >= settings_.maxDepth;
        vec2 sel = Selectors(*v, sampler, vertex, last);
        target += st.throughput * lights_.Sample(rays_, state_.lights, *v, sampler, vertex, sel, !last, counts,
                                               st.depth == 1 ? &primaryLights : nullptr);
        if (last) return false;

        if (!SampleBsdf(v->p.bsdf, v->wo, sampler.BsdfDirection(vertex), sel.y, st.bs)) return false;
        st.wi = v->frame.ToWorld(st.bs.wi);
        if (glm::dot(st.wi, v->ng) <= 0.0f) return false;  // below the geometric surface
        ++counts.bounce;
        return true;
    }

    // The bounce ray's result (next.instance == kNoObject: a miss). Returns true when the path
    // goes on from the new vertex.
    bool Land(PathState& st, const SurfaceSample& next, float t) const {
        vec3& target = st.depth == 1 ? st.direct : st.indirect;
        const vec3& wi = st.wi;
        const BsdfSample& bs = st.bs;
        if (next.instance == kNoObject) {
            target += st.throughput * bs.weight * scene_.background;
            return false;
        }
        st.throughput *= bs.weight;
        PathVertex& landed = st.storage.Emplace();  // st.v's vertex is not read again
        const ShadingPoint& p = landed.p;
        Resolve(next, landed.p);
        if (vec3 le = EmissionToward(p, -wi); le != vec3(0.0f)) {
            float pdfLight = lights_.Pdf(le, p.hit.geomNormal, p.emissionTwoSided, t, wi);
            float weight = PowerHeuristic(bs.pdf, pdfLight);
            target += st.throughput * le * weight;
        }
        InitVertex(landed, -wi);
        st.v = &landed;
        ++st.depth;
        return true;
    }

    // Continues a path one bounce ray at a time until it ends. Always inlined (into ShadePixel),
    // as GCC did before the tracer was split into files; as a call, +0.8 % instructions on the
    // 1-spp Cornell box (callgrind).
    [[gnu::always_inline]] void Finish(PathState& st, const PathSampler& sampler, const DeterministicLights& primaryLights,
                RayCounts& counts) const {
        while (Advance(st, sampler, primaryLights, counts)) {
            SurfaceSample next;
            float t = kInf;
            if (!rays_.Intersect(st.v->origin, st.wi, kInf, next, t)) next = SurfaceSample{};
            if (!Land(st, next, t)) return;
        }
    }

    // Dimension pairs worth hashing once per pixel (PixelSampler's mask): those that n samples
    // read more than once. One sample reads each pair at most once (hashing on use costs no
    // more). Light points are read only with emissive triangles, selectors as ReadsSelectors()
    // says (a later vertex's surface is not known here: taken as specular), BSDF directions by
    // every vertex but the last. (Same numbers either way.)
    uint32_t CachedSamplerPairs(int n, const PathVertex& primary) const {
        if (n <= 1) return 0;
        const bool emitters = lights_.HasEmitters();
        uint32_t mask = 0;
        for (int vertex = 0; vertex < settings_.maxDepth; ++vertex) {
            const uint32_t first = uint32_t(vertex) * PathSampler::kPairsPerVertex;
            if (first + PathSampler::kPairsPerVertex > PixelSampler::kCachedPairs) break;
            const bool last = vertex + 1 >= settings_.maxDepth;
            const float pSpec = vertex == 0 ? primary.wo.pSpec : 1.0f;
            if (emitters) mask |= 1u << first;                                // light point
            if (ReadsSelectors(last, pSpec)) mask |= 1u << (first + 1);      // selectors
            if (!last) mask |= 1u << (first + 2);                            // BSDF direction
        }
        return mask;
    }

    // n samples at one primary surface sample seen from eyePos.
    PixelShade ShadePixel(const vec3& eyePos, const SurfaceSample& s, uint32_t seed, int n,
                          RayCounts& counts, SurfaceHit* hitOut = nullptr) const {
        PathVertex primary;
        ShadingPoint& p = primary.p;
        Resolve(s, p);
        if (hitOut) *hitOut = p.hit;
        const vec3 wo = glm::normalize(eyePos - p.hit.position);
        p.emission = EmissionToward(p, wo);  // what the eye sees of it; read below as out.emission
        InitVertex(primary, wo);
        vec3 direct(0.0f), indirect(0.0f);
        PixelSampler pixelSampler(seed, CachedSamplerPairs(n, primary));
        DeterministicLights primaryLights;
        if (n > 0) primaryLights = lights_.SampleDeterministic(rays_, state_.lights, primary);
        // Samples in groups of 8: the first bounce rays all leave the primary vertex's origin,
        // so they are traced as one 8-wide packet; the rest of each path goes one ray at a time.
        constexpr int kGroup = 8;
        auto accumulate = [&](const vec3& sampleDirect, const vec3& sampleIndirect) {
            ++counts.samples;
            if (!IsFinite(sampleDirect) || !IsFinite(sampleIndirect)) {
                ++counts.dropped;
                return;
            }
            direct += sampleDirect;
            indirect += sampleIndirect;
        };
        for (int base = 0; base < n; base += kGroup) {
            int m = std::min(kGroup, n - base);
            if (m == 1) {  // one sample (1 spp): one ray at a time, no packet bookkeeping
                RawSlot<PathState> one;
                PathState& st = one.Emplace();
                st.v = &primary;
                Finish(st, PathSampler(pixelSampler, uint32_t(base)), primaryLights, counts);
                accumulate(st.direct, st.indirect);
                continue;
            }
            // Only the m lanes in use are constructed: a PathState is ~300 bytes, and building all
            // eight for every group of 2-4 samples cost 2.4 % of the 4-spp tracer's instructions.
            RawSlot<PathState> lanes[kGroup];
            vec3 dirs[kGroup];
            bool active[kGroup];
            SurfaceSample hits[kGroup];
            float ts[kGroup];
            int activeCount = 0;
            for (int j = 0; j < kGroup; ++j) {
                active[j] = false;
                if (j < m) {
                    PathState& st = lanes[j].Emplace();
                    st.v = &primary;
                    active[j] = Advance(st, PathSampler(pixelSampler, uint32_t(base + j)), primaryLights, counts);
                }
                dirs[j] = active[j] ? lanes[j].value.wi : vec3(0.0f, 0.0f, 1.0f);
                activeCount += active[j] ? 1 : 0;
            }
            if (activeCount >= 2) {
                rays_.Intersect8(primary.origin, dirs, active, hits, ts, false);
            } else {
                // A packet of one ray is slower than a single ray (1 spp); same hits either way.
                for (int j = 0; j < m; ++j) {
                    if (!active[j]) continue;
                    ts[j] = kInf;
                    if (!rays_.Intersect(primary.origin, dirs[j], kInf, hits[j], ts[j])) hits[j] = SurfaceSample{};
                }
            }
            for (int j = 0; j < m; ++j) {
                PathState& st = lanes[j].value;
                PathSampler sampler(pixelSampler, uint32_t(base + j));
                if (active[j] && Land(st, hits[j], ts[j])) Finish(st, sampler, primaryLights, counts);
                accumulate(st.direct, st.indirect);
            }
        }
        // Traced once above; every sample counted the tests as reused, so one set is not.
        if (n > 0) counts.shadowReused -= primaryLights.shadowTests;
        PixelShade out;
        float inv = n > 0 ? 1.0f / float(n) : 0.0f;
        direct *= inv;
        indirect *= inv;
        out.albedo = p.albedo;
        const bool brdf = settings_.demodulation == Demodulation::Brdf;
        if (brdf || settings_.fbetaPlane)
            out.fbeta = glm::max(PreintegratedReflectance(*fbetaTable_, p.bsdf, primary.wo.wo.z), vec3(kMinAlbedo));
        out.modulation = brdf ? out.fbeta : out.albedo;
        out.emission = p.emission;
        out.radiance = p.emission + direct + indirect;
        out.direct = direct / out.modulation;  // both factors >= kMinAlbedo
        out.indirect = indirect / out.modulation;
        out.roughness = std::sqrt(p.bsdf.alpha);
        return out;
    }

private:
    static constexpr float kInf = std::numeric_limits<float>::infinity();

    // BSDF parameters of an untextured material, made once instead of at every hit.
    struct ResolvedMaterial {
        bool textured = false;
        BsdfParams bsdf;
        vec3 albedo;
    };

    // The scene as the tracer keeps it (a default material when it has none), after the checks
    // that would otherwise fail mid-frame.
    static Scene Checked(const Scene& scene, const RenderSettings& settings) {
        if (settings.maxDepth < 1) Fail("render: maxDepth must be >= 1 (got {})", settings.maxDepth);
        Scene checked = scene;
        if (checked.materials.empty()) checked.materials.push_back(Material{});
        for (const Mesh& mesh : checked.meshes)
            for (uint32_t m : mesh.materials)
                if (m >= checked.materials.size())
                    Fail("scene {}: mesh '{}' uses material {} but there are {}", checked.name, mesh.name, m,
                         checked.materials.size());
        const int textures = int(checked.textures.size());
        for (const Material& m : checked.materials) {
            if (m.baseColorTexture >= textures || m.metallicRoughnessTexture >= textures ||
                m.roughnessTexture >= textures || m.metallicTexture >= textures)
                Fail("scene {}: material '{}' names a texture that does not exist", checked.name, m.name);
        }
        return checked;
    }

    // Fills p (in place: it is usually a PathVertex's) with the surface and material at s.
    void Resolve(const SurfaceSample& s, ShadingPoint& p) const {
        embree_->SurfaceInto(s, p.hit);
        const Material& m = scene_.materials[p.hit.material];
        const ResolvedMaterial& r = materials_[p.hit.material];
        p.emission = m.emission * embree_->xforms()[s.instance].emissionScale;
        p.emissionTwoSided = m.emissionTwoSided;
        if (!r.textured) {
            p.bsdf = r.bsdf;
            p.albedo = r.albedo;
            return;
        }
        vec3 base = m.baseColor;
        float roughness = m.roughness, metallic = m.metallic;
        if (m.baseColorTexture >= 0) base *= vec3(scene_.textures[m.baseColorTexture].Sample(p.hit.uv));
        if (m.metallicRoughnessTexture >= 0) {
            vec4 mr = scene_.textures[m.metallicRoughnessTexture].Sample(p.hit.uv);
            roughness *= mr.g;
            metallic *= mr.b;
        }
        // Scene-file maps (scene/scene.h): their R channel scales the factor, like glTF's.
        if (m.roughnessTexture >= 0) roughness *= scene_.textures[m.roughnessTexture].Sample(p.hit.uv).r;
        if (m.metallicTexture >= 0) metallic *= scene_.textures[m.metallicTexture].Sample(p.hit.uv).r;
        p.bsdf = MakeBsdfParams(base, roughness, metallic, m.specular);
        p.albedo = glm::clamp(p.bsdf.diffuse + p.bsdf.f0, vec3(kMinAlbedo), vec3(1.0f));
    }


    Scene scene_;
    RenderSettings settings_;
    const BrdfTable* fbetaTable_ = nullptr;  // the process's F_β table, once F_β is needed (SetFbetaPlane)
    std::unique_ptr<EmbreeScene> embree_;
    Rays rays_;  // every ray traced goes through it
    LightSampler lights_;
    std::vector<ResolvedMaterial> materials_;
    SceneState state_;
};

}  // namespace fovrt
