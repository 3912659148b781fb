// Where two-history's foveal flicker comes from (denoise/two_history_stable.md): renders the thesis
// preset's frames (presets/thesis-foveated.toml, --quick size unless --set says otherwise) and
// runs svgf, two-history and two-history-stable on the C++ reference, then prints
//   - per-pixel traces of a few pixels the fovea sweeps: n, p, q, t = p + q − pq, lum of the
//     fed-back I_u and I_w, the moments' variance, and each variant's output luminance;
//   - the foveal temporal error (mean |Δlum| of eye 0 over the 8-spp disc, the experiments'
//     measure) split by the frames since the pixel entered the fovea, with the mean |Δt| and the
//     mean |Δlum| of each history in each split.
// With --svg PREFIX, two plots: PREFIX-choice.svg, the second traced pixel's n/8, p, q and t over
// the frames (the pixel denoise/two_history_stable.md follows), and PREFIX-age.svg, each variant's
// foveal temporal error by the pixels' age (the split's columns).
// Usage: two_history_flicker_probe [--scene NAME] [--frames N (60)] [--set key=value ...] [--svg PREFIX]
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "app/report_html.h"
#include "core/atomic_file.h"
#include "pipeline/frame_pipeline.h"
#include "denoise/reference/svgf_family_ref.h"
#include "denoise/reference/two_history_math.h"
#include "metrics/image_metrics.h"
#include "thesis_preset_frames.h"

using namespace fovrt;

namespace {

constexpr int kAgeBins = 8;  // frames since entering the fovea: 0 … 6, ≥ 7
constexpr int kVariants = 3;
constexpr const char* kNames[kVariants] = {"svgf", "two-history", "two-history-stable"};

struct Split {
    double temporal[kVariants] = {};
    double dt = 0.0, dIu = 0.0, dIw = 0.0;
    long count = 0;
};

float LumSum(const TwoHistoryState& st, bool weighted, size_t i) {
    const auto& planes = weighted ? st.iw : st.iu;
    float l = 0.0f;
    for (const Plane<vec3>& p : planes)
        if (!p.empty()) l += Luminance(p[i]);
    return l;
}

}  // namespace

