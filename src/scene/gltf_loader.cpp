// glTF 2.0 (.gltf with embedded or external buffers, .glb) through tinygltf. Each node that
// references a mesh becomes one part (-> one Instance); the node's world matrix from the scene
// hierarchy is baked into that part's vertices so instances only carry the scene-file transform.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <set>

#include <tiny_gltf.h>

#include "core/error.h"
#include "scene/loaders.h"

namespace fovrt::detail {
namespace {

struct GltfReader {
    const tinygltf::Model& model;
    const std::string& file;

    // Reads accessor `index` as `components` floats per element. Integer components are
    // normalised when the accessor says so (texture coordinates may be u8/u16 normalised).
    std::vector<float> Floats(int index, int components, const std::string& what) const {
        const tinygltf::Accessor& accessor = Accessor(index, what);
        if (tinygltf::GetNumComponentsInType(uint32_t(accessor.type)) != components)
            Fail("{}: accessor {} ({}) has {} components, expected {}", file, index, what,
                 tinygltf::GetNumComponentsInType(uint32_t(accessor.type)), components);
        std::vector<float> out;
        ForEach(accessor, index, what, [&](size_t i, int c, const unsigned char* p) {
            if (out.empty()) out.resize(accessor.count * size_t(components));  // bounds checked by now
            float v = 0.0f;
            switch (accessor.componentType) {
            case TINYGLTF_COMPONENT_TYPE_FLOAT: std::memcpy(&v, p, 4); break;
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: v = float(*p) / (accessor.normalized ? 255.0f : 1.0f); break;
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
                uint16_t s;
                std::memcpy(&s, p, 2);
                v = float(s) / (accessor.normalized ? 65535.0f : 1.0f);
                break;
            }
            default:
                Fail("{}: accessor {} ({}) has unsupported component type {}", file, index, what,
                     accessor.componentType);
            }
            out[i * size_t(components) + size_t(c)] = v;
        });
        return out;
    }

    std::vector<uint32_t> Indices(int index) const {
        const tinygltf::Accessor& accessor = Accessor(index, "indices");
        if (tinygltf::GetNumComponentsInType(uint32_t(accessor.type)) != 1)
            Fail("{}: accessor {} (indices) is not SCALAR", file, index);
        std::vector<uint32_t> out;
        ForEach(accessor, index, "indices", [&](size_t i, int, const unsigned char* p) {
            if (out.empty()) out.resize(accessor.count);  // bounds checked by now
            switch (accessor.componentType) {
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: out[i] = *p; break;
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
                uint16_t s;
                std::memcpy(&s, p, 2);
                out[i] = s;
                break;
            }
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: std::memcpy(&out[i], p, 4); break;
            default: Fail("{}: accessor {} (indices) has component type {}", file, index, accessor.componentType);
            }
        });
        return out;
    }

    const tinygltf::Accessor& Accessor(int index, const std::string& what) const {
        if (index < 0 || size_t(index) >= model.accessors.size())
            Fail("{}: {} refers to accessor {} (of {})", file, what, index, model.accessors.size());
        const tinygltf::Accessor& accessor = model.accessors[size_t(index)];
        if (accessor.sparse.isSparse) Fail("{}: accessor {} ({}) is sparse (unsupported)", file, index, what);
        return accessor;
    }

