// The surface model: Lambert + GGX microfacet (glTF metallic/roughness), evaluated in a local
// shading frame (z = shading normal). Smith height-correlated G2, Schlick Fresnel, visible-normal
// (VNDF, Heitz 2018) sampling for the specular lobe, cosine sampling for the diffuse lobe; the two
// lobes are chosen by their approximate Fresnel-weighted albedo and the pdf is the mixture pdf.
#pragma once

#include <algorithm>
#include <cmath>

#include "core/math.h"

namespace fovrt {

struct Material;

struct BsdfParams {
    vec3 diffuse = vec3(0.0f);  // (1 - metallic) * baseColor
    vec3 f0 = vec3(0.0f);       // specular reflectance at normal incidence
    float alpha = 1.0f;         // GGX alpha = roughness²
};

// Smallest GGX alpha: keeps the lobe a function (no delta mirror). roughness r → alpha =
// max(r², kMinGgxAlpha); the F_β table (render/brdf_table.h) indexes by sqrt(alpha) for that reason.
inline constexpr float kMinGgxAlpha = 1e-3f;
float GgxAlphaFromRoughness(float roughness);

// Schlick's Fresnel weight S = (1 − cosθ)⁵ (cosθ clamped to [0, 1]): F = F0 + (1 − F0) S, linear
// in F0, which is why F_β needs only three pre-integrated channels (SPEC §6).
float SchlickWeight(float cosTheta);

// Parameters of a material at a texture-resolved base colour / roughness / metallic.
BsdfParams MakeBsdfParams(const vec3& baseColor, float roughness, float metallic, float specular);

struct BsdfEval {
    vec3 fCos = vec3(0.0f);  // f(wo, wi) * cos(theta_i)
    float pdf = 0.0f;        // solid-angle pdf of SampleBsdf producing wi
};

struct BsdfSample {
    vec3 wi = vec3(0.0f);      // local frame
    vec3 weight = vec3(0.0f);  // f * cos / pdf
    float pdf = 0.0f;
};

// The terms that depend on wo only, computed once per path vertex.
struct BsdfWo {
    vec3 wo = vec3(0.0f, 0.0f, 1.0f);
    float pSpec = 0.0f;    // probability of sampling the specular lobe
    float lambdaO = 0.0f;  // Smith Lambda(wo)
};
BsdfWo PrepareBsdfWo(const BsdfParams& params, const vec3& wo);

// wo, wi in the local frame (z up), both must have z > 0 for a non-zero value.
inline BsdfEval EvalBsdf(const BsdfParams& params, const BsdfWo& wo, const vec3& wi);  // below
BsdfEval EvalBsdf(const BsdfParams& params, const vec3& wo, const vec3& wi);
// u: direction random numbers, uLobe: lobe selection. Returns false when no direction was made.
inline bool SampleBsdf(const BsdfParams& params, const BsdfWo& wo, const vec2& u, float uLobe,
                       BsdfSample& out);  // below
bool SampleBsdf(const BsdfParams& params, const vec3& wo, const vec2& u, float uLobe, BsdfSample& out);

// GGX pieces (exposed for tests).
float GgxD(float alpha, float cosThetaH);
float GgxLambda(float alpha, float cosTheta);
vec3 SampleGgxVndf(float alpha, const vec3& wo, const vec2& u);
// The same in two steps: u → uniform point on the unit disk (polar map), then the visible normal
// of that disk point (the F_β table maps its point set to the disk once, not per entry).
vec2 VndfDiskPoint(const vec2& u);
vec3 SampleGgxVndfDisk(float alpha, const vec3& wo, const vec2& disk);

// Orthonormal basis around a unit normal (Duff et al. 2017).
struct Frame {
    vec3 t, b, n;
    Frame() = default;  // uninitialised (a PathVertex member, set in place)
    explicit Frame(const vec3& normal);
    vec3 ToLocal(const vec3& v) const { return vec3(glm::dot(v, t), glm::dot(v, b), glm::dot(v, n)); }
    vec3 ToWorld(const vec3& v) const { return v.x * t + v.y * b + v.z * n; }
};

// Defined here, inline: the tracer calls these per ray, and as calls they cost it ~3 % of its
// samples per CPU-second (src/render/PROFILE.md). Schlick's Fresnel with the weight above.

inline vec3 SchlickFresnel(const vec3& f0, float cosTheta) {
    return f0 + (vec3(1.0f) - f0) * SchlickWeight(cosTheta);
}

[[gnu::always_inline]] inline BsdfEval EvalBsdf(const BsdfParams& p, const BsdfWo& w, const vec3& wi) {
    BsdfEval e;
    const vec3& wo = w.wo;
    if (wo.z <= 0.0f || wi.z <= 0.0f) return e;
    if (w.pSpec <= 0.0f) {
        // Pure Lambert (no specular interface): F = 0.
        e.fCos = p.diffuse * (kInvPi * wi.z);
        e.pdf = wi.z * kInvPi;
        return e;
    }
    vec3 h = glm::normalize(wo + wi);
    float woh = std::max(glm::dot(wo, h), 0.0f);
    vec3 fresnel = SchlickFresnel(p.f0, woh);
    // Diffuse: Lambert scaled by the energy the specular interface transmits.
    e.fCos = p.diffuse * (vec3(1.0f) - fresnel) * (kInvPi * wi.z);
    e.pdf = (1.0f - w.pSpec) * wi.z * kInvPi;
    float d = GgxD(p.alpha, h.z);
    float g2 = 1.0f / (1.0f + w.lambdaO + GgxLambda(p.alpha, wi.z));
    float g1 = 1.0f / (1.0f + w.lambdaO);
    // f_s cos = F D G2 / (4 cos_o); VNDF reflection pdf = G1 D / (4 cos_o).
    e.fCos += fresnel * (d * g2 / (4.0f * wo.z));
    e.pdf += w.pSpec * g1 * d / (4.0f * wo.z);
    return e;
}

[[gnu::always_inline]] inline bool SampleBsdf(const BsdfParams& p, const BsdfWo& w, const vec2& u, float uLobe,
                                              BsdfSample& out) {
    const vec3& wo = w.wo;
    if (wo.z <= 0.0f) return false;
    vec3 wi;
    if (uLobe < w.pSpec) {
        vec3 h = SampleGgxVndf(p.alpha, wo, u);
        wi = 2.0f * glm::dot(wo, h) * h - wo;
    } else {
        // Cosine-weighted hemisphere (concentric disk).
        vec2 d = 2.0f * u - vec2(1.0f);
        float r, phi;
        if (d.x == 0.0f && d.y == 0.0f) {
            r = 0.0f;
            phi = 0.0f;
        } else if (std::abs(d.x) > std::abs(d.y)) {
            r = d.x;
            phi = (kPi / 4.0f) * (d.y / d.x);
        } else {
            r = d.y;
            phi = (kPi / 2.0f) - (kPi / 4.0f) * (d.x / d.y);
        }
        float x = r * std::cos(phi), y = r * std::sin(phi);
        wi = vec3(x, y, std::sqrt(std::max(0.0f, 1.0f - x * x - y * y)));
    }
    if (wi.z <= 0.0f) return false;
    BsdfEval e = EvalBsdf(p, w, wi);
    if (!(e.pdf > 0.0f)) return false;
    out.wi = wi;
    out.pdf = e.pdf;
    out.weight = e.fCos / e.pdf;
    return true;
}

}  // namespace fovrt
