// `fovrt vdp TEST REFERENCE`: FovVideoVDP 1.2 (src/metrics/fovvideovdp.h) between two frame
// sequences that need not come from fovrt: folders of EXR or PNG frames (sorted by file name) or
// single images, each sequence read by its own file type (src/app/vdp_inputs.h). Prints JOD with
// the sustained/transient breakdown; foveated along a gaze file (a CSV with frame, x, y columns, in
// pixels) when given; optionally writes per-frame difference maps and a JSON. Every option is
// checked before a frame is read and the outputs' places before the metric runs: a bad value is
// one line naming the option, never a score on a fallback.
#include <array>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <unistd.h>
#include <utility>
#include <variant>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "app/vdp_inputs.h"
#include "commands.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/setting_table.h"
#include "io/exr.h"
#include "metrics/fovvideovdp.h"

namespace fovrt {

namespace {

namespace fs = std::filesystem;

struct VdpCommandOptions {
    std::string test, reference;
    double fps = 30.0;
    std::string display = "headset-25";
    std::optional<double> ppd;    // unset: the profile's geometry
    std::optional<double> fov;    // unset: the profile's geometry
    std::optional<double> peak;   // unset: the profile's
    std::optional<double> black;  // unset: the profile's
    std::string eotf = "auto";
    std::string layer;  // EXR layer holding R, G, B ("" = top-level channels)
    std::string gaze;
    bool foveated = false;
    bool clampNegative = false;
    std::string diffMaps;
    std::string json;
};

// Pixels per degree at the image centre, given (--ppd) or implied by --fov and the frames' width.
// Below 1 a pixel spans more than a degree; the metric's finest band is half of it in cycles/degree.
constexpr ParamRange kPixelsPerDegree = Closed(1, 1000);

// The number options, one row each: spelling (.key), the values allowed, the help line and the
// member it sets. Registration (help), the range check and docs/perceptual-metric.md's table
// follow these rows.
struct VdpNumberOption {
    ParamInfo info;
    std::variant<double VdpCommandOptions::*, std::optional<double> VdpCommandOptions::*> member;
};

constexpr std::array<VdpNumberOption, 5> kNumberOptions{{
    {{.key = "--fps", .range = Closed(1, 1000),
      .doc = "Frame rate of the sequences (the temporal filters span 250 ms: 250 taps at 1000 fps)"},
     &VdpCommandOptions::fps},
    {{.key = "--ppd", .range = kPixelsPerDegree,
      .doc = "Pixels per degree at the image centre (overrides the profile; not with --fov)"},
     &VdpCommandOptions::ppd},
    {{.key = "--fov", .range = OpenMin(0, 160),
      .doc = "Horizontal field of view of the frames in degrees, a flat image (overrides the profile; not with "
             "--ppd; the pixels per degree it implies must lie in --ppd's range)"},
     &VdpCommandOptions::fov},
    {{.key = "--peak", .range = Closed(1, 10000),
      .doc = "Peak luminance in cd/m² (overrides the profile; the metric's sensitivity model spans 0.001 to "
             "10000 cd/m²)"},
     &VdpCommandOptions::peak},
    {{.key = "--black", .range = Closed(0, 1000), .doc = "Black level in cd/m², below the peak (overrides the profile)"},
     &VdpCommandOptions::black},
}};
static_assert(RowsWellFormed(kNumberOptions), "a vdp option row is malformed (see ParamRowProblem)");

// Every number option in its row's range, geometry from one option: before any file is read.
void CheckNumberOptions(const VdpCommandOptions& o) {
    for (const VdpNumberOption& row : kNumberOptions)
        std::visit(
            [&](auto member) {
                const auto& value = o.*member;
                std::optional<std::string> problem;
                if constexpr (std::is_same_v<std::decay_t<decltype(value)>, double>)
                    problem = SettingValueProblem(row.info, value);
                else if (value)
                    problem = SettingValueProblem(row.info, *value);
                if (problem) FailSettingProblem(row.info, *problem);
            },
            row.member);
    if (o.ppd && o.fov) Fail("--ppd and --fov both set the size of a pixel: give one of them");
}

std::optional<VdpEotf> ParseEotf(const std::string& name) {
    if (name == "auto") return std::nullopt;  // by each sequence's file type
    if (name == "srgb") return VdpEotf::Srgb;
    if (name == "linear") return VdpEotf::Linear;
    if (name == "absolute") return VdpEotf::Absolute;
    Fail("--eotf: '{}' is not one of auto, srgb, linear, absolute", name);
}

const char* EotfName(VdpEotf e) {
    return e == VdpEotf::Srgb ? "srgb" : e == VdpEotf::Linear ? "linear" : "absolute";
}

// The profile's photometry with --peak and --black applied; black below peak.
VdpPhotometry Photometry(const VdpCommandOptions& o, const VdpPhotometry& profile) {
    VdpPhotometry p = profile;
    if (o.peak) p.peak = *o.peak;
    if (o.black) p.black = *o.black;
    if (p.black >= p.peak)
        Fail("{}: black {} cd/m² is not below the peak {} cd/m²", o.black ? "--black" : "--peak", p.black, p.peak);
    return p;
}

// `path` (a file, or a folder when `folder`) can be created: it is not the other kind, and its
// nearest existing ancestor is a folder this process may write in. Checked before the metric runs,
// which writes the outputs only at its end.
void CheckWritable(const std::string& option, const std::string& where, bool folder) {
    std::error_code ec;
    const fs::path path = fs::absolute(where, ec);
    if (fs::exists(path, ec) && fs::is_directory(path, ec) != folder)
        Fail("{}: {} is {}", option, where, folder ? "a file, not a folder" : "a folder, not a file");
    fs::path existing = folder ? path : path.parent_path();
    while (!fs::exists(existing, ec) && existing.has_parent_path() && existing != existing.parent_path())
        existing = existing.parent_path();
    if (!fs::is_directory(existing, ec))
        Fail("{}: cannot write {}: {} is not a folder", option, where, existing.string());
    if (::access(existing.c_str(), W_OK | X_OK) != 0)
        Fail("{}: cannot write {}: {}: {}", option, where, existing.string(), std::strerror(errno));
}

void RunVdp(const VdpCommandOptions& o) {
    CheckNumberOptions(o);
    const std::optional<VdpEotf> eotf = ParseEotf(o.eotf);
    VdpDisplay display = FindVdpDisplay(o.display);
    const VdpPhotometry photometry = Photometry(o, display.photometry);
    if (!o.json.empty()) CheckWritable("--json", o.json, false);
    if (!o.diffMaps.empty()) CheckWritable("--diff-maps", o.diffMaps, true);

    const VdpSequence testSeq = ListVdpSequence(o.test, "test"), refSeq = ListVdpSequence(o.reference, "reference");
    if (testSeq.files.size() != refSeq.files.size())
        Fail("{} has {} frames but {} has {}", o.test, testSeq.files.size(), o.reference, refSeq.files.size());
    const int frames = int(testSeq.files.size());
    VdpPhotometry testPhotometry = photometry, refPhotometry = photometry;
    testPhotometry.eotf = SequenceEotf(testSeq, eotf);
    refPhotometry.eotf = SequenceEotf(refSeq, eotf);

    // Frames are read as the metric asks for them (a chunk at a time): a sequence is never held
    // whole. The first pair is read now, for the size that geometry and gaze depend on.
    VdpLuminanceReader testReader(testSeq, testPhotometry, o.layer, o.clampNegative),
        refReader(refSeq, refPhotometry, o.layer, o.clampNegative);
    Plane<float> firstTest, firstRef;
    testReader.Read(0, firstTest);
    refReader.Read(0, firstRef);
    const int width = firstRef.width(), height = firstRef.height();
    auto readPair = [&](int f, Plane<float>& t, Plane<float>& r) {
        if (f == 0) t = std::move(firstTest), r = std::move(firstRef);
        else testReader.Read(size_t(f), t), refReader.Read(size_t(f), r);
        if (t.width() != width || t.height() != height || r.width() != width || r.height() != height)
            Fail("{} ({}x{}) and {} ({}x{}): frames must all be {}x{}", testSeq.files[size_t(f)].string(), t.width(),
                 t.height(), refSeq.files[size_t(f)].string(), r.width(), r.height(), width, height);
    };
    if (o.ppd) display.geometry = VdpGeometry::FromPixelsPerDegree(*o.ppd);
    if (o.fov) {
        display.geometry = VdpGeometry::FromHorizontalFov(width, *o.fov);
        if (!kPixelsPerDegree.Contains(display.geometry.PixelsPerDegree()))
            Fail("--fov: {:g} degrees over {} pixels is {:.4g} pixels/degree at the centre, outside {} (--ppd's range)",
                 *o.fov, width, display.geometry.PixelsPerDegree(), kPixelsPerDegree.Describe());
    }

    VdpOptions options;
    options.foveated = o.foveated || !o.gaze.empty();
    if (!o.gaze.empty()) options.fixations = ReadVdpGaze(o.gaze, frames, width, height);
    options.diffMaps = !o.diffMaps.empty();
    const FovVideoVdp vdp(display.geometry);
    const VdpResult r = vdp.ScoreSequence(frames, readPair, o.fps, options);
    const size_t clampedTest = testReader.clamped(), clampedRef = refReader.clamped();

    const std::string mode = !o.gaze.empty() ? "foveated along " + o.gaze : options.foveated ? "foveated at the centre" : "not foveated";
    const std::string eotfs = testPhotometry.eotf == refPhotometry.eotf
                                  ? EotfName(testPhotometry.eotf)
                                  : fmt::format("test {}, reference {}", EotfName(testPhotometry.eotf),
                                                EotfName(refPhotometry.eotf));
    std::printf("FovVideoVDP 1.2: %.4f JOD (sustained alone %.4f, transient alone %.4f)\n", r.jod, r.jodSustained,
                r.jodTransient);
    std::printf("  %d frame(s) %dx%d%s, %.2f pixels/degree, %g-%g cd/m² (%s), %s\n", frames, width, height,
                frames > 1 ? fmt::format(" at {:g} fps", o.fps).c_str() : "", display.geometry.PixelsPerDegree(),
                photometry.black, photometry.peak, eotfs.c_str(), mode.c_str());
    if (o.clampNegative)
        std::printf("  negative pixels set to 0: %zu in the test, %zu in the reference\n", clampedTest, clampedRef);

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
                            {"peak", photometry.peak},
                            {"black", photometry.black},
                            {"eotf_test", EotfName(testPhotometry.eotf)},
                            {"eotf_reference", EotfName(refPhotometry.eotf)},
                            {"negative_pixels_clamped", {{"test", clampedTest}, {"reference", clampedRef}}},
                            {"foveated", options.foveated},
                            {"band_frequencies", r.bandFrequencies}};
        WriteTextAtomically(o.json, j.dump(2) + "\n");
    }
}

