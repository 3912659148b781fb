// Memory plans of the denoisers: every buffer (name, bytes, history?) exactly as the Vulkan path
// allocates it (the Vulkan SVGF allocates by iterating this very list), plus budget enforcement
// and the `fovrt memory` table.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "denoise/denoiser.h"
#include "denoise/params.h"
#include "denoise/variants.h"

namespace fovrt {

// Staging offsets are aligned like CommandRecorder::Upload/Download (16 bytes).
inline size_t StagingAlign(size_t bytes) { return (bytes + 15) & ~size_t(15); }

// The buffer a FrameInputs plane is uploaded to: this frame's geometry into
// geometry.depth/normal/objectId.<side> (A/B pairs: next frame reads it as the previous one),
// the albedo plane's slot into input.modulation (it carries FrameInputs::Modulation(): the
// albedo or F_β), every other plane into input.<plane>. side "" gives the name without the side.
std::string UploadBufferOf(std::string_view plane, std::string_view side = "");
// Bytes of the input.sampleCount buffer for `pixels` pixels.
size_t SampleCountBytes(size_t pixels);

// Whether a frame uploads this FrameInputs plane with the others: all but the sample counts,
// which only the variants that read them (DenoiserVariant::needsSampleCount) upload; F_β, which no
// shader reads (a +brdf variant's host puts it in the modulation plane's place before the upload:
// denoise/demodulation.h); and the roughness, which only the RAE reads (SPEC §12).
inline bool UploadedWithInputs(std::string_view plane) {
    return plane != "sampleCount" && plane != "fbeta" && plane != "roughness";
}

// Bytes per element of a history plane scalar.
inline size_t HistoryScalarBytes(Precision p) { return p == Precision::Fp16 ? 2 : 4; }

// Every buffer of the SVGF / svgf-weighted Vulkan path at W×H (one eye). Names:
// input.* (per-frame uploads), geometry.*.A/B (this/previous frame, history), <channel>.color|
// moments|length|weight.A/B (history), <channel>.illum0/1 (à-trous ping-pong), output, stats, staging.
std::vector<BufferPlan> PlanSvgfMemory(int width, int height, const DenoiserParams& params);

// Buffers of the named denoiser beyond SVGF's, W×H, one eye, named as the Vulkan path allocates
// them. History (A/B pairs): <channel>.wcolor (I_w, float3), wweight (W_w), powerSums (S_{-1},
// S_0, S_1), gradient (g, one float: its luminance; two-history only); W_u lives in SVGF's
// <channel>.length. Scratch: weighted
// illumination ping-pong, q, sample counts, A-SVGF strata/α/λ, extra staging.
std::vector<BufferPlan> PlanTwoHistoryExtraMemory(const std::string& name, int width, int height,
                                                  const DenoiserParams& params);

// Full plan of the named denoiser: SVGF's buffers (PlanSvgfMemory) + the extra ones above.
std::vector<BufferPlan> PlanTwoHistoryMemory(const std::string& name, int width, int height,
                                             const DenoiserParams& params);

size_t TotalBytes(const std::vector<BufferPlan>& plan);
size_t HistoryBytes(const std::vector<BufferPlan>& plan);

// Throws fovrt::Error when the plan exceeds `budgetBytes`, naming the total and the largest
// buffers. budgetBytes == 0 means no budget.
void EnforceMemoryBudget(const std::vector<BufferPlan>& plan, size_t budgetBytes,
                         const std::string& what = "denoiser");

// Human-readable table: every buffer with bytes and bytes/pixel, then totals.
std::string FormatMemoryPlan(const std::vector<BufferPlan>& plan, int width, int height);

}  // namespace fovrt
