// Memory plans of the denoisers: every buffer (name, bytes, history?) a variant allocates. For the
// SVGF family it is the union of the planes its pass plan names (denoise/pass_plan.h), sized by the
// plane table (denoise/planes.h); the Vulkan host allocates by iterating it, so `fovrt memory`
// lists exactly what is allocated. Also budget enforcement and the `fovrt memory` table.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "denoise/denoiser.h"
#include "denoise/params.h"
#include "denoise/pass_plan.h"
#include "denoise/planes.h"

namespace fovrt {

// Buffers of the named denoiser's plan that svgf's plan at the same parameters lacks: the
// two-history family's extra memory (W_u lives in SVGF's <channel>.length, so two-history's extra
// history is I_w per channel, W_w, S_k and g).
std::vector<BufferPlan> PlanTwoHistoryExtraMemory(const std::string& name, int width, int height,
                                                  const DenoiserParams& params);

// All the allocations: the permanent buffers and the transient pool, held through the whole frame,
// so the peak the device holds.
size_t TotalBytes(const std::vector<BufferPlan>& plan);
size_t HistoryBytes(const std::vector<BufferPlan>& plan);
size_t TransientBytes(const std::vector<BufferPlan>& plan);  // the transient pool's slots

// Throws fovrt::Error when the plan's peak (TotalBytes) exceeds `budgetBytes`, naming the total and the largest
// buffers. budgetBytes == 0 means no budget.
void EnforceMemoryBudget(const std::vector<BufferPlan>& plan, size_t budgetBytes,
                         const std::string& what = "denoiser");

// Human-readable table: every allocation with bytes and bytes/pixel (under a transient slot, the
// planes it holds), then history, other permanent, transient pool, the most transient bytes live
// at once (the floor of any pool) and the peak.
std::string FormatMemoryPlan(const DenoiserPlan& plan, int width, int height);

}  // namespace fovrt
