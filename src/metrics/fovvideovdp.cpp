#include "metrics/fovvideovdp.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <memory>
#include <mutex>

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "core/error.h"
#include "metrics/filter.h"
#include "metrics/vdp_fastmath.h"
#include "metrics/vdp_masking.h"
#include "metrics/vdp_pyramid.h"
#include "metrics/vdp_temporal.h"

namespace fovrt {

namespace {

// Where each pixel of a band looks (degrees from the screen centre, x and y apart so the
// eccentricity loop vectorises) and its resolution magnification; independent of the fixation,
// so computed once per band.
struct BandGeometry {
    Plane<float> directionX, directionY;
    Plane<float> magnification;
};

BandGeometry MakeBandGeometry(const VdpGeometry& g, int w, int h, int imageW, int imageH) {
    BandGeometry b{Plane<float>(w, h), Plane<float>(w, h), Plane<float>(w, h)};
    // A view direction's x depends on the column only and its y on the row only.
    std::vector<double> columnX(static_cast<size_t>(w)), rowY(static_cast<size_t>(h));
    for (int x = 0; x < w; ++x) columnX[size_t(x)] = g.ViewDirection(x + 0.5, 0.5, w, h, imageW, imageH).x;
    for (int y = 0; y < h; ++y) rowY[size_t(y)] = g.ViewDirection(0.5, y + 0.5, w, h, imageW, imageH).y;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const glm::dvec2 d(columnX[size_t(x)], rowY[size_t(y)]);
            b.directionX(x, y) = float(d.x);
            b.directionY(x, y) = float(d.y);
            b.magnification(x, y) = float(g.ResolutionMagnification(glm::length(d)));
        }
    return b;
}

// One frame's temporally filtered images and contrast pyramid, kept for the next frame: fresh
// planes for every frame cost a tenth of the metric's time at 1280×720 in mapping and clearing
// memory. Taken from the pool by one frame at a time (a TBB thread may start another frame while
// it waits inside one, so a per-thread workspace would be shared).
struct FrameWorkspace {
    std::vector<Plane<float>> images;
    VdpContrastPyramid pyramid;
};

class WorkspacePool {
public:
    std::unique_ptr<FrameWorkspace> Take() {
        std::lock_guard lock(mutex_);
        if (free_.empty()) return std::make_unique<FrameWorkspace>();
        std::unique_ptr<FrameWorkspace> w = std::move(free_.back());
        free_.pop_back();
        return w;
    }
    void Give(std::unique_ptr<FrameWorkspace> w) {
        std::lock_guard lock(mutex_);
        free_.push_back(std::move(w));
    }

private:
    std::mutex mutex_;
    std::vector<std::unique_ptr<FrameWorkspace>> free_;
};

}  // namespace

// What Score keeps between calls (FovVideoVdp::cache_).
struct VdpScoreCache {
    WorkspacePool workspaces;
    // The band geometry of the last frame size a foveated Score saw.
    std::shared_ptr<const std::vector<BandGeometry>> BandGeometryFor(const VdpGeometry& g, int width, int height,
                                                                     int bands) {
        std::lock_guard lock(mutex_);
        if (!bandGeometry_ || width != width_ || height != height_ || int(bandGeometry_->size()) != bands) {
            auto made = std::make_shared<std::vector<BandGeometry>>();
            int w = width, h = height;
            for (int b = 0; b < bands; ++b, w = (w + 1) / 2, h = (h + 1) / 2)
                made->push_back(MakeBandGeometry(g, w, h, width, height));
            bandGeometry_ = std::move(made), width_ = width, height_ = height;
        }
        return bandGeometry_;
    }

private:
    std::mutex mutex_;
    int width_ = 0, height_ = 0;
    std::shared_ptr<const std::vector<BandGeometry>> bandGeometry_;
};

