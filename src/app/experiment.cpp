#include "app/experiment.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <map>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "app/build_info.h"
#include "app/config_cli.h"
#include "app/config_io.h"
#include "app/denoiser_set.h"
#include "app/frame_pipeline.h"
#include "app/output_dir.h"
#include "app/progress.h"
#include "app/reference_cache.h"
#include "app/report_collect.h"
#include "app/report_html.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "denoise/denoiser_factory.h"
#include "denoise/memory_plan.h"
#include "io/exr.h"

namespace fovrt {
namespace {

// Per instance: 1 when a material of its mesh has a roughness or metallic map (scene-file maps
// or glTF metallic-roughness): the "detail" region of brdf-demodulation experiments (issue #13).
std::vector<uint8_t> InstancesWithMaterialMaps(const Scene& scene) {
    std::vector<uint8_t> out(scene.instances.size(), 0);
    for (size_t i = 0; i < scene.instances.size(); ++i)
        for (uint32_t m : scene.meshes[scene.instances[i].mesh].materials) {
            const Material& material = scene.materials[m];
            if (material.roughnessTexture >= 0 || material.metallicTexture >= 0 ||
                material.metallicRoughnessTexture >= 0)
                out[i] = 1;
        }
    return out;
}


namespace fs = std::filesystem;

double MsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
}

std::vector<std::string> StringArray(const toml::table& table, const std::string& key,
                                     const std::string& file) {
    const toml::node* node = table.get(key);
    if (!node) Fail("{}: experiment.{} is missing", file, key);
    const toml::array* array = node->as_array();
    if (!array || array->empty()) Fail("{}: experiment.{} must be a non-empty array of strings", file, key);
    std::vector<std::string> values;
    for (const toml::node& element : *array) {
        auto value = element.value<std::string>();
        if (!value) Fail("{}: experiment.{} must contain only strings", file, key);
        values.push_back(*value);
    }
    return values;
}


// Mean per-pass milliseconds per variant, over every frame and eye.
class TimingTable {
public:
    void Add(const std::string& variant, const std::string& pass, double ms) {
        auto& [sum, count] = sums_[variant][pass];
        sum += ms;
        ++count;
        if (std::find(order_.begin(), order_.end(), variant) == order_.end()) order_.push_back(variant);
    }
    ReportTable ToReport(const std::string& title) const {
        ReportTable table{title, {"variant", "pass", "mean ms", "samples"}, {}};
        for (const std::string& variant : order_)
            for (const auto& [pass, sc] : sums_.at(variant))
                table.rows.push_back({variant, pass, fmt::format("{:.3f}", sc.first / double(sc.second)),
                                      std::to_string(sc.second)});
        return table;
    }
    nlohmann::json ToJson() const {
        nlohmann::json j = nlohmann::json::object();
        for (const auto& [variant, passes] : sums_)
            for (const auto& [pass, sc] : passes) j[variant][pass] = sc.first / double(sc.second);
        return j;
    }

private:
    std::map<std::string, std::map<std::string, std::pair<double, int>>> sums_;
    std::vector<std::string> order_;
};

// A scene's label in file names, reports and manifests: its `name` (not the path it was given
// by), reduced to [A-Za-z0-9._-] so it is one path component under output.dir; a label already
// used in this experiment gets "-2", "-3", ...
std::string SceneLabel(const std::string& name, std::vector<std::string>& used) {
    std::string label;
    for (char c : name) {
        const bool keep = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                          c == '.' || c == '_' || c == '-';
        label += keep ? c : '_';
    }
    if (label.empty() || label.find_first_not_of('.') == std::string::npos) label = "scene";
    std::string unique = label;
    for (int n = 2; std::find(used.begin(), used.end(), unique) != used.end(); ++n)
        unique = fmt::format("{}-{}", label, n);
    used.push_back(unique);
    return unique;
}

ReportTable MemoryTable(const RunConfig& config) {
    int w = config.camera.width, h = config.camera.height;
    double pixels = double(w) * double(h);
    ReportTable table{fmt::format("Denoiser memory per eye at {}×{}", w, h),
                      {"variant", "history bytes/pixel", "total bytes/pixel", "total MiB"},
                      {}};
    for (const std::string& name : config.denoise.denoisers) {
        auto plan = PlanDenoiserMemory(name, w, h, ParamsForDenoiser(name, config.denoise.params));
        table.rows.push_back({name, fmt::format("{:.1f}", double(HistoryBytes(plan)) / pixels),
                              fmt::format("{:.1f}", double(TotalBytes(plan)) / pixels),
                              fmt::format("{:.2f}", double(TotalBytes(plan)) / (1024.0 * 1024.0))});
    }
    return table;
}

}  // namespace

