// `fovrt dataset`: training sequences for the recurrent denoising autoencoder (SPEC §12,
// training/). For every scene, spp mode (the config's foveation model, and uniform 1 spp) and eye
// it renders `run.frames` consecutive frames through the same FramePipeline as `run` and
// `experiment`, and writes
//   <scene>_<mode>_<eye>_input.npy   float32 [T, 8, H, W]: the RAE's raw features
//                                    (denoise/reference/rae_features.h; colour linear)
//   <scene>_<mode>_<eye>_target.npy  float32 [T, 3, H, W]: the reference.spp reference,
//                                    demodulated like the input (RaeTarget)
// and manifest.json (channels, sizes, split per sequence, the settings). Scenes listed with
// --eval are marked split "eval" (held out of training); references come from the reference cache
// (rendered with the base seed, so both spp modes share them).
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "app/commands.h"
#include "app/config.h"
#include "app/config_cli.h"
#include "app/frame_pipeline.h"
#include "app/progress.h"
#include "app/reference_cache.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "denoise/reference/rae_features.h"
#include "io/npy.h"

namespace fovrt {
namespace {

struct DatasetOptions {
    std::string out = "out/rae-dataset";
    std::vector<std::string> scenes = {"cornell", "pillars", "room", "box"};
    std::vector<std::string> eval = {"veach-ajar", "suzanne"};
    bool uniform = true;  // also a uniform 1-spp sequence per scene and eye
};

void Append(NpyArray& array, const Tensor& t) {
    array.data.insert(array.data.end(), t.data.begin(), t.data.end());
}

void WriteDataset(RunConfig base, const DatasetOptions& o) {
    const std::filesystem::path dir(o.out);
    std::filesystem::create_directories(dir);
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
    manifest["sequences"] = nlohmann::json::array();
    std::vector<std::pair<std::string, bool>> scenes;
    for (const std::string& s : o.scenes)
        if (!s.empty()) scenes.push_back({s, false});
    for (const std::string& s : o.eval)
        if (!s.empty()) scenes.push_back({s, true});  // --eval "": no held-out scene
    std::vector<std::string> modes = {base.foveation.model};
    if (o.uniform && base.foveation.model != "uniform") modes.push_back("uniform");
    Progress progress("dataset", int(scenes.size() * modes.size()) * base.run.frames);
    const auto start = std::chrono::steady_clock::now();
    for (const auto& [scene, held] : scenes)
        for (size_t m = 0; m < modes.size(); ++m) {
            RunConfig config = base;
            config.scene.name = scene;
            config.run.seed = base.run.seed + uint32_t(m) * 7919u;  // different noise per mode
            if (modes[m] == "uniform") {
                config.foveation.model = "uniform";
                config.foveation.uniformSpp = 1;
            }
            FramePipeline pipeline(config);
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
            for (int eye = 0; eye < 2; ++eye) {
                const std::string name = fmt::format("{}_{}_{}", scene, modes[m], eye == 0 ? "left" : "right");
                WriteNpy(dir / (name + "_input.npy"), inputs[eye]);
                WriteNpy(dir / (name + "_target.npy"), targets[eye]);
                manifest["sequences"].push_back({{"name", name},
                                                  {"scene", scene},
                                                  {"mode", modes[m]},
                                                  {"eye", eye},
                                                  {"split", held ? "eval" : "train"},
                                                  {"frames", T},
                                                  {"seed", config.run.seed},
                                                  {"input", name + "_input.npy"},
                                                  {"target", name + "_target.npy"}});
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
    cmd->callback([options, dataset] { WriteDataset(ResolveConfig(*options), *dataset); });
}

}  // namespace fovrt
