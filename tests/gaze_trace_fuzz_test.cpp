// Randomized fuzz test of the gaze trace parser: mutated rows either parse (and then every query
// gives a finite unit direction) or throw fovrt::Error with the trace name; never crash or hang.
#include <cmath>
#include <sstream>

#include "core/error.h"
#include "core/rng.h"
#include "gaze/sources.h"
#include "test_support.h"

using namespace fovrt;

namespace {

std::string RandomToken(Pcg32& rng) {
    static const char* tokens[] = {"0", "1.5", "-3", "1e3", "1e400", "-1e-400", "nan", "NaN", "inf",
                                   "-inf", "", " ", "abc", "0x10", "+2", "--1", "1,2", ",", "#",
                                   "\t7\t", "\r", "89.9", "90", "1e", ".", "5.", "\xff\xfe", "\"3\""};
    return tokens[rng.NextBounded(sizeof(tokens) / sizeof(tokens[0]))];
}

std::string Mutate(std::string row, Pcg32& rng) {
    switch (rng.NextBounded(6)) {
        case 0: return row;
        case 1: if (!row.empty()) row.erase(rng.NextBounded(uint32_t(row.size()))); return row;
        case 2: row.insert(rng.NextBounded(uint32_t(row.size() + 1)), RandomToken(rng)); return row;
        case 3: if (!row.empty()) row[rng.NextBounded(uint32_t(row.size()))] = char(rng.NextBounded(256)); return row;
        case 4: return RandomToken(rng) + "," + RandomToken(rng) + "," + RandomToken(rng);
        default: return row + "," + RandomToken(rng);
    }
}

}  // namespace

TEST_CASE("Gaze trace parser survives mutated input", "[gaze][fuzz]") {
    Pcg32 rng(20261121);
    int parsed = 0, rejected = 0;
    for (int trial = 0; trial < 3000; ++trial) {
        std::string text = rng.NextBounded(10) == 0 ? Mutate("n,x,y", rng) + "\n" : "n,x,y\n";
        double t = 0.0;
        int rows = 1 + int(rng.NextBounded(12));
        for (int r = 0; r < rows; ++r) {
            t += rng.NextFloat() * 10.0;
            std::string row = fmt::format("{},{},{}", t, rng.NextFloat() * 60 - 30, rng.NextFloat() * 40 - 20);
            text += (rng.NextBounded(3) == 0 ? Mutate(row, rng) : row) + "\n";
        }
        std::istringstream in(text);
        try {
            auto samples = ParseGazeTraceCsv(in, "fuzz.csv");
            TraceGaze trace(samples);
            for (int q = 0; q < 8; ++q) {
                GazeSample s = trace.At(double(rng.NextFloat()) * 0.2 - 0.05);
                REQUIRE(IsFinite(s.direction));
                REQUIRE(glm::length(s.direction) == Approx(1.0f).margin(1e-4));
            }
            ++parsed;
        } catch (const Error& e) {
            REQUIRE(std::string(e.what()).find("fuzz.csv") != std::string::npos);
            ++rejected;
        }
    }
    // Both outcomes were exercised.
    CHECK(parsed > 100);
    CHECK(rejected > 100);
}
