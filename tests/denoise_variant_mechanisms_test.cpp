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
           int(v.hystereticChoice) + int(v.raeSampleCount);
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
