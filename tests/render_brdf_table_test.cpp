// The F_β table (render/brdf_table.h, SPEC §6) holds the pre-integrated reflectance of the
// tracer's own BSDF: against an independent 2^20-point quadrature, against the furnace test's
// GGX albedo at normal incidence, against SPEC §6's reference values, and against the mean
// weight of the tracer's own BSDF sampling.
#include <chrono>
#include <cmath>

#include "core/rng.h"
#include "ggx_quadrature.h"
#include "render/brdf_table.h"
#include "render/bsdf.h"
#include "render/sampler.h"
#include "test_support.h"

using namespace fovrt;
using namespace fovrt::test;

namespace {

const BrdfTable& Table() {
    static bool printed = false;
    auto start = std::chrono::steady_clock::now();
    const BrdfTable& t = SharedBrdfTable();
    if (!printed) {
        printed = true;
        double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        WARN("F_beta table 256x256 built in " << t.buildSeconds() << " s (first use: " << seconds << " s)");
    }
    return t;
}

}  // namespace

TEST_CASE("the table's entries match a 2^20-point quadrature within 2e-3", "[render]") {
    const BrdfTable& t = Table();
    REQUIRE(t.size() == 256);
    const int mus[] = {2, 25, 70, 128, 200, 255};
    const int roughs[] = {5, 13, 40, 100, 180, 250};
    int checked = 0;
    for (int i : mus)
        for (int j : roughs) {
            const float mu = t.TexelMu(i), r = t.TexelRoughness(j);
            const GgxChannels q = GgxChannelsByQuadrature(mu, GgxAlphaFromRoughness(r));
            const BrdfChannels& e = t.Texel(i, j);
            INFO("mu " << mu << " r " << r << ": table A " << e.a << " B " << e.b << " C " << e.c
                       << ", quadrature A " << q.a << " B " << q.b << " C " << q.c);
            CHECK(std::abs(e.a - q.a) < 2e-3);
            CHECK(std::abs(e.b - q.b) < 2e-3);
            CHECK(std::abs(e.c - q.c) < 2e-3);
            ++checked;
        }
    CHECK(checked >= 32);
}

TEST_CASE("A + B at normal incidence is the GGX albedo of the furnace test", "[render]") {
    const BrdfTable& t = Table();
    for (float r : {0.1f, 0.3f, 0.5f, 0.8f, 1.0f}) {
        const double albedo = GgxAlbedoNormalIncidence(GgxAlphaFromRoughness(r));
        const vec2 ab = IntegrateSpecularChannels(1.0f, GgxAlphaFromRoughness(r), 1u << 14, 7u);
        const BrdfChannels l = t.Lookup(1.0f, r);
        INFO("r " << r << " albedo " << albedo << " integrated A+B " << ab.x + ab.y << " table A+B " << l.a + l.b);
        CHECK(std::abs(ab.x + ab.y - albedo) < 1e-3);
        CHECK(std::abs(l.a + l.b - albedo) < 2e-3);
    }
}

TEST_CASE("the table reproduces SPEC section 6's reference values", "[render]") {
    const BrdfTable& t = Table();
    struct Ref {
        float mu, r, a, b, c;  // c < 0: not given
    };
    const Ref refs[] = {
        {1.0f, 0.0f, 1.000f, 0.0f, -1.0f},  {1.0f, 0.5f, 0.916f, -1.0f, -1.0f},
        {1.0f, 1.0f, 0.306f, -1.0f, -1.0f}, {0.5f, 0.5f, 0.835f, 0.022f, 0.00495f},
        {0.1f, 0.5f, 0.752f, 0.140f, 0.0210f}, {0.2f, 0.05f, 0.672f, 0.328f, 0.0153f},
    };
    for (const Ref& ref : refs) {
        const BrdfChannels l = t.Lookup(ref.mu, ref.r);
        INFO("mu " << ref.mu << " r " << ref.r << ": A " << l.a << " B " << l.b << " C " << l.c);
        CHECK(std::abs(l.a - ref.a) < 2e-3);
        if (ref.b >= 0.0f) CHECK(std::abs(l.b - ref.b) < 2e-3);
        if (ref.c >= 0.0f) CHECK(std::abs(l.c - ref.c) < 2e-4);
    }
    // F_beta exceeds 1 at grazing angles for a white dielectric (SPEC §6: 1.29).
    const vec3 white = PreintegratedReflectance(t, MakeBsdfParams(vec3(1.0f), 0.05f, 0.0f, 1.0f), 0.2f);
    INFO("white dielectric F_beta(0.2, 0.05) " << white.x);
    CHECK(white.x > 1.28f);
    CHECK(white.x < 1.31f);
}

