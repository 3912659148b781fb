// Every variant names the mechanisms its row turns on (`fovrt info --denoiser`): a name such as
// two-history-asvgf-stable-hysteresis no longer hides that it also turns on the anti-lag and the
// stabilisation's change detector.
#include <algorithm>
#include <string>

#include "denoise/variant_notes.h"
#include "denoise/variants.h"
#include "test_support.h"

using namespace fovrt;

namespace {

bool Lists(const std::vector<std::string>& names, const std::string& part) {
    return std::any_of(names.begin(), names.end(), [&](const std::string& n) { return n.find(part) != std::string::npos; });
}

int FlagsSet(const DenoiserVariant& v) {
    return int(v.weightBySampleCount) + int(v.twoHistory) + int(v.emaGradient) + int(v.asvgfGradient) + int(v.antilag) +
           int(v.stabilize) + int(v.suppressFireflies) + int(v.clampHistory) + int(v.stabilizeAntilag) +
           int(v.hystereticChoice) + int(v.raeSampleCount) + int(v.raeBalance);
}

}  // namespace

TEST_CASE("every mechanism flag a row sets is named, once", "[denoise][variants]") {
    for (const DenoiserVariant& v : DenoiserVariants()) {
        INFO(v.name);
        const std::vector<std::string> names = VariantMechanisms(v);
        CHECK(int(names.size()) == FlagsSet(v));
    }
    CHECK(VariantMechanisms(FindDenoiserVariant("svgf")).empty());
}

TEST_CASE("a name's hidden mechanisms are listed", "[denoise][variants]") {
    const std::vector<std::string> names = VariantMechanisms(FindDenoiserVariant("two-history-asvgf-stable-hysteresis"));
    CHECK(Lists(names, "anti-lag"));
    CHECK(Lists(names, "change detector"));
    CHECK(Lists(names, "A-SVGF temporal gradient"));
    CHECK(Lists(names, "held history choice"));
    CHECK_FALSE(Lists(names, "EMA"));
    const std::vector<std::string> needs = VariantRendererNeeds(FindDenoiserVariant("two-history-asvgf"));
    CHECK(Lists(needs, "gradient samples"));
    CHECK(Lists(needs, "sample counts"));
    // svgf reads the sample counts only where the spp map may hold zeros; the RAE never.
    const std::vector<std::string> svgfNeeds = VariantRendererNeeds(FindDenoiserVariant("svgf"));
    REQUIRE(svgfNeeds.size() == 1);
    CHECK(Lists(svgfNeeds, "may hold zeros"));
    CHECK_FALSE(Lists(needs, "may hold zeros"));
    CHECK(VariantRendererNeeds(FindDenoiserVariant("rae")).empty());
}

TEST_CASE("every variant has one note for docs/denoisers.md, and every note a variant", "[denoise][variants]") {
    for (const DenoiserVariant& v : DenoiserVariants()) {
        INFO(v.name);
        CHECK(FindVariantNote(v.name) != nullptr);
    }
    for (const VariantNote& note : VariantNotes()) {
        INFO(note.name);
        CHECK(LookupDenoiserVariant(note.name) != nullptr);
        CHECK(note.measured.empty() == note.measuredAt.empty());  // figures name the commit that published them
    }
    CHECK(VariantNotes().size() == DenoiserVariants().size());
}

// ---- Names as compositions (denoise/variants.h) ------------------------------------------------

namespace {

std::string SetFlags(const DenoiserVariant& v) {
    std::string out;
    auto add = [&](bool on, const char* name) {
        if (!on) return;
        if (!out.empty()) out += ' ';
        out += name;
    };
    add(v.weightBySampleCount, "weightBySampleCount");
    add(v.twoHistory, "twoHistory");
    add(v.emaGradient, "emaGradient");
    add(v.asvgfGradient, "asvgfGradient");
    add(v.antilag, "antilag");
    add(v.stabilize, "stabilize");
    add(v.suppressFireflies, "suppressFireflies");
    add(v.stabilizeAntilag, "stabilizeAntilag");
    add(v.clampHistory, "clampHistory");
    add(v.hystereticChoice, "hystereticChoice");
    add(v.needsGradientSamples, "needsGradientSamples");
    add(v.needsSampleCount, "needsSampleCount");
    add(v.raeSampleCount, "raeSampleCount");
    add(v.raeBalance, "raeBalance");
    return out;
}

}  // namespace

