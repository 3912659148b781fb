#include "metrics/vdp_csf.h"

#include <algorithm>
#include <cmath>

#include "metrics/vdp_fastmath.h"

namespace fovrt {

namespace {

constexpr double kPiD = 3.14159265358979323846;

// Luminance dependence of a CSF parameter: constant, one hyperbola, or a product of two.
double LumDep(const std::vector<double>& p, double l) {
    if (p.size() == 1) return p[0];
    if (p.size() == 3) return p[0] * std::pow(1.0 + p[1] / l, -p[2]);
    return p[0] * std::pow(1.0 + p[1] / l, -p[2]) * (1.0 - std::pow(1.0 + p[3] / l, -p[4]));
}

// One mechanism (achromatic, red-green, yellow-violet) of the cone-contrast CSF fitted 16/09/2020.
struct Mechanism {
    std::vector<double> sMax, fMax, bw, gamma;
    double acPrime;
};
const Mechanism kMechanisms[3] = {
    {{356404, 6.2726, 0.320031, 895943, 7.77919e-05}, {2.3021, 3317.45, 0.186215}, {1.07516}, {1.1107}, 52.9768},
    {{423.978, 15.4032, 0.50343}, {0.122699}, {2.70669}, {1.72903}, 1.38437},
    {{11811.9, 196.342, 0.339396}, {7.1099e-08}, {5.3416}, {1.47263}, 0.282573},
};

// The parts of the achromatic sensitivity that depend on the background luminance alone: the
// CSF table computes them once per luminance node rather than at each of its 32 × 32 nodes.
struct LuminanceTerms {
    double sMax[3], fMax[3], log10FMax[3], halfBandwidth[3], gamma[3];  // per mechanism
    double weight[3];  // |achromatic direction in mechanism m| (cone contrast → mechanism)
    double norm2;      // squared norm of the achromatic cone contrast
};

LuminanceTerms TermsAt(double lum) {
    // CIE 1931 XYZ of D65 (0.95047, 1, 1.08883) to CIE 2006 LMS (matrix for an LED LCD).
    static const double kXyzToLms[3][3] = {
        {0.187596268556126, 0.585168649077728, -0.026384263306304},
        {-0.133397430663221, 0.405505777260049, 0.034502127690364},
        {0.000244379021663, -0.000542995890619, 0.019406849066323}};
    static const double kD65[3] = {0.95047, 1.0, 1.08883};
    // Cone contrast -> mechanism matrix (fitted colmat, with the mechanisms' signs).
    static const double c[6] = {0.00130319, 0.256197, 0.933541, 1.1504, 6.42477e-07, 0.00373304};
    static const double kLmsToAcc[3][3] = {{1, c[1], c[4]}, {1, -c[2], c[5]}, {-c[0], -c[3], 1}};
    static const double kAchromaticDelta[3] = {0.698, 0.302, 0.019613};

    double lms[3], coneContrast[3];
    for (int i = 0; i < 3; ++i) {
        lms[i] = lum * (kXyzToLms[i][0] * kD65[0] + kXyzToLms[i][1] * kD65[1] + kXyzToLms[i][2] * kD65[2]);
        coneContrast[i] = kAchromaticDelta[i] / lms[i];
    }
    const double mechanismLum = lms[0] + lms[1];
    LuminanceTerms t{};
    t.norm2 = 0.0;
    for (int m = 0; m < 3; ++m) {
        const Mechanism& mech = kMechanisms[m];
        t.sMax[m] = LumDep(mech.sMax, mechanismLum);
        t.fMax[m] = LumDep(mech.fMax, mechanismLum);
        t.log10FMax[m] = std::log10(t.fMax[m]);
        t.halfBandwidth[m] = 0.5 * std::pow(2.0, LumDep(mech.bw, mechanismLum));
        t.gamma[m] = LumDep(mech.gamma, mechanismLum);
        t.weight[m] = std::abs(kLmsToAcc[m][0] * coneContrast[0] + kLmsToAcc[m][1] * coneContrast[1] +
                               kLmsToAcc[m][2] * coneContrast[2]);
        t.norm2 += coneContrast[m] * coneContrast[m];
    }
    return t;
}

// Log-parabola in frequency (low-pass below the peak for chromatic mechanisms) times Rovamo's
// area summation sqrt(A^γ ρ² / (A'_c + A f₀ + A^γ ρ²)), f₀ = 0.65.
double MechanismSensitivity(int m, double rho, double area, const LuminanceTerms& t) {
    double sPeak = t.sMax[m] / std::pow(10.0, std::pow(std::log10(rho) - t.log10FMax[m], 2.0) / t.halfBandwidth[m]);
    if (m > 0 && rho < t.fMax[m]) sPeak = t.sMax[m];
    const double k = kMechanisms[m].acPrime + area * 0.65;
    const double a = std::pow(area, t.gamma[m]) * rho * rho;
    return sPeak * std::sqrt(a / (k + a));
}

// Achromatic sensitivity on a D65 background: the detection contrast of the achromatic
// cone-contrast direction, combined over the three mechanisms (exponent 2).
double AchromaticSensitivity(double rho, double area, const LuminanceTerms& t) {
    double c2 = 0.0;
    for (int m = 0; m < 3; ++m) {
        const double cn = t.weight[m] * MechanismSensitivity(m, rho, area, t);
        c2 += cn * cn;
    }
    return std::sqrt(c2) * std::sqrt(3.0) / std::sqrt(t.norm2);
}

// Laird et al.'s fit of Daly's spatio-velocity CSF; velocity floored at 0.1 deg/s.
double SpatioVelocityCsf(double rho, double velocity) {
    const double c0 = 0.6329, c1 = 0.8404, c2 = 0.7986;
    const double v = std::max(velocity, 0.1);
    const double k = 6.1 + 7.3 * std::pow(std::abs(std::log10(c2 * v / 3.0)), 3.0);
    const double rhoMax = 45.9 / (c2 * v + 2.0);
    return k * c0 * c1 * c2 * v * std::pow(c1 * 2.0 * kPiD * rho, 2.0) * std::exp(-(c1 * 4.0 * kPiD * rho) / rhoMax);
}

// The stimulus at frequency ρ and eccentricity e, whatever the luminance: frequency and area
// after cortical magnification, and the temporal factor at ω.
struct Stimulus {
    double rhoCm, area, temporal;
};

Stimulus StimulusAt(double rho, double omega, double ecc, double sigma, double kCm) {
    if (sigma < 0) sigma = -sigma / rho;
    const double mRel = std::pow(3.67 / (ecc + 3.67), kCm);  // M(e)/M(0), Dougherty's A cancels
    const double rhoCm = rho / mRel;
    return {rhoCm, kPiD * std::pow(sigma * mRel, 2.0),
            SpatioVelocityCsf(rhoCm, omega / rhoCm) / (SpatioVelocityCsf(rhoCm, 0.0) + 1e-5)};
}

}  // namespace

double VdpCsfModel(double rho, double omega, double luminance, double ecc, double sigma, double kCm) {
    const Stimulus s = StimulusAt(rho, omega, ecc, sigma, kCm);
    return AchromaticSensitivity(s.rhoCm, s.area, TermsAt(luminance)) * s.temporal;
}

namespace {

// The table's nodes: log-spaced L in [0.001, 10⁴] and ρ in [2⁻⁴, 64], e = (uniform in
// [0, √120])², each value rounded to float like the reference's single-precision table.
struct TableNodes {
    static constexpr int kSize = VdpCsfTable::kSize;
    std::array<double, kSize> lum, rho, ecc;
    TableNodes() {
        for (int i = 0; i < kSize; ++i) {
            const double t = double(i) / (kSize - 1);
            lum[i] = float(std::pow(10.0, -3.0 + 7.0 * t));
            rho[i] = float(std::pow(10.0, std::log10(0.0625) + (std::log10(64.0) - std::log10(0.0625)) * t));
            ecc[i] = float(std::pow(std::sqrt(120.0) * t, 2.0));
        }
    }
};

// VdpCsfModel's spatial part (all but the temporal factor) at every node, [lum][rho][ecc]: its
// luminance terms computed once per luminance node and its stimulus once per ρ–e pair.
std::vector<double> SpatialAtNodes(double sigma, double kCm) {
    constexpr size_t n = VdpCsfTable::kSize;
    const TableNodes nodes;
    std::vector<Stimulus> stimuli(n * n);  // [rho][ecc]; ω only changes the temporal factor
    for (size_t r = 0; r < n; ++r)
        for (size_t e = 0; e < n; ++e) stimuli[r * n + e] = StimulusAt(nodes.rho[r], 0.0, nodes.ecc[e], sigma, kCm);
    std::vector<double> spatial(n * n * n);
    for (size_t l = 0; l < n; ++l) {
        const LuminanceTerms terms = TermsAt(nodes.lum[l]);
        for (size_t i = 0; i < n * n; ++i)
            spatial[l * n * n + i] = AchromaticSensitivity(stimuli[i].rhoCm, stimuli[i].area, terms);
    }
    return spatial;
}

}  // namespace

VdpCsfTable::VdpCsfTable(double omega, double sigma, double kCm)
    : VdpCsfTable(omega, sigma, kCm, SpatialAtNodes(sigma, kCm)) {}

std::array<VdpCsfTable, 2> VdpCsfTable::ForOmegas(double omega0, double omega1, double sigma, double kCm) {
    const std::vector<double> spatial = SpatialAtNodes(sigma, kCm);
    return {VdpCsfTable(omega0, sigma, kCm, spatial), VdpCsfTable(omega1, sigma, kCm, spatial)};
}

VdpCsfTable::VdpCsfTable(double omega, double sigma, double kCm, const std::vector<double>& spatial)
    : logS_(size_t(kSize) * kSize * kSize) {
    const TableNodes nodes;
    for (int i = 0; i < kSize; ++i) {
        lum_.grid[i] = float(std::log2(nodes.lum[i]));
        rho_.grid[i] = float(std::log2(nodes.rho[i]));
        ecc_.grid[i] = float(std::sqrt(nodes.ecc[i]));
    }
    lum_.lo = float(nodes.lum[0]), lum_.hi = float(nodes.lum[kSize - 1]);
    rho_.lo = float(nodes.rho[0]), rho_.hi = float(nodes.rho[kSize - 1]);
    ecc_.lo = float(nodes.ecc[0]), ecc_.hi = float(nodes.ecc[kSize - 1]);
    // VdpCsfModel at every node: the spatial part times the temporal factor at ω.
    std::vector<double> temporal(size_t(kSize) * kSize);  // [rho][ecc]
    for (int r = 0; r < kSize; ++r)
        for (int e = 0; e < kSize; ++e)
            temporal[size_t(r) * kSize + size_t(e)] =
                StimulusAt(nodes.rho[r], omega, nodes.ecc[e], sigma, kCm).temporal;
    for (size_t l = 0; l < size_t(kSize); ++l)
        for (size_t i = 0; i < size_t(kSize) * kSize; ++i) {
            const size_t node = l * kSize * kSize + i;
            logS_[node] = float(std::log2(std::max(spatial[node] * temporal[i], 1e-4)));
        }
}

// The reference's interpolant: i1 = first grid point ≥ q, i0 = i1 − 1, fraction with a 1e-6
// guard in the denominator, 0 at and below the first point.
void VdpCsfTable::Axis::Locate(float q, int& i0, int& i1, float& f) const {
    // The grid is uniform up to float rounding: start from the uniform guess, then step to the
    // exact lower_bound (first point ≥ q).
    const float step = (grid[kSize - 1] - grid[0]) / float(kSize - 1);
    i1 = std::clamp(int(std::ceil((q - grid[0]) / step)), 0, kSize - 1);
    while (i1 > 0 && grid[size_t(i1 - 1)] >= q) --i1;
    while (i1 < kSize - 1 && grid[size_t(i1)] < q) ++i1;
    i0 = std::max(i1 - 1, 0);
    f = i0 == i1 ? 0.0f : std::max((q - grid[size_t(i0)]) / (grid[size_t(i1)] - grid[size_t(i0)] + 0.000001f), 0.0f);
}

float VdpCsfTable::Sensitivity(float rho, float luminance, float eccentricity) const {
    int r0, r1, l0, l1, e0, e1;
    float fr, fl, fe;
    rho_.Locate(std::log2(std::clamp(rho, rho_.lo, rho_.hi)), r0, r1, fr);
    lum_.Locate(std::log2(std::clamp(luminance, lum_.lo, lum_.hi)), l0, l1, fl);
    ecc_.Locate(std::sqrt(std::clamp(eccentricity, ecc_.lo, ecc_.hi)), e0, e1, fe);
    auto plane = [&](int e) {
        return (At(l0, r0, e) * (1 - fr) + At(l0, r1, e) * fr) * (1 - fl) +
               (At(l1, r0, e) * (1 - fr) + At(l1, r1, e) * fr) * fl;
    };
    return std::exp2(plane(e0) * (1 - fe) + plane(e1) * fe);
}

VdpCsfTable::LuminanceSlice VdpCsfTable::Slice(float rho, float eccentricity) const {
    int r0, r1, e0, e1;
    float fr, fe;
    rho_.Locate(std::log2(std::clamp(rho, rho_.lo, rho_.hi)), r0, r1, fr);
    ecc_.Locate(std::sqrt(std::clamp(eccentricity, ecc_.lo, ecc_.hi)), e0, e1, fe);
    LuminanceSlice slice;
    for (int l = 0; l < kSize; ++l)
        slice.logS[size_t(l)] = (At(l, r0, e0) * (1 - fr) + At(l, r1, e0) * fr) * (1 - fe) +
                                (At(l, r0, e1) * (1 - fr) + At(l, r1, e1) * fr) * fe;
    return slice;
}

float VdpCsfTable::Sensitivity(const LuminanceSlice& slice, float luminance) const {
    int l0, l1;
    float fl;
    lum_.Locate(std::log2(std::clamp(luminance, lum_.lo, lum_.hi)), l0, l1, fl);
    return std::exp2(slice.logS[size_t(l0)] * (1 - fl) + slice.logS[size_t(l1)] * fl);
}

const VdpCsfTable::Axis& VdpCsfTable::AxisOf(AxisName axis) const {
    switch (axis) {
        case AxisName::Rho: return rho_;
        case AxisName::Luminance: return lum_;
        case AxisName::Eccentricity: return ecc_;
    }
    return rho_;
}

namespace {

// Locate's interpolant on a uniform grid g0 + i·step, for values already in the grid's domain:
// i1 = ⌈(q − g0)/step⌉ clamped to [1, 31] (below the first node i1 = 1 with fraction 0 gives
// Locate's i0 = i1 = 0), computed with truncation (no ceil call) so the loop vectorises; always
// inlined, so it is compiled for each target of LocateRow.
template <typename ToGrid>
[[gnu::always_inline]]
inline void LocateUniform(const float* values, std::size_t n, float lo, float hi, float g0, float step, ToGrid toGrid,
                   int32_t* node, float* fraction) {
    constexpr int kLast = VdpCsfTable::kSize - 1;
    const float invStep = 1.0f / step, denominator = step + 0.000001f;
    for (std::size_t i = 0; i < n; ++i) {
        const float v = values[i] < lo ? lo : (values[i] > hi ? hi : values[i]);
        const float q = toGrid(v);
        const float x = std::clamp((q - g0) * invStep, -1.0f, float(kLast + 1));
        const int32_t truncated = int32_t(x);
        const int32_t up = truncated + (float(truncated) < x ? 1 : 0);  // ⌈x⌉
        const int32_t i0 = std::clamp(up, 1, kLast) - 1;
        node[i] = i0;
        fraction[i] = std::max((q - (g0 + float(i0) * step)) / denominator, 0.0f);
    }
}

}  // namespace

FOVRT_VDP_ROW_CLONES
void VdpCsfTable::LocateRow(AxisName axis, const float* values, std::size_t n, VdpCsfAxisRow& out) const {
    const Axis& a = AxisOf(axis);
    out.Resize(n);
    const float g0 = a.grid[0], step = (a.grid[kSize - 1] - a.grid[0]) / float(kSize - 1);
    if (axis == AxisName::Eccentricity)
        LocateUniform(values, n, a.lo, a.hi, g0, step, [](float v) { return std::sqrt(v); }, out.node.data(),
                      out.fraction.data());
    else
        LocateUniform(values, n, a.lo, a.hi, g0, step, [](float v) { return VdpFastLog2(v); }, out.node.data(),
                      out.fraction.data());
}

FOVRT_VDP_ROW_CLONES
void VdpCsfTable::Log2Sensitivity(const VdpCsfAxisRow& rho, const VdpCsfAxisRow& luminance,
                                  const VdpCsfAxisRow& eccentricity, std::size_t n, float* out) const {
    constexpr std::size_t kRho = kSize, kLum = std::size_t(kSize) * kSize;  // strides in logS_
    const float* table = logS_.data();
    for (std::size_t i = 0; i < n; ++i) {
        const float* c = table + (std::size_t(luminance.node[i]) * kSize + std::size_t(rho.node[i])) * kSize +
                         std::size_t(eccentricity.node[i]);
        const float fr = rho.fraction[i], fl = luminance.fraction[i], fe = eccentricity.fraction[i];
        auto plane = [&](std::size_t e) {
            return (c[e] * (1 - fr) + c[kRho + e] * fr) * (1 - fl) +
                   (c[kLum + e] * (1 - fr) + c[kLum + kRho + e] * fr) * fl;
        };
        out[i] = plane(0) * (1 - fe) + plane(1) * fe;
    }
}

FOVRT_VDP_ROW_CLONES
void VdpCsfTable::Log2Sensitivity(const LuminanceSlice& slice, const VdpCsfAxisRow& luminance, std::size_t n,
                                  float* out) const {
    for (std::size_t i = 0; i < n; ++i) {
        const std::size_t l = std::size_t(luminance.node[i]);
        const float fl = luminance.fraction[i];
        out[i] = slice.logS[l] * (1 - fl) + slice.logS[l + 1] * fl;
    }
}

}  // namespace fovrt
