#include "app/vdp_inputs.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <utility>

#include "core/error.h"
#include "gaze/csv_fields.h"
#include "io/exr.h"
#include "io/png.h"

namespace fovrt {

namespace {

namespace fs = std::filesystem;

bool IsPng(const fs::path& p) { return csv::Lower(p.extension().string()) == ".png"; }
bool IsFrameFile(const fs::path& p) { return IsPng(p) || csv::Lower(p.extension().string()) == ".exr"; }

struct BadPixels {
    size_t nonFinite = 0, tooLarge = 0, negative = 0;
};

BadPixels CountBadPixels(const Plane<vec3>& frame) {
    BadPixels bad;
    for (const vec3& c : frame.vector()) {
        if (!std::isfinite(c.r) || !std::isfinite(c.g) || !std::isfinite(c.b)) ++bad.nonFinite;
        else if (std::max({c.r, c.g, c.b}) > kMaxVdpPixelValue) ++bad.tooLarge;
        else if (std::min({c.r, c.g, c.b}) < 0.0f) ++bad.negative;
    }
    return bad;
}

}  // namespace

VdpSequence ListVdpSequence(const std::string& where, const std::string& role) {
    const fs::path path(where);
    VdpSequence s;
    s.where = where;
    s.role = role;
    if (!fs::exists(path)) Fail("{}: no such file or folder", where);
    if (!fs::is_directory(path)) {
        if (!IsFrameFile(path)) Fail("{}: not an .exr or .png file", where);
        s.files = {path};
    } else {
        for (const auto& entry : fs::directory_iterator(path))
            if (entry.is_regular_file() && IsFrameFile(entry.path())) s.files.push_back(entry.path());
        std::sort(s.files.begin(), s.files.end());
        if (s.files.empty()) Fail("{}: no .exr or .png frames in the folder", where);
    }
    s.png = IsPng(s.files[0]);
    // `--eotf auto` reads a sequence by its file type, so a sequence has one.
    for (const fs::path& f : s.files)
        if (IsPng(f) != s.png)
            Fail("{}: mixes .exr and .png frames ({} and {}); a sequence is one file type", where,
                 s.files[0].filename().string(), f.filename().string());
    return s;
}

VdpEotf SequenceEotf(const VdpSequence& sequence, std::optional<VdpEotf> eotf) {
    return eotf.value_or(sequence.png ? VdpEotf::Srgb : VdpEotf::Linear);
}

Plane<vec3> ReadVdpFrame(const VdpSequence& s, size_t index, const std::string& layer, bool clampNegative,
                         size_t& clamped) {
    const fs::path& file = s.files[index];
    Plane<vec3> frame = s.png ? ReadPngRgb(file) : ReadRgbExr(file, layer);
    const BadPixels bad = CountBadPixels(frame);
    if (bad.nonFinite > 0)
        Fail("{}: {} frame {}: {} pixel(s) are NaN or ±Inf (a broken render; only finite values are scored)",
             file.string(), s.role, index, bad.nonFinite);
    if (bad.tooLarge > 0)
        Fail("{}: {} frame {}: {} pixel(s) are above {:g} (broken values, not a radiance)", file.string(), s.role,
             index, bad.tooLarge, kMaxVdpPixelValue);
    if (bad.negative > 0 && !clampNegative)
        Fail("{}: {} frame {}: {} pixel(s) are negative (--clamp-negative sets them to 0)", file.string(), s.role,
             index, bad.negative);
    if (bad.negative > 0) {
        for (vec3& c : frame.vector()) c = glm::max(c, vec3(0.0f));
        clamped += bad.negative;
    }
    return frame;
}

VdpLuminanceReader::VdpLuminanceReader(const VdpSequence& sequence, const VdpPhotometry& photometry,
                                       std::string layer, bool clampNegative)
    : sequence_(sequence), photometry_(photometry), layer_(std::move(layer)), clampNegative_(clampNegative) {}

void VdpLuminanceReader::Read(size_t index, Plane<float>& out) {
    if (!sequence_.png) {
        out = VdpLuminance(ReadVdpFrame(sequence_, index, layer_, clampNegative_, clamped_), photometry_);
        return;
    }
    // A PNG's codes are finite values in [0, 1]: nothing for ReadVdpFrame's checks to find.
    const PngPixels p = ReadPngPixels(sequence_.files[index]);
    std::optional<VdpCodeLuminance>& table = p.bits == 16 ? codes16_ : codes8_;
    if (!table) table.emplace(photometry_, p.bits);
    if (p.bits == 16) table->Image(p.words(), p.width, p.height, p.channels, out);
    else table->Image(p.bytes(), p.width, p.height, p.channels, out);
}

std::vector<VdpFixation> ReadVdpGaze(const std::string& path, int frames, int width, int height) {
    if (fs::is_directory(path)) Fail("{}: is a folder, not a gaze file (CSV)", path);
    std::ifstream in(path);
    if (!in) Fail("{}: cannot open gaze file", path);
    std::vector<VdpFixation> fix(static_cast<size_t>(frames));
    std::vector<int> lineOf(static_cast<size_t>(frames), 0);  // the line that gave each frame's fixation
    int columnFrame = -1, columnX = -1, columnY = -1;
    size_t columns = 0;
    std::string line;
    for (int n = 1; std::getline(in, line); ++n) {
        const std::string_view view = csv::Trim(line);
        if (view.empty() || view.front() == '#') continue;
        const std::vector<std::string_view> fields = csv::Split(view);
        if (columns == 0) {
            for (size_t i = 0; i < fields.size(); ++i) {
                const std::string name = csv::Lower(fields[i]);
                int* column = name == "frame" ? &columnFrame : name == "x" ? &columnX : name == "y" ? &columnY : nullptr;
                if (column != nullptr && *column >= 0) Fail("{}:{}: the header names column '{}' twice", path, n, name);
                if (column != nullptr) *column = int(i);
            }
            if (columnFrame < 0 || columnX < 0 || columnY < 0)
                Fail("{}:{}: the header must name the columns frame, x and y (pixels); got '{}'", path, n,
                     std::string(view.substr(0, 80)));
            columns = fields.size();
            continue;
        }
        if (fields.size() != columns)
            Fail("{}:{}: {} fields where the header has {}", path, n, fields.size(), columns);
        const std::string_view frameField = fields[size_t(columnFrame)];
        int frame = -1;
        const auto [end, ec] = std::from_chars(frameField.data(), frameField.data() + frameField.size(), frame);
        if (ec != std::errc() || end != frameField.data() + frameField.size())
            Fail("{}:{}: frame '{}' is not a whole number", path, n, std::string(frameField.substr(0, 40)));
        if (frame < 0 || frame >= frames) Fail("{}:{}: frame {} outside 0..{}", path, n, frame, frames - 1);
        if (lineOf[size_t(frame)] != 0)
            Fail("{}:{}: frame {} already has a fixation (line {})", path, n, frame, lineOf[size_t(frame)]);
        double xy[2];
        for (int axis = 0; axis < 2; ++axis) {
            const std::string_view field = fields[size_t(axis == 0 ? columnX : columnY)];
            const double extent = axis == 0 ? width : height;
            if (!csv::ParseDouble(field, xy[axis]) || !std::isfinite(xy[axis]))
                Fail("{}:{}: {} '{}' is not a finite number", path, n, axis == 0 ? "x" : "y",
                     std::string(field.substr(0, 40)));
            if (xy[axis] < 0.0 || xy[axis] > extent)
                Fail("{}:{}: {} = {} is outside the image (0..{} pixels)", path, n, axis == 0 ? "x" : "y", xy[axis],
                     extent);
        }
        fix[size_t(frame)] = {float(xy[0]), float(xy[1])};
        lineOf[size_t(frame)] = n;
    }
    if (columns == 0) Fail("{}: empty gaze file (no header naming frame, x, y)", path);
    for (int f = 0; f < frames; ++f)
        if (lineOf[size_t(f)] == 0) Fail("{}: no fixation for frame {}", path, f);
    return fix;
}

}  // namespace fovrt
