// Plane<T>: one W×H buffer of T in row-major order (row 0 at the top). All per-pixel data in
// fovrt (FrameInputs fields, spp maps, denoised outputs, error maps) is planar.
#pragma once

#include <cstddef>
#include <vector>

#include "check.h"

namespace fovrt {

template <typename T>
class Plane {
public:
    Plane() = default;
    Plane(int width, int height, const T& fill = T{})
        : width_(width), height_(height), data_(size_t(width) * size_t(height), fill) {}

    void Resize(int width, int height, const T& fill = T{}) {
        width_ = width;
        height_ = height;
        data_.assign(size_t(width) * size_t(height), fill);
    }
    void Fill(const T& value) { std::fill(data_.begin(), data_.end(), value); }
    // Resize for a writer that sets every element: the contents are kept (unspecified to the
    // writer) when the size does not change, so no pass over the memory precedes the writes.
    void ResizeForOverwrite(int width, int height, const T& fill = T{}) {
        if (width == width_ && height == height_) return;
        Resize(width, height, fill);
    }

    int width() const { return width_; }
    int height() const { return height_; }
    size_t size() const { return data_.size(); }
    bool empty() const { return data_.empty(); }
    bool InBounds(int x, int y) const { return x >= 0 && y >= 0 && x < width_ && y < height_; }

    T& operator()(int x, int y) { return data_[size_t(y) * size_t(width_) + size_t(x)]; }
    const T& operator()(int x, int y) const { return data_[size_t(y) * size_t(width_) + size_t(x)]; }
    T& operator[](size_t i) { return data_[i]; }
    const T& operator[](size_t i) const { return data_[i]; }

    T* data() { return data_.data(); }
    const T* data() const { return data_.data(); }
    std::vector<T>& vector() { return data_; }
    const std::vector<T>& vector() const { return data_; }
    size_t bytes() const { return data_.size() * sizeof(T); }

private:
    int width_ = 0;
    int height_ = 0;
    std::vector<T> data_;
};

}  // namespace fovrt
