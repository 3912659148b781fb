#include "gaze/tracker.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "core/error.h"
#include "core/rng.h"

namespace fovrt {

// ---- Saccade model -----------------------------------------------------------------------------

double MainSequencePeakVelocity(double amplitudeDeg) {
    return kMainSequenceVmaxDegPerS * (1.0 - std::exp(-amplitudeDeg / kMainSequenceCDeg));
}

double SaccadeDurationS(double amplitudeDeg) {
    return amplitudeDeg > 0.0 ? 2.0 * amplitudeDeg / MainSequencePeakVelocity(amplitudeDeg) : 0.0;
}

double SaccadeDisplacementDeg(double amplitudeDeg, double elapsedS) {
    if (elapsedS <= 0.0 || amplitudeDeg <= 0.0) return 0.0;
    const double d = SaccadeDurationS(amplitudeDeg);
    if (elapsedS >= d) return amplitudeDeg;
    // ∫ (V/2)(1 − cos(2πτ/D)) dτ with V = 2A/D.
    const double x = elapsedS / d;
    return amplitudeDeg * (x - std::sin(2.0 * double(kPi) * x) / (2.0 * double(kPi)));
}

std::optional<vec2> PredictSaccadeLanding(const std::vector<vec2>& a, double periodS, double onsetDegPerS) {
    const size_t n = a.size();
    if (n < 2 || !(periodS > 0.0)) return std::nullopt;
    auto speed = [&](size_t i) { return double(glm::length(a[i] - a[i - 1])) / periodS; };
    if (!(speed(n - 1) > onsetDegPerS)) return std::nullopt;
    // The anchor m: the last sample before the saccade's acceleration, where the speed falls to a
    // fifth of the onset threshold (the first samples of a saccade are slower than the threshold).
    size_t m = n - 2;
    while (m >= 1 && speed(m) > 0.2 * onsetDegPerS) --m;
    // Two parameters: wait for a third sample since the start (two fit anything, often far off).
    if (n - 1 - m < 3) return std::nullopt;
    const vec2 travelled = a[n - 1] - a[m];
    const double covered = glm::length(travelled);
    if (!(covered > 0.0)) return std::nullopt;
    const vec2 u = travelled / float(covered);
    // Sum of squared residuals of (amplitude, onset offset τ0 from sample m's capture): the
    // distances from sample m are D(τ_i − τ0) − D(−τ0) (the onset may precede sample m).
    auto residual = [&](double amplitude, double tau0) {
        const double before = SaccadeDisplacementDeg(amplitude, -tau0);
        double sum = 0.0;
        for (size_t i = m + 1; i < n; ++i) {
            const double observed = double(glm::dot(a[i] - a[m], u));
            const double model = SaccadeDisplacementDeg(amplitude, double(i - m) * periodS - tau0) - before;
            sum += (model - observed) * (model - observed);
        }
        return sum;
    };
    // τ0 in [−2 periods, period]: sample m moved slowly since m − 1, so the onset may precede it.
    constexpr int kOnsetSteps = 48;
    const double tauLow = -2.0 * periodS, tauHigh = periodS;
    constexpr double kMaxAmplitudeDeg = 90.0;
    // A grid (A in 0.5° steps), then a pattern search from each of its best few points: the
    // residual has narrow valleys that one start can miss.
    struct Fit {
        double residual, amplitude, tau0;
    };
    std::vector<Fit> grid;
    for (double amplitude = covered; amplitude <= kMaxAmplitudeDeg; amplitude += 0.5)
        for (int s = 0; s <= kOnsetSteps; ++s) {
            const double tau0 = tauLow + (tauHigh - tauLow) * s / kOnsetSteps;
            grid.push_back({residual(amplitude, tau0), amplitude, tau0});
        }
    constexpr size_t kStarts = 8;
    const size_t starts = std::min(kStarts, grid.size());
    std::partial_sort(grid.begin(), grid.begin() + long(starts), grid.end(),
                      [](const Fit& x, const Fit& y) { return x.residual < y.residual; });
    Fit best = grid.front();
    for (size_t i = 0; i < starts; ++i) {
        Fit fit = grid[i];
        double stepA = 0.25, stepTau = (tauHigh - tauLow) / kOnsetSteps;
        while (stepA > 1e-4) {
            bool moved = false;
            for (const auto& [dA, dTau] : {std::pair{stepA, 0.0}, {-stepA, 0.0}, {0.0, stepTau}, {0.0, -stepTau}}) {
                const Fit next{0.0, fit.amplitude + dA, fit.tau0 + dTau};
                if (next.amplitude < covered || next.amplitude > kMaxAmplitudeDeg || next.tau0 < tauLow ||
                    next.tau0 > tauHigh)
                    continue;
                const double r = residual(next.amplitude, next.tau0);
                if (r < fit.residual) fit = {r, next.amplitude, next.tau0}, moved = true;
            }
            if (!moved) stepA *= 0.5, stepTau *= 0.5;
        }
        if (fit.residual < best.residual) best = fit;
    }
    const double bestAmplitude = best.amplitude, bestTau0 = best.tau0;
    const double remaining = bestAmplitude - SaccadeDisplacementDeg(bestAmplitude, -bestTau0);
    return a[m] + float(std::max(remaining, covered)) * u;
}

float AngleBetweenDeg(const vec3& a, const vec3& b) {
    return Degrees(std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b)));
}

