#include "render/light_sampler.h"

namespace fovrt {

LightSampler::LightSampler(const Scene& scene) {
    for (uint32_t i = 0; i < scene.instances.size(); ++i) {
        const Mesh& mesh = scene.meshes[scene.instances[i].mesh];
        for (uint32_t t = 0; t < mesh.triangles.size(); ++t) {
            uint32_t mat = mesh.materials.empty() ? 0u : mesh.materials[t];
            if (Luminance(scene.materials[mat].emission) > 0.0f) emissive_.push_back({i, t});
        }
    }
}

void LightSampler::Build(const Scene& scene, const EmbreeScene& embree) {
    cdf_.resize(emissive_.size());
    emitters_.resize(emissive_.size());
    double total = 0.0;
    for (size_t i = 0; i < emissive_.size(); ++i) {
        SurfaceSample s{emissive_[i].instance, emissive_[i].primitive, vec2(1.0f / 3.0f)};
        SurfaceHit hit = embree.Surface(s);
        const Material& m = scene.materials[hit.material];
        const vec3 emission = m.emission * embree.xforms()[s.instance].emissionScale;
        float power = hit.area * SelectionLuminance(emission, m.emissionTwoSided);
        total += double(std::max(power, 0.0f));
        cdf_[i] = float(total);
        // What NEE reads of the triangle, with SurfaceAt's arithmetic (bit-identical points).
        auto p = embree.WorldTriangle(s.instance, s.primitive, embree.xforms());
        Emitter& e = emitters_[i];
        e.p0 = p[0];
        e.e1 = p[1] - p[0];
        e.e2 = p[2] - p[0];
        e.normal = hit.geomNormal;
        e.emission = emission;
        e.twoSided = m.emissionTwoSided;
    }
    power_ = float(total);
}

}  // namespace fovrt
