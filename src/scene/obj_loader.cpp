// OBJ + MTL through tinyobjloader. One file -> one mesh (all groups merged, per-triangle
// materials). A strict pre-scan gives line numbers for non-finite vertices and out-of-range face
// indices (tinyobjloader only warns about them, and reads out of bounds for some polygons).
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string_view>
#include <unordered_map>

#include <tiny_obj_loader.h>

#include "core/error.h"
#include "scene/loaders.h"

namespace fovrt::detail {
namespace {

std::string ReadWholeFile(const std::filesystem::path& file, const std::string& what) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file, ec)) Fail("{}: {} not found", file.string(), what);
    std::ifstream in(file, std::ios::binary);
    if (!in) Fail("{}: cannot open {}", file.string(), what);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

bool IsSpace(char c) { return c == ' ' || c == '\t' || c == '\r'; }

// Splits a line into whitespace-separated tokens.
std::vector<std::string_view> Tokens(std::string_view line) {
    std::vector<std::string_view> out;
    size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && IsSpace(line[i])) ++i;
        size_t start = i;
        while (i < line.size() && !IsSpace(line[i])) ++i;
        if (i > start) out.push_back(line.substr(start, i - start));
    }
    return out;
}

// The whole token as a number ("1.0x" is not one, as the MTL scan holds too).
bool ParseFloat(std::string_view token, double& value) {
    std::string s(token);
    char* end = nullptr;
    value = std::strtod(s.c_str(), &end);
    return end != s.c_str() && end == s.c_str() + s.size();
}

// The usemtl names seen in the OBJ and the first line each appears on.
struct ObjScan {
    std::map<std::string, int> usemtlLine;
    std::string mtllibs;  // the MTL file names, for messages about materials
};

// Calls visit(lineNumber, line) for every line of `text` (numbered from 1, without the newline).
template <typename Visit>
void ForEachLine(const std::string& text, Visit&& visit) {
    size_t pos = 0;
    int lineNumber = 0;
    while (pos <= text.size()) {
        size_t end = text.find('\n', pos);
        if (end == std::string::npos) end = text.size();
        visit(++lineNumber, std::string_view(text.data() + pos, end - pos));
        pos = end + 1;
    }
}

// Validates what tinyobjloader would accept silently or mis-read: coordinates that are not
// finite, faces with < 3 corners, indices that are zero, malformed or out of range.
ObjScan ScanObj(const std::string& text, const std::string& file) {
    ObjScan scan;
    long long counts[3] = {0, 0, 0};  // v, vt, vn declared so far
    ForEachLine(text, [&](int lineNumber, std::string_view line) {
        size_t first = 0;
        while (first < line.size() && IsSpace(line[first])) ++first;
        line.remove_prefix(first);
        if (line.empty() || line[0] == '#') return;
        std::vector<std::string_view> tokens = Tokens(line);
        std::string_view kind = tokens[0];
        if (kind == "v" || kind == "vn" || kind == "vt") {
            // The counts tinyobjloader reads: v x y z [w | r g b], vn x y z, vt u [v [w]]. It
            // ignores anything further, so a stray token is refused here (a '#' comment may follow).
            size_t values = 0;
            while (values + 1 < tokens.size() && tokens[values + 1][0] != '#') ++values;
            const bool countOk = kind == "v" ? values == 3 || values == 4 || values == 6
                                 : kind == "vn" ? values == 3
                                                : values >= 1 && values <= 3;
            for (size_t k = 1; k <= values; ++k) {
                double v = 0.0;
                if (!ParseFloat(tokens[k], v))
                    Fail("{}:{}: '{}' has a malformed number '{}'", file, lineNumber, kind, tokens[k]);
                if (!std::isfinite(v) || std::fabs(v) > 3.0e38)
                    Fail("{}:{}: '{}' coordinate is not finite ({})", file, lineNumber, kind, tokens[k]);
            }
            if (!countOk)
                Fail("{}:{}: '{}' has {} numbers (expected {})", file, lineNumber, kind, values,
                     kind == "v" ? "x y z, x y z w or x y z r g b" : kind == "vn" ? "x y z" : "1 to 3");
            counts[kind == "v" ? 0 : kind == "vt" ? 1 : 2]++;
        } else if (kind == "f") {
            if (tokens.size() < 4) Fail("{}:{}: face needs at least 3 vertices", file, lineNumber);
            for (size_t k = 1; k < tokens.size(); ++k) {
                std::string_view corner = tokens[k];
                for (int slot = 0; slot < 3 && !corner.empty(); ++slot) {
                    size_t slash = corner.find('/');
                    std::string_view field = corner.substr(0, slash);
                    corner = slash == std::string_view::npos ? std::string_view() : corner.substr(slash + 1);
                    if (field.empty()) {
                        if (slot == 0) Fail("{}:{}: face corner '{}' has no vertex index", file, lineNumber, tokens[k]);
                        continue;
                    }
                    long long index = 0;
                    const char* b = field.data();
                    if (*b == '+') ++b;
                    auto [ptr, ec] = std::from_chars(b, field.data() + field.size(), index);
                    if (ec != std::errc() || ptr != field.data() + field.size() || index == 0)
                        Fail("{}:{}: malformed face index '{}'", file, lineNumber, tokens[k]);
                    long long resolved = index > 0 ? index - 1 : counts[slot] + index;
                    if (resolved < 0 || resolved >= counts[slot])
                        Fail("{}:{}: face index {} out of range ({} {} declared so far)", file, lineNumber,
                             index, counts[slot], slot == 0 ? "vertices" : slot == 1 ? "texcoords" : "normals");
                }
            }
        } else if (kind == "mtllib") {
            for (size_t k = 1; k < tokens.size(); ++k) {
                if (!scan.mtllibs.empty()) scan.mtllibs += ' ';
                scan.mtllibs.append(tokens[k]);
            }
        } else if (kind == "usemtl") {
            std::string name = tokens.size() > 1 ? std::string(tokens[1]) : std::string();
            scan.usemtlLine.emplace(name, lineNumber);
        }
    });
    return scan;
}

