// The rows of the sections this library owns (the modules own theirs: settings_tables.h).
#include "config/settings_tables.h"

#include <algorithm>
#include <array>
#include <limits>

#include <nlohmann/json.hpp>

#include "config/config_io.h"
#include "core/frame_inputs.h"
#include "metrics/vdp_display.h"

namespace fovrt {
namespace {

constexpr double kMaxInt = double(std::numeric_limits<int>::max());
constexpr ParamRange kSeed = Closed(0, double(std::numeric_limits<uint32_t>::max()));
constexpr ParamRange kPixels = Closed(1, 16384);

// metric.display: "camera" or a FovVideoVDP display profile.
NameList MetricDisplayNames() {
    static const std::vector<const char*> names = [] {
        std::vector<const char*> list = {"camera"};
        for (const VdpDisplay& display : VdpDisplayProfiles()) list.push_back(display.name.c_str());
        return list;
    }();
    return names;
}

constexpr std::array<SettingRow<RunConfig>, 1> kRunConfigRows{{
    {{.key = "memory_budget", .range = Closed(0, 0x1p63),
      .doc = "bytes the denoisers may allocate, 0 = none; also \"512MiB\", \"2GB\" (K/M/G/T, KiB/MiB/GiB/TiB)"},
     &RunConfig::memoryBudget},
}};

constexpr std::array<SettingRow<SceneConfig>, 1> kSceneRows{{
    {{.key = "scene.name",
      .doc = "a scene name (scenes/) or a path to a scene file",
      .nonEmpty = true,
      .path = true,
      .orName = true},
     &SceneConfig::name},
}};

constexpr std::array<SettingRow<CameraConfig>, 4> kCameraRows{{
    {{.key = "camera.width", .range = kPixels, .doc = "pixels per eye (thesis 1280)"}, &CameraConfig::width},
    {{.key = "camera.height", .range = kPixels, .doc = "pixels per eye (thesis 720)"}, &CameraConfig::height},
    {{.key = "camera.fov_deg", .range = Open(-90, 90),
      .doc = "per-eye FOV [left, right, up, down] in degrees (left, down negative); absent = symmetric from "
             "the scene's horizontal FOV and width/height"},
     &CameraConfig::fovDeg},
    {{.key = "camera.ipd", .range = Closed(0, 1), .doc = "interpupillary distance in metres"}, &CameraConfig::ipd},
}};

constexpr std::array<SettingRow<RunSettings>, 8> kRunRows{{
    {{.key = "run.frames", .range = Closed(1, kMaxInt), .doc = "frames to render"}, &RunSettings::frames},
    {{.key = "run.first_frame", .range = Closed(0, kMaxInt), .doc = "index of the first frame"},
     &RunSettings::firstFrame},
    {{.key = "run.warmup_frames", .range = Closed(0, kMaxInt),
      .doc = "frames traced and denoised before first_frame (at most first_frame), neither scored nor written: "
             "the histories' steady state"},
     &RunSettings::warmupFrames},
    {{.key = "run.fps", .range = Closed(0, 10000), .doc = "frame i is at i/fps seconds; 0 = the scene's frame_rate"},
     &RunSettings::fps},
    {{.key = "run.seed", .range = kSeed, .doc = "seed of the noisy renders (the reference has its own)"},
     &RunSettings::seed},
    {{.key = "run.threads", .range = Closed(0, 4096), .doc = "tracer threads; 0 = all cores"}, &RunSettings::threads},
    {{.key = "run.max_depth", .range = Closed(0, 1024),
      .doc = "path vertices after the camera: 1 = direct only, 2 = one indirect bounce"},
     &RunSettings::maxDepth},
    {{.key = "run.score",
      .doc = "`fovrt run` only: score every variant against the cached references (relMSE, SSIM, FLIP, "
             "FovVideoVDP; app/run_score.h)"},
     &RunSettings::score},
}};

constexpr std::array<SettingRow<RenderConfig>, 1> kRenderRows{{
    {{.key = "render.demodulation",
      .doc = "what the tracer divides direct / indirect by: the primary albedo or the BRDF pre-integration "
             "(SPEC §6); a denoiser \"<name>+brdf\" / \"+albedo\" re-demodulates to its own",
      .names = DemodulationNames},
     &RenderConfig::demodulation},
}};

constexpr std::array<SettingRow<DenoiseConfig>, 2> kDenoiseRows{{
    {{.key = "denoise.denoisers", .doc = "denoisers to run: names, or a family and mechanisms joined by + (docs/denoisers.md, `fovrt info`)"},
     &DenoiseConfig::denoisers},
    {{.key = "denoise.device", .doc = "auto, vulkan, cpu or a Vulkan device index (vk/device_choice.h)"},
     &DenoiseConfig::device},
}};

constexpr std::array<SettingRow<OutputConfig>, 7> kOutputRows{{
    {{.key = "output.dir", .doc = "output folder", .nonEmpty = true}, &OutputConfig::dir},
    {{.key = "output.write_exr", .doc = "denoised HDR EXR per eye per frame"}, &OutputConfig::writeExr},
    {{.key = "output.write_png", .doc = "tonemapped PNG previews"}, &OutputConfig::writePng},
    {{.key = "output.write_inputs", .doc = "FrameInputs + spp map EXR per frame and eye (run)"},
     &OutputConfig::writeInputs},
    {{.key = "output.write_debug_views",
      .doc = "each denoiser's debug views (p, t, historyU, ...) as the layers of one EXR per frame and eye (run)"},
     &OutputConfig::writeDebugViews},
    {{.key = "output.exposure", .range = Closed(-64, 64), .doc = "PNG exposure in stops",
      .slider = Closed(-8, 8)},  // the preview panel's and the HTML report's exposure sliders
     &OutputConfig::exposure},
    {{.key = "output.report", .doc = "HTML/JSON report at the end"}, &OutputConfig::report},
}};

constexpr std::array<SettingRow<ReferenceConfig>, 3> kReferenceRows{{
    {{.key = "reference.spp",
      .range = Closed(1, 1 << 24),
      .doc = "samples per pixel of the reference (a multiple of 1024 above it: the mean of cached 1024-spp chunks)"},
     &ReferenceConfig::spp},
    {{.key = "reference.seed", .range = kSeed,
      .doc = "the reference's own sampling seed (every run seed is scored against the same reference)"},
     &ReferenceConfig::seed},
    {{.key = "reference.cache_dir", .doc = "where rendered references are cached"}, &ReferenceConfig::cacheDir},
}};

constexpr std::array<SettingRow<MetricConfig>, 4> kMetricRows{{
    {{.key = "metric.vdp", .doc = "score every variant with FovVideoVDP in `fovrt experiment`"}, &MetricConfig::vdp},
    {{.key = "metric.display",
      .doc = "camera (the eye camera's pixels per degree, 100 cd/m²) or a display profile (metrics/vdp_display.h)",
      .names = MetricDisplayNames},
     &MetricConfig::display},
    {{.key = "metric.ppd", .range = Closed(0, 1000), .doc = "> 0: pixels per degree instead of the display's"},
     &MetricConfig::ppd},
    {{.key = "metric.peak", .range = Closed(0, 100000), .doc = "> 0: peak luminance (cd/m²) instead of the display's"},
     &MetricConfig::peak},
}};

static_assert(RowsWellFormed(kRunConfigRows) && RowsWellFormed(kSceneRows) && RowsWellFormed(kCameraRows) &&
                  RowsWellFormed(kRunRows) && RowsWellFormed(kRenderRows) && RowsWellFormed(kDenoiseRows) &&
                  RowsWellFormed(kOutputRows) && RowsWellFormed(kReferenceRows) && RowsWellFormed(kMetricRows),
              "a settings row is malformed (see ParamRowProblem)");

template <class Value>
std::string Allowed(const ParamInfo& info, const Value&) {
    using T = std::decay_t<Value>;
    if constexpr (std::is_same_v<T, bool>) {
        return "true|false";
    } else if constexpr (std::is_same_v<T, std::string>) {
        if (info.names == nullptr) return info.nonEmpty ? "text, not empty" : "text";
        std::string list;
        for (const char* name : info.names()) {
            if (!list.empty()) list += '|';
            list += name;
        }
        return list;
    } else if constexpr (std::is_same_v<T, std::vector<std::string>>) {
        return "list of names";
    } else if constexpr (std::is_same_v<T, vec2>) {
        return "[x, y], each in " + info.range.Describe();
    } else if constexpr (std::is_same_v<T, FovDegrees>) {
        return "4 angles, each in " + info.range.Describe();
    } else {
        return info.range.Describe();
    }
}

}  // namespace

std::span<const SettingRow<RunConfig>> RunConfigTable() { return kRunConfigRows; }
std::span<const SettingRow<SceneConfig>> SceneTable() { return kSceneRows; }
std::span<const SettingRow<CameraConfig>> CameraTable() { return kCameraRows; }
std::span<const SettingRow<RunSettings>> RunTable() { return kRunRows; }
std::span<const SettingRow<RenderConfig>> RenderTable() { return kRenderRows; }
std::span<const SettingRow<DenoiseConfig>> DenoiseTable() { return kDenoiseRows; }
std::span<const SettingRow<OutputConfig>> OutputTable() { return kOutputRows; }
std::span<const SettingRow<ReferenceConfig>> ReferenceTable() { return kReferenceRows; }
std::span<const SettingRow<MetricConfig>> MetricTable() { return kMetricRows; }

std::vector<SettingLine> DescribeSettings() {
    const RunConfig defaults = DefaultConfig();
    const nlohmann::json written = ConfigToJson(defaults);
    auto writtenValue = [&](const std::string& key) {
        std::string path = "/";
        path += key;
        std::replace(path.begin(), path.end(), '.', '/');
        const nlohmann::json::json_pointer pointer(path);
        if (!written.contains(pointer)) return std::string();
        const nlohmann::json& value = written.at(pointer);
        // Strings bare (disc, not "disc"), except an empty one.
        return value.is_string() && !value.get<std::string>().empty() ? value.get<std::string>() : value.dump();
    };
    std::vector<SettingLine> lines;
    ForEachSetting(defaults, [&](const ParamInfo& info, const auto& value) {
        lines.push_back({info.key, writtenValue(info.key), Allowed(info, value), info.doc});
    });
    const std::string precision;  // the enum's row reads as a string setting
    lines.push_back({kPrecisionKey, writtenValue(kPrecisionKey), Allowed(kPrecisionInfo, precision), kPrecisionDoc});
    return lines;
}

}  // namespace fovrt
