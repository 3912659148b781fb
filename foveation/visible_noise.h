// The Monte Carlo noise a viewer would see, per tile, estimated from the frames an eye has shown:
// what the perceptual model's noise term reads (foveation.noise_visibility, docs/foveation.md).
// The model's derivation assumes one path sample's variance σ² is the same everywhere; the eye
// sees the noise's contrast σ/L at the local luminance L, and both vary over an image (a dim
// corner lit by a few bright indirect paths, a highlight clipped at the display's white).
#pragma once

#include <cstdint>
#include <vector>

#include "core/image.h"

namespace fovrt {

// Per tile of `tileSize` × `tileSize` pixels (the last row and column may be partial): the display
// luminance L (cd/m²) and the contrast r = σ/L of one path sample, σ² the variance of one sample's
// display luminance. Empty (Valid() false) until a frame with samples was seen.
struct VisibleNoise {
    int tileSize = 0;
    int imageWidth = 0, imageHeight = 0;
    Plane<float> luminance;  // cd/m², the samples' mean
    Plane<float> contrast;   // σ / L of one sample
    float meanContrast = 0.0f;  // r averaged over the image's pixels

    bool Valid() const { return tileSize > 0 && meanContrast > 0.0f; }
    bool Matches(int width, int height) const { return imageWidth == width && imageHeight == height; }
    // Bilinear between tile centres, at continuous pixel (x, y); edges clamped.
    float LuminanceAt(float x, float y) const { return Bilinear(luminance, x, y); }
    float ContrastAt(float x, float y) const { return Bilinear(contrast, x, y); }

private:
    float Bilinear(const Plane<float>& tiles, float x, float y) const;
};

// The guides of a frame, noise-free: the demodulation factor's luminance and the object ids (null:
// 1 and one object everywhere).
struct VisibleNoiseGuides {
    const Plane<float>* modulation = nullptr;
    const Plane<uint32_t>* objectId = nullptr;
};

// Accumulates one eye's frames into a VisibleNoise. Per pixel i with nᵢ > 0 samples, of mean display
// luminance Dᵢ over its demodulation factor aᵢ (the albedo's luminance: texture is not noise),
// vᵢ = Dᵢ/aᵢ, against the leave-one-out mean m̂ of its 3×3 neighbours on the same object (N = Σ nⱼ
// samples): E[(vᵢ − m̂)²] = σᵥ² (1/nᵢ + 1/N) where the illumination is locally flat, so
// aᵢ² (vᵢ − m̂)² / (1/nᵢ + 1/N) estimates σ² without the signal's gradients and edges beyond the
// 3×3 scale (the shadows' edges, which no guide holds, are left in). The tile's sums decay by
// `decay` per frame, so a few frames pool (a pixel below 1 spp is seen on some frames only) and
// the estimate follows the view.
class VisibleNoiseEstimator {
public:
    explicit VisibleNoiseEstimator(int tileSize = 16, float decay = 0.5f);
    // One frame: each pixel's mean display luminance over its samples, and their count (0: none).
    // A frame of another size restarts the estimate.
    void Add(const Plane<float>& displayLuminance, const Plane<uint16_t>& sampleCount, const VisibleNoiseGuides& guides = {});
    void Reset();
    const VisibleNoise& Noise() const { return noise_; }

private:
    struct TileSums {
        double variance = 0.0, varianceCount = 0.0;  // Σ σ² estimates, their count
        double luminance = 0.0, samples = 0.0;       // Σ nᵢ Dᵢ, Σ nᵢ
    };
    void Publish();

    int tileSize_;
    float decay_;
    int tilesX_ = 0, tilesY_ = 0;
    std::vector<TileSums> sums_;
    VisibleNoise noise_;
};

}  // namespace fovrt
