// The stereo Embree path tracer: Advance / Land (one path vertex) -> ShadePixel (n from the spp
// map) -> ShadeEntry -> RenderEye. Per eye: visibility buffer (TraceTile, into the eye's
// VisibilityBuffer, which the tracer keeps; FrameInputs gets only what denoisers read), with
// A-SVGF gradient samples the forward-projected previous surface samples merged into it
// (MergeGradientSamples), then every entry shaded once (ShadeEntry, from TraceTile when nothing
// is merged, else from ShadeTile).
//
// Integrator conventions:
// - Primary visibility is noise-free: one ray through the pixel centre (a merged gradient sample
//   excepted); the n samples all start at that primary surface sample (so Shade() can reproduce
//   them from a visibility-buffer entry).
// - maxDepth = path vertices after the camera. Vertex k < maxDepth: next-event estimation (MIS,
//   power heuristic, against BSDF sampling) + a BSDF-sampled continuation whose emitter hits are
//   MIS-weighted. The last vertex only does NEE, with full weight (no continuation ray). So a
//   white furnace with emission Le and albedo a gives Le * sum_{k=0..maxDepth} a^k: k = 0 is the
//   emission seen at the primary hit, k = j the light arriving after j reflections.
// - Area lights are one-sided, as in pbrt and Mitsuba: an emissive triangle emits only to the side
//   of its geometric normal (SurfaceHit::geomNormal: the winding's, or the authored normals' where
//   a mesh has them), both sides when its material is Material::emissionTwoSided. Seen from behind
//   it is black for every estimator alike: camera rays, BSDF-sampled hits and NEE (pdf 0).
// - Emissive triangles are sampled in proportion to their power (world area * luminance of the
//   emitted radiance * sides, times the instance's emission scale), then uniformly in area: a
//   two-sided triangle emits twice the flux of a one-sided one (pbrt's DiffuseAreaLight::Phi), and
//   scenes with one-sided lights only are sampled exactly as when every light was two-sided.
//   Point/spot/directional lights are all sampled at every vertex (one shadow ray each).
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
// - spp-map entries of 0 are taken as 1 (sampleCount records what was traced).
// - Gradient samples replace the pixel's own sample, as in the paper (§3): the merged pixel holds
//   the previous frame's surface sample (not at its centre), seed and sample count n_prev, and is
//   shaded once like every other pixel. Its colour is this frame's sample of the pixel and
//   f_i(G→, ξ_{i−1}); no extra shading, but the frame traces Σ (n_prev − n_cur) samples more or
//   fewer than the spp map says (sampleCount records what was traced).
// - Static instances (at most one transform key) are flattened into the top-level BVH.
// - Throughput (same results as tracing every ray one at a time, bit for bit): the point/spot/
//   directional-light shadow rays of the primary vertex are traced once per pixel and reused by
//   its n samples (RenderStats::shadowRaysReused), and the first bounce rays of up to 8 samples
//   (all leaving the primary vertex) are traced as one rtcIntersect8 packet when n >= 2.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <memory>
#include <new>
#include <type_traits>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "core/check.h"
#include "core/error.h"
#include "core/rng.h"
#include "render/brdf_table.h"
#include "render/bsdf.h"
#include "render/embree_scene.h"
#include "render/probes.h"
#include "render/recording_scene.h"
#include "render/renderer.h"
#include "render/sampler.h"

