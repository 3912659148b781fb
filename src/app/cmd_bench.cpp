// `fovrt bench`: path-tracer throughput (Mrays/s counting primary, shadow and bounce rays;
// Msamples/s counting path samples) on stereo frames, then the side-by-side comparison with
// Embree's own tutorial path tracer (Debian embree-tools, /usr/bin/pathtracer) on the same
// Cornell box OBJ at equal resolution, spp and path length, both on 2 threads.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <tbb/info.h>

#include "commands.h"
#include "core/camera.h"
#include "core/cpu_time.h"
#include "core/error.h"
#include "core/frame_inputs.h"
#include "denoise/bench/denoise_bench.h"
#include "denoise/denoiser_factory.h"
#include "pipeline/build_info.h"
#include "render/probes.h"
#include "render/renderer.h"
#include "scene/scene.h"

namespace fovrt {
namespace {

using Clock = std::chrono::steady_clock;

double Seconds(Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double>(b - a).count();
}

struct BenchOptions {
    std::vector<std::string> scenes = {"cornell", "veach-ajar"};
    int width = 1280;
    int height = 720;
    int spp = 1;
    int maxDepth = 2;
    int frames = 1;
    int threads = 0;
    bool compare = true;
    bool bareProbe = true;  // trace the same rays with bare Embree calls (ProbeBareEmbree)
    std::string fbetaPlane = "off";  // RenderSettings::fbetaPlane: off, on, or ab (both, frames alternated)
    int compareSpp = 4;
    int compareRounds = 3;
    std::string embreeBinary = "/usr/bin/pathtracer";
    bool denoisers = false;  // time the denoisers instead (denoise/bench/denoise_bench.h)
    std::vector<std::string> denoiserNames;  // --denoiser: empty = all
    bool reference = true;
    std::string precision = "fp32";
    int stagingRingMiB = -1;  // --staging-ring-mib: -1 the default ring, 0 the frame's transfers at once
    std::string device = "auto";
};

size_t TriangleCount(const Scene& scene) {
    size_t n = 0;
    for (const Instance& inst : scene.instances) n += scene.meshes[inst.mesh].triangles.size();
    return n;
}

struct Throughput {
    double seconds = 0.0;
    double cpuSeconds = 0.0;
    RenderStats stats;
    uint64_t checksum = 0;  // FNV-1a over every FrameInputs plane of the last frame, both eyes
};

// FNV-1a 64 over the bytes of every plane, eye by eye: equal checksums = bit-identical images
// (A/B checks of tracer optimisations).
uint64_t Checksum(const std::vector<FrameInputs>& frames) {
    uint64_t h = 0xcbf29ce484222325ull;
    for (const FrameInputs& f : frames)
        f.ForEachPlane([&](const PlaneBytes& p) {
            const auto* bytes = static_cast<const unsigned char*>(p.data);
            for (size_t i = 0; i < p.bytes; ++i) h = (h ^ bytes[i]) * 0x100000001b3ull;
        });
    return h;
}

// Renders `frames` frames of the given eye cameras with each renderer (after one untimed warm-up
// frame each). Several renderers take turns frame by frame, so that a load drifting over the run
// falls on each alike (A/B timings on a shared machine).
std::vector<Throughput> Measure(const std::vector<Renderer*>& renderers, const std::vector<EyeCamera>& eyes,
                                int spp, int frames) {
    std::vector<std::vector<FrameInputs>> out(renderers.size(), std::vector<FrameInputs>(eyes.size()));
    std::vector<Throughput> t(renderers.size());
    Plane<uint16_t> sppMap(eyes[0].width(), eyes[0].height(), uint16_t(spp));
    for (size_t r = 0; r < renderers.size(); ++r) {
        for (size_t e = 0; e < eyes.size(); ++e) renderers[r]->RenderEye(int(e), eyes[e], eyes[e], sppMap, out[r][e]);
        renderers[r]->ResetStats();
    }
    for (int f = 1; f <= frames; ++f)
        for (size_t r = 0; r < renderers.size(); ++r) {
            auto start = Clock::now();
            double cpuStart = CpuSeconds(RUSAGE_SELF);
            renderers[r]->SetFrame(uint32_t(f));
            for (size_t e = 0; e < eyes.size(); ++e) renderers[r]->RenderEye(int(e), eyes[e], eyes[e], sppMap, out[r][e]);
            t[r].seconds += Seconds(start, Clock::now());
            t[r].cpuSeconds += CpuSeconds(RUSAGE_SELF) - cpuStart;
        }
    for (size_t r = 0; r < renderers.size(); ++r) {
        t[r].stats = renderers[r]->Stats();
        t[r].checksum = Checksum(out[r]);
    }
    return t;
}

void PrintThroughput(const char* label, const Throughput& t, int frames) {
    const RenderStats& s = t.stats;
    std::printf("  %s: %.1f ms/frame (%.1f per eye), %.2f Mrays/s traced (primary %.2fM of which %.2fM guide rays, "
                "shadow %.2fM of which %.2fM reused per pixel, bounce %.2fM per frame), %.2f Msamples/s (%.2f per "
                "CPU-second), %llu dropped samples, checksum %016llx\n",
                label, 1e3 * t.seconds / frames, 1e3 * t.seconds / frames / 2.0, 1e-6 * double(s.Rays()) / t.seconds,
                1e-6 * double(s.primaryRays) / frames, 1e-6 * double(s.guideRays) / frames,
                1e-6 * double(s.shadowRays) / frames,
                1e-6 * double(s.shadowRaysReused) / frames, 1e-6 * double(s.bounceRays) / frames, 1e-6 * double(s.samples) / t.seconds,
                1e-6 * double(s.samples) / t.cpuSeconds,
                static_cast<unsigned long long>(s.droppedSamples), static_cast<unsigned long long>(t.checksum));
}

// The same rays again with nothing but rtcIntersect1 / rtcOccluded1: the rays of the last timed
// frame are recorded by a probe renderer (render/probes.h; the timed renderer logs nothing), then
// traced `frames` times on its threads. tracer / bare is what shading, sampling and bookkeeping
// cost on top of Embree's traversal (primary rays, which the tracer sends as 8-wide coherent
// packets, go one at a time here).
void ProbeBareEmbree(const Scene& scene, const RenderSettings& settings, const std::vector<EyeCamera>& eyes, int spp,
                     int frames, const Throughput& tracer) {
    auto probe = CreateProbeRenderer(scene, settings);
    ProbeRenderer& renderer = *probe;
    renderer.SetFrame(uint32_t(frames));
    std::vector<TracedRay> rays;
    std::vector<FrameInputs> out(eyes.size());
    Plane<uint16_t> sppMap(eyes[0].width(), eyes[0].height(), uint16_t(spp));
    renderer.RecordRays(&rays);
    for (size_t e = 0; e < eyes.size(); ++e) renderer.RenderEye(int(e), eyes[e], eyes[e], sppMap, out[e]);
    renderer.RecordRays(nullptr);
    uint64_t hits = renderer.TraceBare(rays);  // warm-up
    auto start = Clock::now();
    double cpuStart = CpuSeconds(RUSAGE_SELF);
    for (int f = 0; f < frames; ++f) hits += renderer.TraceBare(rays);
    double seconds = Seconds(start, Clock::now()), cpu = CpuSeconds(RUSAGE_SELF) - cpuStart;
    double bare = double(rays.size()) * frames / seconds, bareCpu = double(rays.size()) * frames / cpu;
    double ours = double(tracer.stats.Rays()) / tracer.seconds, oursCpu = double(tracer.stats.Rays()) / tracer.cpuSeconds;
    std::printf("  bare Embree on the same %zu rays/frame (rtcIntersect1/rtcOccluded1 only, %.1f%% hit): %.2f Mrays/s "
                "(%.2f per CPU-second); tracer / bare = %.2f wall-clock, %.2f per CPU-second\n",
                rays.size(), 100.0 * double(hits) / (double(rays.size()) * (frames + 1)), 1e-6 * bare,
                1e-6 * bareCpu, ours / bare, oursCpu / bareCpu);
}

void BenchScene(const std::string& name, const BenchOptions& o) {
    std::filesystem::path path;
    Scene scene;
    auto t0 = Clock::now();
    try {
        path = ResolveSceneName(name);
        scene = LoadScene(path);
    } catch (const Error& e) {
        std::printf("scene %s: skipped (%s)\n", name.c_str(), e.what());
        return;
    }
    auto t1 = Clock::now();
    RenderSettings settings;
    settings.maxDepth = o.maxDepth;
    settings.threads = o.threads;
    settings.fbetaPlane = o.fbetaPlane == "on";
    auto renderer = CreateRenderer(scene, settings);
    auto t2 = Clock::now();
    std::unique_ptr<Renderer> withFbeta;  // --fbeta-plane ab: the same renderer with the plane on
    if (o.fbetaPlane == "ab") {
        settings.fbetaPlane = true;
        withFbeta = CreateRenderer(scene, settings);
    }
    auto t3 = Clock::now();
    StereoRig rig;
    rig.head = scene.HeadAt(0.0f);
    rig.width = o.width;
    rig.height = o.height;
    rig.fov[0] = rig.fov[1] =
        Fov::FromHorizontal(Radians(scene.horizontalFovDegrees), float(o.width) / float(o.height));
    std::vector<Renderer*> renderers = {renderer.get()};
    if (withFbeta) renderers.push_back(withFbeta.get());
    const std::vector<Throughput> t = Measure(renderers, {rig.Eye(0), rig.Eye(1)}, o.spp, o.frames);
    std::printf("scene %s (%s): %zu triangles, load %.2f s, BVH %.2f s", name.c_str(), path.string().c_str(),
                TriangleCount(scene), Seconds(t0, t1), Seconds(t1, t2));
    // The second renderer's setup is the F_beta table (built once per process, on first need).
    if (withFbeta) std::printf(", second renderer (F_beta table) %.2f s", Seconds(t2, t3));
    std::printf("\n");
    for (size_t r = 0; r < t.size(); ++r) {
        const bool on = o.fbetaPlane == "on" || r == 1;
        std::string label = std::to_string(o.width) + "x" + std::to_string(o.height) + " x 2 eyes, " +
                            std::to_string(o.spp) + " spp, max depth " + std::to_string(o.maxDepth) + ", " +
                            std::to_string(o.frames) + " frames, F_beta plane " + (on ? "on" : "off");
        PrintThroughput(label.c_str(), t[r], o.frames);
    }
    if (t.size() == 2)
        std::printf("  F_beta plane on / off, time per frame (frames alternated): %.3f wall-clock, %.3f CPU\n",
                    t[1].seconds / t[0].seconds, t[1].cpuSeconds / t[0].cpuSeconds);
    if (o.bareProbe) ProbeBareEmbree(scene, settings, {rig.Eye(0), rig.Eye(1)}, o.spp, o.frames, t[0]);
}

// Our tracer vs Embree's pathtracer tutorial on the shared Cornell box OBJ.
void CompareWithEmbree(const BenchOptions& o) {
    std::printf("comparison with Embree's pathtracer (embree-tools):\n");
    if (!std::filesystem::exists(o.embreeBinary)) {
        std::printf("  skipped: %s is absent (install embree-tools)\n", o.embreeBinary.c_str());
        return;
    }
    std::filesystem::path shared = SharedScenesDir();
    std::filesystem::path obj = shared / "cornell-box" / "CornellBox-Original.obj";
    if (shared.empty() || !std::filesystem::exists(obj)) {
        std::printf("  skipped: the shared Cornell box OBJ is absent\n");
        return;
    }
    // One camera for both: at (0, 1, 3.5) looking at (0, 1, 0), 40 degrees vertical FOV.
    const vec3 eye(0.0f, 1.0f, 3.5f), target(0.0f, 1.0f, 0.0f);
    const float vfov = 40.0f;
    float tanY = std::tan(Radians(vfov / 2.0f)), tanX = tanY * float(o.width) / float(o.height);
    Fov fov{-std::atan(tanX), std::atan(tanX), std::atan(tanY), -std::atan(tanY)};
    EyeCamera camera(Pose::LookAt(eye, target), fov, o.width, o.height);

    // Embree's OBJ loader ignores Ke (its image would be black), so both tracers get the same
    // single point light under the ceiling lamp instead of the emissive quad.
    const vec3 lightPosition(0.0f, 1.9f, 0.0f), lightIntensity(3.0f);
    Scene scene = LoadScene(obj);
    for (Material& m : scene.materials) m.emission = vec3(0.0f);
    Light light;
    light.name = "bench-point";
    light.position = lightPosition;
    light.color = lightIntensity;
    light.intensity = 1.0f;
    scene.lights = {light};
    RenderSettings settings;
    settings.maxDepth = o.maxDepth;
    settings.threads = 2;
    auto renderer = CreateRenderer(scene, settings);

    // Embree: time spp S and 3S in one process each; the difference removes loading, BVH build
    // and image writing, leaving the time of 2S spp over the image.
    std::filesystem::path image = std::filesystem::temp_directory_path() / "fovrt_bench_embree.ppm";
    struct Timing {
        double wall = 0.0, cpu = 0.0;
    };
    auto runEmbree = [&](int spp) {
        std::string cmd = o.embreeBinary + " -i '" + obj.string() + "' --size " + std::to_string(o.width) +
                          " " + std::to_string(o.height) + " --spp " + std::to_string(spp) +
                          " --max-path-length " + std::to_string(o.maxDepth) +
                          " --threads 2 --vp 0 1 3.5 --vi 0 1 0 --vu 0 1 0 --fov " + std::to_string(vfov) +
                          " --pointlight " + fmt::format("{} {} {} {} {} {}", lightPosition.x, lightPosition.y,
                                                         lightPosition.z, lightIntensity.x, lightIntensity.y,
                                                         lightIntensity.z) +
                          " -o '" + image.string() + "' > /dev/null 2>&1";
        auto start = Clock::now();
        double cpuStart = CpuSeconds(RUSAGE_CHILDREN);
        int rc = std::system(cmd.c_str());
        Timing t{Seconds(start, Clock::now()), CpuSeconds(RUSAGE_CHILDREN) - cpuStart};
        if (rc != 0) Fail("bench: '{}' failed with status {}", cmd, rc);
        return t;
    };
    // Rounds of fovrt then Embree, so that the machine's speed drifting over the command falls on
    // both alike. Each round times the same work on both sides: fovrt renders 2 frames at S spp,
    // the W x H x 2S samples of Embree's 3S - S difference. Both rates count pixel samples,
    // background pixels included (Embree's tutorial traces them too; ours stops after the primary
    // ray there).
    const double roundSamples = double(o.width) * o.height * 2.0 * o.compareSpp;
    Throughput ours;
    double rays = 0.0;
    Timing embree, embreeS, embree3S;
    std::vector<double> roundRatios;
    for (int round = 0; round < o.compareRounds; ++round) {
        const Throughput t = Measure({renderer.get()}, {camera}, o.compareSpp, 2)[0];
        const Timing tS = runEmbree(o.compareSpp), t3S = runEmbree(3 * o.compareSpp);
        ours.seconds += t.seconds;
        ours.cpuSeconds += t.cpuSeconds;
        rays += double(t.stats.Rays());
        ours.checksum = t.checksum;
        const Timing diff{std::max(t3S.wall - tS.wall, 1e-6), std::max(t3S.cpu - tS.cpu, 1e-6)};
        embree.wall += diff.wall;
        embree.cpu += diff.cpu;
        embreeS.wall += tS.wall;
        embreeS.cpu += tS.cpu;
        embree3S.wall += t3S.wall;
        embree3S.cpu += t3S.cpu;
        roundRatios.push_back((roundSamples / t.cpuSeconds) / (roundSamples / diff.cpu));
    }
    std::filesystem::remove(image);
    const double samples = roundSamples * o.compareRounds;
    const double oursRate = samples / ours.seconds, oursCpuRate = samples / ours.cpuSeconds;
    const double embreeRate = samples / embree.wall, embreeCpuRate = samples / embree.cpu;
    std::printf("  %dx%d, %d spp, path length %d (primary + %d bounce(s), NEE at every vertex), 2 threads,\n"
                "  one point light (%.1f, %.1f, %.1f) in both; %d round(s), each fovrt's 2 frames then Embree's run pair\n",
                o.width, o.height, o.compareSpp, o.maxDepth, o.maxDepth - 1, lightPosition.x, lightPosition.y,
                lightPosition.z, o.compareRounds);
    std::printf("  fovrt:  %.2f Msamples/s wall, %.2f Msamples per CPU-second (%.2f Mrays/s traced; "
                "primary rays and primary-vertex point-light shadow rays once per pixel, not per sample; checksum "
                "%016llx)\n",
                1e-6 * oursRate, 1e-6 * oursCpuRate,
                1e-6 * rays / ours.seconds,
                static_cast<unsigned long long>(ours.checksum));
    std::printf("  embree: %.2f Msamples/s wall, %.2f Msamples per CPU-second (%s, per round on average: %.3f s / %.3f s "
                "CPU at %d spp, %.3f s / %.3f s CPU at %d spp)\n",
                1e-6 * embreeRate, 1e-6 * embreeCpuRate, o.embreeBinary.c_str(), embreeS.wall / o.compareRounds,
                embreeS.cpu / o.compareRounds, o.compareSpp, embree3S.wall / o.compareRounds,
                embree3S.cpu / o.compareRounds, 3 * o.compareSpp);
    std::string rounds;
    for (double r : roundRatios) rounds += fmt::format("{}{:.2f}", rounds.empty() ? "" : " / ", r);
    std::printf("  ratio fovrt / embree samples per second: %.2f wall-clock, %.2f per CPU-second (rounds, per "
                "CPU-second: %s)\n",
                oursRate / embreeRate, oursCpuRate / embreeCpuRate, rounds.c_str());
}

}  // namespace

void RegisterBenchCommand(CLI::App& app) {
    auto o = std::make_shared<BenchOptions>();
    CLI::App* cmd = app.add_subcommand("bench", "Path-tracer throughput (Mrays/s, Msamples/s) and "
                                                "comparison with Embree's own path tracer");
    cmd->add_option("--scene", o->scenes, "Scene names or files (default: cornell veach-ajar)");
    cmd->add_option("--width", o->width, "Width per eye")->check(CLI::Range(1, 16384));
    cmd->add_option("--height", o->height, "Height per eye")->check(CLI::Range(1, 16384));
    cmd->add_option("--spp", o->spp, "Samples per pixel")->check(CLI::Range(1, 4096));
    cmd->add_option("--max-depth", o->maxDepth, "Path vertices after the camera (2 = one bounce)")
        ->check(CLI::Range(1, 64));
    cmd->add_option("--frames", o->frames, "Timed frames per scene")->check(CLI::Range(1, 100000));
    cmd->add_option("--threads", o->threads, "Threads (0 = all)")->check(CLI::Range(0, 1024));
    cmd->add_flag("!--no-compare", o->compare, "Skip the comparison with Embree's pathtracer");
    cmd->add_flag("!--no-bare", o->bareProbe, "Skip tracing the same rays with bare rtcIntersect1/rtcOccluded1");
    cmd->add_option("--fbeta-plane", o->fbetaPlane,
                    "Fill the F_beta plane as for a +brdf variant (albedo demodulation): off, on, or ab "
                    "(both, frames alternated, and their ratio)")
        ->check(CLI::IsMember({"off", "on", "ab"}));
    cmd->add_option("--compare-spp", o->compareSpp, "spp of the Embree comparison")->check(CLI::Range(1, 4096));
    cmd->add_option("--compare-rounds", o->compareRounds,
                    "Rounds of the Embree comparison (each: fovrt's 2 frames, then Embree at spp S and 3S)")
        ->check(CLI::Range(1, 1000));
    cmd->add_option("--embree-bin", o->embreeBinary, "Embree's tutorial path tracer");
    cmd->add_flag("--denoisers", o->denoisers, "Time the denoisers (Vulkan and C++ reference) at --width x --height instead");
    cmd->add_option("--denoiser", o->denoiserNames, "With --denoisers: only these (repeatable; default all)");
    cmd->add_flag("!--no-reference", o->reference, "With --denoisers: skip the C++ reference");
    cmd->add_option("--precision", o->precision, "With --denoisers: history storage (fp32 or fp16)");
    cmd->add_option("--staging-ring-mib", o->stagingRingMiB,
                    "With --denoisers: the staging ring's MiB (0: as large as a frame's transfers, one submit per frame; default: the denoisers' ring)")
        ->check(CLI::Range(0, 65536));
    cmd->add_option("--device", o->device, "With --denoisers: device, as denoise.device (auto, vulkan, cpu or an index from `fovrt info`)");
    cmd->callback([o] {
        // Every figure says where it was measured.
        std::printf("machine: %s\n", FormatCpu(DescribeCpu()).c_str());
        if (o->denoisers) {
            DenoiserBenchOptions options;  // named fields: no -Wmissing-field-initializers
            options.width = o->width;
            options.height = o->height;
            for (const std::string& name : o->denoiserNames) FindDenoiserVariant(name, "bench --denoiser");
            options.params.precision = ParsePrecision(o->precision, "bench --precision");
            if (options.params.precision == Precision::Auto)
                Fail("bench --precision: fp32 or fp16 (a benchmark names the storage it times)");
            if (o->stagingRingMiB == 0) options.params.transferRingBytes = SIZE_MAX;
            if (o->stagingRingMiB > 0) options.params.transferRingBytes = size_t(o->stagingRingMiB) << 20;
            options.denoisers = o->denoiserNames;
            options.reference = o->reference;
            options.device = o->device;
            (void)RunDenoiserBench(options);
            return;
        }
        int threads = o->threads > 0 ? o->threads : tbb::info::default_concurrency();
        std::printf("fovrt bench: %d thread(s)\n", threads);
        for (const std::string& name : o->scenes) BenchScene(name, *o);
        if (o->compare) CompareWithEmbree(*o);
    });
}

}  // namespace fovrt