    // Calls f(element, component, bytes) for every component, with all bounds checked.
    template <typename F>
    void ForEach(const tinygltf::Accessor& accessor, int index, const std::string& what, F&& f) const {
        if (accessor.count == 0) return;
        if (accessor.bufferView < 0 || size_t(accessor.bufferView) >= model.bufferViews.size())
            Fail("{}: accessor {} ({}) has no valid bufferView", file, index, what);
        const tinygltf::BufferView& view = model.bufferViews[size_t(accessor.bufferView)];
        if (view.buffer < 0 || size_t(view.buffer) >= model.buffers.size())
            Fail("{}: bufferView {} has no valid buffer", file, accessor.bufferView);
        const tinygltf::Buffer& buffer = model.buffers[size_t(view.buffer)];
        int componentSize = tinygltf::GetComponentSizeInBytes(uint32_t(accessor.componentType));
        int components = tinygltf::GetNumComponentsInType(uint32_t(accessor.type));
        if (componentSize <= 0 || components <= 0)
            Fail("{}: accessor {} ({}) has an invalid type", file, index, what);
        size_t elementSize = size_t(componentSize) * size_t(components);
        size_t stride = view.byteStride ? view.byteStride : elementSize;
        if (stride < elementSize) Fail("{}: bufferView {} stride {} < element size {}", file, accessor.bufferView, stride, elementSize);
        // Overflow-safe range check: begin + stride * (count - 1) + elementSize <= limit.
        size_t viewEnd = view.byteOffset + view.byteLength;
        if (view.byteOffset > buffer.data.size() || view.byteLength > buffer.data.size() - view.byteOffset)
            Fail("{}: bufferView {} exceeds buffer {} ({} bytes)", file, accessor.bufferView, view.buffer, buffer.data.size());
        size_t begin = view.byteOffset + accessor.byteOffset;
        if (accessor.byteOffset > view.byteLength || accessor.count > (size_t(1) << 40) / stride ||
            begin + stride * (accessor.count - 1) + elementSize > viewEnd)
            Fail("{}: accessor {} ({}) exceeds its bufferView {}", file, index, what, accessor.bufferView);
        for (size_t i = 0; i < accessor.count; ++i) {
            const unsigned char* element = buffer.data.data() + begin + i * stride;
            for (int c = 0; c < components; ++c) f(i, c, element + size_t(c) * size_t(componentSize));
        }
    }
};

mat4 NodeMatrix(const tinygltf::Node& node, const std::string& file) {
    mat4 m(1.0f);
    if (node.matrix.size() == 16) {
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r) m[c][r] = float(node.matrix[size_t(c * 4 + r)]);  // column-major
    } else {
        mat4 t(1.0f), r(1.0f), s(1.0f);
        if (node.translation.size() == 3)
            t = glm::translate(mat4(1.0f), vec3(float(node.translation[0]), float(node.translation[1]),
                                                float(node.translation[2])));
        if (node.rotation.size() == 4)  // glTF (x, y, z, w); glm::quat(w, x, y, z)
            r = glm::mat4_cast(glm::normalize(quat(float(node.rotation[3]), float(node.rotation[0]),
                                                   float(node.rotation[1]), float(node.rotation[2]))));
        if (node.scale.size() == 3)
            s = glm::scale(mat4(1.0f), vec3(float(node.scale[0]), float(node.scale[1]), float(node.scale[2])));
        m = t * r * s;
    }
    for (int c = 0; c < 4; ++c)
        if (!IsFinite(vec3(m[c])) || !std::isfinite(m[c][3]))
            Fail("{}: node '{}' has a non-finite transform", file, node.name);
    return m;
}

int TextureIndex(const tinygltf::Model& model, int gltfTexture, bool srgb, const std::string& file,
                 const std::string& what, LoadContext& context) {
    if (gltfTexture < 0) return -1;
    if (size_t(gltfTexture) >= model.textures.size()) Fail("{}: {} refers to texture {} (of {})", file, what, gltfTexture, model.textures.size());
    int source = model.textures[size_t(gltfTexture)].source;
    if (source < 0 || size_t(source) >= model.images.size()) Fail("{}: texture {} has no valid image source", file, gltfTexture);
    const tinygltf::Image& image = model.images[size_t(source)];
    std::string key = file + "#image" + std::to_string(source) + (image.uri.empty() ? "" : ":" + image.uri);
    if (auto it = context.textures.find({key, srgb}); it != context.textures.end()) return it->second;
    size_t bytesPerChannel = image.bits == 16 ? 2 : 1;
    if (image.width <= 0 || image.height <= 0 || image.component < 1 || image.component > 4 ||
        (image.bits != 8 && image.bits != 16) ||
        image.image.size() < size_t(image.width) * size_t(image.height) * size_t(image.component) * bytesPerChannel)
        Fail("{}: image {} ('{}') could not be decoded", file, source, image.uri);
    context.scene.textures.push_back(TextureFromPixels(key, image.width, image.height, image.component,
                                                       image.bits, image.image.data(), srgb));
    int index = int(context.scene.textures.size()) - 1;
    context.textures[{key, srgb}] = index;
    return index;
}

