#include "denoise/history_window.h"

#include <algorithm>
#include <cmath>

#include "shaders/common/history_window.glsl"

namespace fovrt {

int HistoryWindow::Index(int x, int y) const { return glsl::window_index(ivec2(x, y), origin, size); }

ivec2 WeightedWindowSize(int width, int height, float fraction) {
    auto side = [&](int extent) {
        return std::clamp(int(std::ceil(double(fraction) * double(extent) - 1e-9)), 1, std::max(extent, 1));
    };
    return ivec2(side(width), side(height));
}

HistoryWindow WeightedWindowAt(int width, int height, float fraction, const std::optional<vec2>& gaze) {
    HistoryWindow w;
    w.size = WeightedWindowSize(width, height, fraction);
    const vec2 centre = gaze && std::isfinite(gaze->x) && std::isfinite(gaze->y) ? *gaze : vec2(width, height) * 0.5f;
    auto place = [](float c, int size, int extent) {
        const double start = std::floor(double(c) - 0.5 * double(size) + 0.5);
        return int(std::clamp(start, 0.0, double(extent - size)));
    };
    w.origin = ivec2(place(centre.x, w.size.x, width), place(centre.y, w.size.y, height));
    return w;
}

}  // namespace fovrt
