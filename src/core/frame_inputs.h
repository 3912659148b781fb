// FrameInputs: the only contract between the renderer and the denoisers (SPEC §2).
// One instance per eye per frame. All planes are width×height, row 0 at the top.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "camera.h"
#include "image.h"
#include "math.h"

namespace fovrt {

inline constexpr uint32_t kNoObject = 0xFFFFFFFFu;  // object/instance id of a background pixel

// One A-SVGF gradient sample (SPEC §2, A-SVGF paper §3): the previous frame's surface sample at
// `prevPixel`, forward-projected into this frame's `pixel` (inside stratum `stratum`), shaded now
// with the previous frame's seed; it replaced that pixel's own visibility-buffer entry, so the
// pixel's colour is that shading. Luminances are of the full (remodulated) pixel colour.
struct GradientSample {
    ivec2 stratum;      // stratum coordinates (pixel / kGradientStratumSize)
    ivec2 pixel;        // current-frame pixel the sample landed in
    ivec2 prevPixel;    // previous-frame pixel it came from
    float newLuminance; // f_i(G→): current scene, previous seed
    float oldLuminance; // f_{i-1}(G): previous frame's value of that sample
};

inline constexpr int kGradientStratumSize = 3;

// Remodulation (SVGF §3): the displayed colour from demodulated illumination. The one definition
// the renderer, FrameInputs and the A-SVGF re-shading use, so their luminances match bit for bit.
inline vec3 Remodulate(const vec3& albedo, const vec3& direct, const vec3& indirect,
                       const vec3& emission) {
    return albedo * (direct + indirect) + emission;
}

struct FrameInputs {
    int eye = 0;                 // 0 left, 1 right
    uint32_t frameIndex = 0;
    double timeSeconds = 0.0;
    bool cameraCut = false;      // histories must be reset before this frame
    EyeCamera camera;            // this frame
    EyeCamera prevCamera;        // previous frame (equal to camera on frame 0 / cuts)

    // Illumination demodulated by the primary albedo (SVGF §3), HDR, linear RGB, W/(m²·sr).
    Plane<vec3> direct;
    Plane<vec3> indirect;
    Plane<vec3> albedo;          // primary-hit albedo used for (de)modulation, in [0,1]
    Plane<vec3> emission;        // emitted radiance at the primary hit (added after remodulation)
    Plane<vec3> normal;          // world-space unit shading normal; 0 for background
    Plane<float> linearDepth;    // metres along the view axis; +inf for background
    Plane<vec2> depthGradient;   // (d depth/dx, d depth/dy) in metres per pixel
    Plane<uint32_t> objectId;    // instance id, kNoObject for background
    Plane<vec2> prevPixel;       // motion: previous-frame continuous pixel of this surface point
    // Visibility buffer.
    Plane<uint32_t> primitiveId; // triangle index within the instance's mesh
    Plane<vec2> barycentrics;    // (u, v) of the hit, Embree convention
    Plane<vec3> worldPosition;   // primary hit in world space (this frame)
    Plane<uint16_t> sampleCount; // n ≥ 1: samples the tracer took (= spp map; at an A-SVGF
                                 // gradient sample's pixel the previous frame's n, reused)
    Plane<uint32_t> seed;        // per-pixel RNG seed of this frame

    std::vector<GradientSample> gradientSamples;  // A-SVGF only; empty otherwise

    int width() const { return direct.width(); }
    int height() const { return direct.height(); }

    // Allocates every plane at W×H with neutral values (background everywhere).
    void Allocate(int width, int height);
    // The noisy colour the renderer would display: albedo * (direct + indirect) + emission.
    vec3 NoisyColor(int x, int y) const;
    // NoisyColor of every pixel.
    Plane<vec3> NoisyImage() const;
    // Bytes held by all planes (for memory budgets).
    size_t Bytes() const;
    // Names of the planes, in a fixed order (EXR layers, memory tables).
    static const std::vector<std::string>& PlaneNames();
};

}  // namespace fovrt
