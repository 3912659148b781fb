// A-SVGF's temporal gradient (Schied et al. 2018, §3) as planned passes.
#include "denoise/mechanism_passes.h"
#include "denoise/plan_writer.h"

namespace fovrt::plan {

// A-SVGF's temporal gradient at stratum resolution (Schied 2018 §3): claim a slot per stratum
// (first sample wins), gather (δ, Δ) and the stratum guide, σ_l·std of the guide, à-trous
// iterations; then the per-pixel α (the anti-lag variants: their factor a) and λ. Without a previous frame neither runs: the reset left
// α = λ = 1 (ClearValue).
void AsvgfGradient(Writer& w, const Family& f, FrameCursor&) {
    const int iterations = f.params.asvgf.gradientIterations;
    AsvgfGradientStage stage{{PlaneKind::AsvgfGrad0}, {}};
    for (int i = 0; i < iterations; ++i)
        stage.iterations.push_back({Channel::None, {i & 1 ? PlaneKind::AsvgfGrad1 : PlaneKind::AsvgfGrad0},
                                    {i & 1 ? PlaneKind::AsvgfGrad0 : PlaneKind::AsvgfGrad1}, std::nullopt});
    const PlaneId reconstructed = stage.iterations.empty() ? stage.scattered : stage.iterations.back().out;
    const PlaneRef claim = Shared(PlaneKind::AsvgfClaim), samples = Shared(PlaneKind::AsvgfSamples);
    const PlaneRef guideGeometry = Shared(PlaneKind::AsvgfGuideGeometry);
    const PlaneRef guideLuminance = Shared(PlaneKind::AsvgfGuideLuminance), sigma = Shared(PlaneKind::AsvgfSigma);

    w.Pass("asvgf_gradient", "asvgf_gradient", stage, When::HasPrevious);
    w.Fill(claim, 0xFFFFFFFFu);  // every slot empty
    w.Barrier();
    PushBlock samplesPush = PushBlock::Of(AsvgfSamplesPush{f.size, f.grid, 0u});
    FOVRT_PUSH_PER_FRAME(samplesPush, AsvgfSamplesPush, count, FrameValue::GradientSampleCount);
    Bindings c;  // atomicMin on the claimed slots
    c.Read(ASVGF_CLAIM_B_SAMPLES, samples, Coverage::UploadedSamples)
        .ReadWrite(ASVGF_CLAIM_B_CLAIM, claim, Coverage::ClaimedStrata);
    w.Dispatch(Over(Grid::GradientSamples, f.Pipeline(StageShader::AsvgfClaim), std::move(c), samplesPush),
               When::GradientSamples);
    w.Barrier(When::GradientSamples);
    // The claimed samples → (δ, Δ); the stratum guide from this frame's planes at the guide pixel.
    const Coverage guidePixels = Coverage::StratumGuidePixels;
    Bindings g;
    g.Read(ASVGF_GATHER_B_SAMPLES, samples, Coverage::ClaimedStrata, 0.5)
        .Read(ASVGF_GATHER_B_CLAIM, claim)
        .Write(ASVGF_GATHER_B_GRAD, Shared(stage.scattered.kind))
        .Write(ASVGF_GATHER_B_GUIDE_GEOMETRY, guideGeometry)
        .Write(ASVGF_GATHER_B_GUIDE_LUMINANCE, guideLuminance)
        .Read(ASVGF_GATHER_B_DEPTH, This(PlaneKind::Depth), guidePixels)
        .Read(ASVGF_GATHER_B_NORMAL, This(PlaneKind::Normal), guidePixels)
        .ReadObjectIds(ASVGF_GATHER_B_OBJECT, This(PlaneKind::ObjectId), f.idsInDepth, guidePixels)
        .Read(ASVGF_GATHER_B_DEPTH_GRAD, Shared(PlaneKind::DepthGradient), guidePixels)
        .Read(ASVGF_GATHER_B_DIRECT, Shared(PlaneKind::Direct), guidePixels)
        .Read(ASVGF_GATHER_B_INDIRECT, Shared(PlaneKind::Indirect), guidePixels)
        .Read(ASVGF_GATHER_B_ALBEDO, Shared(PlaneKind::Modulation), guidePixels)
        .Read(ASVGF_GATHER_B_EMISSION, Shared(PlaneKind::Emission), guidePixels);
    w.Dispatch(OverStrata(f.Pipeline(StageShader::AsvgfGather), std::move(g), samplesPush));
    w.Barrier();
    Bindings s;
    s.Read(ASVGF_SIGMA_B_GUIDE_GEOMETRY, guideGeometry)
        .Read(ASVGF_SIGMA_B_GUIDE_LUMINANCE, guideLuminance)
        .Write(ASVGF_SIGMA_B_OUT, sigma);
    w.Dispatch(OverStrata(f.Pipeline(StageShader::AsvgfSigma), std::move(s),
                          PushBlock::Of(AsvgfSigmaPush{f.grid, f.svgf.sigmaLuminance})));
    w.Barrier();
    for (int i = 0; i < iterations; ++i) {
        const StagePlane& it = stage.iterations[size_t(i)];
        Bindings a;
        a.Read(ASVGF_ATROUS_B_GRAD_IN, Shared(it.in.kind))
            .Read(ASVGF_ATROUS_B_GUIDE_GEOMETRY, guideGeometry)
            .Read(ASVGF_ATROUS_B_GUIDE_LUMINANCE, guideLuminance)
            .Read(ASVGF_ATROUS_B_SIGMA, sigma)
            .Write(ASVGF_ATROUS_B_GRAD_OUT, Shared(it.out.kind));
        const AsvgfAtrousPush push{f.size, f.grid, 1 << i, f.svgf.sigmaDepth, f.svgf.sigmaNormal, f.svgf.sigmaLuminance};
        w.Dispatch(OverStrata(f.Pipeline(StageShader::AsvgfAtrous, f.EdgeStopping()), std::move(a), PushBlock::Of(push)));
        w.Barrier();
    }

    w.Pass("asvgf_alpha", "asvgf_gradient", AsvgfAlphaStage{reconstructed, f.v.antilag}, When::HasPrevious);
    Bindings al;
    al.Read(ASVGF_ALPHA_B_GRAD, Shared(reconstructed.kind))
        .Write(ASVGF_ALPHA_B_ALPHA, Shared(PlaneKind::AsvgfAlpha))
        .Write(ASVGF_ALPHA_B_LAMBDA, Shared(PlaneKind::AsvgfLambda));
    const Specialization antilag = Specialization::Of({{FOVRT_SPEC_ASVGF_ANTILAG, f.v.antilag ? 1 : 0}});
    w.Dispatch(OverPixels(f.Pipeline(StageShader::AsvgfAlpha, antilag), std::move(al),
                          PushBlock::Of(AsvgfAlphaPush{f.size, f.grid, f.params.asvgf.alpha,
                                                       f.params.asvgf.antilagGain})));
    w.Barrier();
}

}  // namespace fovrt::plan
