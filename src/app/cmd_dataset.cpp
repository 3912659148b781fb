// `fovrt dataset`: training sequences for the recurrent denoising autoencoder (SPEC §12,
// training/). For every scene, spp mode (the config's foveation model, and uniform 1 spp) and eye
// it renders `run.frames` consecutive frames through the same FramePipeline as `run` and
// `experiment`, and writes
//   <scene>_<mode>_<eye>_input.npy   float32 [T, 8, H, W]: the RAE's raw features
//                                    (denoise/reference/rae_features.h; colour linear)
//   <scene>_<mode>_<eye>_target.npy  float32 [T, 3, H, W]: the reference.spp reference,
//                                    demodulated like the input (RaeTarget)
// and manifest.json (channels, sizes, split per sequence, the settings). With
// --noise-realisations K > 1, training sequences also get K−1 more noisy inputs of the same frames
// traced with other seeds, <scene>_<mode>_<eye>_input_n<r>.npy (manifest "inputs_extra"): the
// paper's camera stops (§4.3) hold the camera and target while the noise advances. Scenes listed with
// --eval are marked split "eval" (held out of training); references come from the reference cache
// (rendered with the base seed, so both spp modes share them).
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "app/commands.h"
#include "app/progress.h"
#include "config/config.h"
#include "config/config_cli.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/rng.h"
#include "denoise/reference/rae_features.h"
#include "io/npy.h"
#include "pipeline/denoiser_set.h"
#include "pipeline/frame_pipeline.h"
#include "pipeline/reference_cache.h"

