// `fovrt run`: the headless job. Renders N frames of both eyes with the configured gaze source
// and spp model, writes per frame and eye a multi-layer EXR with every FrameInputs channel, the
// renderer's visibility buffer and the spp map, denoises with every configured variant, and finishes with a run manifest (JSON: the
// fully resolved config, versions, seed, per-stage timings, counters). The manifest is written
// last: a directory without manifest.json is an interrupted run.
#include <chrono>
#include <cstdio>
#include <filesystem>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "app/build_info.h"
#include "app/commands.h"
#include "app/config.h"
#include "app/config_cli.h"
#include "app/config_io.h"
#include "app/denoiser_set.h"
#include "app/frame_pipeline.h"
#include "app/progress.h"
#include "core/atomic_file.h"
#include "denoise/memory_plan.h"
#include "io/exr.h"
#include "io/png.h"
#include "render/visibility_buffer.h"

namespace fovrt {
namespace {

const char* kEyeNames[2] = {"left", "right"};

double MsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
}

std::string FrameStem(uint32_t frame, int eye) {
    return fmt::format("f{:05d}_{}", frame, kEyeNames[eye]);
}

// Per-frame working memory: two eyes of FrameInputs plus the spp maps.
size_t FrameInputsBytes(const RunConfig& config) {
    FrameInputs probe;
    probe.Allocate(config.camera.width, config.camera.height);
    return 2 * (probe.Bytes() + size_t(config.camera.width) * config.camera.height * 2);
}

// The renderer's visibility buffers, one per eye (the A-SVGF history's second is not counted, as
// before the buffers left FrameInputs).
size_t VisibilityBytes(const RunConfig& config) {
    VisibilityBuffer probe;
    probe.Allocate(config.camera.width, config.camera.height);
    return 2 * probe.Bytes();
}

void EnforceRunBudget(const RunConfig& config) {
    std::vector<BufferPlan> plan = PlanRunMemory(config);
    plan.push_back({"frame_inputs.both_eyes", FrameInputsBytes(config), false});
    plan.push_back({"render.visibility.both_eyes", VisibilityBytes(config), false});
    EnforceMemoryBudget(plan, config.memoryBudget, "run");
}

void Run(const RunConfig& config) {
    namespace fs = std::filesystem;
    EnforceRunBudget(config);
    const fs::path outDir = config.output.dir;
    fs::create_directories(outDir);
    // A stale manifest from an earlier run would make this one look complete while it runs.
    fs::remove(outDir / "manifest.json");

    auto totalStart = std::chrono::steady_clock::now();
    FramePipeline pipeline(config);
    DenoiserSet denoisers(config.denoise);
    std::fprintf(stderr, "fovrt run: scene '%s', %d frames, %d×%d per eye, denoisers on %s -> %s\n",
                 pipeline.GetScene().name.c_str(), config.run.frames, config.camera.width,
                 config.camera.height, denoisers.DeviceDescription().c_str(),
                 outDir.string().c_str());

    nlohmann::json frames = nlohmann::json::array();
    Progress progress("rendering", config.run.frames);
    StereoFrame frame;
    Plane<vec3> denoised;
    uint64_t totalSamples = 0;
    uint64_t recordedSamples = 0;  // Σ FrameInputs::sampleCount: A-SVGF gradient pixels trace n_prev
    for (int i = 0; i < config.run.frames; ++i) {
        uint32_t index = uint32_t(config.run.firstFrame + i);
        pipeline.Render(index, frame);

        nlohmann::json record;
        record["frame"] = index;
        record["time_s"] = frame.timeSeconds;
        record["gaze_head"] = {frame.gaze.direction.x, frame.gaze.direction.y,
                               frame.gaze.direction.z};
        for (int eye = 0; eye < 2; ++eye) {
            EyeFrame& e = frame.eyes[size_t(eye)];
            nlohmann::json eyeRecord;
            eyeRecord["gaze_pixel"] = {e.gazePixel.x, e.gazePixel.y};
            eyeRecord["spp_ms"] = e.sppMs;
            eyeRecord["render_ms"] = e.renderMs;
            uint64_t samples = 0;
            for (size_t p = 0; p < e.sppMap.size(); ++p) samples += e.sppMap[p];
            totalSamples += samples;
            for (size_t p = 0; p < e.inputs.sampleCount.size(); ++p) recordedSamples += e.inputs.sampleCount[p];
            eyeRecord["samples"] = samples;

            auto writeStart = std::chrono::steady_clock::now();
            std::string stem = FrameStem(index, eye);
            if (config.output.writeInputs)
                WriteFrameInputsExr(outDir / "inputs" / (stem + ".exr"), e.inputs, e.sppMap,
                                    PlaneLayers(pipeline.GetRenderer().Visibility(eye)));
            if (config.output.writePng) {
                WritePng(outDir / "noisy" / (stem + ".png"), e.inputs.NoisyImage(),
                         config.output.exposure);
            }
            eyeRecord["write_inputs_ms"] = MsSince(writeStart);

            nlohmann::json denoiseRecord = nlohmann::json::object();
            for (size_t v = 0; v < denoisers.size(); ++v) {
                Denoiser& denoiser = denoisers.At(v, eye);
                auto start = std::chrono::steady_clock::now();
                denoiser.Denoise(e.inputs, denoised);
                nlohmann::json passes = nlohmann::json::object();
                for (const PassTiming& t : denoiser.LastTimings()) passes[t.pass] = t.ms;
                denoiseRecord[denoisers.Name(v)] = {{"wall_ms", MsSince(start)}, {"passes_ms", passes}};
                fs::path dir = outDir / "denoised" / denoisers.Name(v);
                if (config.output.writePng)
                    WritePng(dir / (stem + ".png"), denoised, config.output.exposure);
                if (config.output.writeExr) WriteRgbExr(dir / (stem + ".exr"), denoised);
            }
            eyeRecord["denoise"] = denoiseRecord;
            record[kEyeNames[eye]] = eyeRecord;
        }
        frames.push_back(record);
        progress.Step(fmt::format("frame {}", index));
    }
    progress.Finish();

    RenderStats stats = pipeline.GetRenderer().Stats();
    nlohmann::json manifest;
    manifest["command"] = "run";
    manifest["complete"] = true;
    manifest["build"] = BuildInfoJson();
    manifest["config"] = ConfigToJson(config);
    manifest["seed"] = config.run.seed;
    manifest["scene"] = {{"name", pipeline.GetScene().name},
                         {"source", pipeline.GetScene().sourcePath.string()},
                         {"frame_rate", pipeline.FramesPerSecond()}};
    manifest["denoise_device"] = denoisers.DeviceDescription();
    manifest["counters"] = {{"samples", totalSamples},
                            {"recorded_samples", recordedSamples},
                            {"traced_samples", stats.samples},
                            {"rays", stats.Rays()},
                            {"primary_rays", stats.primaryRays},
                            {"shadow_tests", stats.shadowRays},
                            {"shadow_rays_reused", stats.shadowRaysReused},
                            {"bounce_rays", stats.bounceRays},
                            {"dropped_nonfinite_samples", stats.droppedSamples}};
    nlohmann::json replaced = nlohmann::json::object();
    for (size_t v = 0; v < denoisers.size(); ++v) {
        uint64_t nonFinite = 0, negative = 0;
        for (int eye = 0; eye < 2; ++eye) {
            nonFinite += denoisers.At(v, eye).Stats().nonFiniteSamples;
            negative += denoisers.At(v, eye).Stats().negativeSamples;
        }
        replaced[denoisers.Name(v)] = {{"nonfinite", nonFinite}, {"negative", negative}};
    }
    manifest["counters"]["denoiser_replaced_samples"] = replaced;
    manifest["frames"] = frames;
    manifest["total_s"] = MsSince(totalStart) / 1000.0;
    WriteTextAtomically(outDir / "manifest.json", manifest.dump(2) + "\n");
    std::fprintf(stderr, "fovrt run: %d frames in %.1f s, %.2f Mrays, manifest %s\n",
                 config.run.frames, MsSince(totalStart) / 1000.0, double(stats.Rays()) * 1e-6,
                 (outDir / "manifest.json").string().c_str());
}

}  // namespace

void RegisterRunCommand(CLI::App& app) {
    CLI::App* cmd = app.add_subcommand(
        "run", "Headless job: render N stereo frames with foveated spp maps, write FrameInputs EXRs, "
               "denoise, write a run manifest");
    auto options = std::make_shared<ConfigOptions>();
    AddConfigOptions(cmd, *options);
    cmd->callback([options] { Run(ResolveConfig(*options)); });
}

}  // namespace fovrt