// ---- Tracker sampling ----------------------------------------------------------------------

vec2 ExtrapolateConstantVelocity(const vec2& previous, const vec2& newest, double periodS, double horizonS) {
    return newest + (newest - previous) * float(horizonS / periodS);
}

namespace {

uint32_t SampleHash(uint32_t seed, uint64_t key, uint32_t use) {
    return HashCombine(HashCombine(HashCombine(HashPcg(seed), uint32_t(key)), uint32_t(key >> 32)), use);
}

constexpr double kTwoTo32 = 4294967296.0;

}  // namespace

vec2 TrackerNoiseDeg(uint32_t seed, uint64_t key, float rmsDeg) {
    if (rmsDeg == 0.0f) return vec2(0.0f);
    // Box–Muller: u1 in (0, 1], u2 in [0, 1).
    const double u1 = (double(SampleHash(seed, key, 1)) + 1.0) / kTwoTo32;
    const double u2 = double(SampleHash(seed, key, 2)) / kTwoTo32;
    const double r = std::sqrt(-2.0 * std::log(u1)) * double(rmsDeg) / std::sqrt(2.0);
    return vec2(float(r * std::cos(2.0 * double(kPi) * u2)), float(r * std::sin(2.0 * double(kPi) * u2)));
}

bool TrackerDropout(uint32_t seed, uint64_t key, double probability) {
    return probability > 0.0 && double(SampleHash(seed, key, 3)) / kTwoTo32 < probability;
}

int64_t NewestSampleIndex(const TrackerParams& p, double t) {
    // The 1e-9 of a period absorbs rounding when t is exactly a sample's arrival time.
    return int64_t(std::floor((t - (p.latencyMs + p.phaseMs) / 1000.0) * p.rateHz + 1e-9));
}

double SampleCaptureTime(const TrackerParams& p, int64_t index) { return p.phaseMs / 1000.0 + double(index) / p.rateHz; }

bool IsIdealTracker(const TrackerParams& p) {
    return p.rateHz == 0.0 && p.latencyMs == 0.0 && p.noiseDeg == 0.0f && p.biasDeg == vec2(0.0f) &&
           p.dropout == 0.0 && p.prediction == "none";
}

// ---- TrackedGaze ---------------------------------------------------------------------------

double TrackerLookbackSeconds(const TrackerParams& p) {
    const double latency = p.latencyMs / 1000.0;
    if (p.rateHz == 0.0) return latency;  // one capture at t − latency
    // At(t): sample k is captured up to one period before t − latency; an invalid run looks back
    // max(blink, 1 s) plus a sample for its last valid one; Predict reads the landing window
    // (0.25 s + 2 samples) before that. 6 periods cover every rounding on the way.
    return latency + std::max(p.blinkMs, 1000.0) / 1000.0 + 0.25 + 6.0 / p.rateHz;
}