namespace {

// Per-row working arrays of the band loop.
struct RowScratch {
    std::vector<float> values, log2S, log2D;
    VdpCsfAxisRow rho, luminance, eccentricity;
    void Resize(size_t n) { values.resize(n), log2S.resize(n), log2D.resize(n); }
};

// Where each pixel of a foveated band's row lies for the CSF: its frequency (the band's scaled by
// the pixel's magnification) in `rho` and its eccentricity from the gaze in `eccentricity`.
FOVRT_VDP_ROW_CLONES void FoveatedRow(const float* magnification, const float* directionX, const float* directionY,
                                      std::size_t n, float bandRho, float gazeX, float gazeY, float* rho,
                                      float* eccentricity) {
    for (std::size_t x = 0; x < n; ++x) rho[x] = bandRho * magnification[x];
    for (std::size_t x = 0; x < n; ++x) {
        const float ex = directionX[x] - gazeX, ey = directionY[x] - gazeY;
        eccentricity[x] = std::sqrt(ex * ex + ey * ey);
    }
}

// One row of one band and channel after the CSF: masking (VdpLog2MaskedDifferenceRow) with the
// sensitivity correction added to log2 S, then Σ D^β (D^β in float per pixel, 0 where T = R:
// VdpFastExp2 of −∞), summed in double over eight interleaved partial sums so the loop
// vectorises; with `map`, adds mapGain·D to it.
struct MaskingConstants {
    float log2SensitivityGain, p, q, log2MaskGain, beta;
};
FOVRT_VDP_ROW_CLONES double MaskAndPoolRow(const float* test, const float* reference, float* log2S, std::size_t n,
                                           MaskingConstants k, float* log2D, float* map, float mapGain) {
    for (std::size_t x = 0; x < n; ++x) log2S[x] += k.log2SensitivityGain;
    VdpLog2MaskedDifferenceRow(test, reference, log2S, n, k.p, k.q, k.log2MaskGain, log2D);
    constexpr std::size_t kLanes = 8;
    double lanes[kLanes] = {};
    std::size_t x = 0;
    for (; x + kLanes <= n; x += kLanes)
        for (std::size_t l = 0; l < kLanes; ++l) lanes[l] += double(VdpFastExp2(k.beta * log2D[x + l]));
    for (; x < n; ++x) lanes[0] += double(VdpFastExp2(k.beta * log2D[x]));
    if (map)
        for (std::size_t i = 0; i < n; ++i) map[i] += mapGain * VdpFastExp2(log2D[i]);
    double sum = 0.0;
    for (const double lane : lanes) sum += lane;
    return sum;
}

// Equal counts of equal-size frames, a frame rate for video, one fixation or one per frame.
void ValidateSequence(const std::vector<Plane<float>>& test, const std::vector<Plane<float>>& reference, double fps,
                      const VdpOptions& options) {
    if (test.empty() || test.size() != reference.size())
        Fail("FovVideoVDP: {} test and {} reference frames (need equal, non-zero counts)", test.size(),
             reference.size());
    const int width = reference[0].width(), height = reference[0].height();
    for (size_t f = 0; f < test.size(); ++f)
        if (test[f].width() != width || test[f].height() != height || reference[f].width() != width ||
            reference[f].height() != height)
            Fail("FovVideoVDP: frame {} is not {}x{} in both sequences", f, width, height);
    const int frames = int(test.size());
    if (frames > 1 && !(fps > 0)) Fail("FovVideoVDP: {} frames need a frame rate > 0 (got {})", frames, fps);
    const size_t fixCount = options.fixations.size();
    if (options.foveated && fixCount > 1 && fixCount != size_t(frames))
        Fail("FovVideoVDP: {} fixations for {} frames (need 1 or one per frame)", fixCount, frames);
    if (options.firstScoredFrame < 0 || options.firstScoredFrame >= frames)
        Fail("FovVideoVDP: first scored frame {} of {} frames", options.firstScoredFrame, frames);
}

// Pooling of the per band × channel × frame Q: bands (β_sch), channels (β_tch, transient
// weighted), frames (β_t power mean), then JOD; a channel left out contributes nothing.
double PoolToJod(const VdpResult& r, const VdpParams& params, bool useSustained, bool useTransient) {
    const double channelWeight[2] = {1.0, params.wTransient};
    double frameSum = 0.0;
    for (int f = 0; f < r.frames; ++f) {
        double chSum = 0.0;
        for (int c = 0; c < r.channels; ++c) {
            if ((c == 0 && !useSustained) || (c == 1 && !useTransient)) continue;
            double bandSum = 0.0;
            for (int b = 0; b < r.bands; ++b) bandSum += std::pow(r.Q(b, c, f) * channelWeight[c], params.betaSch);
            chSum += std::pow(std::pow(bandSum, 1.0 / params.betaSch), params.betaTch);
        }
        frameSum += std::pow(std::pow(chSum, 1.0 / params.betaTch), params.betaT);
    }
    return VdpJod(std::pow(frameSum / r.frames, 1.0 / params.betaT), params);
}

void PoolAll(VdpResult& r, const VdpParams& params) {
    r.jod = PoolToJod(r, params, true, true);
    r.jodSustained = PoolToJod(r, params, true, false);
    r.jodTransient = r.channels > 1 ? PoolToJod(r, params, false, true) : 10.0;
}

}  // namespace

