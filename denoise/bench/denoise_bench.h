// Denoiser benchmark (`fovrt bench --denoisers`): for each denoiser at W×H on the Vulkan device in
// use and for the C++ reference: per-pass ms, total ms, MPix/s, bytes moved per pixel per frame
// (reads + writes of every pass, each plane counted once per pass: denoise/bench/pass_bytes.h), and the
// bandwidth bound of each pass against the host memcpy bandwidth and against the Vulkan device's
// own streaming-copy bandwidth (vk/bandwidth.h).
#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include "denoise/bench/atrous_probe.h"
#include "denoise/denoiser.h"
#include "denoise/params.h"
#include "vk/bandwidth.h"

namespace fovrt {

struct DenoiserBenchOptions {
    std::vector<std::string> denoisers;  // empty: every name in DenoiserNames() that exists
    int width = 1280;
    int height = 720;
    int frames = 3;            // timed frames
    int warmup = 5;            // untimed frames first: histories reach the variance threshold (4),
                               // so the timed frames are the steady state
    std::string device = "auto";
    bool reference = true;     // also time the C++ reference (device cpu)
    DenoiserParams params;
    FILE* out = stdout;
};

struct PassBench {
    std::string pass;
    double ms = 0.0;             // mean per frame
    double bytesPerPixel = 0.0;  // reads + writes (0 when unknown)
};

struct DenoiserBenchResult {
    std::string name;
    std::string backend;          // "vulkan" or "cpu"
    std::vector<PassBench> passes;
    double computeMs = 0.0;       // sum of the compute passes (no upload/download)
    double wallMs = 0.0;          // Denoise() wall clock, transfers included
    double bytesPerPixel = 0.0;   // compute passes
    double boundMs = 0.0;         // bytes / memcpy bandwidth
    double deviceBoundMs = 0.0;   // bytes / device streaming-copy bandwidth (Vulkan only)
};

struct DenoiserBenchReport {
    double memcpyGBps = 0.0;      // (read + write) bytes per second of a large memcpy
    DeviceBandwidth device;       // streaming copy on the Vulkan device (zero without one)
    AtrousFloor atrousFloor;      // one à-trous pair dispatch, as run and with unit weights (Vulkan only)
    std::string deviceName;
    std::vector<DenoiserBenchResult> results;
};

// Measures memcpy bandwidth (bytes read + written per second) on `megabytes`-sized buffers.
double MeasureMemcpyBandwidth(size_t megabytes = 256);

DenoiserBenchReport RunDenoiserBench(const DenoiserBenchOptions& options);

}  // namespace fovrt
