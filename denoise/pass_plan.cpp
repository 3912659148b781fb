#include "denoise/pass_plan.h"

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <set>

#include "core/check.h"
#include "core/error.h"
#include "denoise/rae_weights.h"
#include "denoise/svgf_family_plan.h"
#include "denoise/transient_pool.h"
#include "denoise/variants.h"

namespace fovrt {

namespace {

#define FOVRT_STAGE_SHADER_STEM(id, stem, list, pairList) stem,
const char* const kShaderStems[] = {FOVRT_STAGE_SHADERS(FOVRT_STAGE_SHADER_STEM)};
#undef FOVRT_STAGE_SHADER_STEM
#define FOVRT_STAGE_SHADER_COUNTS(id, stem, list, pairList) {FOVRT_BINDING_COUNT(list), FOVRT_BINDING_COUNT(pairList)},
const std::pair<int, int> kBindingCounts[] = {FOVRT_STAGE_SHADERS(FOVRT_STAGE_SHADER_COUNTS)};
#undef FOVRT_STAGE_SHADER_COUNTS

// Every plane a command names, with the history side it names.
template <typename F>
void ForEachPlaneRef(const Command& command, F&& f) {
    std::visit(
        [&](const auto& op) {
            using T = std::decay_t<decltype(op)>;
            if constexpr (std::is_same_v<T, DispatchCommand>) {
                for (const Binding& b : op.bindings) f(b.plane);
                if (op.grid == Grid::PixelList) f(PlaneRef{op.listArgs, HistorySide::None});
            } else if constexpr (std::is_same_v<T, FillCommand>) {
                f(op.plane);
            } else if constexpr (std::is_same_v<T, CopyCommand>) {
                f(op.from);
                f(op.to);
            } else if constexpr (std::is_same_v<T, UploadCommand> || std::is_same_v<T, DownloadCommand>) {
                f(PlaneRef{{PlaneKind::Staging, Channel::None}, HistorySide::None});
                if constexpr (std::is_same_v<T, UploadCommand>) f(op.to);
                else f(op.from);
            }
        },
        command.op);
}

// The memory plan: every plane a command names (a history: both sides), in plane-table order,
// sized by its row (the staging ring by the frame's transfers, up to `ringBytes`), marked when the
// host reads it after the frame; then placed: permanent planes in buffers of their own, the others
// in the transient pool.
void DeriveMemory(DenoiserPlan& plan, const PlaneExtent& extent, size_t ringBytes,
                  const std::set<BufferKey>& readAfterFrame) {
    std::set<BufferKey> keys;
    // The bytes the frame moves through the staging ring, each transfer 16-byte aligned: when
    // they fit, one submit carries the frame, as without a ring.
    size_t transfers = 0;
    bool uploaded = false, downloaded = false, barrierSinceUpload = true;
    for (const PlannedPass& pass : plan.passes)
        for (const Command& command : pass.commands) {
            if (std::holds_alternative<BarrierCommand>(command.op) && pass.when == When::Always &&
                command.when == When::Always)
                barrierSinceUpload = true;
            ForEachPlaneRef(command, [&](const PlaneRef& ref) {
                if (IsHistory(ref.id.kind)) {
                    keys.insert({ref.id, BufferSide::A});
                    keys.insert({ref.id, BufferSide::B});
                } else {
                    keys.insert({ref.id, BufferSide::None});
                }
            });
            // Every upload before the first download, a barrier between them: the ring may flush
            // between any two transfers, and a download must read what the frame computed.
            if (const auto* up = std::get_if<UploadCommand>(&command.op)) {
                FOVRT_CHECK(!downloaded);
                transfers += StagingAlign(PlaneBytes(up->to.id.kind, extent));
                uploaded = true;
                barrierSinceUpload = false;
            }
            if (const auto* down = std::get_if<DownloadCommand>(&command.op)) {
                FOVRT_CHECK(barrierSinceUpload || !uploaded);
                transfers += StagingAlign(PlaneBytes(down->from.id.kind, extent));
                downloaded = true;
            }
        }
    for (const BufferKey& key : keys) {
        const PlaneKind kind = key.id.kind;
        const size_t planeBytes = PlaneBytes(kind, extent);
        const size_t bytes = IsStaging(kind) ? std::min(transfers, ringBytes) : planeBytes;
        plan.planes.push_back({key, bytes, 0, readAfterFrame.count(key) > 0});
    }
    PlaceInTransientPool(plan);
}

// The non-history planes the host reads after a frame: what it downloads, what a debug view of
// the variant reads (histories are permanent anyway).
std::set<BufferKey> ReadAfterFrame(const DenoiserVariant& v, const DenoiserParams& p, const DenoiserPlan& plan) {
    std::set<BufferKey> read;
    for (const PlannedPass& pass : plan.passes)
        for (const Command& command : pass.commands)
            if (const auto* down = std::get_if<DownloadCommand>(&command.op)) read.insert({down->from.id, BufferSide::None});
    for (const DebugView& row : DebugViewTable())
        if (const std::optional<PlaneRef> ref = DebugViewPlane(v, p, row.id); ref && !IsHistory(ref->id.kind))
            read.insert({ref->id, BufferSide::None});
    return read;
}

// The byte model of one pass from its commands (steady state: what runs after a reset only is
// left out; fixed-size planes move ~0 bytes per pixel).
class UseCounter {
  public:
    UseCounter(const PlaneExtent& e, std::vector<PlaneUse>& uses)
        : extent_(e), pixels_(double(e.width) * double(e.height)), uses_(uses) {}