TrackedGaze::TrackedGaze(const GazeSource& truth, const TrackerParams& params) : truth_(truth), params_(params) {
    ValidateTrackerParams(params_);
}

TrackerSample TrackedGaze::Observe(double captureSeconds, uint64_t key) const {
    const GazeSample eye = truth_.At(captureSeconds);
    TrackerSample s;
    s.captureSeconds = captureSeconds;
    s.valid = eye.valid && !TrackerDropout(params_.seed, key, params_.dropout);
    s.anglesDeg = GazeAnglesFromDirection(eye.direction) + params_.biasDeg + TrackerNoiseDeg(params_.seed, key, params_.noiseDeg);
    return s;
}

TrackerSample TrackedGaze::Sample(int64_t index) const {
    return Observe(SampleCaptureTime(params_, index), uint64_t(index));
}

GazeSample TrackedGaze::Predict(double t, int64_t newest) const {
    const TrackerSample s = Sample(newest);
    const double period = 1.0 / params_.rateHz;
    vec2 angles = s.anglesDeg;
    if (params_.prediction == "cv") {
        const TrackerSample previous = Sample(newest - 1);
        if (previous.valid) angles = ExtrapolateConstantVelocity(previous.anglesDeg, s.anglesDeg, period, t - s.captureSeconds);
    } else if (params_.prediction == "landing") {
        // The run of valid samples up to the newest, long enough for the longest saccade (~200 ms).
        const int64_t window = int64_t(std::ceil(0.25 * params_.rateHz)) + 2;
        std::vector<vec2> run{s.anglesDeg};
        for (int64_t i = newest - 1; i > newest - window; --i) {
            const TrackerSample older = Sample(i);
            if (!older.valid) break;
            run.push_back(older.anglesDeg);
        }
        std::reverse(run.begin(), run.end());
        if (auto landing = PredictSaccadeLanding(run, period, params_.saccadeDegPerS)) angles = *landing;
    }
    angles = glm::clamp(angles, vec2(-89.0f), vec2(89.0f));
    return GazeSample{t, GazeDirectionFromAngles(angles.x, angles.y), true};
}

GazeSample TrackedGaze::At(double t) const {
    if (IsIdealTracker(params_)) return truth_.At(t);
    if (params_.rateHz == 0.0) {  // sampled at this frame's time − latency
        const double capture = t - params_.latencyMs / 1000.0;
        const TrackerSample s = Observe(capture, uint64_t(std::llround(capture * 1e6)));
        if (!s.valid) return GazeSample{t, truth_.At(capture).direction, false};
        return GazeSample{t, GazeDirectionFromAngles(s.anglesDeg.x, s.anglesDeg.y), true};
    }
    const int64_t k = NewestSampleIndex(params_, t);
    if (Sample(k).valid) return Predict(t, k);
    // An invalid run: find where it started (and the last valid sample) within blinkMs; a run
    // that has lasted blinkMs is a blink, a shorter one holds the last valid sample.
    const double captureK = SampleCaptureTime(params_, k);
    const int64_t lookBack = int64_t(std::ceil(std::max(params_.blinkMs, 1000.0) / 1000.0 * params_.rateHz)) + 1;
    int64_t lastValid = k - 1;
    while (lastValid > k - lookBack && !Sample(lastValid).valid) --lastValid;
    const bool found = lastValid > k - lookBack;
    const double runMs = found ? (captureK - SampleCaptureTime(params_, lastValid + 1)) * 1000.0
                               : std::numeric_limits<double>::infinity();
    if (found && runMs < params_.blinkMs) return Predict(t, lastValid);
    const vec3 held = found ? GazeDirectionFromAngles(Sample(lastValid).anglesDeg.x, Sample(lastValid).anglesDeg.y)
                            : truth_.At(captureK).direction;
    return GazeSample{t, held, false};
}

}  // namespace fovrt
