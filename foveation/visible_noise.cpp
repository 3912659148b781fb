// VisibleNoiseEstimator: one path sample's noise contrast and the display luminance per tile, from
// the frames an eye has shown (visible_noise.h).
#include "foveation/visible_noise.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace fovrt {

float VisibleNoise::Bilinear(const Plane<float>& tiles, float x, float y) const {
    // Tile t's centre is at (t + ½)·tileSize; outside the outer centres the edge tile holds.
    const float u = std::clamp(x / float(tileSize) - 0.5f, 0.0f, float(tiles.width() - 1));
    const float v = std::clamp(y / float(tileSize) - 0.5f, 0.0f, float(tiles.height() - 1));
    const int x0 = std::min(int(u), tiles.width() - 1), y0 = std::min(int(v), tiles.height() - 1);
    const int x1 = std::min(x0 + 1, tiles.width() - 1), y1 = std::min(y0 + 1, tiles.height() - 1);
    const float fx = u - float(x0), fy = v - float(y0);
    const float top = tiles(x0, y0) + fx * (tiles(x1, y0) - tiles(x0, y0));
    const float bottom = tiles(x0, y1) + fx * (tiles(x1, y1) - tiles(x0, y1));
    return top + fy * (bottom - top);
}

VisibleNoiseEstimator::VisibleNoiseEstimator(int tileSize, float decay) : tileSize_(tileSize), decay_(decay) {
    FOVRT_CHECK(tileSize > 0 && decay >= 0.0f && decay < 1.0f);
}

void VisibleNoiseEstimator::Reset() {
    sums_.clear();
    tilesX_ = tilesY_ = 0;
    noise_ = VisibleNoise();
}

void VisibleNoiseEstimator::Add(const Plane<float>& display, const Plane<uint16_t>& count,
                                const VisibleNoiseGuides& guides) {
    const int w = display.width(), h = display.height();
    FOVRT_CHECK(count.width() == w && count.height() == h);
    FOVRT_CHECK(!guides.modulation || (guides.modulation->width() == w && guides.modulation->height() == h));
    FOVRT_CHECK(!guides.objectId || (guides.objectId->width() == w && guides.objectId->height() == h));
    auto modulation = [&](int x, int y) { return guides.modulation ? std::max((*guides.modulation)(x, y), 1e-3f) : 1.0f; };
    auto object = [&](int x, int y) { return guides.objectId ? (*guides.objectId)(x, y) : 0u; };
    if (!noise_.Matches(w, h) || sums_.empty()) {
        Reset();
        tilesX_ = (w + tileSize_ - 1) / tileSize_, tilesY_ = (h + tileSize_ - 1) / tileSize_;
        sums_.assign(size_t(tilesX_) * size_t(tilesY_), TileSums{});
        noise_.imageWidth = w, noise_.imageHeight = h;
    }
    for (TileSums& t : sums_) {
        t.variance *= decay_, t.varianceCount *= decay_;
        t.luminance *= decay_, t.samples *= decay_;
    }
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const double n = count(x, y);
            if (n == 0.0) continue;
            const double d = display(x, y), a = modulation(x, y);
            const uint32_t id = object(x, y);
            TileSums& tile = sums_[size_t(y / tileSize_) * size_t(tilesX_) + size_t(x / tileSize_)];
            tile.luminance += n * d, tile.samples += n;
            double neighbours = 0.0, weighted = 0.0;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const int nx = x + dx, ny = y + dy;
                    if ((dx == 0 && dy == 0) || !display.InBounds(nx, ny) || object(nx, ny) != id) continue;
                    neighbours += count(nx, ny);
                    weighted += double(count(nx, ny)) * display(nx, ny) / modulation(nx, ny);
                }
            if (neighbours == 0.0) continue;
            const double residual = a * (d / a - weighted / neighbours);
            tile.variance += residual * residual / (1.0 / n + 1.0 / neighbours);
            tile.varianceCount += 1.0;
        }
    }
    Publish();
}

void VisibleNoiseEstimator::Publish() {
    noise_.tileSize = tileSize_;
    noise_.luminance.Resize(tilesX_, tilesY_);
    noise_.contrast.Resize(tilesX_, tilesY_);
    // Tiles without an estimate (no sample yet) take the image's: its pooled σ² and luminance.
    double variance = 0.0, varianceCount = 0.0, luminance = 0.0, samples = 0.0;
    for (const TileSums& t : sums_)
        variance += t.variance, varianceCount += t.varianceCount, luminance += t.luminance, samples += t.samples;
    if (varianceCount <= 0.0 || samples <= 0.0) {
        noise_.meanContrast = 0.0f;
        return;
    }
    auto contrastOf = [](double sigma2, double l) { return l > 0.0 ? float(std::sqrt(std::max(sigma2, 0.0)) / l) : 0.0f; };
    const double imageVariance = variance / varianceCount, imageLuminance = luminance / samples;
    double contrastSum = 0.0;
    for (int ty = 0; ty < tilesY_; ++ty)
        for (int tx = 0; tx < tilesX_; ++tx) {
            const TileSums& t = sums_[size_t(ty) * size_t(tilesX_) + size_t(tx)];
            const bool seen = t.varianceCount > 0.0 && t.samples > 0.0;
            const double l = seen ? t.luminance / t.samples : imageLuminance;
            const float r = contrastOf(seen ? t.variance / t.varianceCount : imageVariance, l);
            noise_.luminance(tx, ty) = float(l);
            noise_.contrast(tx, ty) = r;
            const int pixels = (std::min((tx + 1) * tileSize_, noise_.imageWidth) - tx * tileSize_) *
                               (std::min((ty + 1) * tileSize_, noise_.imageHeight) - ty * tileSize_);
            contrastSum += double(r) * pixels;
        }
    noise_.meanContrast = float(contrastSum / (double(noise_.imageWidth) * noise_.imageHeight));
}

}  // namespace fovrt