FovVideoVdp::FovVideoVdp(VdpGeometry geometry, VdpParams params)
    : geometry_(geometry),
      params_(params),
      csf_(VdpCsfTable::ForOmegas(kVdpChannelOmega[0], kVdpChannelOmega[1], params.csfSigma, params.kCm)),
      sensitivityGain_(float(std::pow(10.0, params.sensitivityCorrection / 20.0))),
      cache_(std::make_shared<VdpScoreCache>()) {}

float FovVideoVdp::Sensitivity(int channel, float rho, float luminance, float eccentricity) const {
    return csf_[channel].Sensitivity(rho, luminance, eccentricity) * sensitivityGain_;
}

VdpResult FovVideoVdp::Score(const std::vector<Plane<float>>& test, const std::vector<Plane<float>>& reference,
                             double fps, const VdpOptions& options) const {
    ValidateSequence(test, reference, fps, options);
    const int width = reference[0].width(), height = reference[0].height();
    const int frames = int(test.size());
    const int first = options.firstScoredFrame;
    const int scored = frames - first;
    const bool video = frames > 1;
    const size_t fixCount = options.fixations.size();

    const double ppd = geometry_.PixelsPerDegree();
    const int bands = VdpBandCount(width, height, ppd);
    if (bands < 1) Fail("FovVideoVDP: a {}x{} image is too small for a contrast pyramid", width, height);
    const int channels = video ? 2 : 1;

    VdpResult result;
    result.bands = bands;
    result.channels = channels;
    result.frames = scored;
    result.bandFrequencies = VdpBandFrequencies(width, height, ppd);
    result.bandFrequencies.resize(size_t(bands));
    result.q.assign(size_t(scored) * size_t(channels) * size_t(bands), 0.0);
    if (options.diffMaps) result.diffMaps.resize(size_t(scored));

    VdpTemporalFilters filters;
    if (video) filters = MakeVdpTemporalFilters(fps, params_);

    // Per band: pixel geometry (foveated) or the CSF sliced at the band's frequency (not foveated).
    std::shared_ptr<const std::vector<BandGeometry>> bandGeometry;
    if (options.foveated) bandGeometry = cache_->BandGeometryFor(geometry_, width, height, bands);
    std::vector<VdpCsfTable::LuminanceSlice> slices;  // [band * 2 + channel]
    for (int b = 0; b < bands; ++b)
        for (int c = 0; c < 2; ++c) slices.push_back(csf_[c].Slice(float(result.bandFrequencies[size_t(b)]), 0.0f));
    auto gaze = [&](int f) {
        const VdpFixation fix = fixCount == 0   ? VdpFixation{float(width / 2), float(height / 2)}
                                : fixCount == 1 ? options.fixations[0]
                                                : options.fixations[size_t(f)];
        return glm::vec2(geometry_.ViewDirection(fix.x + 0.5, fix.y + 0.5, width, height, width, height));
    };

    const float log2MaskGain = float(params_.maskC * std::log2(10.0));
    const float log2SensitivityGain = float(std::log2(double(sensitivityGain_)));
    const float p = float(params_.maskP);
    const float beta = float(params_.beta);
    const float channelWeight[2] = {1.0f, float(params_.wTransient)};

    WorkspacePool& workspaces = cache_->workspaces;
    tbb::parallel_for(first, frames, [&](int f) {
        const size_t out = size_t(f - first);  // the frame's place in the result
        std::unique_ptr<FrameWorkspace> workspace = workspaces.Take();
        // Images in the order test, reference per channel; the reference's sustained image adapts.
        std::vector<Plane<float>>& images = workspace->images;
        if (video) {
            images.resize(4);
            VdpFilterFrameChannels(test, f, filters, images[0], images[2]);
            VdpFilterFrameChannels(reference, f, filters, images[1], images[3]);
        }
        std::vector<const Plane<float>*> inputs;
        if (video) {
            for (const Plane<float>& i : images) inputs.push_back(&i);
        } else {
            inputs = {&test[size_t(f)], &reference[size_t(f)]};
        }
        VdpDecompose(inputs, 1, bands, workspace->pyramid);
        const VdpContrastPyramid& pyr = workspace->pyramid;
        const glm::vec2 gazeDir = options.foveated ? gaze(f) : glm::vec2(0.0f);

        std::vector<Plane<float>> diffBands;
        for (int b = 0; b < bands; ++b) {
            const Plane<float>& adapt = pyr.adaptation[size_t(b)];
            const float rhoBand = float(result.bandFrequencies[size_t(b)]);
            const float bandGain = b == 0 ? 1.0f : 2.0f;
            const int w = adapt.width(), h = adapt.height();
            if (options.diffMaps) diffBands.emplace_back(w, h, 0.0f);
            // Per row: locate the pixels on the CSF's axes once for both channels, then per
            // channel the log2 sensitivity, masking and the pooled D^β, summed in double.
            std::vector<double> rowSums(size_t(channels) * size_t(h), 0.0);
            metrics_detail::ParallelRows(h, [&](int y) {
                const size_t row = size_t(y) * size_t(w), n = size_t(w);
                // Per thread, not per row: a row runs to its end on its thread (nothing in it waits on
                // other tasks), and the arrays keep their memory from row to row.
                thread_local RowScratch s;
                s.Resize(n);
                csf_[0].LocateRow(VdpCsfTable::AxisName::Luminance, &adapt[row], n, s.luminance);
                if (options.foveated) {
                    const BandGeometry& g = (*bandGeometry)[size_t(b)];
                    FoveatedRow(&g.magnification[row], &g.directionX[row], &g.directionY[row], n, rhoBand, gazeDir.x,
                                gazeDir.y, s.values.data(), s.log2D.data());
                    csf_[0].LocateRow(VdpCsfTable::AxisName::Rho, s.values.data(), n, s.rho);
                    csf_[0].LocateRow(VdpCsfTable::AxisName::Eccentricity, s.log2D.data(), n, s.eccentricity);
                }
                for (int c = 0; c < channels; ++c) {
                    if (options.foveated) csf_[c].Log2Sensitivity(s.rho, s.luminance, s.eccentricity, n, s.log2S.data());
                    else csf_[c].Log2Sensitivity(slices[size_t(b) * 2 + size_t(c)], s.luminance, n, s.log2S.data());
                    const MaskingConstants k{log2SensitivityGain, p,
                                             float(c == 0 ? params_.maskQSustained : params_.maskQTransient),
                                             log2MaskGain, beta};
                    rowSums[size_t(c) * size_t(h) + size_t(y)] = MaskAndPoolRow(
                        &pyr.contrast[size_t(b)][size_t(2 * c)][row], &pyr.contrast[size_t(b)][size_t(2 * c + 1)][row],
                        s.log2S.data(), n, k, s.log2D.data(), options.diffMaps ? &diffBands[size_t(b)][row] : nullptr,
                        channelWeight[c] / bandGain);
                }
            });
            for (int c = 0; c < channels; ++c) {
                double sum = 0.0;
                for (int y = 0; y < h; ++y) sum += rowSums[size_t(c) * size_t(h) + size_t(y)];
                result.q[(out * size_t(channels) + size_t(c)) * size_t(bands) + size_t(b)] =
                    std::pow(sum / double(adapt.size()), 1.0 / double(beta));
            }
        }
        if (options.diffMaps) {
            Plane<float> map = VdpReconstruct(diffBands);
            const float bJod = float(std::pow(10.0, params_.logJodExp));
            const float aJod = float(std::abs(params_.jodA));
            for (float& v : map.vector()) v = std::pow(std::max(v, 0.0f), bJod) * aJod;
            result.diffMaps[out] = std::move(map);
        }
        workspaces.Give(std::move(workspace));
    });

    PoolAll(result, params_);
    return result;
}

