// `fovrt reference`: high-spp ground truth of the configured frames and eyes, cached on disk under
// a key of scene content, frame, eye camera and settings (reference_cache.h), so repeated
// experiments do not re-render. Prints one line per frame and eye: cached or rendered, and the path.
#include <chrono>
#include <algorithm>
#include <cstdio>
#include <new>

#include "app/commands.h"
#include "app/experiment.h"
#include "app/output_dir.h"
#include "app/progress.h"
#include "config/config.h"
#include "config/config_cli.h"
#include "core/error.h"
#include "core/interrupt.h"
#include "core/nearest_name.h"
#include "denoise/memory_plan.h"
#include "pipeline/denoiser_set.h"
#include "pipeline/frame_pipeline.h"
#include "pipeline/reference_cache.h"

namespace fovrt {
namespace {

// What one `fovrt reference` renders: frames × eyes of one config's scene.
struct ReferenceSlice {
    int eye = -1;  // 0, 1, or -1 for both
};

void RenderReferencesUnchecked(const RunConfig& config, const ReferenceSlice& slice) {
    EnforceMemoryBudget(PlanReferenceMemory(config), config.memoryBudget, "reference");
    OutputDir cacheDir(config.reference.cacheDir, "reference.cache_dir");  // before any rendering
    FramePipeline pipeline(config);
    ReferenceCache cache(config.reference.cacheDir);
    uint64_t fingerprint = SceneFingerprint(pipeline.GetScene());
    Progress progress("reference", config.run.frames * (slice.eye < 0 ? 2 : 1));
    int rendered = 0, cached = 0;
    auto start = std::chrono::steady_clock::now();
    try {
        for (int i = 0; i < config.run.frames; ++i) {
            uint32_t frame = uint32_t(config.run.firstFrame + i);
            pipeline.SetFrame(frame);
            StereoRig rig = pipeline.RigAt(frame);
            for (int eye = 0; eye < 2; ++eye) {
                if (slice.eye >= 0 && eye != slice.eye) continue;
                ReferenceKey key = MakeReferenceKey(pipeline.GetScene(), fingerprint, frame,
                                                    pipeline.TimeOf(frame), eye, rig.Eye(eye),
                                                    config.reference.spp, config.run.maxDepth,
                                                    config.reference.seed);
                ThrowIfInterrupted();
                bool hit = false;
                cache.GetOrRender(key, pipeline.GetRenderer(), &hit);
                (hit ? cached : rendered)++;
                progress.Step();
                std::printf("%s %s\n", hit ? "cached  " : "rendered", cache.PathOf(key).c_str());
            }
        }
    } catch (const Interrupted& e) {
        cacheDir.Keep();
        throw Interrupted(e.Signal(), fmt::format("{}: {} rendered, {} cached in {}; every entry there is complete",
                                                  e.what(), rendered, cached, config.reference.cacheDir));
    }
    progress.Finish();
    cacheDir.Keep();
    double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::fprintf(stderr, "fovrt reference: %d rendered, %d cached (%d spp) in %.1f s\n", rendered,
                 cached, config.reference.spp, seconds);
}

// RenderReferencesUnchecked with an allocation failure as one line naming the resolution and bytes.
void RenderReferences(const RunConfig& config, const ReferenceSlice& slice = {}) {
    try {
        RenderReferencesUnchecked(config, slice);
    } catch (const std::bad_alloc&) {
        FailOutOfMemory(config, PlanReferenceMemory(config), "fovrt reference");
    }
}

}  // namespace

void RegisterReferenceCommand(CLI::App& app) {
    CLI::App* cmd = app.add_subcommand(
        "reference", "Render (or find in the cache) high-spp reference frames for both eyes");
    auto options = std::make_shared<ConfigOptions>();
    AddConfigOptions(cmd, *options);
    // A slice of an experiment's references (a cluster task: fovrt cluster writes these).
    auto experimentFile = std::make_shared<std::string>();
    auto args = std::make_shared<ExperimentArgs>();
    auto scene = std::make_shared<std::string>();
    auto eye = std::make_shared<std::string>("both");
    auto frames = std::make_shared<std::string>();
    cmd->add_option("--experiment", *experimentFile,
                    "The references of this experiment file (its resolved config; with --quick, --seeds)");
    cmd->add_flag("--quick", args->quick, "With --experiment: its [experiment.quick] overrides");
    cmd->add_option("--seeds", args->seeds, "With --experiment: as `experiment --seeds` (references share one seed)");
    cmd->add_option("--scene", *scene, "With --experiment: one of its scenes (default: each in turn)");
    cmd->add_option("--eye", *eye, "0, 1 or both")->check(CLI::IsMember({"0", "1", "both"}));
    cmd->add_option("--frames", *frames, "A-B: frames A to B inclusive (sets run.first_frame and run.frames)");
    cmd->callback([options, experimentFile, args, scene, eye, frames] {
        InterruptScope interrupts;  // entries are written atomically: an interrupt leaves none half-written
        ReferenceSlice slice;
        slice.eye = *eye == "both" ? -1 : std::stoi(*eye);
        auto applyFrames = [&](RunConfig& config) {
            if (frames->empty()) return;
            int a = 0, b = 0;
            char tail = 0;
            if (std::sscanf(frames->c_str(), "%d-%d%c", &a, &b, &tail) != 2 || a < 0 || b < a)
                Fail("--frames {}: expected A-B with 0 ≤ A ≤ B", *frames);
            config.run.firstFrame = a;
            config.run.frames = b - a + 1;
        };
        if (experimentFile->empty()) {
            if (args->quick || !args->seeds.empty() || !scene->empty())
                Fail("--quick, --seeds and --scene need --experiment FILE");
            RunConfig config = ResolveConfig(*options);
            applyFrames(config);
            RenderReferences(config, slice);
            return;
        }
        ConfigOptions experimentOptions = *options;
        experimentOptions.configPath = *experimentFile;
        const ExperimentSpec spec = LoadExperiment(experimentOptions, *args);
        if (spec.replay) Fail("fovrt reference --experiment: replays render their references in the experiment");
        std::vector<std::string> scenes = spec.scenes;
        if (!scene->empty()) {
            if (std::find(scenes.begin(), scenes.end(), *scene) == scenes.end())
                Fail("--scene {}: not one of {}'s scenes (did you mean {}?)", *scene, *experimentFile,
                     NearestName(*scene, scenes));
            scenes = {*scene};
        }
        for (const std::string& name : scenes) {
            RunConfig config = spec.config;
            config.scene.name = name;
            applyFrames(config);
            RenderReferences(config, slice);
        }
    });
}

}  // namespace fovrt
