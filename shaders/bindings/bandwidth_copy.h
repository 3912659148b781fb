// bandwidth_copy (src/vk/bandwidth.cpp): the device's streaming copy through the passes' access
// layer — the same source read as an rgba32f uniform texel buffer (mode 0) or as std430 vec4
// (mode 1), written as std430 vec4; N elements each.
#define BANDWIDTH_BINDING_LIST(B)                         \
    B(BANDWIDTH, TEXEL_IN, 0, TEXEL, RGBA32F, src_texel)  \
    B(BANDWIDTH, STORAGE_IN, 1, READ, vec4, src)          \
    B(BANDWIDTH, OUT, 2, WRITE, vec4, dst)