// The rows as they were stored, flag by flag, before the aliases were derived from compositions:
// the plans (and so the outputs) follow from these flags and the parameters alone.
TEST_CASE("every alias derives the row it had when rows were written by hand", "[denoise][variants]") {
    struct Stored {
        const char* name;
        DenoiserFamily family;
        const char* flags;
    };
    const Stored stored[] = {
        {"svgf", DenoiserFamily::Svgf, ""},
        {"svgf-weighted", DenoiserFamily::Svgf, "weightBySampleCount needsSampleCount"},
        {"asvgf", DenoiserFamily::TwoHistory, "asvgfGradient needsGradientSamples"},
        {"two-history", DenoiserFamily::TwoHistory, "twoHistory emaGradient needsSampleCount"},
        {"two-history-asvgf", DenoiserFamily::TwoHistory, "twoHistory asvgfGradient needsGradientSamples needsSampleCount"},
        {"asvgf-antilag", DenoiserFamily::TwoHistory, "asvgfGradient antilag needsGradientSamples"},
        {"two-history-asvgf-antilag", DenoiserFamily::TwoHistory,
         "twoHistory asvgfGradient antilag needsGradientSamples needsSampleCount"},
        {"two-history-stable", DenoiserFamily::TwoHistory, "twoHistory emaGradient stabilize needsSampleCount"},
        {"two-history-stable-firefly", DenoiserFamily::TwoHistory,
         "twoHistory emaGradient stabilize suppressFireflies needsSampleCount"},
        {"two-history-stable-antilag", DenoiserFamily::TwoHistory,
         "twoHistory emaGradient stabilize stabilizeAntilag needsSampleCount"},
        {"two-history-asvgf-stable-antilag", DenoiserFamily::TwoHistory,
         "twoHistory asvgfGradient antilag stabilize stabilizeAntilag needsGradientSamples needsSampleCount"},
        {"two-history-clamp", DenoiserFamily::TwoHistory, "twoHistory emaGradient clampHistory needsSampleCount"},
        {"two-history-stable-clamp", DenoiserFamily::TwoHistory,
         "twoHistory emaGradient stabilize clampHistory needsSampleCount"},
        {"two-history-hysteresis", DenoiserFamily::TwoHistory, "twoHistory emaGradient hystereticChoice needsSampleCount"},
        {"two-history-stable-hysteresis", DenoiserFamily::TwoHistory,
         "twoHistory emaGradient stabilize hystereticChoice needsSampleCount"},
        {"two-history-asvgf-stable-hysteresis", DenoiserFamily::TwoHistory,
         "twoHistory asvgfGradient antilag stabilize stabilizeAntilag hystereticChoice needsGradientSamples "
         "needsSampleCount"},
        {"rae", DenoiserFamily::Rae, ""},
        {"rae-spp", DenoiserFamily::Rae, "raeSampleCount"},
    };
    REQUIRE(DenoiserVariants().size() == std::size(stored));
    for (const Stored& s : stored) {
        INFO(s.name);
        const DenoiserVariant& v = FindDenoiserVariant(s.name);
        CHECK(v.name == s.name);
        CHECK(v.family == s.family);
        // The stored order differs; compare as sets of words.
        auto words = [](std::string text) {
            std::vector<std::string> w;
            for (size_t start = 0; start < text.size();) {
                size_t space = text.find(' ', start);
                if (space == std::string::npos) space = text.size();
                w.push_back(text.substr(start, space - start));
                start = space + 1;
            }
            std::sort(w.begin(), w.end());
            return w;
        };
        CHECK(words(SetFlags(v)) == words(s.flags));
        // The composition written out resolves to the same flags, under its canonical name.
        const DenoiserVariant& composed = FindDenoiserVariant(CanonicalDenoiserName(s.name));
        CHECK(SetFlags(composed) == SetFlags(v));
        CHECK(composed.family == v.family);
    }
}

