// What the RAE's tests share: the relative error that holds one tensor to another.
#pragma once

#include <algorithm>
#include <cmath>

#include <catch2/catch.hpp>

#include "denoise/reference/rae_net.h"

namespace fovrt::test {

// max |a − b| / max |b| over every element.
inline double RelativeError(const Tensor& a, const Tensor& b) {
    REQUIRE(a.data.size() == b.data.size());
    double err = 0.0, scale = 0.0;
    for (size_t i = 0; i < a.data.size(); ++i) {
        err = std::max(err, double(std::abs(a.data[i] - b.data[i])));
        scale = std::max(scale, double(std::abs(b.data[i])));
    }
    return err / std::max(scale, 1e-30);
}

}  // namespace fovrt::test
