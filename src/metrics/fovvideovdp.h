// FovVideoVDP 1.2 (Mantiuk et al. 2021): the visible difference between a test and a reference
// frame sequence, in JOD (10 = no visible difference; 1 JOD less ≈ 75 % of observers prefer the
// reference), foveated (eccentricity from a fixation per frame) or not. Per frame: two temporal
// channels (vdp_temporal.h) → contrast pyramid with local adaptation (vdp_pyramid.h) → contrast
// thresholds from the CSF at each pixel's frequency, luminance and eccentricity (vdp_csf.h) →
// masking and pooling (vdp_masking.h). Frames run in parallel (TBB). Input is absolute luminance
// (vdp_display.h turns pixel values into it); geometry is the pixel's, at the frames' own size.
#pragma once

#include <array>
#include <functional>
#include <memory>
#include <vector>

#include "core/image.h"
#include "metrics/vdp_csf.h"
#include "metrics/vdp_display.h"
#include "metrics/vdp_params.h"

namespace fovrt {

// A fixation point in pixel coordinates (x right, y down, pixel (i, j) spans [i, i+1) × [j, j+1)).
// Like the reference, the eye looks at (x + 0.5, y + 0.5): (i, j) means the centre of pixel (i, j).
struct VdpFixation {
    float x = 0.0f;
    float y = 0.0f;
};

struct VdpOptions {
    bool foveated = false;
    // Foveated only: one fixation for every frame or one per frame; none = the image centre
    // (width/2, height/2 in whole pixels, the reference's default).
    std::vector<VdpFixation> fixations;
    bool diffMaps = false;  // per-frame difference maps (VdpResult::diffMaps)
    // Frames before this one only feed the temporal filters: Q, the maps and the JOD are of the
    // frames from here on (a stream scores its newest frame with the frames before it: VdpStream).
    int firstScoredFrame = 0;
};

struct VdpResult {
    double jod = 10.0;
    // JOD of each temporal channel alone (the other's differences removed); a single frame has
    // only the sustained channel (transient = 10).
    double jodSustained = 10.0;
    double jodTransient = 10.0;
    int bands = 0, channels = 0, frames = 0;  // frames: the scored ones (from firstScoredFrame)
    std::vector<double> bandFrequencies;  // peak frequency (cpd) of each band
    std::vector<double> q;                // per band × channel × frame quality, see Q()
    // Per scored frame: the difference map in the units of JOD lost per pixel (reference's "raw" map).
    std::vector<Plane<float>> diffMaps;

    double Q(int band, int channel, int frame) const {
        return q[(size_t(frame) * size_t(channels) + size_t(channel)) * size_t(bands) + size_t(band)];
    }
};

struct VdpScoreCache;  // fovvideovdp.cpp

class FovVideoVdp {
public:
    explicit FovVideoVdp(VdpGeometry geometry, VdpParams params = {});

    // `test` and `reference`: equal counts of equal-size frames in cd/m². `fps` is required for
    // more than one frame (one frame is scored as an image, without temporal channels).
    VdpResult Score(const std::vector<Plane<float>>& test, const std::vector<Plane<float>>& reference,
                    double fps, const VdpOptions& options = {}) const;

    // Score of a `frames`-long sequence that is never held whole: `read(f, test, reference)` fills
    // frame f's planes (given back from earlier frames, to reuse their memory), asked for in order;
    // frames are scored `chunkFrames` at a time (0: as many as the threads score at once) with the
    // frames before each chunk that its temporal filters reach. The result equals Score's on the
    // whole sequence (options as there, firstScoredFrame 0), while memory holds one chunk and its
    // filters' reach: the fewer frames held, the less memory to map and fault in.
    using FrameReader = std::function<void(int frame, Plane<float>& test, Plane<float>& reference)>;
    VdpResult ScoreSequence(int frames, const FrameReader& read, double fps, const VdpOptions& options = {},
                            int chunkFrames = 0) const;

    const VdpGeometry& geometry() const { return geometry_; }
    const VdpParams& params() const { return params_; }
    // Contrast sensitivity after the metric's sensitivity correction, for channel 0 (sustained)
    // or 1 (transient), as Score evaluates it.
    float Sensitivity(int channel, float rho, float luminance, float eccentricity) const;

private:
    VdpGeometry geometry_;
    VdpParams params_;
    std::array<VdpCsfTable, 2> csf_;  // per channel
    float sensitivityGain_;
    // Per-frame workspaces and per-band pixel geometry kept from one Score call to the next (and
    // shared by copies; thread-safe), so a sequence scored in chunks, a stream or the variants of
    // an experiment map memory and compute a tan per band pixel once, not per call.
    std::shared_ptr<VdpScoreCache> cache_;
};

}  // namespace fovrt
