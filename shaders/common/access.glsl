// Access layer of the gather-heavy passes (à-trous, filter moments): their read-only per-pixel
// planes are uniform texel buffers (samplerBuffer / usamplerBuffer) whose format is declared on the
// host's VkBufferView (denoise/vulkan/svgf_texel_formats.h), not std430 arrays. Same bytes, same buffers;
// only the descriptor type differs. Why: lavapipe turns each std430 load into a per-lane loop with
// a bounds check, but a texel fetch into one vector gather — measured ~3.3× faster for a 25-tap
// gather at 1280×720 (denoise/svgf.md, "Speed"). fp16 history planes are R16/R16G16_SFLOAT views:
// the fetch converts, so the _fp16 variants need no 16-bit arithmetic here.
// Out-of-range texel fetches return 0 instead of reading out of bounds (callers still test).
#ifndef FOVRT_ACCESS_GLSL
#define FOVRT_ACCESS_GLSL
#include "depth_id.glsl"
#include "octahedral_normal.glsl"

#define PLANE(binding_, name) layout(binding = binding_) uniform samplerBuffer name
#define UPLANE(binding_, name) layout(binding = binding_) uniform usamplerBuffer name
#define IPLANE(binding_, name) layout(binding = binding_) uniform isamplerBuffer name
#define FETCH1(name, i) texelFetch(name, (i)).x
#define FETCH2(name, i) texelFetch(name, (i)).xy
#define FETCH3(name, i) texelFetch(name, (i)).xyz
#define FETCH4(name, i) texelFetch(name, (i))
// A normal plane (an NTEXEL binding, shaders/bindings.h): RGB32F, or octahedral in the _fp16 variants.
#ifdef FOVRT_FP16
#define FETCH_NORMAL(name, i) octahedral_normal(texelFetch(name, (i)).xy)
#else
#define FETCH_NORMAL(name, i) texelFetch(name, (i)).xyz
#endif
// Linear depth and object id (DTEXEL and OTEXEL bindings): R32F and R32UI planes, or one plane of
// depth + id codes in the _fp16 variants (common/depth_id.glsl).
#ifdef FOVRT_FP16
#define FETCH_DEPTH(name, i) depth_id_depth(texelFetch(name, (i)).x)
#define FETCH_OBJECT(name, i) depth_id_object(texelFetch(name, (i)).x)
#else
#define FETCH_DEPTH(name, i) texelFetch(name, (i)).x
#define FETCH_OBJECT(name, i) texelFetch(name, (i)).x
#endif

// Index of pixel q clamped into a size.x × size.y image. The gather filters (svgf_atrous,
// two_history_gradient) do not skip taps outside the image or on background with `continue`: on
// lavapipe a `continue` (or an early `return`) only narrows the lane mask, after which every
// accumulator update becomes a masked blend (measured: −14 to −20 % per à-trous iteration). Such
// taps are fetched at the clamped index and enter with weight 0; adding an exact 0 leaves the
// sums bit-identical for finite data (the illumination is sanitised before it enters a history).
bool in_image(ivec2 q, ivec2 size) { return all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, size)); }
int clamped_index(ivec2 q, ivec2 size) {
    q = clamp(q, ivec2(0), size - 1);
    return q.y * size.x + q.x;
}

// Edge-stopping guide written by svgf_pack_guide: xyz = normal, w = linear depth, w = −1 on
// background pixels (object id kNoObject).
#define GUIDE_IS_BACKGROUND(g) ((g).w < 0.0)
// An (illumination, variance) texel of a pixel that holds nothing (FOVRT_EMPTY_VARIANCE).
#define HOLDS_NOTHING(v) ((v).a < 0.0)

#endif
