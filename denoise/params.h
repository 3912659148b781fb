// Tunables of the denoisers, each declared once with its default and range. Loaded from the
// [denoise] config table and recorded in every run manifest.
#pragma once

namespace fovrt {

enum class Precision { Fp32, Fp16 };  // storage of history buffers

struct SvgfParams {
    float alphaColor = 0.2f;      // temporal EMA weight of new colour, (0,1]; paper 0.2
    float alphaMoments = 0.2f;    // temporal EMA weight of moments, (0,1]; paper 0.2
    int atrousIterations = 5;     // [0,8]; paper 5
    int feedbackIteration = 1;    // à-trous iteration (1-based) whose output is the colour history;
                                  // paper 1, Falcor 2; 0 = feed back the unfiltered accumulation
    float sigmaDepth = 1.0f;      // σz
    float sigmaNormal = 128.0f;   // σn
    float sigmaLuminance = 4.0f;  // σl
    int varianceHistoryThreshold = 4;  // spatial 7×7 variance below this history length
    bool filterCombined = false;  // filter direct+indirect together instead of separately
    bool weightBySampleCount = false;  // svgf-weighted: temporal weights × n
};

struct AsvgfParams {
    float alpha = 0.1f;            // base temporal weight α (paper 0.1)
    int gradientIterations = 5;    // à-trous iterations at stratum resolution
};

struct TwoHistoryParams {
    float gradientBeta = 0.8f;     // β_g of the gradient EMA
    float qScale = 1.0f;           // S in q = clamp(S·|lum g| / std(lum I_u), 0, 1)
};

struct DenoiserParams {
    SvgfParams svgf;
    AsvgfParams asvgf;
    TwoHistoryParams twoHistory;
    Precision precision = Precision::Fp32;
};

}  // namespace fovrt
