#include "pipeline/build_info.h"

#include <OpenEXR/OpenEXRConfig.h>
#include <embree3/rtcore.h>
#include <tbb/version.h>
#include <vulkan/vulkan.h>

#include <fmt/format.h>

#include <sched.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <thread>
#include <utility>

namespace fovrt {

nlohmann::json BuildInfoJson() {
    nlohmann::json info;
    info["fovrt"] = FOVRT_VERSION;
#ifdef NDEBUG
    info["build_type"] = "Release";
#else
    info["build_type"] = "Debug";
#endif
    info["compiler"] = fmt::format("{} {}",
#if defined(__clang__)
                                   "clang", __clang_version__
#else
                                   "gcc", __VERSION__
#endif
    );
    info["embree"] = fmt::format("{}.{}.{}", RTC_VERSION_MAJOR, RTC_VERSION_MINOR, RTC_VERSION_PATCH);
    info["tbb"] = fmt::format("{}.{}", TBB_VERSION_MAJOR, TBB_VERSION_MINOR);
    info["vulkan_headers"] = fmt::format("{}.{}.{}", VK_API_VERSION_MAJOR(VK_HEADER_VERSION_COMPLETE),
                                         VK_API_VERSION_MINOR(VK_HEADER_VERSION_COMPLETE),
                                         VK_HEADER_VERSION);
    info["openexr"] = OPENEXR_VERSION_STRING;
    return info;
}

namespace {

// The vector extensions that decide the tracer's and Embree's code paths, in /proc/cpuinfo's
// spelling and as printed; the AVX-512 subsets Embree's AVX-512 path needs come last.
struct VectorFlag {
    const char* cpuinfo;
    const char* shown;
};
constexpr VectorFlag kVectorFlags[] = {
    {"sse4_2", "SSE4.2"},     {"avx", "AVX"},           {"avx2", "AVX2"},         {"fma", "FMA"},
    {"avx512f", "AVX-512F"},  {"avx512cd", "AVX-512CD"}, {"avx512dq", "AVX-512DQ"},
    {"avx512bw", "AVX-512BW"}, {"avx512vl", "AVX-512VL"},
};

std::string_view Trim(std::string_view s) {
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
    return s;
}

unsigned UsableCores() {
    cpu_set_t set;
    if (sched_getaffinity(0, sizeof(set), &set) == 0 && CPU_COUNT(&set) > 0) return unsigned(CPU_COUNT(&set));
    return std::thread::hardware_concurrency();
}

}  // namespace

CpuDescription ParseCpuInfo(std::string_view cpuinfo, unsigned cores) {
    CpuDescription cpu;
    cpu.cores = cores;
    std::vector<std::string> flags;
    std::istringstream lines{std::string(cpuinfo)};
    for (std::string line; std::getline(lines, line);) {
        if (Trim(line).empty()) {
            if (!cpu.model.empty() || !flags.empty()) break;  // the first processor's block only
            continue;
        }
        const size_t colon = line.find(':');
        if (colon == std::string::npos) continue;
        const std::string_view key = Trim(std::string_view(line).substr(0, colon));
        const std::string_view value = Trim(std::string_view(line).substr(colon + 1));
        if (key == "model name") cpu.model = value;
        else if (key == "cpu family") cpu.family = std::atoi(std::string(value).c_str());
        else if (key == "model") cpu.modelNumber = std::atoi(std::string(value).c_str());
        else if (key == "flags") {
            std::istringstream words{std::string(value)};
            for (std::string word; words >> word;) flags.push_back(word);
        }
    }
    if (cpu.model.empty()) cpu.model = "unknown";
    for (const VectorFlag& f : kVectorFlags)  // whole flags: "avx512_vnni" is not "avx512f"
        if (std::find(flags.begin(), flags.end(), f.cpuinfo) != flags.end()) cpu.vectorExtensions.push_back(f.shown);
    return cpu;
}

CpuDescription DescribeCpu() {
    std::ifstream file("/proc/cpuinfo");
    std::ostringstream text;
    if (file) text << file.rdbuf();
    CpuDescription cpu = ParseCpuInfo(text.str(), UsableCores());
#if defined(__x86_64__) || defined(__i386__)
    if (cpu.vectorExtensions.empty()) {  // no /proc (another OS, a sandbox): ask the CPU
        __builtin_cpu_init();
        const std::pair<bool, const char*> probe[] = {
            {__builtin_cpu_supports("sse4.2"), "SSE4.2"},     {__builtin_cpu_supports("avx"), "AVX"},
            {__builtin_cpu_supports("avx2"), "AVX2"},         {__builtin_cpu_supports("fma"), "FMA"},
            {__builtin_cpu_supports("avx512f"), "AVX-512F"},  {__builtin_cpu_supports("avx512cd"), "AVX-512CD"},
            {__builtin_cpu_supports("avx512dq"), "AVX-512DQ"}, {__builtin_cpu_supports("avx512bw"), "AVX-512BW"},
            {__builtin_cpu_supports("avx512vl"), "AVX-512VL"},
        };
        for (const auto& [supported, name] : probe)
            if (supported) cpu.vectorExtensions.push_back(name);
    }
#endif
    return cpu;
}

std::string FormatCpu(const CpuDescription& cpu) {
    std::string line = cpu.model;
    if (cpu.family >= 0 && cpu.modelNumber >= 0) line += fmt::format(" (family {} model {})", cpu.family, cpu.modelNumber);
    line += fmt::format(", {} CPU{}", cpu.cores, cpu.cores == 1 ? "" : "s");  // logical CPUs, as lscpu counts
    line += ", vector: ";
    if (cpu.vectorExtensions.empty()) line += "none of SSE4.2/AVX/AVX2/AVX-512";
    for (size_t i = 0; i < cpu.vectorExtensions.size(); ++i) {
        if (i) line += ' ';
        line += cpu.vectorExtensions[i];
    }
    return line;
}

}  // namespace fovrt
