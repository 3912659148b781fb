// Versions of fovrt and of the libraries it was built with, for `fovrt info` and run manifests, and
// the CPU a figure was measured on, for the headers of `fovrt bench`, `fovrt info` and the
// benchmark scripts (which print `fovrt info`'s line).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

namespace fovrt {

nlohmann::json BuildInfoJson();

struct CpuDescription {
    std::string model;                           // /proc/cpuinfo "model name" (or "unknown")
    int family = -1, modelNumber = -1;           // "cpu family", "model"; -1 where absent
    unsigned cores = 0;                          // logical CPUs this process may run on
    std::vector<std::string> vectorExtensions;   // e.g. SSE4.2 AVX AVX2 FMA AVX-512F …, widest last
};

// Reads the first processor's block of a /proc/cpuinfo text; `cores` is passed in.
CpuDescription ParseCpuInfo(std::string_view cpuinfo, unsigned cores);
// This machine: /proc/cpuinfo where readable, else the compiler's cpu-feature probe.
CpuDescription DescribeCpu();
// One line: "Intel(R) Xeon(R) … (family 6 model 85), 2 CPUs, vector: SSE4.2 AVX AVX2 FMA AVX-512F …".
std::string FormatCpu(const CpuDescription& cpu);

}  // namespace fovrt
