#include "denoise/vulkan/svgf_family_vk.h"

#include <span>

#include "core/error.h"
#include "denoise/gradient_strata.h"
#include "denoise/reference/two_history_math.h"  // header-only: p of the debug view
#include "denoise/vulkan/stage_pipelines.h"
#include "denoise/vulkan/svgf_layout.h"

namespace fovrt {

// The shaders read fovrt::GradientSample as uploaded (std430: 3 ivec2 + 2 float).
static_assert(sizeof(GradientSample) == 32);

SvgfFamilyVulkanDenoiser::SvgfFamilyVulkanDenoiser(const DenoiserVariant& variant,
                                                   std::shared_ptr<VulkanContext> context,
                                                   const DenoiserParams& params)
    : variant_(variant), context_(std::move(context)), buffers_(std::string(variant.name)) {
    FOVRT_CHECK(context_ != nullptr && variant.family != DenoiserFamily::Rae);
    Configure(params);
    commands_ = CommandSlot(*context_);
}

void SvgfFamilyVulkanDenoiser::Configure(const DenoiserParams& params) {
    ValidateDenoiserParamRanges(params);
    if (params.precision == Precision::Fp16 && !context_->supports16BitStorage())
        Fail("--precision fp16: Vulkan device '{}' lacks storageBuffer16BitAccess", context_->deviceName());
    params_ = ParamsForVariant(variant_, params);
}

SvgfFamilyVulkanDenoiser::~SvgfFamilyVulkanDenoiser() = default;

void SvgfFamilyVulkanDenoiser::Reset() {
    needsClear_ = true;
    hasFrame_ = false;
}

void SvgfFamilyVulkanDenoiser::SetParams(const DenoiserParams& params) {
    Configure(params);
    prepared_.clear();
    pipelines_.clear();  // the descriptor sets die with them
    buffers_.Release();
    width_ = height_ = 0;  // the next Denoise() plans and allocates
    Reset();
}

void SvgfFamilyVulkanDenoiser::Allocate(int width, int height) {
    width_ = width;
    height_ = height;
    plan_ = BuildDenoiserPlan(variant_.name, params_, width, height);
    buffers_.Allocate(*context_, plan_);
    PrepareDispatches();
    uint32_t timed = 0;
    for (const PlannedPass& pass : plan_.passes) timed += pass.name.empty() ? 0 : 1;
    timestamps_ = TimestampPool(*context_, timed);
    parity_ = 0;
    needsClear_ = true;
    hasFrame_ = false;
}

// Pipelines once per distinct key (kept across resizes: keys do not depend on the size), then a
// descriptor set per dispatch and parity over this size's buffers.
void SvgfFamilyVulkanDenoiser::PrepareDispatches() {
    std::map<PipelineKey, std::pair<uint32_t, uint32_t>> uses;  // key → (dispatches, push bytes)
    for (const PlannedPass& pass : plan_.passes)
        for (const Command& command : pass.commands)
            if (const auto* d = std::get_if<DispatchCommand>(&command.op)) {
                auto& [count, pushBytes] = uses[d->pipeline];
                ++count;
                pushBytes = d->push.bytes;
            }
    if (pipelines_.empty())
        for (const auto& [key, use] : uses)
            pipelines_.emplace(key, MakeStagePipeline(*context_, key, use.second, 2 * use.first));
    else
        for (auto& [key, pipeline] : pipelines_) pipeline.ResetSets();

    preparedGeneration_ = buffers_.SharedGeneration();
    prepared_.assign(plan_.passes.size(), {});
    for (size_t p = 0; p < plan_.passes.size(); ++p) {
        const PlannedPass& pass = plan_.passes[p];
        prepared_[p].resize(pass.commands.size());
        for (size_t c = 0; c < pass.commands.size(); ++c) {
            const auto* d = std::get_if<DispatchCommand>(&pass.commands[c].op);
            if (!d) continue;
            ComputePipeline& pipeline = pipelines_.at(d->pipeline);
            PreparedDispatch& prepared = prepared_[p][c];
            prepared.pipeline = &pipeline;
            for (int parity = 0; parity < 2; ++parity) {
                std::vector<const Buffer*> slots(size_t(BindingCount(d->pipeline)), nullptr);
                for (const Binding& b : d->bindings) {
                    FOVRT_CHECK(b.slot >= 0 && size_t(b.slot) < slots.size() && !slots[size_t(b.slot)]);
                    slots[size_t(b.slot)] = &buffers_[ResolveSide(b.plane, parity)];
                }
                for (const Buffer* slot : slots)
                    if (!slot) Fail("{}: {} has an unbound slot", Name(), ShaderVariantName(d->pipeline));
                prepared.sets[size_t(parity)] = pipeline.MakeSet(slots);
            }
        }
    }
}

void SvgfFamilyVulkanDenoiser::Record(CommandRecorder& rec, const DispatchCommand& d, const PreparedDispatch& prepared,
                                      Frame& frame) {
    std::array<uint32_t, 16> push = d.push.words;
    auto valueOf = [&](FrameValue value) -> uint32_t {
        switch (value) {
            case FrameValue::HasPrevious: return frame.conditions.hasPrevious ? 1u : 0u;
            case FrameValue::GradientSampleCount: return frame.gradientSamples;
            case FrameValue::WindowOriginX: return uint32_t(frame.window.origin.x);
            case FrameValue::WindowOriginY: return uint32_t(frame.window.origin.y);
            case FrameValue::PrevWindowOriginX: return uint32_t(frame.prevWindow.origin.x);
            case FrameValue::PrevWindowOriginY: return uint32_t(frame.prevWindow.origin.y);
        }
        return 0u;
    };
    for (const auto& [word, value] : d.push.perFrame) push[word] = valueOf(value);
    const ComputePipeline& pipeline = *prepared.pipeline;
    const VkDescriptorSet set = prepared.sets[size_t(parity_)];
    uvec2 groups(0);
    switch (d.grid) {
        case Grid::Pixels: groups = DispatchGroups(width_, height_); break;
        case Grid::AtrousBlocks: groups = AtrousBlockGroups(width_, height_, d.step); break;
        case Grid::Strata: {
            const ivec2 grid = StratumGridSize(width_, height_);
            groups = DispatchGroups(grid.x, grid.y);
            break;
        }
        case Grid::GradientSamples:
            groups = uvec2((frame.gradientSamples + FOVRT_WORKGROUP_1D - 1) / FOVRT_WORKGROUP_1D, 1);
            break;
        case Grid::PixelList:
            rec.DispatchIndirect(pipeline, set, push.data(), d.push.bytes, buffers_[{d.listArgs, BufferSide::None}]);
            return;
    }
    rec.Dispatch(pipeline, set, push.data(), d.push.bytes, groups);
}

void SvgfFamilyVulkanDenoiser::Record(CommandRecorder& rec, const Command& command, const PreparedDispatch& prepared,
                                      Frame& frame) {
    auto buffer = [&](const PlaneRef& ref) -> Buffer& { return buffers_[ResolveSide(ref, parity_)]; };
    std::visit(
        [&](const auto& op) {
            using T = std::decay_t<decltype(op)>;
            if constexpr (std::is_same_v<T, DispatchCommand>) {
                Record(rec, op, prepared, frame);
            } else if constexpr (std::is_same_v<T, FillCommand>) {
                rec.Fill(buffer(op.plane), op.value);
            } else if constexpr (std::is_same_v<T, CopyCommand>) {
                rec.Copy(buffer(op.from), buffer(op.to), buffers_.Bytes(ResolveSide(op.from, parity_)));
            } else if constexpr (std::is_same_v<T, UploadCommand>) {
                const HostBytes source = FrameSource(op.to.id.kind, frame.inputs);
                if (ConvertedOnUpload(op.to.id.kind, params_.precision)) {  // the ring copies it at once
                    ConvertForUpload(op.to.id.kind, frame.inputs, halfInput_);
                    frame.transfers.Upload(halfInput_.data(), halfInput_.size() * sizeof(uint16_t), buffer(op.to));
                } else {
                    frame.transfers.Upload(source.data, source.bytes, buffer(op.to));
                }
            } else if constexpr (std::is_same_v<T, DownloadCommand>) {
                const Buffer& from = buffer(op.from);
                switch (op.from.id.kind) {
                    case PlaneKind::Output: frame.transfers.Download(from, frame.output.bytes(), frame.output.data()); break;
                    case PlaneKind::Stats: frame.transfers.Download(from, sizeof(frame.counters), frame.counters.data()); break;
                    default: Fail("{}: the host has no place for a download of {}", Name(), PlaneName(op.from.id));
                }
            } else if constexpr (std::is_same_v<T, ClearCommand>) {
                buffers_.RecordClear(rec, params_.precision);
            } else {
                static_assert(std::is_same_v<T, BarrierCommand>);
                rec.Barrier();
            }
        },
        command.op);
}

void SvgfFamilyVulkanDenoiser::Denoise(const FrameInputs& in, Plane<vec3>& output) {
    const int w = in.width(), h = in.height();
    if (w <= 0 || h <= 0) Fail("{}: empty FrameInputs", Name());
    if (w != width_ || h != height_) Allocate(w, h);
    // Another denoiser on the device grew a shared buffer since: the sets name the old one.
    if (buffers_.SharedGeneration() != preparedGeneration_) PrepareDispatches();
    buffers_.BeginFrame();
    if (in.cameraCut) needsClear_ = true;
    const size_t samples = variant_.needsGradientSamples ? in.gradientSamples.size() : 0;
    if (samples > GradientSampleCapacity(w, h))
        Fail("{}: {} gradient samples exceed the capacity {} (two per 3x3 stratum)", Name(), samples,
             GradientSampleCapacity(w, h));
    output.Resize(w, h);
    std::array<uint32_t, 2> counters{};
    CommandRecorder rec(*context_, commands_, &timestamps_);
    TransferRing transfers(rec, buffers_[{{PlaneKind::Staging, Channel::None}, BufferSide::None}]);
    const HistoryWindow window = FrameWeightedWindow(variant_, params_, in);
    Frame frame{in, {!needsClear_, samples > 0}, uint32_t(samples), transfers, output, counters, window,
                needsClear_ ? window : window_};

    for (size_t p = 0; p < plan_.passes.size(); ++p) {
        const PlannedPass& pass = plan_.passes[p];
        if (!Holds(pass.when, frame.conditions)) continue;
        if (!pass.name.empty()) rec.BeginPass(pass.name);
        for (size_t c = 0; c < pass.commands.size(); ++c)
            if (Holds(pass.commands[c].when, frame.conditions)) Record(rec, pass.commands[c], prepared_[p][c], frame);
        if (!pass.name.empty()) rec.EndPass();
    }
    transfers.Submit();  // the output and the sanitising counters land
    needsClear_ = false;
    stats_.nonFiniteSamples += counters[0];
    stats_.negativeSamples += counters[1];
    timings_ = PassTimings(timestamps_);
    parity_ ^= 1;
    window_ = window;
    hasFrame_ = true;
}

bool SvgfFamilyVulkanDenoiser::ReadDebugPlane(DebugViewId view, Plane<float>& out) {
    if (!hasFrame_) return false;
    const int lastParity = parity_ ^ 1;
    auto scalarBytes = [&](PlaneKind kind) { return ScalarBytes(kind, params_.precision); };
    const std::optional<PlaneRef> ref = DebugViewPlane(variant_, params_, view);
    if (view == DebugViewId::P && !ref) {
        // Not stored: the blend evaluates p from this frame's state, and so does this, with the
        // shader's formula (common/two_history.glsl, the one text both compile).
        if (!variant_.twoHistory) return false;
        auto floats = [&](PlaneKind kind, Channel ch) {
            const BufferKey key = ResolveSide({{kind, ch}, HistorySide::This}, lastParity);
            return buffers_.ReadFloats(*context_, key, scalarBytes(kind));
        };
        const std::vector<float> wu = floats(PlaneKind::Length, FilteredChannels(params_.svgf).front());
        const std::vector<float> ww = floats(PlaneKind::WWeight, Channel::None);
        const std::vector<float> s = floats(PlaneKind::PowerSums, Channel::None);
        FOVRT_CHECK(wu.size() == size_t(width_) * size_t(height_) && ww.size() == window_.Pixels() &&
                    s.size() == 3 * window_.Pixels());
        // Outside the window the blend keeps I_u: p = 1.
        out = WindowOverImage(width_, height_, window_, 1.0f, [&](size_t j) {
            const ivec2 p = window_.ImagePixel(j);
            const size_t i = size_t(p.y) * size_t(width_) + size_t(p.x);
            const vec3 powerSums(s[3 * j], s[3 * j + 1], s[3 * j + 2]);
            return TwoHistoryOptimalBlend(StoredTwoHistoryWeights(wu[i], ww[j], powerSums));
        });
        return true;
    }
    if (!ref) return false;
    const BufferKey key = ResolveSide(*ref, lastParity);
    const int components = DebugViewComponents(view);
    if (components == 1 && !IsWindowed(ref->id.kind)) {
        buffers_.ReadPlane(*context_, key, width_, height_, scalarBytes(ref->id.kind), out);
        return true;
    }
    // A colour history or the moments (reduced per pixel), or a windowed plane (0 outside its window).
    const std::vector<float> values = buffers_.ReadFloats(*context_, key, scalarBytes(ref->id.kind));
    const HistoryWindow held = IsWindowed(ref->id.kind) ? window_ : HistoryWindow::Whole(width_, height_);
    FOVRT_CHECK(values.size() == size_t(components) * held.Pixels());
    out = WindowOverImage(width_, height_, held, 0.0f, [&](size_t j) {
        return components == 1 ? values[j] : ReduceDebugPixel(view, &values[size_t(components) * j]);
    });
    return true;
}

std::vector<uint8_t> SvgfFamilyVulkanDenoiser::ReadBuffer(const std::string& name) {
    return buffers_.Read(*context_, name);
}

}  // namespace fovrt
