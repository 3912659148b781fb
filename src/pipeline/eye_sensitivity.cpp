#include "pipeline/eye_sensitivity.h"

#include "metrics/vdp_csf.h"
#include "metrics/vdp_params.h"

namespace fovrt {

ContrastSensitivity MetricContrastSensitivity() {
    // The metric's sensitivity correction is a constant factor, which a relative map drops.
    const VdpParams params;
    return [sigma = params.csfSigma, kCm = params.kCm](double rho, double luminance, double eccentricity) {
        return VdpCsfModel(rho, kVdpChannelOmega[0], luminance, eccentricity, sigma, kCm);
    };
}

}  // namespace fovrt
