// RunConfig: the typed configuration every fovrt command uses. Plain structs only: reading and
// writing TOML/JSON is in config/config_io.h, the command-line options in config/config_cli.h.
//
// Sources, applied to one TOML table before validation: built-in defaults (the default job runs
// with no file at all; a replay starts from the recording's config instead) <- `-c FILE` (TOML) <- each `--set section.key=value` in order (value in
// TOML syntax; a value that is not valid TOML is taken as a bare string, so
// `--set scene.name=veach-ajar` works) <- `--memory-budget BYTES`. Unknown keys, wrong types and
// out-of-range values are fovrt::Error naming the key (and file:line or "--set").
//
// Keys (TOML):
//   memory_budget = 0              bytes, 0 = none; also "512MiB", "2GB" (K/M/G/T, KiB/MiB/GiB/TiB)
//   [scene]      name = "cornell"  a scene name or a path to a scene file
//   [camera]     width = 640, height = 360 (per eye; thesis: 1280×720)
//                fov_deg = [left, right, up, down]  per-eye FOV in degrees (left/down negative);
//                    absent = symmetric from the scene's horizontal fov and width/height
//                ipd = 0.063 (metres)
//   [run]        frames = 16, first_frame = 0, fps = 0 (frame i at i/fps s; 0 = the scene's
//                frame_rate), seed = 1,
//                threads = 0 (0 = all cores), max_depth = 2 (1 = direct only, 2 = one bounce),
//                score = false (`run` only: score every variant against the cached references,
//                app/run_score.h)
//   [render]     demodulation = "albedo"|"brdf": what the tracer divides direct / indirect by
//                (the primary albedo, or the BRDF pre-integration F_β, SPEC §6); both factor
//                planes are written either way, and a denoiser named "<name>+brdf"/"+albedo"
//                re-demodulates to its own (denoise/variants.h)
//   [foveation]  model = "disc"|"linear"|"acuity"|"uniform", spp_inside = 8, spp_outside = 1,
//                radius_px = 200, radius_reference_width = 1280, radius_deg = 0, spp_max = 8,
//                spp_min = 1, foveal_deg = 5, peripheral_deg = 30, omega0_deg = 1/48,
//                mar_slope = 0.022, uniform_spp = 1, ray_budget = 0 (samples per eye per frame)
//   [gaze]       source = "lissajous"|"trace"|"recording"|"static"|"mouse" (preview only), units = "px"|"deg",
//                amplitude = [640, 360], frequency_hz = [0.4, 0.5], phase_deg = [90, 0],
//                offset = [0, 0], reference_width = 1280, reference_height = 720,
//                trace_path = "", trace_start_ms = 0, yaw_deg = 0, pitch_deg = 0,
//                blink = "hold"|"uniform" (an invalid sample: hold = foveate on the last valid
//                direction; uniform = a uniform spp map at the foveated map's mean, rounded),
//                recording_path = "" (headset recording, gaze/recording.h), the eye tracker
//                (gaze/tracker.h; defaults = ideal): tracker_rate_hz = 0, tracker_phase_ms = 0,
//                tracker_latency_ms = 0, tracker_noise_deg = 0, tracker_bias_deg = [0, 0],
//                tracker_dropout = 0, tracker_blink_ms = 0, tracker_seed = 1,
//                prediction = "none"|"cv"|"landing", saccade_deg_s = 100
//   [denoise]    denoisers = ["svgf"], device = "auto"|"vulkan"|"cpu"|"<index>" (vk/device_choice.h)
//   denoise.precision and [denoise.svgf], [denoise.asvgf], [denoise.two_history]: the parameter
//                tables in denoise/params.cpp (key, default, range, doc; `fovrt config --keys`)
//   [output]     dir = "out", write_exr = false, write_png = true, write_inputs = true,
//                exposure = 0 (stops, PNG only), report = true
//   [reference]  spp = 1024, seed = 1 (the reference's own; independent of run.seed), cache_dir = "cache/reference"
//   [metric]     FovVideoVDP in `fovrt experiment` (app/experiment_vdp.h): vdp = true,
//                display = "camera" (the eye camera's own pixels per degree, 100 cd/m²) or a
//                profile of metrics/vdp_display.h ("headset-25", ...), ppd = 0 and peak = 0
//                (> 0: override the display's pixels per degree / peak cd/m²)
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
    DenoiserParams params;        // includes precision (fp32 | fp16)
};

struct OutputConfig {
    std::string dir = "out";
    bool writeExr = false;     // denoised HDR per eye per frame
    bool writePng = true;      // tonemapped previews
    bool writeInputs = true;   // FrameInputs + spp map EXR per frame and eye (`run`'s product)
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

// Per-eye FOV: camera.fov_deg when given, else symmetric from the scene's horizontal FOV and
// camera.width / camera.height.
Fov EyeFov(const CameraConfig& camera, float sceneHorizontalFovDegrees);
// Time of a frame in seconds: frame / run.fps, or frame / sceneFrameRate when run.fps = 0.
double FrameTimeSeconds(const RunSettings& run, float sceneFrameRate, int frame);

}  // namespace fovrt
