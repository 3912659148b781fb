#include "denoise/planes.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include <glm/gtc/packing.hpp>

#include "core/check.h"
#include "denoise/gradient_strata.h"
#include "shaders/common/depth_id.glsl"
#include "shaders/common/octahedral_normal.glsl"
#include "shaders/shared_constants.h"

namespace fovrt {

namespace {

enum class Scope : uint8_t { Shared, PerChannel };
enum class Lifetime : uint8_t { Scratch, History, Staging };
enum class SizeRule : uint8_t {
    PixelsOf, InputRgb, InputNormal, InputDepth, Pixels, Stored, WindowStored, Strata, Fixed, SampleCounts, GradientSamples, Transfers
};
enum class Source : uint8_t { None, EveryFrame, WhenRead };

struct PlaneRow {
    const char* name;
    Scope scope;
    Lifetime lifetime;
    SizeRule size;
    size_t amount;  // bytes or scalars, by the rule
    Source source;
};

#define FOVRT_FRAME_ELEMENT(member) sizeof(*std::declval<const FrameInputs&>().member.data())

#define PIXELS_OF(member) SizeRule::PixelsOf, FOVRT_FRAME_ELEMENT(member)
#define INPUT_RGB(member) SizeRule::InputRgb, FOVRT_FRAME_ELEMENT(member)
#define INPUT_NORMAL(member) SizeRule::InputNormal, FOVRT_FRAME_ELEMENT(member)
#define INPUT_DEPTH(member) SizeRule::InputDepth, FOVRT_FRAME_ELEMENT(member)
#define PIXELS(bytes) SizeRule::Pixels, bytes
#define STORED(scalars) SizeRule::Stored, scalars
#define WINDOW_STORED(scalars) SizeRule::WindowStored, scalars
#define STRATA(bytes) SizeRule::Strata, bytes
#define FIXED(bytes) SizeRule::Fixed, bytes
#define SAMPLE_COUNTS SizeRule::SampleCounts, 0
#define GRADIENT_SAMPLES SizeRule::GradientSamples, 0
#define TRANSFERS SizeRule::Transfers, 0
#define EVERY_FRAME(member) Source::EveryFrame
#define MODULATION Source::EveryFrame
#define WHEN_READ(member) Source::WhenRead
#define NONE Source::None
#define FOVRT_PLANE_ROW(kind, name, scope, lifetime, size, source) \
    {name, Scope::scope, Lifetime::lifetime, size, source},
const PlaneRow kRows[] = {FOVRT_DENOISER_PLANES(FOVRT_PLANE_ROW)};
#undef FOVRT_PLANE_ROW
#undef PIXELS_OF
#undef INPUT_RGB
#undef INPUT_NORMAL
#undef INPUT_DEPTH
#undef PIXELS
#undef STORED
#undef WINDOW_STORED
#undef STRATA
#undef FIXED
#undef SAMPLE_COUNTS
#undef GRADIENT_SAMPLES
#undef TRANSFERS
#undef EVERY_FRAME
#undef MODULATION
#undef WHEN_READ
#undef NONE

const PlaneRow& Row(PlaneKind kind) { return kRows[size_t(kind)]; }

template <typename T>
HostBytes BytesOf(const Plane<T>& plane) { return {plane.data(), plane.bytes()}; }
template <typename T>
HostBytes BytesOf(const std::vector<T>& values) { return {values.data(), values.size() * sizeof(T)}; }

}  // namespace

const char* ChannelName(Channel channel) {
    switch (channel) {
        case Channel::Direct: return "direct";
        case Channel::Indirect: return "indirect";
        case Channel::Combined: return "combined";
        case Channel::None: break;
    }
    return "";
}

std::vector<Channel> FilteredChannels(const SvgfParams& params) {
    if (params.filterCombined) return {Channel::Combined};
    return {Channel::Direct, Channel::Indirect};
}

bool IsPerChannel(PlaneKind kind) { return Row(kind).scope == Scope::PerChannel; }
bool IsHistory(PlaneKind kind) { return Row(kind).lifetime == Lifetime::History; }
bool IsStaging(PlaneKind kind) { return Row(kind).lifetime == Lifetime::Staging; }
bool IsFixedSize(PlaneKind kind) { return Row(kind).size == SizeRule::Fixed; }
bool IsWindowed(PlaneKind kind) { return Row(kind).size == SizeRule::WindowStored; }
size_t ScalarBytes(PlaneKind kind, Precision precision) {
    const SizeRule rule = Row(kind).size;
    return rule == SizeRule::Stored || rule == SizeRule::WindowStored ? StoredScalarBytes(precision) : 4;
}
uint32_t ClearValue(PlaneKind kind, Precision precision) {
    constexpr uint32_t kFloatOne = 0x3F800000u;  // bit pattern of 1.0f
    if (kind == PlaneKind::ObjectId) return kNoObject;
    if (kind == PlaneKind::Normal && ConvertedOnUpload(kind, precision)) return 0x80008000u;  // (−32768, −32768)
    // Depth 0 with the background's id: nothing reprojects onto a reset.
    if (kind == PlaneKind::Depth && ConvertedOnUpload(kind, precision)) return DepthIdCode(0.0f, kNoObject);
    if (kind == PlaneKind::AsvgfAlpha || kind == PlaneKind::AsvgfLambda) return kFloatOne;
    return 0u;
}

BufferSide SideOf(HistorySide side, int parity) {
    if (side == HistorySide::None) return BufferSide::None;
    return (parity == 0) == (side == HistorySide::This) ? BufferSide::A : BufferSide::B;
}

BufferKey ResolveSide(const PlaneRef& ref, int parity) {
    FOVRT_CHECK((ref.side != HistorySide::None) == IsHistory(ref.id.kind));
    return {ref.id, SideOf(ref.side, parity)};
}

std::string PlaneName(const PlaneId& id) {
    FOVRT_CHECK(IsPerChannel(id.kind) == (id.channel != Channel::None));
    if (id.channel == Channel::None) return Row(id.kind).name;
    return std::string(ChannelName(id.channel)) + "." + Row(id.kind).name;
}

std::string BufferName(const BufferKey& key) {
    const std::string plane = PlaneName(key.id);
    if (key.side == BufferSide::None) return plane;
    return plane + (key.side == BufferSide::A ? ".A" : ".B");
}

size_t PlaneElementBytes(PlaneKind kind, Precision precision) {
    const PlaneRow& row = Row(kind);
    switch (row.size) {
        case SizeRule::PixelsOf:
        case SizeRule::InputDepth:
        case SizeRule::Pixels: return row.amount;
        case SizeRule::Stored:
        case SizeRule::WindowStored: return row.amount * StoredScalarBytes(precision);
        case SizeRule::InputRgb: return precision == Precision::Fp16 ? 4 * sizeof(uint16_t) : row.amount;
        case SizeRule::InputNormal: return precision == Precision::Fp16 ? 2 * sizeof(int16_t) : row.amount;
        default: return 0;
    }
}

size_t PlaneBytes(PlaneKind kind, const PlaneExtent& e) {
    const size_t pixels = size_t(e.width) * size_t(e.height);
    const ivec2 grid = StratumGridSize(e.width, e.height);
    const size_t strata = size_t(grid.x) * size_t(grid.y);
    const PlaneRow& row = Row(kind);
    switch (row.size) {
        case SizeRule::PixelsOf:
        case SizeRule::InputRgb:
        case SizeRule::InputNormal:
        case SizeRule::InputDepth:
        case SizeRule::Pixels:
        case SizeRule::Stored: return PlaneElementBytes(kind, e.precision) * pixels;
        case SizeRule::WindowStored:
            return PlaneElementBytes(kind, e.precision) *
                   (e.window.x > 0 ? size_t(e.window.x) * size_t(e.window.y) : pixels);
        case SizeRule::Strata: return row.amount * strata;
        case SizeRule::Fixed: return row.amount;
        case SizeRule::SampleCounts: return ((sizeof(uint16_t) * pixels + 3) / 4) * 4;
        case SizeRule::GradientSamples: return GradientSampleCapacity(e.width, e.height) * sizeof(GradientSample);
        case SizeRule::Transfers: return 0;
    }
    return 0;
}

HostBytes FrameSource(PlaneKind kind, const FrameInputs& in) {
#define EVERY_FRAME(member) return BytesOf(in.member);
#define MODULATION return BytesOf(in.Modulation());
#define WHEN_READ(member) return BytesOf(in.member);
#define NONE break;
#define FOVRT_PLANE_SOURCE(kind, name, scope, lifetime, size, source) \
    case PlaneKind::kind: source
    switch (kind) { FOVRT_DENOISER_PLANES(FOVRT_PLANE_SOURCE) }
#undef FOVRT_PLANE_SOURCE
#undef EVERY_FRAME
#undef MODULATION
#undef WHEN_READ
#undef NONE
    return {};
}

bool ConvertedOnUpload(PlaneKind kind, Precision precision) {
    const SizeRule rule = Row(kind).size;
    return (rule == SizeRule::InputRgb || rule == SizeRule::InputNormal || rule == SizeRule::InputDepth) &&
           precision == Precision::Fp16;
}

bool StoresObjectIdsInDepth(Precision precision) { return ConvertedOnUpload(PlaneKind::Depth, precision); }

uint32_t DepthIdCode(float depth, uint32_t objectId) { return glsl::depth_id_code(depth, objectId); }
float DepthOfCode(uint32_t code) { return glsl::depth_id_depth(code); }
uint32_t ObjectIdOfCode(uint32_t code) { return glsl::depth_id_object(code); }

namespace {
uint16_t InputHalf(float v) {
    constexpr float kMax = float(FOVRT_HALF_SATURATION);
    return glm::packHalf1x16(std::isfinite(v) ? std::clamp(v, -kMax, kMax) : v);
}
}  // namespace

float QuantizeInput(float v) { return glm::unpackHalf1x16(InputHalf(v)); }

// Cigolle et al. 2014: project onto the octahedron |x| + |y| + |z| = 1, fold the lower half over
// the diagonals, round to 16-bit signed integers (scale 32767).
ivec2 OctahedralCode(const vec3& n) {
    const float l1 = std::abs(n.x) + std::abs(n.y) + std::abs(n.z);
    if (!(l1 > 0.0f) || !std::isfinite(l1)) return {-32768, -32768};  // no normal
    vec2 p = vec2(n.x, n.y) / l1;
    if (n.z < 0.0f) p = (vec2(1.0f) - glm::abs(vec2(p.y, p.x))) * vec2(p.x >= 0.0f ? 1.0f : -1.0f, p.y >= 0.0f ? 1.0f : -1.0f);
    return ivec2(glm::round(glm::clamp(p, vec2(-1.0f), vec2(1.0f)) * 32767.0f));
}

vec3 QuantizeNormal(const vec3& n) { return glsl::octahedral_normal(OctahedralCode(n)); }

void ConvertForUpload(PlaneKind kind, const FrameInputs& in, std::vector<uint16_t>& out) {
    const SizeRule rule = Row(kind).size;
    FOVRT_CHECK(rule == SizeRule::InputRgb || rule == SizeRule::InputNormal || rule == SizeRule::InputDepth);
    if (rule == SizeRule::InputDepth) {
        FOVRT_CHECK(kind == PlaneKind::Depth);
        const size_t pixels = in.linearDepth.size();
        out.resize(2 * pixels);
        for (size_t i = 0; i < pixels; ++i) {
            const uint32_t code = DepthIdCode(in.linearDepth[i], in.objectId[i]);
            out[2 * i] = uint16_t(code & 0xFFFFu);
            out[2 * i + 1] = uint16_t(code >> 16);
        }
        return;
    }
    const HostBytes source = FrameSource(kind, in);
    const auto* values = static_cast<const vec3*>(source.data);
    const size_t pixels = source.bytes / sizeof(vec3);
    if (rule == SizeRule::InputNormal) {
        out.resize(2 * pixels);
        for (size_t i = 0; i < pixels; ++i) {
            const ivec2 code = OctahedralCode(values[i]);
            out[2 * i] = uint16_t(int16_t(code.x));
            out[2 * i + 1] = uint16_t(int16_t(code.y));
        }
        return;
    }
    out.resize(4 * pixels);
    for (size_t i = 0; i < pixels; ++i) {
        for (int c = 0; c < 3; ++c) out[4 * i + size_t(c)] = InputHalf(values[i][c]);
        out[4 * i + 3] = 0;
    }
}

std::vector<PlaneKind> PlanesUploadedEveryFrame(Precision precision) {
    std::vector<PlaneKind> kinds;
    for (size_t i = 0; i < std::size(kRows); ++i) {
        const PlaneKind kind = PlaneKind(i);
        if (kRows[i].source != Source::EveryFrame) continue;
        if (kind == PlaneKind::ObjectId && StoresObjectIdsInDepth(precision)) continue;  // in the depth codes
        kinds.push_back(kind);
    }
    return kinds;
}

}  // namespace fovrt
