#include "render/bsdf.h"

#include <algorithm>
#include <cmath>

namespace fovrt {
namespace {

vec3 SchlickFresnel(const vec3& f0, float cosTheta) {
    return f0 + (vec3(1.0f) - f0) * SchlickWeight(cosTheta);
}

// Probability of choosing the specular lobe for outgoing direction wo.
float SpecularProbability(const BsdfParams& p, float cosThetaO) {
    // No specular interface (F0 = 0, e.g. an MTL with Ks 0): no Fresnel term to evaluate.
    float spec = p.f0 == vec3(0.0f) ? 0.0f : Luminance(SchlickFresnel(p.f0, cosThetaO));
    float diff = Luminance(p.diffuse);
    if (spec + diff <= 0.0f) return 0.0f;
    return spec / (spec + diff);
}

}  // namespace

float SchlickWeight(float cosTheta) {
    float m = std::clamp(1.0f - cosTheta, 0.0f, 1.0f);
    float m2 = m * m;
    return m2 * m2 * m;
}

float GgxAlphaFromRoughness(float roughness) {
    return std::max(roughness * roughness, kMinGgxAlpha);
}

BsdfParams MakeBsdfParams(const vec3& baseColor, float roughness, float metallic, float specular) {
    metallic = std::clamp(metallic, 0.0f, 1.0f);
    roughness = std::clamp(roughness, 0.0f, 1.0f);
    BsdfParams p;
    p.diffuse = (1.0f - metallic) * baseColor;
    p.f0 = glm::mix(vec3(0.04f * std::max(specular, 0.0f)), baseColor, metallic);
    p.alpha = GgxAlphaFromRoughness(roughness);
    return p;
}

float GgxD(float alpha, float cosThetaH) {
    float a2 = alpha * alpha;
    float c2 = cosThetaH * cosThetaH;
    float d = c2 * (a2 - 1.0f) + 1.0f;
    return a2 / (kPi * d * d);
}

float GgxLambda(float alpha, float cosTheta) {
    float c2 = cosTheta * cosTheta;
    float tan2 = std::max(0.0f, 1.0f - c2) / std::max(c2, 1e-12f);
    return 0.5f * (std::sqrt(1.0f + alpha * alpha * tan2) - 1.0f);
}

vec2 VndfDiskPoint(const vec2& u) {
    float r = std::sqrt(u.x);
    float phi = 2.0f * kPi * u.y;
    return vec2(r * std::cos(phi), r * std::sin(phi));
}

vec3 SampleGgxVndf(float alpha, const vec3& wo, const vec2& u) {
    return SampleGgxVndfDisk(alpha, wo, VndfDiskPoint(u));
}

vec3 SampleGgxVndfDisk(float alpha, const vec3& wo, const vec2& disk) {
    // Heitz 2018, "Sampling the GGX Distribution of Visible Normals".
    vec3 vh = glm::normalize(vec3(alpha * wo.x, alpha * wo.y, wo.z));
    float lensq = vh.x * vh.x + vh.y * vh.y;
    vec3 t1 = lensq > 0.0f ? vec3(-vh.y, vh.x, 0.0f) / std::sqrt(lensq) : vec3(1.0f, 0.0f, 0.0f);
    vec3 t2 = glm::cross(vh, t1);
    float p1 = disk.x;
    float p2 = disk.y;
    float s = 0.5f * (1.0f + vh.z);
    p2 = (1.0f - s) * std::sqrt(std::max(0.0f, 1.0f - p1 * p1)) + s * p2;
    vec3 nh = p1 * t1 + p2 * t2 + std::sqrt(std::max(0.0f, 1.0f - p1 * p1 - p2 * p2)) * vh;
    return glm::normalize(vec3(alpha * nh.x, alpha * nh.y, std::max(1e-6f, nh.z)));
}

BsdfWo PrepareBsdfWo(const BsdfParams& p, const vec3& wo) {
    BsdfWo w;
    w.wo = wo;
    w.pSpec = SpecularProbability(p, wo.z);
    w.lambdaO = w.pSpec > 0.0f ? GgxLambda(p.alpha, wo.z) : 0.0f;
    return w;
}

BsdfEval EvalBsdf(const BsdfParams& p, const BsdfWo& w, const vec3& wi) {
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

BsdfEval EvalBsdf(const BsdfParams& p, const vec3& wo, const vec3& wi) {
    return EvalBsdf(p, PrepareBsdfWo(p, wo), wi);
}

bool SampleBsdf(const BsdfParams& p, const BsdfWo& w, const vec2& u, float uLobe, BsdfSample& out) {
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

bool SampleBsdf(const BsdfParams& p, const vec3& wo, const vec2& u, float uLobe, BsdfSample& out) {
    return SampleBsdf(p, PrepareBsdfWo(p, wo), u, uLobe, out);
}

Frame::Frame(const vec3& normal) : n(normal) {
    float sign = std::copysign(1.0f, n.z);
    float a = -1.0f / (sign + n.z);
    float b0 = n.x * n.y * a;
    t = vec3(1.0f + sign * n.x * n.x * a, sign * b0, -sign * n.x);
    b = vec3(b0, sign + n.y * n.y * a, -n.y);
}

}  // namespace fovrt
