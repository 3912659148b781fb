#include "denoise/debug_views.h"

#include <algorithm>
#include <limits>

#include "core/math.h"
#include "denoise/denoiser.h"
#include "denoise/reference/two_history_math.h"
#include "denoise/variants.h"

namespace fovrt {

const std::vector<DebugView>& DebugViewTable() {
    constexpr float kUnbounded = std::numeric_limits<float>::infinity();
    static const std::vector<DebugView> rows = {
        {.id = DebugViewId::HistoryLength,
         .name = "historyLength",
         .meaning = "frames in the temporal history: SVGF's history length (at most 64), the "
                    "two-history family's W_u (saturates at 1/alpha); 1 where it was dropped",
         .lo = 1.0f,
         .hi = kUnbounded},
        {.id = DebugViewId::HistorySamples,
         .name = "historySamples",
         .meaning = "samples in the weighted history, sum of beta^(t-i) n_i: svgf-weighted's W, "
                    "two-history's W_w",
         .lo = 1.0f,
         .hi = kUnbounded},
        {.id = DebugViewId::Alpha,
         .name = "alpha",
         .meaning = "A-SVGF's temporal alpha_i = (1 - lambda) alpha + lambda of colour and "
                    "moments (1 on a frame without a previous one)"},
        {.id = DebugViewId::Antilag,
         .name = "antilag",
         .meaning = "anti-lag factor a = clamp(gain lambda, 0, 1): the history length shrinks by "
                    "(1 - a)^power and alpha = lerp(warm-up alpha, 1, a) (1 on a frame without a previous one)"},
        {.id = DebugViewId::Lambda,
         .name = "lambda",
         .meaning = "A-SVGF's lambda = min(1, |delta|/Delta) of the reconstructed temporal "
                    "gradient, max over 3x3 strata"},
        {.id = DebugViewId::P,
         .name = "p",
         .meaning = "two-history's variance-optimal blend factor: I_opt = lerp(I_w, I_u, p) (the hysteresis "
                    "variants: the held choice the blend uses)"},
        {.id = DebugViewId::Q,
         .name = "q",
         .meaning = "two-history's gradient-guided blend factor: I_b = lerp(I_opt, I_u, q) "
                    "(two-history-asvgf: A-SVGF's lambda)"},
        {.id = DebugViewId::T,
         .name = "t",
         .meaning = "two-history's history choice t = p + q - pq: I_b = lerp(I_w, I_u, t), 1 takes "
                    "the unweighted history"},
        {.id = DebugViewId::HistoryU,
         .name = "historyU",
         .meaning = "luminance of the unweighted colour history I_u (after the a-trous feedback; "
                    "the first channel: direct, or combined)",
         .lo = 0.0f,
         .hi = kUnbounded},
        {.id = DebugViewId::HistoryW,
         .name = "historyW",
         .meaning = "luminance of the sample-count-weighted colour history I_w (the first channel)",
         .lo = 0.0f,
         .hi = kUnbounded},
        {.id = DebugViewId::Variance,
         .name = "variance",
         .meaning = "variance m2 - m1^2 of the unweighted luminance moments, the edge-stopping "
                    "guide of both histories (the first channel)",
         .lo = 0.0f,
         .hi = kUnbounded},
        {.id = DebugViewId::StableLum,
         .name = "stableLum",
         .meaning = "two-history-stable's stabilised luminance L_s of the filtered illumination "
                    "(the first channel)",
         .lo = 0.0f,
         .hi = kUnbounded},
    };
    return rows;
}

namespace {
bool Offers(const DenoiserVariant& variant, DebugViewId id) {
    const std::vector<DebugViewId> views = VariantDebugViews(variant);
    return std::find(views.begin(), views.end(), id) != views.end();
}
}  // namespace

std::vector<std::string> DebugViewNames(const DenoiserVariant& variant) {
    std::vector<std::string> names;
    for (const DebugView& view : DebugViewTable())
        if (Offers(variant, view.id)) names.emplace_back(view.name);
    return names;
}

const DebugView* FindDebugView(const DenoiserVariant& variant, std::string_view name) {
    for (const DebugView& view : DebugViewTable())
        if (view.name == name) return Offers(variant, view.id) ? &view : nullptr;
    return nullptr;
}

// The Denoiser side (denoise/denoiser.h): names and the unknown-name rule once, for every host.
std::vector<std::string> Denoiser::DebugViews() const {
    const DenoiserVariant* variant = LookupDenoiserVariant(Name());
    return variant ? DebugViewNames(*variant) : std::vector<std::string>{};
}

bool Denoiser::ReadDebugView(const std::string& name, Plane<float>& out) {
    const DenoiserVariant* variant = LookupDenoiserVariant(Name());
    const DebugView* view = variant ? FindDebugView(*variant, name) : nullptr;
    if (!view) return false;
    if (view->id != DebugViewId::T) return ReadDebugPlane(view->id, out);
    // Not a plane: the blend combines p and q as it goes (two_history_math.h).
    Plane<float> p, q;
    if (!ReadDebugPlane(DebugViewId::P, p) || !ReadDebugPlane(DebugViewId::Q, q)) return false;
    for (size_t i = 0; i < p.size(); ++i) p[i] = TwoHistoryFinalBlend(p[i], q[i]);
    out = std::move(p);
    return true;
}

int DebugViewComponents(DebugViewId view) {
    switch (view) {
        case DebugViewId::HistoryU:
        case DebugViewId::HistoryW: return 3;
        case DebugViewId::Variance: return 2;
        default: return 1;
    }
}

float ReduceDebugPixel(DebugViewId view, const float* c) {
    switch (DebugViewComponents(view)) {
        case 3: return Luminance(vec3(c[0], c[1], c[2]));
        case 2: return std::max(0.0f, c[1] - c[0] * c[0]);
        default: return c[0];
    }
}

}  // namespace fovrt
