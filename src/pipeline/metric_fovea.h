// MetricFovea: the fovea a frame is scored in, read from the foveation settings the frame was
// rendered with. The experiment's fovea region and the live preview's fovea outline both take it,
// so the circle on screen is the region the metrics call the fovea.
#pragma once

#include "foveation/spp_model.h"
#include "metrics/regions.h"

namespace fovrt {

// The disc model's spp disc, the linear model's full-rate angle, else the first eccentricity
// band (5°).
FoveaRadius MetricFovea(const FoveationParams& foveation, int imageWidth);

}  // namespace fovrt