// The help line of a number option: its doc, range and default (when it has one).
template <class Value>
std::string NumberOptionHelp(const ParamInfo& info, const Value& initial) {
    if constexpr (std::is_same_v<Value, double>)
        return fmt::format("{}; {}, default {:g}", info.doc, info.range.Describe(), initial);
    else
        return fmt::format("{}; {}", info.doc, info.range.Describe());
}

}  // namespace

void RegisterVdpCommand(CLI::App& app) {
    auto o = std::make_shared<VdpCommandOptions>();
    CLI::App* cmd = app.add_subcommand("vdp", "FovVideoVDP 1.2 (JOD) between two frame sequences (EXR/PNG)");
    cmd->add_option("test", o->test, "Test frames: a folder of .exr/.png (sorted by name, one type) or one file")
        ->required();
    cmd->add_option("reference", o->reference, "Reference frames, as many as the test's")->required();
    std::string profiles;
    for (const VdpDisplay& d : VdpDisplayProfiles()) profiles += (profiles.empty() ? "" : ", ") + d.name;
    cmd->add_option("--display", o->display, "Display profile: " + profiles);
    for (const VdpNumberOption& row : kNumberOptions)
        std::visit(
            [&](auto member) {
                cmd->add_option_function<double>(
                    row.info.key, [o, member](const double& value) { (*o).*member = value; },
                    NumberOptionHelp(row.info, (*o).*member));
            },
            row.member);
    cmd->add_option("--eotf", o->eotf,
                    "auto (each sequence by its type: PNG srgb, EXR linear), srgb, linear (1 = peak) or absolute (cd/m²)");
    cmd->add_option("--layer", o->layer, "EXR layer with the R, G, B channels");
    cmd->add_flag("--clamp-negative", o->clampNegative, "Set negative pixel values to 0 (counted) instead of refusing");
    cmd->add_option("--gaze", o->gaze, "CSV with a header naming frame, x, y (fixations in pixels): foveated scoring");
    cmd->add_flag("--foveated", o->foveated, "Foveated at the image centre when no gaze file is given");
    cmd->add_option("--diff-maps", o->diffMaps, "Folder for per-frame difference maps (EXR)");
    cmd->add_option("--json", o->json, "Write the result as JSON");
    cmd->callback([o] { RunVdp(*o); });
}

}  // namespace fovrt
