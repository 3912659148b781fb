#include "metrics/flip.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "metrics/filter.h"
#include "metrics/image_metrics.h"
#include "metrics/tonemap.h"

namespace fovrt {

namespace {

// D65 white and the sRGB ↔ XYZ matrices (rows), as in the FLIP reference.
constexpr double kWhite[3] = {0.950428545, 1.0, 1.088900371};
constexpr double kRgbToXyz[3][3] = {{10135552.0 / 24577794.0, 8788810.0 / 24577794.0, 4435075.0 / 24577794.0},
                                    {2613072.0 / 12288897.0, 8788810.0 / 12288897.0, 887015.0 / 12288897.0},
                                    {1425312.0 / 73733382.0, 8788810.0 / 73733382.0, 70074185.0 / 73733382.0}};
constexpr double kXyzToRgb[3][3] = {{3.241003275, -1.537398934, -0.498615861},
                                    {-0.969224334, 1.875930071, 0.041554224},
                                    {0.055639423, -0.204011202, 1.057148933}};

vec3 Mul(const double m[3][3], const vec3& v) {
    return vec3(float(m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z),
                float(m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z),
                float(m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z));
}

vec3 LinearRgbToYCxCz(const vec3& rgb) {
    vec3 xyz = Mul(kRgbToXyz, rgb);
    double x = xyz.x / kWhite[0], y = xyz.y / kWhite[1], z = xyz.z / kWhite[2];
    return vec3(float(116 * y - 16), float(500 * (x - y)), float(200 * (y - z)));
}

vec3 YCxCzToLinearRgb(const vec3& ycc) {
    double y = (ycc.x + 16.0) / 116.0;
    double x = y + ycc.y / 500.0, z = y - ycc.z / 200.0;
    return Mul(kXyzToRgb, vec3(float(x * kWhite[0]), float(y * kWhite[1]), float(z * kWhite[2])));
}

// CIELAB of linear RGB followed by the Hunt adjustment (float: cbrt dominates FLIP's cost).
vec3 HuntLab(const vec3& rgb) {
    const vec3 xyz = Mul(kRgbToXyz, rgb);
    constexpr float delta = 6.0f / 29.0f;
    auto f = [&](float t) {
        return t > delta * delta * delta ? std::cbrt(t) : t / (3 * delta * delta) + 4.0f / 29.0f;
    };
    const float fx = f(xyz.x / float(kWhite[0])), fy = f(xyz.y), fz = f(xyz.z / float(kWhite[2]));
    const float l = 116 * fy - 16, a = 500 * (fx - fy), b = 200 * (fy - fz);
    return vec3(l, 0.01f * l * a, 0.01f * l * b);
}

float HyAb(const vec3& p, const vec3& q) {
    vec3 d = p - q;
    return std::abs(d.x) + std::sqrt(d.y * d.y + d.z * d.z);
}

float Cmax() {
    static const float cmax = std::pow(HyAb(HuntLab(vec3(0, 1, 0)), HuntLab(vec3(0, 0, 1))), kFlipQc);
    return cmax;
}

float RedistributeColorError(float hyab) {
    const float powered = std::pow(hyab, kFlipQc), cmax = Cmax(), pccmax = kFlipPc * cmax;
    return powered < pccmax ? (kFlipPt / pccmax) * powered
                            : kFlipPt + ((powered - pccmax) / (cmax - pccmax)) * (1.0f - kFlipPt);
}

Plane<float> Separable(const Plane<float>& in, const std::vector<float>& kx, const std::vector<float>& ky) {
    return metrics_detail::ConvolveSeparable(in, kx, ky, metrics_detail::Border::kReplicate);
}

// CSF: s(x, y) = Σ_i a_i sqrt(π / b_i) exp(−π² (x² + y²) Δ² / b_i), normalised to sum 1 over the
// (2r+1)² grid. Each term is a separable Gaussian, so filter per term and weight.
struct CsfTerm {
    float a, b;
};

Plane<float> CsfFilter(const Plane<float>& in, const std::vector<CsfTerm>& terms, float ppd) {
    constexpr float kMaxB = 0.04f;  // the largest scale parameter of the three channels
    const int r = int(std::ceil(3.0f * std::sqrt(kMaxB / (2 * kPi * kPi)) * ppd));
    const float dx = 1.0f / ppd;
    std::vector<std::vector<float>> gauss;
    std::vector<double> weight;
    double total = 0;
    for (const CsfTerm& t : terms) {
        std::vector<float> g(size_t(2 * r + 1));
        double s = 0;
        for (int i = -r; i <= r; ++i) {
            g[size_t(i + r)] = std::exp(-kPi * kPi * (i * dx) * (i * dx) / t.b);
            s += g[size_t(i + r)];
        }
        double c = t.a * std::sqrt(kPi / t.b);
        gauss.push_back(std::move(g));
        weight.push_back(c);
        total += c * s * s;
    }
    Plane<float> out(in.width(), in.height(), 0.0f);
    for (size_t k = 0; k < terms.size(); ++k) {
        Plane<float> part = Separable(in, gauss[k], gauss[k]);
        const float wk = float(weight[k] / total);
        for (size_t i = 0; i < out.size(); ++i) out[i] += wk * part[i];
    }
    return out;
}

// Feature kernels: the x-profile (normalised by sign) and the y Gaussian (sum 1).
struct FeatureKernels {
    std::vector<float> gauss, edge, point;
};

FeatureKernels MakeFeatureKernels(float ppd) {
    const float sd = 0.5f * kFlipGw * ppd;
    const int r = int(std::ceil(3.0f * sd));
    FeatureKernels k;
    k.gauss.resize(size_t(2 * r + 1));
    k.edge.resize(k.gauss.size());
    k.point.resize(k.gauss.size());
    double gsum = 0;
    for (int i = -r; i <= r; ++i) {
        float g = std::exp(-float(i * i) / (2 * sd * sd));
        k.gauss[size_t(i + r)] = g;
        k.edge[size_t(i + r)] = -float(i) * g;
        k.point[size_t(i + r)] = (float(i * i) / (sd * sd) - 1.0f) * g;
        gsum += g;
    }
    for (float& g : k.gauss) g = float(g / gsum);
    auto normaliseBySign = [](std::vector<float>& v) {
        double pos = 0, neg = 0;
        for (float e : v) (e > 0 ? pos : neg) += e;
        for (float& e : v) {
            if (e > 0) e = float(e / pos);
            else if (e < 0) e = float(e / -neg);
        }
    };
    normaliseBySign(k.edge);
    normaliseBySign(k.point);
    return k;
}

struct Features {
    Plane<float> edge, point;  // magnitudes ‖(fx, fy)‖
};

Features DetectFeatures(const Plane<float>& y, const FeatureKernels& k) {
    Features f{Plane<float>(y.width(), y.height()), Plane<float>(y.width(), y.height())};
    Plane<float> ex = Separable(y, k.edge, k.gauss), ey = Separable(y, k.gauss, k.edge);
    Plane<float> px = Separable(y, k.point, k.gauss), py = Separable(y, k.gauss, k.point);
    for (size_t i = 0; i < y.size(); ++i) {
        f.edge[i] = std::sqrt(ex[i] * ex[i] + ey[i] * ey[i]);
        f.point[i] = std::sqrt(px[i] * px[i] + py[i] * py[i]);
    }
    return f;
}

}  // namespace

float FlipColorError(const vec3& testLinear, const vec3& referenceLinear) {
    auto clamp01 = [](const vec3& v) { return glm::clamp(v, vec3(0.0f), vec3(1.0f)); };
    return RedistributeColorError(HyAb(HuntLab(clamp01(testLinear)), HuntLab(clamp01(referenceLinear))));
}

namespace {

// LDR-FLIP on linear RGB in [0,1] (the reference's first step, sRGB → linear, already done).
Plane<float> FlipMapLinear(const Plane<vec3>& testLinear, const Plane<vec3>& referenceLinear, float ppd) {
    FOVRT_CHECK_OP(testLinear.width(), ==, referenceLinear.width());
    FOVRT_CHECK_OP(testLinear.height(), ==, referenceLinear.height());
    FOVRT_CHECK_OP(ppd, >, 0.0f);
    const int w = testLinear.width(), h = testLinear.height();
    const std::vector<CsfTerm> csf[3] = {{{1.0f, 0.0047f}}, {{1.0f, 0.0053f}}, {{34.1f, 0.04f}, {13.5f, 0.025f}}};
    const FeatureKernels kernels = MakeFeatureKernels(ppd);

    // Per image: filtered Hunt-Lab colours and feature magnitudes.
    auto prepare = [&](const Plane<vec3>& linear, Plane<vec3>& lab, Features& features) {
        Plane<float> channel[3] = {Plane<float>(w, h), Plane<float>(w, h), Plane<float>(w, h)};
        Plane<float> normY(w, h);
        for (size_t i = 0; i < linear.size(); ++i) {
            vec3 ycc = LinearRgbToYCxCz(linear[i]);
            for (int c = 0; c < 3; ++c) channel[c][i] = ycc[c];
            normY[i] = (ycc.x + 16.0f) / 116.0f;
        }
        for (int c = 0; c < 3; ++c) channel[c] = CsfFilter(channel[c], csf[c], ppd);
        lab.Resize(w, h);
        metrics_detail::ParallelRows(h, [&](int y) {
            for (int x = 0; x < w; ++x) {
                vec3 rgb = YCxCzToLinearRgb(vec3(channel[0](x, y), channel[1](x, y), channel[2](x, y)));
                lab(x, y) = HuntLab(glm::clamp(rgb, vec3(0.0f), vec3(1.0f)));
            }
        });
        features = DetectFeatures(normY, kernels);
    };
    Plane<vec3> labTest, labRef;
    Features featTest, featRef;
    prepare(testLinear, labTest, featTest);
    prepare(referenceLinear, labRef, featRef);

    Plane<float> map(w, h);
    metrics_detail::ParallelRows(h, [&](int y) {
        for (int x = 0; x < w; ++x) {
            const size_t i = size_t(y) * size_t(w) + size_t(x);
            float deltaC = RedistributeColorError(HyAb(labRef[i], labTest[i]));
            float deltaF = std::max(std::abs(featRef.edge[i] - featTest.edge[i]),
                                    std::abs(featRef.point[i] - featTest.point[i]));
            deltaF = std::pow(deltaF / std::sqrt(2.0f), kFlipQf);
            map[i] = std::pow(deltaC, 1.0f - deltaF);
        }
    });
    return map;
}

Plane<vec3> ClampedLinear(const Plane<vec3>& hdr) {
    Plane<vec3> out(hdr.width(), hdr.height());
    for (size_t i = 0; i < hdr.size(); ++i)
        for (int c = 0; c < 3; ++c) out[i][c] = std::isfinite(hdr[i][c]) ? std::clamp(hdr[i][c], 0.0f, 1.0f) : 0.0f;
    return out;
}

}  // namespace

Plane<float> FlipMapLdr(const Plane<vec3>& testSrgb, const Plane<vec3>& referenceSrgb, float ppd) {
    auto decode = [](const Plane<vec3>& srgb) {
        Plane<vec3> out(srgb.width(), srgb.height());
        for (size_t i = 0; i < srgb.size(); ++i)
            out[i] = vec3(SrgbDecode(srgb[i].r), SrgbDecode(srgb[i].g), SrgbDecode(srgb[i].b));
        return out;
    };
    return FlipMapLinear(decode(testSrgb), decode(referenceSrgb), ppd);
}

Plane<float> FlipMap(const Plane<vec3>& test, const Plane<vec3>& reference, float ppd) {
    // ToneMap is clamp + sRGB encode, and FLIP starts by decoding sRGB: skip the round trip.
    return FlipMapLinear(ClampedLinear(test), ClampedLinear(reference), ppd);
}

double Flip(const Plane<vec3>& test, const Plane<vec3>& reference, float ppd, const Plane<uint8_t>* mask) {
    return MaskedMean(FlipMap(test, reference, ppd), mask);
}

}  // namespace fovrt
