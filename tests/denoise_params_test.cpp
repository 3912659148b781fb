// The denoiser parameter tables: well-formed rows, every range enforced naming its key, the rule
// between keys, and the denoisers checking the same ranges.
#include <cmath>
#include <limits>
#include <set>
#include <string>
#include <type_traits>
#include <vector>

#include "core/error.h"
#include "denoise/denoiser_factory.h"
#include "denoise/params.h"
#include "shaders/shared_constants.h"
#include "test_support.h"

using namespace fovrt;

namespace {

std::vector<ParamInfo> AllRows() {
    std::vector<ParamInfo> rows;
    const DenoiserParams defaults;
    ForEachDenoiserParam(defaults, [&](const ParamInfo& info, const auto&) { rows.push_back(info); });
    return rows;
}

template <class T>
constexpr bool kIsBool = std::is_same_v<std::decay_t<T>, bool>;

// Default params with the member named `key` set to `value` (converted to its type).
DenoiserParams With(const std::string& key, double value) {
    DenoiserParams params;
    bool found = false;
    ForEachDenoiserParam(params, [&](const ParamInfo& info, auto& member) {
        if (key != info.key) return;
        found = true;
        if constexpr (kIsBool<decltype(member)>) member = value != 0.0;
        else member = static_cast<std::decay_t<decltype(member)>>(value);
    });
    REQUIRE(found);
    return params;
}

enum class Kind { Bool, Int, Float };
Kind KindOf(const std::string& key) {
    Kind kind = Kind::Bool;
    const DenoiserParams defaults;
    ForEachDenoiserParam(defaults, [&](const ParamInfo& info, const auto& member) {
        using T = std::decay_t<decltype(member)>;
        if (key == info.key) kind = std::is_same_v<T, bool> ? Kind::Bool : std::is_same_v<T, int> ? Kind::Int : Kind::Float;
    });
    return kind;
}

// Values just outside a range: at an open bound, else one past it; NaN for floats.
std::vector<double> OutsideValues(const ParamRange& range, Kind kind) {
    std::vector<double> values = {range.minOpen ? range.min : range.min - 1.0,
                                  range.maxOpen ? range.max : range.max + 1.0};
    if (kind == Kind::Float) values.push_back(std::numeric_limits<double>::quiet_NaN());
    return values;
}

}  // namespace

TEST_CASE("parameter tables: every row has a unique denoise key, a doc and a non-empty range", "[params]") {
    const std::vector<ParamInfo> rows = AllRows();
    CHECK(rows.size() == 23);  // 10 svgf + 4 asvgf (2 of them anti-lag) + 6 two-history + 3 two-history-stable
    std::set<std::string> keys;
    for (const ParamInfo& info : rows) {
        INFO(info.key);
        CHECK(ParamRowProblem(info) == nullptr);
        CHECK(std::string(info.key).rfind("denoise.", 0) == 0);
        CHECK(keys.insert(info.key).second);
    }
    CHECK(keys.count(kPrecisionKey) == 0);
}

TEST_CASE("ParamRowProblem catches rows without doc or key, and empty ranges", "[params]") {
    CHECK(ParamRowProblem({"denoise.x", {0, 1, false, false}, "fine"}) == nullptr);
    CHECK(ParamRowProblem({"denoise.x", {0, 1, false, false}, ""}) != nullptr);
    CHECK(ParamRowProblem({"denoise.x", {0, 1, false, false}, nullptr}) != nullptr);
    CHECK(ParamRowProblem({"", {0, 1, false, false}, "doc"}) != nullptr);
    CHECK(ParamRowProblem({"denoise.x", {2, 1, false, false}, "doc"}) != nullptr);
    CHECK(ParamRowProblem({"denoise.x", {1, 1, true, false}, "doc"}) != nullptr);
    CHECK(ParamRowProblem({"denoise.x", {1, 1, false, false}, "doc"}) == nullptr);  // one value
}

TEST_CASE("ParamRange: open ends exclude their bound, non-finite values are out", "[params]") {
    const ParamRange halfOpen{0.0, 1.0, true, false};
    CHECK(!halfOpen.Contains(0.0));
    CHECK(halfOpen.Contains(1e-9));
    CHECK(halfOpen.Contains(1.0));
    CHECK(!halfOpen.Contains(1.0 + 1e-9));
    CHECK(!halfOpen.Contains(std::numeric_limits<double>::infinity()));
    CHECK(halfOpen.Describe() == "(0, 1]");
    const ParamRange closed{0.0, 8.0, false, true};
    CHECK(!closed.Contains(8.0));
    CHECK(closed.Describe() == "[0, 8)");
}

