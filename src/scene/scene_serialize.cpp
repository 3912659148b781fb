#include "scene/scene_serialize.h"

#include <bit>
#include <cstdint>
#include <string_view>
#include <type_traits>
#include <vector>

namespace fovrt {
namespace {

// Raw bytes are the canonical form only where they carry no padding and the byte order is fixed.
static_assert(std::endian::native == std::endian::little, "the stream is little-endian");
static_assert(sizeof(vec2) == 8 && sizeof(vec3) == 12 && sizeof(vec4) == 16 && sizeof(uvec3) == 12 &&
              sizeof(quat) == 16);

// Batches small values so the sink sees few large chunks; big arrays go straight through.
class StreamWriter {
public:
    explicit StreamWriter(const ByteSink& sink) : sink_(sink) { buffer_.reserve(kBufferBytes); }
    ~StreamWriter() { Flush(); }

    template <typename T>
    void Value(const T& v) {
        static_assert(std::is_arithmetic_v<T> || std::is_same_v<T, vec2> || std::is_same_v<T, vec3> ||
                      std::is_same_v<T, vec4> || std::is_same_v<T, uvec3> || std::is_same_v<T, quat>);
        Bytes(&v, sizeof(T));
    }
    void Bool(bool b) { Value(uint8_t(b ? 1 : 0)); }
    void Count(size_t n) { Value(uint64_t(n)); }
    void Tag(std::string_view tag) {
        Count(tag.size());
        Bytes(tag.data(), tag.size());
    }
    template <typename T>
    void Array(const std::vector<T>& v) {
        Count(v.size());
        if (v.empty()) return;
        Value(v.front());  // checks T is a padding-free value type
        Bytes(v.data() + 1, (v.size() - 1) * sizeof(T));
    }

private:
    static constexpr size_t kBufferBytes = 1 << 16;
    void Bytes(const void* data, size_t size) {
        if (buffer_.size() + size > kBufferBytes) Flush();
        if (size > kBufferBytes) {
            sink_(data, size);
            return;
        }
        const auto* p = static_cast<const uint8_t*>(data);
        buffer_.insert(buffer_.end(), p, p + size);
    }
    void Flush() {
        if (!buffer_.empty()) sink_(buffer_.data(), buffer_.size());
        buffer_.clear();
    }
    const ByteSink& sink_;
    std::vector<uint8_t> buffer_;
};

// Each Write binds every field of its struct by name: a new field breaks the binding (wrong
// count), so it cannot be forgotten here. Fields that never change an image are named and voided.

void Write(StreamWriter& out, const Pose& pose) {
    const auto& [orientation, position] = pose;
    out.Value(orientation);
    out.Value(position);
}

void Write(StreamWriter& out, const std::vector<TransformKey>& keys) {
    out.Count(keys.size());
    for (const TransformKey& key : keys) {
        const auto& [time, pose, scale] = key;
        out.Value(time);
        Write(out, pose);
        out.Value(scale);
    }
}

void Write(StreamWriter& out, const Mesh& mesh) {
    const auto& [name, positions, normals, uvs, triangles, materials] = mesh;
    (void)name;
    out.Array(positions);
    out.Array(normals);
    out.Array(uvs);
    out.Array(triangles);
    out.Array(materials);
}

void Write(StreamWriter& out, const Material& material) {
    const auto& [name, baseColor, baseColorTexture, roughness, metallic, metallicRoughnessTexture,
                 roughnessTexture, metallicTexture, specular, emission, emissionTwoSided] = material;
    (void)name;
    out.Value(baseColor);
    out.Value(int32_t(baseColorTexture));
    out.Value(roughness);
    out.Value(metallic);
    out.Value(int32_t(metallicRoughnessTexture));
    out.Value(specular);
    out.Value(emission);
    out.Bool(emissionTwoSided);
    // Scene-file roughness / metallic maps: only when present, so that the stream (and the
    // reference-cache keys) of scenes without them is what it was before they existed.
    if (roughnessTexture >= 0 || metallicTexture >= 0) {
        out.Value(int32_t(roughnessTexture));
        out.Value(int32_t(metallicTexture));
    }
}

void Write(StreamWriter& out, const Texture& texture) {
    const auto& [path, width, height, texels] = texture;
    (void)path;  // the texels are the content
    out.Value(int32_t(width));
    out.Value(int32_t(height));
    out.Array(texels);
}

void Write(StreamWriter& out, const Instance& instance) {
    const auto& [name, mesh, keys, loop] = instance;
    (void)name;
    out.Value(mesh);
    Write(out, keys);
    out.Bool(loop);
}

void Write(StreamWriter& out, const Light& light) {
    const auto& [name, type, color, intensity, position, direction, spotInner, spotOuter, path,
                 pathLoop, aimAtTarget, target, switchPeriod, switchOnDuration, switchOffset] = light;
    (void)name;
    out.Value(int32_t(type));
    out.Value(color);
    out.Value(intensity);
    out.Value(position);
    out.Value(direction);
    out.Value(spotInner);
    out.Value(spotOuter);
    Write(out, path);
    out.Bool(pathLoop);
    out.Bool(aimAtTarget);
    out.Value(target);
    out.Value(switchPeriod);
    out.Value(switchOnDuration);
    out.Value(switchOffset);
}

void Write(StreamWriter& out, const Scene::EmissionSwitch& s) {
    const auto& [instance, period, onDuration, offset] = s;
    out.Value(instance);
    out.Value(period);
    out.Value(onDuration);
    out.Value(offset);
}

void Write(StreamWriter& out, const CameraKey& key) {
    const auto& [time, pose] = key;
    out.Value(time);
    Write(out, pose);
}

template <typename T>
void WriteAll(StreamWriter& out, const std::vector<T>& items) {
    out.Count(items.size());
    for (const T& item : items) Write(out, item);
}

}  // namespace

void SerializeScene(const Scene& scene, const ByteSink& sink) {
    StreamWriter out(sink);
    out.Tag("fovrt-scene-v1");
    const auto& [name, sourcePath, files, meshes, materials, textures, instances, lights, emissionSwitches,
                 cameraPath, cameraLoop, horizontalFovDegrees, frameRate, background] = scene;
    (void)name;
    (void)sourcePath;
    (void)files;  // their content is what the fields here hold
    WriteAll(out, meshes);
    WriteAll(out, materials);
    WriteAll(out, textures);
    WriteAll(out, instances);
    WriteAll(out, lights);
    WriteAll(out, emissionSwitches);
    WriteAll(out, cameraPath);
    out.Bool(cameraLoop);
    out.Value(horizontalFovDegrees);
    out.Value(frameRate);
    out.Value(background);
}

}  // namespace fovrt
