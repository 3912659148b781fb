#include "denoise/bench/denoise_bench.h"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <map>
#include <memory>
#include <random>

#include <fmt/format.h>

#include "core/error.h"
#include "denoise/denoiser_factory.h"
#include "denoise/reference/asvgf_ref.h"
#include "denoise/bench/pass_bytes.h"
#include "shaders/shared_constants.h"
#include "vk/bandwidth.h"
#include "vk/context.h"
#include "vk/device_choice.h"

namespace fovrt {

namespace {

using Clock = std::chrono::steady_clock;

// A plausible frame: a floor, a wall and boxes with different object ids, noisy HDR illumination,
// slow camera drift (sub-pixel motion), foveated sample counts.
FrameInputs BenchFrame(int w, int h, uint32_t frame) {
    FrameInputs f;
    f.Allocate(w, h);
    f.frameIndex = frame;
    std::mt19937 rng(1234u + frame);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            bool floor = y > h / 2;
            bool box = (x / 160) % 2 == 1 && y > h / 3 && y < 2 * h / 3;
            uint32_t id = box ? 2u + uint32_t(x / 160) : floor ? 0u : 1u;
            f.objectId(x, y) = id;
            float depth = box ? 3.0f : floor ? 2.0f + 20.0f * float(h - y) / float(h) : 10.0f;
            f.linearDepth(x, y) = depth;
            f.depthGradient(x, y) = floor ? vec2(0.0f, -20.0f / float(h)) : vec2(0.0f);
            f.normal(x, y) = floor ? vec3(0, 1, 0) : vec3(0, 0, 1);
            f.albedo(x, y) = vec3(0.7f, 0.6f, 0.5f);
            f.prevPixel(x, y) = vec2(x + 0.5f + 0.3f, y + 0.5f);
            float dx = float(x - w / 2), dy = float(y - h / 2);
            uint16_t n = dx * dx + dy * dy < 200.0f * 200.0f ? 8 : 1;
            f.sampleCount(x, y) = n;
            auto noisy = [&](float mean) { float v = u(rng); return vec3(mean * 2.0f * v * v * 1.5f); };
            f.direct(x, y) = noisy(1.0f);
            f.indirect(x, y) = noisy(0.3f);
        }
    return f;
}

bool IsComputePass(const std::string& pass) { return pass != "upload" && pass != "download"; }

}  // namespace

double MeasureMemcpyBandwidth(size_t megabytes) {
    const size_t bytes = megabytes << 20;
    std::vector<char> a(bytes, 1), b(bytes, 2);
    std::memcpy(b.data(), a.data(), bytes);  // warm up (page faults)
    double best = 1e30;
    for (int i = 0; i < 5; ++i) {
        auto t0 = Clock::now();
        std::memcpy(i % 2 ? a.data() : b.data(), i % 2 ? b.data() : a.data(), bytes);
        best = std::min(best, std::chrono::duration<double>(Clock::now() - t0).count());
    }
    volatile char sink = a[bytes / 2] + b[bytes / 3];
    (void)sink;
    return 2.0 * double(bytes) / best / 1e9;
}