// Validates the colours of every MTL file the OBJ names, with file:line (tinyobjloader reads
// "nan" as a number it substitutes, and 3e38 as a colour whose square is inf): Kd, Ks, Ke, Ka
// pass the material colour check shared with the scene file's overrides; Ns must be finite.
void ScanMtl(const std::filesystem::path& mtlFile) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(mtlFile, ec)) return;  // tinyobjloader reports it
    const std::string file = mtlFile.lexically_normal().string();
    const std::string text = ReadWholeFile(mtlFile, "MTL file");
    std::string material;
    ForEachLine(text, [&](int lineNumber, std::string_view line) {
        line = line.substr(0, line.find('#'));  // a comment may follow the values
        std::vector<std::string_view> tokens = Tokens(line);
        if (tokens.empty()) return;
        const std::string_view key = tokens[0];
        if (key == "newmtl") {
            material = tokens.size() > 1 ? std::string(tokens[1]) : std::string();
            return;
        }
        const bool colour = key == "Kd" || key == "Ks" || key == "Ke" || key == "Ka";
        if (!colour && key != "Ns") return;
        if (colour && tokens.size() > 1 && tokens[1] == "spectral") return;  // a file, not numbers
        if (colour && tokens.size() > 1 && tokens[1] == "xyz") tokens.erase(tokens.begin() + 1);
        if (tokens.size() < 2) Fail("{}:{}: material '{}': {} needs a value", file, lineNumber, material, key);
        std::vector<double> values;
        for (size_t k = 1; k < tokens.size(); ++k) {
            double v = 0.0;
            char* stop = nullptr;
            std::string token(tokens[k]);
            v = std::strtod(token.c_str(), &stop);
            if (stop != token.c_str() + token.size())
                Fail("{}:{}: material '{}': {}: malformed number '{}'", file, lineNumber, material, key, token);
            values.push_back(v);
        }
        std::string problem = colour ? MaterialColourProblem(values)
                              : std::isfinite(values[0]) && std::fabs(values[0]) <= 1e30
                                  ? std::string()
                                  : fmt::format("{} is not a finite number", tokens[1]);
        if (!problem.empty()) Fail("{}:{}: material '{}': {}: {}", file, lineNumber, material, key, problem);
    });
}

std::vector<std::string> Lines(const std::string& text) {
    std::vector<std::string> out;
    std::istringstream ss(text);
    for (std::string line; std::getline(ss, line);)
        if (!line.empty()) out.push_back(line);
    return out;
}

vec3 ToVec3(const tinyobj::real_t* v) { return vec3(float(v[0]), float(v[1]), float(v[2])); }

float MaxComponent(const vec3& v) { return std::max(v.x, std::max(v.y, v.z)); }

