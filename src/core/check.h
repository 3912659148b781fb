// Invariant checks that print the values involved. These guard programming errors (a broken
// invariant), not user input: user input errors go through fovrt::Fail with a readable message.
#pragma once

#include <cstdlib>

#include <fmt/format.h>

namespace fovrt::detail {
[[noreturn]] void CheckFailed(const char* file, int line, const std::string& message);
}  // namespace fovrt::detail

#define FOVRT_CHECK(cond)                                                                   \
    do {                                                                                    \
        if (!(cond)) ::fovrt::detail::CheckFailed(__FILE__, __LINE__, "CHECK(" #cond ")"); \
    } while (0)

// CHECK with a binary comparison that prints both operands, e.g. FOVRT_CHECK_OP(a, <, b).
#define FOVRT_CHECK_OP(a, op, b)                                                            \
    do {                                                                                    \
        const auto& check_a_ = (a);                                                         \
        const auto& check_b_ = (b);                                                         \
        if (!(check_a_ op check_b_))                                                        \
            ::fovrt::detail::CheckFailed(                                                   \
                __FILE__, __LINE__,                                                         \
                fmt::format("CHECK({} {} {}) with {} = {}, {} = {}", #a, #op, #b, #a,       \
                            check_a_, #b, check_b_));                                       \
    } while (0)