TEST_CASE("the tracer's own BSDF sampling averages to F_beta within 3e-3", "[render]") {
    const BrdfTable& t = Table();
    Pcg32 rng(2024);
    const uint32_t n = 1u << 20;
    for (int trial = 0; trial < 24; ++trial) {
        const float mu = 0.05f + 0.95f * rng.NextFloat();
        const float r = rng.NextFloat();
        const vec3 base(rng.NextFloat(), rng.NextFloat(), rng.NextFloat());
        // Metals, dielectrics and blends; the last trial is pure Lambert (specular 0).
        const float metallic = trial % 3 == 0 ? 1.0f : trial % 3 == 1 ? 0.0f : rng.NextFloat();
        const float specular = trial == 23 ? 0.0f : 1.0f;
        const BsdfParams p = MakeBsdfParams(base, r, trial == 23 ? 0.0f : metallic, specular);
        const vec3 wo(std::sqrt(1.0f - mu * mu), 0.0f, mu);
        const BsdfWo w = PrepareBsdfWo(p, wo);
        glm::dvec3 sum(0.0);
        const uint32_t seed = HashCombine(99u, uint32_t(trial));
        for (uint32_t k = 0; k < n; ++k) {
            BsdfSample s;
            const vec2 sel = SobolOwen2D(seed, k, 1);
            if (SampleBsdf(p, w, SobolOwen2D(seed, k, 0), sel.x, s)) sum += glm::dvec3(s.weight);
        }
        const vec3 sampled = vec3(sum / double(n));
        const vec3 fBeta = PreintegratedReflectance(t, p, mu);
        INFO("trial " << trial << " mu " << mu << " r " << r << " metallic " << metallic << " base (" << base.x
                      << ", " << base.y << ", " << base.z << "): sampled (" << sampled.x << ", " << sampled.y
                      << ", " << sampled.z << ") F_beta (" << fBeta.x << ", " << fBeta.y << ", " << fBeta.z << ")");
        for (int c = 0; c < 3; ++c) CHECK(std::abs(sampled[c] - fBeta[c]) < 3e-3f);
    }
}

TEST_CASE("bilinear lookups return texel centres exactly and extrapolate over the outer half texel", "[render]") {
    const BrdfTable t = BrdfTable::Build(8, 64, 64);
    const BrdfChannels& e = t.Texel(3, 5);
    const BrdfChannels l = t.Lookup(t.TexelMu(3), t.TexelRoughness(5));
    CHECK(l.a == Approx(e.a).margin(1e-6));
    CHECK(l.b == Approx(e.b).margin(1e-6));
    CHECK(l.c == Approx(e.c).margin(1e-6));
    const BrdfChannels edge = t.Lookup(1.5f, t.TexelRoughness(0));  // μ clamped to 1: 1.5 texels past texel 6
    CHECK(edge.a == Approx(t.Texel(6, 0).a + 1.5f * (t.Texel(7, 0).a - t.Texel(6, 0).a)).margin(1e-6));
    const BrdfChannels mid = t.Lookup(0.5f, t.TexelRoughness(0));  // halfway between texels 3 and 4
    CHECK(mid.a == Approx(0.5f * (t.Texel(3, 0).a + t.Texel(4, 0).a)).margin(1e-6));
}

TEST_CASE("the per-pixel F_beta of the tracer costs a table lookup (timing printed)", "[render]") {
    const BrdfTable& t = Table();
    const BsdfParams p = MakeBsdfParams(vec3(0.9f, 0.6f, 0.5f), 0.4f, 0.5f, 1.0f);
    const int n = 1 << 22;
    vec3 sum(0.0f);
    auto start = std::chrono::steady_clock::now();
    for (int i = 0; i < n; ++i) sum += PreintegratedReflectance(t, p, 0.05f + 0.9f * float(i & 1023) / 1024.0f);
    const double ns = std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - start).count() / n;
    WARN("PreintegratedReflectance: " << ns << " ns per call (one thread)");
    CHECK(IsFinite(sum));
}
