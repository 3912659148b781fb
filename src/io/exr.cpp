#include "io/exr.h"

#include <cmath>
#include <cstring>
#include <exception>
#include <limits>
#include <type_traits>

#include <Imath/half.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfCompression.h>
#include <OpenEXR/ImfDoubleAttribute.h>
#include <OpenEXR/ImfFloatVectorAttribute.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfIntAttribute.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>

#include "core/atomic_file.h"
#include "core/check.h"
#include "core/error.h"

namespace fovrt {
namespace {

constexpr const char* kFrameInputsFormat = "fovrt-frame-inputs-1";

std::string ChannelName(const std::string& layer, const std::string& channel) {
    if (layer.empty()) return channel;
    return channel.empty() ? layer : layer + "." + channel;
}

template <typename T>
ExrLayer FloatLayer(std::string name, const Plane<T>& plane, std::vector<std::string> channels,
                    ExrStorage storage) {
    static_assert(sizeof(T) % sizeof(float) == 0);
    FOVRT_CHECK(storage != ExrStorage::Uint);
    FOVRT_CHECK_OP(channels.size(), ==, sizeof(T) / sizeof(float));
    ExrLayer layer;
    layer.name = std::move(name);
    layer.channels = std::move(channels);
    layer.storage = storage;
    layer.base = reinterpret_cast<const char*>(plane.data());
    layer.pixelStride = sizeof(T);
    layer.pixelCount = plane.size();
    return layer;
}

Imf::PixelType PixelTypeOf(ExrStorage storage) {
    switch (storage) {
        case ExrStorage::Float: return Imf::FLOAT;
        case ExrStorage::Half: return Imf::HALF;
        case ExrStorage::Uint: return Imf::UINT;
    }
    return Imf::FLOAT;
}

// Copies one float/uint component plane out of an ExrImage into an interleaved Plane.
template <typename T>
void ReadFloatPlane(const ExrImage& image, const std::string& layer,
                    const std::vector<std::string>& channels, Plane<T>& plane) {
    plane.Resize(image.width, image.height);
    float* out = reinterpret_cast<float*>(plane.data());
    const size_t components = sizeof(T) / sizeof(float);
    for (size_t c = 0; c < channels.size(); ++c) {
        const std::vector<float>& src = image.Floats(ChannelName(layer, channels[c]));
        for (size_t i = 0; i < plane.size(); ++i) out[i * components + c] = src[i];
    }
}

// "RGB" -> {"R", "G", "B"}; "" -> {""} (one channel named after the layer).
std::vector<std::string> ChannelNames(const char* letters) {
    std::vector<std::string> names;
    for (const char* c = letters; *c != '\0'; ++c) names.emplace_back(1, *c);
    if (names.empty()) names.emplace_back();
    return names;
}

// Copies a UINT channel into a uint32 or uint16 plane (uint16: values must fit).
template <typename T>
void ReadUintPlane(const ExrImage& image, const std::string& name, Plane<T>& plane) {
    const std::vector<uint32_t>& src = image.Uints(name);
    plane.Resize(image.width, image.height);
    for (size_t i = 0; i < src.size(); ++i) {
        if constexpr (sizeof(T) < sizeof(uint32_t)) {
            if (src[i] > std::numeric_limits<T>::max())
                Fail("EXR '{}': channel '{}' value {} does not fit {} bits", image.path.string(),
                     name, src[i], 8 * sizeof(T));
        }
        plane[i] = T(src[i]);
    }
}

std::vector<float> CameraToFloats(const EyeCamera& camera) {
    const Pose& p = camera.pose();
    const Fov& f = camera.fov();
    return {p.orientation.w, p.orientation.x, p.orientation.y, p.orientation.z,
            p.position.x,    p.position.y,    p.position.z,    f.angleLeft,
            f.angleRight,    f.angleUp,       f.angleDown,     float(camera.width()),
            float(camera.height())};
}

EyeCamera CameraFromFloats(const std::vector<float>& v, const std::filesystem::path& path,
                           const std::string& name) {
    if (v.size() != 13) Fail("EXR '{}': attribute '{}' has {} values, expected 13", path.string(), name, v.size());
    int width = int(v[11]), height = int(v[12]);
    if (width <= 0 || height <= 0) return EyeCamera();  // a default (unset) camera
    Pose pose{quat(v[0], v[1], v[2], v[3]), vec3(v[4], v[5], v[6])};
    Fov fov{v[7], v[8], v[9], v[10]};
    return EyeCamera(pose, fov, width, height);
}

}  // namespace

ExrLayer ExrLayer::FromPlane(std::string name, const Plane<float>& plane, ExrStorage storage) {
    return FloatLayer(std::move(name), plane, {""}, storage);
}
ExrLayer ExrLayer::FromPlane(std::string name, const Plane<vec2>& plane,
                             std::vector<std::string> channels, ExrStorage storage) {
    return FloatLayer(std::move(name), plane, std::move(channels), storage);
}
ExrLayer ExrLayer::FromPlane(std::string name, const Plane<vec3>& plane,
                             std::vector<std::string> channels, ExrStorage storage) {
    return FloatLayer(std::move(name), plane, std::move(channels), storage);
}
ExrLayer ExrLayer::FromPlane(std::string name, const Plane<uint32_t>& plane) {
    ExrLayer layer;
    layer.name = std::move(name);
    layer.channels = {""};
    layer.storage = ExrStorage::Uint;
    layer.sourceIsUint = true;
    layer.base = reinterpret_cast<const char*>(plane.data());
    layer.pixelStride = sizeof(uint32_t);
    layer.pixelCount = plane.size();
    return layer;
}
ExrLayer ExrLayer::FromPlane(std::string name, const Plane<uint16_t>& plane) {
    // EXR has no 16-bit integer type: widen to UINT.
    auto owned = std::make_shared<std::vector<uint32_t>>(plane.vector().begin(), plane.vector().end());
    ExrLayer layer;
    layer.name = std::move(name);
    layer.channels = {""};
    layer.storage = ExrStorage::Uint;
    layer.sourceIsUint = true;
    layer.base = reinterpret_cast<const char*>(owned->data());
    layer.pixelStride = sizeof(uint32_t);
    layer.pixelCount = plane.size();
    layer.owned = std::move(owned);
    return layer;
}

void WriteExrLayers(const std::filesystem::path& path, int width, int height,
                    const std::vector<ExrLayer>& layers, const ExrAttributes& attributes) {
    if (width <= 0 || height <= 0)
        Fail("cannot write EXR '{}': empty image ({}x{})", path.string(), width, height);
    Imf::Header header(width, height);
    header.compression() = Imf::ZIP_COMPRESSION;
    Imf::FrameBuffer frameBuffer;
    std::vector<std::vector<half>> halves;  // HALF channels: OpenEXR does not convert on write
    halves.reserve(layers.size() * 4);
    for (const ExrLayer& layer : layers) {
        FOVRT_CHECK_OP(layer.pixelCount, ==, size_t(width) * size_t(height));
        // Only float<->float(half) conversions are lossless-meaningful; uint stays uint.
        FOVRT_CHECK(layer.sourceIsUint == (layer.storage == ExrStorage::Uint));
        for (size_t c = 0; c < layer.channels.size(); ++c) {
            std::string name = ChannelName(layer.name, layer.channels[c]);
            if (header.channels().findChannel(name))
                Fail("cannot write EXR '{}': channel '{}' given twice", path.string(), name);
            header.channels().insert(name, Imf::Channel(PixelTypeOf(layer.storage)));
            const char* base = layer.base + c * 4;
            if (layer.storage == ExrStorage::Half) {
                std::vector<half>& h = halves.emplace_back(layer.pixelCount);
                for (size_t i = 0; i < layer.pixelCount; ++i) {
                    float v;
                    std::memcpy(&v, base + i * layer.pixelStride, sizeof(float));
                    h[i] = half(v);
                }
                frameBuffer.insert(name, Imf::Slice(Imf::HALF, reinterpret_cast<char*>(h.data()),
                                                    sizeof(half), sizeof(half) * size_t(width)));
                continue;
            }
            Imf::PixelType sourceType = layer.sourceIsUint ? Imf::UINT : Imf::FLOAT;
            frameBuffer.insert(name, Imf::Slice(sourceType, const_cast<char*>(base), layer.pixelStride,
                                                layer.pixelStride * size_t(width)));
        }
    }
    for (const auto& [name, value] : attributes.ints) header.insert(name, Imf::IntAttribute(value));
    for (const auto& [name, value] : attributes.doubles)
        header.insert(name, Imf::DoubleAttribute(value));
    for (const auto& [name, value] : attributes.floats)
        header.insert(name, Imf::FloatVectorAttribute(value));
    for (const auto& [name, value] : attributes.strings)
        header.insert(name, Imf::StringAttribute(value));

    WriteAtomically(path, [&](const std::filesystem::path& temp) {
        try {
            Imf::OutputFile file(temp.c_str(), header);
            file.setFrameBuffer(frameBuffer);
            file.writePixels(height);
        } catch (const Error&) {
            throw;
        } catch (const std::exception& e) {
            Fail("cannot write EXR '{}': {}", path.string(), e.what());
        }
    });
}

const std::vector<float>& ExrImage::Floats(const std::string& channel) const {
    auto it = channels.find(channel);
    if (it == channels.end()) Fail("EXR '{}': missing channel '{}'", path.string(), channel);
    if (it->second.isUint) Fail("EXR '{}': channel '{}' is UINT, expected float", path.string(), channel);
    return it->second.floats;
}

const std::vector<uint32_t>& ExrImage::Uints(const std::string& channel) const {
    auto it = channels.find(channel);
    if (it == channels.end()) Fail("EXR '{}': missing channel '{}'", path.string(), channel);
    if (!it->second.isUint) Fail("EXR '{}': channel '{}' is float, expected UINT", path.string(), channel);
    return it->second.uints;
}

ExrImage ReadExr(const std::filesystem::path& path) {
    if (!std::filesystem::exists(path)) Fail("EXR '{}' does not exist", path.string());
    ExrImage image;
    image.path = path;
    try {
        Imf::InputFile file(path.c_str());
        const Imf::Header& header = file.header();
        const Imath::Box2i dw = header.dataWindow();
        image.width = dw.max.x - dw.min.x + 1;
        image.height = dw.max.y - dw.min.y + 1;
        if (image.width <= 0 || image.height <= 0) Fail("EXR '{}': empty data window", path.string());
        const size_t count = size_t(image.width) * size_t(image.height);
        Imf::FrameBuffer frameBuffer;
        for (auto it = header.channels().begin(); it != header.channels().end(); ++it) {
            if (it.channel().xSampling != 1 || it.channel().ySampling != 1)
                Fail("EXR '{}': subsampled channel '{}' is not supported", path.string(), it.name());
            ExrChannelData& data = image.channels[it.name()];
            data.isUint = it.channel().type == Imf::UINT;
            void* base;
            if (data.isUint) {
                data.uints.assign(count, 0u);
                base = data.uints.data();
            } else {
                data.floats.assign(count, 0.0f);
                base = data.floats.data();
            }
            frameBuffer.insert(it.name(), Imf::Slice::Make(data.isUint ? Imf::UINT : Imf::FLOAT, base,
                                                           dw, 4, 4 * size_t(image.width)));
        }
        file.setFrameBuffer(frameBuffer);
        file.readPixels(dw.min.y, dw.max.y);
        for (auto it = header.begin(); it != header.end(); ++it) {
            const Imf::Attribute& a = it.attribute();
            if (auto* v = dynamic_cast<const Imf::IntAttribute*>(&a)) image.attributes.ints[it.name()] = v->value();
            else if (auto* d = dynamic_cast<const Imf::DoubleAttribute*>(&a))
                image.attributes.doubles[it.name()] = d->value();
            else if (auto* f = dynamic_cast<const Imf::FloatVectorAttribute*>(&a))
                image.attributes.floats[it.name()] = f->value();
            else if (auto* s = dynamic_cast<const Imf::StringAttribute*>(&a))
                image.attributes.strings[it.name()] = s->value();
        }
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        Fail("cannot read EXR '{}': {}", path.string(), e.what());
    }
    return image;
}

template <typename T>
ExrLayer PlaneLayer(const PlaneSpec& spec, const Plane<T>& plane) {
    if constexpr (std::is_integral_v<T>) {
        FOVRT_CHECK(spec.channels[0] == '\0');  // integer planes are scalar
        return ExrLayer::FromPlane(spec.name, plane);
    } else {
        return FloatLayer(spec.name, plane, ChannelNames(spec.channels), ExrStorage::Float);
    }
}

template <typename T>
void ReadPlaneLayer(const ExrImage& image, const PlaneSpec& spec, Plane<T>& plane) {
    if constexpr (std::is_integral_v<T>) ReadUintPlane(image, spec.name, plane);
    else ReadFloatPlane(image, spec.name, ChannelNames(spec.channels), plane);
}

#define FOVRT_EXR_PLANE_TYPE(T)                                                  \
    template ExrLayer PlaneLayer(const PlaneSpec&, const Plane<T>&);            \
    template void ReadPlaneLayer(const ExrImage&, const PlaneSpec&, Plane<T>&);
FOVRT_EXR_PLANE_TYPE(float)
FOVRT_EXR_PLANE_TYPE(vec2)
FOVRT_EXR_PLANE_TYPE(vec3)
FOVRT_EXR_PLANE_TYPE(uint32_t)
FOVRT_EXR_PLANE_TYPE(uint16_t)
#undef FOVRT_EXR_PLANE_TYPE

void WriteFrameInputsExr(const std::filesystem::path& path, const FrameInputs& inputs,
                         const Plane<uint16_t>& sppMap, const std::vector<ExrLayer>& extraLayers) {
    const int width = inputs.width(), height = inputs.height();
    inputs.VisitPlanes([&](const PlaneSpec&, const auto& plane) {
        FOVRT_CHECK(plane.width() == width && plane.height() == height);
    });
    std::vector<ExrLayer> layers = PlaneLayers(inputs);
    for (const ExrLayer& layer : extraLayers) {
        FOVRT_CHECK_OP(layer.pixelCount, ==, size_t(width) * size_t(height));
        layers.push_back(layer);
    }
    if (!sppMap.empty()) {
        FOVRT_CHECK(sppMap.width() == width && sppMap.height() == height);
        layers.push_back(ExrLayer::FromPlane("spp", sppMap));
    }
    ExrAttributes attributes;
    attributes.strings["fovrt.format"] = kFrameInputsFormat;
    attributes.ints["fovrt.eye"] = inputs.eye;
    attributes.ints["fovrt.frameIndex"] = int(inputs.frameIndex);  // bit pattern round-trips
    attributes.ints["fovrt.cameraCut"] = inputs.cameraCut ? 1 : 0;
    if (inputs.gazePixel) attributes.floats["fovrt.gazePixel"] = {inputs.gazePixel->x, inputs.gazePixel->y};
    attributes.strings["fovrt.demodulation"] = DemodulationName(inputs.demodulation);
    attributes.doubles["fovrt.timeSeconds"] = inputs.timeSeconds;
    attributes.floats["fovrt.camera"] = CameraToFloats(inputs.camera);
    attributes.floats["fovrt.prevCamera"] = CameraToFloats(inputs.prevCamera);
    // Gradient samples: 8 floats each (integer coordinates are exact in float below 2^24).
    std::vector<float> gradients;
    gradients.reserve(inputs.gradientSamples.size() * 8);
    for (const GradientSample& g : inputs.gradientSamples) {
        gradients.insert(gradients.end(), {float(g.stratum.x), float(g.stratum.y), float(g.pixel.x),
                                           float(g.pixel.y), float(g.prevPixel.x), float(g.prevPixel.y),
                                           g.newLuminance, g.oldLuminance});
    }
    attributes.floats["fovrt.gradientSamples"] = gradients;
    WriteExrLayers(path, width, height, layers, attributes);
}

FrameInputs ReadFrameInputsExr(const std::filesystem::path& path, Plane<uint16_t>* sppMap) {
    ExrImage image = ReadExr(path);
    auto format = image.attributes.strings.find("fovrt.format");
    if (format == image.attributes.strings.end() || format->second != kFrameInputsFormat)
        Fail("EXR '{}' is not a fovrt FrameInputs dump (attribute fovrt.format != '{}')", path.string(),
             kFrameInputsFormat);
    auto intAttr = [&](const char* name) {
        auto it = image.attributes.ints.find(name);
        if (it == image.attributes.ints.end()) Fail("EXR '{}': missing attribute '{}'", path.string(), name);
        return it->second;
    };
    auto floatsAttr = [&](const char* name) -> const std::vector<float>& {
        auto it = image.attributes.floats.find(name);
        if (it == image.attributes.floats.end()) Fail("EXR '{}': missing attribute '{}'", path.string(), name);
        return it->second;
    };
    FrameInputs inputs;
    ReadPlaneLayers(image, inputs);
    inputs.eye = intAttr("fovrt.eye");
    inputs.frameIndex = uint32_t(intAttr("fovrt.frameIndex"));
    inputs.cameraCut = intAttr("fovrt.cameraCut") != 0;
    // Dumps from before the gaze was recorded have none: the denoisers take the image's centre.
    if (auto g = image.attributes.floats.find("fovrt.gazePixel"); g != image.attributes.floats.end()) {
        if (g->second.size() != 2 || !std::isfinite(g->second[0]) || !std::isfinite(g->second[1]))
            Fail("EXR '{}': attribute 'fovrt.gazePixel' is not two finite floats", path.string());
        inputs.gazePixel = vec2(g->second[0], g->second[1]);
    }
    // Dumps from before brdf demodulation have no attribute: they are albedo-demodulated.
    if (auto d = image.attributes.strings.find("fovrt.demodulation"); d != image.attributes.strings.end())
        if (!ParseDemodulation(d->second, inputs.demodulation))
            Fail("EXR '{}': attribute 'fovrt.demodulation' is '{}', not albedo or brdf", path.string(), d->second);
    auto time = image.attributes.doubles.find("fovrt.timeSeconds");
    if (time == image.attributes.doubles.end())
        Fail("EXR '{}': missing attribute 'fovrt.timeSeconds'", path.string());
    inputs.timeSeconds = time->second;
    inputs.camera = CameraFromFloats(floatsAttr("fovrt.camera"), path, "fovrt.camera");
    inputs.prevCamera = CameraFromFloats(floatsAttr("fovrt.prevCamera"), path, "fovrt.prevCamera");
    const std::vector<float>& g = floatsAttr("fovrt.gradientSamples");
    if (g.size() % 8 != 0) Fail("EXR '{}': attribute 'fovrt.gradientSamples' size {} is not a multiple of 8", path.string(), g.size());
    for (size_t i = 0; i < g.size(); i += 8) {
        inputs.gradientSamples.push_back(GradientSample{ivec2(int(g[i]), int(g[i + 1])),
                                                        ivec2(int(g[i + 2]), int(g[i + 3])),
                                                        ivec2(int(g[i + 4]), int(g[i + 5])), g[i + 6], g[i + 7]});
    }
    if (sppMap) {
        if (image.Has("spp")) ReadUintPlane(image, "spp", *sppMap);
        else *sppMap = Plane<uint16_t>();
    }
    return inputs;
}

void WriteRgbExr(const std::filesystem::path& path, const Plane<vec3>& image, ExrStorage storage) {
    WriteExrLayers(path, image.width(), image.height(),
                   {ExrLayer::FromPlane("", image, {"R", "G", "B"}, storage)});
}

Plane<vec3> ReadRgbExr(const std::filesystem::path& path, const std::string& layer) {
    ExrImage image = ReadExr(path);
    std::string prefix = layer.empty() ? "" : layer + ".";
    Plane<vec3> plane;
    ReadFloatPlane(image, "", {prefix + "R", prefix + "G", prefix + "B"}, plane);
    return plane;
}

}  // namespace fovrt