namespace fovrt {
namespace {

constexpr int kTileSize = 16;               // pixels; fixed so work splits identically for any thread count
constexpr float kMinAlbedo = 1e-3f;         // demodulation guard (Falcor's max(albedo, 1e-3))
constexpr float kGradientDepthTolerance = 0.01f;  // relative depth match for forward projection
constexpr uint32_t kReferenceStream = 0x52454631u;  // decorrelates reference seeds from noisy ones
constexpr uint32_t kGradientStream = 0x47524144u;   // random pixel per stratum

struct RayCounts {
    uint64_t primary = 0, shadow = 0, shadowReused = 0, bounce = 0, samples = 0, dropped = 0;
};

// The point/spot/directional-light part of NEE at the primary vertex: it does not depend on the
// sample (same origin, same light direction), so it is computed and traced once per pixel and
// reused by all n samples (bit-identical: the same sum in the same order).
struct DeterministicLights {
    vec3 sum = vec3(0.0f);
    uint64_t shadowTests = 0;
};

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
// must be trivially destructible). Not std::optional: GCC zero-fills an optional's whole storage
// when it is constructed (192 bytes per path vertex, 2.3 KB for a group of eight path lanes).
template <typename T>
union RawSlot {
    static_assert(std::is_trivially_destructible_v<T>);
    RawSlot() {}
    T& Emplace() { return *new (&value) T(); }
    T value;
};

// core's Remodulate, as FrameInputs::NoisyColor uses: re-shaded and stored luminances match bit for bit.
vec3 Remodulate(const PixelShade& s) { return fovrt::Remodulate(s.modulation, s.direct, s.indirect, s.emission); }

// What A-SVGF's forward projection reads of one eye's previous frame besides its visibility buffer.
struct EyeHistory {
    bool valid = false;
    uint32_t frame = 0;
    Plane<uint32_t> instance;
    Plane<uint16_t> sampleCount;
    Plane<float> luminance;  // of the noisy remodulated colour
};

// One eye's visibility buffers: the latest frame's and, with gradient samples, the one before
// (the history's); they trade places each frame instead of being copied.
struct EyeVisibility {
    VisibilityBuffer buffers[2];
    int latest = 0;
    VisibilityBuffer& Latest() { return buffers[latest]; }
    const VisibilityBuffer& Latest() const { return buffers[latest]; }
    const VisibilityBuffer& Previous() const { return buffers[1 - latest]; }
};

// The path tracer, over `Rays`: the EmbreeScene itself (CreateRenderer) or a RecordingScene over it
// (CreateProbeRenderer), whichever the ray calls go through; `Interface`: Renderer or ProbeRenderer.
template <typename Rays, typename Interface>
class PathTracer : public Interface {
public:
    PathTracer(const Scene& scene, const RenderSettings& settings)
        : scene_(Checked(scene, settings)), settings_(settings),
          arena_(settings.threads > 0 ? settings.threads : tbb::task_arena::automatic),
          embree_(std::make_unique<EmbreeScene>(scene_)), rays_(*embree_) {
        for (const Material& m : scene_.materials) {
            ResolvedMaterial r;
            r.textured = m.baseColorTexture >= 0 || m.metallicRoughnessTexture >= 0 || m.roughnessTexture >= 0 ||
                         m.metallicTexture >= 0;
            r.bsdf = MakeBsdfParams(m.baseColor, m.roughness, m.metallic, m.specular);
            r.albedo = glm::clamp(r.bsdf.diffuse + r.bsdf.f0, vec3(kMinAlbedo), vec3(1.0f));
            materials_.push_back(r);
        }
        for (uint32_t i = 0; i < scene_.instances.size(); ++i) {
            const Mesh& mesh = scene_.meshes[scene_.instances[i].mesh];
            for (uint32_t t = 0; t < mesh.triangles.size(); ++t) {
                uint32_t mat = mesh.materials.empty() ? 0u : mesh.materials[t];
                if (Luminance(scene_.materials[mat].emission) > 0.0f) emissive_.push_back({i, t});
            }
        }
        SetFbetaPlane(settings_.fbetaPlane);
        SetFrame(0);
        prevState_ = state_;
        prevXforms_ = embree_->xforms();
    }

    using Interface::SetFrame;
    void SetFrame(uint32_t frame, float timeSeconds) override {
        if (hasFrame_ && frame == frame_) return;
        if (hasFrame_) {
            prevState_ = state_;
            prevXforms_ = embree_->xforms();
        }
        frame_ = frame;
        state_ = scene_.StateAt(timeSeconds);
        embree_->Update(state_);
        if (!hasFrame_) {
            prevState_ = state_;
            prevXforms_ = embree_->xforms();
        }
        hasFrame_ = true;
        BuildLightDistribution();
    }

    const SceneState& State() const override { return state_; }
    void SetGradientSamples(bool on) override { settings_.gradientSamples = on; }
    void SetFbetaPlane(bool on) override {
        settings_.fbetaPlane = on;
        // The table (seconds to build) only once some frame needs F_β.
        if (!fbetaTable_ && (on || settings_.demodulation == Demodulation::Brdf)) fbetaTable_ = &SharedBrdfTable();
    }
    const Scene& GetScene() const override { return scene_; }

