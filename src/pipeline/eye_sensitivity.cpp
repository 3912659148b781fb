#include "pipeline/eye_sensitivity.h"

#include <cmath>

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

ContrastMasking MetricContrastMasking() {
    // The sustained channel's: the denoisers leave slow noise (as the sensitivity above).
    const VdpParams params;
    return {std::pow(10.0, params.sensitivityCorrection / 20.0), std::pow(10.0, params.maskC),
            params.maskQSustained, params.maskP, params.beta};
}

}  // namespace fovrt
