// The inputs of `fovrt vdp` (src/app/cmd_vdp.cpp) read from files that need not come from fovrt:
// frame sequences (folders of EXR or PNG frames, or single images) and a gaze CSV. Each is checked
// as it is read, so a broken input is one line naming the file (and frame or line), never a score.
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/image.h"
#include "metrics/fovvideovdp.h"

namespace fovrt {

// A pixel channel above this is a broken value, not a radiance or a luminance: its square
// overflows 32-bit float (the bound material colours have, kMaxMaterialColour in scene/loaders.h).
inline constexpr float kMaxVdpPixelValue = 1e9f;

// One sequence: a file, or every .exr/.png in a folder sorted by name; all of one file type, which
// decides how `--eotf auto` reads it.
struct VdpSequence {
    std::string where;  // as given on the command line
    std::string role;   // "test" or "reference", for messages
    std::vector<std::filesystem::path> files;
    bool png = false;  // every frame a .png (else every frame an .exr)
};
VdpSequence ListVdpSequence(const std::string& where, const std::string& role);

// How the sequence's values become luminance: `eotf` when given, else by its file type (PNG
// sRGB-encoded, EXR linear).
VdpEotf SequenceEotf(const VdpSequence& sequence, std::optional<VdpEotf> eotf);

// Frame `index` of `sequence` (RGB; EXRs from `layer`). Refused, naming the file, the frame and
// the number of pixels: NaN or ±Inf, a channel above kMaxVdpPixelValue, and a negative channel
// unless `clampNegative`, which sets it to 0 and adds the pixel to `clamped`.
Plane<vec3> ReadVdpFrame(const VdpSequence& sequence, size_t index, const std::string& layer, bool clampNegative,
                         size_t& clamped);

// A sequence's frames as luminance in cd/m²: VdpLuminance of ReadVdpFrame's values, bit for bit.
// PNG codes go through VdpCodeLuminance's tables (made once per bit depth the sequence uses),
// never through RGB floats: decoding and the EOTF were half of `fovrt vdp`'s time.
class VdpLuminanceReader {
public:
    VdpLuminanceReader(const VdpSequence& sequence, const VdpPhotometry& photometry, std::string layer,
                       bool clampNegative);
    // Frame `index` into `out`, reusing its memory when it has the frame's size (PNG frames).
    void Read(size_t index, Plane<float>& out);
    size_t clamped() const { return clamped_; }  // negative pixels set to 0 so far

private:
    const VdpSequence& sequence_;
    VdpPhotometry photometry_;
    std::string layer_;
    bool clampNegative_;
    size_t clamped_ = 0;
    std::optional<VdpCodeLuminance> codes8_, codes16_;
};

// A gaze CSV read by its header's column names, as gaze traces are (gaze/sources.cpp): a header
// naming `frame`, `x` and `y` (any order, any case; other named columns are ignored), then rows
// with the header's field count ('#' comments and blank lines skipped). `frame` a whole number in
// 0..frames-1, each exactly once; x, y finite pixels inside the width × height image (x right,
// y down, [0, width] × [0, height]). Anything else is one error naming path:line.
std::vector<VdpFixation> ReadVdpGaze(const std::string& path, int frames, int width, int height);

}  // namespace fovrt
