// Deterministic quadratures of fovrt's GGX BSDF written independently of render/bsdf.cpp (double
// precision, own formulas), shared by the furnace and F_β table tests.
#pragma once

#include <algorithm>
#include <cmath>

#include "core/math.h"

namespace fovrt::test {

// Directional albedo of a GGX conductor with F = 1 at normal incidence, by quadrature of
// D(h) G2 / (4 cos_o) over the hemisphere.
inline double GgxAlbedoNormalIncidence(double alpha) {
    const int n = 200000;
    double a2 = alpha * alpha, sum = 0.0;
    for (int i = 0; i < n; ++i) {
        double theta = (i + 0.5) / n * (kPi / 2.0);
        double cosI = std::cos(theta), sinI = std::sin(theta);
        double cosH = std::cos(theta / 2.0);  // wo = n: the half vector bisects
        double d = a2 / (kPi * std::pow(cosH * cosH * (a2 - 1.0) + 1.0, 2.0));
        double tan2 = sinI * sinI / (cosI * cosI);
        double lambdaI = 0.5 * (std::sqrt(1.0 + a2 * tan2) - 1.0);
        double g2 = 1.0 / (1.0 + lambdaI);
        sum += 2.0 * kPi * sinI * d * g2 / 4.0 * (kPi / 2.0 / n);
    }
    return sum;
}

// SPEC §6's three channels at (μ, alpha) by an n × n midpoint grid (2^20 points at n = 1024):
// A and B over the unit square of the visible-normal map (Heitz 2018, written out again here in
// double precision), where D G2 / (4μ) dω_i = (G2 / G1) · pdf_VNDF dω_i: a bounded, smooth
// integrand down to grazing μ; C over cosine-distributed ω_i (sin²θ_i uniform).
struct GgxChannels {
    double a = 0.0, b = 0.0, c = 0.0;
};
inline GgxChannels GgxChannelsByQuadrature(double mu, double alpha, int n = 1024) {
    const double a2 = alpha * alpha;
    const double sinO = std::sqrt(std::max(0.0, 1.0 - mu * mu));
    auto lambda = [&](double cosT) {
        double c2 = cosT * cosT;
        return 0.5 * (std::sqrt(1.0 + a2 * (1.0 - c2) / c2) - 1.0);
    };
    auto schlick = [](double c) { return std::pow(std::clamp(1.0 - c, 0.0, 1.0), 5.0); };
    const double lambdaO = lambda(mu);
    // The stretched view direction and its frame (ω_o = (sinO, 0, μ)).
    double vx = alpha * sinO, vz = mu;
    const double vl = std::sqrt(vx * vx + vz * vz);
    vx /= vl;
    vz /= vl;
    // t1 = (0, 1, 0) (vh lies in the xz plane), t2 = vh × t1 = (−vz, 0, vx).
    GgxChannels r;
    for (int iu = 0; iu < n; ++iu) {
        const double u = (iu + 0.5) / n;
        const double rad = std::sqrt(u);
        const double cosI = std::sqrt(1.0 - u), sinI = std::sqrt(u);
        for (int ip = 0; ip < n; ++ip) {
            const double phi = 2.0 * kPi * (ip + 0.5) / n;
            const double cp = std::cos(phi), sp = std::sin(phi);
            // Specular: visible normal of disk point (p1, p2).
            const double p1 = rad * cp;
            const double s = 0.5 * (1.0 + vz);
            const double p2 = (1.0 - s) * std::sqrt(std::max(0.0, 1.0 - p1 * p1)) + s * rad * sp;
            const double p3 = std::sqrt(std::max(0.0, 1.0 - p1 * p1 - p2 * p2));
            // nh = p1 t1 + p2 t2 + p3 vh
            const double nx = -p2 * vz + p3 * vx, ny = p1, nz = p2 * vx + p3 * vz;
            double hx = alpha * nx, hy = alpha * ny, hz = std::max(0.0, nz);
            const double hl = std::sqrt(hx * hx + hy * hy + hz * hz);
            hx /= hl;
            hy /= hl;
            hz /= hl;
            const double woh = sinO * hx + mu * hz;
            const double wiz = 2.0 * woh * hz - mu;
            if (wiz > 0.0) {
                const double w = (1.0 + lambdaO) / (1.0 + lambdaO + lambda(wiz));  // G2 / G1
                const double sch = schlick(woh);
                r.a += (1.0 - sch) * w;
                r.b += sch * w;
            }
            // Diffuse: ω_i cosine-distributed (cos²θ_i = 1 − u), S at its half vector.
            const double dx = sinO + sinI * cp, dy = sinI * sp, dz = mu + cosI;
            const double len = std::sqrt(dx * dx + dy * dy + dz * dz);
            r.c += schlick((sinO * dx + mu * dz) / len);
        }
    }
    const double inv = 1.0 / (double(n) * double(n));
    r.a *= inv;
    r.b *= inv;
    r.c *= inv;
    return r;
}

}  // namespace fovrt::test
