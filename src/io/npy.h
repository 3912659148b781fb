// NumPy .npy files (format version 1.0): little-endian float32 arrays in C order, the exchange
// format between fovrt and the training code (training/), which reads them with numpy alone.
// Only what that exchange needs: '<f4', fortran_order False, any rank.
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

namespace fovrt {

struct NpyArray {
    std::vector<int64_t> shape;
    std::vector<float> data;  // C order, product(shape) values
};

// Writes `array` to `path` (atomically: a temporary file renamed). fovrt::Error on I/O failure.
void WriteNpy(const std::filesystem::path& path, const NpyArray& array);
// Reads a '<f4' C-order array; fovrt::Error naming the file for any other dtype or a bad header.
NpyArray ReadNpy(const std::filesystem::path& path);

}  // namespace fovrt