// MTL -> metallic/roughness (documented in scenes/README.md):
//   baseColor = Kd, emission = Ke, roughness = sqrt(2 / (Ns + 2)) clamped to [0.02, 1];
//   Ks beyond a dielectric's 4 %: metallic = lum(Ks) / (lum(Kd) + lum(Ks)),
//   baseColor = mix(Kd, Ks, metallic) (pure-specular MTLs such as conductors become metals);
//   non-metals: specular = clamp(lum(Ks) / 0.04, 0, 1) (Ks 0 -> pure Lambert).
Material ConvertMaterial(const tinyobj::material_t& m, const std::filesystem::path& baseDir,
                         const std::string& objFile, const std::string& mtllibs, LoadContext& context) {
    const std::string file = mtllibs.empty() ? objFile : fmt::format("{} (mtllib {})", objFile, mtllibs);
    Material out;
    out.name = m.name;
    vec3 kd = ToVec3(m.diffuse), ks = ToVec3(m.specular), ke = ToVec3(m.emission);
    float ns = float(m.shininess);
    if (!IsFinite(kd) || !IsFinite(ks) || !IsFinite(ke) || !std::isfinite(ns))
        Fail("{}: material '{}' has a non-finite Kd/Ks/Ke/Ns", file, m.name);
    if (MaxComponent(-kd) > 0.0f || MaxComponent(-ks) > 0.0f || MaxComponent(-ke) > 0.0f)
        Fail("{}: material '{}' has a negative Kd/Ks/Ke", file, m.name);
    out.roughness = std::clamp(std::sqrt(2.0f / (std::max(ns, 0.0f) + 2.0f)), 0.02f, 1.0f);
    float lkd = Luminance(kd), lks = Luminance(ks);
    out.metallic = lks > 0.04f ? lks / (lkd + lks) : 0.0f;
    // Dielectric specular weight (F0 = 0.04 * specular): Ks 0 (or absent) is pure Lambert, as
    // the MTL's Phong model means; lum(Ks) >= 0.04 is the full dielectric interface.
    out.specular = out.metallic > 0.0f ? 1.0f : std::clamp(lks / 0.04f, 0.0f, 1.0f);
    out.baseColor = glm::clamp(glm::mix(kd, ks, out.metallic), vec3(0.0f), vec3(1.0f));
    out.emission = ke;
    if (!m.diffuse_texname.empty()) {
        std::string referrer = fmt::format("{}: material '{}' map_Kd", file, m.name);
        out.baseColorTexture = LoadTextureFile(baseDir / m.diffuse_texname, true, referrer, context);
    }
    return out;
}

struct CornerKey {
    int v, vt, vn;
    bool operator==(const CornerKey&) const = default;
};
struct CornerHash {
    size_t operator()(const CornerKey& k) const {
        uint64_t h = uint64_t(uint32_t(k.v)) * 0x9E3779B97F4A7C15ull;
        h ^= uint64_t(uint32_t(k.vt)) * 0xC2B2AE3D27D4EB4Full + (h << 6) + (h >> 2);
        h ^= uint64_t(uint32_t(k.vn)) * 0x165667B19E3779F9ull + (h << 6) + (h >> 2);
        return size_t(h);
    }
};

}  // namespace