TEST_CASE("the à-trous iteration ranges are the shaders' cap", "[params]") {
    for (const ParamInfo& info : AllRows()) {
        const std::string key = info.key;
        if (key.find("iterations") == std::string::npos && key.find("feedback") == std::string::npos) continue;
        INFO(key);
        CHECK(info.range.min == 0.0);
        CHECK(info.range.max == double(FOVRT_MAX_ATROUS_ITERATIONS));
    }
}

TEST_CASE("ValidateDenoiserParams: every numeric key out of range fails naming it", "[params]") {
    CHECK_NOTHROW(ValidateDenoiserParams(DenoiserParams{}));
    int numeric = 0;
    for (const ParamInfo& info : AllRows()) {
        const Kind kind = KindOf(info.key);
        if (kind == Kind::Bool) continue;
        ++numeric;
        for (double value : OutsideValues(info.range, kind)) {
            INFO(info.key << " = " << value);
            const DenoiserParams params = With(info.key, value);
            CHECK_THROWS_WITH(ValidateDenoiserParams(params),
                              Catch::StartsWith(std::string(info.key) + ": ") && Catch::Contains("out of range"));
            CHECK_THROWS_AS(ValidateDenoiserParamRanges(params), Error);
        }
        // Closed bounds themselves are allowed.
        if (!info.range.minOpen) CHECK_NOTHROW(ValidateDenoiserParamRanges(With(info.key, info.range.min)));
        if (!info.range.maxOpen) CHECK_NOTHROW(ValidateDenoiserParamRanges(With(info.key, info.range.max)));
    }
    CHECK(numeric == 22);  // 8 svgf + 4 asvgf + 6 two-history + 3 two-history-stable (the 2 svgf booleans have no range)
}

TEST_CASE("feedback_iteration <= atrous_iterations: the rule names both keys", "[params]") {
    DenoiserParams params;
    params.svgf.atrousIterations = 2;
    params.svgf.feedbackIteration = 3;
    CHECK_THROWS_WITH(ValidateDenoiserParams(params),
                      Catch::Contains("denoise.svgf.feedback_iteration") &&
                          Catch::Contains("denoise.svgf.atrous_iterations"));
    // The denoisers take it as "no à-trous feedback" and check ranges only.
    CHECK_NOTHROW(ValidateDenoiserParamRanges(params));
    params.svgf.feedbackIteration = 2;
    CHECK_NOTHROW(ValidateDenoiserParams(params));
}

TEST_CASE("the denoisers check the table's ranges", "[params]") {
    DenoiserParams params;
    params.svgf.sigmaDepth = 0.0f;  // open lower bound
    CHECK_THROWS_WITH(CreateDenoiser("svgf", "cpu", params), Catch::Contains("denoise.svgf.sigma_depth"));
    params = DenoiserParams{};
    params.twoHistory.gradientBeta = 1.5f;
    CHECK_THROWS_WITH(CreateDenoiser("two-history", "cpu", params),
                      Catch::Contains("denoise.two_history.gradient_beta"));
    params = DenoiserParams{};
    params.svgf.atrousIterations = 0;  // feedback_iteration 1 > 0: accepted by the denoisers
    CHECK_NOTHROW(CreateDenoiser("svgf", "cpu", params));
}

TEST_CASE("precision table: names and values map both ways", "[params]") {
    CHECK(PrecisionTable().size() == 3);  // fp32, fp16, auto
    for (const PrecisionRow& row : PrecisionTable()) {
        Precision back = row.value == Precision::Fp32 ? Precision::Fp16 : Precision::Fp32;
        CHECK(PrecisionFromName(row.name, back));
        CHECK(back == row.value);
        CHECK(std::string(PrecisionName(row.value)) == row.name);
        CHECK(row.doc[0] != '\0');
    }
    Precision unchanged = Precision::Fp16;
    CHECK(!PrecisionFromName("fp64", unchanged));
    CHECK(unchanged == Precision::Fp16);
}
