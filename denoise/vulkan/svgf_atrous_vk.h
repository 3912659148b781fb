// The SVGF stages shared by the SVGF and two-history Vulkan hosts: the à-trous pipelines and sets,
// the two reprojection passes (ReprojectionPipelines), and SvgfStagePipelines (guide, moments,
// à-trous, modulate) with their descriptor sets. One
// dispatch filters one illumination channel ("svgf_atrous") or a pair ("svgf_atrous_pair": direct
// + indirect, or two-history's unweighted + weighted history) that shares the per-tap guide fetch,
// depth gradient and w_z·w_n exponent; each channel keeps its own w_l and variance
// (shaders/svgf_atrous.comp), so a pair gives exactly the two one-channel results.
// One invocation filters a 2×2 block of pixels at stride `step` (the four 5×5 windows share a 6×6
// lattice of taps): dispatch AtrousBlockGroups(w, h, step), and the "_step1" pipeline at step 1
// (its 3×3 variance windows form one 4×4 block). The step-1 and any-step pipelines have
// identically defined set layouts, so a set made from one may be bound with the other.
#pragma once

#include <algorithm>
#include <array>
#include <span>
#include <string>
#include <vector>

#include "core/check.h"
#include "denoise/params.h"
#include "denoise/vulkan/svgf_layout.h"
#include "denoise/vulkan/svgf_texel_formats.h"
#include "denoise/vulkan/vk_denoiser_buffers.h"
#include "vk/pipeline.h"
#include "vk/recorder.h"

