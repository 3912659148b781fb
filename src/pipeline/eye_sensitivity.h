// The eye's contrast sensitivity the perceptual spp model reads (foveation/spp_model.h,
// ContrastSensitivity): FovVideoVDP's CSF (metrics/vdp_csf.h) in its sustained channel (ω = 0 Hz),
// with the metric's stimulus size (csf_sigma) and cortical-magnification exponent (k_cm) from
// VdpParams, so the map puts samples where the metric that scores it sees noise. It lives here
// because foveation/ and metrics/ share a floor and may not include each other.
#pragma once

#include "foveation/spp_model.h"

namespace fovrt {

ContrastSensitivity MetricContrastSensitivity();
// The metric's contrast masking (its sensitivity correction, mask_c and sustained mask_q) and
// pooling (mask_p, beta), which the perceptual model's content term (foveation.content_masking) and
// its pooling = "metric" read.
ContrastMasking MetricContrastMasking();

}  // namespace fovrt
