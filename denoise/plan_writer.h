// The toolkit of the SVGF-family plan builders (svgf_family_plan.cpp, reprojection_plan.cpp,
// asvgf_plan.cpp, mechanism_passes.cpp): plane references, a dispatch's bindings, the variant's
// resolved flags, the writer that appends passes and commands, and what a mechanism's fragment
// moves on. Only those files and the plan's tests include it.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "denoise/gradient_strata.h"
#include "denoise/mechanism_slots.h"
#include "denoise/pass_plan.h"
#include "denoise/schedule.h"
#include "denoise/svgf_family_plan.h"
#include "denoise/variants.h"
#include "shaders/push_constants.h"

namespace fovrt::plan {

inline PlaneRef Shared(PlaneKind kind) { return {{kind, Channel::None}, HistorySide::None}; }
inline PlaneRef Scratch(PlaneKind kind, Channel ch) { return {{kind, ch}, HistorySide::None}; }
inline PlaneRef This(PlaneKind kind, Channel ch = Channel::None) { return {{kind, ch}, HistorySide::This}; }
inline PlaneRef Previous(PlaneKind kind, Channel ch = Channel::None) {
    return {{kind, ch}, HistorySide::Previous};
}
// Bound where a mode leaves a slot unread / unwritten: planes every plan has.
inline const PlaneRef kUnreadSlot = Shared(PlaneKind::PrevPixel);
inline const PlaneRef kUnwrittenSlot = Shared(PlaneKind::Output);

// A dispatch's bindings, slot by slot.
class Bindings {
  public:
    Bindings& Read(int slot, PlaneRef p, Coverage c = Coverage::EveryPixel, double share = 1.0) {
        return Add({slot, p, Access::Read, c, share});
    }
    Bindings& Write(int slot, PlaneRef p, Coverage c = Coverage::EveryPixel) {
        return Add({slot, p, Access::Write, c});
    }
    Bindings& ReadWrite(int slot, PlaneRef p, Coverage c = Coverage::EveryPixel) {
        return Add({slot, p, Access::ReadWrite, c});
    }
    Bindings& Unused(int slot, PlaneRef p) { return Add({slot, p, Access::Unused}); }
    // The object ids of a geometry side (This or Previous ObjectId), or, where the depth plane
    // holds them (`inDepth`: StoresObjectIdsInDepth), that depth plane bound again: the shader
    // reads the same texel as at its depth slot, so the byte model counts it there only.
    Bindings& ReadObjectIds(int slot, PlaneRef ids, bool inDepth, Coverage c = Coverage::EveryPixel) {
        if (!inDepth) return Read(slot, ids, c);
        return Add({slot, {{PlaneKind::Depth, ids.id.channel}, ids.side}, Access::Unused});
    }
    // `p` read where `used`, else the slot holds a plane nothing reads.
    Bindings& ReadIf(bool used, int slot, PlaneRef p) { return used ? Read(slot, p) : Unused(slot, kUnreadSlot); }
    Bindings& WriteIf(bool used, int slot, PlaneRef p) {
        return used ? Write(slot, p) : Unused(slot, kUnwrittenSlot);
    }
    // A slot the shader loads on every pixel whatever is bound (`bytesPerPixel` each).
    Bindings& Placeholder(int slot, PlaneRef p, double bytesPerPixel) {
        return Add({slot, p, Access::Read, Coverage::EveryPixel, 1.0, bytesPerPixel});
    }
    std::vector<Binding> list;

  private:
    Bindings& Add(Binding b) {
        list.push_back(b);
        return *this;
    }
};

// What every pass builder reads: the variant's flags and the parameters, resolved once.
struct Family {
    const DenoiserVariant& v;
    const DenoiserParams& params;
    const SvgfParams& svgf;
    int width, height;
    std::vector<Channel> channels;  // filtered channels: direct + indirect, or combined
    bool pair;                      // both channels in one dispatch
    bool twoHistoryFamily;          // the two-history family's passes (vs SVGF's)
    int feedback;                   // FeedbackIteration
    // A variant that weighs by no sample count reads them anyway, only to keep a pixel without a
    // path sample (DenoiserParams::sampleCountsMayBeZero; the ZERO_SAMPLES reprojection flags).
    bool zeroSamples;
    bool readsSampleCounts;  // the sample counts are uploaded: needsSampleCount or zeroSamples
    bool idsInDepth;         // the depth plane holds the object ids (StoresObjectIdsInDepth)
    ivec2 size, grid;
    ivec2 window;  // the WINDOW_STORED planes' pixels (the weighted history's window)