VdpResult FovVideoVdp::ScoreSequence(int frames, const FrameReader& read, double fps, const VdpOptions& options,
                                     int chunkFrames) const {
    if (frames < 1) Fail("FovVideoVDP: a sequence of {} frames", frames);
    if (frames > 1 && !(fps > 0)) Fail("FovVideoVDP: {} frames need a frame rate > 0 (got {})", frames, fps);
    if (options.firstScoredFrame != 0) Fail("FovVideoVDP: a sequence read in chunks is scored from its first frame");
    const size_t fixCount = options.fixations.size();
    if (options.foveated && fixCount > 1 && fixCount != size_t(frames))
        Fail("FovVideoVDP: {} fixations for {} frames (need 1 or one per frame)", fixCount, frames);
    // A chunk of a video holds two frames at least, with the frames before it that the temporal
    // filters of its first frame reach (one at least): never a single frame, which Score would
    // take for a still.
    if (chunkFrames == 0) chunkFrames = tbb::this_task_arena::max_concurrency();
    chunkFrames = std::max(chunkFrames, frames > 1 ? 2 : 1);
    const int context = frames > 1 ? std::max(VdpTemporalFilterLength(fps), 2) - 1 : 0;

    std::vector<Plane<float>> test, reference;  // the window: frames [windowStart, windowStart + size)
    int windowStart = 0;
    VdpResult all;
    for (int start = 0; start < frames; start += chunkFrames) {
        const int end = std::min(start + chunkFrames, frames), keepFrom = std::max(start - context, 0);
        // Frames before keepFrom leave the window; their planes go to its end for the new frames.
        const auto dropped = std::ptrdiff_t(keepFrom - windowStart);
        std::rotate(test.begin(), test.begin() + dropped, test.end());
        std::rotate(reference.begin(), reference.begin() + dropped, reference.end());
        test.resize(size_t(end - keepFrom));
        reference.resize(size_t(end - keepFrom));
        windowStart = keepFrom;
        for (int f = start; f < end; ++f) read(f, test[size_t(f - keepFrom)], reference[size_t(f - keepFrom)]);

        VdpOptions chunk = options;
        chunk.firstScoredFrame = start - keepFrom;
        if (fixCount > 1)
            chunk.fixations.assign(options.fixations.begin() + keepFrom, options.fixations.begin() + end);
        VdpResult r = Score(test, reference, fps, chunk);
        if (start == 0) {
            all = std::move(r);
            continue;
        }
        // Per-frame results follow one another (VdpResult::q is frame-major).
        all.frames += r.frames;
        all.q.insert(all.q.end(), r.q.begin(), r.q.end());
        for (Plane<float>& map : r.diffMaps) all.diffMaps.push_back(std::move(map));
    }
    PoolAll(all, params_);
    return all;
}

}  // namespace fovrt
