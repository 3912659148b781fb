// FovVideoVDP 1.2 calibration (Mantiuk et al. 2021, "FovVideoVDP: A visible difference predictor
// for wide field-of-view video", ACM TOG 40(4)), as published in the reference implementation's
// parameter file fvvdp_parameters.json v1.2.3 (gfxdisp/FovVideoVDP). Values are facts of the
// published model; the model structure they belong to is fixed in fovrt: masking
// "min_mutual_masking_perc_norm2", local adaptation "gpyr", Weber contrast, no phase-uncertainty
// dilation (pu_dilate = 0). docs/perceptual-metric.md describes each.
#pragma once

namespace fovrt {

struct VdpParams {
    double maskP = 2.4;                   // mask_p: exponent of the excitation |T−R|
    double maskC = -0.973838;             // mask_c: log10 gain of the mutual masking signal
    double maskQSustained = 2.43685;      // mask_q_sust: exponent of the masking signal
    double maskQTransient = 4.946;        // mask_q_trans
    double wTransient = 0.25;             // w_transient: weight of the transient channel
    double beta = 1.52134;                // beta: spatial (per-band) pooling exponent
    double betaT = 1.0;                   // beta_t: pooling over frames
    double betaTch = 0.666092;            // beta_tch: pooling over the two temporal channels
    double betaSch = 1.0;                 // beta_sch: pooling over spatial bands
    double sustainedSigma = 0.5;          // log-Gaussian impulse response: σ
    double sustainedBeta = 0.06;          // and its peak time β in seconds
    double csfSigma = -1.5;               // stimulus size: negative = 1.5 cycles of the band
    double sensitivityCorrection = 16.2596;  // dB added to the CSF
    double jodA = -0.0161713;             // JOD = 10 + sign(a)·(|a|^{1/b}·Q)^b
    double logJodExp = -0.2280;           // b = 10^log_jod_exp
    double kCm = 0.604562;                // exponent of the cortical magnification factor
};

// Temporal frequencies (Hz) at which the CSF is evaluated for the sustained and transient channel.
inline constexpr double kVdpChannelOmega[2] = {0.0, 5.0};
// The reference's constant that scales the transient (derivative) filter.
inline constexpr double kVdpTransientGain = 0.062170507756932;

}  // namespace fovrt
