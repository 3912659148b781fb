// `fovrt vdp TEST REFERENCE`: FovVideoVDP 1.2 (src/metrics/fovvideovdp.h) between two frame
// sequences that need not come from fovrt: folders of EXR or PNG frames (sorted by file name) or
// single images. Prints JOD with the sustained/transient breakdown; foveated along a gaze file
// (CSV frame,x,y in pixels) when given; optionally writes per-frame difference maps and a JSON.
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "io/exr.h"
#include "io/png.h"
#include "metrics/fovvideovdp.h"

namespace fovrt {

namespace {

namespace fs = std::filesystem;

struct VdpCommandOptions {
    std::string test, reference;
    double fps = 30.0;
    std::string display = "headset-25";
    double ppd = 0.0;     // overrides the profile's geometry when > 0
    double fov = 0.0;     // horizontal FOV of the frames (degrees), overrides when > 0
    double peak = 0.0;    // cd/m², overrides when > 0
    double black = -1.0;  // cd/m², overrides when ≥ 0
    std::string eotf = "auto";
    std::string layer;  // EXR layer holding R, G, B ("" = top-level channels)
    std::string gaze;
    bool foveated = false;
    std::string diffMaps;
    std::string json;
};

std::string Lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return s;
}

bool IsFrameFile(const fs::path& p) {
    const std::string ext = Lower(p.extension().string());
    return ext == ".exr" || ext == ".png";
}

// The frames of a sequence: one file, or every .exr/.png in a folder sorted by name.
std::vector<fs::path> ListFrames(const std::string& where) {
    const fs::path path(where);
    if (!fs::exists(path)) Fail("{}: no such file or folder", where);
    if (!fs::is_directory(path)) {
        if (!IsFrameFile(path)) Fail("{}: not an .exr or .png file", where);
        return {path};
    }
    std::vector<fs::path> frames;
    for (const auto& entry : fs::directory_iterator(path))
        if (entry.is_regular_file() && IsFrameFile(entry.path())) frames.push_back(entry.path());
    std::sort(frames.begin(), frames.end());
    if (frames.empty()) Fail("{}: no .exr or .png frames in the folder", where);
    return frames;
}

Plane<vec3> ReadFrame(const fs::path& path, const std::string& layer) {
    return Lower(path.extension().string()) == ".png" ? ReadPngRgb(path) : ReadRgbExr(path, layer);
}

VdpEotf ParseEotf(const std::string& name, const fs::path& firstFrame) {
    if (name == "srgb") return VdpEotf::Srgb;
    if (name == "linear") return VdpEotf::Linear;
    if (name == "absolute") return VdpEotf::Absolute;
    if (name == "auto") return Lower(firstFrame.extension().string()) == ".png" ? VdpEotf::Srgb : VdpEotf::Linear;
    Fail("--eotf: '{}' is not one of auto, srgb, linear, absolute", name);
}

const char* EotfName(VdpEotf e) {
    return e == VdpEotf::Srgb ? "srgb" : e == VdpEotf::Linear ? "linear" : "absolute";
}

// Gaze CSV: lines "frame,x,y" (pixels; an optional header line; '#' comments); every frame needs
// a fixation.
std::vector<VdpFixation> ReadGaze(const std::string& path, int frames) {
    std::ifstream in(path);
    if (!in) Fail("{}: cannot open gaze file", path);
    std::vector<VdpFixation> fix(static_cast<size_t>(frames));
    std::vector<bool> seen(size_t(frames), false);
    std::string line;
    for (int n = 1; std::getline(in, line); ++n) {
        if (line.empty() || line[0] == '#') continue;
        std::replace(line.begin(), line.end(), ',', ' ');
        std::istringstream fields(line);
        long frame;
        float x, y;
        if (!(fields >> frame >> x >> y)) {
            if (n == 1) continue;  // header
            Fail("{}:{}: expected 'frame,x,y'", path, n);
        }
        if (frame < 0 || frame >= frames) Fail("{}:{}: frame {} outside 0..{}", path, n, frame, frames - 1);
        fix[size_t(frame)] = {x, y};
        seen[size_t(frame)] = true;
    }
    for (int f = 0; f < frames; ++f)
        if (!seen[size_t(f)]) Fail("{}: no fixation for frame {}", path, f);
    return fix;
}

void RunVdp(const VdpCommandOptions& o) {
    const std::vector<fs::path> testFiles = ListFrames(o.test), refFiles = ListFrames(o.reference);
    if (testFiles.size() != refFiles.size())
        Fail("{} has {} frames but {} has {}", o.test, testFiles.size(), o.reference, refFiles.size());
    const int frames = int(testFiles.size());
    if (frames > 1 && !(o.fps > 0)) Fail("--fps: {} frames need a frame rate > 0", frames);

    VdpDisplay display = FindVdpDisplay(o.display);
    display.photometry.eotf = ParseEotf(o.eotf, refFiles[0]);
    if (o.peak > 0) display.photometry.peak = o.peak;
    if (o.black >= 0) display.photometry.black = o.black;
    if (display.photometry.black >= display.photometry.peak)
        Fail("--black: {} cd/m² is not below the peak {} cd/m²", display.photometry.black, display.photometry.peak);

    std::vector<Plane<float>> test, reference;
    for (int f = 0; f < frames; ++f) {
        const Plane<vec3> t = ReadFrame(testFiles[size_t(f)], o.layer), r = ReadFrame(refFiles[size_t(f)], o.layer);
        const int w0 = f == 0 ? r.width() : reference[0].width(), h0 = f == 0 ? r.height() : reference[0].height();
        if (t.width() != w0 || t.height() != h0 || r.width() != w0 || r.height() != h0)
            Fail("{} ({}x{}) and {} ({}x{}): frames must all be {}x{}", testFiles[size_t(f)].string(), t.width(),
                 t.height(), refFiles[size_t(f)].string(), r.width(), r.height(), w0, h0);
        test.push_back(VdpLuminance(t, display.photometry));
        reference.push_back(VdpLuminance(r, display.photometry));
    }
    const int width = reference[0].width(), height = reference[0].height();
    if (o.ppd > 0) display.geometry = VdpGeometry::FromPixelsPerDegree(o.ppd);
    if (o.fov > 0) display.geometry = VdpGeometry::FromHorizontalFov(width, o.fov);

    VdpOptions options;
    options.foveated = o.foveated || !o.gaze.empty();
    if (!o.gaze.empty()) options.fixations = ReadGaze(o.gaze, frames);
    options.diffMaps = !o.diffMaps.empty();
    const FovVideoVdp vdp(display.geometry);
    const VdpResult r = vdp.Score(test, reference, o.fps, options);

    const std::string mode = !o.gaze.empty() ? "foveated along " + o.gaze : options.foveated ? "foveated at the centre" : "not foveated";
    std::printf("FovVideoVDP 1.2: %.4f JOD (sustained alone %.4f, transient alone %.4f)\n", r.jod, r.jodSustained,
                r.jodTransient);
    std::printf("  %d frame(s) %dx%d%s, %.2f pixels/degree, %g-%g cd/m² (%s), %s\n", frames, width, height,
                frames > 1 ? fmt::format(" at {:g} fps", o.fps).c_str() : "", display.geometry.PixelsPerDegree(),
                display.photometry.black, display.photometry.peak, EotfName(display.photometry.eotf), mode.c_str());

    if (!o.diffMaps.empty()) {
        fs::create_directories(o.diffMaps);
        for (int f = 0; f < frames; ++f)
            WriteExrLayers(fs::path(o.diffMaps) / fmt::format("vdp_diff_{:04d}.exr", f), width, height,
                           {ExrLayer::FromPlane("jod_loss", r.diffMaps[size_t(f)])});
        std::printf("  difference maps: %s/vdp_diff_NNNN.exr (layer jod_loss)\n", o.diffMaps.c_str());
    }
    if (!o.json.empty()) {
        nlohmann::json j = {{"metric", "FovVideoVDP 1.2"},
                            {"jod", r.jod},
                            {"jod_sustained", r.jodSustained},
                            {"jod_transient", r.jodTransient},
                            {"frames", frames},
                            {"width", width},
                            {"height", height},
                            {"fps", o.fps},
                            {"pixels_per_degree", display.geometry.PixelsPerDegree()},
                            {"peak", display.photometry.peak},
                            {"black", display.photometry.black},
                            {"eotf", EotfName(display.photometry.eotf)},
                            {"foveated", options.foveated},
                            {"band_frequencies", r.bandFrequencies}};
        WriteTextAtomically(o.json, j.dump(2) + "\n");
    }
}

}  // namespace

