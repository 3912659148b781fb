#include "denoise/reference/rae_net.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>

#include "core/error.h"

namespace fovrt {
namespace {

constexpr float kLeakySlope = 0.1f;

}  // namespace

size_t RaeState::Bytes() const {
    size_t n = 0;
    for (const Tensor& t : hidden) n += t.Bytes();
    return n;
}

void RaeConv3x3(const RaeConv& conv, const Tensor& a, const Tensor* b, bool leaky, Tensor& out) {
    const int inA = a.c, inB = b ? b->c : 0;
    if (!(inA + inB == conv.in)) Fail("conv input channels {} + {} != {}", inA, inB, conv.in);
    const int h = a.h, w = a.w;
    if (b && (b->h != h || b->w != w)) Fail("concatenated tensors differ in size");
    if (out.c != conv.out || out.h != h || out.w != w) out = Tensor(conv.out, h, w);
    constexpr int kRows = 8;
    const int rowBlocks = (h + kRows - 1) / kRows;
    tbb::parallel_for(tbb::blocked_range<int>(0, conv.out * rowBlocks), [&](const tbb::blocked_range<int>& r) {
        for (int job = r.begin(); job != r.end(); ++job) {
            const int o = job / rowBlocks;
            const int y0 = (job % rowBlocks) * kRows, y1 = std::min(h, y0 + kRows);
            for (int y = y0; y < y1; ++y) {
                float* dst = out.Channel(o) + size_t(y) * w;
                std::fill(dst, dst + w, conv.bias[size_t(o)]);
                for (int i = 0; i < conv.in; ++i) {
                    const float* src = i < inA ? a.Channel(i) : b->Channel(i - inA);
                    const float* k = conv.weight.data() + (size_t(o) * conv.in + i) * 9;
                    for (int ky = 0; ky < 3; ++ky) {
                        const int sy = y + ky - 1;
                        if (sy < 0 || sy >= h) continue;
                        const float* row = src + size_t(sy) * w;
                        const float k0 = k[ky * 3 + 0], k1 = k[ky * 3 + 1], k2 = k[ky * 3 + 2];
                        // x - 1 and x + 1 outside the row read the zero padding.
                        if (w > 1) {
                            dst[0] += k1 * row[0] + k2 * row[1];
                            for (int x = 1; x < w - 1; ++x) dst[x] += k0 * row[x - 1] + k1 * row[x] + k2 * row[x + 1];
                            dst[w - 1] += k0 * row[w - 2] + k1 * row[w - 1];
                        } else {
                            dst[0] += k1 * row[0];
                        }
                    }
                }
                if (leaky)
                    for (int x = 0; x < w; ++x) dst[x] = dst[x] > 0.0f ? dst[x] : kLeakySlope * dst[x];
            }
        }
    });
}

void RaeMaxPool2x2(const Tensor& in, Tensor& out) {
    if (!(in.h % 2 == 0 && in.w % 2 == 0)) Fail("max-pool of an odd size {}x{}", in.w, in.h);
    if (out.c != in.c || out.h != in.h / 2 || out.w != in.w / 2) out = Tensor(in.c, in.h / 2, in.w / 2);
    for (int c = 0; c < in.c; ++c)
        for (int y = 0; y < out.h; ++y)
            for (int x = 0; x < out.w; ++x)
                out.At(c, y, x) = std::max(std::max(in.At(c, 2 * y, 2 * x), in.At(c, 2 * y, 2 * x + 1)),
                                           std::max(in.At(c, 2 * y + 1, 2 * x), in.At(c, 2 * y + 1, 2 * x + 1)));
}

void RaeUpsample2x2(const Tensor& in, Tensor& out) {
    if (out.c != in.c || out.h != in.h * 2 || out.w != in.w * 2) out = Tensor(in.c, in.h * 2, in.w * 2);
    for (int c = 0; c < in.c; ++c)
        for (int y = 0; y < out.h; ++y)
            for (int x = 0; x < out.w; ++x) out.At(c, y, x) = in.At(c, y / 2, x / 2);
}

void RaeForward(const RaeWeights& weights, const Tensor& in, RaeState& state, Tensor& out, double* encoderMs,
                double* decoderMs) {
    auto start = std::chrono::steady_clock::now();
    auto lap = [&](double* ms) {
        const auto now = std::chrono::steady_clock::now();
        if (ms) *ms = std::chrono::duration<double, std::milli>(now - start).count();
        start = now;
    };
    const int L = weights.Levels();
    const RaeConvOrder order{L};
    if (!(in.c == weights.inChannels)) Fail("input has {} channels, the network {}", in.c, weights.inChannels);
    if (!(in.h % (1 << L) == 0 && in.w % (1 << L) == 0)) Fail("frame {}x{} is not a multiple of {}", in.w, in.h,
          1 << L);
    const bool fresh = state.hidden.size() != size_t(L + 1);
    std::vector<Tensor> hidden(size_t(L + 1));
    Tensor x, a, t;
    // R(I, h') = C(C([C(I), h'])), h' = 0 after a reset.
    auto recurrent = [&](int level, const Tensor& input, Tensor& h) {
        RaeConv3x3(weights.convs[size_t(order.Recurrent(level, 0))], input, nullptr, true, a);
        Tensor zeros;
        const Tensor* prev = nullptr;
        if (!fresh && state.hidden[size_t(level)].h == a.h && state.hidden[size_t(level)].w == a.w) {
            prev = &state.hidden[size_t(level)];
        } else {
            zeros = Tensor(a.c, a.h, a.w);
            prev = &zeros;
        }
        RaeConv3x3(weights.convs[size_t(order.Recurrent(level, 1))], a, prev, true, t);
        RaeConv3x3(weights.convs[size_t(order.Recurrent(level, 2))], t, nullptr, true, h);
    };
    const Tensor* cur = &in;
    Tensor pooled;
    for (int l = 0; l < L; ++l) {
        RaeConv3x3(weights.convs[size_t(order.Encoder(l))], *cur, nullptr, true, x);
        recurrent(l, x, hidden[size_t(l)]);
        RaeMaxPool2x2(hidden[size_t(l)], pooled);
        cur = &pooled;
    }
    RaeConv3x3(weights.convs[size_t(order.Bottleneck())], *cur, nullptr, true, x);
    recurrent(L, x, hidden[size_t(L)]);
    lap(encoderMs);
    Tensor up, y = hidden[size_t(L)];
    for (int l = L - 1; l >= 0; --l) {
        RaeUpsample2x2(y, up);
        RaeConv3x3(weights.convs[size_t(order.Decoder(l, 0))], up, &hidden[size_t(l)], true, t);
        RaeConv3x3(weights.convs[size_t(order.Decoder(l, 1))], t, nullptr, true, y);
    }
    RaeConv3x3(weights.convs[size_t(order.Output())], y, nullptr, false, out);
    lap(decoderMs);
    state.hidden = std::move(hidden);
}

}  // namespace fovrt