TEST_CASE("a composition is read in any order and written canonically", "[denoise][variants]") {
    CHECK(CanonicalDenoiserName("clamp+stabilize+two-history") == "two-history+clamp+stabilize");
    CHECK(CanonicalDenoiserName("brdf+stabilize+two-history") == "two-history+stabilize+brdf");
    CHECK(CanonicalDenoiserName("two-history-stable") == "two-history+stabilize");
    CHECK(CanonicalDenoiserName("two-history-stable+clamp") == "two-history+clamp+stabilize");
    CHECK(CanonicalDenoiserName("asvgf") == "svgf+asvgf");
    CHECK(CanonicalDenoiserName("asvgf+antilag") == "svgf+asvgf+antilag");
    CHECK(CanonicalDenoiserName("two-history+asvgf") == "two-history+asvgf");
    CHECK(CanonicalDenoiserName("svgf-weighted+albedo") == "svgf+weighted+albedo");
    // A composition no alias names: its own row, with needs derived from its mechanisms.
    const DenoiserVariant& v = FindDenoiserVariant("firefly+two-history+asvgf+clamp");
    CHECK(v.name == "two-history+asvgf+firefly+clamp");
    CHECK(v.family == DenoiserFamily::TwoHistory);
    CHECK(v.twoHistory);
    CHECK_FALSE(v.emaGradient);  // A-SVGF's λ is its q
    CHECK(v.needsGradientSamples);
    CHECK(v.needsSampleCount);
    CHECK(&FindDenoiserVariant("two-history+clamp+firefly+asvgf") == &v);  // one row per composition
    CHECK(DenoiserDemodulation("two-history+brdf+clamp") == Demodulation::Brdf);
    CHECK_FALSE(DenoiserDemodulation("two-history+clamp").has_value());
}

TEST_CASE("a composition that breaks a rule is refused naming the rule", "[denoise][variants]") {
    auto problem = [](const char* name) { return DenoiserNameProblem(name).value_or(""); };
    CHECK_THAT(problem("two-history+antilag"), Catch::Contains("antilag requires asvgf"));
    CHECK_THAT(problem("two-history+clamp+hysteresis"), Catch::Contains("hysteresis excludes clamp"));
    CHECK_THAT(problem("svgf+stabilize"), Catch::Contains("stabilize does not join the svgf family"));
    CHECK_THAT(problem("two-history+weighted"), Catch::Contains("weighted does not join the two-history family"));
    CHECK_THAT(problem("svgf+weighted+asvgf"), Catch::Contains("weighted excludes asvgf"));
    CHECK_THAT(problem("two-history+stabilize-antilag"), Catch::Contains("stabilize-antilag requires stabilize"));
    CHECK_THAT(problem("rae+clamp"), Catch::Contains("clamp does not join the rae family"));
    CHECK_THAT(problem("rae+brdf"), Catch::Contains("albedo-demodulated"));
    CHECK_THAT(problem("svgf+two-history"), Catch::Contains("two families"));
    CHECK_THAT(problem("clamp+stabilize"), Catch::Contains("names no family"));
    CHECK_THAT(problem("two-history+brdf+albedo"), Catch::Contains("two demodulations"));
    CHECK_THAT(problem("two-history++clamp"), Catch::Contains("empty part"));
    CHECK_THAT(problem("two-history+clmap"), Catch::Contains("did you mean 'clamp'"));
    CHECK_THROWS_WITH(FindDenoiserVariant("two-history+antilag", "denoise.denoisers"),
                      Catch::StartsWith("denoise.denoisers: 'two-history+antilag': antilag requires asvgf"));
    for (const DenoiserVariant& v : DenoiserVariants()) CHECK_FALSE(DenoiserNameProblem(v.name).has_value());
}

TEST_CASE("the compositions: every valid one once, the aliases among them", "[denoise][variants]") {
    const std::vector<std::string> all = DenoiserCompositions();
    // svgf: alone, +weighted, +asvgf, +asvgf+antilag; two-history: (none | asvgf | asvgf+antilag) ×
    // firefly × (none | hysteresis | clamp) × (none | stabilize | stabilize+stabilize-antilag);
    // rae: (none | spp) × (none | balance).
    CHECK(all.size() == 4 + 3 * 2 * 3 * 3 + 2 * 2);
    for (const std::string& name : all) {
        INFO(name);
        CHECK(CanonicalDenoiserName(name) == name);
        CHECK_FALSE(DenoiserNameProblem(name).has_value());
    }
    for (const DenoiserVariant& v : DenoiserVariants()) {
        INFO(v.name);
        CHECK(std::count(all.begin(), all.end(), CanonicalDenoiserName(v.name)) == 1);
    }
}