namespace fovrt {

// The planes of one channel of an à-trous dispatch.
struct AtrousChannel {
    const Buffer* in;       // illumination + variance read
    const Buffer* out;      // illumination + variance written
    const Buffer* history;  // colour history written on the feedback iteration
};

// `channels` (1 or 2) illumination planes per dispatch; `step1`: the variant for step 1 only;
// `writeHistory`: the feedback iteration's pipeline, which also writes the colour history;
// `unitWeights`: every edge-stopping weight 1 (the bench's floor probe, denoise/bench/atrous_probe.h).
inline ComputePipeline MakeAtrousPipeline(VulkanContext& context, int channels, const DenoiserParams& params,
                                          uint32_t maxSets, bool step1, bool writeHistory,
                                          bool unitWeights = false) {
    const Precision precision = params.precision;
    FOVRT_CHECK(channels == 1 || channels == 2);
    const std::string name = std::string(channels == 2 ? "svgf_atrous_pair" : "svgf_atrous") +
                             (step1 ? "_step1" : "") + (precision == Precision::Fp16 ? "_fp16" : "");
    const uint32_t bindings = channels == 2 ? SVGF_ATROUS_PAIR_BINDINGS : SVGF_ATROUS_BINDINGS;
    static const std::array<VkFormat, SVGF_ATROUS_PAIR_BINDINGS> kFormats = SvgfAtrousTexelFormats();
    static_assert(FOVRT_SPEC_NORMAL_SQUARINGS == 0 && FOVRT_SPEC_ATROUS_WRITE_HISTORY == 2 &&
                  FOVRT_SPEC_ATROUS_UNIT_WEIGHTS == 4);
    const std::array<int32_t, 5> spec{EdgeStoppingSpecialization(params.svgf)[0], -1, writeHistory ? 1 : 0, -1,
                                      unitWeights ? 1 : 0};
    return ComputePipeline(context, name, bindings, sizeof(SvgfAtrousPush), maxSets,
                           std::span<const VkFormat>(kFormats).first(bindings), spec);
}

// Blocks per axis of `n` pixels at stride `step`: pixels pair up (x, x + step) inside each run of
// 2·step, and a last partial run of r pixels has min(r, step) blocks (partners past the edge).
inline int AtrousBlocks(int n, int step) { return n / (2 * step) * step + std::min(n % (2 * step), step); }

// Workgroups of an à-trous dispatch at `step` (one invocation per 2×2 block).
inline uvec2 AtrousBlockGroups(int width, int height, int step) {
    return DispatchGroups(AtrousBlocks(width, step), FOVRT_ATROUS_BLOCK_Y == 2 ? AtrousBlocks(height, step) : height);
}

// A set of a pipeline from MakeAtrousPipeline with as many channels as `channels` holds.
inline VkDescriptorSet MakeAtrousSet(ComputePipeline& pipeline, const Buffer& guide, const Buffer& depthGradient,
                                     std::span<const AtrousChannel> channels) {
    FOVRT_CHECK(channels.size() == 1 || channels.size() == 2);
    std::array<const Buffer*, SVGF_ATROUS_PAIR_BINDINGS> a{};
    a[SVGF_ATROUS_B_GUIDE] = &guide;
    a[SVGF_ATROUS_B_DEPTH_GRAD] = &depthGradient;
    a[SVGF_ATROUS_B_ILLUM_IN] = channels[0].in;
    a[SVGF_ATROUS_B_ILLUM_OUT] = channels[0].out;
    a[SVGF_ATROUS_B_HIST_COLOR] = channels[0].history;
    if (channels.size() == 2) {
        a[SVGF_ATROUS_B_ILLUM_IN2] = channels[1].in;
        a[SVGF_ATROUS_B_ILLUM_OUT2] = channels[1].out;
        a[SVGF_ATROUS_B_HIST_COLOR2] = channels[1].history;
    }
    return pipeline.MakeSet(
        std::span<const Buffer* const>(a).first(channels.size() == 2 ? SVGF_ATROUS_PAIR_BINDINGS : SVGF_ATROUS_BINDINGS));
}

// The inputs every reprojection shader binds at the same slots 0–11 (svgf_reproject and
// two_history_reproject: SVGF_REPROJECT_B_COLOR_IN … LIST): both colour channels, the geometry of
// this frame (`side`) and the previous one (`prevSide`), depth gradient and motion, and the list
// of the box-fallback pixels. The list borrows channel `listChannel`'s spatial-variance list: the
// reprojection has used it up before svgf_moments_classify refills it (memory_plan.cpp).
template <size_t N>
void BindReprojectionInputs(std::array<const Buffer*, N>& r, DenoiserBuffers& buf, const std::string& side,
                            const std::string& prevSide, const std::string& listChannel) {
    static_assert(N > SVGF_REPROJECT_B_LIST);
    r[SVGF_REPROJECT_B_COLOR_IN] = &buf["input.direct"];
    r[SVGF_REPROJECT_B_COLOR_IN2] = &buf["input.indirect"];
    r[SVGF_REPROJECT_B_DEPTH] = &buf["geometry.depth." + side];
    r[SVGF_REPROJECT_B_NORMAL] = &buf["geometry.normal." + side];
    r[SVGF_REPROJECT_B_OBJECT] = &buf["geometry.objectId." + side];
    r[SVGF_REPROJECT_B_PREV_DEPTH] = &buf["geometry.depth." + prevSide];
    r[SVGF_REPROJECT_B_PREV_NORMAL] = &buf["geometry.normal." + prevSide];
    r[SVGF_REPROJECT_B_PREV_OBJECT] = &buf["geometry.objectId." + prevSide];
    r[SVGF_REPROJECT_B_DEPTH_GRAD] = &buf["input.depthGradient"];
    r[SVGF_REPROJECT_B_PREV_PIXEL] = &buf["input.prevPixel"];
    r[SVGF_REPROJECT_B_LIST_ARGS] = &buf[listChannel + ".spatialArgs"];
    r[SVGF_REPROJECT_B_LIST] = &buf[listChannel + ".spatialList"];
}

// Temporal accumulation as two passes of one shader (shaders/common/reprojection.glsl): `main`
// on every pixel with the bilinear taps, listing the pixels whose taps all failed, then `box`
// ("<shader>_box") on the listed pixels only, with the 3×3 fallback taps (indirect dispatch).
// `flags` (the shader's mode bits) is a specialization constant of both. The two variants declare
// the same bindings, so a set made from `main` is bound with `box` too.
struct ReprojectionPipelines {
    ComputePipeline main, box;

