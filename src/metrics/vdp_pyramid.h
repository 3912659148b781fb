// The contrast pyramid of FovVideoVDP: a decimated Laplacian pyramid (Burt & Adelson, 5-tap kernel
// a = 0.4) whose bands are divided by the local adaptation luminance, the expanded next Gaussian
// level of the reference's sustained channel ("gpyr" adaptation, Weber contrast).
//
// Reduce and expand follow the reference implementation sample for sample, including its border
// handling (mirror padding on reduce, edge-replicated zero-interleave on expand) and one quirk:
// reduce picks the horizontal border rule from the parity of the image's *height* (not width).
// Matching it keeps band values equal to the reference's on images whose levels have odd height
// and even width (320×180 → 40×23, for one).
#pragma once

#include <vector>

#include "core/image.h"

namespace fovrt {

Plane<float> VdpGaussReduce(const Plane<float>& image);
// The same into `out`, with `rows` for the vertical pass: both reuse their memory when they
// already have the sizes they need.
void VdpGaussReduce(const Plane<float>& image, Plane<float>& out, Plane<float>& rows);
// Expands `image` to width × height (each at most twice the input's size).
Plane<float> VdpGaussExpand(const Plane<float>& image, int width, int height);
// The same into `out`, with `rows` for the vertical pass, reusing their memory as above.
void VdpGaussExpand(const Plane<float>& image, int width, int height, Plane<float>& out, Plane<float>& rows);

// Number of contrast bands for an image at `pixelsPerDegree` (the base band is not one of them):
// bands stop at the first whose peak frequency falls to 0.5 cpd, and at log2(min(w, h)) − 1.
int VdpBandCount(int width, int height, double pixelsPerDegree);
// Peak frequency (cpd) of each contrast band: ppd/2, then 0.3228·2^−k·ppd/2.
std::vector<double> VdpBandFrequencies(int width, int height, double pixelsPerDegree);

struct VdpContrastPyramid {
    // contrast[band][image]: Weber contrast of each input image in each band, multiplied by the
    // reference's band gain (1 for band 0, 2 for the others).
    std::vector<std::vector<Plane<float>>> contrast;
    // adaptation[band]: local adaptation luminance (cd/m², ≥ 0.1) of each band.
    std::vector<Plane<float>> adaptation;

    // VdpDecompose's working planes, one set per band so that each keeps its size from one
    // decomposition to the next: reused, they cost neither fresh memory nor clearing.
    struct BandScratch {
        std::vector<Plane<float>> next;  // [image]: the next Gaussian level
        Plane<float> expandedAdapting, expanded, reduceRows, expandRows;
    };
    std::vector<BandScratch> scratch;
};
// Decomposes each of `images` (same size, cd/m²) into `bands` contrast bands, adapting every
// image to image `adaptingImage` (the reference's sustained channel).
VdpContrastPyramid VdpDecompose(const std::vector<const Plane<float>*>& images, int adaptingImage,
                                int bands);
// The same into `pyramid`, reusing its planes' memory (scratch included) where the sizes match:
// the metric keeps one pyramid per frame in flight, since mapping and clearing fresh memory for
// every frame's planes cost a fifth of its time at 1280×720.
void VdpDecompose(const std::vector<const Plane<float>*>& images, int adaptingImage, int bands,
                  VdpContrastPyramid& pyramid);

// Collapses per-band maps (band b at the band's size, without band gain) into one full-size map:
// the reference's Laplacian reconstruction with a zero base band.
Plane<float> VdpReconstruct(const std::vector<Plane<float>>& bands);

}  // namespace fovrt
