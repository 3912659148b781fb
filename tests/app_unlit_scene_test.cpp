// A scene with no light renders every image black, which every metric scores as perfect (relMSE
// 0, JOD 10): the frame pipeline (run, reference, experiment, dataset, the live apps) refuses it
// when it loads the scene, naming it, before anything is rendered.
#include <fstream>

#include "app_test_configs.h"
#include "core/error.h"
#include "pipeline/frame_pipeline.h"
#include "test_support.h"

using namespace fovrt;
namespace fs = std::filesystem;

TEST_CASE("the frame pipeline refuses a scene with no emitter, no light and a black background", "[app][scene]") {
    const fs::path dir = test::ScratchDir("fovrt-unlit-scene-test");
    std::ofstream(dir / "quad.obj") << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";
    std::ofstream(dir / "dark.toml") << "name = \"dark\"\n[[mesh]]\nfile = \"quad.obj\"\n";
    RunConfig config = test::SmallCornellConfig();
    config.scene.name = (dir / "dark.toml").string();
    CHECK_THROWS_WITH(FramePipeline(config), Catch::Contains("scene 'dark'") && Catch::Contains("dark.toml") &&
                                                 Catch::Contains("has no light"));
    // The same geometry under a grey sky renders.
    std::ofstream(dir / "dark.toml") << "name = \"dark\"\nbackground = [0.2, 0.2, 0.2]\n"
                                        "[[mesh]]\nfile = \"quad.obj\"\n";
    CHECK_NOTHROW(FramePipeline(config));
}