    void RenderEye(int eye, const EyeCamera& camera, const EyeCamera& prevCamera,
                   const Plane<uint16_t>& spp, FrameInputs& out) override {
        FOVRT_CHECK(eye == 0 || eye == 1);
        int w = camera.width(), h = camera.height();
        FOVRT_CHECK_OP(spp.width(), ==, w);
        FOVRT_CHECK_OP(spp.height(), ==, h);
        bool cut = out.cameraCut;
        out.AllocateForOverwrite(w, h);  // TraceTile sets every pixel of every plane
        out.eye = eye;
        out.frameIndex = frame_;
        out.timeSeconds = state_.time;
        out.camera = camera;
        out.prevCamera = prevCamera;
        out.demodulation = settings_.demodulation;
        // The noisy luminance only feeds A-SVGF's gradient samples (this frame's and the history's).
        Plane<float> luminance;
        if (settings_.gradientSamples) luminance.Resize(w, h, 0.0f);

        EyeHistory& history = history_[eye];
        EyeVisibility& visibility = visibility_[eye];
        if (settings_.gradientSamples) visibility.latest = 1 - visibility.latest;  // last frame's is now Previous()
        VisibilityBuffer& vis = visibility.Latest();
        vis.AllocateForOverwrite(w, h);
        bool merge = settings_.gradientSamples && history.valid && !cut && history.frame + 1 == frame_ &&
                     history.instance.width() == w && history.instance.height() == h;
        const EyeView view(camera, prevCamera);
        // Nothing to merge: visibility and shading in one sweep.
        ForEachTile(w, h, [&](int x0, int y0, int x1, int y1, RayCounts& counts) {
            TraceTile(eye, view, spp, x0, y0, x1, y1, !merge, out, vis, luminance, counts);
        });
        if (merge) {
            // A-SVGF (paper §3): the forward-projected previous surface samples and seeds merged
            // into the new visibility buffer, then every entry shaded once.
            Plane<uint8_t> merged(w, h, uint8_t(0));
            MergeGradientSamples(eye, camera, history, visibility.Previous(), out, vis, merged);
            ForEachTile(w, h, [&](int x0, int y0, int x1, int y1, RayCounts& counts) {
                ShadeTile(view, merged, x0, y0, x1, y1, out, vis, luminance, counts);
            });
            // f_i(G→, ξ_{i−1}) is the merged pixel's own shading.
            for (GradientSample& g : out.gradientSamples) g.newLuminance = luminance(g.pixel.x, g.pixel.y);
        }

        if (!settings_.gradientSamples) return;  // the history only feeds gradient samples
        history.valid = true;
        history.frame = frame_;
        history.instance = out.objectId;
        history.sampleCount = out.sampleCount;
        history.luminance = std::move(luminance);
    }

    void RenderReference(int eye, const EyeCamera& camera, int spp, uint32_t seed, Plane<vec3>& out) override {
        FOVRT_CHECK_OP(spp, >=, 1);
        int w = camera.width(), h = camera.height();
        out.Resize(w, h, vec3(0.0f));
        const uint32_t referenceSeed = HashCombine(seed, kReferenceStream);
        ForEachTile(w, h, [&](int x0, int y0, int x1, int y1, RayCounts& counts) {
            for (int y = y0; y < y1; ++y)
                for (int x = x0; x < x1; ++x) {
                    vec3 dir = camera.WorldDirection(vec2(x + 0.5f, y + 0.5f));
                    SurfaceSample s;
                    float t;
                    ++counts.primary;
                    if (!rays_.Intersect(camera.Position(), dir, kInf, s, t, true)) {
                        out(x, y) = scene_.background;
                        continue;
                    }
                    const uint32_t pixelSeed = PixelSeed(referenceSeed, uint32_t(eye), uint32_t(x), uint32_t(y), 0u);
                    out(x, y) = ShadePixel(camera.Position(), s, pixelSeed, spp, counts).radiance;
                }
        });
    }

    const VisibilityBuffer& Visibility(int eye) const override {
        FOVRT_CHECK(eye == 0 || eye == 1);
        return visibility_[eye].Latest();
    }

