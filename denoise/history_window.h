// Where two-history keeps its weighted history: the whole image, or a window that follows the gaze
// (denoise.two_history.window, the fraction of the image's width and height it spans). Outside the
// window the blend takes the unweighted history alone (SVGF's path); a pixel that enters it starts
// its weighted history afresh (docs/algorithms.md, "The weighted history's window"). The index
// arithmetic is shaders/common/history_window.glsl, shared by the shaders and the C++ reference.
#pragma once

#include <optional>

#include "core/image.h"
#include "core/math.h"

namespace fovrt {

struct HistoryWindow {
    ivec2 origin{0};
    ivec2 size{0};  // 0: unset (the stages that take a window read it as the whole image)
    // Index of image pixel (x, y) in the window's planes; −1 outside.
    int Index(int x, int y) const;
    // The image pixel of the window's index j.
    ivec2 ImagePixel(size_t j) const { return origin + ivec2(int(j % size_t(size.x)), int(j / size_t(size.x))); }
    size_t Pixels() const { return size_t(size.x) * size_t(size.y); }
    // The whole width × height image as a window (indexed as the image is).
    static HistoryWindow Whole(int width, int height) { return {ivec2(0), ivec2(width, height)}; }
    // This window, or the whole image where it is unset.
    HistoryWindow OrWhole(int width, int height) const { return size.x > 0 ? *this : Whole(width, height); }
};

// An image-sized plane from a window's values: valueAt(window index) inside, `outside` elsewhere
// (the debug views of the windowed planes).
template <typename F>
Plane<float> WindowOverImage(int width, int height, const HistoryWindow& window, float outside, F&& valueAt) {
    Plane<float> plane(width, height);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const int j = window.Index(x, y);
            plane(x, y) = j < 0 ? outside : valueAt(size_t(j));
        }
    return plane;
}

// The window's size for an image of width × height: ⌈fraction·width⌉ × ⌈fraction·height⌉, at least
// one pixel; fraction 1 is the image.
ivec2 WeightedWindowSize(int width, int height, float fraction);
// The window of that size centred on `gaze` (a continuous pixel; unknown: the image's centre),
// moved inside the image where the gaze is near an edge.
HistoryWindow WeightedWindowAt(int width, int height, float fraction, const std::optional<vec2>& gaze);

}  // namespace fovrt
