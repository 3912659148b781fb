// FovVideoVDP one frame at a time (the live preview's "vdp" view): keeps the frames the temporal
// filters reach (⌈250 ms · fps⌉, the first frame standing in for the frames before it, as Score
// pads a sequence), so the difference map of the newest frame is the one FovVideoVdp::Score gives
// for that frame of the whole sequence.
#pragma once

#include <vector>

#include "metrics/fovvideovdp.h"

namespace fovrt {

class VdpStream {
public:
    VdpStream(VdpGeometry geometry, double fps);

    // The newest frame's difference map (JOD lost per pixel), foveated at `fixation`. Frames of
    // another size than the ones held start the stream again.
    Plane<float> Next(Plane<float> test, Plane<float> reference, VdpFixation fixation);
    // Forgets every frame: the next one starts a new sequence.
    void Reset();
    // The frames held (0 after Reset; then the filter length).
    size_t Held() const { return test_.size(); }

private:
    FovVideoVdp vdp_;
    double fps_;
    size_t window_;
    std::vector<Plane<float>> test_, reference_;
    std::vector<VdpFixation> fixations_;
};

}  // namespace fovrt
