#include "denoise/variants.h"

#include <fmt/format.h>

#include <algorithm>

#include "core/error.h"
#include "core/nearest_name.h"

namespace fovrt {

const std::vector<DenoiserVariant>& DenoiserVariants() {
    using F = DenoiserFamily;
    static const std::vector<DenoiserVariant> rows = {
        {.name = "svgf", .summary = "SVGF (Schied 2017)", .family = F::Svgf},
        {.name = "svgf-weighted",
         .summary = "SVGF with temporal weights x sample count",
         .family = F::Svgf,
         .weightBySampleCount = true,
         .needsSampleCount = true},
        {.name = "asvgf",
         .summary = "A-SVGF temporal gradients (Schied 2018)",
         .family = F::TwoHistory,
         .asvgfGradient = true,
         .needsGradientSamples = true},
        {.name = "two-history",
         .summary = "two-history SVGF (Tu 2024)",
         .family = F::TwoHistory,
         .twoHistory = true,
         .emaGradient = true,
         .needsSampleCount = true},
        {.name = "two-history-asvgf",
         .summary = "two-history SVGF with A-SVGF's gradient as q",
         .family = F::TwoHistory,
         .twoHistory = true,
         .asvgfGradient = true,
         .needsGradientSamples = true,
         .needsSampleCount = true},
        {.name = "rae",
         .summary = "recurrent denoising autoencoder (Chaitanya 2017), denoise.rae.weights",
         .family = F::Rae},
        {.name = "rae-spp",
         .summary = "rae with the per-pixel sample count as an 8th input, denoise.rae.weights_spp",
         .family = F::Rae,
         .raeSampleCount = true},
    };
    return rows;
}

const DenoiserVariant* LookupDenoiserVariant(std::string_view name) {
    for (const DenoiserVariant& v : DenoiserVariants())
        if (v.name == name) return &v;
    return nullptr;
}


std::string UnknownDenoiserMessage(std::string_view name) {
    return fmt::format("unknown denoiser '{}' (did you mean '{}'? known: {})", name, NearestName(name, DenoiserNames()),
                       fmt::join(DenoiserNames(), ", "));
}

const DenoiserVariant& FindDenoiserVariant(std::string_view name, std::string_view what) {
    if (const DenoiserVariant* v = LookupDenoiserVariant(name)) return *v;
    Fail("{}: {}", what, UnknownDenoiserMessage(name));
}

const std::vector<std::string>& DenoiserNames() {
    static const std::vector<std::string> names = [] {
        std::vector<std::string> n;
        for (const DenoiserVariant& v : DenoiserVariants()) n.emplace_back(v.name);
        return n;
    }();
    return names;
}

DenoiserParams ParamsForVariant(const DenoiserVariant& variant, DenoiserParams params) {
    params.svgf.weightBySampleCount = variant.weightBySampleCount;
    if (variant.raeSampleCount) params.rae.weights = params.rae.weightsSpp;
    return params;
}

std::vector<std::string> SvgfChannels(const SvgfParams& params) {
    if (params.filterCombined) return {"combined"};
    return {"direct", "indirect"};
}

}  // namespace fovrt