    Family(const DenoiserVariant& variant, const DenoiserParams& p, int w, int h)
        : v(variant), params(p), svgf(p.svgf), width(w), height(h), channels(FilteredChannels(p.svgf)),
          pair(channels.size() == 2), twoHistoryFamily(variant.family == DenoiserFamily::TwoHistory),
          feedback(FeedbackIteration(p.svgf, variant.twoHistory)),
          zeroSamples(p.sampleCountsMayBeZero && !variant.needsSampleCount),
          readsSampleCounts(variant.needsSampleCount || zeroSamples), idsInDepth(StoresObjectIdsInDepth(p.precision)),
          size(w, h), grid(StratumGridSize(w, h)),
          window(WeightedWindowSize(w, h, WeightedWindowFraction(variant, p))) {}

    Channel First() const { return channels.front(); }
    Channel Last() const { return channels.back(); }
    // The channel whose "length" plane holds `ch`'s history length: the two-history family's
    // channels share one W_u, channel 0's (its reprojection counts one for both).
    Channel LengthOf(Channel ch) const { return twoHistoryFamily ? First() : ch; }
    PipelineKey Pipeline(StageShader shader, Specialization spec = {}, bool pairVariant = false) const {
        return {shader, pairVariant, false, false, params.precision == Precision::Fp16, spec};
    }
    Specialization EdgeStopping() const {
        return Specialization::Of({{FOVRT_SPEC_NORMAL_SQUARINGS, NormalWeightSquarings(svgf.sigmaNormal)}});
    }
};

// Appends passes and their commands, in recording order.
class Writer {
  public:
    explicit Writer(std::vector<PlannedPass>& passes) : passes_(passes) {}
    void Pass(std::string name, std::string referenceTimer, ReferenceStage stage, When when = When::Always) {
        passes_.push_back({std::move(name), when, std::move(referenceTimer), std::move(stage), {}, {}});
    }
    void Dispatch(DispatchCommand d, When when = When::Always) { Add(when, std::move(d)); }
    void Fill(PlaneRef p, uint32_t value, When when = When::Always) { Add(when, FillCommand{p, value}); }
    void Copy(PlaneRef from, PlaneRef to) { Add(When::Always, CopyCommand{from, to}); }
    void Upload(PlaneRef to, Coverage c = Coverage::EveryPixel, When when = When::Always) {
        Add(when, UploadCommand{to, c});
    }
    void Download(PlaneRef from) { Add(When::Always, DownloadCommand{from}); }
    void Clear(When when) { Add(when, ClearCommand{}); }
    void Barrier(When when = When::Always) { Add(when, BarrierCommand{}); }

  private:
    template <typename Op>
    void Add(When when, Op op) {
        passes_.back().commands.push_back({when, std::move(op)});
    }
    std::vector<PlannedPass>& passes_;
};

inline DispatchCommand Over(Grid grid, PipelineKey pipeline, Bindings b, PushBlock push, int step = 1) {
    return {.pipeline = pipeline, .bindings = std::move(b.list), .push = std::move(push), .grid = grid, .step = step};
}
inline DispatchCommand OverPixels(PipelineKey pipeline, Bindings b, PushBlock push) {
    return Over(Grid::Pixels, pipeline, std::move(b), std::move(push));
}
inline DispatchCommand OverStrata(PipelineKey pipeline, Bindings b, PushBlock push) {
    return Over(Grid::Strata, pipeline, std::move(b), std::move(push));
}
inline DispatchCommand OverList(PipelineKey pipeline, Bindings b, PushBlock push, PlaneId args, Coverage listed) {
    return {pipeline, std::move(b.list), std::move(push), Grid::PixelList, 1, args, listed};
}

// The passes built in their own files.
void Reproject(Writer& w, const Family& f);  // reprojection_plan.cpp

// What a mechanism's fragment (denoise/mechanism_passes.h) may move on in the frame: the
// ping-pong plane that holds the filtered illumination (FrameSlot::AfterFilter; modulation reads it).
struct FrameCursor {
    PlaneKind filtered = PlaneKind::Illum0;
};
// The passes of `f`'s mechanisms at `slot`, in frame order.
void EmitMechanismPasses(Writer& w, const Family& f, FrameSlot slot, FrameCursor& cursor);

}  // namespace fovrt::plan
