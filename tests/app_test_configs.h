// Small configurations the app-level tests render (header only: app_ and live_ tests link the app).
#pragma once

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "config/config.h"
#include "config/config_cli.h"

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

// The options of a command given the experiment file dir/exp.toml holding `text`.
inline ConfigOptions ExperimentFileOptions(const std::filesystem::path& dir, const std::string& text) {
    std::filesystem::create_directories(dir);
    ConfigOptions options;
    options.configPath = (dir / "exp.toml").string();
    std::ofstream(options.configPath) << text;
    return options;
}

// The options of an experiment over the Cornell box with SmallCornellConfig's foveation and
// denoiser device, its file, reference cache and output under `dir`, variants svgf and
// two-history; the [experiment] table ends with `experimentLines`.
struct SmallExperiment {
    int width = 32, height = 18, frames = 3, referenceSpp = 4;
    bool report = false;
    std::string experimentLines;
};

inline ConfigOptions SmallExperimentOptions(const std::filesystem::path& dir, const SmallExperiment& e) {
    std::ostringstream text;
    text << "[camera]\nwidth = " << e.width << "\nheight = " << e.height << "\n"
         << "[run]\nframes = " << e.frames << "\n"
         << "[foveation]\nradius_px = 80\nradius_reference_width = 320\n"
         << "[denoise]\ndevice = \"cpu\"\n"
         << "[reference]\nspp = " << e.referenceSpp << "\ncache_dir = \"" << (dir / "cache").string() << "\"\n"
         << "[output]\ndir = \"" << (dir / "out").string() << "\"\nreport = " << (e.report ? "true" : "false")
         << "\n"
         << "[experiment]\nscenes = [\"cornell\"]\nvariants = [\"svgf\", \"two-history\"]\n"
         << e.experimentLines;
    return ExperimentFileOptions(dir, text.str());
}

}  // namespace fovrt::test