FoveaRadius MetricFovea(const FoveationParams& f, int imageWidth) {
    if (f.model == "disc") {
        if (f.radiusDeg > 0.0f) return FoveaRadius::Degrees(f.radiusDeg);
        return FoveaRadius::Pixels(f.radiusPx * float(imageWidth) / float(f.radiusReferenceWidth));
    }
    if (f.model == "linear") return FoveaRadius::Degrees(f.fovealDeg);
    return FoveaRadius::Degrees(5.0f);  // the first eccentricity band
}

ExperimentSpec LoadExperiment(const ConfigOptions& options, bool quick,
                              const std::vector<std::string>& scenes, const std::string& replayPath,
                              bool allowChanges) {
    if (options.configPath.empty()) Fail("fovrt experiment needs an experiment file (e.g. presets/thesis-foveated.toml)");
    if (allowChanges && replayPath.empty()) Fail("--allow-changes needs --replay FILE");
    if (!replayPath.empty() && !scenes.empty())
        Fail("--scene and --replay exclude each other (a recording has its own scene)");
    ExperimentSpec spec;
    spec.file = options.configPath;
    spec.quick = quick;
    const std::string file = spec.file.string();
    toml::table experiment;
    // The config with the variants as its denoisers (a replay checks the list it renders with).
    auto resolve = [&](const ConfigOptions& resolved) {
        RunConfig config = ResolveExperimentConfig(resolved, quick, experiment);
        for (const auto& [key, node] : experiment) {
            std::string k(key.str());
            if (k != "scenes" && k != "variants" && k != "visual_frame" && k != "quick")
                Fail("{}: unknown key experiment.{}", file, k);
        }
        spec.variants = StringArray(experiment, "variants", file);
        for (const std::string& variant : spec.variants)
            FindDenoiserVariant(variant, file + ": experiment.variants");
        config.denoise.denoisers = spec.variants;
        return config;
    };
    if (replayPath.empty()) {
        spec.config = resolve(options);
        spec.scenes = scenes.empty() ? StringArray(experiment, "scenes", file) : scenes;
    } else {
        spec.replay = OpenReplay(replayPath, allowChanges);
        spec.config = ResolveReplayConfig(*spec.replay, options, resolve, "fovrt experiment");
        spec.scenes = {spec.config.scene.name};
        if (experiment.contains("scenes"))
            std::fprintf(stderr, "fovrt experiment: replay: experiment.scenes is ignored (the recording's scene '%s' "
                                 "is rendered)\n", spec.config.scene.name.c_str());
    }
    if (const toml::node* frame = experiment.get("visual_frame")) {
        auto value = frame->value<int64_t>();
        if (!value || *value < -1) Fail("{}: experiment.visual_frame must be an integer ≥ -1", file);
        spec.visualFrame = int(*value);
    }
    return spec;
}

