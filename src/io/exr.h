// OpenEXR I/O: multi-layer writers/readers for FrameInputs dumps, spp maps and RGB images.
//
// A layer is a named group of channels ("direct" + {R,G,B} -> channels direct.R, direct.G,
// direct.B); a layer with one unnamed channel is stored under the layer name alone ("objectId").
// Float data may be stored as FLOAT (bit-exact) or HALF (compact, lossy); uint32 data as UINT.
// Compression is ZIP (lossless). Every writer goes through core/atomic_file.h, so a failed write
// leaves no file at `path`; every reader failure is a fovrt::Error naming the file.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/frame_inputs.h"
#include "core/image.h"
#include "core/math.h"
#include "core/plane_list.h"

namespace fovrt {

enum class ExrStorage { Float, Half, Uint };

// One layer to write. Points at caller memory (or owns a converted copy, e.g. uint16 -> uint32):
// component c of pixel i lives at base + i * pixelStride + c * 4 bytes, as float or uint32.
struct ExrLayer {
    std::string name;                   // layer name; channels are "<name>.<channel>"
    std::vector<std::string> channels;  // {""} = a single channel named <name>
    ExrStorage storage = ExrStorage::Float;
    bool sourceIsUint = false;          // source components are uint32 (else float)
    const char* base = nullptr;
    size_t pixelStride = 0;             // bytes between consecutive pixels
    size_t pixelCount = 0;              // width * height of the source plane
    std::shared_ptr<std::vector<uint32_t>> owned;  // keeps converted data alive

    static ExrLayer FromPlane(std::string name, const Plane<float>& plane,
                              ExrStorage storage = ExrStorage::Float);
    static ExrLayer FromPlane(std::string name, const Plane<vec2>& plane,
                              std::vector<std::string> channels = {"X", "Y"},
                              ExrStorage storage = ExrStorage::Float);
    static ExrLayer FromPlane(std::string name, const Plane<vec3>& plane,
                              std::vector<std::string> channels = {"R", "G", "B"},
                              ExrStorage storage = ExrStorage::Float);
    static ExrLayer FromPlane(std::string name, const Plane<uint32_t>& plane);
    static ExrLayer FromPlane(std::string name, const Plane<uint16_t>& plane);  // stored as UINT
};

// Extra header attributes (fovrt metadata): int, double, float-vector and string attributes.
struct ExrAttributes {
    std::map<std::string, int> ints;
    std::map<std::string, double> doubles;
    std::map<std::string, std::vector<float>> floats;
    std::map<std::string, std::string> strings;
};

// Writes all layers (each width*height pixels) into one scanline EXR at `path`, atomically.
void WriteExrLayers(const std::filesystem::path& path, int width, int height,
                    const std::vector<ExrLayer>& layers, const ExrAttributes& attributes = {});

// One channel read back: float channels (FLOAT or HALF in the file) in `floats`, UINT in `uints`.
struct ExrChannelData {
    bool isUint = false;
    std::vector<float> floats;
    std::vector<uint32_t> uints;
};

struct ExrImage {
    int width = 0;
    int height = 0;
    std::map<std::string, ExrChannelData> channels;  // by full channel name ("direct.R")
    ExrAttributes attributes;                          // attributes of the kinds above
    std::filesystem::path path;                        // for error messages

    // Throws fovrt::Error naming the file and the channel when absent or of the wrong kind.
    const std::vector<float>& Floats(const std::string& channel) const;
    const std::vector<uint32_t>& Uints(const std::string& channel) const;
    bool Has(const std::string& channel) const { return channels.count(channel) != 0; }
};

// Reads every channel of a scanline EXR (data window must start at 0,0).
ExrImage ReadExr(const std::filesystem::path& path);

// A plane of a plane list (core/plane_list.h: FrameInputs, the renderer's VisibilityBuffer) as the
// layer the list declares: named spec.name, channels spec.channels; floats FLOAT, integers UINT
// (bit-exact). T is float, vec2, vec3, uint32_t or uint16_t.
template <typename T>
ExrLayer PlaneLayer(const PlaneSpec& spec, const Plane<T>& plane);
// Inverse of PlaneLayer: fills `plane` from its layer in `image` (fovrt::Error if absent).
template <typename T>
void ReadPlaneLayer(const ExrImage& image, const PlaneSpec& spec, Plane<T>& plane);

// Every plane of a plane list as layers, in list order.
template <typename Planes>
std::vector<ExrLayer> PlaneLayers(const Planes& planes) {
    std::vector<ExrLayer> layers;
    planes.VisitPlanes(
        [&](const PlaneSpec& spec, const auto& plane) { layers.push_back(PlaneLayer(spec, plane)); });
    return layers;
}
// Every plane of a plane list read back from `image`.
template <typename Planes>
void ReadPlaneLayers(const ExrImage& image, Planes& planes) {
    planes.VisitPlanes(
        [&](const PlaneSpec& spec, auto& plane) { ReadPlaneLayer(image, spec, plane); });
}

// Every FrameInputs plane (PlaneLayers), `extraLayers` (e.g. the renderer's visibility buffer,
// which ReadFrameInputsExr skips), the spp map as layer "spp", and the scalar fields / cameras /
// gradient samples as fovrt.* attributes.
void WriteFrameInputsExr(const std::filesystem::path& path, const FrameInputs& inputs,
                         const Plane<uint16_t>& sppMap,
                         const std::vector<ExrLayer>& extraLayers = {});
// Inverse of WriteFrameInputsExr. `sppMap` may be null.
FrameInputs ReadFrameInputsExr(const std::filesystem::path& path, Plane<uint16_t>* sppMap = nullptr);

// Plain RGB images: channels R, G, B (FLOAT by default).
void WriteRgbExr(const std::filesystem::path& path, const Plane<vec3>& image,
                 ExrStorage storage = ExrStorage::Float);
// Reads channels R, G, B, or "<layer>.R/G/B" when `layer` is given.
Plane<vec3> ReadRgbExr(const std::filesystem::path& path, const std::string& layer = "");

}  // namespace fovrt
