// Small configurations the app-level tests render (header only: app_ and live_ tests link the app).
#pragma once

#include "config/config.h"

namespace fovrt::test {

// The built-in Cornell box at 32×18 per eye with both spp levels of the disc present (a 6 px
// foveal disc), denoised by the C++ reference: fast, and still foveated.
inline RunConfig SmallCornellConfig() {
    RunConfig config = DefaultConfig();
    config.scene.name = "cornell";
    config.camera.width = 32;
    config.camera.height = 18;
    config.foveation.radiusPx = 80.0f;  // a 6 px foveal disc at 32 px: both spp levels present
    config.foveation.radiusReferenceWidth = 320;
    config.denoise.device = "cpu";
    return config;
}

}  // namespace fovrt::test