Results RunExperiment(const ExperimentSpec& spec) {
    const RunConfig& base = spec.config;
    OutputDir out(base.output.dir, "output.dir");
    OutputDir cacheDir(base.reference.cacheDir, "reference.cache_dir");  // before any rendering
    const fs::path outDir = out.Path();
    fs::remove(outDir / "manifest.json");  // present only once this run is complete

    auto totalStart = std::chrono::steady_clock::now();
    Results results;
    TimingTable timings;
    HtmlReport report;
    report.title = fmt::format("fovrt experiment: {}{}", spec.file.filename().string(),
                               spec.quick ? " (--quick)" : "");
    report.results = &results;
    nlohmann::json sceneRecords = nlohmann::json::array();
    nlohmann::json replayRecord;  // the recording replayed, with what CheckReplayScene found
    std::string deviceDescription;

    std::vector<std::string> labels;
    Progress progress("experiment", int(spec.scenes.size()) * base.run.frames);
    for (const std::string& sceneName : spec.scenes) {
        RunConfig config = base;
        config.scene.name = sceneName;
        std::vector<BufferPlan> plan = PlanRunMemory(config);
        EnforceMemoryBudget(plan, config.memoryBudget, "experiment");

        FramePipeline pipeline(spec.replay ? ReplayPipelineConfig(config) : config);
        std::optional<Replay> replay = spec.replay;
        if (replay) {
            CheckReplayScene(*replay, pipeline);
            replayRecord = replay->ToJson();
        }
        FrameSequence sequence = replay ? FrameSequence(pipeline, *replay) : FrameSequence(pipeline);
        const std::string label = SceneLabel(pipeline.GetScene().name, labels);
        DenoiserSet denoisers(config.denoise);
        deviceDescription = denoisers.DeviceDescription();
        ReferenceCache cache(config.reference.cacheDir);
        const uint64_t fingerprint = SceneFingerprint(pipeline.GetScene());
        MetricsCollector collector(results);
        const FoveaRadius fovea = MetricFovea(config.foveation, config.camera.width);
        const int visualFrame = spec.visualFrame >= 0 ? spec.visualFrame : int(sequence.LastFrame());
        const std::vector<uint8_t> detailInstances = InstancesWithMaterialMaps(pipeline.GetScene());

        SceneVisuals visuals;
        visuals.scene = label;
        visuals.width = config.camera.width;
        visuals.height = config.camera.height;
        visuals.eye = 0;
        visuals.foveaRadiusPixels = fovea.RadiusPixels(pipeline.RigAt(0).Eye(0));
        double renderMs = 0.0, referenceMs = 0.0;
        int referenceHits = 0;
        int blinkFrames = 0;

        RecordedFrame request;
        StereoFrame frame;
        std::vector<Plane<vec3>> outputs(denoisers.size());
        while (sequence.Next(request)) {
            const uint32_t index = request.request.frame;
            pipeline.Render(request.request, frame);
            blinkFrames += frame.gaze.valid ? 0 : 1;
            for (int eye = 0; eye < 2; ++eye) {
                EyeFrame& e = frame.eyes[size_t(eye)];
                renderMs += e.renderMs;
                const EyeCamera& camera = e.camera;

                auto start = std::chrono::steady_clock::now();
                ReferenceKey key = MakeReferenceKey(pipeline.GetScene(), fingerprint, index,
                                                    frame.timeSeconds, eye, camera,
                                                    config.reference.spp, config.run.maxDepth,
                                                    config.run.seed);
                bool hit = false;
                Plane<vec3> reference = cache.GetOrRender(key, pipeline.GetRenderer(), &hit);
                referenceHits += hit ? 1 : 0;
                referenceMs += MsSince(start);

                EyeFrameImages images;
                images.scene = label;
                images.frame = int(index);
                images.eye = eye;
                images.camera = camera;
                images.gazeEye = e.gazeEye;
                images.fovea = fovea;
                images.cameraCut = e.inputs.cameraCut;
                images.reference = &reference;
                // "detail": pixels whose primary hit is an instance with roughness/metallic maps.
                Plane<uint8_t> detail(camera.width(), camera.height(), uint8_t(0));
                for (size_t p = 0; p < detail.size(); ++p) {
                    const uint32_t id = e.inputs.objectId[p];
                    detail[p] = id < detailInstances.size() ? detailInstances[id] : uint8_t(0);
                }
                images.detailMask = &detail;
                for (size_t v = 0; v < denoisers.size(); ++v) {
                    Denoiser& denoiser = denoisers.At(v, eye);
                    denoiser.Denoise(e.inputs, outputs[v]);
                    for (const PassTiming& t : denoiser.LastTimings())
                        timings.Add(denoisers.Name(v), t.pass, t.ms);
                    images.outputs.emplace_back(denoisers.Name(v), &outputs[v]);
                    if (config.output.writeExr)
                        WriteRgbExr(outDir / label / denoisers.Name(v) /
                                        fmt::format("f{:05d}_{}.exr", index, eye == 0 ? "left" : "right"),
                                    outputs[v]);
                }
                collector.Add(images);

                if (eye == visuals.eye) {
                    visuals.gazePath.push_back(e.gazePixel);
                    if (int(index) == visualFrame) {
                        visuals.frame = int(index);
                        visuals.gazePixel = e.gazePixel;
                        visuals.sppMap = e.sppMap;
                        visuals.reference = reference;
                        visuals.noisy = e.inputs.NoisyImage();
                        visuals.variants.clear();
                        for (size_t v = 0; v < denoisers.size(); ++v)
                            visuals.variants.emplace_back(denoisers.Name(v), outputs[v]);
                    }
                }
            }
            progress.Step(fmt::format("{} frame {}", label, index));
        }
        WriteFrameCsv(outDir / fmt::format("frames-{}.csv", label), results, label);
        report.scenes.push_back(std::move(visuals));
        RenderStats stats = pipeline.GetRenderer().Stats();
        sceneRecords.push_back({{"scene", label},
                                {"requested", sceneName},
                                {"source", pipeline.GetScene().sourcePath.string()},
                                {"fingerprint", fmt::format("{:016x}", fingerprint)},
                                {"render_ms_per_eye", renderMs / (2.0 * config.run.frames)},
                                {"reference_ms_per_eye", referenceMs / (2.0 * config.run.frames)},
                                {"reference_cache_hits", referenceHits},
                                {"rays", stats.Rays()},
                                {"dropped_nonfinite_samples", stats.droppedSamples},
                                {"blink_frames", blinkFrames}});
    }
    progress.Finish();

    WriteSummaryJson(outDir / "summary.json", results);
    std::printf("%s", SummaryTable(results).c_str());

    report.manifest = {{"experiment", spec.file.string()},
                       {"quick", spec.quick ? "yes" : "no"},
                       {"resolution per eye", fmt::format("{}×{}", base.camera.width, base.camera.height)},
                       {"frames", std::to_string(base.run.frames)},
                       {"seed", std::to_string(base.run.seed)},
                       {"foveation", base.foveation.model},
                       {"gaze", base.gaze.source},
                       {"reference spp", std::to_string(base.reference.spp)},
                       {"denoise device", deviceDescription},
                       {"relMSE ε", "0.01"},
                       {"fovrt", FOVRT_VERSION}};
    report.tables.push_back(MemoryTable(base));
    report.tables.push_back(timings.ToReport("Per-pass denoiser timings (mean over frames and eyes)"));
    if (base.output.report) WriteHtmlReport(outDir / "report.html", report);

    nlohmann::json manifest;
    manifest["command"] = "experiment";
    manifest["complete"] = true;
    manifest["experiment_file"] = spec.file.string();
    manifest["quick"] = spec.quick;
    if (spec.replay) manifest["replay"] = replayRecord;
    manifest["scenes"] = sceneRecords;
    manifest["variants"] = spec.variants;
    manifest["build"] = BuildInfoJson();
    // The config as rendered: scene.name is the scene each pass used (experiment.scenes or
    // --scene replace it), one string for one scene, else the list in order.
    manifest["config"] = ConfigToJson(base);
    if (spec.scenes.size() == 1) manifest["config"]["scene"]["name"] = spec.scenes.front();
    else manifest["config"]["scene"]["name"] = spec.scenes;
    manifest["denoise_device"] = deviceDescription;
    manifest["pass_ms"] = timings.ToJson();
    manifest["total_s"] = MsSince(totalStart) / 1000.0;
    WriteTextAtomically(outDir / "manifest.json", manifest.dump(2) + "\n");
    out.Keep();
    cacheDir.Keep();
    std::fprintf(stderr, "fovrt experiment: done in %.1f s -> %s\n", MsSince(totalStart) / 1000.0,
                 outDir.string().c_str());
    return results;
}

}  // namespace fovrt