DenoiserBenchReport RunDenoiserBench(const DenoiserBenchOptions& o) {
    DenoiserBenchReport report;
    FILE* out = o.out;
    std::vector<std::string> names = o.denoisers.empty() ? DenoiserNames() : o.denoisers;
    report.memcpyGBps = MeasureMemcpyBandwidth();
    const double pixels = double(o.width) * double(o.height);

    std::unique_ptr<VulkanContext> context;
    if (const DeviceDecision decision = ResolveVulkanDevice(o.device); decision.vulkan) {
        context = std::make_unique<VulkanContext>(VulkanContext::Create(decision.options));
        report.deviceName = context->deviceName();
    } else if (!decision.notice.empty()) {
        fmt::print(out, "{}\n", decision.notice);
    }
    if (context) {
        report.device = MeasureDeviceBandwidth(*context);
        report.atrousFloor = MeasureAtrousFloor(*context, o.width, o.height);
    }
    fmt::print(out, "denoiser bench: {}x{}, {} timed frame(s) after {} warm-up frame(s); Vulkan device: {}\n",
               o.width, o.height, o.frames, o.warmup, context ? context->deviceName() : std::string("none"));
    fmt::print(out, "bandwidth (bytes read + written per second, best of a few runs):\n");
    fmt::print(out, "  host memcpy            {:7.1f} GB/s  (256 MiB buffers; the bound of the C++ reference)\n",
               report.memcpyGBps);
    if (context) {
        fmt::print(out, "  device streaming copy  {:7.1f} GB/s  (rgba32f texel-buffer read -> std430 vec4 write: the "
                        "passes' access layer)\n", report.device.texelGBps);
        fmt::print(out, "  device streaming copy  {:7.1f} GB/s  (std430 vec4 read -> std430 vec4 write)\n",
                   report.device.storageGBps);
        fmt::print(out, "  (device copies: shaders/bandwidth_copy.comp on {}, {} MiB, GPU timestamps)\n",
                   context->deviceName(), report.device.bytes >> 20);
        if (report.device.exp2PerSecond > 0.0)
            fmt::print(out, "  device exp2 throughput {:7.2f} G/s   (the same copy + {} exp2 per element; every "
                            "edge-stopping weight costs one exp2 per channel: an ALU floor of the à-trous taps)\n",
                       report.device.exp2PerSecond / 1e9, BANDWIDTH_EXP2_PER_ELEMENT);
        else
            fmt::print(out, "  device exp2 throughput  not resolved (hidden behind the copy's memory traffic)\n");
        const AtrousFloor& af = report.atrousFloor;
        const double bytes = af.bytesPerPixel * double(af.width) * double(af.height);
        const double memcpyBoundMs = bytes / (report.memcpyGBps * 1e9) * 1e3;
        const double deviceBoundMs = bytes / (report.device.texelGBps * 1e9) * 1e3;
        fmt::print(out, "a-trous floor (svgf_atrous_pair at step {}, {} B/pixel; best of 3, alternated; "
                        "denoise/bench/atrous_probe.h):\n", af.step, af.bytesPerPixel);
        fmt::print(out, "  as the denoisers run it {:8.2f} ms  = {:5.1f}x memcpy bound, {:5.1f}x device-copy bound\n",
                   af.fullMs, af.fullMs / memcpyBoundMs, af.fullMs / deviceBoundMs);
        fmt::print(out, "  every weight 1          {:8.2f} ms  = {:5.1f}x memcpy bound, {:5.1f}x device-copy bound "
                        "(same fetches, sums and stores; no weight arithmetic)\n",
                   af.unitWeightsMs, af.unitWeightsMs / memcpyBoundMs, af.unitWeightsMs / deviceBoundMs);
    }
    fmt::print(out, "bytes/pixel: what each pass reads + writes per pixel per frame, every plane counted once per "
                    "dispatch (gather taps assumed to hit cache; sizes from the memory plan; steady state: no pixel "
                    "below the variance threshold): a lower bound on the traffic\n");
    fmt::print(out, "bound = bytes / bandwidth; x = measured / bound. Vulkan passes: against memcpy and against the "
                    "texel-buffer device copy; on a GPU both are device memory, on lavapipe the device copy is the compute "
                    "path's real ceiling. C++ reference: against memcpy only. upload/download are transfer copies, not in the compute total\n");
    if (o.reference) fmt::print(out, "C++ reference: scalar per-pixel loops, rows in parallel with TBB\n");

    std::vector<FrameInputs> frames;
    const int total = o.warmup + o.frames;
    for (int t = 0; t < std::min(total, 4); ++t) frames.push_back(BenchFrame(o.width, o.height, uint32_t(t)));

    for (const std::string& name : names) {
        std::vector<std::string> devices;
        if (context) devices.push_back("vulkan");
        if (o.reference || !context) devices.push_back("cpu");
        for (const std::string& device : devices) {
            std::unique_ptr<Denoiser> d;
            try {
                d = CreateDenoiser(name, device, o.params, device == "vulkan" ? context.get() : nullptr);
            } catch (const Error& e) {
                fmt::print(out, "{} ({}): skipped: {}\n", name, device, e.what());
                continue;
            }
            DenoiserBenchResult r;
            r.name = name;
            r.backend = d->Backend();
            Plane<vec3> output;
            std::map<std::string, double> sums;
            std::vector<std::string> order;
            double wall = 0.0;
            for (int t = 0; t < total; ++t) {
                auto t0 = Clock::now();
                d->Denoise(frames[size_t(t) % frames.size()], output);
                double ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
                if (t < o.warmup) continue;
                wall += ms;
                for (const PassTiming& p : d->LastTimings()) {
                    if (!sums.count(p.pass)) order.push_back(p.pass);
                    sums[p.pass] += p.ms;
                }
            }
            r.wallMs = wall / o.frames;
            PassBytesOptions bo;
            const ivec2 grid = StratumGridSize(o.width, o.height);
            bo.gradientSamplesPerStratum =
                double(frames[0].gradientSamples.size()) / (double(grid.x) * double(grid.y));
            std::map<std::string, double> bytes;
            for (const PassBytes& b :
                 DenoiserPassBytes(name, r.backend, o.width, o.height, ParamsForDenoiser(name, o.params), bo))
                bytes[b.pass] = b.bytesPerPixel;
            for (const std::string& pass : order) {
                if (!bytes.count(pass)) Fail("denoiser bench: no byte model for pass '{}' of {} ({})", pass, name, r.backend);
                PassBench pb{pass, sums[pass] / o.frames, bytes[pass]};
                r.passes.push_back(pb);
                if (IsComputePass(pass)) {
                    r.computeMs += pb.ms;
                    r.bytesPerPixel += pb.bytesPerPixel;
                }
            }
            const bool onDevice = r.backend == "vulkan" && report.device.texelGBps > 0.0;
            auto boundMs = [&](double bytesPerPixel, double gbps) { return bytesPerPixel * pixels / (gbps * 1e9) * 1e3; };
            auto times = [](double ms, double bound) {
                return bound > 0 ? fmt::format("{:.1f}", ms / bound) : std::string("-");
            };
            r.boundMs = boundMs(r.bytesPerPixel, report.memcpyGBps);
            r.deviceBoundMs = onDevice ? boundMs(r.bytesPerPixel, report.device.texelGBps) : 0.0;
            fmt::print(out, "\n{} [{}]\n", name, r.backend);
            fmt::print(out, "  {:<22} {:>9} {:>11} {:>12} {:>9} {:>12} {:>9}\n", "pass", "ms", "bytes/pixel",
                       "memcpy bound", "x memcpy", "device bound", "x device");
            for (const PassBench& p : r.passes) {
                const double host = boundMs(p.bytesPerPixel, report.memcpyGBps);
                const double dev = onDevice ? boundMs(p.bytesPerPixel, report.device.texelGBps) : 0.0;
                fmt::print(out, "  {:<22} {:>9.2f} {:>11.1f} {:>12.2f} {:>9} {:>12} {:>9}\n", p.pass, p.ms,
                           p.bytesPerPixel, host, times(p.ms, host), onDevice ? fmt::format("{:.2f}", dev) : "-",
                           times(p.ms, dev));
            }
            fmt::print(out, "  compute total {:.2f} ms ({:.1f} MPix/s), {:.0f} B/pixel moved; bound at memcpy {:.2f} ms "
                            "({}x)",
                       r.computeMs, pixels / (r.computeMs * 1e3), r.bytesPerPixel, r.boundMs,
                       times(r.computeMs, r.boundMs));
            if (onDevice)
                fmt::print(out, ", at device copy {:.2f} ms ({}x)", r.deviceBoundMs, times(r.computeMs, r.deviceBoundMs));
            fmt::print(out, "; Denoise() wall {:.2f} ms incl. transfers\n", r.wallMs);
            report.results.push_back(std::move(r));
        }
    }
    // Speed-up of each Vulkan denoiser over its reference.
    for (const auto& v : report.results) {
        if (v.backend != "vulkan") continue;
        for (const auto& c : report.results)
            if (c.backend == "cpu" && c.name == v.name)
                fmt::print(out, "{}: vulkan {:.2f} ms vs C++ reference {:.2f} ms (compute): {:.2f}x faster\n", v.name,
                           v.computeMs, c.computeMs, c.computeMs / v.computeMs);
    }
    return report;
}

}  // namespace fovrt