    RenderStats Stats() const override {
        RenderStats s;
        s.primaryRays = primaryRays_.load();
        s.shadowRays = shadowRays_.load();
        s.shadowRaysReused = shadowRaysReused_.load();
        s.bounceRays = bounceRays_.load();
        s.samples = samples_.load();
        s.droppedSamples = dropped_.load();
        return s;
    }
    void ResetStats() override {
        primaryRays_ = 0;
        shadowRays_ = 0;
        shadowRaysReused_ = 0;
        bounceRays_ = 0;
        samples_ = 0;
        dropped_ = 0;
    }

protected:
    static constexpr float kInf = std::numeric_limits<float>::infinity();

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

    // World position of a surface sample in the current frame.
    vec3 PositionOf(const SurfaceSample& sample) const { return embree_->Surface(sample).position; }

    struct EmissiveTriangle {
        uint32_t instance, primitive;
    };

    // An emissive triangle as NEE samples it in the current frame: world corner p0 and edges
    // (p1 - p0, p2 - p0), unit geometric normal (SurfaceHit's at the centroid: the front side)
    // and emitted radiance with the instance's emission scale. Built per frame, so a light
    // sample costs no surface reconstruction.
    struct Emitter {
        vec3 p0, e1, e2, normal, emission;
        bool twoSided;
    };

    // BSDF parameters of an untextured material, made once instead of at every hit.
    struct ResolvedMaterial {
        bool textured = false;
        BsdfParams bsdf;
        vec3 albedo;
    };

    // Runs fn over fixed 16×16 tiles in parallel; each tile's counters are summed afterwards.
    template <typename Fn>
    void ForEachTile(int w, int h, Fn&& fn) const {
        int tilesX = (w + kTileSize - 1) / kTileSize, tilesY = (h + kTileSize - 1) / kTileSize;
        arena_.execute([&] {
            tbb::parallel_for(0, tilesX * tilesY, [&](int tile) {
                int x0 = (tile % tilesX) * kTileSize, y0 = (tile / tilesX) * kTileSize;
                RayCounts counts;
                fn(x0, y0, std::min(x0 + kTileSize, w), std::min(y0 + kTileSize, h), counts);
                AddStats(counts);
            });
        });
    }

    void AddStats(const RayCounts& c) const {
        primaryRays_ += c.primary;
        shadowRays_ += c.shadow;
        shadowRaysReused_ += c.shadowReused;
        bounceRays_ += c.bounce;
        samples_ += c.samples;
        dropped_ += c.dropped;
    }

    // The luminance by which lights are picked (per unit area): a two-sided emitter sends twice the
    // flux of a one-sided one (pbrt's DiffuseAreaLight). BuildLightDistribution and LightPdf must
    // agree on it, so both call this.
    static float SelectionLuminance(const vec3& emission, bool twoSided) {
        return Luminance(emission) * (twoSided ? 2.0f : 1.0f);
    }

    void BuildLightDistribution() {
        lightCdf_.resize(emissive_.size());
        emitters_.resize(emissive_.size());
        double total = 0.0;
        for (size_t i = 0; i < emissive_.size(); ++i) {
            SurfaceSample s{emissive_[i].instance, emissive_[i].primitive, vec2(1.0f / 3.0f)};
            SurfaceHit hit = embree_->Surface(s);
            const bool twoSided = scene_.materials[hit.material].emissionTwoSided;
            float power = hit.area * SelectionLuminance(EmissionOf(hit, s.instance), twoSided);
            total += double(std::max(power, 0.0f));
            lightCdf_[i] = float(total);
            // What NEE reads of the triangle, with SurfaceAt's arithmetic (bit-identical points).
            auto p = embree_->WorldTriangle(s.instance, s.primitive, embree_->xforms());
            Emitter& e = emitters_[i];
            e.p0 = p[0];
            e.e1 = p[1] - p[0];
            e.e2 = p[2] - p[0];
            e.normal = hit.geomNormal;
            e.emission = EmissionOf(hit, s.instance);
            e.twoSided = twoSided;
        }
        lightPower_ = float(total);
    }

