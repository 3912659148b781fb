// Existing configurations keep their maps: every model at its defaults and under a ray budget
// produces, byte for byte, the maps it produced before the spp range reached below one sample
// (FNV-1a of the uint16 maps over a few gazes and frames, recorded from that code).
#include "foveation/spp_model.h"
#include "gaze/gaze_source.h"
#include "test_support.h"

using namespace fovrt;

namespace {

uint64_t Fnv1a(uint64_t hash, uint16_t value) {
    for (int byte = 0; byte < 2; ++byte) {
        hash ^= uint64_t((value >> (8 * byte)) & 0xffu);
        hash *= 1099511628211ull;
    }
    return hash;
}

// The maps of four gazes × three frames at 96×64 (100° wide), hashed in order.
uint64_t MapsHash(const FoveationParams& p) {
    const int w = 96, h = 64;
    EyeCamera cam(Pose(), Fov::FromHorizontal(Radians(100.0f), float(w) / h), w, h);
    auto model = CreateSppModel(p);
    uint64_t hash = 14695981039346656037ull;
    Plane<uint16_t> spp;
    for (vec2 angles : {vec2(0, 0), vec2(12, -7), vec2(-30, 15), vec2(41, 22)})
        for (uint32_t frame : {0u, 1u, 977u}) {
            model->Generate(cam, GazeDirectionFromAngles(angles.x, angles.y), frame, spp);
            for (size_t i = 0; i < spp.size(); ++i) hash = Fnv1a(hash, spp[i]);
        }
    return hash;
}

}  // namespace

TEST_CASE("Every model's maps at its defaults and under a budget are unchanged", "[foveation]") {
    struct Golden {
        const char* model;
        int64_t budget;  // samples per eye per frame at 96×64 (0 = none)
        uint64_t hash;
    };
    const Golden goldens[] = {
        {"disc", 0, 0xfc6e34b56b796844ull},     {"linear", 0, 0x563f4950b0bd4f6bull},
        {"acuity", 0, 0x265338df54351358ull},   {"uniform", 0, 0x003c181d73d8a325ull},
        {"disc", 12000, 0x0fbedddf6244fc3full}, {"linear", 12000, 0xd5d7419a92aac167ull},
        {"acuity", 12000, 0x7e589fc26713e1afull}, {"uniform", 12000, 0xd5ef2517f8ffa325ull},
        {"disc", 6144, 0x003c181d73d8a325ull},  {"acuity", 90000, 0x5d887c08019db2f4ull},
    };
    for (const Golden& g : goldens) {
        FoveationParams p;
        p.model = g.model;
        p.rayBudget = g.budget;
        const uint64_t hash = MapsHash(p);
        INFO(g.model << " budget " << g.budget);
        CHECK(hash == g.hash);
    }
}