Material ConvertMaterial(const tinygltf::Model& model, int index, const std::string& file,
                         LoadContext& context) {
    const tinygltf::Material& m = model.materials[size_t(index)];
    const auto& pbr = m.pbrMetallicRoughness;
    Material out;
    out.name = m.name.empty() ? fmt::format("{}/material{}", std::filesystem::path(file).stem().string(), index) : m.name;
    std::string what = fmt::format("material '{}'", out.name);
    // The colour rule of the MTL reader and the scene file's overrides, on the file's doubles
    // before they become floats (3e38 is a finite float whose square is not).
    auto checkColour = [&](const std::string& key, const std::vector<double>& values) {
        std::string problem = MaterialColourProblem(values);
        if (!problem.empty()) Fail("{}: {}: {}: {}", file, what, key, problem);
    };
    checkColour("pbrMetallicRoughness.baseColorFactor", pbr.baseColorFactor);
    if (pbr.baseColorFactor.size() >= 3)
        out.baseColor = vec3(float(pbr.baseColorFactor[0]), float(pbr.baseColorFactor[1]), float(pbr.baseColorFactor[2]));
    out.metallic = float(pbr.metallicFactor);
    out.roughness = float(pbr.roughnessFactor);
    checkColour("emissiveFactor", m.emissiveFactor);
    std::vector<double> emission = m.emissiveFactor.size() == 3 ? m.emissiveFactor : std::vector<double>{0.0, 0.0, 0.0};
    if (auto it = m.extensions.find("KHR_materials_emissive_strength"); it != m.extensions.end()) {
        const std::string key = "KHR_materials_emissive_strength.emissiveStrength";
        const tinygltf::Value& strength = it->second.Get("emissiveStrength");
        if (strength.Type() != tinygltf::NULL_TYPE) {  // absent: the extension's default, 1
            if (!strength.IsNumber()) Fail("{}: {}: {}: not a number", file, what, key);
            checkColour(key, {strength.GetNumberAsDouble()});
            for (double& c : emission) c *= strength.GetNumberAsDouble();
            checkColour("emissiveFactor * " + key, emission);
        }
    }
    out.emission = vec3(float(emission[0]), float(emission[1]), float(emission[2]));
    out.emissionTwoSided = m.doubleSided;  // glTF's back-face flag; the BSDF is two-sided anyway
    if (!IsFinite(out.baseColor) || !IsFinite(out.emission) || !std::isfinite(out.metallic) || !std::isfinite(out.roughness))
        Fail("{}: {} has non-finite factors", file, what);
    out.metallic = std::clamp(out.metallic, 0.0f, 1.0f);
    out.roughness = std::clamp(out.roughness, 0.0f, 1.0f);
    out.baseColorTexture = TextureIndex(model, pbr.baseColorTexture.index, true, file, what, context);
    out.metallicRoughnessTexture = TextureIndex(model, pbr.metallicRoughnessTexture.index, false, file, what, context);
    return out;
}

}  // namespace

