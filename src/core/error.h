// fovrt::Error: the one exception type that reaches the user as a single line.
// Recoverable failures (missing file, bad config value, no device) throw it with a message that
// names the file/key/line; the app prints "fovrt: error: <what>" and exits non-zero.
#pragma once

#include <stdexcept>
#include <string>

#include <fmt/format.h>

namespace fovrt {

class Error : public std::runtime_error {
public:
    explicit Error(const std::string& message) : std::runtime_error(message) {}
};

// Throws fovrt::Error with a fmt-formatted message.
template <typename... Args>
[[noreturn]] void Fail(fmt::format_string<Args...> format, Args&&... args) {
    throw Error(fmt::format(format, std::forward<Args>(args)...));
}

}  // namespace fovrt
