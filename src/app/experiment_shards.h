// Sharded experiments (SPEC §13, issue #15): an experiment is a list of runs, one per
// (scene, run seed, eye, variant) in the order a single machine runs them; `--shard I/N` computes a
// contiguous block of them (never part of a denoiser's frame sequence) and writes its part apart,
// and `--merge` combines the N parts into the same CSV (byte for byte), summary, table and report
// a single run writes.
//
// A shard's part is a directory <output.dir>/shards/shard-I-of-N/, built under a temporary name
// and renamed into place when complete, so a killed shard leaves nothing that looks finished:
//   part.json     the experiment's fingerprint, the runs, per-scene records (with the content hash
//                 of the scene and of each file it loaded), pass timings
//   rows.tsv      every result row, values as %.17g (exact)
//   visuals-K/    scene K's report images (EXR) when the shard ran the report's eye and seed
#pragma once

#include <cstdint>
#include <filesystem>
#include <array>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/experiment_vdp.h"
#include "app/report.h"
#include "app/report_html.h"

namespace fovrt {

struct ExperimentSpec;

// --shard I/N: 0 ≤ I < N. {0, 1} is the whole experiment.
struct ShardSelection {
    int index = 0;
    int count = 1;
    bool Sharded() const { return count > 1 || index != 0; }
    std::string Name() const;  // "shard-1-of-3"
};
// "I/N" with 0 ≤ I < N; a bad text is one error naming --shard.
ShardSelection ParseShard(const std::string& text);

// One run: a denoiser's whole frame sequence for one eye of one scene under one run seed.
struct RunUnit {
    size_t scene = 0;
    size_t seed = 0;  // index into the experiment's seeds
    int eye = 0;
    size_t variant = 0;
};
// Every run in single-machine order: scene, seed, eye, variant.
std::vector<RunUnit> ExperimentUnits(size_t scenes, size_t seeds, size_t variants);
// The block [begin, end) of `count` runs that shard `selection` computes: contiguous, sizes
// differing by at most one.
std::pair<size_t, size_t> ShardBlock(size_t count, const ShardSelection& selection);
// The block of runs shard `selection` computes (ShardBlock of all).
std::vector<RunUnit> ShardUnits(const std::vector<RunUnit>& all, const ShardSelection& selection);

// Mean per-pass denoiser times, mergeable (sums and counts).
class PassTimings {
public:
    void Add(const std::string& variant, const std::string& pass, double ms, int count = 1);
    void Merge(const PassTimings& other);
    ReportTable ToReport(const std::string& title) const;
    nlohmann::json MeansJson() const;      // variant -> pass -> mean ms (the manifest's pass_ms)
    nlohmann::json ToJson() const;         // sums and counts, for a shard's part
    static PassTimings FromJson(const nlohmann::json& json);

private:
    std::map<std::string, std::map<std::string, std::pair<double, int>>> sums_;
    std::vector<std::string> order_;
};

// Wall time a scene's runs spent per stage, summed over its eye-frames (and, merged, its shards).
struct SceneTimes {
    double renderMs = 0.0, referenceMs = 0.0;
    double denoiseMs = 0.0, metricMs = 0.0;  // every variant's Denoise(); scoring them (errors, FovVideoVDP)
    SceneTimes& operator+=(const SceneTimes& o) {
        renderMs += o.renderMs, referenceMs += o.referenceMs, denoiseMs += o.denoiseMs, metricMs += o.metricMs;
        return *this;
    }
};

// What the runs of one scene measured (the manifest's scene record) and its report images.
struct SceneRecord {
    size_t index = 0;  // in the experiment's scenes
    std::string label, requested, source;
    uint64_t fingerprint = 0;                  // SceneFingerprint: the loaded content
    std::map<std::string, std::string> files;  // SceneFileHashes: each file it loaded -> its hash
    SceneTimes times;
    int referenceHits = 0, referenceLookups = 0, eyeFrames = 0, blinkFrames = 0;
    uint64_t rays = 0, droppedSamples = 0;
    // Measured sampling (TracedSamples, app/experiment_pass.h): Σ FrameInputs::sampleCount and the
    // pixel count of each of kTracedRegions over every eye-frame a pass rendered, at the true gaze.
    std::array<uint64_t, 3> tracedSamples{}, tracedPixels{};
    std::array<uint64_t, 3> guidePixels{};  // of those pixels, the ones without a path sample (a guide ray only)
    bool hasVisuals = false;  // ran the report's eye under the first seed
    SceneVisuals visuals;     // its variants: those this part ran
};

// The result of computing some (or all) runs.
struct ExperimentPart {
    Results results;
    std::vector<SceneRecord> scenes;  // scenes this part touched, by index
    PassTimings timings;
    std::string deviceDescription;
    nlohmann::json replayRecord;
    std::vector<VdpScore> vdp;  // FovVideoVDP per sequence (app/experiment_vdp.h)
    std::string vdpDisplay;     // the display they were scored on, in words
};

// Sorts the rows into single-machine order (scene, seed, frame, eye, variant; the order of rows
// within one denoised frame is kept), given each label's scene index.
void SortRowsCanonically(Results& results, const std::map<std::string, size_t>& sceneIndex,
                         const std::vector<uint32_t>& seeds, const std::vector<std::string>& variants);

// What identifies an experiment for its shards: the resolved config, scenes, variants, seeds,
// quick, replay. Shards of different experiments never merge.
std::string ExperimentFingerprint(const ExperimentSpec& spec);

// Writes `part` as shard `selection`'s directory under `shardsDir`, atomically (a rerun replaces it).
void WriteShardPart(const std::filesystem::path& shardsDir, const ShardSelection& selection,
                    const std::string& fingerprint, const ExperimentPart& part);
// Reads and combines every part under `shardsDir`. Refuses a set that is incomplete (naming the
// missing shards and the command that makes them), mixed (different N or experiment), corrupt, or
// rendered from different contents of a scene (naming the files that differ).
ExperimentPart MergeShardParts(const std::filesystem::path& shardsDir, const std::string& fingerprint,
                               const std::string& rerunCommand);

}  // namespace fovrt
