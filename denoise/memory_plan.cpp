#include "denoise/memory_plan.h"

#include <algorithm>
#include <set>

#include <fmt/format.h>

#include "core/error.h"
#include "denoise/pass_plan.h"
#include "denoise/transient_pool.h"

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

size_t TransientBytes(const std::vector<BufferPlan>& plan) {
    size_t total = 0;
    for (const auto& b : plan)
        if (b.transient) total += b.bytes;
    return total;
}

void AddDenoiserOnDevice(std::vector<BufferPlan>& device, const std::string& prefix,
                         const std::vector<BufferPlan>& denoiser) {
    for (BufferPlan b : denoiser) {
        if (!b.shared) {
            b.name = prefix + b.name;
            device.push_back(std::move(b));
            continue;
        }
        b.name = "shared." + b.name;
        auto same = std::find_if(device.begin(), device.end(), [&](const BufferPlan& d) { return d.name == b.name; });
        if (same == device.end())
            device.push_back(std::move(b));
        else
            same->bytes = std::max(same->bytes, b.bytes);
    }
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

std::string FormatMemoryPlan(const DenoiserPlan& plan, int width, int height) {
    const double pixels = double(width) * double(height);
    auto row = [&](const std::string& name, size_t bytes, const char* kind) {
        return fmt::format("{:<28} {:>14} {:>10.2f} {}\n", name, bytes, bytes / pixels, kind);
    };
    std::string out = fmt::format("{:<28} {:>14} {:>10} {}\n", "buffer", "bytes", "B/pixel", "kind");
    for (size_t i = 0; i < plan.buffers.size(); ++i) {
        const BufferPlan& b = plan.buffers[i];
        out += row(b.name, b.bytes, b.history ? "history" : b.transient ? "transient" : "scratch");
        if (!b.transient) continue;
        for (const PlanePlacement& p : plan.planes)
            if (p.allocation == i) out += row("  " + BufferName(p.key), p.bytes, "");
    }
    const size_t total = TotalBytes(plan.buffers), history = HistoryBytes(plan.buffers);
    const size_t transient = TransientBytes(plan.buffers);
    out += row("history total", history, "");
    out += row("other permanent", total - history - transient, "");
    out += row("transient pool", transient, "");
    if (!plan.planes.empty()) out += row("  live at once, at most", PeakLiveTransientBytes(plan), "");
    out += row("peak (all allocations)", total, "");
    return out;
}

}  // namespace fovrt
