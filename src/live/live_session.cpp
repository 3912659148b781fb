#include "live/live_session.h"

#include <algorithm>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "config/config_io.h"
#include "core/error.h"
#include "io/exr.h"
#include "pipeline/build_info.h"

namespace fovrt {

namespace fs = std::filesystem;

void CheckViewName(const std::string& view, const std::vector<std::string>& views, const std::string& denoiser) {
    if (std::find(views.begin(), views.end(), view) == views.end())
        Fail("--view {}: not a view of denoiser {} (views: {})", view, denoiser, fmt::format("{}", fmt::join(views, ", ")));
}

std::string LiveDisplayDevice(const RunConfig& config) {
    return config.denoise.device == "cpu" ? "auto" : config.denoise.device;
}

LiveSessionWiring::LiveSessionWiring(LiveLoop& loop, const LiveSessionOptions& options,
                                     nlohmann::json recordingHeader) {
    CheckViewName(options.view, loop.ViewNames(), loop.Controls().denoiser);
    loop.SetView(options.view);
    if (options.writeInputs) {
        const fs::path dir = fs::path(loop.Config().output.dir) / "inputs";
        fs::create_directories(dir);
        loop.OnFrameDone([dir](const LiveFrame& f) {
            for (int eye = 0; eye < 2; ++eye) {
                const EyeFrame& e = f.stereo.eyes[size_t(eye)];
                WriteFrameInputsExr(dir / (FrameOutputStem(f.stereo.frame, eye) + ".exr"), e.inputs, e.sppMap);
            }
        });
    }
    if (!options.record.empty()) {
        recordingHeader["build"] = BuildInfoJson();
        loop.OnFrameStart([this, path = fs::path(options.record), config = ConfigToJson(loop.Config()),
                           header = std::move(recordingHeader)](const SourcedFrame& f) {
            if (!recorder_) recorder_.emplace(path, config, header);
            std::vector<GazeSample> samples;
            for (const TimedGaze& g : f.gazeSamples) samples.push_back(g.gaze);
            recorder_->Append(f.request, f.head, samples);
        });
    }
}

void LiveSessionWiring::Close() {
    if (recorder_) recorder_->Close();
}

std::optional<fs::path> LiveSessionWiring::RecordedTo() const {
    if (!recorder_) return std::nullopt;
    return recorder_->Path();
}

}  // namespace fovrt
