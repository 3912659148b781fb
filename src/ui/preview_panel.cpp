#include "ui/preview_panel.h"

#include <GLFW/glfw3.h>

#include <algorithm>
#include <vector>

#include <fmt/format.h>
#include <imgui.h>

#include "config/settings_tables.h"
#include "core/check.h"
#include "denoise/variants.h"
#include "ui/tracker_panel.h"

namespace fovrt {
namespace {

bool Combo(const char* label, const std::vector<std::string>& items, std::string& current) {
    bool changed = false;
    if (ImGui::BeginCombo(label, current.c_str())) {
        for (const std::string& item : items) {
            const bool selected = item == current;
            if (ImGui::Selectable(item.c_str(), selected)) {
                changed = item != current;
                current = item;
            }
            if (selected) ImGui::SetItemDefaultFocus();
        }
        ImGui::EndCombo();
    }
    return changed;
}

void Text(const std::string& s) { ImGui::TextUnformatted(s.c_str()); }

std::string Bytes(size_t b) {
    return b >= (1u << 20) ? fmt::format("{:.2f} MiB", double(b) / double(1u << 20))
                           : fmt::format("{:.1f} KiB", double(b) / 1024.0);
}

// Sliders over the span the setting's row gives (foveation/foveation_params.cpp,
// gaze/gaze_params.cpp).
bool SliderOf(const char* label, const char* key, int& value) {
    const ParamRange span = SliderSpan(FoveationParamTable(), key);
    return ImGui::SliderInt(label, &value, int(span.min), int(span.max));
}
bool SliderOf(const char* label, const char* key, float& value, const char* format) {
    const ParamRange span = SliderSpan(FoveationParamTable(), key);
    return ImGui::SliderFloat(label, &value, float(span.min), float(span.max), format);
}

// The cap ratio a "cap follows the budget" tick starts from: the best cap measured for a steep
// map is about four times the budget's mean (docs/foveation-study.md, a cap that follows the budget).
constexpr float kStartingCapRatio = 4.0f;

// `pixels`: one eye's W·H, to show the cap a ratio gives.
bool FoveationControls(FoveationParams& f, int64_t pixels) {
    std::vector<std::string> models(FoveationModelNames().begin(), FoveationModelNames().end());
    bool changed = Combo("model", models, f.model);
    if (f.model != "perceptual") {  // read by the perceptual model only
        f.contentMasking = false;
        f.pooling = "energy";
    }
    if (f.model == "disc") {
        changed |= SliderOf("spp inside", "foveation.spp_inside", f.sppInside);
        changed |= SliderOf("spp outside", "foveation.spp_outside", f.sppOutside, "%.3g");
        changed |= SliderOf("radius px @1280", "foveation.radius_px", f.radiusPx, "%.0f");
    } else if (f.model == "linear" || f.model == "acuity" || f.model == "perceptual") {
        changed |= SliderOf("spp max", "foveation.spp_max", f.sppMax);
        changed |= SliderOf("spp min", "foveation.spp_min", f.sppMin, "%.3g");
        if (f.model == "linear") {
            changed |= SliderOf("foveal deg", "foveation.foveal_deg", f.fovealDeg, "%.1f");
            changed |= SliderOf("peripheral deg", "foveation.peripheral_deg", f.peripheralDeg, "%.1f");
        } else if (f.model == "acuity") {
            changed |= SliderOf("MAR slope", "foveation.mar_slope", f.marSlope, "%.4f");
        } else {
            changed |= SliderOf("noise x Nyquist", "foveation.noise_frequency", f.noiseFrequency, "%.2f");
            changed |= ImGui::Checkbox("texture masks noise", &f.contentMasking);
            const std::vector<std::string> poolings(PerceptualPoolingNames().begin(), PerceptualPoolingNames().end());
            changed |= Combo("pooling", poolings, f.pooling);
        }
    } else {
        changed |= SliderOf("spp", "foveation.uniform_spp", f.uniformSpp, "%.3g");
    }
    int budget = int(f.rayBudget);
    if (ImGui::InputInt("ray budget (0: none)", &budget, 1000, 10000)) {
        f.rayBudget = std::max(0, budget);
        changed = true;
    }
    if (f.rayBudget > 0) {
        changed |= SliderOf("spp floor", "foveation.spp_floor", f.sppFloor, "%.3g");
        bool capFollows = f.sppCapRatio > 0.0f;
        if (ImGui::Checkbox("cap follows the budget", &capFollows)) {
            f.sppCapRatio = capFollows ? kStartingCapRatio : 0.0f;
            changed = true;
        }
        if (capFollows) {  // spp_cap is not read while a ratio is set
            changed |= SliderOf("cap x mean", "foveation.spp_cap_ratio", f.sppCapRatio, "%.2g");
            Text(fmt::format("cap: {} spp", BudgetSppCap(f, pixels)));
        } else {
            changed |= SliderOf("spp cap", "foveation.spp_cap", f.sppCap);
        }
        if (!capFollows && FlatSppMap(f) && BudgetSppCap(f, pixels) > f.sppCap)
            Text(fmt::format("uniform: cap {} spp, the mean", BudgetSppCap(f, pixels)));
    }
    return changed;
}

}  // namespace

void DrawPreviewPanel(LiveLoop& loop, PreviewFrameSource* sourcePtr, const LiveStats& stats,
                      const std::shared_ptr<const LiveFrame>& shown, const std::string& presentMode,
                      PanelState& state) {
    ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(360, 0), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowBgAlpha(0.85f);
    if (!ImGui::Begin(state.title.c_str())) {
        ImGui::End();
        return;
    }
    LiveControls controls = loop.Controls();

    if (ImGui::CollapsingHeader("Denoiser and view", ImGuiTreeNodeFlags_DefaultOpen)) {
        std::string denoiser = controls.denoiser;
        if (Combo("denoiser", DenoiserNames(), denoiser)) loop.SetDenoiser(denoiser);
        std::string view = controls.view;
        if (Combo("view", loop.ViewNames(), view)) loop.SetView(view);
        if (shown) ImGui::TextWrapped("%s", shown->shown[0].legend.c_str());
        int layout = int(state.display.layout);
        ImGui::RadioButton("both eyes", &layout, int(DisplayLayout::SideBySide));
        ImGui::SameLine();
        ImGui::RadioButton("left", &layout, int(DisplayLayout::LeftEye));
        ImGui::SameLine();
        ImGui::RadioButton("right", &layout, int(DisplayLayout::RightEye));
        state.display.layout = DisplayLayout(layout);
        ImGui::Checkbox("gaze + fovea overlay (O)", &state.display.overlay);
        const ParamRange exposure = SliderSpan(OutputTable(), "output.exposure");
        ImGui::SliderFloat("exposure (stops)", &state.display.exposure, float(exposure.min), float(exposure.max),
                           "%.1f");
    }
    if (ImGui::CollapsingHeader("Foveation")) {
        const int64_t pixels = int64_t(loop.Config().camera.width) * loop.Config().camera.height;
        if (FoveationControls(controls.foveation, pixels)) {
            try {
                loop.SetFoveation(controls.foveation);
            } catch (const std::exception&) {
                // an inconsistent pair (e.g. spp min > max) while dragging: keep the running model
            }
        }
    }
    if (!sourcePtr && ImGui::CollapsingHeader("Headset", ImGuiTreeNodeFlags_DefaultOpen))
        for (const std::string& line : state.sessionLines) Text(line);
    if (sourcePtr && ImGui::CollapsingHeader("Gaze and head", ImGuiTreeNodeFlags_DefaultOpen)) {
        PreviewFrameSource& source = *sourcePtr;
        std::string gaze = source.GazeSourceName();
        if (Combo("gaze (G: mouse)", source.GazeSourceNames(), gaze)) source.SetGazeSource(gaze);
        GazeParams params = source.SyntheticParams();
        bool changed = false;
        const auto& rows = GazeParamTable();
        if (gaze == "lissajous") {
            // In degrees the amplitude spans what a static gaze may take.
            const ParamRange amplitude = SliderSpan(rows, "gaze.amplitude");
            const float top = float(params.units == "deg" ? SliderSpan(rows, "gaze.yaw_deg").max : amplitude.max);
            changed |= ImGui::SliderFloat2(params.units == "deg" ? "amplitude deg" : "amplitude px",
                                           &params.amplitude.x, float(amplitude.min), top, "%.0f");
            const ParamRange frequency = SliderSpan(rows, "gaze.frequency_hz");
            changed |= ImGui::SliderFloat2("frequency Hz", &params.frequencyHz.x, float(frequency.min),
                                           float(frequency.max), "%.2f");
        } else if (gaze == "static") {
            const ParamRange yaw = SliderSpan(rows, "gaze.yaw_deg"), pitch = SliderSpan(rows, "gaze.pitch_deg");
            changed |= ImGui::SliderFloat("yaw deg", &params.yawDeg, float(yaw.min), float(yaw.max), "%.1f");
            changed |= ImGui::SliderFloat("pitch deg", &params.pitchDeg, float(pitch.min), float(pitch.max), "%.1f");
        }
        if (changed) {
            try {
                source.SetSyntheticParams(params);
            } catch (const std::exception&) {
                // a value the gaze checks refuse while dragging: keep the running source
            }
        }
        const bool free = source.FreeHead().has_value();
        Text(free ? "head: free camera (WASD, Q/E, right-drag)" : "head: the scene's camera path");
        if (free && ImGui::Button("back to the camera path (C)")) state.requestReturnToPath = true;
    }
    if (state.tracker) DrawTrackerControls(*state.tracker, state.trackerRefused);
    if (ImGui::CollapsingHeader("Playback", ImGuiTreeNodeFlags_DefaultOpen)) {
        bool paused = controls.paused;
        if (ImGui::Checkbox("pause (space)", &paused)) loop.SetPaused(paused);
        ImGui::SameLine();
        if (ImGui::Button("step (N)")) loop.Step();
        float speed = controls.speed;
        if (ImGui::SliderFloat("speed", &speed, 0.0f, 4.0f, "%.2fx")) loop.SetSpeed(speed);
        if (ImGui::Button("save frame (F12)")) state.requestCapture = true;
    }
    if (ImGui::CollapsingHeader("Timing", ImGuiTreeNodeFlags_DefaultOpen) && shown) {
        const LiveTimings& t = shown->timings;
        Text(fmt::format("frame {}  {:.1f} frames/s  (window {:.0f} Hz, {})", shown->number,
                         stats.FramesPerSecond(), stats.DisplayFramesPerSecond(), presentMode));
        const auto& history = stats.History();
        if (!history.empty())
            Text(fmt::format("gaze-to-photon {:.1f} ms (median {:.1f}, p95 {:.1f})", history.back().latencyMs,
                             stats.LatencyPercentile(0.5), stats.LatencyPercentile(0.95)));
        Text(fmt::format("spp {:.1f}  trace {:.1f}  denoise {:.1f}  view {:.1f} ms", t.sppMs, t.traceMs,
                         t.denoiseMs, t.viewMs));
        if (!history.empty()) Text(fmt::format("present {:.1f} ms", history.back().presentMs));
        Text(fmt::format("{:.2f} Mrays/s ({} rays, {} guide rays)", t.RaysPerSecond() * 1e-6, t.rays, t.guideRays));
        std::vector<float> frameMs, denoiseMs;
        for (const auto& f : history) {
            frameMs.push_back(float(f.timings.frameMs));
            denoiseMs.push_back(float(f.timings.denoiseMs));
        }
        if (!frameMs.empty()) {
            ImGui::PlotLines("frame ms", frameMs.data(), int(frameMs.size()), 0, nullptr, 0.0f, FLT_MAX,
                             ImVec2(0, 40));
            ImGui::PlotLines("denoise ms", denoiseMs.data(), int(denoiseMs.size()), 0, nullptr, 0.0f,
                             FLT_MAX, ImVec2(0, 40));
        }
        // Per-pass plot: the last frame's denoiser passes (both eyes), one bar each, in order.
        std::vector<float> passMs;
        for (const PassTiming& p : t.passes) passMs.push_back(float(p.ms));
        if (!passMs.empty())
            ImGui::PlotHistogram("passes ms", passMs.data(), int(passMs.size()), 0, nullptr, 0.0f, FLT_MAX,
                                 ImVec2(0, 50));
        if (ImGui::BeginTable("passes", 2, ImGuiTableFlags_SizingStretchProp)) {
            for (const PassTiming& p : t.passes) {
                ImGui::TableNextRow();
                ImGui::TableNextColumn();
                Text(p.pass);
                ImGui::TableNextColumn();
                Text(fmt::format("{:.3f} ms", p.ms));
            }
            ImGui::EndTable();
        }
    }
    if (ImGui::CollapsingHeader("Memory")) {
        const std::vector<BufferPlan> memory = loop.DenoiserMemory();
        size_t total = 0;
        for (const BufferPlan& b : memory) total += b.bytes;
        const RunConfig& config = loop.Config();
        const double pixels = 2.0 * config.camera.width * config.camera.height;
        Text(fmt::format("{}: {} for both eyes, {:.1f} B/pixel", controls.denoiser, Bytes(total),
                         double(total) / pixels));
        if (ImGui::BeginTable("memory", 3, ImGuiTableFlags_SizingStretchProp | ImGuiTableFlags_ScrollY,
                              ImVec2(0, 160))) {
            for (const BufferPlan& b : memory) {
                ImGui::TableNextRow();
                ImGui::TableNextColumn();
                Text(b.name);
                ImGui::TableNextColumn();
                Text(Bytes(b.bytes));
                ImGui::TableNextColumn();
                Text(b.history ? "history" : b.transient ? "transient" : "scratch");
            }
            ImGui::EndTable();
        }
    }
    ImGui::End();
}

bool HandleLiveWindowKey(int key, LiveLoop& loop, GLFWwindow* window, PanelState& state, bool& panelShown) {
    const LiveControls controls = loop.Controls();
    switch (key) {
        case GLFW_KEY_SPACE: loop.SetPaused(!controls.paused); return true;
        case GLFW_KEY_TAB: panelShown = !panelShown; return true;
        case GLFW_KEY_O: state.display.overlay = !state.display.overlay; return true;
        case GLFW_KEY_L: state.display.layout = DisplayLayout((int(state.display.layout) + 1) % 3); return true;
        case GLFW_KEY_V: {
            const auto names = loop.ViewNames();
            auto it = std::find(names.begin(), names.end(), controls.view);
            loop.SetView(it == names.end() || it + 1 == names.end() ? names.front() : *(it + 1));
            return true;
        }
        case GLFW_KEY_ESCAPE: glfwSetWindowShouldClose(window, GLFW_TRUE); return true;
        default:
            if (key >= GLFW_KEY_1 && key <= GLFW_KEY_9) {
                const auto& names = DenoiserNames();
                const size_t i = size_t(key - GLFW_KEY_1);
                if (i < names.size()) loop.SetDenoiser(names[i]);
                return true;
            }
            return false;
    }
}

}  // namespace fovrt
