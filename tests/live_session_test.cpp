// The wiring both live apps share (src/live/live_session.h): `--view` with a name the denoiser
// does not offer is refused with every view it does offer, for the preview and the headset alike
// (both call CheckViewName through LiveSessionWiring); the window device stays a Vulkan device
// when the denoiser runs on the CPU.
#include <catch2/catch.hpp>

#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "live/live_session.h"

using namespace fovrt;

namespace {

std::string ViewError(const std::string& view, const std::vector<std::string>& views, const std::string& denoiser) {
    try {
        CheckViewName(view, views, denoiser);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST_CASE("an unknown --view is refused with the denoiser's views listed", "[live]") {
    const std::vector<std::string> views = {"denoised", "noisy", "spp", "historyLength"};
    CHECK(ViewError("lambda", views, "svgf") ==
          "--view lambda: not a view of denoiser svgf (views: denoised, noisy, spp, historyLength)");
    CHECK(ViewError("noisy", views, "svgf").empty());
    CHECK(ViewError("historyLength", views, "svgf").empty());
}

TEST_CASE("a live session presents on a Vulkan device even when the denoiser runs on the CPU", "[live]") {
    auto withDevice = [](std::string device) {
        RunConfig config;
        config.denoise.device = std::move(device);
        return config;
    };
    CHECK(LiveDisplayDevice(withDevice("cpu")) == "auto");
    CHECK(LiveDisplayDevice(withDevice("1")) == "1");
    CHECK(LiveDisplayDevice(withDevice("vulkan")) == "vulkan");
}
