#include "render/bsdf.h"

#include <algorithm>
#include <cmath>

namespace fovrt {
namespace {

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

BsdfEval EvalBsdf(const BsdfParams& p, const vec3& wo, const vec3& wi) {
    return EvalBsdf(p, PrepareBsdfWo(p, wo), wi);
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
