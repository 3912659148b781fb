#include "denoise/vulkan/svgf_vk.h"

#include <array>
#include <cstring>
#include <span>

#include "core/error.h"
#include "denoise/memory_plan.h"
#include "denoise/schedule.h"
#include "denoise/vulkan/svgf_atrous_vk.h"
#include "denoise/vulkan/svgf_layout.h"
#include "denoise/vulkan/svgf_texel_formats.h"

namespace fovrt {

namespace {
const char* Side(int parity) { return parity ? "B" : "A"; }
}  // namespace

SvgfVulkanDenoiser::SvgfVulkanDenoiser(std::string name, std::shared_ptr<VulkanContext> context,
                                       const DenoiserParams& params)
    : name_(std::move(name)), context_(std::move(context)), params_(params) {
    FOVRT_CHECK(context_ != nullptr);
    commands_ = CommandSlot(*context_);
    CreatePipelines();
}

void SvgfVulkanDenoiser::CreatePipelines() {
    const SvgfParams& p = params_.svgf;
    ValidateDenoiserParamRanges(params_);
    if (params_.precision == Precision::Fp16 && !context_->supports16BitStorage())
        Fail("--precision fp16: Vulkan device '{}' lacks storageBuffer16BitAccess", context_->deviceName());
    channels_ = SvgfChannels(p);
    const std::string suffix = params_.precision == Precision::Fp16 ? "_fp16" : "";
    const uint32_t sets = 4 * uint32_t(channels_.size()) + 2;
    // Direct and indirect in one dispatch (svgf_reproject_pair: the taps are found once per pixel).
    const bool pair = channels_.size() == 2;
    const uint32_t reprojectBindings = pair ? SVGF_REPROJECT_PAIR_BINDINGS : SVGF_REPROJECT_BINDINGS;
    const auto reprojectFormats = SvgfReprojectTexelFormats(params_.precision);
    const int feedback = FeedbackIteration(p, false);
    const bool atrousFeedback = feedback > 0;
    const uint32_t flags = (p.weightBySampleCount ? SVGF_REPROJECT_FLAG_WEIGHTED : 0u) |
                           (p.filterCombined ? SVGF_REPROJECT_FLAG_COMBINED : 0u) |
                           (atrousFeedback ? 0u : SVGF_REPROJECT_FLAG_WRITE_COLOR);
    reproject_ = ReprojectionPipelines(*context_, pair ? "svgf_reproject_pair" : "svgf_reproject", suffix,
                                       reprojectBindings, sizeof(SvgfReprojectPush), sets,
                                       std::span<const VkFormat>(reprojectFormats).first(reprojectBindings), flags);
    // Direct and indirect in one à-trous dispatch (svgf_atrous_pair); combined: one channel.
    stages_ = SvgfStagePipelines(*context_, int(channels_.size()), params_, sets,
                                 feedback);
    timestamps_ = TimestampPool(*context_, 8 + FOVRT_MAX_ATROUS_ITERATIONS);
}

SvgfVulkanDenoiser::~SvgfVulkanDenoiser() = default;

Buffer& SvgfVulkanDenoiser::Buf(const std::string& name) { return buffers_[name]; }

void SvgfVulkanDenoiser::Allocate(int width, int height) {
    width_ = width;
    height_ = height;
    buffers_.Allocate(*context_, PlanSvgfMemory(width, height, params_));  // its own params: tests set weighting directly
    BuildSets();
    parity_ = 0;
    needsClear_ = true;
    hasFrame_ = false;
}

void SvgfVulkanDenoiser::BuildSets() {
    stages_.guide.ResetSets();
    reproject_.main.ResetSets();
    stages_.moments.ResetSets();
    stages_.classify.ResetSets();
    stages_.atrous.ResetSets();
    stages_.modulate.ResetSets();
    const bool weighted = params_.svgf.weightBySampleCount;
    momentsSets_.assign(channels_.size(), {});
    classifySets_.assign(channels_.size(), {});
    for (int parity = 0; parity < 2; ++parity) guideSets_[size_t(parity)] = stages_.GuideSet(buffers_, Side(parity));
    for (int parity = 0; parity < 2; ++parity) {
        // One reprojection dispatch: channel 0 (direct, or combined: direct + indirect summed) at
        // the base bindings, indirect at the *2 bindings of svgf_reproject_pair.
        const std::string cur = Side(parity), prev = Side(parity ^ 1);
        std::array<const Buffer*, SVGF_REPROJECT_PAIR_BINDINGS> r{};
        BindReprojectionInputs(r, buffers_, cur, prev, channels_[0]);
        // Unused bindings (unweighted mode) point at a buffer of the plan that is never read.
        r[SVGF_REPROJECT_B_SAMPLE_COUNT] = &Buf(weighted ? "input.sampleCount" : "input.prevPixel");
        r[SVGF_REPROJECT_B_STATS] = &Buf("stats");
        const std::string weight = weighted ? ".weight." : ".length.";
        for (size_t c = 0; c < channels_.size(); ++c) {
            const std::string& ch = channels_[c];
            // Binding of channel 0, or its *2 twin for channel 1.
            auto b = [&](int first, int second) { return size_t(c == 0 ? first : second); };
            r[b(SVGF_REPROJECT_B_PREV_COLOR, SVGF_REPROJECT_B_PREV_COLOR2)] = &Buf(ch + ".color." + prev);
            r[b(SVGF_REPROJECT_B_PREV_MOMENTS, SVGF_REPROJECT_B_PREV_MOMENTS2)] = &Buf(ch + ".moments." + prev);
            r[b(SVGF_REPROJECT_B_PREV_LENGTH, SVGF_REPROJECT_B_PREV_LENGTH2)] = &Buf(ch + ".length." + prev);
            r[b(SVGF_REPROJECT_B_PREV_WEIGHT, SVGF_REPROJECT_B_PREV_WEIGHT2)] = &Buf(ch + weight + prev);
            r[b(SVGF_REPROJECT_B_CUR_COLOR, SVGF_REPROJECT_B_CUR_COLOR2)] = &Buf(ch + ".color." + cur);
            r[b(SVGF_REPROJECT_B_CUR_MOMENTS, SVGF_REPROJECT_B_CUR_MOMENTS2)] = &Buf(ch + ".moments." + cur);
            r[b(SVGF_REPROJECT_B_CUR_LENGTH, SVGF_REPROJECT_B_CUR_LENGTH2)] = &Buf(ch + ".length." + cur);
            r[b(SVGF_REPROJECT_B_CUR_WEIGHT, SVGF_REPROJECT_B_CUR_WEIGHT2)] = &Buf(ch + weight + cur);
            r[b(SVGF_REPROJECT_B_ILLUM_OUT, SVGF_REPROJECT_B_ILLUM_OUT2)] = &Buf(ch + ".illum0");
        }
        const size_t bindings = channels_.size() == 2 ? SVGF_REPROJECT_PAIR_BINDINGS : SVGF_REPROJECT_BINDINGS;
        reprojectSets_[size_t(parity)] = reproject_.main.MakeSet(std::span<const Buffer* const>(r).first(bindings));
    }
    for (size_t c = 0; c < channels_.size(); ++c) {
        const std::string& ch = channels_[c];
        for (int parity = 0; parity < 2; ++parity) {
            const std::string cur = Side(parity);
            momentsSets_[c][size_t(parity)] = stages_.MomentsSet(buffers_, ch, cur, ch + ".illum0", ch + ".illum1");
            classifySets_[c][size_t(parity)] = stages_.ClassifySet(buffers_, ch, cur);
        }
    }
    for (int parity = 0; parity < 2; ++parity)
        for (int pp = 0; pp < 2; ++pp) {
            // pp = 0: illum1 → illum0 (even iterations); pp = 1: illum0 → illum1.
            std::vector<AtrousChannel> a;
            for (const std::string& ch : channels_)
                a.push_back({&Buf(ch + (pp ? ".illum0" : ".illum1")), &Buf(ch + (pp ? ".illum1" : ".illum0")),
                             &Buf(ch + ".color." + Side(parity))});
            atrousSets_[size_t(parity)][size_t(pp)] =
                MakeAtrousSet(stages_.atrous, Buf("geometry.guide"), Buf("input.depthGradient"), a);
        }
    const int iterations = params_.svgf.atrousIterations;
    const std::string last = FilteredIlluminationPlane(iterations) ? ".illum1" : ".illum0";
    modulateSet_ = stages_.ModulateSet(buffers_, channels_[0] + last, channels_.back() + last);
}

void SvgfVulkanDenoiser::Reset() {
    needsClear_ = true;
    hasFrame_ = false;
}

void SvgfVulkanDenoiser::SetParams(const DenoiserParams& params) {
    buffers_.Release();  // descriptor sets refer to them; rebuilt with the new layout
    params_ = params;
    CreatePipelines();
    width_ = height_ = 0;  // next Denoise() allocates
    Reset();
}

void SvgfVulkanDenoiser::Denoise(const FrameInputs& in, Plane<vec3>& output) {
    const int w = in.width(), h = in.height();
    if (w <= 0 || h <= 0) Fail("svgf: empty FrameInputs");
    if (w != width_ || h != height_) Allocate(w, h);
    if (in.cameraCut) needsClear_ = true;
    const SvgfParams& p = params_.svgf;
    const size_t n = size_t(w) * size_t(h);
    const int iterations = p.atrousIterations;
    const std::string cur = Side(parity_);

    CommandRecorder rec(*context_, commands_, &timestamps_);
    Buffer& staging = Buf("staging");
    const bool hasPrev = !needsClear_;
    rec.BeginPass("upload");
    if (needsClear_) {
        buffers_.RecordClear(rec);  // Reset(): nothing reprojects on the next frame
        needsClear_ = false;
    }
    size_t off = buffers_.RecordUploadInputs(rec, in, cur);
    if (p.weightBySampleCount)
        off = rec.Upload(in.sampleCount.data(), 2 * n, staging, off, Buf("input.sampleCount"));
    rec.Barrier();
    rec.EndPass();

    stages_.RecordGuide(rec, guideSets_[size_t(parity_)], w, h);

    rec.BeginPass("reproject");
    const SvgfReprojectPush rp{ivec2(w, h), p.alphaColor, p.alphaMoments, hasPrev ? 1u : 0u};
    reproject_.Record(rec, reprojectSets_[size_t(parity_)], &rp, w, h, Buf(channels_[0] + ".spatialArgs"), hasPrev);
    rec.EndPass();

    std::vector<MomentsChannel> moments;
    for (size_t c = 0; c < channels_.size(); ++c) {
        const std::string& ch = channels_[c];
        moments.push_back({classifySets_[c][size_t(parity_)], &Buf(ch + ".spatialArgs"),
                           {{momentsSets_[c][size_t(parity_)], &Buf(ch + ".illum0"), &Buf(ch + ".illum1")}}});
    }
    stages_.RecordFilterMoments(rec, p, w, h, moments);

    for (int i = 0; i < iterations; ++i) {
        rec.BeginPass(fmt::format("atrous{}", i));
        const SvgfAtrousPush ap{ivec2(w, h), 1 << i, p.sigmaDepth, p.sigmaNormal, p.sigmaLuminance};
        rec.Dispatch(stages_.Atrous(i), atrousSets_[size_t(parity_)][size_t(i & 1)], &ap, sizeof(ap),
                     AtrousBlockGroups(w, h, 1 << i));
        rec.Barrier();
        rec.EndPass();
    }

    stages_.RecordModulate(rec, modulateSet_, w, h);

    rec.BeginPass("download");
    buffers_.RecordDownloadOutput(rec, off, n);
    rec.EndPass();
    rec.Submit();
    buffers_.FinishOutput(w, h, output, stats_);
    timings_ = PassTimings(timestamps_);
    parity_ ^= 1;
    hasFrame_ = true;
}

bool SvgfVulkanDenoiser::ReadDebugPlane(DebugViewId view, Plane<float>& out) {
    if (!hasFrame_) return false;
    // A plane of this frame's history side; every channel holds the same length (and weight).
    auto readHistory = [&](const char* plane) {
        buffers_.ReadPlane(*context_, channels_[0] + plane + LastWrittenSide(), width_, height_,
                           HistoryScalarBytes(params_.precision), out);
        return true;
    };
    switch (view) {
        case DebugViewId::HistoryLength:
            return readHistory(".length.");
        case DebugViewId::HistorySamples:  // W of svgf-weighted
            return params_.svgf.weightBySampleCount && readHistory(".weight.");
        case DebugViewId::Alpha:
        case DebugViewId::Lambda:
        case DebugViewId::P:
        case DebugViewId::Q:
            return false;  // views of the two-history family
    }
    return false;
}

std::vector<uint8_t> SvgfVulkanDenoiser::ReadBuffer(const std::string& name) {
    return buffers_.Read(*context_, name);
}

}  // namespace fovrt
