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
// One invocation: RAE_PIXELS_PER_INVOCATION pixels of a row × RAE_OUT_PER_INVOCATION output
// channels (each input tap loaded once for all outputs, each weight once for all pixels);
// workgroups along x cover tiles_x × (output-channel groups).
#include "shared_constants.h"
#include "push_constants.h"
#include "common/packing.glsl"

layout(local_size_x = RAE_WORKGROUP, local_size_y = RAE_WORKGROUP) in;

FOVRT_DECLARE_BINDINGS(RAE_CONV_BINDING_LIST)  // shaders/bindings/rae.h

FOVRT_PUSH_CONSTANTS(FOVRT_PUSH_RAE_CONV);  // shaders/push_constants.h

void main() {
    const int tile = int(gl_WorkGroupID.x) % pc.tiles_x;
    const int group = int(gl_WorkGroupID.x) / pc.tiles_x;
    // RAE_PIXELS_PER_INVOCATION consecutive pixels of a row: each weight is loaded once for all of
    // them (on lavapipe a weight load is a gather across the SIMD lanes: measured 5.0 s → see README
    // for the run at 640×360 with one pixel per invocation).
    const int x0 = (tile * RAE_WORKGROUP + int(gl_LocalInvocationID.x)) * RAE_PIXELS_PER_INVOCATION;
    const int py = int(gl_GlobalInvocationID.y);
    if (x0 >= pc.size.x || py >= pc.size.y) return;
    const int o0 = group * RAE_OUT_PER_INVOCATION;
    const int inTotal = pc.in_a + pc.in_b;
    const bool up = (pc.flags & RAE_FLAG_UPSAMPLE_A) != 0u;
    const ivec2 sizeA = up ? pc.size / 2 : pc.size;
    const uint planeA = uint(sizeA.x * sizeA.y), plane = uint(pc.size.x * pc.size.y);
    // Output channels past out_channels read the last one's weights and are not stored.
    uint wBase[RAE_OUT_PER_INVOCATION];
    float acc[RAE_OUT_PER_INVOCATION][RAE_PIXELS_PER_INVOCATION];
    [[unroll]] for (int k = 0; k < RAE_OUT_PER_INVOCATION; ++k) {
        const int o = min(o0 + k, pc.out_channels - 1);
        wBase[k] = pc.w_offset + uint(o * inTotal) * 9u;
        const float b = weights[pc.bias_offset + uint(o)];
        [[unroll]] for (int j = 0; j < RAE_PIXELS_PER_INVOCATION; ++j) acc[k][j] = b;
    }
    const int span = RAE_PIXELS_PER_INVOCATION + 2;
    for (int i = 0; i < inTotal; ++i) {
        const bool fromA = i < pc.in_a;
        // The 3 × (pixels + 2) input window, zero outside the image (zero padding).
        float v[3][RAE_PIXELS_PER_INVOCATION + 2];
        [[unroll]] for (int ky = 0; ky < 3; ++ky) {
            const int y = py + ky - 1;
            const bool rowIn = y >= 0 && y < pc.size.y;
            const int yc = clamp(y, 0, pc.size.y - 1);
            [[unroll]] for (int c = 0; c < span; ++c) {
                const int x = x0 + c - 1;
                const bool inside = rowIn && x >= 0 && x < pc.size.x;
                const int xc = clamp(x, 0, pc.size.x - 1);
                uint index;
                if (fromA) {
                    const ivec2 q = up ? ivec2(xc, yc) / 2 : ivec2(xc, yc);
                    index = pc.a_offset + uint(i) * planeA + uint(q.y * sizeA.x + q.x);
                } else {
                    index = pc.b_offset + uint(i - pc.in_a) * plane + uint(yc * pc.size.x + xc);
                }
                const float value = float(act[index]);
                v[ky][c] = inside ? value : 0.0;
            }
        }
        [[unroll]] for (int k = 0; k < RAE_OUT_PER_INVOCATION; ++k) {
            const uint w = wBase[k] + uint(i) * 9u;
            [[unroll]] for (int t = 0; t < 9; ++t) {
                const float wt = weights[w + uint(t)];
                [[unroll]] for (int j = 0; j < RAE_PIXELS_PER_INVOCATION; ++j) acc[k][j] += wt * v[t / 3][j + t % 3];
            }
        }
    }
    [[unroll]] for (int k = 0; k < RAE_OUT_PER_INVOCATION; ++k) {
        const int o = o0 + k;
        if (o >= pc.out_channels) break;
        [[unroll]] for (int j = 0; j < RAE_PIXELS_PER_INVOCATION; ++j) {
            if (x0 + j >= pc.size.x) break;
            float r = acc[k][j];
            if ((pc.flags & RAE_FLAG_LEAKY) != 0u) r = r > 0.0 ? r : 0.1 * r;
            act[pc.dst_offset + uint(o) * plane + uint(py * pc.size.x + x0 + j)] = hfloat(r);
        }
    }
}
