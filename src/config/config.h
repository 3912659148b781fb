// RunConfig: the typed configuration every fovrt command uses. Plain structs only: reading and
// writing TOML/JSON is in config/config_io.h, the command-line options in config/config_cli.h.
//
// Sources, applied to one TOML table before validation: built-in defaults (the default job runs
// with no file at all; a replay starts from the recording's config instead) <- `-c FILE` (TOML) <- each `--set section.key=value` in order (value in
// TOML syntax; a value that is not valid TOML is taken as a bare string, so
// `--set scene.name=veach-ajar` works) <- `--memory-budget BYTES`. Unknown keys, wrong types and
// out-of-range values are fovrt::Error naming the key (and file:line or "--set").
//
// Keys: every member below is one row of a settings table (key, member, range or names, meaning;
// the default is the member's initialiser): this library's sections in config/settings_tables.cpp,
// [foveation] in foveation/foveation_params.cpp, [gaze] in gaze/gaze_params.cpp, [denoise.*] in
// denoise/params.cpp. `fovrt config --keys` lists them all with their defaults.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "denoise/params.h"
#include "foveation/spp_model.h"
#include "gaze/gaze_source.h"

namespace fovrt {

struct SceneConfig {
    std::string name = "cornell";  // scene name or path
};

struct CameraConfig {
    int width = 640;   // per eye; thesis 1280
    int height = 360;  // per eye; thesis 720
    // Per-eye FOV in degrees {left, right, up, down}; nullopt = symmetric from the scene's
    // horizontal FOV and width/height (resolved by whoever builds the StereoRig).
    std::optional<std::array<float, 4>> fovDeg;
    float ipd = 0.063f;  // metres
};

struct RunSettings {
    int frames = 16;
    int firstFrame = 0;
    // Frames traced and denoised before first_frame, neither scored nor written: the denoisers'
    // histories reach the steady state a running headset shows before the first scored frame.
    int warmupFrames = 0;
    float fps = 0.0f;    // frame i is at time i / fps seconds; 0 = the scene's frame rate
    uint32_t seed = 1;
    int threads = 0;     // 0 = all cores
    int maxDepth = 2;    // path vertices after the camera: 1 = direct only, 2 = one indirect bounce
    bool score = false;  // `run`: relMSE, SSIM, FLIP and FovVideoVDP against the cached references
};

struct RenderConfig {
    std::string demodulation = "albedo";  // "albedo" | "brdf" (core/frame_inputs.h Demodulation)
};

using FoveationConfig = FoveationParams;
using GazeConfig = GazeParams;

struct DenoiseConfig {
    std::vector<std::string> denoisers = {"svgf"};
    std::string device = "auto";  // auto | vulkan | cpu | <Vulkan device index> (vk/device_choice.h)
    // Includes precision: the setting's default is auto (fp16 storage on a GPU, ResolvePrecision).
    DenoiserParams params = [] {
        DenoiserParams p;
        p.precision = Precision::Auto;
        return p;
    }();
};

struct OutputConfig {
    std::string dir = "out";
    bool writeExr = false;     // denoised HDR per eye per frame
    bool writePng = true;      // tonemapped previews
    bool writeInputs = true;   // FrameInputs + spp map EXR per frame and eye (`run`'s product)
    bool writeDebugViews = false;  // each denoiser's debug views, one EXR layer each, per frame and eye (`run`)
    float exposure = 0.0f;     // stops, PNG only
    bool report = true;        // HTML/JSON report at the end
};

struct ReferenceConfig {
    int spp = 1024;
    // The reference's own sampling seed: fixed, so every run seed is scored against the same
    // reference (its noise is then one bias shared by all seeds and variants, not seed noise).
    uint32_t seed = 1;
    std::string cacheDir = "cache/reference";
};

struct MetricConfig {
    bool vdp = true;                  // score every variant with FovVideoVDP
    std::string display = "camera";   // "camera" or a VdpDisplayProfiles() name
    float ppd = 0.0f;                 // > 0: pixels per degree instead of the display's
    float peak = 0.0f;                // > 0: peak luminance (cd/m²) instead of the display's
};

struct RunConfig {
    SceneConfig scene;
    CameraConfig camera;
    RunSettings run;
    RenderConfig render;
    FoveationConfig foveation;
    GazeConfig gaze;
    DenoiseConfig denoise;
    OutputConfig output;
    ReferenceConfig reference;
    MetricConfig metric;
    uint64_t memoryBudget = 0;  // bytes, 0 = none
};

// The default job's configuration (validated like any other).
RunConfig DefaultConfig();

// Parses "1234", "512MiB", "2GB" etc. into bytes; `what` names the option/key in errors.
uint64_t ParseByteSize(const std::string& text, const std::string& what);

}  // namespace fovrt
