#include "denoise/planes.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include <glm/gtc/packing.hpp>

#include "core/check.h"
#include "denoise/gradient_strata.h"
#include "shaders/shared_constants.h"

namespace fovrt {

namespace {

enum class Scope : uint8_t { Shared, PerChannel };
enum class Lifetime : uint8_t { Scratch, History, Staging };
enum class SizeRule : uint8_t {
    PixelsOf, InputRgb, Pixels, Stored, Strata, Fixed, SampleCounts, GradientSamples, Transfers
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
#define PIXELS(bytes) SizeRule::Pixels, bytes
#define STORED(scalars) SizeRule::Stored, scalars
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
#undef PIXELS
#undef STORED
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
bool ConvertedOnUpload(PlaneKind kind, Precision precision) {
    return Row(kind).size == SizeRule::InputRgb && precision == Precision::Fp16;
}

namespace {
uint16_t InputHalf(float v) {
    constexpr float kMax = float(FOVRT_HALF_SATURATION);
    return glm::packHalf1x16(std::isfinite(v) ? std::clamp(v, -kMax, kMax) : v);
}
}  // namespace

float QuantizeInput(float v) { return glm::unpackHalf1x16(InputHalf(v)); }

void StoreInputRgb(const vec3* rgb, size_t pixels, std::vector<uint16_t>& rgba) {
    rgba.resize(4 * pixels);
    for (size_t i = 0; i < pixels; ++i) {
        for (int c = 0; c < 3; ++c) rgba[4 * i + size_t(c)] = InputHalf(rgb[i][c]);
        rgba[4 * i + 3] = 0;
    }
}

size_t ScalarBytes(PlaneKind kind, Precision precision) {
    return Row(kind).size == SizeRule::Stored ? StoredScalarBytes(precision) : 4;
}
uint32_t ClearValue(PlaneKind kind) {
    constexpr uint32_t kFloatOne = 0x3F800000u;  // bit pattern of 1.0f
    if (kind == PlaneKind::ObjectId) return kNoObject;
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
        case SizeRule::Pixels: return row.amount;
        case SizeRule::Stored: return row.amount * StoredScalarBytes(precision);
        case SizeRule::InputRgb: return precision == Precision::Fp16 ? 4 * sizeof(uint16_t) : row.amount;
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
        case SizeRule::Pixels:
        case SizeRule::Stored: return PlaneElementBytes(kind, e.precision) * pixels;
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

const std::vector<PlaneKind>& PlanesUploadedEveryFrame() {
    static const std::vector<PlaneKind> kinds = [] {
        std::vector<PlaneKind> k;
        for (size_t i = 0; i < std::size(kRows); ++i)
            if (kRows[i].source == Source::EveryFrame) k.push_back(PlaneKind(i));
        return k;
    }();
    return kinds;
}

}  // namespace fovrt
