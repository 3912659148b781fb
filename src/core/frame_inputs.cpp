#include "frame_inputs.h"

namespace fovrt {

void FrameInputs::Allocate(int width, int height) {
    FOVRT_FRAME_INPUT_PLANES(FOVRT_PLANE_RESIZE)
    gradientSamples.clear();
}

const char* DemodulationName(Demodulation d) { return d == Demodulation::Brdf ? "brdf" : "albedo"; }

bool ParseDemodulation(std::string_view name, Demodulation& d) {
    if (name == "albedo") d = Demodulation::Albedo;
    else if (name == "brdf") d = Demodulation::Brdf;
    else return false;
    return true;
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
