#include "denoise/denoise_bench.h"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <map>
#include <memory>
#include <random>

#include <fmt/format.h>

#include "core/error.h"
#include "denoise/denoiser_factory.h"
#include "denoise/memory_plan.h"
#include "denoise/svgf_layout.h"
#include "vk/context.h"

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

std::vector<PassBench> SvgfPassBytes(const DenoiserParams& params) {
    const SvgfParams& p = params.svgf;
    const double hs = double(HistoryScalarBytes(params.precision));
    const double channels = p.filterCombined ? 1 : 2;
    const bool weighted = p.weightBySampleCount;
    const int iterations = p.atrousIterations;
    const bool atrousFeedback = p.feedbackIteration >= 1 && p.feedbackIteration <= iterations;
    const double geometry = 4 + 12 + 4;  // depth, normal, object id
    std::vector<PassBench> out;
    double uploads = 12 * 4 + 8 + 8 + geometry + (weighted ? 2 : 0);
    out.push_back({"upload", 0.0, 2 * uploads});  // staging read + device write
    // Both channels in one pass: geometry of both frames, depth gradient, motion and sample counts
    // are read once per pixel; colour in, histories and illumination per channel.
    double reprojectShared = geometry * 2 + 8 + 8 + (weighted ? 2 : 0);
    double reprojectChannel = (p.filterCombined ? 24 : 12) +
                              hs * (3 + 2 + 1 + (weighted ? 1 : 0)) +                       // history read
                              hs * (2 + 1 + (weighted ? 1 : 0) + (atrousFeedback ? 0 : 3)) +  // history write
                              16;
    out.push_back({"reproject", 0.0, reprojectShared + channels * reprojectChannel});
    double moments = 16 + geometry + 8 + hs * (2 + 1) + 16;
    out.push_back({"filter_moments", 0.0, channels * moments});
    for (int i = 0; i < iterations; ++i) {
        // Both channels in one pass: the geometry and depth gradient are read once per pixel.
        double perChannel = 16 + 16 + (atrousFeedback && i + 1 == p.feedbackIteration ? 3 * hs : 0);
        out.push_back({fmt::format("atrous{}", i), 0.0, geometry + 8 + channels * perChannel});
    }
    out.push_back({"modulate", 0.0, 16 * channels + 12 + 12 + 12});
    out.push_back({"download", 0.0, 2 * 12});
    return out;
}

DenoiserBenchReport RunDenoiserBench(const DenoiserBenchOptions& o) {
    DenoiserBenchReport report;
    FILE* out = o.out;
    std::vector<std::string> names = o.denoisers.empty() ? DenoiserNames() : o.denoisers;
    report.memcpyGBps = MeasureMemcpyBandwidth();
    const double pixels = double(o.width) * double(o.height);

    std::unique_ptr<VulkanContext> context;
    if (o.device != "cpu") {
        if (o.device == "auto" && !VulkanContext::Available()) {
            fmt::print(out, "no Vulkan device: timing the C++ reference only\n");
        } else {
            VulkanContextOptions vo;
            vo.device = o.device == "vulkan" ? "auto" : o.device;
            context = std::make_unique<VulkanContext>(VulkanContext::Create(vo));
            report.deviceName = context->deviceName();
        }
    }
    fmt::print(out, "denoiser bench: {}x{}, {} timed frame(s) after {} warm-up frame(s); Vulkan device: {}\n",
               o.width, o.height, o.frames, o.warmup, context ? context->deviceName() : std::string("none"));
    fmt::print(out, "memcpy bandwidth: {:.1f} GB/s (bytes read + written per second, 256 MiB buffers)\n",
               report.memcpyGBps);
    fmt::print(out, "C++ reference: scalar per-pixel loops, rows in parallel with TBB\n");

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
            std::map<std::string, double> bytes;
            if (name == "svgf" || name == "svgf-weighted")
                for (const PassBench& b : SvgfPassBytes(ParamsForDenoiser(name, o.params))) bytes[b.pass] = b.bytesPerPixel;
            // Vulkan only: the guide packing pass reads depth, normal, object id and writes a vec4.
            if ((name == "svgf" || name == "svgf-weighted") && r.backend == "vulkan") bytes["pack_guide"] = 4 + 12 + 4 + 16;
            for (const std::string& pass : order) {
                PassBench pb{pass, sums[pass] / o.frames, bytes.count(pass) ? bytes[pass] : 0.0};
                r.passes.push_back(pb);
                if (IsComputePass(pass)) {
                    r.computeMs += pb.ms;
                    r.bytesPerPixel += pb.bytesPerPixel;
                }
            }
            bool compulsoryOnly = false;
            if (r.bytesPerPixel == 0.0) {
                // No per-pass model for this denoiser: bound it by its compulsory traffic from the
                // memory plan — every history read once and written once (an A/B pair is one read
                // and one write), inputs written, output written. A lower bound on bytes moved.
                double bytes = 0.0;
                for (const BufferPlan& b : PlanDenoiserMemory(name, o.width, o.height, ParamsForDenoiser(name, o.params)))
                    if (b.history || b.name.rfind("input.", 0) == 0 || b.name == "output") bytes += double(b.bytes);
                r.bytesPerPixel = bytes / pixels;
                compulsoryOnly = true;
            }
            r.boundMs = r.bytesPerPixel * pixels / (report.memcpyGBps * 1e9) * 1e3;
            fmt::print(out, "\n{} [{}]\n", name, r.backend);
            fmt::print(out, "  {:<16} {:>10} {:>12} {:>12} {:>10}\n", "pass", "ms", "bytes/pixel", "bound ms",
                       "x bound");
            for (const PassBench& p : r.passes) {
                double bound = p.bytesPerPixel * pixels / (report.memcpyGBps * 1e9) * 1e3;
                fmt::print(out, "  {:<16} {:>10.2f} {:>12.1f} {:>12.2f} {:>10}\n", p.pass, p.ms, p.bytesPerPixel,
                           bound, bound > 0 ? fmt::format("{:.1f}", p.ms / bound) : std::string("-"));
            }
            fmt::print(out, "  compute total {:.2f} ms ({:.1f} MPix/s), {:.0f} B/pixel moved, bandwidth bound "
                            "{:.2f} ms ({:.1f}x); Denoise() wall {:.2f} ms incl. transfers\n",
                       r.computeMs, pixels / (r.computeMs * 1e3), r.bytesPerPixel, r.boundMs,
                       r.boundMs > 0 ? r.computeMs / r.boundMs : 0.0, r.wallMs);
            if (compulsoryOnly)
                fmt::print(out, "  (no per-pass byte model: B/pixel is the compulsory traffic of the memory "
                                "plan — histories read and written once, inputs, output — a lower bound)\n");
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
