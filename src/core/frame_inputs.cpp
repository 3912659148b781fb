#include "frame_inputs.h"

#include <limits>

namespace fovrt {

void FrameInputs::Allocate(int width, int height) {
    direct.Resize(width, height, vec3(0.0f));
    indirect.Resize(width, height, vec3(0.0f));
    albedo.Resize(width, height, vec3(0.0f));
    emission.Resize(width, height, vec3(0.0f));
    normal.Resize(width, height, vec3(0.0f));
    linearDepth.Resize(width, height, std::numeric_limits<float>::infinity());
    depthGradient.Resize(width, height, vec2(0.0f));
    objectId.Resize(width, height, kNoObject);
    prevPixel.Resize(width, height, vec2(0.0f));
    primitiveId.Resize(width, height, kNoObject);
    barycentrics.Resize(width, height, vec2(0.0f));
    worldPosition.Resize(width, height, vec3(0.0f));
    sampleCount.Resize(width, height, uint16_t(1));
    seed.Resize(width, height, 0u);
    gradientSamples.clear();
}

vec3 FrameInputs::NoisyColor(int x, int y) const {
    return Remodulate(albedo(x, y), direct(x, y), indirect(x, y), emission(x, y));
}

Plane<vec3> FrameInputs::NoisyImage() const {
    Plane<vec3> image(width(), height());
    for (int y = 0; y < height(); ++y)
        for (int x = 0; x < width(); ++x) image(x, y) = NoisyColor(x, y);
    return image;
}

size_t FrameInputs::Bytes() const {
    return direct.bytes() + indirect.bytes() + albedo.bytes() + emission.bytes() + normal.bytes() +
           linearDepth.bytes() + depthGradient.bytes() + objectId.bytes() + prevPixel.bytes() +
           primitiveId.bytes() + barycentrics.bytes() + worldPosition.bytes() +
           sampleCount.bytes() + seed.bytes() + gradientSamples.size() * sizeof(GradientSample);
}

const std::vector<std::string>& FrameInputs::PlaneNames() {
    static const std::vector<std::string> names = {
        "direct",      "indirect",     "albedo",       "emission",      "normal",
        "linearDepth", "depthGradient", "objectId",    "prevPixel",     "primitiveId",
        "barycentrics", "worldPosition", "sampleCount", "seed"};
    return names;
}

}  // namespace fovrt