int main(int argc, char** argv) {
    std::string scene = "cornell";
    int frames = 60;
    std::vector<std::string> sets;
    std::string svgPrefix;
    for (int a = 1; a + 1 < argc; a += 2) {
        const std::string arg = argv[a];
        if (arg == "--scene") scene = argv[a + 1];
        else if (arg == "--frames") frames = std::atoi(argv[a + 1]);
        else if (arg == "--set") sets.push_back(argv[a + 1]);
        else if (arg == "--svg") svgPrefix = argv[a + 1];
        else {
            std::fprintf(stderr, "two_history_flicker_probe: unknown argument '%s'\n", arg.c_str());
            return 2;
        }
    }
    try {
        const RunConfig config = test::ThesisPresetConfig(scene, sets);
        FramePipeline pipeline(config);
        const DenoiserParams& params = config.denoise.params;
        std::array<SvgfFamilyReferenceDenoiser, kVariants> denoisers = {
            SvgfFamilyReferenceDenoiser(FindDenoiserVariant(kNames[0]), params),
            SvgfFamilyReferenceDenoiser(FindDenoiserVariant(kNames[1]), params),
            SvgfFamilyReferenceDenoiser(FindDenoiserVariant(kNames[2]), params)};
        const int w = config.camera.width, h = config.camera.height;
        const int sppInside = config.foveation.sppInside;
        const std::array<ivec2, 3> probes = {ivec2(w / 2, h / 2), ivec2(w / 4, h / 2), ivec2(3 * w / 4, h / 3)};
        std::vector<int> entered(size_t(w) * h, -1);
        std::vector<float> prevT(size_t(w) * h, 0.0f), prevIu(size_t(w) * h, 0.0f), prevIw(size_t(w) * h, 0.0f);
        std::array<Plane<vec3>, kVariants> out, prev;
        std::array<Split, kAgeBins> splits;
        StereoFrame frame;
        // The second traced pixel over time, for --svg.
        LinePlot choice, flickerPlot;
        choice.title = fmt::format("{} pixel ({}, {}): the history choice", scene, probes[1].x, probes[1].y);
        choice.yLabel = "blend factor";
        for (const char* name : {"n / 8 (samples this frame)", "p", "q", "t = p + q - pq"})
            choice.series.push_back({name, {}});
        flickerPlot.title = fmt::format("{}: foveal temporal error by the pixel's age", scene);
        flickerPlot.xLabel = "frames since the pixel entered the fovea (7: 7 or more)";
        flickerPlot.yLabel = "mean |delta lum|";
        for (const char* name : kNames) flickerPlot.series.push_back({name, {}});
        std::printf("%s %dx%d, %d frames; trace: frame x y n p q t lum(I_u) lum(I_w) var lum(out) svgf two-history "
                    "two-history-stable\n",
                    scene.c_str(), w, h, frames);
        for (int f = 0; f < frames; ++f) {
            pipeline.Render(uint32_t(f), frame);
            const FrameInputs& in = frame.eyes[0].inputs;
            for (int v = 0; v < kVariants; ++v) denoisers[size_t(v)].Denoise(in, out[size_t(v)]);
            const SvgfFamilyReferenceDenoiser& th = denoisers[1];
            const TwoHistoryState& st = th.CurrentState();
            const Plane<float>& q = th.Q();
            std::array<Plane<float>, kVariants> flicker;  // |Δlum| per pixel, the experiments' measure
            if (f > 0)
                for (int v = 0; v < kVariants; ++v) flicker[size_t(v)] = TemporalErrorMap(out[size_t(v)], prev[size_t(v)]);
            for (size_t i = 0; i < in.sampleCount.size(); ++i) {
                const bool inside = in.sampleCount[i] >= sppInside;
                if (!inside) entered[i] = -1;
                else if (entered[i] < 0) entered[i] = f;
                const float p = TwoHistoryOptimalBlend(StoredTwoHistoryWeights(st.wu[i], st.ww[i], st.powerSums[i]));
                const float t = TwoHistoryFinalBlend(p, q[i]);
                const float iu = LumSum(st, false, i), iw = LumSum(st, true, i);
                if (f > 0 && inside && in.objectId[i] != kNoObject) {
                    Split& s = splits[size_t(std::min(f - entered[i], kAgeBins - 1))];
                    for (int v = 0; v < kVariants; ++v) s.temporal[v] += flicker[size_t(v)][i];
                    s.dt += std::abs(t - prevT[i]);
                    s.dIu += std::abs(iu - prevIu[i]);
                    s.dIw += std::abs(iw - prevIw[i]);
                    ++s.count;
                }
                prevT[i] = t, prevIu[i] = iu, prevIw[i] = iw;
            }
            for (const ivec2& px : probes) {
                const size_t i = size_t(px.y) * w + size_t(px.x);
                const float p = TwoHistoryOptimalBlend(StoredTwoHistoryWeights(st.wu[i], st.ww[i], st.powerSums[i]));
                float var = 0.0f;
                for (size_t c = 0; c < th.ChannelCount(); ++c) var += th.Illum(c, 1)[i].a;
                if (px == probes[1]) {
                    const double values[] = {double(in.sampleCount[i]) / 8.0, p, q[i], TwoHistoryFinalBlend(p, q[i])};
                    for (size_t s = 0; s < 4; ++s) choice.series[s].points.emplace_back(f, values[s]);
                }
                std::printf("trace %3d %3d %3d %2d %.3f %.3f %.3f %.4f %.4f %.5f %.4f %.4f %.4f\n", f, px.x, px.y,
                            int(in.sampleCount[i]), p, q[i], TwoHistoryFinalBlend(p, q[i]), LumSum(st, false, i),
                            LumSum(st, true, i), var, Luminance(out[0][i]), Luminance(out[1][i]),
                            Luminance(out[2][i]));
            }
            prev = out;
        }
        std::printf("fovea split by frames since entering it: share of pixel-frames, mean |dlum out| per variant, "
                    "mean |dt|, mean |dlum I_u|, mean |dlum I_w|\n");
        long total = 0;
        for (const Split& s : splits) total += s.count;
        for (int b = 0; b < kAgeBins; ++b) {
            const Split& s = splits[size_t(b)];
            if (s.count == 0) continue;
            const double n = double(s.count);
            for (int v = 0; v < kVariants; ++v) flickerPlot.series[size_t(v)].points.emplace_back(b, s.temporal[v] / n);
            std::printf("age %s%d: %5.1f%%  svgf %.5f  two-history %.5f  two-history-stable %.5f  |dt| %.4f  "
                        "|dI_u| %.5f  |dI_w| %.5f\n",
                        b == kAgeBins - 1 ? ">=" : "", b, 100.0 * n / double(total), s.temporal[0] / n,
                        s.temporal[1] / n, s.temporal[2] / n, s.dt / n, s.dIu / n, s.dIw / n);
        }
        if (!svgPrefix.empty()) {
            WriteTextAtomically(svgPrefix + "-choice.svg", SvgLinePlot(choice) + "\n");
            WriteTextAtomically(svgPrefix + "-age.svg", SvgLinePlot(flickerPlot) + "\n");
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "two_history_flicker_probe: %s\n", e.what());
        return 1;
    }
    return 0;
}
