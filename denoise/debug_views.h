// Debug views: a denoiser's internal per-pixel planes of its last Denoise() call, one float per
// pixel (A-SVGF's α and λ̂, two-history's p and q, the temporal history length …), for the live
// preview panel and for debugging.
//
// The one table of views: each row names a view and says what it means and its valid range. Which
// variants offer it, the family and mechanism units say (VariantDebugViews, denoise/variants.cpp)
// — so a new composition offers the views of the passes it runs with no other edit, and both
// backends of a variant offer the same names. Denoiser::DebugViews() and
// Denoiser::ReadDebugView() (denoise/denoiser.h) read this table; the hosts only say where each
// view's plane lives (a switch over DebugViewId, so a new row fails to compile until every host
// handles it). Reading a view is a synchronous read-back on Vulkan: nothing is recorded or copied
// per frame for it, so a view costs nothing until someone reads it.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace fovrt {

struct DenoiserVariant;

enum class DebugViewId {
    HistoryLength,   // frames in the (unweighted) temporal history
    HistorySamples,  // sample-count-weighted total weight of the weighted history
    Alpha,           // A-SVGF's temporal α_i(p)
    Antilag,         // the anti-lag variants' factor a(p)
    Lambda,          // A-SVGF's λ̂(p)
    P,               // two-history's variance-optimal blend factor
    Q,               // two-history's gradient-guided blend factor
    T,               // two-history's history choice t = p + q − pq (computed from P and Q)
    HistoryU,        // luminance of two-history's unweighted colour history I_u (first channel)
    HistoryW,        // luminance of its weighted colour history I_w (first channel)
    Variance,        // the variance of the unweighted luminance moments, m2 − m1² (first channel)
    StableLum,       // two-history-stable's stabilised luminance L_s (first channel)
};

// How many floats per pixel the plane behind `view` holds (3: a colour history, 2: moments, else
// 1), and the one value the view shows of them: the luminance, the variance m2 − m1² (≥ 0), or
// the value itself. The hosts read the plane; this reduces it, the same for both.
int DebugViewComponents(DebugViewId view);
float ReduceDebugPixel(DebugViewId view, const float* components);

struct DebugView {
    DebugViewId id;
    std::string_view name;       // what ReadDebugView() takes, e.g. "alpha"
    std::string_view meaning;    // one line for a legend or tooltip
    float lo = 0.0f, hi = 1.0f;  // valid range of every pixel; hi = +inf when unbounded
};

// Every view, in the order DebugViews() lists them.
const std::vector<DebugView>& DebugViewTable();
// The names of the views `variant` offers, in table order.
std::vector<std::string> DebugViewNames(const DenoiserVariant& variant);
// The row of `name` when `variant` offers it; null otherwise (unknown name, or another variant's).
const DebugView* FindDebugView(const DenoiserVariant& variant, std::string_view name);

}  // namespace fovrt
