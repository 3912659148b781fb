// The edge-stopping weights of the SVGF spatial filters (Schied et al. 2017, §4.3), written once
// for GLSL and C++ (shared_language.glsl): the shaders call them through edge_stopping.glsl, the C++
// reference through DepthWeight, NormalWeight and LuminanceWeight (denoise/reference/svgf_ref.h).
//   w_z = exp(−|z(p)−z(q)| / (σz |∇z(p)·(p−q)| + ε)),  w_n = max(0, n·n')^σn,
//   w_l = exp(−|l(p)−l(q)| / (σl sqrt(g3×3(Var l(p))) + ε)).
#ifndef FOVRT_EDGE_STOPPING_WEIGHTS_GLSL
#define FOVRT_EDGE_STOPPING_WEIGHTS_GLSL
#include "shared_language.glsl"
#include "../shared_constants.h"

FOVRT_GLSL_BEGIN

// The denominator of w_z: the depth change the local gradient predicts over the offset, plus ε.
FOVRT_SHARED_FN float depth_weight_denominator(vec2 depth_grad, vec2 offset, float sigma_depth) {
    return sigma_depth * abs(dot(depth_grad, offset)) + float(FOVRT_ATROUS_DEPTH_EPSILON);
}

FOVRT_SHARED_FN float depth_weight(float zp, float zq, vec2 depth_grad, vec2 offset, float sigma_depth) {
    return exp(-abs(zp - zq) / depth_weight_denominator(depth_grad, offset, sigma_depth));
}

// w_n for any σn (the shaders take k squarings instead where σn = 2^k: edge_stopping.glsl).
FOVRT_SHARED_FN float normal_weight_pow(vec3 np, vec3 nq, float sigma_normal) {
    return pow(max(0.0f, dot(np, nq)), sigma_normal);
}

FOVRT_SHARED_FN float luminance_weight(float lp, float lq, float sigma_l_std) {
    return exp(-abs(lp - lq) / (sigma_l_std + float(FOVRT_ATROUS_LUMINANCE_EPSILON)));
}

FOVRT_GLSL_END

#endif