    ReprojectionPipelines() = default;
    // `shader` without the variant suffix (e.g. "svgf_reproject_pair"), `suffix` "" or "_fp16".
    ReprojectionPipelines(VulkanContext& context, const std::string& shader, const std::string& suffix,
                          uint32_t bindings, uint32_t pushBytes, uint32_t maxSets,
                          std::span<const VkFormat> texelFormats, uint32_t flags) {
        const std::array<int32_t, 2> spec{-1, int32_t(flags)};  // constant_id 1: FOVRT_SPEC_REPROJECT_FLAGS
        static_assert(FOVRT_SPEC_REPROJECT_FLAGS == 1);
        main = ComputePipeline(context, shader + suffix, bindings, pushBytes, maxSets, texelFormats, spec);
        box = ComputePipeline(context, shader + "_box" + suffix, bindings, pushBytes, 1, texelFormats, spec);
    }
    // Both passes over a W×H image; `listArgs` is the buffer bound at SVGF_REPROJECT_B_LIST_ARGS.
    // Without a previous frame nothing is listed, and the box pass is not recorded.
    void Record(CommandRecorder& rec, VkDescriptorSet set, const void* push, int w, int h, Buffer& listArgs,
                bool hasPrev) const {
        rec.Fill(listArgs, 0u);
        rec.Barrier();
        rec.Dispatch(main, set, push, main.pushBytes(), DispatchGroups(w, h));
        rec.Barrier();
        if (!hasPrev) return;
        rec.DispatchIndirect(box, set, push, box.pushBytes(), listArgs);
        rec.Barrier();
    }
};

// The illumination planes of one channel that the "filter_moments" pass handles: the pixels
// listed by `classify` (history shorter than the threshold, counted in `args`) get the spatial
// variance estimate of each plane (SVGF: illum0 → illum1; two-history also willum0 → willum1),
// every other pixel is copied through.
struct MomentsPlane {
    VkDescriptorSet set;  // SvgfStagePipelines::MomentsSet over in → out
    Buffer* in;
    Buffer* out;
};
struct MomentsChannel {
    VkDescriptorSet classify;  // SvgfStagePipelines::ClassifySet
    Buffer* args;              // the channel's indirect-dispatch arguments (".spatialArgs")
    std::vector<MomentsPlane> planes;
};

// The SVGF stages both Vulkan hosts (svgf_vk, two_history_vk) run unchanged, built one way for
// both: the guide pack, the moments classify + spatial filter, à-trous with `channels` planes per
// dispatch (its step-1 variant for iteration 0, and the variant that writes the colour history
// for the feedback iteration), and the remodulation; the passes that both hosts record
// identically are recorded here too.
struct SvgfStagePipelines {
    ComputePipeline guide, classify, moments, modulate;
    // À-trous: `atrous` for iterations ≥ 1, `atrousStep1` for iteration 0 (writes the colour
    // history when the feedback iteration is 1), `atrousFeedback` for a feedback iteration ≥ 2.
    // Same set layouts: sets made from `atrous` are bound with all three.
    ComputePipeline atrous, atrousStep1, atrousFeedback;
    int feedbackIteration = 0;  // 1-based à-trous iteration that feeds back; 0: none

    // The pipeline of à-trous iteration i (0-based).
    const ComputePipeline& Atrous(int i) const {
        if (i == 0) return atrousStep1;
        return i + 1 == feedbackIteration ? atrousFeedback : atrous;
    }

    // The "pack_guide" pass.
    void RecordGuide(CommandRecorder& rec, VkDescriptorSet set, int w, int h) const {
        rec.BeginPass("pack_guide");
        const ImageSizePush size{ivec2(w, h)};
        rec.Dispatch(guide, set, &size, sizeof(size), DispatchGroups(w, h));
        rec.Barrier();
        rec.EndPass();
    }
    // The "filter_moments" pass: classify each channel and copy its planes through, then filter
    // only the listed pixels (indirect dispatch; one list per channel serves all its planes).
    void RecordFilterMoments(CommandRecorder& rec, const SvgfParams& p, int w, int h,
                             std::span<const MomentsChannel> channels) const {
        rec.BeginPass("filter_moments");
        for (const MomentsChannel& c : channels) rec.Fill(*c.args, 0u);
        rec.Barrier();
        const SvgfClassifyPush cp{ivec2(w, h), float(p.varianceHistoryThreshold)};
        const size_t bytes = sizeof(vec4) * size_t(w) * size_t(h);
        for (const MomentsChannel& c : channels) {
            rec.Dispatch(classify, c.classify, &cp, sizeof(cp), DispatchGroups(w, h));
            for (const MomentsPlane& plane : c.planes) rec.Copy(*plane.in, *plane.out, bytes);
        }
        rec.Barrier();
        const SvgfFilterMomentsPush mp{ivec2(w, h), p.sigmaDepth, p.sigmaNormal, float(p.varianceHistoryThreshold)};
        for (const MomentsChannel& c : channels)
            for (const MomentsPlane& plane : c.planes) rec.DispatchIndirect(moments, plane.set, &mp, sizeof(mp), *c.args);
        rec.Barrier();
        rec.EndPass();
    }
    // The "modulate" pass (one channel: it holds direct + indirect).
    void RecordModulate(CommandRecorder& rec, VkDescriptorSet set, int w, int h) const {
        rec.BeginPass("modulate");
        const ImageSizePush mo{ivec2(w, h)};
        rec.Dispatch(modulate, set, &mo, sizeof(mo), DispatchGroups(w, h));
        rec.Barrier();
        rec.EndPass();
    }

