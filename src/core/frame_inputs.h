// FrameInputs: the only contract between the renderer and the denoisers (SPEC §2).
// One instance per eye per frame. All planes are width×height, row 0 at the top.
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "camera.h"
#include "image.h"
#include "math.h"
#include "plane_list.h"
#include "setting_table.h"

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
// `albedo` is the demodulation factor: the albedo, or F_β under brdf demodulation.
inline vec3 Remodulate(const vec3& albedo, const vec3& direct, const vec3& indirect,
                       const vec3& emission) {
    return albedo * (direct + indirect) + emission;
}

// What direct and indirect are divided by (render.demodulation): the primary albedo (SVGF §3)
// or the primary hit's BRDF pre-integration F_β (Zhuang et al., SPEC §6).
enum class Demodulation : uint8_t { Albedo, Brdf };
NameList DemodulationNames();                  // "albedo", "brdf", in enum order
const char* DemodulationName(Demodulation d);  // one of DemodulationNames()
// False (d untouched) for any other name.
bool ParseDemodulation(std::string_view name, Demodulation& d);

// The per-pixel planes, declared once (core/plane_list.h): X(member, element type, neutral value,
// EXR channels, doc). The fields, Allocate (neutral = background everywhere), Bytes, PlaneNames,
// ForEachPlane and the EXR layers all expand from this list, in this order. The renderer's own
// working planes (primitive ids, barycentrics, world positions, seeds) are not here: they are its
// VisibilityBuffer (render/visibility_buffer.h), which no denoiser reads.
#define FOVRT_FRAME_INPUT_PLANES(X)                                                               \
    X(direct, vec3, vec3(0.0f), "RGB",                                                            \
      "paths with one reflection, divided by the demodulation factor (Modulation()); HDR "       \
      "linear RGB, W/(m²·sr)")                                                                    \
    X(indirect, vec3, vec3(0.0f), "RGB", "the other paths, demodulated like direct")              \
    X(albedo, vec3, vec3(0.0f), "RGB",                                                            \
      "primary-hit albedo (diffuse + F0, in [1e-3, 1]): the (de)modulation factor under albedo "  \
      "demodulation")                                                                             \
    X(fbeta, vec3, vec3(0.0f), "RGB",                                                             \
      "primary-hit BRDF pre-integration F_beta (SPEC §6), >= 1e-3 (may exceed 1): the "           \
      "(de)modulation factor under brdf demodulation; 0 when not asked for "                      \
      "(RenderSettings::fbetaPlane)")                                                             \
    X(emission, vec3, vec3(0.0f), "RGB",                                                          \
      "emitted radiance at the primary hit (added after remodulation)")                           \
    X(normal, vec3, vec3(0.0f), "XYZ", "world-space unit shading normal; 0 for background")       \
    X(linearDepth, float, std::numeric_limits<float>::infinity(), "",                             \
      "metres along the view axis; +inf for background")                                          \
    X(depthGradient, vec2, vec2(0.0f), "XY", "(d depth/dx, d depth/dy) in metres per pixel")      \
    X(objectId, uint32_t, kNoObject, "", "instance id, kNoObject for background")                 \
    X(prevPixel, vec2, vec2(0.0f), "XY",                                                          \
      "motion: previous-frame continuous pixel of this surface point; (-1, -1) behind the "       \
      "previous eye")                                                                             \
    X(sampleCount, uint16_t, uint16_t(1), "",                                                     \
      "n >= 0: samples the tracer took (= spp map; at an A-SVGF gradient sample's pixel the "     \
      "previous frame's n, reused). n = 0: no path sample, direct = indirect = 0, the other "     \
      "planes (the guides) filled as for any n")                                                 \
    X(roughness, float, 0.0f, "",                                                                 \
      "primary hit's GGX roughness in [0,1] (sqrt of alpha); 0 for background. Only the RAE "    \
      "(SPEC §12) reads it")

struct FrameInputs {
    int eye = 0;                 // 0 left, 1 right
    uint32_t frameIndex = 0;
    double timeSeconds = 0.0;
    bool cameraCut = false;      // histories must be reset before this frame
    Demodulation demodulation = Demodulation::Albedo;  // what direct / indirect are divided by
    EyeCamera camera;            // this frame
    EyeCamera prevCamera;        // previous frame (equal to camera on frame 0 / cuts)
    // Where the eye looks on this image (continuous pixel; the spp map's centre); unset where no
    // gaze is known (the denoisers that follow it take the image's centre).
    std::optional<vec2> gazePixel;

    FOVRT_FRAME_INPUT_PLANES(FOVRT_PLANE_MEMBER)

    std::vector<GradientSample> gradientSamples;  // A-SVGF only; empty otherwise

    int width() const { return direct.width(); }
    int height() const { return direct.height(); }

    // Allocates every plane at W×H with neutral values (background everywhere).
    void Allocate(int width, int height);
    // Every plane at W×H with unspecified contents, for a writer that then sets every pixel
    // (the path tracer: SetNeutral per tile, then its values), and no gradient samples.
    void AllocateForOverwrite(int width, int height) {
        FOVRT_FRAME_INPUT_PLANES(FOVRT_PLANE_RESIZE_FOR_OVERWRITE)
        gradientSamples.clear();
    }
    // Neutral values (background) in the rectangle [x0, x1) × [y0, y1) of every plane.
    void SetNeutral(int x0, int y0, int x1, int y1) { FOVRT_FRAME_INPUT_PLANES(FOVRT_PLANE_SET_NEUTRAL) }
    // The (de)modulation factor of direct and indirect: albedo, or fbeta under brdf demodulation.
    const Plane<vec3>& Modulation() const { return demodulation == Demodulation::Brdf ? fbeta : albedo; }
    // The noisy colour the renderer would display: Modulation() * (direct + indirect) + emission.
    vec3 NoisyColor(int x, int y) const;
    // NoisyColor of every pixel.
    Plane<vec3> NoisyImage() const;
    // Bytes held by all planes and the gradient samples (for memory budgets).
    size_t Bytes() const;
    // Names of the planes, in list order (EXR layers, memory tables).
    static const std::vector<std::string>& PlaneNames();

    // f(const PlaneSpec&, Plane<T>&) per plane, in list order (EXR layers: io/exr.h PlaneLayers).
    template <typename F>
    void VisitPlanes(F&& f) { FOVRT_FRAME_INPUT_PLANES(FOVRT_PLANE_VISIT) }
    template <typename F>
    void VisitPlanes(F&& f) const { FOVRT_FRAME_INPUT_PLANES(FOVRT_PLANE_VISIT) }
    // f(PlaneBytes{name, data, element size, byte size}) per plane, in list order (GPU uploads).
    template <typename F>
    void ForEachPlane(F&& f) const { ForEachPlaneBytes(*this, std::forward<F>(f)); }
};

}  // namespace fovrt
