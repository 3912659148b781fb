// Separable filtering shared by SSIM and FLIP (internal to fovrt_metrics). Rows run in parallel;
// every output pixel is computed by one fixed sequence of operations, so results do not depend on
// the thread count.
#pragma once

#include <functional>
#include <vector>

#include "core/image.h"

namespace fovrt::metrics_detail {

enum class Border {
    kReplicate,    // clamp coordinates to the image (FLIP reference: BORDER_REPLICATE)
    kRenormalise,  // drop taps outside the image and rescale the rest to the full kernel sum
};

// out(x, y) = Σ_i Σ_j kx[i] ky[j] in(x + i − rx, y + j − ry); kernels have odd length.
// Instantiated for float (FLIP) and double (SSIM moments, where E[x²] − μ² needs the precision).
template <typename T>
Plane<T> ConvolveSeparable(const Plane<T>& in, const std::vector<T>& kx, const std::vector<T>& ky, Border border);

// Runs body(y) for every row y in [0, height), in parallel.
void ParallelRows(int height, const std::function<void(int)>& body);

}  // namespace fovrt::metrics_detail
