#include "denoise/demodulation.h"

#include <utility>

#include "core/check.h"
#include "core/error.h"

namespace fovrt {

const FrameInputs& Redemodulate(const FrameInputs& in, Demodulation want, FrameInputs& scratch) {
    if (in.demodulation == want) return in;
    scratch = in;
    scratch.demodulation = want;
    const Plane<vec3>& from = in.Modulation();
    const Plane<vec3>& to = scratch.Modulation();
    for (size_t i = 0; i < from.size(); ++i) {
        for (int c = 0; c < 3; ++c) {
            if (!(to[i][c] > 0.0f)) {
                // Both factors are >= 1e-3 on surfaces: a 0 there is a plane the renderer skipped.
                if (in.objectId[i] != kNoObject)
                    Fail("{} demodulation: the frame's {} plane is 0 on a surface (the renderer fills fbeta "
                         "only under render.demodulation = \"brdf\" or for a +brdf variant: "
                         "RenderSettings::fbetaPlane)",
                         DemodulationName(want), want == Demodulation::Brdf ? "fbeta" : "albedo");
                continue;
            }
            const float ratio = from[i][c] / to[i][c];
            scratch.direct[i][c] = in.direct[i][c] * ratio;
            scratch.indirect[i][c] = in.indirect[i][c] * ratio;
        }
    }
    return scratch;
}

namespace {

class DemodulatingDenoiser final : public Denoiser {
public:
    DemodulatingDenoiser(std::unique_ptr<Denoiser> inner, Demodulation want, std::string name)
        : inner_(std::move(inner)), want_(want), name_(std::move(name)) {}
    std::string Name() const override { return name_; }
    std::string Backend() const override { return inner_->Backend(); }
    void Reset() override { inner_->Reset(); }
    void Denoise(const FrameInputs& inputs, Plane<vec3>& output) override {
        inner_->Denoise(Redemodulate(inputs, want_, scratch_), output);
    }
    std::vector<PassTiming> LastTimings() const override { return inner_->LastTimings(); }
    DenoiseStats Stats() const override { return inner_->Stats(); }

private:
    bool ReadDebugPlane(DebugViewId view, Plane<float>& out) override {
        for (const DebugView& row : DebugViewTable())
            if (row.id == view) return inner_->ReadDebugView(std::string(row.name), out);
        return false;
    }

    std::unique_ptr<Denoiser> inner_;
    Demodulation want_;
    std::string name_;
    FrameInputs scratch_;  // the re-demodulated frame (reused: no allocation after the first)
};

}  // namespace

std::unique_ptr<Denoiser> WithDemodulation(std::unique_ptr<Denoiser> inner, Demodulation want,
                                           std::string name) {
    FOVRT_CHECK(inner != nullptr);
    return std::make_unique<DemodulatingDenoiser>(std::move(inner), want, std::move(name));
}

}  // namespace fovrt
