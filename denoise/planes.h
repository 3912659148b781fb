// The planes of the SVGF-family denoisers (svgf, svgf-weighted, asvgf, two-history,
// two-history-asvgf), declared once: one row per kind of plane with its printed name, whether
// each filtered channel has its own, whether it is a history (an A/B pair: this frame writes one
// side, the next frame reads it as "previous"), its size and, for the per-frame inputs, the
// FrameInputs data it is uploaded from. The pass plan (denoise/pass_plan.h) names planes by
// PlaneId; the memory plan is the union of what its passes name, sized by these rows; the Vulkan
// host and the C++ reference address their buffers and planes by the same ids. Names are for
// printing (`fovrt memory`, error messages, tests): nothing is looked up by a name built at run
// time.
#pragma once

#include <compare>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/frame_inputs.h"
#include "denoise/params.h"

namespace fovrt {

// Size rules of the rows below (W×H pixels, strata of 3×3 pixels):
//   PIXELS_OF(m)      one element of FrameInputs::m per pixel
//   INPUT_RGB(m)      FrameInputs::m, an RGB float plane: 12 bytes per pixel in fp32; in fp16 the
//                     host uploads it as RGBA16F, 8 bytes (ConvertForUpload)
//   INPUT_NORMAL(m)   FrameInputs::m, unit normals: 12 bytes per pixel in fp32; in fp16 the host
//                     uploads them octahedral, two int16, 4 bytes (ConvertForUpload)
//   INPUT_DEPTH(m)    FrameInputs::m, linear depth, 4 bytes per pixel; in fp16 the host uploads
//                     each with the pixel's object id in its low mantissa bits (DepthIdCode), and
//                     the object-id plane is not stored (StoresObjectIdsInDepth)
//   PIXELS(b)         b bytes per pixel
//   STORED(k)         k scalars per pixel stored at the denoiser's precision (4 bytes each, 2 in
//                     fp16): the histories and the (illumination, variance) ping-pong
//   WINDOW_STORED(k)  k stored scalars per pixel of the weighted history's window
//                     (denoise/history_window.h; the whole image unless denoise.two_history.window < 1)
//   STRATA(b)         b bytes per stratum
//   FIXED(b)          b bytes whatever the size (counters, dispatch arguments)
//   SAMPLE_COUNTS     uint16 per pixel, padded to whole 32-bit words (the shaders read pairs)
//   GRADIENT_SAMPLES  the gradient-sample capacity, two per stratum
//   TRANSFERS         the ring the frame's uploads and downloads stream through (vk/transfer_ring.h):
//                     their sum, each 16-byte aligned, or DenoiserParams::transferRingBytes if smaller
// Sources: EVERY_FRAME(m) uploaded from FrameInputs::m every frame; MODULATION from
// FrameInputs::Modulation() (the albedo, or F_β under brdf demodulation); WHEN_READ(m) uploaded
// only by the variants that read it; NONE written on the device.
// X(kind, name, scope, lifetime, size, source); per-channel names are prefixed by the channel.
#define FOVRT_DENOISER_PLANES(X)                                                                    \
    X(Direct, "input.direct", Shared, Scratch, INPUT_RGB(direct), EVERY_FRAME(direct))              \
    X(Indirect, "input.indirect", Shared, Scratch, INPUT_RGB(indirect), EVERY_FRAME(indirect))      \
    X(Modulation, "input.modulation", Shared, Scratch, INPUT_RGB(albedo), MODULATION)               \
    X(Emission, "input.emission", Shared, Scratch, INPUT_RGB(emission), EVERY_FRAME(emission))      \
    X(DepthGradient, "input.depthGradient", Shared, Scratch, PIXELS_OF(depthGradient),              \
      EVERY_FRAME(depthGradient))                                                                   \
    X(PrevPixel, "input.prevPixel", Shared, Scratch, PIXELS_OF(prevPixel), EVERY_FRAME(prevPixel))  \
    X(SampleCount, "input.sampleCount", Shared, Scratch, SAMPLE_COUNTS, WHEN_READ(sampleCount))     \
    /* this frame's geometry, the next frame's previous one */                                      \
    X(Normal, "geometry.normal", Shared, History, INPUT_NORMAL(normal), EVERY_FRAME(normal))        \
    X(Depth, "geometry.depth", Shared, History, INPUT_DEPTH(linearDepth), EVERY_FRAME(linearDepth)) \
    X(ObjectId, "geometry.objectId", Shared, History, PIXELS_OF(objectId), EVERY_FRAME(objectId))   \
    /* edge-stopping guide (svgf_pack_guide): normal, depth */                                      \
    X(Guide, "geometry.guide", Shared, Scratch, PIXELS(16), NONE)                                   \
    /* per channel: SVGF's histories; W_u of two-history is the channel's length */                 \
    X(Color, "color", PerChannel, History, STORED(3), NONE)                                         \
    X(Moments, "moments", PerChannel, History, STORED(2), NONE)                                     \
    X(Length, "length", PerChannel, History, STORED(1), NONE)                                       \
    X(Weight, "weight", PerChannel, History, STORED(1), NONE)                                       \
    X(WColor, "wcolor", PerChannel, History, WINDOW_STORED(3), NONE)                                \
    /* per channel: (illumination, variance) ping-pong of the unweighted / weighted history */      \
    X(Illum0, "illum0", PerChannel, Scratch, STORED(4), NONE)                                       \
    X(Illum1, "illum1", PerChannel, Scratch, STORED(4), NONE)                                       \
    X(WIllum0, "willum0", PerChannel, Scratch, STORED(4), NONE)                                     \
    X(WIllum1, "willum1", PerChannel, Scratch, STORED(4), NONE)                                     \
    /* pixels needing the spatial variance estimate (svgf_moments_classify) and the indirect */     \
    /* dispatch arguments (groups x, y, z, count); earlier in the frame channel 0's list holds */   \
    /* the reprojection's box-fallback pixels, used up before the classify pass refills it */       \
    X(SpatialList, "spatialList", PerChannel, Scratch, PIXELS(4), NONE)                             \
    X(SpatialArgs, "spatialArgs", PerChannel, Scratch, FIXED(16), NONE)                             \
    /* two-history: W_w, (S_-1, S_0, S_1), the luminance gradient g, and q */                       \
    X(WWeight, "wweight", Shared, History, WINDOW_STORED(1), NONE)                                  \
    X(PowerSums, "powerSums", Shared, History, WINDOW_STORED(3), NONE)                              \
    X(Gradient, "gradient", Shared, History, STORED(1), NONE)                                       \
    X(Q, "q", Shared, Scratch, PIXELS(4), NONE)                                                     \
    /* two-history-stable: the stabilised luminance of each channel's filtered illumination */      \
    X(StableLum, "stableLum", PerChannel, History, STORED(1), NONE)                                 \
    /* two-history hysteresis variants: the held history choice p (HystereticChoice) */             \
    X(Choice, "choice", Shared, History, STORED(1), NONE)                                           \
    /* A-SVGF: samples, stratum claims, (δ, Δ) ping-pong, stratum guide, σ_l·std, α, λ */           \
    X(AsvgfSamples, "asvgf.samples", Shared, Scratch, GRADIENT_SAMPLES, WHEN_READ(gradientSamples)) \
    X(AsvgfClaim, "asvgf.claim", Shared, Scratch, STRATA(4), NONE)                                  \
    X(AsvgfGrad0, "asvgf.grad0", Shared, Scratch, STRATA(8), NONE)                                  \
    X(AsvgfGrad1, "asvgf.grad1", Shared, Scratch, STRATA(8), NONE)                                  \
    X(AsvgfGuideGeometry, "asvgf.guideGeometry", Shared, Scratch, STRATA(16), NONE)                 \
    X(AsvgfGuideLuminance, "asvgf.guideLuminance", Shared, Scratch, STRATA(16), NONE)               \
    X(AsvgfSigma, "asvgf.sigmaL", Shared, Scratch, STRATA(4), NONE)                                 \
    X(AsvgfAlpha, "asvgf.alpha", Shared, Scratch, PIXELS(4), NONE)                                  \
    X(AsvgfLambda, "asvgf.lambda", Shared, Scratch, PIXELS(4), NONE)                                \
    X(Output, "output", Shared, Scratch, PIXELS(12), NONE)                                          \
    /* sanitising counters: non-finite and negative inputs */                                       \
    X(Stats, "stats", Shared, Scratch, FIXED(8), NONE)                                              \
    X(Staging, "staging", Shared, Staging, TRANSFERS, NONE)

#define FOVRT_PLANE_KIND(kind, name, scope, lifetime, size, source) kind,
enum class PlaneKind : uint8_t { FOVRT_DENOISER_PLANES(FOVRT_PLANE_KIND) };
#undef FOVRT_PLANE_KIND

// The illumination a plane of scope PerChannel belongs to (SvgfParams::filterCombined: one
// "combined" channel, else "direct" and "indirect").
enum class Channel : uint8_t { None, Direct, Indirect, Combined };
const char* ChannelName(Channel channel);  // "direct", "indirect", "combined"; "" for None
// The channels the SVGF stages filter, in order.
std::vector<Channel> FilteredChannels(const SvgfParams& params);

struct PlaneId {
    PlaneKind kind = PlaneKind::Output;
    Channel channel = Channel::None;  // set exactly for the PerChannel kinds
    auto operator<=>(const PlaneId&) const = default;
};

// Which side of a history a use reads or writes; the host and the reference map it to A or B
// by the parity of the frame.
enum class HistorySide : uint8_t { None, This, Previous };
struct PlaneRef {
    PlaneId id;
    HistorySide side = HistorySide::None;  // set exactly for the history kinds
};
// A buffer: a plane, and for a history its side A or B.
enum class BufferSide : uint8_t { None, A, B };
struct BufferKey {
    PlaneId id;
    BufferSide side = BufferSide::None;
    auto operator<=>(const BufferKey&) const = default;
};
// The buffer side of `side` in a frame whose histories are written to side A (parity 0) or B (1).
BufferSide SideOf(HistorySide side, int parity);
// The buffer of `ref` in that frame.
BufferKey ResolveSide(const PlaneRef& ref, int parity);

bool IsPerChannel(PlaneKind kind);
bool IsHistory(PlaneKind kind);
bool IsStaging(PlaneKind kind);  // host-visible: the transfers go through it
// Fixed-size planes (counters, dispatch arguments) move ~0 bytes per pixel: the byte model and
// the plan ↔ memory test leave them out.
bool IsFixedSize(PlaneKind kind);
// The value a reset fills a plane with (as 32-bit words): background object ids, so that nothing
// reprojects; A-SVGF's α = λ = 1.0f, so that the first frame is taken whole (its gradient passes
// need a previous frame and do not run); in fp16 the normals' "no normal" octahedral code, so that
// a reset holds zero normals at both precisions; 0 everywhere else.
uint32_t ClearValue(PlaneKind kind, Precision precision);

// "input.direct", "direct.color", "direct.color.A".
std::string PlaneName(const PlaneId& id);
std::string BufferName(const BufferKey& key);

// What a plane's size depends on.
struct PlaneExtent {
    int width = 0, height = 0;
    Precision precision = Precision::Fp32;
    ivec2 window{0};  // the WINDOW_STORED planes' pixels; 0: width × height
};
// Whether `kind` holds the weighted history's window (WINDOW_STORED) rather than every pixel.
bool IsWindowed(PlaneKind kind);
inline size_t StoredScalarBytes(Precision p) { return p == Precision::Fp16 ? 2 : 4; }
// Bytes of one scalar of a plane: StoredScalarBytes for the STORED planes, 4 for the others
// (how a host reading a plane back converts it).
size_t ScalarBytes(PlaneKind kind, Precision precision);
// Staging offsets are aligned like CommandRecorder::Upload/Download (16 bytes).
inline size_t StagingAlign(size_t bytes) { return (bytes + 15) & ~size_t(15); }
// Bytes of one buffer of `kind` (one side of a history). Staging (TRANSFERS) is sized by the
// plan from its transfers: 0 here.
size_t PlaneBytes(PlaneKind kind, const PlaneExtent& extent);
// Bytes per element of a plane whose every pixel holds one (0 for strata and fixed planes).
size_t PlaneElementBytes(PlaneKind kind, Precision precision);

// Where the per-frame planes come from: the data of a FrameInputs plane (or its gradient
// samples) for the kinds with a source; null data for the others.
struct HostBytes {
    const void* data = nullptr;
    size_t bytes = 0;
};
HostBytes FrameSource(PlaneKind kind, const FrameInputs& in);
// The kinds every frame uploads at `precision` (EVERY_FRAME and MODULATION), in table order: the
// object ids only where the depth plane does not hold them (StoresObjectIdsInDepth).
std::vector<PlaneKind> PlanesUploadedEveryFrame(Precision precision);

// Whether the host converts the plane's FrameInputs data before uploading it: the INPUT_RGB,
// INPUT_NORMAL and INPUT_DEPTH planes in fp16.
bool ConvertedOnUpload(PlaneKind kind, Precision precision);
// Whether the depth plane holds the object ids (fp16): the plans bind it where a pass reads ids
// and neither upload nor store the ObjectId plane.
bool StoresObjectIdsInDepth(Precision precision);
// A colour input as fp16 storage holds it: rounded to the nearest half, finite values beyond
// ±FOVRT_HALF_SATURATION saturated; NaN and ±inf stay what they are, so that the shaders'
// sanitising counts them as in fp32.
float QuantizeInput(float v);
// A normal as fp16 storage holds it: its octahedral code (OctahedralCode), decoded as the shaders
// decode it (shaders/common/octahedral_normal.glsl); a zero or non-finite normal becomes 0.
ivec2 OctahedralCode(const vec3& n);
vec3 QuantizeNormal(const vec3& n);
// A pixel's depth and object id as fp16 storage holds them: one 32-bit code
// (shaders/common/depth_id.glsl), the depth truncated to 14 mantissa bits, the id modulo 511.
uint32_t DepthIdCode(float depth, uint32_t objectId);
// The depth and the id a code reads back as (kNoObject for the background's).
float DepthOfCode(uint32_t code);
uint32_t ObjectIdOfCode(uint32_t code);
// The upload of a ConvertedOnUpload plane, from `in`, into `out` (16-bit words): RGBA16F texels
// (alpha 0) rounded by QuantizeInput, octahedral codes, or depth + id codes (two words each, low
// first). The host uploads these; the C++ reference rounds its copy of the inputs by
// QuantizeInput, QuantizeNormal, DepthOfCode and ObjectIdOfCode.
void ConvertForUpload(PlaneKind kind, const FrameInputs& in, std::vector<uint16_t>& out);

}  // namespace fovrt
