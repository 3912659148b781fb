// Registry of the SPIR-V compiled from shaders/*.comp and embedded at build time.
// Names are the file stems ("svgf_reproject"); "<stem>_fp16" is the variant built with
// FOVRT_FP16 (16-bit history storage).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace fovrt {

namespace detail {
struct ShaderEntry {
    const char* name;
    const uint32_t* words;
    size_t wordCount;
};
}  // namespace detail

// SPIR-V words of the named shader; fovrt::Error listing the known names when absent.
std::span<const uint32_t> ShaderCode(const std::string& name);
// Every embedded shader name (both variants).
std::vector<std::string> ShaderNames();

}  // namespace fovrt