    void Count(const Command& command) {
        if (command.when == When::NoPrevious) return;
        std::visit([&](const auto& op) { Count(op); }, command.op);
    }

  private:
    void Add(const PlaneRef& p, Access access, double times, Coverage coverage, double fixedBytes = 0.0) {
        if (IsFixedSize(p.id.kind)) return;
        const double planeBytes = double(PlaneBytes(p.id.kind, extent_)) / pixels_;
        uses_.push_back({PlaneName(p.id), access, times, coverage, planeBytes, fixedBytes});
    }
    void Count(const DispatchCommand& d) {
        for (const Binding& b : d.bindings) {
            const Coverage c = d.grid == Grid::PixelList && b.coverage == Coverage::EveryPixel ? d.listCoverage : b.coverage;
            if (b.access == Access::Read || b.access == Access::ReadWrite)
                Add(b.plane, Access::Read, b.share, c, b.placeholderBytesPerPixel);
            if (b.access == Access::Write || b.access == Access::ReadWrite) Add(b.plane, Access::Write, b.share, c);
        }
    }
    void Count(const FillCommand& f) { Add(f.plane, Access::Write, 1.0, Coverage::EveryPixel); }
    void Count(const CopyCommand& c) {
        Add(c.from, Access::Read, 1.0, Coverage::EveryPixel);
        Add(c.to, Access::Write, 1.0, Coverage::EveryPixel);
    }
    // Staging → device: the staging copy is read, the device plane written.
    void Count(const UploadCommand& u) { Add(u.to, Access::Write, 2.0, u.coverage); }
    // Device → staging: the device plane read, the staging copy written.
    void Count(const DownloadCommand& d) {
        Add(d.from, Access::Read, 1.0, Coverage::EveryPixel);
        Add(d.from, Access::Write, 1.0, Coverage::EveryPixel);
    }
    void Count(const ClearCommand&) {}
    void Count(const BarrierCommand&) {}

