// Bindings declared once for GLSL and C++. A pass lists its bindings (set 0) in
// shaders/bindings/<pass>.h as a macro of rows B(PASS, NAME, slot, KIND, FORMAT, variable):
//   TEXEL   read-only uniform texel buffer (samplerBuffer) of VkBufferView format FORMAT
//   HTEXEL  read-only plane stored at the denoiser's precision (a history, the illumination
//           ping-pong, a colour input) as a texel buffer: FORMAT in fp32, its 16-bit twin in the
//           _fp16 variants, RGBA16F for RGB32F (the fetch converts, so the shader code is the same)
//   NTEXEL  read-only normal plane: a texel buffer of FORMAT (RGB32F) in fp32, an isamplerBuffer of
//           octahedral R16G16_SINT codes in the _fp16 variants (read with FETCH_NORMAL)
//   UTEXEL  read-only usamplerBuffer of format FORMAT
//   DTEXEL  read-only linear-depth plane: a texel buffer of FORMAT (R32F) in fp32, a usamplerBuffer
//           of depth + object id codes (R32UI, common/depth_id.glsl) in the _fp16 variants (read
//           with FETCH_DEPTH)
//   OTEXEL  read-only object-id plane: a usamplerBuffer of FORMAT (R32UI); in the _fp16 variants
//           bound to the depth plane, whose codes hold the ids (read with FETCH_OBJECT)
//   HTEXEL3 an RGB history plane: a texel buffer of FORMAT in fp32, a readonly std430 hfloat array
//           in the _fp16 variants (RGB16F texel buffers are rarely supported)
//   READ    std430 readonly array of GLSL type FORMAT (uint, GradientSample, …)
//   WRITE   std430 writeonly array of GLSL type FORMAT (vec4, float, hfloat, hvec4, …)
//   RW      std430 array of GLSL type FORMAT, read and written
//   LIST    a pixel list / its dispatch arguments, declared by common/pixel_list.glsl
// From the rows, GLSL gets `const int PASS_B_NAME = slot;` and the declaration
// (FOVRT_DECLARE_BINDINGS(LIST)); C++ gets the same constants, the binding count
// (FOVRT_BINDING_COUNT) and, on the host, the texel-format table (denoise/vulkan/
// svgf_texel_formats.h: FOVRT_TEXEL_FORMATS). Why texel buffers: common/access.glsl.
#ifndef FOVRT_BINDINGS_H
#define FOVRT_BINDINGS_H

#define FOVRT_BINDING_PLUS_ONE(pass, name, slot, kind, format, variable) +1
// Number of bindings of a list (slots are 0 … count − 1).
#define FOVRT_BINDING_COUNT(LIST) (0 LIST(FOVRT_BINDING_PLUS_ONE))

#ifdef __cplusplus
#define FOVRT_BINDING_CONSTANT(pass, name, slot, kind, format, variable) inline constexpr int pass##_B_##name = slot;
// The slot constants of a list, at namespace scope.
#define FOVRT_BINDING_CONSTANTS(LIST) LIST(FOVRT_BINDING_CONSTANT)
// A pass's slot constants PASS_B_* and its count PASS_BINDINGS, from PASS_BINDING_LIST.
#define FOVRT_PASS_BINDINGS(PASS)                      \
    FOVRT_BINDING_CONSTANTS(PASS##_BINDING_LIST)       \
    inline constexpr int PASS##_BINDINGS = FOVRT_BINDING_COUNT(PASS##_BINDING_LIST);
// Its pair variant (two channels per dispatch): the second channel's constants
// (PASS_PAIR_BINDING_LIST) and PASS_PAIR_BINDINGS over both (PASS_PAIR_ALL_BINDING_LIST).
#define FOVRT_PAIR_BINDINGS(PASS)                      \
    FOVRT_BINDING_CONSTANTS(PASS##_PAIR_BINDING_LIST)  \
    inline constexpr int PASS##_PAIR_BINDINGS = FOVRT_BINDING_COUNT(PASS##_PAIR_ALL_BINDING_LIST);
#else
#define FOVRT_GLSL_DECL_TEXEL(slot, format, variable, block) layout(binding = slot) uniform samplerBuffer variable;
#define FOVRT_GLSL_DECL_HTEXEL(slot, format, variable, block) layout(binding = slot) uniform samplerBuffer variable;
#define FOVRT_GLSL_DECL_UTEXEL(slot, format, variable, block) layout(binding = slot) uniform usamplerBuffer variable;
#define FOVRT_GLSL_DECL_OTEXEL(slot, format, variable, block) layout(binding = slot) uniform usamplerBuffer variable;
#ifdef FOVRT_FP16
#define FOVRT_GLSL_DECL_NTEXEL(slot, format, variable, block) layout(binding = slot) uniform isamplerBuffer variable;
#define FOVRT_GLSL_DECL_DTEXEL(slot, format, variable, block) layout(binding = slot) uniform usamplerBuffer variable;
#else
#define FOVRT_GLSL_DECL_NTEXEL(slot, format, variable, block) layout(binding = slot) uniform samplerBuffer variable;
#define FOVRT_GLSL_DECL_DTEXEL(slot, format, variable, block) layout(binding = slot) uniform samplerBuffer variable;
#endif
#ifdef FOVRT_FP16
#define FOVRT_GLSL_DECL_HTEXEL3(slot, format, variable, block) \
    layout(std430, binding = slot) readonly buffer block { hfloat variable[]; };
#else
#define FOVRT_GLSL_DECL_HTEXEL3(slot, format, variable, block) layout(binding = slot) uniform samplerBuffer variable;
#endif
#define FOVRT_GLSL_DECL_READ(slot, type, variable, block) \
    layout(std430, binding = slot) readonly buffer block { type variable[]; };
#define FOVRT_GLSL_DECL_WRITE(slot, type, variable, block) \
    layout(std430, binding = slot) writeonly buffer block { type variable[]; };
#define FOVRT_GLSL_DECL_RW(slot, type, variable, block) layout(std430, binding = slot) buffer block { type variable[]; };
#define FOVRT_GLSL_DECL_LIST(slot, type, variable, block)
#define FOVRT_GLSL_BINDING(pass, name, slot, kind, format, variable) \
    const int pass##_B_##name = slot;                                 \
    FOVRT_GLSL_DECL_##kind(slot, format, variable, pass##_##name##_Block)
// Every binding of a list: its slot constant and its declaration.
#define FOVRT_DECLARE_BINDINGS(LIST) LIST(FOVRT_GLSL_BINDING)
#endif

#endif
