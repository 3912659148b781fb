// `fovrt info`: versions of fovrt and the libraries it was built with, the Vulkan devices the
// loader reports (the indices `--set denoise.device=<index>` accepts), the CPU thread count and model, and
// the denoiser variants with one line each (denoise/variants.cpp). `--denoiser NAME`: one variant —
// its family and mechanisms, what it needs from the renderer, its passes in recording order and
// its memory plan (every plane, bytes per pixel) at --width × --height.
#include <algorithm>
#include <cstdio>
#include <thread>

#include <string>

#include <fmt/format.h>

#include "app/commands.h"
#include "core/error.h"
#include "denoise/denoiser_factory.h"
#include "denoise/memory_plan.h"
#include "denoise/pass_plan.h"
#include "denoise/variants.h"
#include "pipeline/build_info.h"
#include "vk/context.h"

namespace fovrt {

namespace {

struct InfoOptions {
    std::string denoiser;  // --denoiser NAME: describe one variant instead
    int width = 1280, height = 720;
};

std::string Joined(const std::vector<std::string>& items, const char* none) {
    return items.empty() ? std::string(none) : fmt::format("{}", fmt::join(items, "; "));
}

const char* WhenText(When when) {
    switch (when) {
        case When::Always: return "";
        case When::HasPrevious: return " (with a previous frame)";
        case When::NoPrevious: return " (first frame after a reset)";
        case When::GradientSamples: return " (with gradient samples)";
    }
    return "";
}

// `fovrt info --denoiser NAME`: the variant as the pass plan and the memory plan see it.
void PrintDenoiser(const InfoOptions& o) {
    const DenoiserVariant& v = FindDenoiserVariant(o.denoiser, "--denoiser");
    if (o.width < 1 || o.height < 1 || o.width > 16384 || o.height > 16384)
        Fail("--width/--height: {}x{} is outside 1..16384", o.width, o.height);
    const DenoiserParams params = ParamsForDenoiser(o.denoiser, DenoiserParams{});
    const DenoiserPlan plan = BuildDenoiserPlan(v.name, params, o.width, o.height);
    const char* families[] = {"svgf", "two-history", "rae"};
    std::printf("denoiser    %s\n", o.denoiser.c_str());
    std::printf("summary     %.*s\n", int(v.summary.size()), v.summary.data());
    std::printf("family      %s\n", families[int(v.family)]);
    std::printf("mechanisms  %s\n", Joined(VariantMechanisms(v), "none beyond the family's passes").c_str());
    if (std::optional<Demodulation> d = DenoiserDemodulation(o.denoiser))
        std::printf("demodulation %s (re-demodulated before filtering)\n",
                    *d == Demodulation::Brdf ? "BRDF pre-integration F_beta" : "albedo");
    std::printf("renderer    %s\n", Joined(VariantRendererNeeds(v), "the noisy inputs alone").c_str());
    std::printf("passes      (recording order; default parameters)\n");
    for (const PlannedPass& pass : plan.passes)
        if (!pass.name.empty()) std::printf("  %s%s\n", pass.name.c_str(), WhenText(pass.when));
    std::printf("memory per eye at %dx%d\n%s", o.width, o.height, FormatMemoryPlan(plan.buffers, o.width, o.height).c_str());
}

}  // namespace

void RegisterInfoCommand(CLI::App& app) {
    CLI::App* cmd = app.add_subcommand("info", "Print versions, Vulkan devices and build settings; "
                                               "--denoiser NAME: one denoiser's mechanisms, passes and memory");
    auto options = std::make_shared<InfoOptions>();
    cmd->add_option("--denoiser", options->denoiser,
                    "Describe one denoiser: family, mechanisms, renderer needs, passes, planes and bytes per pixel");
    cmd->add_option("--width", options->width, "With --denoiser: the eye width of the memory plan (default 1280)");
    cmd->add_option("--height", options->height, "With --denoiser: the eye height of the memory plan (default 720)");
    cmd->callback([options] {
        if (!options->denoiser.empty()) {
            PrintDenoiser(*options);
            return;
        }
        const nlohmann::json build = BuildInfoJson();  // items() must not outlive its object
        for (const auto& [key, value] : build.items())
            std::printf("%-16s %s\n", key.c_str(), value.get<std::string>().c_str());
        std::printf("%-16s %u\n", "cpu threads", std::thread::hardware_concurrency());
        std::printf("%-16s %s\n", "machine", FormatCpu(DescribeCpu()).c_str());  // the benchmark scripts' header
        auto devices = VulkanContext::ListDevices();
        if (devices.empty()) std::printf("vulkan devices   none (denoisers fall back to the C++ reference)\n");
        for (const VulkanDeviceInfo& d : devices)
            std::printf("vulkan device %u  %s (%s)\n", d.index, d.name.c_str(), d.type.c_str());
        int nameWidth = 0;  // the names in one column, as wide as the longest
        for (const DenoiserVariant& v : DenoiserVariants()) nameWidth = std::max(nameWidth, int(v.name.size()));
        for (const DenoiserVariant& v : DenoiserVariants())  // the names denoise.denoisers accepts
            std::printf("denoiser         %-*.*s %.*s\n", nameWidth, int(v.name.size()), v.name.data(),
                        int(v.summary.size()), v.summary.data());
    });
}

}  // namespace fovrt