namespace fovrt {
namespace {

struct DatasetOptions {
    std::string out = "out/rae-dataset";
    std::vector<std::string> scenes = {"cornell", "pillars", "room", "box"};
    std::vector<std::string> eval = {"veach-ajar", "suzanne"};
    bool uniform = true;  // also a uniform 1-spp sequence per scene and eye
    int noiseRealisations = 1;  // noisy inputs per training frame (1 + extra seeds)
    bool gazePerScene = false;  // each scene its own Lissajous path (GazeForScene)
};

// --gaze-per-scene: the config's Lissajous path varied per scene, drawn from the scene's name (the
// same scene always gets the same path): phases uniform in [0°, 360°), frequencies scaled by
// [0.6, 1.4) and amplitudes by [0.5, 1), so that where the dense samples go over a room differs
// from room to room, as it does between viewers.
GazeParams GazeForScene(GazeParams gaze, const std::string& sceneName) {
    uint32_t h = 2166136261u;  // FNV-1a of the name
    for (const char c : sceneName) h = (h ^ uint8_t(c)) * 16777619u;
    auto uniform = [&](uint32_t i) { return float(double(HashCombine(h, i)) / 4294967296.0); };
    for (int a = 0; a < 2; ++a) {
        gaze.phaseDeg[a] = 360.0f * uniform(uint32_t(a));
        gaze.frequencyHz[a] *= 0.6f + 0.8f * uniform(uint32_t(2 + a));
        gaze.amplitude[a] *= 0.5f + 0.5f * uniform(uint32_t(4 + a));
    }
    return gaze;
}

// Seed of noise realisation r (>= 1) of spp mode m: apart from every mode's base seed.
uint32_t RealisationSeed(uint32_t base, size_t mode, int r) { return base + uint32_t(mode) * 7919u + uint32_t(r) * 104729u; }

void Append(NpyArray& array, const Tensor& t) {
    array.data.insert(array.data.end(), t.data.begin(), t.data.end());
}

void WriteDataset(RunConfig base, const DatasetOptions& o) {
    // Before anything large is allocated (the same model as `fovrt run`; every listed variant counted).
    EnforceRunBudget(base, "dataset");
    if (o.gazePerScene && base.gaze.source != "lissajous")
        Fail("--gaze-per-scene varies a Lissajous path, and gaze.source = \"{}\"", base.gaze.source);
    nlohmann::json manifest;
    manifest["channels"] = {"illum_r", "illum_g", "illum_b", "normal_view_x", "normal_view_y",
                            "depth_d_over_d_plus_1", "roughness", "log2_spp_over_4"};
    manifest["gamma"] = 0.2;
    manifest["width"] = base.camera.width;
    manifest["height"] = base.camera.height;
    manifest["frames"] = base.run.frames;
    manifest["first_frame"] = base.run.firstFrame;
    manifest["reference_spp"] = base.reference.spp;
    manifest["max_depth"] = base.run.maxDepth;
    manifest["foveation"] = base.foveation.model;
    manifest["noise_realisations"] = o.noiseRealisations;
    manifest["sequences"] = nlohmann::json::array();
    std::vector<std::pair<std::string, bool>> scenes;
    for (const std::string& s : o.scenes)
        if (!s.empty()) scenes.push_back({s, false});
    for (const std::string& s : o.eval)
        if (!s.empty()) scenes.push_back({s, true});  // --eval "": no held-out scene
    std::vector<std::string> modes = {base.foveation.model};
    if (o.uniform && base.foveation.model != "uniform") modes.push_back("uniform");
    // Files are named by the scene's own name (a scene given as a path has one too), so two scenes
    // of one name would overwrite each other's sequences: refused before anything is written.
    std::map<std::string, std::string> sceneOfName;
    std::map<std::string, std::string> nameOfScene;
    for (const auto& [scene, held] : scenes) {
        const std::string name = nameOfScene[scene] = LoadScene(ResolveSceneName(scene)).name;
        if (const auto [first, fresh] = sceneOfName.emplace(name, scene); !fresh)
            Fail("scene '{}' is named '{}' like scene '{}' earlier in the list; its sequences would overwrite that "
                 "one's",
                 scene, name, first->second);
    }
    const std::filesystem::path dir(o.out);
    std::filesystem::create_directories(dir);
    size_t heldScenes = 0;
    for (const auto& s : scenes) heldScenes += s.second ? 1 : 0;
    const int extraPerTrainScene = int(modes.size()) * (o.noiseRealisations - 1);
    Progress progress("dataset", (int(scenes.size() * modes.size()) +
                                  int(scenes.size() - heldScenes) * extraPerTrainScene) * base.run.frames);
    const auto start = std::chrono::steady_clock::now();
    for (const auto& [scene, held] : scenes)
        for (size_t m = 0; m < modes.size(); ++m) {
            RunConfig config = base;
            config.scene.name = scene;
            if (o.gazePerScene) config.gaze = GazeForScene(base.gaze, nameOfScene[scene]);
            config.run.seed = base.run.seed + uint32_t(m) * 7919u;  // different noise per mode
            if (modes[m] == "uniform") {
                config.foveation.model = "uniform";
                config.foveation.uniformSpp = 1;
            }
            FramePipeline pipeline(config);
            pipeline.CheckGazeCovers(uint32_t(config.run.firstFrame), config.run.frames);
            const std::string sceneName = pipeline.GetScene().name;
            ReferenceCache cache(config.reference.cacheDir);
            const uint64_t fingerprint = SceneFingerprint(pipeline.GetScene());
            const int w = config.camera.width, h = config.camera.height, T = config.run.frames;
            NpyArray inputs[2], targets[2];
            for (int eye = 0; eye < 2; ++eye) {
                inputs[eye].shape = {T, kRaeFeatureChannels, h, w};
                targets[eye].shape = {T, 3, h, w};
            }
            StereoFrame frame;
            for (int i = 0; i < T; ++i) {
                const uint32_t index = uint32_t(config.run.firstFrame + i);
                pipeline.Render(index, frame);
                for (int eye = 0; eye < 2; ++eye) {
                    const EyeFrame& e = frame.eyes[size_t(eye)];
                    const ReferenceKey key =
                        MakeReferenceKey(pipeline.GetScene(), fingerprint, index, frame.timeSeconds, eye, e.camera,
                                         config.reference.spp, config.run.maxDepth, base.run.seed);
                    const Plane<vec3> reference = cache.GetOrRender(key, pipeline.GetRenderer());
                    Tensor features, target;
                    RaeFeatures(e.inputs, features);
                    RaeTarget(e.inputs, reference, target);
                    Append(inputs[eye], features);
                    Append(targets[eye], target);
                }
                progress.Step();
            }
            // Extra noise realisations of the training frames: same camera, gaze and references.
            const int extra = held ? 0 : o.noiseRealisations - 1;
            std::vector<std::array<NpyArray, 2>> extraInputs(size_t(std::max(extra, 0)));
            std::vector<uint32_t> extraSeeds;
            for (int r = 1; r <= extra; ++r) {
                RunConfig noisy = config;
                noisy.run.seed = RealisationSeed(base.run.seed, m, r);
                extraSeeds.push_back(noisy.run.seed);
                FramePipeline again(noisy);
                auto& arrays = extraInputs[size_t(r - 1)];
                for (int eye = 0; eye < 2; ++eye) arrays[size_t(eye)].shape = {T, kRaeFeatureChannels, h, w};
                for (int i = 0; i < T; ++i) {
                    again.Render(uint32_t(config.run.firstFrame + i), frame);
                    for (int eye = 0; eye < 2; ++eye) {
                        Tensor features;
                        RaeFeatures(frame.eyes[size_t(eye)].inputs, features);
                        Append(arrays[size_t(eye)], features);
                    }
                    progress.Step();
                }
            }
            for (int eye = 0; eye < 2; ++eye) {
                const std::string name = fmt::format("{}_{}_{}", sceneName, modes[m], eye == 0 ? "left" : "right");
                WriteNpy(dir / (name + "_input.npy"), inputs[eye]);
                WriteNpy(dir / (name + "_target.npy"), targets[eye]);
                nlohmann::json extraFiles = nlohmann::json::array();
                for (int r = 1; r <= extra; ++r) {
                    const std::string file = fmt::format("{}_input_n{}.npy", name, r);
                    WriteNpy(dir / file, extraInputs[size_t(r - 1)][size_t(eye)]);
                    extraFiles.push_back(file);
                }
                nlohmann::json sequence = {{"name", name},
                                           {"scene", sceneName},
                                           {"mode", modes[m]},
                                           {"eye", eye},
                                           {"split", held ? "eval" : "train"},
                                           {"frames", T},
                                           {"seed", config.run.seed},
                                           {"input", name + "_input.npy"},
                                           {"target", name + "_target.npy"},
                                           {"inputs_extra", extraFiles},
                                           {"seeds_extra", extraSeeds}};
                if (o.gazePerScene) {
                    const GazeParams& g = config.gaze;
                    sequence["gaze"] = {{"amplitude", {g.amplitude.x, g.amplitude.y}},
                                        {"frequency_hz", {g.frequencyHz.x, g.frequencyHz.y}},
                                        {"phase_deg", {g.phaseDeg.x, g.phaseDeg.y}}};
                }
                manifest["sequences"].push_back(sequence);
            }
        }
    progress.Finish();
    WriteTextAtomically(dir / "manifest.json", manifest.dump(2) + "\n");
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::fprintf(stderr, "fovrt dataset: %zu sequences in %s (%.0f s)\n", manifest["sequences"].size(),
                 dir.string().c_str(), seconds);
}

}  // namespace

void RegisterDatasetCommand(CLI::App& app) {
    CLI::App* cmd = app.add_subcommand(
        "dataset", "Render RAE training sequences (noisy features + demodulated references) as .npy");
    auto options = std::make_shared<ConfigOptions>();
    auto dataset = std::make_shared<DatasetOptions>();
    AddConfigOptions(cmd, *options);
    cmd->add_option("--out", dataset->out, "output folder (manifest.json + .npy per sequence)");
    cmd->add_option("--scenes", dataset->scenes, "training scenes")->delimiter(',');
    cmd->add_option("--eval", dataset->eval, "held-out scenes (split \"eval\")")->delimiter(',');
    cmd->add_flag("!--no-uniform", dataset->uniform, "only the config's foveation, no uniform 1-spp sequences");
    cmd->add_option("--noise-realisations", dataset->noiseRealisations,
                    "noisy inputs per training frame (other seeds, same camera and target): camera stops")
        ->check(CLI::Range(1, 16));
    cmd->add_flag("--gaze-per-scene", dataset->gazePerScene,
                  "each scene its own Lissajous path, drawn from its name (phases, frequencies x 0.6-1.4, "
                  "amplitudes x 0.5-1 of the config's); manifest key \"gaze\"");
    cmd->callback([options, dataset] { WriteDataset(ResolveConfig(*options), *dataset); });
}

}  // namespace fovrt
