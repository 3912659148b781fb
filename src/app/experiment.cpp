#include "app/experiment.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <limits>
#include <map>
#include <new>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "app/design_sweep.h"
#include "app/experiment_pass.h"
#include "app/experiment_run.h"
#include "app/experiment_shards.h"
#include "app/experiment_stats.h"
#include "app/experiment_vdp.h"
#include "app/gaze_tracking_report.h"
#include "app/output_dir.h"
#include "app/progress.h"
#include "app/report_collect.h"
#include "app/report_html.h"
#include "app/report_summary.h"
#include "config/config_cli.h"
#include "config/config_io.h"
#include "core/atomic_file.h"
#include "core/cpu_time.h"
#include "core/error.h"
#include "core/interrupt.h"
#include "core/nearest_name.h"
#include "denoise/denoiser_factory.h"
#include "denoise/memory_plan.h"
#include "gaze/tracker.h"
#include "io/exr.h"
#include "pipeline/build_info.h"
#include "pipeline/denoiser_set.h"
#include "pipeline/frame_pipeline.h"
#include "pipeline/metric_fovea.h"
#include "pipeline/reference_cache.h"

namespace fovrt {
namespace {

namespace fs = std::filesystem;

constexpr int64_t kMaxSeed = std::numeric_limits<uint32_t>::max();


std::vector<std::string> StringArray(const ExperimentTable& experiment, const std::string& key) {
    const std::string file = experiment.Origin(key);
    const toml::node* node = experiment.table.get(key);
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

// "312.4 s wall, 590.1 s CPU (user + system, all threads)": the experiment's cost so far.
std::string RunTimeText(std::chrono::steady_clock::time_point start) {
    return fmt::format("{:.1f} s wall, {:.1f} s CPU (user + system, all threads)", MsSince(start) / 1000.0,
                       CpuSeconds());
}

std::string SeedsText(const std::vector<uint32_t>& seeds) {
    std::string out;
    for (uint32_t s : seeds) out += (out.empty() ? "" : ", ") + std::to_string(s);
    return out;
}

// The path samples traced per pixel, by region at the true gaze, over every eye-frame rendered:
// the measured sampling (a blink rendered uniform, A-SVGF's re-shaded pixels included).
nlohmann::json TracedSppJson(const SceneRecord& r) {
    nlohmann::json j = nlohmann::json::object();
    for (size_t i = 0; i < kTracedRegions.size(); ++i)
        if (r.tracedPixels[i] > 0) j[kTracedRegions[i]] = TracedSamples::SamplesPerPixel(r, i);
    if (r.tracedPixels[0] > 0) j["guide_rays_whole"] = TracedSamples::GuideRaysPerPixel(r, 0);
    return j;
}

// "cornell 1.95 / 8.00 / 1.00": the measured sampling of every scene, for the report's run table.
std::string TracedSppText(const std::vector<SceneRecord>& scenes) {
    std::string text;
    for (const SceneRecord& r : scenes)
        text += fmt::format("{}{} {:.2f} / {:.2f} / {:.2f}", text.empty() ? "" : "; ", r.label,
                            TracedSamples::SamplesPerPixel(r, 0), TracedSamples::SamplesPerPixel(r, 1),
                            TracedSamples::SamplesPerPixel(r, 2));
    return text;
}

ReportTable MemoryTable(const RunConfig& config) {
    int w = config.camera.width, h = config.camera.height;
    double pixels = double(w) * double(h);
    ReportTable table{fmt::format("Denoiser memory per eye at {}×{}", w, h),
                      {"variant", "history bytes/pixel", "total bytes/pixel", "total MiB"},
                      {}};
    for (const std::string& name : config.denoise.denoisers) {
        auto plan = PlanDenoiserMemory(name, w, h, RunDenoiserParams(config, name));
        table.rows.push_back({name, fmt::format("{:.1f}", double(HistoryBytes(plan)) / pixels),
                              fmt::format("{:.1f}", double(TotalBytes(plan)) / pixels),
                              fmt::format("{:.2f}", double(TotalBytes(plan)) / (1024.0 * 1024.0))});
    }
    return table;
}

}  // namespace

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

std::string ScoredFramesText(const RunSettings& run) {
    if (run.warmupFrames == 0) return std::to_string(run.frames);
    return fmt::format("{} from frame {}, after {} warm-up frames", run.frames, run.firstFrame, run.warmupFrames);
}

std::vector<uint32_t> ParseSeedsOption(const std::string& text, uint32_t first) {
    auto bad = [&](const std::string& why) -> std::vector<uint32_t> {
        Fail("--seeds {}: {} (a count N >= 1, or a list such as 1,2,3)", text.empty() ? "''" : text, why);
    };
    std::vector<int64_t> numbers;
    size_t pos = 0;
    while (true) {
        const size_t comma = text.find(',', pos);
        const std::string part = text.substr(pos, comma == std::string::npos ? std::string::npos : comma - pos);
        if (part.empty() || part.find_first_not_of("0123456789") != std::string::npos || part.size() > 10)
            return bad(fmt::format("'{}' is not a non-negative integer", part));
        numbers.push_back(std::stoll(part));
        if (numbers.back() > kMaxSeed) return bad(fmt::format("{} is above 2^32 - 1", part));
        if (comma == std::string::npos) break;
        pos = comma + 1;
    }
    std::vector<uint32_t> seeds;
    if (numbers.size() == 1 && text.find(',') == std::string::npos) {
        if (numbers[0] < 1 || numbers[0] > 1000) return bad("the count must be in [1, 1000]");
        if (int64_t(first) + numbers[0] - 1 > kMaxSeed) return bad("run.seed + N - 1 is above 2^32 - 1");
        for (int64_t i = 0; i < numbers[0]; ++i) seeds.push_back(uint32_t(first + uint32_t(i)));
        return seeds;
    }
    for (int64_t n : numbers) {
        if (std::find(seeds.begin(), seeds.end(), uint32_t(n)) != seeds.end())
            return bad(fmt::format("seed {} is listed twice", n));
        seeds.push_back(uint32_t(n));
    }
    return seeds;
}

ExperimentSpec LoadExperiment(const ConfigOptions& options, const ExperimentArgs& args) {
    const bool quick = args.quick;
    const std::vector<std::string>& scenes = args.scenes;
    const std::string& replayPath = args.replayPath;
    const bool allowChanges = args.allowChanges;
    if (options.configPath.empty()) Fail("fovrt experiment needs an experiment file (e.g. presets/thesis-foveated.toml)");
    if (allowChanges && replayPath.empty()) Fail("--allow-changes needs --replay FILE");
    if (!replayPath.empty() && !scenes.empty())
        Fail("--scene and --replay exclude each other (a recording has its own scene)");
    if (!replayPath.empty() && !args.seeds.empty())
        Fail("--seeds and --replay exclude each other (a recording is rendered with its own run.seed)");
    ExperimentSpec spec;
    spec.file = options.configPath;
    spec.quick = quick;
    if (!args.shard.empty()) spec.shard = ParseShard(args.shard);
    spec.merge = args.merge;
    if (spec.merge && spec.shard.Sharded()) Fail("--merge and --shard exclude each other");
    ExperimentTable experiment;
    // The config with the variants as its denoisers (a replay checks the list it renders with).
    auto resolve = [&](const ConfigOptions& resolved) {
        RunConfig config = ResolveExperimentConfig(resolved, quick, experiment);
        for (const auto& [key, node] : experiment.table) {
            std::string k(key.str());
            static const std::vector<std::string> known = [] {
                std::vector<std::string> keys = {"scenes", "variants", "visual_frame", "quick",
                                                 "seeds",  "baseline", "suppress_saccades"};
                keys.insert(keys.end(), std::begin(kSweepKeys), std::end(kSweepKeys));
                return keys;
            }();
            if (std::find(known.begin(), known.end(), k) == known.end())
                Fail("{}: unknown key experiment.{} (did you mean experiment.{}?)", experiment.Origin(k), k, NearestName(k, known));
        }
        spec.variants = StringArray(experiment, "variants");
        for (const std::string& variant : spec.variants)
            FindDenoiserVariant(variant, experiment.Origin("variants") + ": experiment.variants");
        config.denoise.denoisers = spec.variants;
        return config;
    };
    if (replayPath.empty()) {
        spec.config = resolve(options);
        spec.scenes = scenes.empty() ? StringArray(experiment, "scenes") : scenes;
    } else {
        spec.replay = OpenReplay(replayPath, allowChanges);
        spec.config = ResolveReplayConfig(*spec.replay, options, resolve, "fovrt experiment");
        spec.scenes = {spec.config.scene.name};
        if (experiment.table.contains("scenes"))
            std::fprintf(stderr, "fovrt experiment: replay: experiment.scenes is ignored (the recording's scene '%s' "
                                 "is rendered)\n", spec.config.scene.name.c_str());
    }
    if (replayPath.empty()) {
        spec.sweep = LoadSamplingSweep(experiment, options, quick, spec.variants);
        if (spec.sweep.Active() && !spec.config.metric.vdp)
            Fail("{}: experiment.designs needs metric.vdp = true (the curves are FovVideoVDP's JOD against rays)",
                 experiment.Origin("designs"));
    }
    if (!replayPath.empty() && experiment.table.contains("designs")) {
        Fail("{}: experiment.designs and --replay exclude each other (a recording has its own sampling)",
             experiment.Origin("designs"));
    }
    if (const toml::node* baseline = experiment.table.get("baseline")) {
        auto value = baseline->value<std::string>();
        if (!value) Fail("{}: experiment.baseline must be a string (one of experiment.variants)", experiment.Origin("baseline"));
        if (std::find(spec.variants.begin(), spec.variants.end(), *value) == spec.variants.end())
            Fail("{}: experiment.baseline '{}' is not in experiment.variants (did you mean '{}'?)", experiment.Origin("baseline"), *value,
                 NearestName(*value, spec.variants));
        spec.baseline = *value;
    } else {
        spec.baseline = spec.variants.front();
    }
    if (!args.seeds.empty()) {
        spec.seeds = ParseSeedsOption(args.seeds, spec.config.run.seed);
    } else if (const toml::node* seeds = experiment.table.get("seeds"); seeds && !spec.replay) {
        const toml::array* array = seeds->as_array();
        if (!array || array->empty())
            Fail("{}: experiment.seeds must be a non-empty array of integers in [0, 2^32), e.g. [1, 2, 3]", experiment.Origin("seeds"));
        for (const toml::node& element : *array) {
            auto value = element.value<int64_t>();
            if (!element.is_integer() || !value || *value < 0 || *value > kMaxSeed)
                Fail("{}: experiment.seeds must hold only integers in [0, 2^32), e.g. [1, 2, 3]", experiment.Origin("seeds"));
            if (std::find(spec.seeds.begin(), spec.seeds.end(), uint32_t(*value)) != spec.seeds.end())
                Fail("{}: experiment.seeds lists seed {} twice", experiment.Origin("seeds"), *value);
            spec.seeds.push_back(uint32_t(*value));
        }
    } else {
        if (spec.replay && experiment.table.contains("seeds"))
            std::fprintf(stderr, "fovrt experiment: replay: experiment.seeds is ignored (the recording's run.seed %u "
                                 "is rendered)\n", spec.config.run.seed);
        spec.seeds = {spec.config.run.seed};
    }
    if (const toml::node* suppress = experiment.table.get("suppress_saccades")) {
        auto value = suppress->value<bool>();
        if (!suppress->is_boolean() || !value)
            Fail("{}: experiment.suppress_saccades must be true or false", experiment.Origin("suppress_saccades"));
        spec.suppressSaccades = *value;
    }
    if (const toml::node* frame = experiment.table.get("visual_frame")) {
        auto value = frame->value<int64_t>();
        if (!value || *value < -1) Fail("{}: experiment.visual_frame must be an integer ≥ -1", experiment.Origin("visual_frame"));
        spec.visualFrame = int(*value);
    }
    return spec;
}

namespace {

bool Owns(const std::vector<RunUnit>& units, size_t scene, size_t seed, int eye, size_t variant) {
    for (const RunUnit& u : units)
        if (u.scene == scene && u.seed == seed && u.eye == eye && u.variant == variant) return true;
    return false;
}

}  // namespace

ExperimentPart ComputeRuns(const ExperimentSpec& spec, const std::vector<RunUnit>& units, const fs::path& outDir) {
    const RunConfig& base = spec.config;
    const std::vector<uint32_t> seeds = spec.seeds.empty() ? std::vector<uint32_t>{base.run.seed} : spec.seeds;
    ExperimentPart part;
    std::vector<std::string> labels;
    size_t seedRuns = 0;
    for (size_t sc = 0; sc < spec.scenes.size(); ++sc)
        for (size_t sd = 0; sd < seeds.size(); ++sd)
            for (const RunUnit& u : units)
                if (u.scene == sc && u.seed == sd) {
                    ++seedRuns;
                    break;
                }
    Progress progress("experiment", int(seedRuns) * base.run.frames);
    for (size_t sceneIndex = 0; sceneIndex < spec.scenes.size(); ++sceneIndex) {
        RunConfig config = base;
        config.scene.name = spec.scenes[sceneIndex];
        // The denoisers' pipelines are built once per scene (on lavapipe each one is compiled);
        // their histories are reset for every seed. Only the variants of this part's runs.
        std::vector<std::string> sceneVariants;
        for (size_t v = 0; v < spec.variants.size(); ++v)
            for (const RunUnit& u : units)
                if (u.scene == sceneIndex && u.variant == v) {
                    sceneVariants.push_back(spec.variants[v]);
                    break;
                }
        if (sceneVariants.empty()) continue;
        config.denoise.denoisers = sceneVariants;
        // One pass per run seed, as a separate run with that seed would render it.
        std::vector<std::pair<size_t, SeedWork>> passes;
        for (size_t seedIndex = 0; seedIndex < seeds.size(); ++seedIndex) {
            SeedWork work{seeds[seedIndex], std::vector<std::array<bool, 2>>(sceneVariants.size(), {false, false})};
            bool any = false;
            for (size_t v = 0; v < sceneVariants.size(); ++v) {
                const size_t variant = size_t(std::find(spec.variants.begin(), spec.variants.end(), sceneVariants[v]) -
                                              spec.variants.begin());
                for (int eye = 0; eye < 2; ++eye)
                    any |= work.runs[v][size_t(eye)] = Owns(units, sceneIndex, seedIndex, eye, variant);
            }
            if (any) passes.emplace_back(seedIndex, std::move(work));
        }
        if (passes.empty()) continue;
        config.run.seed = passes.front().second.seed;

        const RunConfig pipelineConfig = spec.replay ? ReplayPipelineConfig(config) : config;
        FrameLoop loop(config, true, &pipelineConfig);  // the scene and its BVH, once
        // With the storage denoise.precision (auto by default) resolved to on that device.
        part.deviceDescription = loop.Denoisers().DeviceDescription() + ", storage " + loop.Denoisers().StorageDescription();
        std::optional<Replay> replay = spec.replay;
        if (replay) {
            CheckReplayScene(*replay, loop.Pipeline());
            part.replayRecord = replay->ToJson();
        }
        SceneRecord record;
        record.index = sceneIndex;
        record.requested = spec.scenes[sceneIndex];
        record.label = SceneLabel(loop.Pipeline().GetScene().name, labels);
        record.fingerprint = loop.SceneFingerprint();
        record.files = SceneFileHashes(loop.Pipeline().GetScene());
        record.source = loop.Pipeline().GetScene().sourcePath.string();

        const int visualFrame =
            spec.visualFrame >= 0 ? spec.visualFrame : int(LastFrameOf(config, replay ? &*replay : nullptr));
        // The fovea the errors and measured sampling are taken in (a sweep's points share one).
        RunConfig scored = config;
        if (spec.scoredFoveation) scored.foveation = *spec.scoredFoveation;
        ExperimentScoring scoring(scored, record, part, visualFrame);
        ReportVisuals visuals(scored, loop, record, visualFrame);
        PassCosts costs(record, part, progress, seeds.size() > 1);
        TracedSamples traced(scored, record);
        std::optional<ExperimentExr> exr;
        loop.Attach(visuals);
        loop.Attach(scoring);
        if (config.output.writeExr) loop.Attach(exr.emplace(outDir / record.label, seeds.size() > 1));
        loop.Attach(costs);
        loop.Attach(traced);
        for (auto& [seedIndex, work] : passes) {
            visuals.Prepare(seedIndex, work);
            traced.CountEyes({Owns(units, sceneIndex, seedIndex, 0, 0), Owns(units, sceneIndex, seedIndex, 1, 0)});
            scoring.SetVisualsHere(ReportVisuals::ShownIn(seedIndex, work));
            // A fresh sequence per pass: the pipeline restarts with the seed before the first frame.
            std::optional<FrameSequence> sequence;
            RecordedFrame recorded;
            auto next = [&](FrameRequest& request) {
                if (!sequence) sequence.emplace(replay ? FrameSequence(loop.Pipeline(), *replay) : FrameSequence(loop.Pipeline()));
                if (!sequence->Next(recorded)) return false;
                request = recorded.request;
                return true;
            };
            loop.RunSeed(seedIndex, work, next);
        }
        part.scenes.push_back(std::move(record));
    }
    progress.Finish();
    return part;
}

Results WriteExperimentOutputs(const ExperimentSpec& spec, ExperimentPart& part, const fs::path& outDir,
                               std::chrono::steady_clock::time_point totalStart, ExperimentOutputs outputs) {
    const bool print = outputs == ExperimentOutputs::kPrinted;
    const RunConfig& base = spec.config;
    const std::vector<uint32_t> seeds = spec.seeds.empty() ? std::vector<uint32_t>{base.run.seed} : spec.seeds;
    std::map<std::string, size_t> sceneIndex;
    for (const SceneRecord& r : part.scenes) sceneIndex[r.label] = r.index;
    SortRowsCanonically(part.results, sceneIndex, seeds, spec.variants);
    Results& results = part.results;

    HtmlReport report;
    report.title = fmt::format("fovrt experiment: {}{}", spec.file.filename().string(),
                               spec.quick ? " (--quick)" : "");
    report.results = &results;
    report.baseline = spec.baseline;
    nlohmann::json sceneRecords = nlohmann::json::array();
    nlohmann::json tracedSpp = nlohmann::json::object();  // summary.json: the measured sampling per scene
    for (SceneRecord& r : part.scenes) {
        WriteFrameCsv(outDir / fmt::format("frames-{}.csv", r.label), results, r.label);
        // The report's images in the experiment's variant order.
        std::vector<std::pair<std::string, Plane<vec3>>> ordered;
        for (const std::string& v : spec.variants)
            for (auto& entry : r.visuals.variants)
                if (entry.first == v) ordered.push_back(std::move(entry));
        r.visuals.variants = std::move(ordered);
        report.scenes.push_back(std::move(r.visuals));
        const double eyeFramesDenominator = std::max(1, r.eyeFrames);
        sceneRecords.push_back({{"scene", r.label},
                                {"requested", r.requested},
                                {"source", r.source},
                                {"fingerprint", fmt::format("{:016x}", r.fingerprint)},
                                {"seeds", seeds},
                                {"render_ms_per_eye", r.times.renderMs / eyeFramesDenominator},
                                {"reference_ms_per_eye", r.times.referenceMs / eyeFramesDenominator},
                                // Wall time of every variant's Denoise() and of scoring them (the
                                // per-region errors and FovVideoVDP), per eye-frame.
                                {"denoise_ms_per_eye", r.times.denoiseMs / eyeFramesDenominator},
                                {"metric_ms_per_eye", r.times.metricMs / eyeFramesDenominator},
                                {"reference_cache_hits", r.referenceHits},
                                {"reference_lookups", r.referenceLookups},
                                {"rays", r.rays},
                                {"dropped_nonfinite_samples", r.droppedSamples},
                                {"blink_frames", r.blinkFrames},
                                {"traced_spp", TracedSppJson(r)}});
        tracedSpp[r.label] = TracedSppJson(r);
    }

    // The eye tracker beside the errors; with experiment.suppress_saccades the statistics leave
    // out the saccade frames (the per-frame CSV keeps every row).
    nlohmann::json gazeTracking = nlohmann::json::object();
    std::map<std::string, std::vector<int>> saccadeFrames;
    for (const SceneVisuals& v : report.scenes) {
        if (v.gazeMarks.empty()) continue;
        WriteTextAtomically(outDir / fmt::format("gaze-{}.csv", v.scene), GazeTrackingCsv(v.gazeMarks));
        gazeTracking[v.scene] = GazeTrackingJson(SummarizeGazeTracking(v.gazeMarks), results, v.scene, v.gazeMarks);
        saccadeFrames[v.scene] = SaccadeFrames(v.gazeMarks);
    }
    Results suppressed;
    if (spec.suppressSaccades) suppressed = WithoutFrames(results, saccadeFrames);
    const Results& scored = spec.suppressSaccades ? suppressed : results;
    report.results = &scored;
    const ExperimentStats stats(scored, spec.baseline);
    nlohmann::json summary = SummaryJson(scored, stats);
    summary["gaze_tracking"] = gazeTracking;
    summary["traced_spp"] = tracedSpp;
    summary["saccade_frames_suppressed"] = spec.suppressSaccades;
    const std::string vdpTable = base.metric.vdp ? AddVdpResults(part.vdp, spec.variants, spec.baseline,
                                                                  part.vdpDisplay, outDir, summary, report)
                                                 : "";
    WriteTextAtomically(outDir / "summary.json", summary.dump(2) + "\n");
    if (print) std::printf("%s%s", SummaryTable(scored, stats).c_str(), vdpTable.c_str());
    if (print && (!IsIdealTracker(base.gaze.tracker) || spec.suppressSaccades))
        for (const auto& [scene, json] : gazeTracking.items()) std::printf("%s", GazeTrackingTable(json, scene).c_str());

    report.manifest = {{"experiment", spec.file.string()},
                       {"quick", spec.quick ? "yes" : "no"},
                       {"resolution per eye", fmt::format("{}×{}", base.camera.width, base.camera.height)},
                       {"frames", ScoredFramesText(base.run)},
                       {"seeds", SeedsText(seeds)},
                       {"baseline", spec.baseline},
                       {"reference seed", std::to_string(base.reference.seed)},
                       {"foveation", base.foveation.model},
                       {"gaze", base.gaze.source},
                       {"reference spp", std::to_string(base.reference.spp)},
                       {"denoise device", part.deviceDescription},
                       {"relMSE ε", "0.01"},
                       {"traced spp (whole / fovea / periphery)", TracedSppText(part.scenes)},
                       {"fovrt", FOVRT_VERSION},
                       // Up to the report: the outputs above are written, the manifest follows.
                       {spec.merge ? "time (this merge)" : "time", RunTimeText(totalStart)}};
    report.tables.push_back(PerSeedTable(scored, base.metric.vdp ? part.vdp : std::vector<VdpScore>{}));
    report.tables.push_back(MemoryTable(base));
    report.tables.push_back(part.timings.ToReport("Per-pass denoiser timings (mean over frames and eyes)"));
    report.stats = &stats;
    if (base.output.report) WriteHtmlReport(outDir / "report.html", report);

    nlohmann::json manifest;
    manifest["command"] = "experiment";
    manifest["complete"] = true;
    manifest["experiment_file"] = spec.file.string();
    manifest["quick"] = spec.quick;
    if (spec.replay) manifest["replay"] = part.replayRecord;
    manifest["scenes"] = sceneRecords;
    manifest["variants"] = spec.variants;
    manifest["baseline"] = spec.baseline;
    manifest["seeds"] = seeds;
    manifest["build"] = BuildInfoJson();
    // The config as rendered: scene.name is the scene each pass used (experiment.scenes or
    // --scene replace it), one string for one scene, else the list in order.
    manifest["config"] = ConfigToJson(base);
    if (spec.scenes.size() == 1) manifest["config"]["scene"]["name"] = spec.scenes.front();
    else manifest["config"]["scene"]["name"] = spec.scenes;
    if (spec.merge) manifest["merged_shards"] = true;
    manifest["denoise_device"] = part.deviceDescription;
    // Derived from the foveation, not a config key: whether svgf, asvgf and asvgf-antilag read the
    // sample counts to keep pixels without a path sample.
    manifest["denoise_sample_counts_may_be_zero"] = RunDenoiseConfig(base).params.sampleCountsMayBeZero;
    manifest["pass_ms"] = part.timings.MeansJson();
    manifest["total_s"] = MsSince(totalStart) / 1000.0;
    manifest["cpu_s"] = CpuSeconds();
    WriteTextAtomically(outDir / "manifest.json", manifest.dump(2) + "\n");
    if (!print) return results;
    SceneTimes times;
    for (const SceneRecord& r : part.scenes) times += r.times;
    std::fprintf(stderr, "fovrt experiment: tracing %.1f s, denoising %.1f s, FovVideoVDP %.1f s (wall, all scenes and seeds)\n",
                 times.renderMs / 1000.0, times.denoiseMs / 1000.0, times.metricMs / 1000.0);
    std::fprintf(stderr, "fovrt experiment: done in %.1f s -> %s\n", MsSince(totalStart) / 1000.0,
                 outDir.string().c_str());
    if (base.output.report) std::printf("HTML report: %s\n", (outDir / "report.html").string().c_str());
    return results;
}

namespace {

// Every large buffer of one scene's pass (the scene does not change it): the run's, the
// references' and the metric's frames (an experiment always scores).
std::vector<BufferPlan> PlanExperimentMemory(const RunConfig& config) {
    std::vector<BufferPlan> plan = PlanRunMemory(config);  // with run.score it has the metric's frames
    for (BufferPlan& reference : PlanReferenceMemory(config)) plan.push_back(std::move(reference));
    if (!config.run.score)
        for (BufferPlan& vdp : PlanVdpMemory(config, true)) plan.push_back(std::move(vdp));
    return plan;
}

}  // namespace

std::string RerunCommand(const ExperimentSpec& spec) {
    return fmt::format("fovrt experiment {}{} --shard I/N (the same options as the others)", spec.file.string(),
                       spec.quick ? " --quick" : "");
}

namespace {

Results RunOrMerge(const ExperimentSpec& spec, OutputDir& out) {
    const RunConfig& base = spec.config;
    const fs::path outDir = out.Path();
    const fs::path shardsDir = outDir / "shards";
    auto totalStart = std::chrono::steady_clock::now();
    if (spec.sweep.Active()) return RunSweep(spec, out);
    const std::string fingerprint = ExperimentFingerprint(spec);
    if (spec.merge) {
        ExperimentPart part = MergeShardParts(shardsDir, fingerprint, RerunCommand(spec));
        out.MoveAsideEarlierOutputs(false);  // the shards' scene folders stay: they are this merge's
        return WriteExperimentOutputs(spec, part, outDir, totalStart);
    }
    const std::vector<uint32_t> seeds = spec.seeds.empty() ? std::vector<uint32_t>{base.run.seed} : spec.seeds;
    const std::vector<RunUnit> all = ExperimentUnits(spec.scenes.size(), seeds.size(), spec.variants.size());
    if (spec.shard.Sharded()) {
        const std::vector<RunUnit> units = ShardUnits(all, spec.shard);
        ExperimentPart part = ComputeRuns(spec, units, outDir);
        WriteShardPart(shardsDir, spec.shard, fingerprint, part);
        std::fprintf(stderr, "fovrt experiment: %s (%zu of %zu runs) done in %.1f s -> %s\n", spec.shard.Name().c_str(),
                     units.size(), all.size(), MsSince(totalStart) / 1000.0,
                     (shardsDir / spec.shard.Name()).string().c_str());
        return part.results;
    }
    out.MoveAsideEarlierOutputs(true);
    ExperimentPart part = ComputeRuns(spec, all, outDir);
    return WriteExperimentOutputs(spec, part, outDir, totalStart);
}

}  // namespace

Results RunExperiment(const ExperimentSpec& spec) {
    if (!spec.merge) EnforceMemoryBudget(PlanExperimentMemory(spec.config), spec.config.memoryBudget, "experiment");
    OutputDir out(spec.config.output.dir, "output.dir");
    // One writer per folder; the shards of one experiment write disjoint parts side by side.
    out.Lock(spec.shard.Sharded() ? fmt::format(".fovrt-{}.lock", spec.shard.Name()) : OutputDir::kFolderLock);
    OutputDir cacheDir(spec.config.reference.cacheDir, "reference.cache_dir");  // before any rendering
    try {
        Results results = RunOrMerge(spec, out);
        out.Keep();
        cacheDir.Keep();
        return results;
    } catch (const Interrupted& e) {
        out.Keep();
        cacheDir.Keep();
        throw Interrupted(e.Signal(), fmt::format("{}: {} {} not written (no manifest)", e.what(), out.Path().string(),
                                                  spec.shard.Sharded() ? "shard part " + spec.shard.Name()
                                                                       : std::string("outputs")));
    } catch (const std::bad_alloc&) {
        FailOutOfMemory(spec.config, PlanExperimentMemory(spec.config), "fovrt experiment");
    }
}

}  // namespace fovrt
