// rae_check WEIGHTS INPUT.npy EXPECTED.npy: runs the C++ reference (denoise/reference/rae_net.h)
// on every frame of INPUT ([T, C, H, W], network inputs, colour already raised to γ) with the
// hidden state carried, and exits 0 when every frame is within 1e-4 relative (max |a − b| /
// max |b|) of EXPECTED ([T, 3, H, W], PyTorch's outputs). Used by tests/rae_training_check.sh:
// export → C++ load reproduces PyTorch's output.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>

#include "denoise/rae_weights.h"
#include "denoise/reference/rae_net.h"
#include "io/npy.h"

int main(int argc, char** argv) {
    using namespace fovrt;
    if (argc != 4) {
        std::fprintf(stderr, "usage: rae_check WEIGHTS INPUT.npy EXPECTED.npy\n");
        return 2;
    }
    try {
        const RaeWeights w = LoadRaeWeights(argv[1]);
        const NpyArray in = ReadNpy(argv[2]), expected = ReadNpy(argv[3]);
        if (in.shape.size() != 4 || expected.shape.size() != 4 || in.shape[0] != expected.shape[0]) {
            std::fprintf(stderr, "rae_check: shapes do not match\n");
            return 2;
        }
        RaeState state;
        double worst = 0.0;
        for (int64_t t = 0; t < in.shape[0]; ++t) {
            Tensor x(int(in.shape[1]), int(in.shape[2]), int(in.shape[3])), y;
            std::copy_n(in.data.begin() + std::ptrdiff_t(size_t(t) * x.data.size()), x.data.size(), x.data.begin());
            RaeForward(w, x, state, y);
            double err = 0.0, scale = 0.0;
            const size_t base = size_t(t) * y.data.size();
            for (size_t i = 0; i < y.data.size(); ++i) {
                err = std::max(err, double(std::abs(y.data[i] - expected.data[base + i])));
                scale = std::max(scale, double(std::abs(expected.data[base + i])));
            }
            const double rel = err / std::max(scale, 1e-30);
            std::printf("frame %lld: max |C++ - PyTorch| / max |PyTorch| = %.3g\n", (long long)t, rel);
            worst = std::max(worst, rel);
        }
        return worst < 1e-4 ? 0 : 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "rae_check: %s\n", e.what());
        return 2;
    }
}