    PlaneExtent extent_;
    double pixels_;
    std::vector<PlaneUse>& uses_;
};

DenoiserPlan PlanSvgfFamilyDenoiser(const DenoiserVariant& v, const DenoiserParams& p, int width, int height) {
    DenoiserPlan plan;
    plan.passes = PlanSvgfFamily(v, p, width, height);
    const PlaneExtent extent{width, height, p.precision, WeightedWindowSize(width, height, WeightedWindowFraction(v, p))};
    DeriveMemory(plan, extent, p.transferRingBytes, ReadAfterFrame(v, p, plan));
    for (PlannedPass& pass : plan.passes) {
        if (pass.when == When::NoPrevious) continue;
        UseCounter counter(extent, pass.uses);
        for (const Command& command : pass.commands) counter.Count(command);
    }
    return plan;
}

// The recurrent autoencoder (denoise/rae_weights.h; its own host, denoise/vulkan/rae_vk.h):
// features on the host, the network's encoder (recurrent blocks: the previous hidden side read,
// the other written) and decoder (reading the hidden states as skips) on the device, remodulation
// on the host. Its buffers are the slots of its tensor layout, named there. Every activation
// counts once per pass that writes or reads it (the byte model's convention; a conv's 3×3 taps
// hit cache).
DenoiserPlan PlanRae(int width, int height, const DenoiserParams& params) {
    DenoiserPlan plan;
    plan.buffers = PlanRaeMemory(width, height, params);
    const double pixels = double(width) * double(height);
    std::vector<PlannedPass>& passes = plan.passes;
    auto pass = [&](const char* name) { passes.push_back({name, When::Always, "", {}, {}, {}}); };
    auto use = [&](const BufferPlan& b, Access access, double times = 1.0) {
        const std::string name = b.name.rfind("rae.hidden", 0) == 0 ? b.name.substr(0, b.name.rfind('.')) : b.name;
        passes.back().uses.push_back({name, access, times, Coverage::EveryPixel, double(b.bytes) / pixels, 0.0});
    };
    auto buffer = [&](const char* name) -> const BufferPlan& {
        for (const BufferPlan& b : plan.buffers)
            if (b.name == name) return b;
        Fail("rae plan: no buffer '{}'", name);
    };
    auto starts = [](const std::string& n, const char* p) { return n.rfind(p, 0) == 0; };
    auto hiddenA = [&](const BufferPlan& b) { return starts(b.name, "rae.hidden") && b.name.back() == 'A'; };
    pass("rae_features");
    use(buffer("rae.input"), Access::Write);
    pass("upload");
    use(buffer("rae.input"), Access::Write, 2.0);
    pass("rae_encoder");
    use(buffer("rae.input"), Access::Read);
    use(buffer("rae.weights"), Access::Read);
    for (const BufferPlan& b : plan.buffers) {
        if (starts(b.name, "rae.enc") || starts(b.name, "rae.bottleneck")) {
            use(b, Access::Write);
            use(b, Access::Read);
        }
        if (hiddenA(b)) {
            use(b, Access::Read);
            use(b, Access::Write);
        }
    }
    pass("rae_decoder");
    use(buffer("rae.weights"), Access::Read);
    use(buffer("rae.output"), Access::Write);
    for (const BufferPlan& b : plan.buffers) {
        if (starts(b.name, "rae.dec")) {
            use(b, Access::Write);
            use(b, Access::Read);
        }
        if (hiddenA(b)) use(b, Access::Read);
    }
    pass("download");
    use(buffer("rae.output"), Access::Read, 2.0);
    pass("rae_remodulate");
    use(buffer("rae.output"), Access::Read);
    return plan;
}

}  // namespace

bool Holds(When when, const FrameConditions& frame) {
    switch (when) {
        case When::Always: return true;
        case When::HasPrevious: return frame.hasPrevious;
        case When::NoPrevious: return !frame.hasPrevious;
        case When::GradientSamples: return frame.gradientSamples;
    }
    return true;
}

Specialization Specialization::Of(std::initializer_list<std::pair<int, int32_t>> idValues) {
    Specialization s;
    s.values.fill(-1);
    for (const auto& [id, value] : idValues) {
        FOVRT_CHECK(id >= 0 && size_t(id) < s.values.size());
        s.values[size_t(id)] = value;
        s.count = uint8_t(std::max<int>(s.count, id + 1));
    }
    for (size_t i = s.count; i < s.values.size(); ++i) s.values[i] = 0;  // unused: equal keys compare equal
    return s;
}

std::string ShaderVariantName(const PipelineKey& key) {
    std::string name = kShaderStems[size_t(key.shader)];
    if (key.pair) name += "_pair";
    if (key.step1) name += "_step1";
    if (key.box) name += "_box";
    if (key.fp16) name += "_fp16";
    return name;
}

int BindingCount(const PipelineKey& key) {
    const auto& [one, pair] = kBindingCounts[size_t(key.shader)];
    return key.pair ? pair : one;
}

DenoiserPlan BuildDenoiserPlan(std::string_view name, const DenoiserParams& params, int width, int height) {
    const DenoiserVariant& v = FindDenoiserVariant(name);
    if (width <= 0 || height <= 0) Fail("denoiser plan: invalid size {}x{}", width, height);
    // auto is resolved against a device first (ResolvePrecision): a plan has one storage.
    if (params.precision == Precision::Auto) Fail("denoiser plan of {}: denoise.precision auto is not resolved", name);
    const DenoiserParams p = ParamsForVariant(v, params);
    if (v.family == DenoiserFamily::Rae) return PlanRae(width, height, p);
    return PlanSvgfFamilyDenoiser(v, p, width, height);
}

float WeightedWindowFraction(const DenoiserVariant& variant, const DenoiserParams& params) {
    return variant.twoHistory ? params.twoHistory.window : 1.0f;
}

HistoryWindow FrameWeightedWindow(const DenoiserVariant& variant, const DenoiserParams& params,
                                  const FrameInputs& frame) {
    return WeightedWindowAt(frame.width(), frame.height(), WeightedWindowFraction(variant, params), frame.gazePixel);
}

std::optional<PlaneRef> DebugViewPlane(const DenoiserVariant& v, const DenoiserParams& params, DebugViewId view) {
    if (v.family == DenoiserFamily::Rae) return std::nullopt;
    const Channel first = FilteredChannels(params.svgf).front();
    switch (view) {
        case DebugViewId::HistoryLength:  // W_u: every channel's length holds it
            return PlaneRef{{PlaneKind::Length, first}, HistorySide::This};
        case DebugViewId::HistorySamples:  // W of svgf-weighted, W_w of two-history
            if (v.weightBySampleCount) return PlaneRef{{PlaneKind::Weight, first}, HistorySide::This};
            if (v.twoHistory) return PlaneRef{{PlaneKind::WWeight, Channel::None}, HistorySide::This};
            return std::nullopt;
        case DebugViewId::Alpha:  // A-SVGF's α; the anti-lag variants keep their factor a in its plane
        case DebugViewId::Antilag:
            if (v.asvgfGradient && v.antilag == (view == DebugViewId::Antilag)) return PlaneRef{{PlaneKind::AsvgfAlpha, Channel::None}, HistorySide::None};
            return std::nullopt;
        case DebugViewId::Lambda:
            if (v.asvgfGradient) return PlaneRef{{PlaneKind::AsvgfLambda, Channel::None}, HistorySide::None};
            return std::nullopt;
        case DebugViewId::Q:
            if (v.twoHistory) return PlaneRef{BlendQPlane(v), HistorySide::None};
            return std::nullopt;
        case DebugViewId::P:  // the hysteresis variants' held choice; else evaluated from W_u, W_w and S
            if (v.hystereticChoice) return PlaneRef{{PlaneKind::Choice, Channel::None}, HistorySide::This};
            return std::nullopt;
        case DebugViewId::T:  // from P and Q (Denoiser::ReadDebugView)
            return std::nullopt;
        case DebugViewId::HistoryU:  // the first channel's two colour histories and its moments
        case DebugViewId::HistoryW:
        case DebugViewId::Variance: {
            if (!v.twoHistory) return std::nullopt;
            const PlaneKind kind = view == DebugViewId::HistoryU   ? PlaneKind::Color
                                   : view == DebugViewId::HistoryW ? PlaneKind::WColor
                                                                   : PlaneKind::Moments;
            return PlaneRef{{kind, first}, HistorySide::This};
        }
        case DebugViewId::StableLum:
            if (v.stabilize) return PlaneRef{{PlaneKind::StableLum, first}, HistorySide::This};
            return std::nullopt;
    }
    return std::nullopt;
}

}  // namespace fovrt
