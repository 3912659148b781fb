// `fovrt memory`: every buffer a denoiser allocates at W×H (per eye, then for all eyes on one
// device, which share the transient pool and the staging ring), with bytes and bytes/pixel, the
// planes each slot of the transient pool holds, permanent against transient bytes and the peak
// (what the budget is checked against), and what two-history adds over svgf (the thesis: 88 B/pixel in fp32;
// fovrt's default, direct and indirect separate, matches it).
#include <cstdio>
#include <memory>
#include <string>
#include <tuple>

#include <fmt/format.h>

#include "config/config.h"
#include "config/settings_tables.h"
#include "commands.h"
#include "core/error.h"
#include "denoise/denoiser.h"
#include "denoise/denoiser_factory.h"
#include "denoise/memory_plan.h"
#include "denoise/pass_plan.h"
#include "pipeline/denoiser_set.h"

namespace fovrt {

namespace {

struct MemoryOptions {
    int width = 1280;
    int height = 720;
    int eyes = 2;
    std::string denoiser = "two-history";
    std::string precision = "auto";
    std::string device = "auto";  // what precision auto resolves for (denoise.device's forms)
    bool filterCombined = false;
    bool zeroSamples = false;  // the spp map may hold zeros (DenoiserParams::sampleCountsMayBeZero)
    float window = TwoHistoryParams{}.window;  // denoise.two_history.window
    std::string budget;  // bytes for all eyes, "2GiB" style accepted; empty = none
    int scoredFrames = 0;  // > 0: also FovVideoVDP's frames of a scored run of this many frames
};

void PrintMemory(const MemoryOptions& o) {
    DenoiserParams params;
    const Precision requested = ParsePrecision(o.precision, "--precision");
    const DenoiserVariant& variant = FindDenoiserVariant(o.denoiser, "--denoiser");
    const PrecisionTarget target = requested == Precision::Auto ? PlannedPrecisionTarget(o.device) : PrecisionTarget{};
    params.precision = ResolvePrecision(requested, variant, target);
    params.svgf.filterCombined = o.filterCombined;
    params.sampleCountsMayBeZero = o.zeroSamples;
    params.twoHistory.window = o.window;
    ValidateDenoiserParamRanges(params);  // names the key of an out-of-range --window
    const uint64_t budget = o.budget.empty() ? 0 : ParseByteSize(o.budget, "--memory-budget");
    const DenoiserPlan denoiser = BuildDenoiserPlan(o.denoiser, params, o.width, o.height);
    const std::vector<BufferPlan>& plan = denoiser.buffers;
    const double pixels = double(o.width) * double(o.height);
    const std::string storage = requested == Precision::Auto
                                    ? fmt::format("{} (auto, for device {})", PrecisionName(params.precision), o.device)
                                    : o.precision;
    const std::string window =
        variant.twoHistory && o.window < 1.0f ? fmt::format(", weighted history in a window of {:g} per side", o.window) : "";
    std::printf("denoiser %s, %dx%d per eye, %s histories, %s illumination%s%s\n", o.denoiser.c_str(),
                o.width, o.height, storage.c_str(),
                o.filterCombined ? "combined" : "direct + indirect separate",
                o.zeroSamples ? ", spp map may hold zeros" : "", window.c_str());
    std::printf("%s", FormatMemoryPlan(denoiser, o.width, o.height).c_str());
    // The eyes' denoisers take turns with one transient pool and staging ring (vk/shared_buffers.h).
    auto onDevice = [&](const std::vector<BufferPlan>& eye) {
        std::vector<BufferPlan> device;
        for (int e = 0; e < o.eyes; ++e) AddDenoiserOnDevice(device, fmt::format("eye{}.", e), eye);
        return device;
    };
    std::vector<BufferPlan> all = onDevice(plan);
    size_t shared = 0;
    for (const BufferPlan& b : all) shared += b.shared ? b.bytes : 0;
    const size_t total = TotalBytes(all);
    std::printf("all %d eye(s) on one device: peak %zu bytes (%.1f MiB, %.2f B/pixel): own %.1f MiB, "
                "shared by the eyes (transient pool, staging) %.1f MiB\n",
                o.eyes, total, double(total) / 1048576.0, double(total) / (pixels * o.eyes),
                double(total - shared) / 1048576.0, double(shared) / 1048576.0);
    // Extra of two-history over svgf: the thesis counts only the added history planes.
    try {
        auto svgf = PlanDenoiserMemory("svgf", o.width, o.height, params);
        auto two = PlanDenoiserMemory("two-history", o.width, o.height, params);
        double extraHist = (double(HistoryBytes(two)) - double(HistoryBytes(svgf))) / pixels;
        double extraAll = (double(TotalBytes(two)) - double(TotalBytes(svgf))) / pixels;
        const double extraDevice = double(TotalBytes(onDevice(two))) - double(TotalBytes(onDevice(svgf)));
        std::printf("two-history over svgf: +%.1f B/pixel of history (+%.1f B/pixel at one eye's peak), "
                    "%.1f MiB for %d eye(s) on one device\n",
                    extraHist, extraAll, extraDevice / 1048576.0, o.eyes);
        std::printf(
            "  (thesis: +88 B/pixel in fp32, +44 in fp16 = per A/B side float3 weighted\n"
            "   illumination, float2 total weights, float3 gradient, float3 power sums, for one\n"
            "   illumination. fovrt per side: a float3 weighted illumination per filtered\n"
            "   channel, one total weight W_w (W_u is svgf's history length, already counted in\n"
            "   svgf), the gradient as one float (its signed luminance; q uses |lum g|, equal to\n"
            "   the thesis's lum|g| where R, G, B change with one sign, smaller otherwise), float3\n"
            "   power sums: 24+4+4+12 = 44 B with direct and indirect separate (= thesis),\n"
            "   12+4+4+12 = 32 B with --filter-combined; fp16 halves both. The two channels\n"
            "   share one W_u, so against svgf's two lengths the whole history adds 4 B less)\n");
    } catch (const Error& e) {
        std::printf("two-history over svgf: not available (%s)\n", e.what());
    }
    if (o.scoredFrames > 0) {
        // The metric keeps each eye's luminance frames of the reference and of every variant
        // until the sequence is scored (pipeline/denoiser_set.h: PlanVdpMemory).
        RunConfig scored = DefaultConfig();
        scored.camera.width = o.width;
        scored.camera.height = o.height;
        scored.run.frames = o.scoredFrames;
        scored.denoise.denoisers = {o.denoiser};
        std::vector<BufferPlan> vdp = PlanVdpMemory(scored, true, o.eyes);
        std::printf("FovVideoVDP of %d scored frames (run --score, experiment), %d eye(s):\n", o.scoredFrames, o.eyes);
        for (const BufferPlan& b : vdp) std::printf("  %-40s %12zu bytes\n", b.name.c_str(), b.bytes);
        std::printf("  total %zu bytes (%.1f MiB)\n", TotalBytes(vdp), double(TotalBytes(vdp)) / 1048576.0);
        for (BufferPlan& b : vdp) all.push_back(std::move(b));
    }
    EnforceMemoryBudget(all, budget, o.denoiser);
}

}  // namespace

void RegisterMemoryCommand(CLI::App& app) {
    auto o = std::make_shared<MemoryOptions>();
    CLI::App* cmd = app.add_subcommand("memory", "List every denoiser buffer with bytes and bytes/pixel");
    // The sizes camera.width/height accept, so the plan never describes a run the config refuses.
    for (auto [option, key, value] : {std::tuple{"--width", "camera.width", &o->width},
                                      std::tuple{"--height", "camera.height", &o->height}}) {
        const ParamInfo* row = FindRow(CameraTable(), key);
        cmd->add_option(option, *value, fmt::format("Pixels per eye, as {}", key))
            ->check(CLI::Range(int(row->range.min), int(row->range.max)));
    }
    cmd->add_option("--eyes", o->eyes, "Eyes")->check(CLI::Range(1, 2));
    cmd->add_option("--denoiser", o->denoiser, "Denoiser name");
    cmd->add_option("--precision", o->precision,
                    "Storage: fp32, fp16 or auto (as denoise.precision: fp16 on a GPU with 16-bit storage)");
    cmd->add_option("--device", o->device, "With --precision auto: the device it resolves for (as denoise.device)");
    cmd->add_flag("--filter-combined", o->filterCombined, "Plan for direct+indirect filtered together");
    cmd->add_flag("--zero-samples", o->zeroSamples,
                  "Plan for an spp map that may hold zeros (a foveation below 1 spp): svgf, asvgf and "
                  "asvgf-antilag then upload the sample counts");
    cmd->add_option("--window", o->window,
                    "Fraction of each side of the image, centred on the gaze, where two-history keeps its "
                    "weighted history (as denoise.two_history.window; 1: all of it)");
    cmd->add_option("--memory-budget", o->budget, "Fail when all eyes' peak (permanent buffers + transient pool) exceeds BYTES (e.g. 1GiB)");
    cmd->add_option("--scored-frames", o->scoredFrames,
                    "Also list FovVideoVDP's frames when N frames are scored (run --score, experiment)")
        ->check(CLI::Range(0, 1000000));
    cmd->callback([o] { PrintMemory(*o); });
}

}  // namespace fovrt
