// "Did you mean": the known name nearest to a misspelt one (Levenshtein distance), for one-line
// errors that name what was unknown and what was probably meant.
#pragma once

#include <algorithm>
#include <string>
#include <string_view>
#include <vector>

namespace fovrt {

// Insertions, deletions and substitutions turning `a` into `b`.
inline size_t EditDistance(std::string_view a, std::string_view b) {
    std::vector<size_t> row(b.size() + 1);
    for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (size_t i = 1; i <= a.size(); ++i) {
        size_t diag = row[0];
        row[0] = i;
        for (size_t j = 1; j <= b.size(); ++j) {
            const size_t up = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
            diag = up;
        }
    }
    return row[b.size()];
}

// The first of `known` nearest to `name`; empty when `known` is.
template <typename Names>
std::string NearestName(std::string_view name, const Names& known) {
    std::string best;
    size_t bestDistance = 0;
    for (const auto& candidate : known) {
        const size_t d = EditDistance(name, candidate);
        if (best.empty() || d < bestDistance) best = std::string(candidate), bestDistance = d;
    }
    return best;
}

}  // namespace fovrt
