#include "ui/tracker_panel.h"

#include <exception>
#include <string>

#include <imgui.h>

namespace fovrt {

void DrawTrackerControls(TrackedFrameSource& tracker, std::string& refused) {
    if (!ImGui::CollapsingHeader("Eye tracker")) return;
    const auto& rows = TrackerParamTable();
    TrackerParams params = tracker.Params();
    bool changed = false;
    constexpr ImGuiSliderFlags kLog = ImGuiSliderFlags_Logarithmic;
    float rate = float(params.rateHz), latency = float(params.latencyMs);
    if (ImGui::SliderFloat("rate Hz (0: every frame)", &rate, 0.0f, float(SliderSpan(rows, "gaze.tracker_rate_hz").max), "%.0f", kLog)) {
        params.rateHz = rate;
        changed = true;
    }
    if (ImGui::SliderFloat("latency ms", &latency, 0.0f, float(SliderSpan(rows, "gaze.tracker_latency_ms").max), "%.0f", kLog)) {
        params.latencyMs = latency;
        changed = true;
    }
    changed |= ImGui::SliderFloat("noise deg RMS", &params.noiseDeg, 0.0f, float(SliderSpan(rows, "gaze.tracker_noise_deg").max), "%.2f", kLog);
    if (ImGui::BeginCombo("prediction", params.prediction.c_str())) {
        for (const std::string name : PredictionNames())
            if (ImGui::Selectable(name.c_str(), name == params.prediction)) {
                changed |= name != params.prediction;
                params.prediction = name;
            }
        ImGui::EndCombo();
    }
    // A refusal stays on screen until a change is accepted (e.g. prediction without a rate).
    if (changed) {
        try {
            tracker.SetParams(params);
            refused.clear();
        } catch (const std::exception& e) {
            refused = e.what();
        }
    }
    if (!refused.empty()) ImGui::TextWrapped("%s", refused.c_str());
    ImGui::TextWrapped(IsIdealTracker(tracker.Params())
                           ? "ideal: the spp map follows the gaze itself"
                           : "overlay: + and circle = the tracked gaze the spp map follows, x = the true gaze");
}

}  // namespace fovrt
