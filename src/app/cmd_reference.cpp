// `fovrt reference`: high-spp ground truth of the configured frames and eyes, cached on disk under
// a key of scene content, frame, eye camera and settings (reference_cache.h), so repeated
// experiments do not re-render. Prints one line per frame and eye: cached or rendered, and the path.
#include <chrono>
#include <cstdio>

#include "app/commands.h"
#include "app/config.h"
#include "app/config_cli.h"
#include "app/frame_pipeline.h"
#include "app/output_dir.h"
#include "app/progress.h"
#include "app/reference_cache.h"
#include "denoise/memory_plan.h"

namespace fovrt {
namespace {

void RenderReferences(const RunConfig& config) {
    // The reference path holds one HDR image per eye in flight.
    const size_t imageBytes = size_t(config.camera.width) * size_t(config.camera.height) * sizeof(vec3);
    EnforceMemoryBudget({{"reference.image.eye0", imageBytes, false},
                         {"reference.image.eye1", imageBytes, false}},
                        config.memoryBudget, "reference");
    OutputDir cacheDir(config.reference.cacheDir, "reference.cache_dir");  // before any rendering
    FramePipeline pipeline(config);
    ReferenceCache cache(config.reference.cacheDir);
    uint64_t fingerprint = SceneFingerprint(pipeline.GetScene());
    Progress progress("reference", config.run.frames * 2);
    int rendered = 0, cached = 0;
    auto start = std::chrono::steady_clock::now();
    for (int i = 0; i < config.run.frames; ++i) {
        uint32_t frame = uint32_t(config.run.firstFrame + i);
        pipeline.SetFrame(frame);
        StereoRig rig = pipeline.RigAt(frame);
        for (int eye = 0; eye < 2; ++eye) {
            ReferenceKey key = MakeReferenceKey(pipeline.GetScene(), fingerprint, frame,
                                                pipeline.TimeOf(frame), eye, rig.Eye(eye),
                                                config.reference.spp, config.run.maxDepth,
                                                config.reference.seed);
            bool hit = false;
            cache.GetOrRender(key, pipeline.GetRenderer(), &hit);
            (hit ? cached : rendered)++;
            progress.Step();
            std::printf("%s %s\n", hit ? "cached  " : "rendered", cache.PathOf(key).c_str());
        }
    }
    progress.Finish();
    cacheDir.Keep();
    double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::fprintf(stderr, "fovrt reference: %d rendered, %d cached (%d spp) in %.1f s\n", rendered,
                 cached, config.reference.spp, seconds);
}

}  // namespace

void RegisterReferenceCommand(CLI::App& app) {
    CLI::App* cmd = app.add_subcommand(
        "reference", "Render (or find in the cache) high-spp reference frames for both eyes");
    auto options = std::make_shared<ConfigOptions>();
    AddConfigOptions(cmd, *options);
    cmd->callback([options] { RenderReferences(ResolveConfig(*options)); });
}

}  // namespace fovrt
