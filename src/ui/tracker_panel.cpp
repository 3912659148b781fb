#include "ui/tracker_panel.h"

#include <exception>
#include <string>

#include <imgui.h>

namespace fovrt {

void DrawTrackerControls(TrackedFrameSource& tracker, std::string& refused) {
    if (!ImGui::CollapsingHeader("Eye tracker")) return;
    TrackerParams params = tracker.Params();
    bool changed = false;
    // A logarithmic slider over the span of the key's row (gaze/gaze_params.cpp).
    auto slider = [&](const char* label, const char* key, float& value, const char* format) {
        const ParamRange span = SliderSpan(TrackerParamTable(), key);
        return ImGui::SliderFloat(label, &value, float(span.min), float(span.max), format,
                                  ImGuiSliderFlags_Logarithmic);
    };
    float rate = float(params.rateHz), latency = float(params.latencyMs);
    if (slider("rate Hz (0: every frame)", "gaze.tracker_rate_hz", rate, "%.0f")) {
        params.rateHz = rate;
        changed = true;
    }
    if (slider("latency ms", "gaze.tracker_latency_ms", latency, "%.0f")) {
        params.latencyMs = latency;
        changed = true;
    }
    changed |= slider("noise deg RMS", "gaze.tracker_noise_deg", params.noiseDeg, "%.2f");
    if (ImGui::BeginCombo("prediction", params.prediction.c_str())) {
        for (const char* name : PredictionNames())
            if (ImGui::Selectable(name, params.prediction == name)) {
                changed |= params.prediction != name;
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