    vec3 EmissionOf(const SurfaceHit& hit, uint32_t instance) const {
        return scene_.materials[hit.material].emission * embree_->xforms()[instance].emissionScale;
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

    // The radiance p emits towards w (any length): none from the back of a one-sided emitter.
    static vec3 EmissionToward(const ShadingPoint& p, const vec3& w) {
        return p.emissionTwoSided || glm::dot(p.hit.geomNormal, w) > 0.0f ? p.emission : vec3(0.0f);
    }

    // Solid-angle pdf with which NEE picks a point on an emitter seen at distance t along wi
    // (from the receiver): 0 when the receiver is behind a one-sided emitter, which NEE then
    // skips and a BSDF-sampled hit sees black, so MIS weights stay consistent.
    float LightPdf(const vec3& emission, const vec3& geomNormal, bool twoSided, float t, const vec3& wi) const {
        float lum = SelectionLuminance(emission, twoSided);
        float cosL = -glm::dot(geomNormal, wi);
        if (twoSided) cosL = std::abs(cosL);
        if (lightPower_ <= 0.0f || lum <= 0.0f || cosL <= 0.0f) return 0.0f;
        return lum / lightPower_ * t * t / cosL;
    }

    // Point/spot/directional lights at one vertex (one shadow ray each): the sample-independent
    // first part of SampleLights.
    DeterministicLights SampleDeterministicLights(const PathVertex& v) const {
        const ShadingPoint& p = v.p;
        const vec3& ng = v.ng;
        const vec3& origin = v.origin;
        DeterministicLights out;
        vec3& result = out.sum;
        for (const LightState& light : state_.lights) {
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
            if (rays_.Occluded(origin, wi, tFar)) continue;
            result += e.fCos * li;
        }
        return out;
    }

    // Next-event estimation at one vertex. `mis`: weight emitter samples against BSDF sampling.
    // `cached`: the vertex's SampleDeterministicLights() computed earlier (its shadow tests are
    // counted again here, as reused).
    vec3 SampleLights(const PathVertex& v, const PathSampler& sampler, int vertex, const vec2& sel,
                      bool mis, RayCounts& counts, const DeterministicLights* cached = nullptr) const {
        const ShadingPoint& p = v.p;
        const vec3& ng = v.ng;
        const vec3& origin = v.origin;
        vec3 result(0.0f);
        if (cached) {
            result = cached->sum;
            counts.shadow += cached->shadowTests;
            counts.shadowReused += cached->shadowTests;
        } else {
            DeterministicLights fresh = SampleDeterministicLights(v);
            result = fresh.sum;
            counts.shadow += fresh.shadowTests;
        }
        if (lightPower_ > 0.0f) {
            size_t index = size_t(std::upper_bound(lightCdf_.begin(), lightCdf_.end(), sel.x * lightPower_) -
                                  lightCdf_.begin());
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
                float pdf = LightPdf(emission, light.normal, light.twoSided, dist, wi);
                if (pdf > 0.0f && glm::dot(wi, ng) > 0.0f) {
                    BsdfEval e = EvalBsdf(p.bsdf, v.wo, v.frame.ToLocal(wi));
                    if (e.fCos != vec3(0.0f)) {
                        ++counts.shadow;
                        // The ray leaves the offset origin, so it meets the light's plane short
                        // of dist by offset / cos: near a light at grazing angles that exceeds the
                        // 1e-3 margin and the light shadowed itself (a ceiling 2 cm above one).
                        float tPlane = glm::dot(light.normal, lightPosition - origin) / glm::dot(light.normal, wi);
                        if (!rays_.Occluded(origin, wi, std::min(dist, tPlane) * (1.0f - 1e-3f))) {
                            float weight = mis ? pdf * pdf / (pdf * pdf + e.pdf * e.pdf) : 1.0f;
                            result += e.fCos * emission * (weight / pdf);
                        }
                    }
                }
            }
        }
        return result;
    }

    // Whether a vertex reads its selectors: x picks the emitter (only with emissive triangles), y
    // the BSDF lobe (only where a bounce follows and the surface has a specular lobe: with
    // pSpec = 0 every y in [0, 1) picks the diffuse lobe, as 0 does).
    bool ReadsSelectors(bool last, float pSpec) const { return lightPower_ > 0.0f || (!last && pSpec > 0.0f); }

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
        target += st.throughput * SampleLights(*v, sampler, vertex, sel, !last, counts,
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
            float pdfLight = LightPdf(le, p.hit.geomNormal, p.emissionTwoSided, t, wi);
            float weight = bs.pdf * bs.pdf / (bs.pdf * bs.pdf + pdfLight * pdfLight);
            target += st.throughput * le * weight;
        }
        InitVertex(landed, -wi);
        st.v = &landed;
        ++st.depth;
        return true;
    }

