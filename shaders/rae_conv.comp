#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
// rae_conv — one 3×3 convolution layer of the recurrent denoising autoencoder (SPEC §12; C++
// reference RaeConv3x3 in denoise/reference/rae_net.cpp): zero padding 1, bias, optional leaky
// ReLU 0.1. Its input is the concatenation [a, b] in PyTorch's channel order (b: in_b channels,
// possibly none), where a may be read 2×2-nearest-upsampled (the decoder's first conv), so the
// U-Net's concatenations and upsampling never copy a tensor.
// Reads:  act (input tensors a, b at a_offset, b_offset; planar C×H×W), weights.
// Writes: act (out_channels planes at dst_offset).
// One invocation: one pixel × RAE_OUT_PER_INVOCATION output channels (each input tap is loaded
// once for all four); workgroups along x cover tiles_x × (output-channel groups).
#include "shared_constants.h"
#include "push_constants.h"
#include "common/packing.glsl"

layout(local_size_x = RAE_WORKGROUP, local_size_y = RAE_WORKGROUP) in;

FOVRT_DECLARE_BINDINGS(RAE_CONV_BINDING_LIST)  // shaders/bindings/rae.h

FOVRT_PUSH_CONSTANTS(FOVRT_PUSH_RAE_CONV);  // shaders/push_constants.h

void main() {
    const int tile = int(gl_WorkGroupID.x) % pc.tiles_x;
    const int group = int(gl_WorkGroupID.x) / pc.tiles_x;
    const ivec2 p = ivec2(tile * RAE_WORKGROUP + int(gl_LocalInvocationID.x), int(gl_GlobalInvocationID.y));
    if (any(greaterThanEqual(p, pc.size))) return;
    const int o0 = group * RAE_OUT_PER_INVOCATION;
    const int inTotal = pc.in_a + pc.in_b;
    const bool up = (pc.flags & RAE_FLAG_UPSAMPLE_A) != 0u;
    const ivec2 sizeA = up ? pc.size / 2 : pc.size;
    const uint planeA = uint(sizeA.x * sizeA.y), plane = uint(pc.size.x * pc.size.y);
    // Output channels past out_channels read the last one's weights and are not stored.
    uint wBase[RAE_OUT_PER_INVOCATION];
    float acc[RAE_OUT_PER_INVOCATION];
    [[unroll]] for (int k = 0; k < RAE_OUT_PER_INVOCATION; ++k) {
        const int o = min(o0 + k, pc.out_channels - 1);
        wBase[k] = pc.w_offset + uint(o * inTotal) * 9u;
        acc[k] = weights[pc.bias_offset + uint(o)];
    }
    for (int i = 0; i < inTotal; ++i) {
        const bool fromA = i < pc.in_a;
        [[unroll]] for (int ky = 0; ky < 3; ++ky) {
            const int y = p.y + ky - 1;
            if (y < 0 || y >= pc.size.y) continue;
            [[unroll]] for (int kx = 0; kx < 3; ++kx) {
                const int x = p.x + kx - 1;
                if (x < 0 || x >= pc.size.x) continue;
                float v;
                if (fromA) {
                    const ivec2 q = up ? ivec2(x, y) / 2 : ivec2(x, y);
                    v = float(act[pc.a_offset + uint(i) * planeA + uint(q.y * sizeA.x + q.x)]);
                } else {
                    v = float(act[pc.b_offset + uint(i - pc.in_a) * plane + uint(y * pc.size.x + x)]);
                }
                const uint tap = uint(i) * 9u + uint(ky * 3 + kx);
                [[unroll]] for (int k = 0; k < RAE_OUT_PER_INVOCATION; ++k) acc[k] += weights[wBase[k] + tap] * v;
            }
        }
    }
    const uint pixel = uint(p.y * pc.size.x + p.x);
    [[unroll]] for (int k = 0; k < RAE_OUT_PER_INVOCATION; ++k) {
        const int o = o0 + k;
        if (o >= pc.out_channels) break;
        float v = acc[k];
        if ((pc.flags & RAE_FLAG_LEAKY) != 0u) v = v > 0.0 ? v : 0.1 * v;
        act[pc.dst_offset + uint(o) * plane + pixel] = hfloat(v);
    }
}