void RegisterVdpCommand(CLI::App& app) {
    auto o = std::make_shared<VdpCommandOptions>();
    CLI::App* cmd = app.add_subcommand("vdp", "FovVideoVDP 1.2 (JOD) between two frame sequences (EXR/PNG)");
    cmd->add_option("test", o->test, "Test frames: a folder of .exr/.png (sorted by name) or one file")->required();
    cmd->add_option("reference", o->reference, "Reference frames, as many as the test's")->required();
    cmd->add_option("--fps", o->fps, "Frame rate of the sequences");
    std::string profiles;
    for (const VdpDisplay& d : VdpDisplayProfiles()) profiles += (profiles.empty() ? "" : ", ") + d.name;
    cmd->add_option("--display", o->display, "Display profile: " + profiles);
    cmd->add_option("--ppd", o->ppd, "Pixels per degree at the image centre (overrides the profile)");
    cmd->add_option("--fov", o->fov, "Horizontal field of view of the frames in degrees (overrides the profile)");
    cmd->add_option("--peak", o->peak, "Peak luminance in cd/m² (overrides the profile)");
    cmd->add_option("--black", o->black, "Black level in cd/m² (overrides the profile)");
    cmd->add_option("--eotf", o->eotf, "auto (PNG srgb, EXR linear), srgb, linear (1 = peak) or absolute (cd/m²)");
    cmd->add_option("--layer", o->layer, "EXR layer with the R, G, B channels");
    cmd->add_option("--gaze", o->gaze, "CSV of frame,x,y fixations in pixels: foveated scoring");
    cmd->add_flag("--foveated", o->foveated, "Foveated at the image centre when no gaze file is given");
    cmd->add_option("--diff-maps", o->diffMaps, "Folder for per-frame difference maps (EXR)");
    cmd->add_option("--json", o->json, "Write the result as JSON");
    cmd->callback([o] { RunVdp(*o); });
}

}  // namespace fovrt