    // Continues a path one bounce ray at a time until it ends.
    void Finish(PathState& st, const PathSampler& sampler, const DeterministicLights& primaryLights,
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
        const bool emitters = lightPower_ > 0.0f;
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
        if (n > 0) primaryLights = SampleDeterministicLights(primary);
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

    // Per-eye constants of the pinhole model: eye-space ray through pixel centre (x, y) is
    // (tanLeft + (x + 0.5) sx, tanUp + (y + 0.5) sy, -1).
    struct EyeRays {
        mat3 worldFromEye;
        mat3 eyeFromWorld;
        float tanLeft, tanUp, sx, sy;
        explicit EyeRays(const EyeCamera& camera) {
            worldFromEye = glm::mat3_cast(camera.pose().orientation);
            eyeFromWorld = glm::transpose(worldFromEye);
            const Fov& f = camera.fov();
            tanLeft = std::tan(f.angleLeft);
            tanUp = std::tan(f.angleUp);
            sx = (std::tan(f.angleRight) - tanLeft) / float(camera.width());
            sy = (std::tan(f.angleDown) - tanUp) / float(camera.height());
        }
        vec3 Eye(int x, int y) const { return vec3(tanLeft + (x + 0.5f) * sx, tanUp + (y + 0.5f) * sy, -1.0f); }
        // World-space unit primary ray direction through pixel centre (x, y).
        vec3 Direction(int x, int y) const { return glm::normalize(worldFromEye * Eye(x, y)); }
    };

    // Change of linear depth per pixel along x and y on the primary hit's tangent plane: with the
    // eye-space ray e(x, y) (z = -1), depth = c / (n.e), so d depth / dx = -depth n_x sx / (n.e).
    static vec2 DepthGradient(const EyeRays& rays, const vec3& eyeDir, const vec3& ngWorld, float depth) {
        vec3 n = rays.eyeFromWorld * ngWorld;
        float denom = glm::dot(n, eyeDir);
        // Grazing planes: a gradient as large as the depth itself (lenient depth weights).
        if (!(std::abs(denom) > 1e-6f)) return vec2(depth);
        vec2 g(-depth * n.x * rays.sx / denom, -depth * n.y * rays.sy / denom);
        return glm::clamp(g, vec2(-depth), vec2(depth));
    }

    // Per-tile constants of one eye's shading.
    struct EyeView {
        const EyeCamera& camera;
        const EyeCamera& prevCamera;
        vec3 eyePos;
        mat3 prevView;
        EyeRays rays;
        EyeView(const EyeCamera& c, const EyeCamera& prev)
            : camera(c), prevCamera(prev), eyePos(c.Position()), prevView(mat3(prev.View())), rays(c) {}
    };

    // Visibility buffer of one tile: primary rays through the pixel centres (8-wide packets along
    // the row), the fresh per-pixel seeds and the spp map's sample counts. `shade`: nothing will
    // be merged, so each pixel is shaded right after its packet (one sweep, the rays at hand).
    void TraceTile(int eye, const EyeView& view, const Plane<uint16_t>& spp, int x0, int y0, int x1, int y1,
                   bool shade, FrameInputs& out, VisibilityBuffer& vis, Plane<float>& luminance,
                   RayCounts& counts) const {
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
                rays_.Intersect8(view.eyePos, dirs, valid, hits, ts, true);
                for (int i = 0; i < 8 && xs + i < x1; ++i) {
                    int x = xs + i;
                    uint32_t seed = PixelSeed(settings_.seed, uint32_t(eye), uint32_t(x), uint32_t(y), frame_);
                    int n = std::max<int>(1, spp(x, y));
                    vis.seed(x, y) = seed;
                    out.sampleCount(x, y) = uint16_t(n);
                    out.objectId(x, y) = hits[i].instance;
                    vis.primitiveId(x, y) = hits[i].primitive;
                    vis.barycentrics(x, y) = hits[i].barycentrics;
                    if (shade)
                        ShadeEntry(view, x, y, hits[i], seed, n, dirs[i], view.rays.Eye(x, y), out, vis, luminance,
                                   counts);
                }
            }
        }
    }

