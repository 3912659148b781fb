// The Vulkan context GPU tests share: created once per test executable, validation layers on, so
// each test can assert that no validation error was reported.
#pragma once

#include <memory>

#include "vk/context.h"

namespace fovrt::test {

inline std::shared_ptr<VulkanContext> TestContext() {
    static std::shared_ptr<VulkanContext> ctx = [] {
        VulkanContextOptions o;
        o.validation = Validation::On;
        return std::make_shared<VulkanContext>(VulkanContext::Create(o));
    }();
    return ctx;
}

}  // namespace fovrt::test