std::vector<MeshPart> LoadObj(const std::filesystem::path& path, LoadContext& context) {
    const std::string file = path.lexically_normal().string();
    const std::string text = ReadWholeFile(path, "OBJ file");
    context.Read(path);
    ObjScan scan = ScanObj(text, file);
    for (std::string_view name : Tokens(scan.mtllibs)) {
        ScanMtl(path.parent_path() / name);
        context.Read(path.parent_path() / name);
    }

    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
    std::vector<tinyobj::material_t> objMaterials;
    std::string warn, err;
    std::filesystem::path baseDir = path.parent_path();
    std::string mtlDir = baseDir.empty() ? std::string("./") : baseDir.string() + "/";
    tinyobj::MaterialFileReader mtlReader(mtlDir);
    std::istringstream in(text);
    bool ok = tinyobj::LoadObj(&attrib, &shapes, &objMaterials, &warn, &err, &in, &mtlReader,
                               /*triangulate=*/true, /*default_vcols_fallback=*/false);
    if (!ok || !err.empty()) {
        auto lines = Lines(err);
        Fail("{}: {}", file, lines.empty() ? std::string("cannot parse OBJ") : lines.front());
    }
    for (const std::string& line : Lines(warn)) {
        if (line.rfind("material [", 0) == 0) {
            // "material [ 'name' ] not found in .mtl"
            size_t a = line.find('\''), b = line.rfind('\'');
            std::string name = (a != std::string::npos && b > a) ? line.substr(a + 1, b - a - 1) : line;
            auto it = scan.usemtlLine.find(name);
            Fail("{}:{}: usemtl '{}': unknown material (not in the MTL file)", file,
                 it != scan.usemtlLine.end() ? it->second : 0, name);
        }
        if (line.rfind("Material file [", 0) == 0 || line.rfind("Failed to load material", 0) == 0)
            Fail("{}: mtllib: {}", file, line);
    }

    // Materials: appended to the scene; triangles without one get a per-file default.
    const uint32_t materialBase = uint32_t(context.scene.materials.size());
    for (const tinyobj::material_t& m : objMaterials)
        context.scene.materials.push_back(ConvertMaterial(m, baseDir, file, scan.mtllibs, context));
    int defaultMaterial = -1;

    const size_t nv = attrib.vertices.size() / 3, nt = attrib.texcoords.size() / 2,
                 nn = attrib.normals.size() / 3;
    Mesh mesh;
    mesh.name = path.stem().string();
    std::unordered_map<CornerKey, uint32_t, CornerHash> corners;
    bool anyNormals = false, anyUvs = false;
    std::vector<uint32_t> polygon;
    for (const tinyobj::shape_t& shape : shapes) {
        size_t offset = 0;
        for (size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f) {
            size_t fv = shape.mesh.num_face_vertices[f];
            polygon.clear();
            for (size_t k = 0; k < fv; ++k) {
                const tinyobj::index_t& idx = shape.mesh.indices.at(offset + k);
                if (idx.vertex_index < 0 || size_t(idx.vertex_index) >= nv ||
                    (idx.texcoord_index >= 0 && size_t(idx.texcoord_index) >= nt) ||
                    (idx.normal_index >= 0 && size_t(idx.normal_index) >= nn))
                    Fail("{}: face {} of group '{}' has an index out of range", file, f, shape.name);
                CornerKey key{idx.vertex_index, idx.texcoord_index, idx.normal_index};
                auto [it, inserted] = corners.emplace(key, uint32_t(mesh.positions.size()));
                if (inserted) {
                    mesh.positions.push_back(ToVec3(&attrib.vertices[3 * size_t(key.v)]));
                    if (key.vn >= 0) {
                        mesh.normals.push_back(ToVec3(&attrib.normals[3 * size_t(key.vn)]));
                        anyNormals = true;
                    } else {
                        mesh.normals.push_back(vec3(0.0f));  // filled from faces by FinishMesh
                    }
                    if (key.vt >= 0) {
                        // OBJ v grows upwards; glTF's (and ours) downwards from the top row.
                        const auto* t = &attrib.texcoords[2 * size_t(key.vt)];
                        mesh.uvs.push_back(vec2(float(t[0]), 1.0f - float(t[1])));
                        anyUvs = true;
                    } else {
                        mesh.uvs.push_back(vec2(0.0f));
                    }
                }
                polygon.push_back(it->second);
            }
            offset += fv;
            int objMaterial = f < shape.mesh.material_ids.size() ? shape.mesh.material_ids[f] : -1;
            uint32_t material;
            if (objMaterial >= 0 && size_t(objMaterial) < objMaterials.size()) {
                material = materialBase + uint32_t(objMaterial);
            } else {
                if (defaultMaterial < 0) {
                    Material m;
                    m.name = mesh.name + "/default";
                    context.scene.materials.push_back(m);
                    defaultMaterial = int(context.scene.materials.size()) - 1;
                }
                material = uint32_t(defaultMaterial);
            }
            for (size_t k = 2; k < polygon.size(); ++k) {  // fan; tinyobj already triangulated
                mesh.triangles.push_back(uvec3(polygon[0], polygon[k - 1], polygon[k]));
                mesh.materials.push_back(material);
            }
        }
    }
    if (mesh.triangles.empty()) Fail("{}: OBJ file has no faces", file);
    if (!anyNormals) mesh.normals.clear();
    if (!anyUvs) mesh.uvs.clear();
    FinishMesh(mesh, file);
    context.scene.meshes.push_back(std::move(mesh));
    return {MeshPart{uint32_t(context.scene.meshes.size() - 1), ""}};
}

}  // namespace fovrt::detail