    // Shades every visibility-buffer entry of one tile once (after the merge). `merged` marks
    // the forward-projected gradient samples: their surface point is not at the pixel centre, so
    // view direction and depth gradient use the ray through the point itself.
    void ShadeTile(const EyeView& view, const Plane<uint8_t>& merged, int x0, int y0, int x1, int y1,
                   FrameInputs& out, VisibilityBuffer& vis, Plane<float>& luminance, RayCounts& counts) const {
        for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x) {
                SurfaceSample s{out.objectId(x, y), vis.primitiveId(x, y), vis.barycentrics(x, y)};
                uint32_t seed = vis.seed(x, y);
                int n = out.sampleCount(x, y);
                if (!merged(x, y)) {
                    ShadeEntry(view, x, y, s, seed, n, view.rays.Direction(x, y), view.rays.Eye(x, y), out,
                               vis, luminance, counts);
                    continue;
                }
                vec3 dir = PositionOf(s) - view.eyePos;
                vec3 eyeRay = view.rays.eyeFromWorld * dir;
                eyeRay /= -eyeRay.z;  // in front of the camera (forward projection checked it)
                ShadeEntry(view, x, y, s, seed, n, dir, eyeRay, out, vis, luminance, counts);
            }
    }

    // Shades visibility-buffer entry (x, y) = s with n samples from `seed` and fills the remaining
    // G-buffer planes. `dir`: world ray towards s (any length; background: the pixel's unit ray);
    // `eyeRay`: the same ray in eye space with z = -1. Always inlined: as a call, the 1-spp
    // bench ran 1.6 % more instructions than the single-sweep tracer before the split (callgrind).
    [[gnu::always_inline]] void ShadeEntry(const EyeView& view, int x, int y, const SurfaceSample& s,
                                           uint32_t seed, int n, const vec3& dir, const vec3& eyeRay,
                                           FrameInputs& out, VisibilityBuffer& vis, Plane<float>& luminance,
                                           RayCounts& counts) const {
        if (s.instance == kNoObject) {
            out.emission(x, y) = scene_.background;
            if (!luminance.empty()) luminance(x, y) = Luminance(scene_.background);
            vec3 e = view.prevView * dir;
            out.prevPixel(x, y) = e.z < 0.0f ? view.prevCamera.PixelOfEyeDirection(e) : vec2(-1.0f);
            return;
        }
        SurfaceHit hit;
        PixelShade shade = ShadePixel(view.eyePos, s, seed, n, counts, &hit);
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
        vec3 prevWorld = vec3(prevXforms_[s.instance].worldFromObject * vec4(embree_->ObjectPosition(s), 1.0f));
        auto prev = view.prevCamera.Project(prevWorld);
        out.prevPixel(x, y) = prev ? prev->pixel : vec2(-1.0f);
        if (!luminance.empty()) luminance(x, y) = Luminance(Remodulate(shade));
    }

    // A-SVGF forward projection and merge (paper §3, "Constructing Gradient Samples"): one random
    // previous-frame pixel per 3×3 stratum, moved to this frame with current transforms, dropped
    // if off-screen or occluded in the new visibility buffer, at most one per current stratum
    // (first wins, raster order of the previous strata). A survivor replaces the visibility-buffer
    // entry of the pixel it lands in, with the previous seed and the previous sample count n_prev
    // (the same random numbers), so its shading is both the pixel's sample of this frame and
    // f_i(G→, ξ_{i−1}): no extra work, but that pixel traces n_prev instead of the spp map's
    // n_cur samples. Appends the gradient samples (newLuminance filled in after shading).
    void MergeGradientSamples(int eye, const EyeCamera& camera, const EyeHistory& history,
                              const VisibilityBuffer& prevVis, FrameInputs& out, VisibilityBuffer& vis,
                              Plane<uint8_t>& merged) const {
        int w = camera.width(), h = camera.height();
        int sw = (w + kGradientStratumSize - 1) / kGradientStratumSize;
        int sh = (h + kGradientStratumSize - 1) / kGradientStratumSize;
        std::vector<uint8_t> taken(size_t(sw) * size_t(sh), 0);
        for (int sy = 0; sy < sh; ++sy) {
            for (int sx = 0; sx < sw; ++sx) {
                Pcg32 rng(PixelSeed(HashCombine(settings_.seed, kGradientStream), uint32_t(eye),
                                    uint32_t(sx), uint32_t(sy), frame_));
                int bx = sx * kGradientStratumSize, by = sy * kGradientStratumSize;
                int px = bx + int(rng.NextBounded(uint32_t(std::min(kGradientStratumSize, w - bx))));
                int py = by + int(rng.NextBounded(uint32_t(std::min(kGradientStratumSize, h - by))));
                if (history.instance(px, py) == kNoObject) continue;
                SurfaceSample s{history.instance(px, py), prevVis.primitiveId(px, py), prevVis.barycentrics(px, py)};
                auto proj = camera.Project(PositionOf(s));
                if (!proj) continue;
                int cx = int(std::floor(proj->pixel.x)), cy = int(std::floor(proj->pixel.y));
                if (!out.objectId.InBounds(cx, cy) || out.objectId(cx, cy) == kNoObject) continue;
                size_t stratum = size_t(cy / kGradientStratumSize) * size_t(sw) + size_t(cx / kGradientStratumSize);
                if (taken[stratum]) continue;  // first wins; so (cx, cy) still holds its own entry
                SurfaceSample here{out.objectId(cx, cy), vis.primitiveId(cx, cy), vis.barycentrics(cx, cy)};
                bool sameSurface = here.instance == s.instance && here.primitive == s.primitive;
                if (!sameSurface) {
                    float depth = camera.LinearDepth(PositionOf(here));
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

    Scene scene_;
    RenderSettings settings_;
    mutable tbb::task_arena arena_;
    const BrdfTable* fbetaTable_ = nullptr;  // the process's F_β table, once F_β is needed (SetFbetaPlane)
    std::unique_ptr<EmbreeScene> embree_;
    Rays rays_;  // every ray traced goes through it
    bool hasFrame_ = false;
    uint32_t frame_ = 0;
    SceneState state_, prevState_;
    std::vector<InstanceXform> prevXforms_;
    std::vector<EmissiveTriangle> emissive_;
    std::vector<Emitter> emitters_;  // per emissive_ entry, current frame
    std::vector<ResolvedMaterial> materials_;
    std::vector<float> lightCdf_;
    float lightPower_ = 0.0f;
    EyeHistory history_[2];
    EyeVisibility visibility_[2];
    mutable std::atomic<uint64_t> primaryRays_{0}, shadowRays_{0}, shadowRaysReused_{0},
        bounceRays_{0}, samples_{0}, dropped_{0};
};

// The probe renderer: the tracer over a RecordingScene, and the probes.
class ProbePathTracer final : public PathTracer<RecordingScene, ProbeRenderer> {
public:
    using PathTracer::PathTracer;

    vec3 Shade(const EyeCamera& camera, const SurfaceSample& sample, uint32_t seed,
               int sampleCount) const override {
        RayCounts counts;
        vec3 color = Remodulate(ShadePixel(camera.Position(), sample, seed, sampleCount, counts));
        AddStats(counts);
        return color;
    }

    vec3 WorldPosition(const SurfaceSample& sample) const override { return PositionOf(sample); }

    void RecordRays(std::vector<TracedRay>* log) override { rays_.SetLog(log); }

    uint64_t TraceBare(const std::vector<TracedRay>& rays) const override {
        std::atomic<uint64_t> hits{0};
        arena_.execute([&] {
            tbb::parallel_for(tbb::blocked_range<size_t>(0, rays.size(), 4096), [&](const tbb::blocked_range<size_t>& r) {
                uint64_t n = 0;
                for (size_t i = r.begin(); i != r.end(); ++i) n += fovrt::TraceBare(*embree_, rays[i]) ? 1 : 0;
                hits += n;
            });
        });
        return hits.load();
    }
};

}  // namespace

std::unique_ptr<Renderer> CreateRenderer(const Scene& scene, const RenderSettings& settings) {
    return std::make_unique<PathTracer<const EmbreeScene&, Renderer>>(scene, settings);
}

std::unique_ptr<ProbeRenderer> CreateProbeRenderer(const Scene& scene, const RenderSettings& settings) {
    return std::make_unique<ProbePathTracer>(scene, settings);
}

}  // namespace fovrt