    SvgfStagePipelines() = default;
    // `feedbackIteration`: the 1-based à-trous iteration whose output is the colour history (0: none).
    SvgfStagePipelines(VulkanContext& context, int channels, const DenoiserParams& params, uint32_t maxSets,
                       int feedback)
        : feedbackIteration(feedback) {
        const Precision precision = params.precision;
        const std::string sfx = precision == Precision::Fp16 ? "_fp16" : "";
        guide = ComputePipeline(context, "svgf_pack_guide", SVGF_GUIDE_BINDINGS, sizeof(ImageSizePush), 2,
                                SvgfGuideTexelFormats());
        classify = ComputePipeline(context, "svgf_moments_classify" + sfx, SVGF_CLASSIFY_BINDINGS,
                                   sizeof(SvgfClassifyPush), maxSets, SvgfClassifyTexelFormats(precision));
        moments = ComputePipeline(context, "svgf_filter_moments" + sfx, SVGF_MOMENTS_BINDINGS,
                                  sizeof(SvgfFilterMomentsPush), maxSets, SvgfMomentsTexelFormats(precision),
                                  EdgeStoppingSpecialization(params.svgf));
        atrous = MakeAtrousPipeline(context, channels, params, maxSets, false, false);
        // Bound with atrous's sets:
        atrousStep1 = MakeAtrousPipeline(context, channels, params, 1, true, feedback == 1);
        if (feedback >= 2) atrousFeedback = MakeAtrousPipeline(context, channels, params, 1, false, true);
        static_assert(FOVRT_SPEC_MODULATE_COMBINED == 3);
        const std::array<int32_t, 4> combined{-1, -1, -1, channels == 1 ? 1 : 0};
        modulate = ComputePipeline(context, "svgf_modulate" + sfx, SVGF_MODULATE_BINDINGS, sizeof(ImageSizePush), 2,
                                   SvgfModulateTexelFormats(), combined);
    }

    // Descriptor sets of these stages over the plan's buffers (names as in the memory plan);
    // `side` is the history side ("A"/"B") of this frame.
    VkDescriptorSet GuideSet(DenoiserBuffers& buf, const std::string& side) {
        std::array<const Buffer*, SVGF_GUIDE_BINDINGS> g{};
        g[SVGF_GUIDE_B_DEPTH] = &buf["geometry.depth." + side];
        g[SVGF_GUIDE_B_NORMAL] = &buf["geometry.normal." + side];
        g[SVGF_GUIDE_B_OBJECT] = &buf["geometry.objectId." + side];
        g[SVGF_GUIDE_B_OUT] = &buf["geometry.guide"];
        return guide.MakeSet(g);
    }
    // Lists the pixels of channel `ch` whose history length is below the variance threshold.
    VkDescriptorSet ClassifySet(DenoiserBuffers& buf, const std::string& ch, const std::string& side) {
        std::array<const Buffer*, SVGF_CLASSIFY_BINDINGS> k{};
        k[SVGF_CLASSIFY_B_GUIDE] = &buf["geometry.guide"];
        k[SVGF_CLASSIFY_B_LENGTH] = &buf[ch + ".length." + side];
        k[SVGF_CLASSIFY_B_ARGS] = &buf[ch + ".spatialArgs"];
        k[SVGF_CLASSIFY_B_LIST] = &buf[ch + ".spatialList"];
        return classify.MakeSet(k);
    }
    // Spatial variance of the listed pixels: illumination `in` → `out`, with channel ch's moments.
    VkDescriptorSet MomentsSet(DenoiserBuffers& buf, const std::string& ch, const std::string& side,
                               const std::string& in, const std::string& out) {
        std::array<const Buffer*, SVGF_MOMENTS_BINDINGS> m{};
        m[SVGF_MOMENTS_B_ILLUM_IN] = &buf[in];
        m[SVGF_MOMENTS_B_GUIDE] = &buf["geometry.guide"];
        m[SVGF_MOMENTS_B_DEPTH_GRAD] = &buf["input.depthGradient"];
        m[SVGF_MOMENTS_B_MOMENTS] = &buf[ch + ".moments." + side];
        m[SVGF_MOMENTS_B_LENGTH] = &buf[ch + ".length." + side];
        m[SVGF_MOMENTS_B_ILLUM_OUT] = &buf[out];
        m[SVGF_MOMENTS_B_ARGS] = &buf[ch + ".spatialArgs"];
        m[SVGF_MOMENTS_B_LIST] = &buf[ch + ".spatialList"];
        return moments.MakeSet(m);
    }
    // albedo · (illum0 + illum1) + emission → output (combined: both name the one channel, read once).
    VkDescriptorSet ModulateSet(DenoiserBuffers& buf, const std::string& illum0, const std::string& illum1) {
        std::array<const Buffer*, SVGF_MODULATE_BINDINGS> mod{};
        mod[SVGF_MODULATE_B_ILLUM0] = &buf[illum0];
        mod[SVGF_MODULATE_B_ILLUM1] = &buf[illum1];
        mod[SVGF_MODULATE_B_ALBEDO] = &buf["input.modulation"];
        mod[SVGF_MODULATE_B_EMISSION] = &buf["input.emission"];
        mod[SVGF_MODULATE_B_OUT] = &buf["output"];
        return modulate.MakeSet(mod);
    }
};

}  // namespace fovrt
