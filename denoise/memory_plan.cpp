#include "denoise/memory_plan.h"

#include <algorithm>
#include <set>

#include <fmt/format.h>

#include "core/error.h"
#include "denoise/pass_plan.h"

namespace fovrt {

std::vector<BufferPlan> PlanDenoiserMemory(const std::string& name, int width, int height,
                                           const DenoiserParams& params) {
    return BuildDenoiserPlan(name, params, width, height).buffers;
}

std::vector<BufferPlan> PlanTwoHistoryExtraMemory(const std::string& name, int width, int height,
                                                  const DenoiserParams& params) {
    std::set<std::string> svgf;
    for (const BufferPlan& b : PlanDenoiserMemory("svgf", width, height, params)) svgf.insert(b.name);
    std::vector<BufferPlan> extra;
    for (const BufferPlan& b : PlanDenoiserMemory(name, width, height, params))
        if (!svgf.count(b.name)) extra.push_back(b);
    return extra;
}

size_t TotalBytes(const std::vector<BufferPlan>& plan) {
    size_t total = 0;
    for (const auto& b : plan) total += b.bytes;
    return total;
}

size_t HistoryBytes(const std::vector<BufferPlan>& plan) {
    size_t total = 0;
    for (const auto& b : plan)
        if (b.history) total += b.bytes;
    return total;
}

void EnforceMemoryBudget(const std::vector<BufferPlan>& plan, size_t budgetBytes, const std::string& what) {
    if (budgetBytes == 0) return;
    size_t total = TotalBytes(plan);
    if (total <= budgetBytes) return;
    std::vector<BufferPlan> sorted = plan;
    std::sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& b) { return a.bytes > b.bytes; });
    std::string largest;
    for (size_t i = 0; i < std::min<size_t>(3, sorted.size()); ++i)
        largest += fmt::format("{}{} ({:.1f} MiB)", i ? ", " : "", sorted[i].name, sorted[i].bytes / 1048576.0);
    Fail("--memory-budget {} bytes exceeded: {} needs {} bytes ({:.1f} MiB); largest buffers: {}",
         budgetBytes, what, total, total / 1048576.0, largest);
}

std::string FormatMemoryPlan(const std::vector<BufferPlan>& plan, int width, int height) {
    const double pixels = double(width) * double(height);
    std::string out = fmt::format("{:<28} {:>14} {:>10} {}\n", "buffer", "bytes", "B/pixel", "kind");
    for (const auto& b : plan)
        out += fmt::format("{:<28} {:>14} {:>10.2f} {}\n", b.name, b.bytes, b.bytes / pixels,
                           b.history ? "history" : "scratch");
    size_t total = TotalBytes(plan), hist = HistoryBytes(plan);
    out += fmt::format("{:<28} {:>14} {:>10.2f}\n", "history total", hist, hist / pixels);
    out += fmt::format("{:<28} {:>14} {:>10.2f}\n", "total", total, total / pixels);
    return out;
}

}  // namespace fovrt
