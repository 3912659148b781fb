// The CPU line that benchmark headers print (pipeline/build_info.h): parsed from a /proc/cpuinfo text
// with known answers, and read on this machine.
#include <catch2/catch.hpp>

#include "pipeline/build_info.h"

namespace fovrt {
namespace {

// Two processors' blocks as Linux writes them (abridged); the second must not be read.
constexpr const char* kXeon = R"(processor	: 0
vendor_id	: GenuineIntel
cpu family	: 6
model		: 85
model name	: Intel(R) Xeon(R) Gold 6148 CPU @ 2.40GHz
flags		: fpu sse sse2 ssse3 fma sse4_1 sse4_2 avx f16c avx2 avx512f avx512dq avx512cd avx512bw avx512vl

processor	: 1
model name	: Something Else
flags		: fpu sse
)";

TEST_CASE("cpu description: model, family, model number and vector extensions from /proc/cpuinfo", "[app]") {
    const CpuDescription cpu = ParseCpuInfo(kXeon, 2);
    CHECK(cpu.model == "Intel(R) Xeon(R) Gold 6148 CPU @ 2.40GHz");
    CHECK(cpu.family == 6);
    CHECK(cpu.modelNumber == 85);
    CHECK(cpu.cores == 2u);
    CHECK(cpu.vectorExtensions == std::vector<std::string>{"SSE4.2", "AVX", "AVX2", "FMA", "AVX-512F", "AVX-512CD",
                                                           "AVX-512DQ", "AVX-512BW", "AVX-512VL"});
    CHECK(FormatCpu(cpu) == "Intel(R) Xeon(R) Gold 6148 CPU @ 2.40GHz (family 6 model 85), 2 CPUs, vector: SSE4.2 "
                            "AVX AVX2 FMA AVX-512F AVX-512CD AVX-512DQ AVX-512BW AVX-512VL");
}

TEST_CASE("cpu description: a flag is matched whole, and a CPU without the extensions says so", "[app]") {
    // "avx512_vnni" must not count as "avx512f"-family, "sse4_1" not as "sse4_2".
    const CpuDescription cpu = ParseCpuInfo("model name : Old\nflags : sse4_1 avx512_vnni avx2x\n", 1);
    CHECK(cpu.family == -1);
    CHECK(cpu.vectorExtensions.empty());
    CHECK(FormatCpu(cpu) == "Old, 1 CPU, vector: none of SSE4.2/AVX/AVX2/AVX-512");
    CHECK(ParseCpuInfo("", 4).model == "unknown");
}

TEST_CASE("cpu description: this machine", "[app]") {
    const CpuDescription cpu = DescribeCpu();
    CHECK(cpu.cores >= 1u);
    CHECK_FALSE(cpu.model.empty());
#if defined(__x86_64__)
    // x86-64 guarantees SSE2 only, but every machine this project builds for has SSE4.2; the line
    // must then list it, whichever way (/proc/cpuinfo or the compiler's probe) it was found.
    if (__builtin_cpu_supports("sse4.2")) CHECK(cpu.vectorExtensions.front() == "SSE4.2");
#endif
}

}  // namespace
}  // namespace fovrt
