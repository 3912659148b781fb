// Edge-stopping weights of the SVGF spatial filters: w_z, w_n and w_l as edge_stopping_weights.glsl
// writes them once for GLSL and C++, plus the shaders' fast forms (σn = 2^k as squarings, the
// product as one exp2).
#ifndef FOVRT_EDGE_STOPPING_GLSL
#define FOVRT_EDGE_STOPPING_GLSL
#extension GL_EXT_control_flow_attributes : require
#include "shared_constants.h"
#include "edge_stopping_weights.glsl"

// σn = 2^k (the default 128 = 2^7) is a specialization constant: w_n is then k squarings.
layout(constant_id = FOVRT_SPEC_NORMAL_SQUARINGS) const int kNormalSquarings = -1;

float normal_weight_squared(float cos_nq) {
    float w = max(0.0, cos_nq);
    [[unroll]] for (int i = 0; i < FOVRT_MAX_NORMAL_SQUARINGS; ++i)
        if (i < kNormalSquarings) w *= w;  // folded at pipeline creation
    return w;
}

float normal_weight(vec3 np, vec3 nq, float sigma_normal) {
    if (kNormalSquarings >= 0) return normal_weight_squared(dot(np, nq));
    return normal_weight_pow(np, nq, sigma_normal);
}

// The product w_z·w_n(·w_l) as one exp2 (one transcendental pair per tap instead of three; same
// value up to rounding): lavapipe executes every tap of every lane, so this is the hot path.
// Split in terms so a multi-channel filter (svgf_atrous_pair) computes the geometric part once
// per tap and only the luminance term per channel; geometry_weight is their composition. With
// σn = 2^k the normal term is a factor (k squarings) instead of a log2 in the exponent:
// geometry_normal_log2 is then 0 and geometry_normal_factor carries w_n (else it is 1).
float geometry_depth_term(float zp, float zq, vec2 depth_grad, vec2 offset, float sigma_depth) {
    return abs(zp - zq) / depth_weight_denominator(depth_grad, offset, sigma_depth);
}
float geometry_normal_log2(vec3 np, vec3 nq, float sigma_normal) {
    if (kNormalSquarings >= 0) return 0.0;
    return sigma_normal * log2(max(dot(np, nq), 1e-30));
}
float geometry_normal_factor(vec3 np, vec3 nq) {
    return kNormalSquarings >= 0 ? normal_weight_squared(dot(np, nq)) : 1.0;
}
float geometry_weight_from_terms(float depth_term, float normal_log2, float normal_factor, float extra_exponent) {
    return normal_factor * exp2(-(depth_term + extra_exponent) * 1.4426950408889634 + normal_log2);  // log2(e)
}
float geometry_weight(float zp, float zq, vec2 depth_grad, vec2 offset, float sigma_depth, vec3 np, vec3 nq,
                      float sigma_normal, float extra_exponent) {
    return geometry_weight_from_terms(geometry_depth_term(zp, zq, depth_grad, offset, sigma_depth),
                                      geometry_normal_log2(np, nq, sigma_normal), geometry_normal_factor(np, nq),
                                      extra_exponent);
}

// À-trous 1-D kernel h = (1/16, 1/4, 3/8, 1/4, 1/16), indexed by offset + 2.
const float kAtrousKernel[5] = float[5](1.0 / 16.0, 1.0 / 4.0, 3.0 / 8.0, 1.0 / 4.0, 1.0 / 16.0);
// 3×3 Gaussian prefilter of the variance: 1/4 centre, 1/8 edges, 1/16 corners.
float gauss3(int dx, int dy) { return (dx == 0 ? 0.5 : 0.25) * (dy == 0 ? 0.5 : 0.25); }

#endif
