#include "frame_inputs.h"

#include <array>

namespace fovrt {

void FrameInputs::Allocate(int width, int height) {
    FOVRT_FRAME_INPUT_PLANES(FOVRT_PLANE_RESIZE)
    gradientSamples.clear();
}

namespace {
// Indexed by Demodulation: the names render.demodulation takes.
constexpr std::array<const char*, 2> kDemodulationNames = {"albedo", "brdf"};
}  // namespace

NameList DemodulationNames() { return kDemodulationNames; }

const char* DemodulationName(Demodulation d) { return kDemodulationNames[size_t(d)]; }

bool ParseDemodulation(std::string_view name, Demodulation& d) {
    for (size_t i = 0; i < kDemodulationNames.size(); ++i)
        if (name == kDemodulationNames[i]) {
            d = Demodulation(i);
            return true;
        }
    return false;
}

vec3 FrameInputs::NoisyColor(int x, int y) const {
    return Remodulate(Modulation()(x, y), direct(x, y), indirect(x, y), emission(x, y));
}

Plane<vec3> FrameInputs::NoisyImage() const {
    Plane<vec3> image(width(), height());
    for (int y = 0; y < height(); ++y)
        for (int x = 0; x < width(); ++x) image(x, y) = NoisyColor(x, y);
    return image;
}

size_t FrameInputs::Bytes() const {
    return TotalPlaneBytes(*this) + gradientSamples.size() * sizeof(GradientSample);
}

const std::vector<std::string>& FrameInputs::PlaneNames() {
    static const std::vector<std::string> names = {FOVRT_FRAME_INPUT_PLANES(FOVRT_PLANE_NAME)};
    return names;
}

}  // namespace fovrt
