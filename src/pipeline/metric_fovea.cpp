#include "pipeline/metric_fovea.h"

namespace fovrt {

FoveaRadius MetricFovea(const FoveationParams& f, int imageWidth) {
    if (f.model == "disc") {
        if (f.radiusDeg > 0.0f) return FoveaRadius::Degrees(f.radiusDeg);
        return FoveaRadius::Pixels(f.radiusPx * float(imageWidth) / float(f.radiusReferenceWidth));
    }
    if (f.model == "linear") return FoveaRadius::Degrees(f.fovealDeg);
    return FoveaRadius::Degrees(5.0f);  // the first eccentricity band
}

}  // namespace fovrt