std::vector<MeshPart> LoadGltf(const std::filesystem::path& path, LoadContext& context) {
    const std::string file = path.lexically_normal().string();
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) Fail("{}: glTF file not found", file);
    tinygltf::Model model;
    tinygltf::TinyGLTF loader;
    std::string err, warn;
    bool binary = path.extension() == ".glb" || path.extension() == ".GLB";
    bool ok = false;
    try {
        ok = binary ? loader.LoadBinaryFromFile(&model, &err, &warn, file)
                    : loader.LoadASCIIFromFile(&model, &err, &warn, file);
    } catch (const std::exception& e) {
        Fail("{}: cannot parse glTF: {}", file, e.what());
    }
    if (!ok) {
        std::string first = err.substr(0, err.find('\n'));
        Fail("{}: cannot load glTF: {}", file, first.empty() ? "parse error" : first);
    }
    // The files it read: itself, and the buffers and images it names by a relative URI (not data: URIs).
    context.Read(path);
    auto readUri = [&](const std::string& uri) {
        if (!uri.empty() && uri.rfind("data:", 0) != 0) context.Read(path.parent_path() / uri);
    };
    for (const auto& buffer : model.buffers) readUri(buffer.uri);
    for (const auto& image : model.images) readUri(image.uri);
    GltfReader reader{model, file};

    // Which nodes to instantiate: the default scene's roots, else every node that is nobody's child.
    std::vector<int> roots;
    if (!model.scenes.empty()) {
        int s = model.defaultScene >= 0 && size_t(model.defaultScene) < model.scenes.size() ? model.defaultScene : 0;
        roots = model.scenes[size_t(s)].nodes;
    } else {
        std::set<int> children;
        for (const auto& node : model.nodes) children.insert(node.children.begin(), node.children.end());
        for (size_t i = 0; i < model.nodes.size(); ++i)
            if (!children.count(int(i))) roots.push_back(int(i));
    }

    std::vector<int> materialMap(model.materials.size(), -1);
    int defaultMaterial = -1;
    auto sceneMaterial = [&](int gltfMaterial) -> uint32_t {
        if (gltfMaterial >= 0 && size_t(gltfMaterial) < model.materials.size()) {
            int& mapped = materialMap[size_t(gltfMaterial)];
            if (mapped < 0) {
                context.scene.materials.push_back(ConvertMaterial(model, gltfMaterial, file, context));
                mapped = int(context.scene.materials.size()) - 1;
            }
            return uint32_t(mapped);
        }
        if (gltfMaterial >= 0) Fail("{}: primitive refers to material {} (of {})", file, gltfMaterial, model.materials.size());
        if (defaultMaterial < 0) {
            Material m;
            m.name = path.stem().string() + "/default";
            context.scene.materials.push_back(m);
            defaultMaterial = int(context.scene.materials.size()) - 1;
        }
        return uint32_t(defaultMaterial);
    };

    std::vector<MeshPart> parts;
    std::set<int> onPath;
    std::function<void(int, const mat4&, int)> visit = [&](int nodeIndex, const mat4& parent, int depth) {
        if (nodeIndex < 0 || size_t(nodeIndex) >= model.nodes.size())
            Fail("{}: node index {} out of range ({} nodes)", file, nodeIndex, model.nodes.size());
        if (depth > 256 || onPath.count(nodeIndex)) Fail("{}: node hierarchy has a cycle at node {}", file, nodeIndex);
        onPath.insert(nodeIndex);
        const tinygltf::Node& node = model.nodes[size_t(nodeIndex)];
        mat4 world = parent * NodeMatrix(node, file);
        if (node.mesh >= 0) {
            if (size_t(node.mesh) >= model.meshes.size())
                Fail("{}: node {} refers to mesh {} (of {})", file, nodeIndex, node.mesh, model.meshes.size());
            const tinygltf::Mesh& gltfMesh = model.meshes[size_t(node.mesh)];
            Mesh mesh;
            mesh.name = gltfMesh.name.empty() ? fmt::format("mesh{}", node.mesh) : gltfMesh.name;
            mat3 normalMatrix = glm::transpose(glm::inverse(mat3(world)));
            // glTF: a mirroring world matrix makes clockwise the front; the baked triangles keep
            // counter-clockwise = front (the side one-sided emitters light).
            const bool mirrored = glm::determinant(mat3(world)) < 0.0f;
            bool anyNormals = false, anyUvs = false;
            for (size_t p = 0; p < gltfMesh.primitives.size(); ++p) {
                const tinygltf::Primitive& prim = gltfMesh.primitives[p];
                if (prim.mode != -1 && prim.mode != TINYGLTF_MODE_TRIANGLES) continue;  // points/lines/strips
                std::string what = fmt::format("mesh '{}' primitive {}", mesh.name, p);
                auto position = prim.attributes.find("POSITION");
                if (position == prim.attributes.end()) Fail("{}: {} has no POSITION", file, what);
                std::vector<float> pos = reader.Floats(position->second, 3, what + " POSITION");
                size_t count = pos.size() / 3, base = mesh.positions.size();
                std::vector<float> nrm, uv;
                if (auto it = prim.attributes.find("NORMAL"); it != prim.attributes.end()) {
                    nrm = reader.Floats(it->second, 3, what + " NORMAL");
                    if (nrm.size() != pos.size()) Fail("{}: {} NORMAL count differs from POSITION", file, what);
                    anyNormals = true;
                }
                if (auto it = prim.attributes.find("TEXCOORD_0"); it != prim.attributes.end()) {
                    uv = reader.Floats(it->second, 2, what + " TEXCOORD_0");
                    if (uv.size() != 2 * count) Fail("{}: {} TEXCOORD_0 count differs from POSITION", file, what);
                    anyUvs = true;
                }
                for (size_t i = 0; i < count; ++i) {
                    vec3 p3(pos[3 * i], pos[3 * i + 1], pos[3 * i + 2]);
                    if (!IsFinite(p3)) Fail("{}: {} POSITION vertex {} is not finite", file, what, i);
                    mesh.positions.push_back(vec3(world * vec4(p3, 1.0f)));
                    vec3 n = nrm.empty() ? vec3(0.0f) : normalMatrix * vec3(nrm[3 * i], nrm[3 * i + 1], nrm[3 * i + 2]);
                    mesh.normals.push_back(n);  // zero: filled from faces by FinishMesh
                    mesh.uvs.push_back(uv.empty() ? vec2(0.0f) : vec2(uv[2 * i], uv[2 * i + 1]));
                }
                std::vector<uint32_t> indices;
                if (prim.indices >= 0) {
                    indices = reader.Indices(prim.indices);
                } else {
                    indices.resize(count);
                    for (size_t i = 0; i < count; ++i) indices[i] = uint32_t(i);
                }
                if (indices.size() % 3 != 0) Fail("{}: {} has {} indices (not a multiple of 3)", file, what, indices.size());
                uint32_t material = sceneMaterial(prim.material);
                for (size_t i = 0; i + 2 < indices.size(); i += 3) {
                    for (size_t k = 0; k < 3; ++k)
                        if (indices[i + k] >= count)
                            Fail("{}: {} index {} = {} out of range ({} vertices)", file, what, i + k, indices[i + k], count);
                    uint32_t b = indices[i + (mirrored ? 2 : 1)], c = indices[i + (mirrored ? 1 : 2)];
                    mesh.triangles.push_back(uvec3(base + indices[i], base + b, base + c));
                    mesh.materials.push_back(material);
                }
            }
            if (!anyNormals) mesh.normals.clear();
            if (!anyUvs) mesh.uvs.clear();
            if (!mesh.triangles.empty()) {
                FinishMesh(mesh, file);
                context.scene.meshes.push_back(std::move(mesh));
                std::string name = node.name.empty() ? fmt::format("node{}", nodeIndex) : node.name;
                parts.push_back(MeshPart{uint32_t(context.scene.meshes.size() - 1), name});
            }
        }
        for (int child : node.children) visit(child, world, depth + 1);
        onPath.erase(nodeIndex);
    };
    for (int root : roots) visit(root, mat4(1.0f), 0);
    if (parts.empty()) Fail("{}: glTF file has no triangle meshes", file);
    return parts;
}

}  // namespace fovrt::detail
