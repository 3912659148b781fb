#include "denoise/vulkan/two_history_vk.h"

#include <fmt/format.h>

#include <array>
#include <cstring>
#include <span>

#include "core/error.h"
#include "denoise/memory_plan.h"
#include "denoise/reference/two_history_math.h"  // header-only: p of the debug view
#include "denoise/schedule.h"
#include "denoise/vulkan/svgf_layout.h"
#include "denoise/vulkan/svgf_atrous_vk.h"
#include "denoise/vulkan/svgf_texel_formats.h"
#include "shaders/common/two_history_constants.glsl"

namespace fovrt {

// two_history_reproject binds colour, geometry and motion at svgf_reproject's slots 0–11: both
// lists begin with REPROJECT_INPUT_BINDINGS (shaders/bindings/reprojection_inputs.h), so
// BindReprojectionInputs serves both.


namespace {

const char* Side(int parity) { return parity ? "B" : "A"; }

// The shaders read fovrt::GradientSample as uploaded (std430: 3 ivec2 + 2 float).
static_assert(sizeof(GradientSample) == 32);

constexpr uint32_t kFloatOne = 0x3F800000u;  // bit pattern of 1.0f, for vkCmdFillBuffer

}  // namespace

TwoHistoryVulkanDenoiser::TwoHistoryVulkanDenoiser(const DenoiserVariant& variant,
                                                   std::shared_ptr<VulkanContext> context,
                                                   const DenoiserParams& params)
    : variant_(variant), context_(std::move(context)), params_(params) {
    FOVRT_CHECK(context_ != nullptr);
    commands_ = CommandSlot(*context_);
    buffers_ = DenoiserBuffers(Name());
    ValidateDenoiserParamRanges(params_);
    params_.svgf.weightBySampleCount = false;  // the weighted history is this family's own
    if (params_.precision == Precision::Fp16 && !context_->supports16BitStorage())
        Fail("--precision fp16: Vulkan device '{}' lacks storageBuffer16BitAccess",
             context_->deviceName());
    two_ = variant_.twoHistory;
    asvgf_ = variant_.asvgfGradient;
    channels_ = SvgfChannels(params_.svgf);
    const std::string sfx = params_.precision == Precision::Fp16 ? "_fp16" : "";
    constexpr uint32_t kSets = 16;
    // Direct and indirect in one dispatch (two_history_reproject_pair: taps and per-pixel state once).
    const bool pair = channels_.size() == 2;
    const uint32_t reprojectBindings = pair ? TH_REPROJECT_PAIR_BINDINGS : TH_REPROJECT_BINDINGS;
    const auto reprojectFormats = TwoHistoryReprojectTexelFormats(params_.precision);
    const int feedback = FeedbackIteration(params_.svgf, two_);
    uint32_t flags = 0;
    if (two_) flags |= TH_REPROJECT_FLAG_TWO_HISTORY;
    if (variant_.emaGradient) flags |= TH_REPROJECT_FLAG_GRADIENT;
    if (!pair) flags |= TH_REPROJECT_FLAG_COMBINED;
    if (asvgf_) flags |= TH_REPROJECT_FLAG_ALPHA_MAP;
    if (feedback == 0) flags |= TH_REPROJECT_FLAG_WRITE_COLOR;
    reproject_ = ReprojectionPipelines(*context_, pair ? "two_history_reproject_pair" : "two_history_reproject", sfx,
                                       reprojectBindings, sizeof(TwoHistoryReprojectPush), kSets,
                                       std::span<const VkFormat>(reprojectFormats).first(reprojectBindings), flags);
    // Both channels per dispatch (svgf_atrous_pair); combined: one channel, and iteration 0 of
    // the two-history variants filters I_u and I_w of it as a pair.
    // Iteration 0 (step 1) runs the _step1 variants: stages_.atrousStep1 with stages_.atrous's sets, and
    // atrousPair_, which only iteration 0 uses.
    stages_ = SvgfStagePipelines(*context_, int(channels_.size()), params_, kSets, feedback);
    if (two_ && channels_.size() == 1)
        atrousPair_ = MakeAtrousPipeline(*context_, 2, params_, kSets, true, feedback == 1);
    const auto edgeStopping = EdgeStoppingSpecialization(params_.svgf);
    if (two_) {
        gradient_ = ComputePipeline(*context_, "two_history_gradient" + sfx, TH_GRADIENT_BINDINGS,
                                    sizeof(TwoHistoryGradientPush), kSets, GradientTexelFormats(params_.precision),
                                    edgeStopping);
        blend_ = ComputePipeline(*context_, "two_history_blend" + sfx, TH_BLEND_BINDINGS,
                                 sizeof(ImageSizePush), kSets, BlendTexelFormats(params_.precision));
    }
    if (asvgf_) {
        claim_ = ComputePipeline(*context_, "asvgf_gradient_claim" + sfx, ASVGF_CLAIM_BINDINGS,
                                 sizeof(AsvgfSamplesPush), kSets);
        gather_ = ComputePipeline(*context_, "asvgf_gradient_gather" + sfx, ASVGF_GATHER_BINDINGS,
                                  sizeof(AsvgfSamplesPush), kSets, GradientGatherTexelFormats());
        stratumSigma_ = ComputePipeline(*context_, "asvgf_stratum_sigma" + sfx, ASVGF_SIGMA_BINDINGS,
                                        sizeof(AsvgfSigmaPush), 1, StratumSigmaTexelFormats());
        gradAtrous_ = ComputePipeline(*context_, "asvgf_gradient_atrous" + sfx,
                                      ASVGF_ATROUS_BINDINGS, sizeof(AsvgfAtrousPush), kSets,
                                      GradientAtrousTexelFormats(), edgeStopping);
        alpha_ = ComputePipeline(*context_, "asvgf_alpha" + sfx, ASVGF_ALPHA_BINDINGS,
                                 sizeof(AsvgfAlphaPush), kSets, AlphaTexelFormats());
    }
    timestamps_ = TimestampPool(*context_, 16 + FOVRT_MAX_ATROUS_ITERATIONS);
}

TwoHistoryVulkanDenoiser::~TwoHistoryVulkanDenoiser() = default;

Buffer& TwoHistoryVulkanDenoiser::Buf(const std::string& name) { return buffers_[name]; }

void TwoHistoryVulkanDenoiser::Allocate(int width, int height) {
    width_ = width;
    height_ = height;
    grid_ = StratumGridSize(width, height);
    buffers_.Allocate(*context_, PlanDenoiserMemory(Name(), width, height, params_));
    BuildSets();
    parity_ = 0;
    needsClear_ = true;
    hasFrame_ = false;
}

void TwoHistoryVulkanDenoiser::BuildSets() {
    for (ComputePipeline* p : {&stages_.guide, &stages_.classify, &reproject_.main, &stages_.moments, &stages_.atrous,
                               &atrousPair_, &stages_.modulate, &gradient_, &blend_, &claim_, &gather_,
                               &stratumSigma_, &gradAtrous_, &alpha_})
        if (p->handle() != VK_NULL_HANDLE) p->ResetSets();
    const size_t nch = channels_.size();
    const std::string& ch0 = channels_[0];
    const std::string& ch1 = channels_.back();
    const int iterations = params_.svgf.atrousIterations;
    momentsU_.assign(nch, {});
    classifySets_.assign(nch, {});
    momentsW_.assign(nch, {});
    blendSets_.assign(nch, {});
    for (int parity = 0; parity < 2; ++parity) {
        const std::string cur = Side(parity), prev = Side(parity ^ 1);
        const size_t pi = size_t(parity);
        // Bindings a variant does not use point at plan buffers that are never accessed.
        const Buffer* dummyIn = &Buf("input.prevPixel");
        const Buffer* dummyOut = &Buf("output");
        auto two = [&](const std::string& name) { return two_ ? &Buf(name) : dummyIn; };
        auto twoOut = [&](const std::string& name) { return two_ ? &Buf(name) : dummyOut; };
        // g exists for two-history only (two-history-asvgf takes q from A-SVGF).
        const bool withGradient = variant_.emaGradient;

        guideSets_[pi] = stages_.GuideSet(buffers_, cur);

        // Channel 0 (direct, or combined) at the base bindings; the pair's indirect at
        // COLOR_IN2, PREV_IU_OTHER and the *2 bindings.
        std::array<const Buffer*, TH_REPROJECT_PAIR_BINDINGS> r{};
        BindReprojectionInputs(r, buffers_, cur, prev, ch0);  // slots 0–11, as svgf_reproject
        r[TH_REPROJECT_B_SAMPLE_COUNT] = two("input.sampleCount");
        r[TH_REPROJECT_B_ALPHA] = asvgf_ ? &Buf("asvgf.alpha") : dummyIn;
        r[TH_REPROJECT_B_PREV_IU] = &Buf(ch0 + ".color." + prev);
        r[TH_REPROJECT_B_PREV_IU_OTHER] = &Buf(ch1 + ".color." + prev);  // unused when combined
        r[TH_REPROJECT_B_PREV_WW] = two("wweight." + prev);
        r[TH_REPROJECT_B_PREV_S] = two("powerSums." + prev);
        r[TH_REPROJECT_B_PREV_G] = withGradient ? &Buf("gradient." + prev) : dummyIn;
        r[TH_REPROJECT_B_CUR_WW] = twoOut("wweight." + cur);
        r[TH_REPROJECT_B_CUR_S] = twoOut("powerSums." + cur);
        r[TH_REPROJECT_B_CUR_G] = withGradient ? &Buf("gradient." + cur) : dummyOut;
        r[TH_REPROJECT_B_STATS] = &Buf("stats");
        for (size_t c = 0; c < nch; ++c) {
            const std::string& ch = channels_[c];
            auto b = [&](int base, int second) { return size_t(c == 0 ? base : second); };
            r[b(TH_REPROJECT_B_PREV_IW, TH_REPROJECT_B_PREV_IW2)] = two(ch + ".wcolor." + prev);
            r[b(TH_REPROJECT_B_PREV_M, TH_REPROJECT_B_PREV_M2)] = &Buf(ch + ".moments." + prev);
            r[b(TH_REPROJECT_B_PREV_WU, TH_REPROJECT_B_PREV_WU2)] = &Buf(ch + ".length." + prev);
            r[b(TH_REPROJECT_B_CUR_IU, TH_REPROJECT_B_CUR_IU2)] = &Buf(ch + ".color." + cur);
            r[b(TH_REPROJECT_B_CUR_IW, TH_REPROJECT_B_CUR_IW2)] = twoOut(ch + ".wcolor." + cur);
            r[b(TH_REPROJECT_B_CUR_M, TH_REPROJECT_B_CUR_M2)] = &Buf(ch + ".moments." + cur);
            r[b(TH_REPROJECT_B_CUR_WU, TH_REPROJECT_B_CUR_WU2)] = &Buf(ch + ".length." + cur);
            r[b(TH_REPROJECT_B_ILLUM_U, TH_REPROJECT_B_ILLUM_U2)] = &Buf(ch + ".illum0");
            r[b(TH_REPROJECT_B_ILLUM_W, TH_REPROJECT_B_ILLUM_W2)] = twoOut(ch + ".willum0");
        }
        const size_t reprojectBindings = nch == 2 ? TH_REPROJECT_PAIR_BINDINGS : TH_REPROJECT_BINDINGS;
        reprojectSets_[pi] = reproject_.main.MakeSet(std::span<const Buffer* const>(r).first(reprojectBindings));

        for (size_t c = 0; c < nch; ++c) {
            const std::string& ch = channels_[c];
            momentsU_[c][pi] = stages_.MomentsSet(buffers_, ch, cur, ch + ".illum0", ch + ".illum1");
            // One list per channel serves both histories: both test W_u (the channel's length).
            classifySets_[c][pi] = stages_.ClassifySet(buffers_, ch, cur);
            if (two_) {
                momentsW_[c][pi] = stages_.MomentsSet(buffers_, ch, cur, ch + ".willum0", ch + ".willum1");
                std::array<const Buffer*, TH_BLEND_BINDINGS> b{};
                b[TH_BLEND_B_ILLUM_U] = &Buf(ch + (iterations == 0 ? ".illum1" : ".illum0"));
                b[TH_BLEND_B_ILLUM_W] = &Buf(ch + (iterations == 0 ? ".willum1" : ".willum0"));
                b[TH_BLEND_B_WU] = &Buf(ch0 + ".length." + cur);
                b[TH_BLEND_B_WW] = &Buf("wweight." + cur);
                b[TH_BLEND_B_S] = &Buf("powerSums." + cur);
                b[TH_BLEND_B_Q] = &Buf(QBuffer());
                blendSets_[c][pi] = blend_.MakeSet(b);
            }
        }
        // À-trous sets. pp = 0: illum1 → illum0 (even iterations); pp = 1: illum0 → illum1 (as SVGF).
        const Buffer& guide = Buf("geometry.guide");
        const Buffer& depthGrad = Buf("input.depthGradient");
        std::vector<AtrousChannel> u[2], wts;
        for (const std::string& ch : channels_) {
            const Buffer* hist = &Buf(ch + ".color." + cur);
            u[0].push_back({&Buf(ch + ".illum1"), &Buf(ch + ".illum0"), hist});
            u[1].push_back({&Buf(ch + ".illum0"), &Buf(ch + ".illum1"), hist});
            if (two_) wts.push_back({&Buf(ch + ".willum1"), &Buf(ch + ".willum0"), &Buf(ch + ".wcolor." + cur)});
        }
        for (int pp = 0; pp < 2; ++pp)
            atrousU_[pi][size_t(pp)] = MakeAtrousSet(stages_.atrous, guide, depthGrad, u[pp]);
        atrousFirst_[pi].clear();
        if (!two_) {
            atrousFirst_[pi].push_back({&stages_.atrousStep1, atrousU_[pi][0]});
        } else if (nch == 2) {  // (I_u direct, I_u indirect), (I_w direct, I_w indirect)
            atrousFirst_[pi].push_back({&stages_.atrousStep1, atrousU_[pi][0]});
            atrousFirst_[pi].push_back({&stages_.atrousStep1, MakeAtrousSet(stages_.atrous, guide, depthGrad, wts)});
        } else {  // combined: (I_u, I_w)
            const std::array<AtrousChannel, 2> uw{u[0][0], wts[0]};
            atrousFirst_[pi].push_back({&atrousPair_, MakeAtrousSet(atrousPair_, guide, depthGrad, uw)});
        }

        if (variant_.emaGradient) {
            std::array<const Buffer*, TH_GRADIENT_BINDINGS> g{};
            g[TH_GRADIENT_B_GRADIENT] = &Buf("gradient." + cur);
            g[TH_GRADIENT_B_ILLUM_U0] = &Buf(ch0 + ".illum1");
            g[TH_GRADIENT_B_ILLUM_U1] = &Buf(ch1 + ".illum1");
            g[TH_GRADIENT_B_GUIDE] = &Buf("geometry.guide");
            g[TH_GRADIENT_B_DEPTH_GRAD] = &Buf("input.depthGradient");
            g[TH_GRADIENT_B_Q] = &Buf("q");
            gradientSets_[pi] = gradient_.MakeSet(g);
        }
        if (asvgf_) {  // the gather reads this frame's geometry at the guide pixels
            std::array<const Buffer*, ASVGF_GATHER_BINDINGS> g{};
            g[ASVGF_GATHER_B_SAMPLES] = &Buf("asvgf.samples");
            g[ASVGF_GATHER_B_CLAIM] = &Buf("asvgf.claim");
            g[ASVGF_GATHER_B_GRAD] = &Buf("asvgf.grad0");
            g[ASVGF_GATHER_B_GUIDE_GEOMETRY] = &Buf("asvgf.guideGeometry");
            g[ASVGF_GATHER_B_GUIDE_LUMINANCE] = &Buf("asvgf.guideLuminance");
            g[ASVGF_GATHER_B_DEPTH] = &Buf("geometry.depth." + cur);
            g[ASVGF_GATHER_B_NORMAL] = &Buf("geometry.normal." + cur);
            g[ASVGF_GATHER_B_OBJECT] = &Buf("geometry.objectId." + cur);
            g[ASVGF_GATHER_B_DEPTH_GRAD] = &Buf("input.depthGradient");
            g[ASVGF_GATHER_B_DIRECT] = &Buf("input.direct");
            g[ASVGF_GATHER_B_INDIRECT] = &Buf("input.indirect");
            g[ASVGF_GATHER_B_ALBEDO] = &Buf("input.modulation");
            g[ASVGF_GATHER_B_EMISSION] = &Buf("input.emission");
            gatherSets_[pi] = gather_.MakeSet(g);
        }
    }
    if (asvgf_) {
        std::array<const Buffer*, ASVGF_CLAIM_BINDINGS> c{&Buf("asvgf.samples"),
                                                          &Buf("asvgf.claim")};
        claimSet_ = claim_.MakeSet(c);
        const std::array<const Buffer*, ASVGF_SIGMA_BINDINGS> sg{
            &Buf("asvgf.guideGeometry"), &Buf("asvgf.guideLuminance"), &Buf("asvgf.sigmaL")};
        sigmaSet_ = stratumSigma_.MakeSet(sg);
        for (int pp = 0; pp < 2; ++pp) {
            std::array<const Buffer*, ASVGF_ATROUS_BINDINGS> a{};
            a[ASVGF_ATROUS_B_GRAD_IN] = &Buf(pp ? "asvgf.grad1" : "asvgf.grad0");
            a[ASVGF_ATROUS_B_GUIDE_GEOMETRY] = &Buf("asvgf.guideGeometry");
            a[ASVGF_ATROUS_B_GUIDE_LUMINANCE] = &Buf("asvgf.guideLuminance");
            a[ASVGF_ATROUS_B_SIGMA] = &Buf("asvgf.sigmaL");
            a[ASVGF_ATROUS_B_GRAD_OUT] = &Buf(pp ? "asvgf.grad0" : "asvgf.grad1");
            gradAtrousSets_[size_t(pp)] = gradAtrous_.MakeSet(a);
        }
        const int gi = params_.asvgf.gradientIterations;
        std::array<const Buffer*, ASVGF_ALPHA_BINDINGS> a{};
        a[ASVGF_ALPHA_B_GRAD] = &Buf(gi > 0 && (gi - 1) % 2 == 0 ? "asvgf.grad1" : "asvgf.grad0");
        a[ASVGF_ALPHA_B_ALPHA] = &Buf("asvgf.alpha");
        a[ASVGF_ALPHA_B_LAMBDA] = &Buf("asvgf.lambda");
        alphaSet_ = alpha_.MakeSet(a);
    }
    const std::string last = FilteredIlluminationPlane(iterations) ? ".illum1" : ".illum0";
    modulateSet_ = stages_.ModulateSet(buffers_, ch0 + last, ch1 + last);
}

void TwoHistoryVulkanDenoiser::Denoise(const FrameInputs& in, Plane<vec3>& output) {
    const int w = in.width(), h = in.height();
    if (w <= 0 || h <= 0) Fail("{}: empty FrameInputs", Name());
    if (w != width_ || h != height_) Allocate(w, h);
    if (in.cameraCut) needsClear_ = true;
    const SvgfParams& p = params_.svgf;
    const size_t n = size_t(w) * size_t(h);
    const uvec2 groups = DispatchGroups(w, h);
    const uvec2 gridGroups = DispatchGroups(grid_.x, grid_.y);
    const int iterations = p.atrousIterations;
    const std::string cur = Side(parity_);
    const size_t sampleCount = asvgf_ ? in.gradientSamples.size() : 0;
    if (sampleCount > GradientSampleCapacity(w, h))
        Fail("{}: {} gradient samples exceed the capacity {} (two per 3x3 stratum)", Name(),
             sampleCount, GradientSampleCapacity(w, h));

    CommandRecorder rec(*context_, commands_, &timestamps_);
    Buffer& stagingExtra = Buf("staging.extra");
    rec.BeginPass("upload");
    if (needsClear_) {
        buffers_.RecordClear(rec);  // nothing reprojects on the next frame
        needsClear_ = false;
        hasPrev_ = false;
    }
    const size_t off = buffers_.RecordUploadInputs(rec, in, cur);
    size_t offExtra = 0;
    if (variant_.needsSampleCount)
        offExtra = rec.Upload(in.sampleCount.data(), 2 * n, stagingExtra, offExtra,
                              Buf("input.sampleCount"));
    if (sampleCount > 0)
        rec.Upload(in.gradientSamples.data(), sampleCount * sizeof(GradientSample), stagingExtra,
                   offExtra, Buf("asvgf.samples"));
    rec.Barrier();
    rec.EndPass();

    if (asvgf_) {
        if (hasPrev_) {
            rec.BeginPass("asvgf_gradient");
            rec.Fill(Buf("asvgf.claim"), 0xFFFFFFFFu);
            rec.Barrier();
            const AsvgfSamplesPush sp{ivec2(w, h), grid_, uint32_t(sampleCount)};
            if (sampleCount > 0) {
                rec.Dispatch(
                    claim_, claimSet_, &sp, sizeof(sp),
                    uvec2((uint32_t(sampleCount) + FOVRT_WORKGROUP_1D - 1) / FOVRT_WORKGROUP_1D,
                          1));
                rec.Barrier();
            }
            rec.Dispatch(gather_, gatherSets_[size_t(parity_)], &sp, sizeof(sp), gridGroups);
            rec.Barrier();
            const AsvgfSigmaPush sigma{grid_, p.sigmaLuminance};
            rec.Dispatch(stratumSigma_, sigmaSet_, &sigma, sizeof(sigma), gridGroups);
            rec.Barrier();
            for (int i = 0; i < params_.asvgf.gradientIterations; ++i) {
                const AsvgfAtrousPush ap{ivec2(w, h),  grid_,         1 << i,
                                         p.sigmaDepth, p.sigmaNormal, p.sigmaLuminance};
                rec.Dispatch(gradAtrous_, gradAtrousSets_[size_t(i & 1)], &ap, sizeof(ap), gridGroups);
                rec.Barrier();
            }
            rec.EndPass();
            rec.BeginPass("asvgf_alpha");
            const AsvgfAlphaPush alp{ivec2(w, h), grid_, params_.asvgf.alpha};
            rec.Dispatch(alpha_, alphaSet_, &alp, sizeof(alp), groups);
            rec.Barrier();
            rec.EndPass();
        } else {
            // No previous frame: α = λ = 1 (the reference does the same).
            rec.Fill(Buf("asvgf.alpha"), kFloatOne);
            rec.Fill(Buf("asvgf.lambda"), kFloatOne);
            rec.Barrier();
        }
    }

    stages_.RecordGuide(rec, guideSets_[size_t(parity_)], w, h);

    rec.BeginPass("two_history_reproject");
    // Both channels (pair) or the combined one per dispatch.
    const TwoHistoryReprojectPush rp{ivec2(w, h), p.alphaColor, p.alphaMoments, params_.twoHistory.gradientBeta,
                                     hasPrev_ ? 1u : 0u};
    reproject_.Record(rec, reprojectSets_[size_t(parity_)], &rp, w, h, Buf(channels_[0] + ".spatialArgs"), hasPrev_);
    rec.EndPass();

    // One list per channel serves both histories: both test W_u (the channel's length).
    std::vector<MomentsChannel> moments;
    for (size_t c = 0; c < channels_.size(); ++c) {
        const std::string& ch = channels_[c];
        MomentsChannel mc{classifySets_[c][size_t(parity_)], &Buf(ch + ".spatialArgs"),
                          {{momentsU_[c][size_t(parity_)], &Buf(ch + ".illum0"), &Buf(ch + ".illum1")}}};
        if (two_) mc.planes.push_back({momentsW_[c][size_t(parity_)], &Buf(ch + ".willum0"), &Buf(ch + ".willum1")});
        moments.push_back(std::move(mc));
    }
    stages_.RecordFilterMoments(rec, p, w, h, moments);

    if (variant_.emaGradient) {
        rec.BeginPass("two_history_gradient");
        const TwoHistoryGradientPush gp{ivec2(w, h), p.sigmaDepth, p.sigmaNormal,
                                        params_.twoHistory.qScale, channels_.size() == 2 ? 1u : 0u};
        rec.Dispatch(gradient_, gradientSets_[size_t(parity_)], &gp, sizeof(gp), groups);
        rec.Barrier();
        rec.EndPass();
    }

    auto blend = [&] {
        rec.BeginPass("two_history_blend");
        const ImageSizePush bp{ivec2(w, h)};
        for (size_t c = 0; c < channels_.size(); ++c)
            rec.Dispatch(blend_, blendSets_[c][size_t(parity_)], &bp, sizeof(bp), groups);
        rec.Barrier();
        rec.EndPass();
    };
    if (two_ && iterations == 0) blend();
    for (int i = 0; i < iterations; ++i) {
        rec.BeginPass(fmt::format("atrous{}", i));
        const SvgfAtrousPush ap{ivec2(w, h), 1 << i, p.sigmaDepth, p.sigmaNormal, p.sigmaLuminance};
        if (i == 0)  // the step-1 pipelines, writing the histories when the feedback iteration is 1
            for (const auto& [pipeline, set] : atrousFirst_[size_t(parity_)])
                rec.Dispatch(*pipeline, set, &ap, sizeof(ap), AtrousBlockGroups(w, h, 1));
        else
            rec.Dispatch(stages_.Atrous(i), atrousU_[size_t(parity_)][size_t(i & 1)], &ap, sizeof(ap),
                         AtrousBlockGroups(w, h, 1 << i));
        rec.Barrier();
        rec.EndPass();
        if (two_ && i == 0) blend();
    }

    stages_.RecordModulate(rec, modulateSet_, w, h);

    rec.BeginPass("download");
    buffers_.RecordDownloadOutput(rec, off, n);
    rec.EndPass();
    rec.Submit();
    buffers_.FinishOutput(w, h, output, stats_);
    timings_ = PassTimings(timestamps_);
    hasPrev_ = true;
    hasFrame_ = true;
    parity_ ^= 1;
}

bool TwoHistoryVulkanDenoiser::ReadDebugPlane(DebugViewId view, Plane<float>& out) {
    if (!hasFrame_) return false;
    const std::string side = LastWrittenSide();
    const size_t history = HistoryScalarBytes(params_.precision);
    const size_t scratch = sizeof(float);  // α, λ̂ and q are fp32 at every precision
    auto read = [&](const std::string& buffer, size_t scalarBytes) {
        buffers_.ReadPlane(*context_, buffer, width_, height_, scalarBytes, out);
        return true;
    };
    switch (view) {
        case DebugViewId::HistoryLength:  // W_u, the same in every channel's length
            return read(channels_[0] + ".length." + side, history);
        case DebugViewId::HistorySamples:  // W_w
            return two_ && read("wweight." + side, history);
        case DebugViewId::Alpha:
            return asvgf_ && read("asvgf.alpha", scratch);
        case DebugViewId::Lambda:
            return asvgf_ && read("asvgf.lambda", scratch);
        case DebugViewId::P: {
            // Not stored: the blend evaluates p from this frame's state, and so does this, with
            // the shader's formula (two_history_math.h, mirrored by common/two_history.glsl).
            if (!two_) return false;
            auto floats = [&](const std::string& buffer) {
                return buffers_.ReadFloats(*context_, buffer, history);
            };
            const std::vector<float> wu = floats(channels_[0] + ".length." + side);
            const std::vector<float> ww = floats("wweight." + side);
            const std::vector<float> s = floats("powerSums." + side);
            Plane<float> p(width_, height_);
            FOVRT_CHECK(wu.size() == p.size() && ww.size() == p.size() && s.size() == 3 * p.size());
            for (size_t i = 0; i < p.size(); ++i) {
                const vec3 powerSums(s[3 * i], s[3 * i + 1], s[3 * i + 2]);
                p[i] = TwoHistoryOptimalBlend(StoredTwoHistoryWeights(wu[i], ww[i], powerSums));
            }
            out = std::move(p);
            return true;
        }
        case DebugViewId::Q:
            return two_ && read(QBuffer(), scratch);
    }
    return false;
}

std::vector<uint8_t> TwoHistoryVulkanDenoiser::ReadBuffer(const std::string& name) {
    return buffers_.Read(*context_, name);
}

}  // namespace fovrt
