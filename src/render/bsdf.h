// The surface model: Lambert + GGX microfacet (glTF metallic/roughness), evaluated in a local
// shading frame (z = shading normal). Smith height-correlated G2, Schlick Fresnel, visible-normal
// (VNDF, Heitz 2018) sampling for the specular lobe, cosine sampling for the diffuse lobe; the two
// lobes are chosen by their approximate Fresnel-weighted albedo and the pdf is the mixture pdf.
#pragma once

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
BsdfEval EvalBsdf(const BsdfParams& params, const BsdfWo& wo, const vec3& wi);
BsdfEval EvalBsdf(const BsdfParams& params, const vec3& wo, const vec3& wi);
// u: direction random numbers, uLobe: lobe selection. Returns false when no direction was made.
bool SampleBsdf(const BsdfParams& params, const BsdfWo& wo, const vec2& u, float uLobe, BsdfSample& out);
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

}  // namespace fovrt
