#include "app/experiment_shards.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>

#include <fmt/format.h>

#include "config/config_io.h"
#include "app/experiment.h"
#include "core/atomic_file.h"
#include "core/content_hash.h"
#include "core/error.h"
#include "core/interrupt.h"
#include "io/exr.h"

namespace fovrt {
namespace {

namespace fs = std::filesystem;

// 2: FovVideoVDP scores; 3: denoise and metric times; 4: the hash of each file a scene loaded
constexpr int kPartVersion = 5;

nlohmann::json Vec2Json(const vec2& v) { return {v.x, v.y}; }
vec2 Vec2From(const nlohmann::json& j) { return vec2(j.at(0).get<float>(), j.at(1).get<float>()); }

// A SceneRecord's fields in part.json, one list for the writer and the reader: `field(key, member)`
// over a SceneRecord or a const one.
template <class Record, class Field>
void RecordFields(Record& r, Field&& field) {
    field("index", r.index);
    field("label", r.label);
    field("requested", r.requested);
    field("source", r.source);
    field("fingerprint", r.fingerprint);
    field("files", r.files);
    field("render_ms", r.times.renderMs);
    field("reference_ms", r.times.referenceMs);
    field("denoise_ms", r.times.denoiseMs);
    field("metric_ms", r.times.metricMs);
    field("reference_hits", r.referenceHits);
    field("reference_lookups", r.referenceLookups);
    field("eye_frames", r.eyeFrames);
    field("blink_frames", r.blinkFrames);
    field("rays", r.rays);
    field("dropped_samples", r.droppedSamples);
    field("traced_samples", r.tracedSamples);
    field("traced_pixels", r.tracedPixels);
    field("guide_pixels", r.guidePixels);
    field("has_visuals", r.hasVisuals);
}

// The scalar fields of a report's visuals.json, likewise.
template <class Visuals, class Field>
void VisualsFields(Visuals& v, Field&& field) {
    field("scene", v.scene);
    field("width", v.width);
    field("height", v.height);
    field("frame", v.frame);
    field("eye", v.eye);
    field("seed", v.seed);
    field("fovea_radius_px", v.foveaRadiusPixels);
}

// A VdpScore's fields, likewise.
template <class Score, class Field>
void VdpScoreFields(Score& s, Field&& field) {
    field("scene", s.scene);
    field("seed", s.seed);
    field("eye", s.eye);
    field("variant", s.variant);
    field("jod", s.jod);
    field("jod_sustained", s.jodSustained);
    field("jod_transient", s.jodTransient);
}

// A *Fields list's `field` that writes each member into a JSON object, and one that reads it back.
struct JsonFieldWriter {
    nlohmann::json& json;
    template <class V>
    void operator()(const char* key, const V& value) const { json[key] = value; }
};
struct JsonFieldReader {
    const nlohmann::json& json;
    template <class V>
    void operator()(const char* key, V& value) const { json.at(key).get_to(value); }
};

void WriteVisuals(const fs::path& dir, const SceneVisuals& v) {
    fs::create_directories(dir);
    nlohmann::json marks = nlohmann::json::array();
    for (const GazeMark& m : v.gazeMarks) marks.push_back({m.frame, m.blink, m.speedDegPerSecond, m.timeSeconds, m.foveaDistanceDeg, m.outsideFovea,
                          m.gazeHeld, m.yawDeg, m.pitchDeg});
    nlohmann::json path = nlohmann::json::array();
    for (const vec2& p : v.gazePath) path.push_back(Vec2Json(p));
    nlohmann::json variants = nlohmann::json::array();
    std::vector<ExrLayer> layers;
    if (!v.reference.empty()) layers.push_back(ExrLayer::FromPlane("reference", v.reference));
    if (!v.noisy.empty()) layers.push_back(ExrLayer::FromPlane("noisy", v.noisy));
    if (!v.sppMap.empty()) layers.push_back(ExrLayer::FromPlane("spp", v.sppMap));
    for (size_t i = 0; i < v.variants.size(); ++i) {
        variants.push_back(v.variants[i].first);
        layers.push_back(ExrLayer::FromPlane(fmt::format("variant{}", i), v.variants[i].second));
    }
    nlohmann::json vdpMaps = nlohmann::json::array();
    for (const auto& [name, map] : v.vdpMaps) {
        layers.push_back(ExrLayer::FromPlane(fmt::format("vdp{}", vdpMaps.size()), map));
        vdpMaps.push_back(name);
    }
    nlohmann::json meta = nlohmann::json::object();
    VisualsFields(v, JsonFieldWriter{meta});
    meta["gaze_marks"] = marks;
    meta["gaze_path"] = path;
    meta["gaze_pixel"] = Vec2Json(v.gazePixel);
    meta["variants"] = variants;
    meta["vdp_maps"] = vdpMaps;
    meta["has_images"] = !layers.empty();
    WriteTextAtomically(dir / "visuals.json", meta.dump() + "\n");  // a full disk is an error, not a cut-off file
    if (!layers.empty()) WriteExrLayers(dir / "visuals.exr", v.width, v.height, layers);
}

SceneVisuals ReadVisuals(const fs::path& dir) {
    std::ifstream in(dir / "visuals.json");
    const nlohmann::json meta = nlohmann::json::parse(in);
    SceneVisuals v;
    VisualsFields(v, JsonFieldReader{meta});
    for (const auto& m : meta.at("gaze_marks")) {
        GazeMark& mark = v.gazeMarks.emplace_back();
        m.at(0).get_to(mark.frame), m.at(1).get_to(mark.blink), m.at(2).get_to(mark.speedDegPerSecond);
        m.at(3).get_to(mark.timeSeconds), m.at(4).get_to(mark.foveaDistanceDeg), m.at(5).get_to(mark.outsideFovea);
        m.at(6).get_to(mark.gazeHeld), m.at(7).get_to(mark.yawDeg), m.at(8).get_to(mark.pitchDeg);
    }
    for (const auto& p : meta.at("gaze_path")) v.gazePath.push_back(Vec2From(p));
    v.gazePixel = Vec2From(meta.at("gaze_pixel"));
    if (!meta.at("has_images").get<bool>()) return v;
    const ExrImage image = ReadExr(dir / "visuals.exr");
    if (image.Has("reference.R")) v.reference = ReadRgbExr(dir / "visuals.exr", "reference");
    if (image.Has("noisy.R")) v.noisy = ReadRgbExr(dir / "visuals.exr", "noisy");
    if (image.Has("spp")) {
        v.sppMap = Plane<uint16_t>(image.width, image.height);
        const auto& spp = image.Uints("spp");
        for (size_t i = 0; i < spp.size(); ++i) v.sppMap[i] = uint16_t(spp[i]);
    }
    const auto& names = meta.at("variants");
    for (size_t i = 0; i < names.size(); ++i)
        v.variants.emplace_back(names[i].get<std::string>(), ReadRgbExr(dir / "visuals.exr", fmt::format("variant{}", i)));
    const auto& maps = meta.at("vdp_maps");
    for (size_t i = 0; i < maps.size(); ++i) {
        const std::vector<float>& values = image.Floats(fmt::format("vdp{}", i));
        Plane<float>& map = v.vdpMaps[maps[i].get<std::string>()] = Plane<float>(image.width, image.height);
        std::copy(values.begin(), values.end(), &map[0]);
    }
    return v;
}

nlohmann::json RecordJson(const SceneRecord& r) {
    nlohmann::json j = nlohmann::json::object();
    RecordFields(r, JsonFieldWriter{j});
    return j;
}

nlohmann::json VdpScoresJson(const std::vector<VdpScore>& scores) {
    nlohmann::json out = nlohmann::json::array();
    for (const VdpScore& s : scores) {
        nlohmann::json j = nlohmann::json::object();
        VdpScoreFields(s, JsonFieldWriter{j});
        out.push_back(std::move(j));
    }
    return out;
}

// rows.tsv: a header line with the key the rows were made for (experiment fingerprint, shard) and
// the checksum of every line after it, then the rows as text that reads back bit-identical
// (%.17g); fields never contain tabs or newlines.
constexpr const char* kRowsHeader = "# fovrt-rows";

std::string RowsHeader(const std::string& fingerprint, const std::string& shard, size_t rows,
                       const std::string& checksum) {
    return fmt::format("{} experiment={} shard={} rows={} checksum={}", kRowsHeader, fingerprint, shard, rows,
                       checksum);
}

void WriteRows(const fs::path& path, const Results& results, const std::string& fingerprint,
               const std::string& shard) {
    std::string body;
    for (const ResultRow& r : results.rows())
        body += fmt::format("{}\t{}\t{}\t{}\t{}\t{}\t{}\t{:.17g}\n", r.scene, r.seed, r.frame, r.eye, r.variant,
                            r.region, r.metric, r.value);
    std::ofstream out(path, std::ios::binary);
    out << RowsHeader(fingerprint, shard, results.rows().size(), HashHex(body)) << '\n' << body;
    out.close();
    if (!out) Fail("cannot write {}", path.string());
}

std::string ReadWholeFile(const fs::path& path, const char* what) {
    std::ifstream in(path, std::ios::binary);
    if (!in) Fail("missing {}", what);
    std::ostringstream text;
    text << in.rdbuf();
    if (in.bad()) Fail("{}: cannot read", what);
    return text.str();
}

// Reads rows.tsv after checking that it was made for this experiment and shard and is unchanged.
void ReadRows(const fs::path& path, const std::string& fingerprint, const std::string& shard, Results& results) {
    const std::string text = ReadWholeFile(path, "rows.tsv");
    const size_t headerEnd = text.find('\n');
    const std::string header = text.substr(0, headerEnd == std::string::npos ? text.size() : headerEnd);
    const std::string body = headerEnd == std::string::npos ? "" : text.substr(headerEnd + 1);
    if (header.rfind(kRowsHeader, 0) != 0) Fail("rows.tsv: no '{}' header line (not written by this fovrt)", kRowsHeader);
    std::map<std::string, std::string> fields;
    std::stringstream words(header.substr(std::string(kRowsHeader).size()));
    for (std::string word; words >> word;)
        if (size_t eq = word.find('='); eq != std::string::npos) fields[word.substr(0, eq)] = word.substr(eq + 1);
    if (fields["experiment"] != fingerprint || fields["shard"] != shard)
        Fail("rows.tsv was made for experiment {} {}, not {} {}", fields["experiment"], fields["shard"], fingerprint,
             shard);
    if (fields["checksum"] != HashHex(body))
        Fail("rows.tsv: checksum mismatch (the file changed after it was written)");
    size_t number = 1;
    std::stringstream lines(body);
    for (std::string line; std::getline(lines, line);) {
        ++number;
        std::vector<std::string> f;
        std::stringstream row(line);
        for (std::string field; std::getline(row, field, '\t');) f.push_back(field);
        if (f.size() != 8) Fail("rows.tsv: line {}: {} fields, expected 8", number, f.size());
        ResultRow r;
        r.scene = f[0];
        r.seed = uint32_t(std::stoul(f[1]));
        r.frame = std::stoi(f[2]);
        r.eye = std::stoi(f[3]);
        r.variant = f[4];
        r.region = f[5];
        r.metric = f[6];
        char* end = nullptr;
        r.value = std::strtod(f[7].c_str(), &end);
        if (f[7].empty() || *end) Fail("rows.tsv: line {}: value '{}' is not a number", number, f[7]);
        results.Add(std::move(r));
    }
    if (std::to_string(results.rows().size()) != fields["rows"])
        Fail("rows.tsv holds {} rows, its header says {}", results.rows().size(), fields["rows"]);
}

// part.json is sealed the same way: "checksum" is the hash of the rest of the document as dumped
// (object keys sorted, numbers round-trip), and "files" the hash of each visuals file.
constexpr const char* kPartChecksum = "checksum";

std::string PartChecksum(nlohmann::json meta) {
    meta.erase(kPartChecksum);
    return HashHex(meta.dump());
}

std::string FileChecksum(const fs::path& path, const std::string& name) {
    return HashHex(ReadWholeFile(path, name.c_str()));
}

}  // namespace

std::string ShardSelection::Name() const { return fmt::format("shard-{}-of-{}", index, count); }

ShardSelection ParseShard(const std::string& text) {
    ShardSelection s;
    char tail = 0;
    if (std::sscanf(text.c_str(), "%d/%d%c", &s.index, &s.count, &tail) != 2 || s.count < 1 || s.index < 0 ||
        s.index >= s.count)
        Fail("--shard {}: expected I/N with 0 ≤ I < N (e.g. 0/3, 1/3, 2/3)", text);
    return s;
}

std::vector<RunUnit> ExperimentUnits(size_t scenes, size_t seeds, size_t variants) {
    std::vector<RunUnit> units;
    for (size_t sc = 0; sc < scenes; ++sc)
        for (size_t sd = 0; sd < seeds; ++sd)
            for (int eye = 0; eye < 2; ++eye)
                for (size_t v = 0; v < variants; ++v) units.push_back({sc, sd, eye, v});
    return units;
}

std::pair<size_t, size_t> ShardBlock(size_t count, const ShardSelection& selection) {
    const size_t shards = size_t(selection.count), i = size_t(selection.index);
    return {i * count / shards, (i + 1) * count / shards};
}

std::vector<RunUnit> ShardUnits(const std::vector<RunUnit>& all, const ShardSelection& selection) {
    const auto [begin, end] = ShardBlock(all.size(), selection);
    return std::vector<RunUnit>(all.begin() + long(begin), all.begin() + long(end));
}

void PassTimings::Add(const std::string& variant, const std::string& pass, double ms, int count) {
    auto& [sum, n] = sums_[variant][pass];
    sum += ms;
    n += count;
    if (std::find(order_.begin(), order_.end(), variant) == order_.end()) order_.push_back(variant);
}

void PassTimings::Merge(const PassTimings& other) {
    for (const std::string& variant : other.order_)
        for (const auto& [pass, sc] : other.sums_.at(variant)) Add(variant, pass, sc.first, sc.second);
}

ReportTable PassTimings::ToReport(const std::string& title) const {
    ReportTable table{title, {"variant", "pass", "mean ms", "samples"}, {}};
    for (const std::string& variant : order_)
        for (const auto& [pass, sc] : sums_.at(variant))
            table.rows.push_back({variant, pass, fmt::format("{:.3f}", sc.first / double(sc.second)),
                                  std::to_string(sc.second)});
    return table;
}

nlohmann::json PassTimings::MeansJson() const {
    nlohmann::json j = nlohmann::json::object();
    for (const auto& [variant, passes] : sums_)
        for (const auto& [pass, sc] : passes) j[variant][pass] = sc.first / double(sc.second);
    return j;
}

nlohmann::json PassTimings::ToJson() const {
    nlohmann::json j = nlohmann::json::array();
    for (const std::string& variant : order_)
        for (const auto& [pass, sc] : sums_.at(variant)) j.push_back({variant, pass, sc.first, sc.second});
    return j;
}

PassTimings PassTimings::FromJson(const nlohmann::json& json) {
    PassTimings t;
    for (const auto& e : json) t.Add(e.at(0), e.at(1), e.at(2), e.at(3));
    return t;
}

void SortRowsCanonically(Results& results, const std::map<std::string, size_t>& sceneIndex,
                         const std::vector<uint32_t>& seeds, const std::vector<std::string>& variants) {
    auto indexOf = [](const auto& list, const auto& value) {
        return size_t(std::find(list.begin(), list.end(), value) - list.begin());
    };
    std::vector<ResultRow> rows = results.rows();
    std::stable_sort(rows.begin(), rows.end(), [&](const ResultRow& a, const ResultRow& b) {
        auto key = [&](const ResultRow& r) {
            const auto scene = sceneIndex.find(r.scene);
            return std::make_tuple(scene == sceneIndex.end() ? sceneIndex.size() : scene->second,
                                   indexOf(seeds, r.seed), r.frame, r.eye, indexOf(variants, r.variant));
        };
        return key(a) < key(b);
    });
    Results sorted;
    sorted.relMseEpsilon = results.relMseEpsilon;
    for (ResultRow& r : rows) sorted.Add(std::move(r));
    results = std::move(sorted);
}

std::string ExperimentFingerprint(const ExperimentSpec& spec) {
    nlohmann::json j = {{"config", ConfigToJson(spec.config)}, {"scenes", spec.scenes},
                        {"variants", spec.variants},           {"seeds", spec.seeds},
                        {"baseline", spec.baseline},           {"visual_frame", spec.visualFrame},
                        {"quick", spec.quick},                 {"replay", spec.replay ? spec.replay->ToJson() : nullptr}};
    // Where outputs and the cache live and how many threads trace do not change what a shard
    // computes (the tracer is deterministic for any thread count).
    j["config"].erase("output");
    j["config"]["reference"].erase("cache_dir");
    j["config"]["run"].erase("threads");
    if (spec.scoredFoveation) {  // a sweep's point: scored in the experiment's fovea
        RunConfig scored = spec.config;
        scored.foveation = *spec.scoredFoveation;
        j["scored_foveation"] = ConfigToJson(scored)["foveation"];
    }
    return HashHex(j.dump());
}

void WriteShardPart(const fs::path& shardsDir, const ShardSelection& selection, const std::string& fingerprint,
                    const ExperimentPart& part) {
    fs::create_directories(shardsDir);
    char host[256] = "host";
    ::gethostname(host, sizeof host - 1);
    const fs::path final = shardsDir / selection.Name();
    const fs::path temp = shardsDir / fmt::format(".{}.tmp-{}-{}", selection.Name(), host, ::getpid());
    fs::remove_all(temp);
    fs::create_directories(temp);
    try {
        WriteRows(temp / "rows.tsv", part.results, fingerprint, selection.Name());
        nlohmann::json scenes = nlohmann::json::array();
        nlohmann::json files = nlohmann::json::object();
        for (const SceneRecord& r : part.scenes) {
            scenes.push_back(RecordJson(r));
            if (!r.hasVisuals) continue;
            const std::string dir = fmt::format("visuals-{}", r.index);
            WriteVisuals(temp / dir, r.visuals);
            for (const char* file : {"visuals.json", "visuals.exr"})
                if (fs::exists(temp / dir / file)) files[dir + "/" + file] = FileChecksum(temp / dir / file, file);
        }
        nlohmann::json meta = {{"format", "fovrt-experiment-part"},
                               {"version", kPartVersion},
                               {"index", selection.index},
                               {"count", selection.count},
                               {"experiment", fingerprint},
                               {"scenes", scenes},
                               {"timings", part.timings.ToJson()},
                               {"device", part.deviceDescription},
                               {"replay", part.replayRecord},
                               {"rows", part.results.rows().size()},
                               {"files", files},
                               {"vdp_display", part.vdpDisplay},
                               {"vdp", VdpScoresJson(part.vdp)}};
        meta[kPartChecksum] = PartChecksum(meta);
        std::ofstream json(temp / "part.json");
        json << meta.dump(1) << "\n";
        json.close();
        if (!json) Fail("cannot write {}", (temp / "part.json").string());
        // The part is complete on disk before it gets its final name.
        ThrowIfInterrupted();
        // A rerun replaces an earlier part whole: the old one goes only once the new one is complete.
        const fs::path old = shardsDir / fmt::format(".{}.old-{}-{}", selection.Name(), host, ::getpid());
        if (fs::exists(final)) fs::rename(final, old);
        fs::rename(temp, final);
        fs::remove_all(old);
    } catch (...) {
        std::error_code ignored;
        fs::remove_all(temp, ignored);
        throw;
    }
}

namespace {

// One shard's part read back and verified (nothing of it is used before every part verified).
struct LoadedPart {
    nlohmann::json meta;
    Results results;
    std::vector<SceneRecord> scenes;
};

LoadedPart LoadPart(const fs::path& dir, const ShardSelection& selection, const std::string& fingerprint) {
    LoadedPart part;
    const std::string text = ReadWholeFile(dir / "part.json", "part.json");
    try {
        part.meta = nlohmann::json::parse(text);
    } catch (const std::exception& e) {
        Fail("part.json: not valid JSON ({})", e.what());
    }
    const nlohmann::json& meta = part.meta;
    if (!meta.is_object() || meta.value("format", "") != "fovrt-experiment-part" ||
        meta.value("version", 0) != kPartVersion)
        Fail("part.json: not a fovrt experiment part of version {}", kPartVersion);
    if (meta.value(kPartChecksum, "") != PartChecksum(meta))
        Fail("part.json: checksum mismatch (the file changed after it was written)");
    if (meta.at("experiment") != fingerprint)
        Fail("was computed for another experiment (config, scenes, variants or seeds differ)");
    if (meta.at("index") != selection.index || meta.at("count") != selection.count)
        Fail("part.json was made for shard {}/{}", meta.at("index").dump(), meta.at("count").dump());
    ReadRows(dir / "rows.tsv", fingerprint, selection.Name(), part.results);
    if (part.results.rows().size() != meta.at("rows").get<size_t>())
        Fail("rows.tsv holds {} rows, part.json says {}", part.results.rows().size(), meta.at("rows").get<size_t>());
    for (const auto& [file, checksum] : meta.at("files").items())
        if (FileChecksum(dir / file, file) != checksum)
            Fail("{}: checksum mismatch (the file changed after it was written)", file);
    for (const auto& j : meta.at("scenes")) {
        SceneRecord r;
        RecordFields(r, JsonFieldReader{j});
        if (r.hasVisuals) r.visuals = ReadVisuals(dir / fmt::format("visuals-{}", r.index));
        part.scenes.push_back(std::move(r));
    }
    return part;
}

// "" when every shard that rendered a scene loaded the same content for it; else, for the first
// scene that differs, the shards and the files whose hashes differ between them.
std::string SceneContentProblem(const std::vector<LoadedPart>& parts) {
    std::map<size_t, std::pair<std::string, const SceneRecord*>> first;  // scene -> (shard, record)
    for (const LoadedPart& part : parts) {
        const std::string shard =
            ShardSelection{part.meta.at("index").get<int>(), part.meta.at("count").get<int>()}.Name();
        for (const SceneRecord& r : part.scenes) {
            const auto [it, inserted] = first.try_emplace(r.index, shard, &r);
            const SceneRecord& f = *it->second.second;
            if (inserted || (f.fingerprint == r.fingerprint && f.files == r.files)) continue;
            std::set<std::string> changed;
            for (const auto& [file, hash] : f.files)
                if (!r.files.count(file) || r.files.at(file) != hash) changed.insert(file);
            for (const auto& [file, hash] : r.files)
                if (!f.files.count(file)) changed.insert(file);
            return fmt::format("scene '{}' ({}) changed between {} and {}: {}", r.label, r.source, it->second.first,
                               shard,
                               changed.empty() ? std::string("its loaded content differs")
                                               : fmt::format("files that differ: {}", fmt::join(changed, ", ")));
        }
    }
    return "";
}

}  // namespace

ExperimentPart MergeShardParts(const fs::path& shardsDir, const std::string& fingerprint,
                               const std::string& rerunCommand) {
    if (!fs::is_directory(shardsDir)) Fail("--merge: {} holds no shards (run the shards first: {})",
                                           shardsDir.string(), rerunCommand);
    std::map<int, fs::path> parts;
    int count = 0;
    for (const auto& entry : fs::directory_iterator(shardsDir)) {
        const std::string name = entry.path().filename().string();
        if (name.rfind("shard-", 0) != 0) continue;  // temporaries of shards still running or killed
        int i = 0, n = 0;
        char tail = 0;
        if (std::sscanf(name.c_str(), "shard-%d-of-%d%c", &i, &n, &tail) != 2) continue;
        if (count && n != count)
            Fail("--merge: {} mixes shard counts ({} and {}): remove the stale ones", shardsDir.string(), count, n);
        count = n;
        parts[i] = entry.path();
    }
    if (!count) Fail("--merge: {} holds no shards (run the shards first: {})", shardsDir.string(), rerunCommand);
    // Every part is checked before any is used, and every problem is reported at once.
    std::vector<std::string> missing, bad;
    std::vector<LoadedPart> loaded;
    for (int i = 0; i < count; ++i) {
        if (!parts.count(i)) {
            missing.push_back(fmt::format("{}/{}", i, count));
            continue;
        }
        try {
            loaded.push_back(LoadPart(parts[i], ShardSelection{i, count}, fingerprint));
        } catch (const std::exception& e) {
            bad.push_back(fmt::format("{}: {}", parts[i].string(), e.what()));
        }
    }
    if (!missing.empty() || !bad.empty()) {
        std::string problems;
        if (!missing.empty()) problems = fmt::format("missing {}", fmt::join(missing, ", "));
        for (const std::string& b : bad) problems += (problems.empty() ? "" : "; ") + b;
        Fail("--merge: cannot merge {}: {} (rerun those shards: {})", shardsDir.string(), problems, rerunCommand);
    }

    if (const std::string problem = SceneContentProblem(loaded); !problem.empty())
        Fail("--merge: cannot merge {}: {} (rerun the shards of the scene as it is now: {})", shardsDir.string(), problem,
             rerunCommand);

    ExperimentPart merged;
    std::map<size_t, SceneRecord> scenes;
    for (LoadedPart& part : loaded) {
        const nlohmann::json& meta = part.meta;
        for (const ResultRow& row : part.results.rows()) merged.results.Add(row);
        merged.timings.Merge(PassTimings::FromJson(meta.at("timings")));
        if (merged.deviceDescription.empty()) merged.deviceDescription = meta.at("device");
        if (merged.replayRecord.is_null()) merged.replayRecord = meta.at("replay");
        if (merged.vdpDisplay.empty()) merged.vdpDisplay = meta.at("vdp_display").get<std::string>();
        for (const auto& j : meta.at("vdp")) VdpScoreFields(merged.vdp.emplace_back(), JsonFieldReader{j});
        for (SceneRecord& r : part.scenes) {
            auto it = scenes.find(r.index);
            if (it == scenes.end()) {
                scenes.emplace(r.index, std::move(r));
                continue;
            }
            SceneRecord& m = it->second;
            m.times += r.times;
            m.referenceHits += r.referenceHits;
            m.referenceLookups += r.referenceLookups;
            m.eyeFrames += r.eyeFrames;
            m.blinkFrames = std::max(m.blinkFrames, r.blinkFrames);  // counted by the first seed's shards alike
            m.rays += r.rays;
            m.droppedSamples += r.droppedSamples;
            for (size_t i = 0; i < m.tracedSamples.size(); ++i) {
                m.tracedSamples[i] += r.tracedSamples[i];
                m.tracedPixels[i] += r.tracedPixels[i];
                m.guidePixels[i] += r.guidePixels[i];
            }
            if (r.hasVisuals) {
                if (!m.hasVisuals) {
                    auto variants = std::move(m.visuals.variants);
                    auto maps = std::move(m.visuals.vdpMaps);
                    m.visuals = std::move(r.visuals);
                    for (auto& v : variants) m.visuals.variants.push_back(std::move(v));
                    for (auto& [name, map] : maps) m.visuals.vdpMaps[name] = std::move(map);
                    m.hasVisuals = true;
                } else {
                    for (auto& v : r.visuals.variants) m.visuals.variants.push_back(std::move(v));
                    for (auto& [name, map] : r.visuals.vdpMaps) m.visuals.vdpMaps[name] = std::move(map);
                }
            }
        }
    }
    for (auto& [index, r] : scenes) merged.scenes.push_back(std::move(r));
    return merged;
}

}  // namespace fovrt
