#include "shaders/shader_registry.h"

#include <fmt/format.h>

#include "core/error.h"

namespace fovrt {

namespace detail {
extern const ShaderEntry kShaderTable[];
}  // namespace detail

std::span<const uint32_t> ShaderCode(const std::string& name) {
    for (const detail::ShaderEntry* e = detail::kShaderTable; e->name; ++e)
        if (name == e->name) return {e->words, e->wordCount};
    Fail("no embedded shader '{}' (known: {})", name, fmt::join(ShaderNames(), ", "));
}

std::vector<std::string> ShaderNames() {
    std::vector<std::string> names;
    for (const detail::ShaderEntry* e = detail::kShaderTable; e->name; ++e) names.push_back(e->name);
    return names;
}

}  // namespace fovrt
