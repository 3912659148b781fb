#include "denoise/variants.h"

#include <fmt/format.h>

#include <algorithm>
#include <deque>
#include <mutex>
#include <span>

#include "core/check.h"
#include "core/error.h"
#include "core/nearest_name.h"
#include "denoise/debug_views.h"
#include "denoise/params.h"
#include "denoise/planes.h"

namespace fovrt {

namespace {

// The families a name starts from (any position in it; exactly one). A family's own mechanisms
// are implied: two-history keeps the second, sample-count-weighted history and, unless A-SVGF's
// gradient replaces it, the EMA luminance gradient as its change detector q.
enum class MethodFamily : uint8_t { Svgf, TwoHistory, Rae };
using Settings = std::span<const std::string_view>;
using Planes = std::span<const PlaneKind>;
using Views = std::span<const DebugViewId>;
// A family: its token, its summary, and what its own passes bring before any mechanism: the
// settings they read (the precision and device: every denoiser's), the planes of the plane table
// they name (none for the RAE, whose tensors are its own) and the debug views they offer.
struct FamilyToken {
    MethodFamily family;
    std::string_view token;
    std::string_view summary;
    Settings settings;
    Planes planes = {};
    Views views = {};
};
constexpr std::string_view kSvgfSettings[] = {
    "denoise.svgf.alpha_color",     "denoise.svgf.alpha_moments",   "denoise.svgf.atrous_iterations",
    "denoise.svgf.feedback_iteration", "denoise.svgf.sigma_depth",  "denoise.svgf.sigma_normal",
    "denoise.svgf.sigma_luminance", "denoise.svgf.variance_history_threshold", "denoise.svgf.filter_combined"};
constexpr std::string_view kRaeSettings[] = {"denoise.rae.weights"};
// Upload, guide, reprojection, variance estimate, à-trous, modulation, download.
constexpr PlaneKind kSvgfPlanes[] = {
    PlaneKind::Direct,      PlaneKind::Indirect,    PlaneKind::Modulation, PlaneKind::Emission,
    PlaneKind::DepthGradient, PlaneKind::PrevPixel, PlaneKind::Normal,     PlaneKind::Depth,
    PlaneKind::ObjectId,    PlaneKind::Guide,       PlaneKind::Color,      PlaneKind::Moments,
    PlaneKind::Length,      PlaneKind::Illum0,      PlaneKind::Illum1,     PlaneKind::SpatialList,
    PlaneKind::SpatialArgs, PlaneKind::Output,      PlaneKind::Stats,      PlaneKind::Staging};
constexpr DebugViewId kSvgfViews[] = {DebugViewId::HistoryLength};
constexpr FamilyToken kFamilies[] = {
    {MethodFamily::Svgf, "svgf", "SVGF (Schied 2017)", kSvgfSettings, kSvgfPlanes, kSvgfViews},
    {MethodFamily::TwoHistory, "two-history", "two-history SVGF (Tu 2024)", kSvgfSettings, kSvgfPlanes, kSvgfViews},
    {MethodFamily::Rae, "rae", "recurrent denoising autoencoder (Chaitanya 2017), denoise.rae.weights", kRaeSettings},
};
constexpr unsigned Bit(MethodFamily f) { return 1u << unsigned(f); }
constexpr unsigned kSvgfFamilies = Bit(MethodFamily::Svgf) | Bit(MethodFamily::TwoHistory);

// One row per mechanism flag of DenoiserVariant, in the order a frame runs them: the unit a
// mechanism is. The token a name writes it with (empty: implied by the family, or derived), what
// `fovrt info` calls it, and its rules: the families it joins, the token it requires, the token it
// excludes, each with the reason a refusal gives. Then what it brings: the settings it reads and
// those of the rows before it that it makes unread (A-SVGF's per-pixel alpha replaces SVGF's;
// anti-lag returns to SVGF's as its base); the planes its passes add to the family's (the plane
// table, denoise/planes.h); the debug views it offers and those of the rows before it it takes
// away (the clamp has no p); the token with which it changes nothing, and why (its settings are
// then unread too); and its plan fragment, the passes of its own it adds at a slot of the frame
// (denoise/mechanism_slots.h; none for a mechanism that switches a mode of a family pass).
// denoise_settings_test holds the settings to what changes the output of every composition,
// denoise_pass_plan_test the planes to what its plan names and the fragment to where its passes
// run, and the debug-view tests the views to what both backends read.
struct Mechanism {
    bool DenoiserVariant::*flag;
    std::string_view token;
    std::string_view description;
    unsigned families = 0;
    std::string_view requiresToken = {};
    std::string_view excludesToken = {};
    std::string_view why = {};  // the reason behind `requiresToken` / `excludesToken`
    Settings reads = {};
    Settings replaces = {};
    Planes planes = {};
    Views views = {};
    Views hidesViews = {};
    std::string_view inertWith = {};
    std::string_view inertWhy = {};
    MechanismPasses passes = {};
};
constexpr std::string_view kSvgfAlpha[] = {"denoise.svgf.alpha_color", "denoise.svgf.alpha_moments"};
constexpr std::string_view kAsvgfAlpha[] = {"denoise.asvgf.alpha"};
constexpr std::string_view kAsvgfSettings[] = {"denoise.asvgf.alpha", "denoise.asvgf.gradient_iterations"};
constexpr std::string_view kAntilagSettings[] = {"denoise.asvgf.antilag_gain", "denoise.asvgf.antilag_power",
                                                 "denoise.svgf.alpha_color", "denoise.svgf.alpha_moments"};
constexpr std::string_view kFireflySettings[] = {"denoise.two_history.firefly_sigma"};
constexpr std::string_view kTwoHistorySettings[] = {"denoise.two_history.window"};
constexpr std::string_view kEmaGradientSettings[] = {"denoise.two_history.gradient_beta", "denoise.two_history.q_scale"};
constexpr std::string_view kHysteresisSettings[] = {"denoise.two_history.choice_rate", "denoise.two_history.choice_band"};
constexpr std::string_view kClampSettings[] = {"denoise.two_history.clamp_sigma"};
constexpr std::string_view kStabilizeSettings[] = {"denoise.two_history_stable.alpha",
                                                   "denoise.two_history_stable.sigma_scale"};
constexpr std::string_view kStabilizeAntilagSettings[] = {"denoise.two_history_stable.antilag_q"};
constexpr std::string_view kSppSettings[] = {"denoise.rae.weights_spp"};
constexpr std::string_view kRaeWeights[] = {"denoise.rae.weights"};
using K = PlaneKind;
using D = DebugViewId;
constexpr PlaneKind kWeightedPlanes[] = {K::SampleCount, K::Weight};
constexpr PlaneKind kAsvgfPlanes[] = {K::AsvgfSamples, K::AsvgfClaim, K::AsvgfGrad0, K::AsvgfGrad1,
                                      K::AsvgfGuideGeometry, K::AsvgfGuideLuminance, K::AsvgfSigma,
                                      K::AsvgfAlpha, K::AsvgfLambda};
constexpr PlaneKind kTwoHistoryPlanes[] = {K::SampleCount, K::WColor, K::WIllum0, K::WIllum1, K::WWeight, K::PowerSums};
constexpr PlaneKind kEmaGradientPlanes[] = {K::Gradient, K::Q};
constexpr PlaneKind kChoicePlanes[] = {K::Choice};
constexpr PlaneKind kStabilizePlanes[] = {K::StableLum};
constexpr DebugViewId kWeightedViews[] = {D::HistorySamples};
constexpr DebugViewId kAsvgfViews[] = {D::Alpha, D::Lambda};
constexpr DebugViewId kAntilagViews[] = {D::Antilag};
constexpr DebugViewId kAlphaView[] = {D::Alpha};
constexpr DebugViewId kTwoHistoryViews[] = {D::HistorySamples, D::P, D::Q, D::T, D::HistoryU, D::HistoryW, D::Variance};
constexpr DebugViewId kChoiceViews[] = {D::P, D::T};
constexpr DebugViewId kStabilizeViews[] = {D::StableLum};
const Mechanism kMechanisms[] = {
    {.flag = &DenoiserVariant::weightBySampleCount, .token = "weighted",
     .description = "temporal weights x sample count (svgf-weighted)", .families = Bit(MethodFamily::Svgf),
     .excludesToken = "asvgf", .why = "the sample-count weights are SVGF's reprojection's, A-SVGF runs the gradient family's",
     .planes = kWeightedPlanes, .views = kWeightedViews},
    {.flag = &DenoiserVariant::asvgfGradient, .token = "asvgf",
     .description = "A-SVGF temporal gradient -> per-pixel alpha (Schied 2018)", .families = kSvgfFamilies,
     .reads = kAsvgfSettings, .replaces = kSvgfAlpha, .planes = kAsvgfPlanes, .views = kAsvgfViews,
     .passes = {FrameSlot::BeforeGuide, MechanismPass::AsvgfGradient}},
    {.flag = &DenoiserVariant::antilag, .token = "antilag", .description = "anti-lag: lambda shortens the history (Q2RTX)",
     .families = kSvgfFamilies, .requiresToken = "asvgf", .why = "the anti-lag factor is A-SVGF's lambda",
     .reads = kAntilagSettings, .replaces = kAsvgfAlpha, .views = kAntilagViews, .hidesViews = kAlphaView},
    {.flag = &DenoiserVariant::suppressFireflies, .token = "firefly",
     .description = "firefly suppression before accumulation", .families = Bit(MethodFamily::TwoHistory),
     .reads = kFireflySettings},
    {.flag = &DenoiserVariant::twoHistory, .token = {},
     .description = "second, sample-count-weighted history and the variance-optimal blend (Tu 2024)",
     .reads = kTwoHistorySettings, .planes = kTwoHistoryPlanes, .views = kTwoHistoryViews},
    {.flag = &DenoiserVariant::emaGradient, .token = {}, .description = "EMA luminance gradient -> q (Tu 2024)",
     .reads = kEmaGradientSettings, .planes = kEmaGradientPlanes, .passes = {FrameSlot::AfterVariance, MechanismPass::EmaGradient}},
    {.flag = &DenoiserVariant::hystereticChoice, .token = "hysteresis",
     .description = "held history choice (band and rate)", .families = Bit(MethodFamily::TwoHistory),
     .excludesToken = "clamp", .why = "both replace the choice p between the two histories",
     .reads = kHysteresisSettings, .planes = kChoicePlanes, .passes = {FrameSlot::BeforeBlend, MechanismPass::HeldChoice}},
    {.flag = &DenoiserVariant::clampHistory, .token = "clamp",
     .description = "history clamp to the weighted history's neighbourhood", .families = Bit(MethodFamily::TwoHistory),
     .reads = kClampSettings, .hidesViews = kChoiceViews},
    {.flag = &DenoiserVariant::stabilize, .token = "stabilize", .description = "luminance stabilisation pass",
     .families = Bit(MethodFamily::TwoHistory), .reads = kStabilizeSettings, .planes = kStabilizePlanes,
     .views = kStabilizeViews, .passes = {FrameSlot::AfterFilter, MechanismPass::Stabilize}},
    {.flag = &DenoiserVariant::stabilizeAntilag, .token = "stabilize-antilag",
     .description = "stabilisation weight driven by the change detector", .families = Bit(MethodFamily::TwoHistory),
     .requiresToken = "stabilize", .why = "it drives the stabilisation's weight", .reads = kStabilizeAntilagSettings,
     .inertWith = "asvgf",
     .inertWhy = "with A-SVGF's gradient as q the weight max(alpha_s, 1/W_u) is already at least lambda = q, above "
                 "the change weight (q - q0)/(1 - q0): the accumulation's alpha is at least lambda while "
                 "denoise.asvgf.antilag_gain >= 1"},
    {.flag = &DenoiserVariant::raeSampleCount, .token = "spp", .description = "sample count as an extra network input",
     .families = Bit(MethodFamily::Rae), .reads = kSppSettings, .replaces = kRaeWeights},
    {.flag = &DenoiserVariant::raeBalance, .token = "balance",
     .description = "input balanced to grey by per-channel gains from the frame's mean illumination, undone on the "
                    "output (a colour cast passes through)",
     .families = Bit(MethodFamily::Rae)},
};

// Today's names: aliases of compositions, each with the summary it had as a row of its own.
struct Alias {
    std::string_view name, composition, summary;
};
constexpr Alias kAliases[] = {
    {"svgf", "svgf", "SVGF (Schied 2017)"},
    {"svgf-weighted", "svgf+weighted", "SVGF with temporal weights x sample count"},
    {"asvgf", "svgf+asvgf", "A-SVGF temporal gradients (Schied 2018)"},
    {"two-history", "two-history", "two-history SVGF (Tu 2024)"},
    {"two-history-asvgf", "two-history+asvgf", "two-history SVGF with A-SVGF's gradient as q"},
    {"asvgf-antilag", "svgf+asvgf+antilag",
     "A-SVGF with gradient-driven history-length reduction (Q2RTX anti-lag), SVGF's base alpha"},
    {"two-history-asvgf-antilag", "two-history+asvgf+antilag",
     "two-history-asvgf with the anti-lag history-length reduction"},
    {"two-history-stable", "two-history+stabilize",
     "two-history SVGF with a clamped luminance stabilisation pass (less flicker)"},
    {"two-history-stable-firefly", "two-history+firefly+stabilize",
     "two-history-stable with firefly suppression before accumulation (outliers vs their past and neighbours "
     "clamped)"},
    {"two-history-stable-antilag", "two-history+stabilize+stabilize-antilag",
     "two-history-stable whose stabilisation follows two-history's change detector q (no lag under changing "
     "light)"},
    {"two-history-asvgf-stable-antilag", "two-history+asvgf+antilag+stabilize+stabilize-antilag",
     "two-history-asvgf-antilag with the stabilisation pass, its weight driven by A-SVGF's lambda"},
    {"two-history-clamp", "two-history+clamp",
     "two-history with I_u clamped to I_w's neighbourhood (mean +- k sigma) instead of the choice p"},
    {"two-history-stable-clamp", "two-history+clamp+stabilize",
     "two-history-clamp with two-history-stable's luminance stabilisation pass"},
    {"two-history-hysteresis", "two-history+hysteresis",
     "two-history with a temporally filtered, hysteretic history choice p (held within a band, moved at a rate)"},
    {"two-history-stable-hysteresis", "two-history+hysteresis+stabilize",
     "two-history-hysteresis with two-history-stable's luminance stabilisation pass"},
    {"two-history-asvgf-stable-hysteresis", "two-history+asvgf+antilag+hysteresis+stabilize+stabilize-antilag",
     "two-history-asvgf-stable-antilag with the held history choice of two-history-hysteresis"},
    {"rae", "rae", "recurrent denoising autoencoder (Chaitanya 2017), denoise.rae.weights"},
    {"rae-spp", "rae+spp", "rae with the per-pixel sample count as an 8th input, denoise.rae.weights_spp"},
};

std::vector<std::string_view> SplitTokens(std::string_view name) {
    std::vector<std::string_view> tokens;
    for (size_t start = 0;;) {
        const size_t plus = name.find('+', start);
        tokens.push_back(name.substr(start, plus == std::string_view::npos ? plus : plus - start));
        if (plus == std::string_view::npos) return tokens;
        start = plus + 1;
    }
}

const Alias* FindAlias(std::string_view name) {
    for (const Alias& a : kAliases)
        if (a.name == name) return &a;
    return nullptr;
}

// Every token a name may hold, for suggestions.
std::vector<std::string> KnownTokens() {
    std::vector<std::string> tokens;
    for (const FamilyToken& f : kFamilies) tokens.emplace_back(f.token);
    for (const Mechanism& m : kMechanisms)
        if (!m.token.empty()) tokens.emplace_back(m.token);
    for (const Alias& a : kAliases) tokens.emplace_back(a.name);
    for (const char* d : DemodulationNames()) tokens.emplace_back(d);
    return tokens;
}

// A name read into its family, mechanisms and demodulation.
struct Composition {
    std::optional<MethodFamily> family;
    std::vector<bool> mechanisms = std::vector<bool>(std::size(kMechanisms), false);
    std::optional<Demodulation> demodulation;
};

bool Has(const Composition& c, std::string_view token) {
    for (size_t i = 0; i < std::size(kMechanisms); ++i)
        if (c.mechanisms[i] && kMechanisms[i].token == token) return true;
    return false;
}

// Reads `name`'s tokens (a family, mechanisms, a demodulation, or an alias standing for its
// composition; in any order) and checks the rules; the problem in one line otherwise.
std::optional<std::string> Read(std::string_view name, Composition& c) {
    auto setFamily = [&](MethodFamily f) -> std::optional<std::string> {
        if (c.family && *c.family != f) return fmt::format("'{}' names two families; a name has one", name);
        c.family = f;
        return std::nullopt;
    };
    auto isMechanism = [](std::string_view token) {
        return std::any_of(std::begin(kMechanisms), std::end(kMechanisms),
                           [&](const Mechanism& m) { return !m.token.empty() && m.token == token; });
    };
    auto isFamily = [](std::string_view token) {
        return std::any_of(std::begin(kFamilies), std::end(kFamilies), [&](const FamilyToken& f) { return f.token == token; });
    };
    // "asvgf" is both a mechanism and the alias of svgf+asvgf: the alias where nothing else in the
    // name gives the family ("asvgf+antilag"), the mechanism where something does ("two-history+asvgf").
    const std::vector<std::string_view> tokens = SplitTokens(name);
    const bool familyElsewhere = std::any_of(tokens.begin(), tokens.end(), [&](std::string_view t) {
        return isFamily(t) || (FindAlias(t) && !isMechanism(t));
    });
    for (std::string_view token : tokens) {
        if (token.empty()) return fmt::format("'{}' has an empty part between '+'", name);
        const Alias* alias = FindAlias(token);
        if (alias && alias->composition != token && !(isMechanism(token) && familyElsewhere)) {
            Composition inner;
            if (auto problem = Read(alias->composition, inner)) return problem;
            if (auto problem = setFamily(*inner.family)) return problem;
            for (size_t i = 0; i < inner.mechanisms.size(); ++i) c.mechanisms[i] = c.mechanisms[i] || inner.mechanisms[i];
            continue;
        }
        bool known = false;
        for (const FamilyToken& f : kFamilies)
            if (f.token == token) {
                if (auto problem = setFamily(f.family)) return problem;
                known = true;
            }
        for (size_t i = 0; i < std::size(kMechanisms); ++i)
            if (!kMechanisms[i].token.empty() && kMechanisms[i].token == token) {
                c.mechanisms[i] = true;
                known = true;
            }
        Demodulation d;
        if (ParseDemodulation(token, d)) {
            if (c.demodulation && *c.demodulation != d)
                return fmt::format("'{}' names two demodulations; a name has at most one", name);
            c.demodulation = d;
            known = true;
        }
        if (!known)
            return fmt::format("unknown denoiser '{}'{} (did you mean '{}'? known names: {}; or a family ({}) and "
                               "mechanisms joined by '+': {}; each also +brdf or +albedo)",
                               name,
                               tokens.size() > 1 ? fmt::format(": '{}' is no family, mechanism or demodulation", token)
                                                 : std::string(),
                               NearestName(token, KnownTokens()), fmt::join(DenoiserNames(), ", "),
                               fmt::join(FamilyTokens(), ", "), fmt::join(MechanismTokens(), ", "));
    }
    if (!c.family)
        return fmt::format("'{}' names no family: start from one of {}", name, fmt::join(FamilyTokens(), ", "));
    for (size_t i = 0; i < std::size(kMechanisms); ++i) {
        if (!c.mechanisms[i]) continue;
        const Mechanism& m = kMechanisms[i];
        if (!(m.families & Bit(*c.family)))
            return fmt::format("'{}': {} does not join the {} family ({})", name, m.token,
                               kFamilies[size_t(*c.family)].token, m.description);
        if (!m.requiresToken.empty() && !Has(c, m.requiresToken))
            return fmt::format("'{}': {} requires {} ({})", name, m.token, m.requiresToken, m.why);
        if (!m.excludesToken.empty() && Has(c, m.excludesToken))
            return fmt::format("'{}': {} excludes {} ({})", name, m.token, m.excludesToken, m.why);
    }
    // The network's weights were trained on albedo-demodulated illumination (Chaitanya et al. 2017,
    // §3.2); F_β input would need weights trained on it.
    if (*c.family == MethodFamily::Rae && c.demodulation == Demodulation::Brdf)
        return fmt::format("'{}': the RAE's weights were trained on albedo-demodulated illumination; use it "
                           "without +brdf (it re-divides an F_beta-demodulated frame by the albedo itself)",
                           name);
    return std::nullopt;
}

std::string CanonicalBaseName(const Composition& c) {
    std::string name(kFamilies[size_t(*c.family)].token);
    for (size_t i = 0; i < std::size(kMechanisms); ++i)
        if (c.mechanisms[i] && !kMechanisms[i].token.empty()) name.append("+").append(kMechanisms[i].token);
    return name;
}

// The row a composition runs as: its mechanisms' flags, the ones its family implies, and what the
// renderer must produce, derived from them.
DenoiserVariant Derive(const Composition& c) {
    DenoiserVariant v;
    for (size_t i = 0; i < std::size(kMechanisms); ++i)
        if (c.mechanisms[i]) v.*kMechanisms[i].flag = true;
    v.twoHistory = *c.family == MethodFamily::TwoHistory;
    v.emaGradient = v.twoHistory && !v.asvgfGradient;
    v.family = *c.family == MethodFamily::Rae                  ? DenoiserFamily::Rae
               : v.twoHistory || v.asvgfGradient ? DenoiserFamily::TwoHistory
                                                               : DenoiserFamily::Svgf;
    v.needsGradientSamples = v.asvgfGradient;
    v.needsSampleCount = v.twoHistory || v.weightBySampleCount;
    return v;
}

Composition MustRead(std::string_view name) {
    Composition c;
    if (std::optional<std::string> problem = Read(name, c)) Fail("denoiser table: {}", *problem);
    return c;
}

// Compositions that are no alias, made once per canonical name and kept (the denoisers hold
// references to their row).
struct ComposedRows {
    std::mutex mutex;
    std::deque<DenoiserVariant> rows;
    std::deque<std::string> text;  // the rows' names and summaries
};
ComposedRows& Composed() {
    static ComposedRows composed;
    return composed;
}

}  // namespace

std::vector<std::string> FamilyTokens() {
    std::vector<std::string> tokens;
    for (const FamilyToken& f : kFamilies) tokens.emplace_back(f.token);
    return tokens;
}

std::vector<std::string> MechanismRules() {
    std::vector<std::string> lines;
    for (const Mechanism& m : kMechanisms) {
        if (m.token.empty()) continue;
        std::vector<std::string_view> families;
        for (const FamilyToken& f : kFamilies)
            if (m.families & Bit(f.family)) families.push_back(f.token);
        std::string line = fmt::format("`{}`: {}; joins {}", m.token, m.description, fmt::join(families, ", "));
        if (!m.requiresToken.empty()) line += fmt::format("; requires `{}` ({})", m.requiresToken, m.why);
        if (!m.excludesToken.empty()) line += fmt::format("; excludes `{}` ({})", m.excludesToken, m.why);
        if (!m.inertWith.empty()) line += fmt::format("; changes nothing with `{}` ({})", m.inertWith, m.inertWhy);
        lines.push_back(std::move(line));
    }
    return lines;
}

std::vector<std::string> MechanismTokens() {
    std::vector<std::string> tokens;
    for (const Mechanism& m : kMechanisms)
        if (!m.token.empty()) tokens.emplace_back(m.token);
    return tokens;
}

const std::vector<DenoiserVariant>& DenoiserVariants() {
    static const std::vector<DenoiserVariant> rows = [] {
        std::vector<DenoiserVariant> out;
        for (const Alias& a : kAliases) {
            DenoiserVariant v = Derive(MustRead(a.composition));
            v.name = a.name;
            v.summary = a.summary;
            out.push_back(v);
        }
        return out;
    }();
    return rows;
}

std::string CanonicalDenoiserName(std::string_view name) {
    Composition c;
    if (std::optional<std::string> problem = Read(name, c)) Fail("denoiser: {}", *problem);
    std::string canonical = CanonicalBaseName(c);
    if (c.demodulation) canonical.append("+").append(DemodulationName(*c.demodulation));
    return canonical;
}

std::vector<std::string> DenoiserCompositions() {
    std::vector<std::string> names;
    const size_t tokens = std::size(kMechanisms);
    for (const FamilyToken& f : kFamilies)
        for (size_t mask = 0; mask < (size_t(1) << tokens); ++mask) {
            std::string name(f.token);
            bool skip = false;
            for (size_t i = 0; i < tokens; ++i)
                if (mask >> i & 1) {
                    if (kMechanisms[i].token.empty()) skip = true;
                    else name.append("+").append(kMechanisms[i].token);
                }
            Composition c;
            if (!skip && !Read(name, c)) names.push_back(name);
        }
    return names;
}

std::optional<Demodulation> DenoiserDemodulation(std::string_view name) {
    Demodulation d;
    for (std::string_view token : SplitTokens(name))
        if (ParseDemodulation(token, d)) return d;
    return std::nullopt;
}

const DenoiserVariant* LookupDenoiserVariant(std::string_view name) {
    // An alias, bare or with a demodulation suffix: its row, named as it always was.
    const size_t plus = name.rfind('+');
    Demodulation d;
    const std::string_view stem =
        plus != std::string_view::npos && ParseDemodulation(name.substr(plus + 1), d) ? name.substr(0, plus) : name;
    for (const DenoiserVariant& v : DenoiserVariants())
        if (v.name == stem) return &v;
    Composition c;
    if (Read(name, c)) return nullptr;
    const std::string canonical = CanonicalBaseName(c);
    ComposedRows& composed = Composed();
    std::lock_guard lock(composed.mutex);
    for (const DenoiserVariant& v : composed.rows)
        if (v.name == canonical) return &v;
    DenoiserVariant v = Derive(c);
    v.name = composed.text.emplace_back(canonical);
    std::string summary(kFamilies[size_t(*c.family)].summary);
    for (size_t i = 0; i < std::size(kMechanisms); ++i)
        if (c.mechanisms[i] && !kMechanisms[i].token.empty())
            summary += fmt::format("{} {}", summary.find(" with ") == std::string::npos ? " with" : ";",
                                   kMechanisms[i].description);
    v.summary = composed.text.emplace_back(std::move(summary));
    return &composed.rows.emplace_back(v);
}

std::optional<std::string> DenoiserNameProblem(std::string_view name) {
    Composition c;
    return Read(name, c);
}

const DenoiserVariant& FindDenoiserVariant(std::string_view name, std::string_view what) {
    if (std::optional<std::string> problem = DenoiserNameProblem(name)) Fail("{}: {}", what, *problem);
    return *LookupDenoiserVariant(name);
}

RendererNeeds RendererNeedsOf(const std::vector<std::string>& names, std::string_view what) {
    RendererNeeds needs;
    for (const std::string& name : names) {
        needs.gradientSamples |= FindDenoiserVariant(name, what).needsGradientSamples;
        needs.fbetaPlane |= DenoiserDemodulation(name) == Demodulation::Brdf;
    }
    return needs;
}

std::string_view DenoiserFamilyName(DenoiserFamily family) {
    switch (family) {
        case DenoiserFamily::Svgf: return "svgf";
        case DenoiserFamily::TwoHistory: return "two-history";
        case DenoiserFamily::Rae: return "rae";
    }
    return "";
}

std::vector<std::string> VariantMechanisms(const DenoiserVariant& variant) {
    std::vector<std::string> names;
    for (const Mechanism& m : kMechanisms)
        if (variant.*m.flag) names.emplace_back(m.description);
    return names;
}

namespace {
// The family token a row was composed from (a row's pass family is TwoHistory for svgf+asvgf too).
const FamilyToken& FamilyOf(const DenoiserVariant& variant) {
    return kFamilies[size_t(variant.family == DenoiserFamily::Rae ? MethodFamily::Rae
                            : variant.twoHistory                  ? MethodFamily::TwoHistory
                                                                  : MethodFamily::Svgf)];
}
}  // namespace

std::vector<PlaneKind> VariantPlanes(const DenoiserVariant& variant) {
    const FamilyToken& family = FamilyOf(variant);
    std::vector<PlaneKind> kinds(family.planes.begin(), family.planes.end());
    for (const Mechanism& m : kMechanisms)
        if (variant.*m.flag)
            for (PlaneKind kind : m.planes)
                if (std::find(kinds.begin(), kinds.end(), kind) == kinds.end()) kinds.push_back(kind);
    std::sort(kinds.begin(), kinds.end());
    return kinds;
}

std::vector<MechanismFragment> MechanismFragments() {
    std::vector<MechanismFragment> fragments;
    for (const Mechanism& m : kMechanisms)
        if (m.passes.pass != MechanismPass::None) fragments.push_back({m.flag, m.passes});
    return fragments;
}

std::vector<MechanismPass> MechanismPassesAt(const DenoiserVariant& variant, FrameSlot slot) {
    std::vector<MechanismPass> passes;
    for (const Mechanism& m : kMechanisms)
        if (m.passes.pass != MechanismPass::None && m.passes.slot == slot && variant.*m.flag)
            passes.push_back(m.passes.pass);
    return passes;
}

std::vector<DebugViewId> VariantDebugViews(const DenoiserVariant& variant) {
    const FamilyToken& family = FamilyOf(variant);
    std::vector<DebugViewId> views(family.views.begin(), family.views.end());
    for (const Mechanism& m : kMechanisms) {
        if (!(variant.*m.flag)) continue;
        for (DebugViewId gone : m.hidesViews) std::erase(views, gone);
        for (DebugViewId view : m.views)
            if (std::find(views.begin(), views.end(), view) == views.end()) views.push_back(view);
    }
    return views;
}

std::vector<std::string> VariantSettings(const DenoiserVariant& variant) {
    const FamilyToken& family = FamilyOf(variant);
    std::vector<std::string_view> keys(family.settings.begin(), family.settings.end());
    auto on = [&](std::string_view token) {
        return std::any_of(std::begin(kMechanisms), std::end(kMechanisms),
                           [&](const Mechanism& m) { return m.token == token && variant.*m.flag; });
    };
    for (const Mechanism& m : kMechanisms) {
        if (!(variant.*m.flag) || (!m.inertWith.empty() && on(m.inertWith))) continue;
        for (std::string_view gone : m.replaces) std::erase(keys, gone);
        for (std::string_view key : m.reads)
            if (std::find(keys.begin(), keys.end(), key) == keys.end()) keys.push_back(key);
    }
    // In the order of the settings tables (`fovrt config --keys`).
    std::vector<std::string> ordered;
    for (const std::string& key : DenoiserSettingKeys())
        if (std::find(keys.begin(), keys.end(), key) != keys.end()) ordered.push_back(key);
    FOVRT_CHECK(ordered.size() == keys.size());  // every key a row declares is a setting
    return ordered;
}

std::vector<std::string> VariantRendererNeeds(const DenoiserVariant& variant) {
    std::vector<std::string> needs;
    if (variant.needsGradientSamples) needs.emplace_back("A-SVGF gradient samples (forward-projected, re-shaded)");
    if (variant.needsSampleCount)
        needs.emplace_back("per-pixel sample counts");
    else if (variant.family != DenoiserFamily::Rae)  // the RAE reads them on the host, from FrameInputs
        needs.emplace_back("per-pixel sample counts where the spp map may hold zeros (a foveation below 1 spp)");
    return needs;
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
    params.rae.balance = variant.raeBalance;
    return params;
}

std::vector<std::string> SvgfChannels(const SvgfParams& params) {
    std::vector<std::string> names;
    for (Channel ch : FilteredChannels(params)) names.emplace_back(ChannelName(ch));
    return names;
}

}  // namespace fovrt
