// What a reader choosing a denoiser needs beyond its row in DenoiserVariants(): where the method
// comes from, its standing (recommended, a paper's baseline, an experiment, a counter-example),
// when to use it, and its measured full-size results against svgf where they exist. One note per
// variant (denoise_variant_notes_test holds the two tables to each other); docs/denoisers.md is
// generated from both (`fovrt info --denoisers-page`, test docs_denoisers).
#pragma once

#include <optional>
#include <string_view>
#include <vector>

namespace fovrt {

enum class VariantStatus { Recommended, PaperMethod, Experimental, CounterExample };

// Foveal relMSE and foveal flicker as geometric-mean ratios to svgf, JOD as the mean paired
// difference to svgf: the thesis preset at 1280×720, 60 frames, 1024-spp references, seeds 1–3,
// both eyes (docs/experiments.md says how each was run).
struct MeasuredAgainstSvgf {
    std::string_view scene;
    std::string_view foveaRelMse, foveaFlicker, jod;
};

struct VariantNote {
    std::string_view name;
    std::string_view origin;  // the paper it implements, or "fovrt" with what it adds
    VariantStatus status = VariantStatus::Experimental;
    std::string_view whenToUse;
    std::vector<MeasuredAgainstSvgf> measured{};  // empty: not measured at full size
    std::string_view measuredAt{};                // the commit whose docs give the figures
};

const std::vector<VariantNote>& VariantNotes();
// Null for a name without a note.
const VariantNote* FindVariantNote(std::string_view name);
std::string_view VariantStatusName(VariantStatus status);

}  // namespace fovrt
