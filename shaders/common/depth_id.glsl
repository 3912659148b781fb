// Depth and object id in one 32-bit word: fp16 storage keeps the geometry's linear depth and
// object id as one R32UI plane, 4 bytes per pixel instead of 8 (denoise/planes.h, INPUT_DEPTH).
// The depth keeps its float bits less the low FOVRT_DEPTH_ID_BITS of the mantissa (truncated: a
// relative error below 2^-14), which hold the object id modulo 2^FOVRT_DEPTH_ID_BITS − 1; the
// all-ones code is the background's FOVRT_NO_OBJECT. Ids that differ by a multiple of 511 read
// as one object: the reprojection's depth and normal tests still separate them. The host packs
// (DepthIdCode, denoise/planes.cpp); the decoding is written once for GLSL and C++
// (shared_language.glsl): the shaders read depth and ids through FETCH_DEPTH and FETCH_OBJECT
// (access.glsl), the C++ reference rounds its copy of the inputs through the same functions.
#ifndef FOVRT_DEPTH_ID_GLSL
#define FOVRT_DEPTH_ID_GLSL
#include "shared_language.glsl"
#include "../shared_constants.h"

FOVRT_GLSL_BEGIN

// The id bits of a code; all set: the background.
FOVRT_SHARED_FN uint depth_id_mask() { return (1u << FOVRT_DEPTH_ID_BITS) - 1u; }

FOVRT_SHARED_FN uint depth_id_code(float depth, uint id) {
    const uint idCode = id == FOVRT_NO_OBJECT ? depth_id_mask() : id % depth_id_mask();
    return (floatBitsToUint(depth) & ~depth_id_mask()) | idCode;
}

FOVRT_SHARED_FN float depth_id_depth(uint code) { return uintBitsToFloat(code & ~depth_id_mask()); }

FOVRT_SHARED_FN uint depth_id_object(uint code) {
    const uint id = code & depth_id_mask();
    return id == depth_id_mask() ? FOVRT_NO_OBJECT : id;
}

FOVRT_GLSL_END

#endif
