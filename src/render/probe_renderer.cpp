// The probe renderer (probes.h): PathTracer (path_tracer.h) over a RecordingScene, plus the
// probes. Kept out of the render library's unity translation unit (CMakeLists.txt): with both
// instantiations of the tracer in it, GCC inlined less into the production one (callgrind,
// `RenderEye` on the 1-spp Cornell box: +1.3 %, PixelSampler::Get out of line).
#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "render/path_tracer.h"
#include "render/probes.h"
#include "render/recording_scene.h"

namespace fovrt {
namespace {

// The probe renderer: the tracer over a RecordingScene, and the probes.
class ProbePathTracer final : public PathTracer<RecordingScene, ProbeRenderer> {
public:
    using PathTracer::PathTracer;

    vec3 Shade(const EyeCamera& camera, const SurfaceSample& sample, uint32_t seed,
               int sampleCount) const override {
        RayCounts counts;
        vec3 color = Remodulate(integrator_.ShadePixel(camera.Position(), sample, seed, sampleCount, counts));
        counters_.Add(counts);
        return color;
    }

    vec3 WorldPosition(const SurfaceSample& sample) const override { return integrator_.PositionOf(sample); }

    void RecordRays(std::vector<TracedRay>* log) override { integrator_.rays().SetLog(log); }

    uint64_t TraceBare(const std::vector<TracedRay>& rays) const override {
        std::atomic<uint64_t> hits{0};
        arena_.execute([&] {
            tbb::parallel_for(tbb::blocked_range<size_t>(0, rays.size(), 4096), [&](const tbb::blocked_range<size_t>& r) {
                uint64_t n = 0;
                for (size_t i = r.begin(); i != r.end(); ++i)
                    n += fovrt::TraceBare(integrator_.embree(), rays[i]) ? 1 : 0;
                hits += n;
            });
        });
        return hits.load();
    }
};

}  // namespace

std::unique_ptr<ProbeRenderer> CreateProbeRenderer(const Scene& scene, const RenderSettings& settings) {
    return std::make_unique<ProbePathTracer>(scene, settings);
}

}  // namespace fovrt
