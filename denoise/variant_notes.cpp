#include "denoise/variant_notes.h"

namespace fovrt {

const std::vector<VariantNote>& VariantNotes() {
    using S = VariantStatus;
    // Full-size figures: docs/experiments.md ("The full protocol with the perceptual metric") and
    // denoise/two_history_stable.md, as published at commit 5c17947 (2026-11-27).
    static const std::vector<VariantNote> notes = {
        {"svgf", "Schied et al. 2017 (SVGF)", S::PaperMethod,
         "the baseline every ratio is taken against; steady in the fovea, no use of the sample count"},
        {"svgf-weighted", "Tu 2024's \"Weighted\" baseline (SVGF with temporal weights × n)", S::CounterExample,
         "only as the thesis's comparison: the lowest foveal error, but its fovea flickers most and the "
         "perceptual metric ranks it below svgf",
         {{"cornell", "×0.74", "×3.34", "−0.046"}, {"veach-ajar", "×0.90", "×2.82", "−0.139"}},
         "5c17947"},
        {"asvgf", "Schied et al. 2018 (A-SVGF)", S::PaperMethod,
         "scenes whose lighting changes (a lamp switching off): the gradient shortens the history; on static "
         "views its alpha 0.1 flickers more than svgf's 0.05",
         {{"cornell", "×1.01 (ns)", "×1.74", "−0.090"}, {"veach-ajar", "×0.95", "×1.64", "−0.459"}},
         "5c17947"},
        {"two-history", "Tu 2024 (two-history SVGF)", S::PaperMethod,
         "reproducing the thesis: the lowest foveal relMSE of the paper methods, with a fovea that flickers "
         "more; perceptually a wash against svgf",
         {{"cornell", "×0.80", "×2.27", "−0.009"}, {"veach-ajar", "×0.93", "×1.64", "+0.008"}},
         "5c17947"},
        {"two-history-asvgf", "Tu 2024 with Schied et al. 2018's gradient as q", S::Experimental,
         "studying the change detector: A-SVGF's gradient in place of two-history's EMA",
         {{"cornell", "×0.80", "×3.25", "−0.094"}, {"veach-ajar", "×0.90", "×2.70", "−0.382"}},
         "5c17947"},
        {"asvgf-antilag", "fovrt: Schied et al. 2018 with Q2RTX's anti-lag and SVGF's base alpha", S::Experimental,
         "changing light without asvgf's extra flicker: follows a light switching off in the switch frame; on "
         "static views it is svgf"},
        {"two-history-asvgf-antilag", "fovrt: two-history-asvgf with Q2RTX's anti-lag", S::Experimental,
         "two-history under changing light"},
        {"two-history-stable", "fovrt: two-history plus a clamped luminance stabilisation pass", S::Recommended,
         "static or slowly changing views at full size: better than svgf on both scenes perceptually; lags "
         "sliding penumbrae (pillars at 320×180: whole-image relMSE ×1.26, −0.12 JOD)",
         {{"cornell", "×0.91", "×0.76", "+0.014"}, {"veach-ajar", "×1.04", "×0.57", "+0.213"}},
         "5c17947"},
        {"two-history-stable-firefly", "fovrt: two-history-stable with firefly suppression", S::CounterExample,
         "not recommended: it helps cornell a little and darkens veach-ajar"},
        {"two-history-stable-antilag", "fovrt: two-history-stable whose stabilisation follows q", S::Experimental,
         "two-history-stable where light changes: halves its loss on pillars at 320×180"},
        {"two-history-asvgf-stable-antilag",
         "fovrt: two-history-asvgf-antilag with the stabilisation driven by A-SVGF's lambda", S::Recommended,
         "the general choice: better than svgf on both thesis scenes and does not lag sliding penumbrae "
         "(pillars at full size +0.30 JOD, though its fovea flickers ×1.5 there)",
         {{"cornell", "×0.88", "×0.79", "+0.013"}, {"veach-ajar", "×0.98", "×0.70", "+0.203"}},
         "5c17947"},
        {"two-history-clamp", "fovrt: two-history with ReLAX-style history clamping in place of p", S::Experimental,
         "trading part of two-history's foveal gain for less flicker along one line (k)"},
        {"two-history-stable-clamp", "fovrt: two-history-clamp plus the stabilisation pass", S::Experimental,
         "as two-history-clamp, steadier"},
        {"two-history-hysteresis", "fovrt: two-history with a held, hysteretic history choice", S::Experimental,
         "cutting two-history's foveal flicker by a quarter to a half, giving back part of its foveal gain"},
        {"two-history-stable-hysteresis", "fovrt: two-history-hysteresis plus the stabilisation pass",
         S::Experimental, "as two-history-stable, with the held choice"},
        {"two-history-asvgf-stable-hysteresis",
         "fovrt: two-history-asvgf-stable-antilag with the held history choice", S::Experimental,
         "as two-history-asvgf-stable-antilag, with a steadier fovea on cornell",
         {{"cornell", "×0.97", "×0.59", "+0.014"}},
         "75cda1d"},
        {"rae", "Chaitanya et al. 2017 (recurrent denoising autoencoder)", S::Experimental,
         "comparing learned against hand-built reconstruction; the committed quarter-width weights (7,200 steps, "
         "2 core-hours on a CPU) are undertrained and pull the light's hue towards grey (+balance restores the "
         "hue, not the JOD): at 320×180 −1.0 JOD against svgf on cornell, −0.28 on veach-ajar "
         "(training/README.md), so it is no fair rival yet"},
        {"rae-spp", "fovrt: Chaitanya et al. 2017 with the sample count as an 8th input", S::Experimental,
         "as rae, with the foveated sample count as an input (10,700 steps, 2.6 core-hours): at 320×180 −1.13 "
         "JOD against svgf on cornell, −0.12 on veach-ajar, −1.54 on pillars"},
    };
    return notes;
}

const VariantNote* FindVariantNote(std::string_view name) {
    for (const VariantNote& note : VariantNotes())
        if (note.name == name) return &note;
    return nullptr;
}

std::string_view VariantStatusName(VariantStatus status) {
    switch (status) {
        case VariantStatus::Recommended: return "recommended";
        case VariantStatus::PaperMethod: return "a paper's method";
        case VariantStatus::Experimental: return "experimental";
        case VariantStatus::CounterExample: return "counter-example";
    }
    return "";
}

}  // namespace fovrt
