// Contrast sensitivity of FovVideoVDP 1.2: achromatic sensitivity as a function of spatial
// frequency ρ (cpd), temporal frequency ω (Hz), background luminance L (cd/m²) and eccentricity
// e (deg), derived here from the published model the reference tabulates (its
// matlab/utils/CSF_st_fov.m; tables recomputed by this code, not copied):
//   - cortical magnification (Dougherty et al. 2003) M(e) = 29.2/(e + 3.67) mm/deg; relative
//     M_rel = (M(e)/M(0))^k_cm scales the frequency ρ_cm = ρ/M_rel and the stimulus area
//     A = π (σ M_rel)², σ = 1.5/ρ degrees (1.5 cycles of the band);
//   - spatial part: the achromatic direction of the cone-contrast spatio-chromatic CSF fitted on
//     16/09/2020 (log-parabola in frequency with luminance-dependent peak, frequency and
//     bandwidth, Rovamo's area summation, three mechanisms combined with exponent 2), on a D65
//     background of luminance L in CIE 2006 LMS;
//   - temporal part: Daly / Laird's spatio-velocity CSF at velocity ω/ρ_cm relative to its value
//     at rest (velocity floor 0.1 deg/s).
// Like the reference, the metric reads the model through a 32³ table over log2 ρ ∈ [−4, 6],
// log2 L ∈ [log2 0.001, log2 10⁴] and √e ∈ [0, √120], trilinear, inputs clamped to the table.
// The metric's loop reads it a row of pixels at a time (VdpCsfAxisRow, Log2Sensitivity): each
// axis is located once per pixel for both channels' tables, in loops GCC vectorises.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace fovrt {

// The model itself (double precision).
double VdpCsfModel(double rho, double omega, double luminance, double eccentricity, double sigma,
                   double kCm);

// Where a row of queries falls on one axis of the table: the lower node of each and the fraction
// towards the next node (the reference's interpolant, see VdpCsfTable::Axis::Locate).
struct VdpCsfAxisRow {
    std::vector<int32_t> node;
    std::vector<float> fraction;
    void Resize(std::size_t n) { node.resize(n), fraction.resize(n); }
};

class VdpCsfTable {
public:
    static constexpr int kSize = 32;
    enum class AxisName { Rho, Luminance, Eccentricity };

    VdpCsfTable(double omega, double sigma, double kCm);
    // Tables at two temporal frequencies (the metric's two channels), sharing the model's spatial
    // part, which does not depend on ω: half the setup of two tables made apart, the same values.
    static std::array<VdpCsfTable, 2> ForOmegas(double omega0, double omega1, double sigma, double kCm);

    // Sensitivity (1/threshold Weber contrast), before the metric's sensitivity correction.
    float Sensitivity(float rho, float luminance, float eccentricity) const;

    // A 1D table over log2 L at fixed ρ and e (the non-foveated case: one per band); it gives the
    // same values as Sensitivity with that ρ and e.
    struct LuminanceSlice {
        std::array<float, kSize> logS;
    };
    LuminanceSlice Slice(float rho, float eccentricity) const;
    float Sensitivity(const LuminanceSlice& slice, float luminance) const;

    // Row forms, equal to the scalar ones to float rounding (the axes are read as exactly uniform
    // grids and log2 is VdpFastLog2): locate n values (ρ in cpd, L in cd/m², e in degrees) on an
    // axis, then the log2 sensitivity of n pixels from their three (or, with a slice, one) axis
    // rows. The axes are the same in every table.
    void LocateRow(AxisName axis, const float* values, std::size_t n, VdpCsfAxisRow& out) const;
    void Log2Sensitivity(const VdpCsfAxisRow& rho, const VdpCsfAxisRow& luminance, const VdpCsfAxisRow& eccentricity,
                         std::size_t n, float* out) const;
    void Log2Sensitivity(const LuminanceSlice& slice, const VdpCsfAxisRow& luminance, std::size_t n, float* out) const;

private:
    // `spatial`: the model's achromatic sensitivity at every node, [lum][rho][ecc].
    VdpCsfTable(double omega, double sigma, double kCm, const std::vector<double>& spatial);
    struct Axis {
        std::array<float, kSize> grid;  // in the interpolated domain (log2 or sqrt)
        float lo, hi;                   // clamp range in the input domain
        void Locate(float q, int& i0, int& i1, float& f) const;
    };
    const Axis& AxisOf(AxisName axis) const;
    Axis rho_, lum_, ecc_;
    std::vector<float> logS_;  // [lum][rho][ecc]
    float At(int l, int r, int e) const { return logS_[(std::size_t(l) * kSize + std::size_t(r)) * kSize + std::size_t(e)]; }
};

}  // namespace fovrt
