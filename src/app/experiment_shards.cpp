#include "app/experiment_shards.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>

#include <fmt/format.h>

#include "app/config_io.h"
#include "app/experiment.h"
#include "core/error.h"
#include "io/exr.h"

namespace fovrt {
namespace {

namespace fs = std::filesystem;

constexpr int kPartVersion = 2;  // 2: FovVideoVDP scores

// FNV-1a, as a hex string: enough to tell experiments apart, stable across machines.
std::string Hash(const std::string& text) {
    uint64_t h = 1469598103934665603ull;
    for (unsigned char c : text) {
        h ^= c;
        h *= 1099511628211ull;
    }
    return fmt::format("{:016x}", h);
}

nlohmann::json Vec2Json(const vec2& v) { return {v.x, v.y}; }
vec2 Vec2From(const nlohmann::json& j) { return vec2(j.at(0).get<float>(), j.at(1).get<float>()); }

void WriteVisuals(const fs::path& dir, const SceneVisuals& v) {
    fs::create_directories(dir);
    nlohmann::json marks = nlohmann::json::array();
    for (const GazeMark& m : v.gazeMarks) marks.push_back({m.frame, m.blink, m.speedDegPerSecond, m.timeSeconds, m.foveaDistanceDeg, m.outsideFovea});
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
    const nlohmann::json meta = {{"scene", v.scene},   {"width", v.width},
                                 {"height", v.height}, {"frame", v.frame},
                                 {"eye", v.eye},       {"seed", v.seed},
                                 {"gaze_marks", marks}, {"gaze_path", path},
                                 {"fovea_radius_px", v.foveaRadiusPixels},
                                 {"gaze_pixel", Vec2Json(v.gazePixel)},
                                 {"variants", variants},
                                 {"vdp_maps", vdpMaps},
                                 {"has_images", !layers.empty()}};
    std::ofstream(dir / "visuals.json") << meta.dump() << "\n";
    if (!layers.empty()) WriteExrLayers(dir / "visuals.exr", v.width, v.height, layers);
}

SceneVisuals ReadVisuals(const fs::path& dir) {
    std::ifstream in(dir / "visuals.json");
    const nlohmann::json meta = nlohmann::json::parse(in);
    SceneVisuals v;
    v.scene = meta.at("scene");
    v.width = meta.at("width");
    v.height = meta.at("height");
    v.frame = meta.at("frame");
    v.eye = meta.at("eye");
    v.seed = meta.at("seed");
    for (const auto& m : meta.at("gaze_marks")) v.gazeMarks.push_back({m.at(0), m.at(1), m.at(2), m.at(3), m.at(4), m.at(5)});
    for (const auto& p : meta.at("gaze_path")) v.gazePath.push_back(Vec2From(p));
    v.foveaRadiusPixels = meta.at("fovea_radius_px");
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
    return {{"index", r.index},
            {"label", r.label},
            {"requested", r.requested},
            {"source", r.source},
            {"fingerprint", r.fingerprint},
            {"render_ms", r.renderMs},
            {"reference_ms", r.referenceMs},
            {"reference_hits", r.referenceHits},
            {"reference_lookups", r.referenceLookups},
            {"eye_frames", r.eyeFrames},
            {"blink_frames", r.blinkFrames},
            {"rays", r.rays},
            {"dropped_samples", r.droppedSamples},
            {"has_visuals", r.hasVisuals}};
}

SceneRecord RecordFrom(const nlohmann::json& j) {
    SceneRecord r;
    r.index = j.at("index");
    r.label = j.at("label");
    r.requested = j.at("requested");
    r.source = j.at("source");
    r.fingerprint = j.at("fingerprint");
    r.renderMs = j.at("render_ms");
    r.referenceMs = j.at("reference_ms");
    r.referenceHits = j.at("reference_hits");
    r.referenceLookups = j.at("reference_lookups");
    r.eyeFrames = j.at("eye_frames");
    r.blinkFrames = j.at("blink_frames");
    r.rays = j.at("rays");
    r.droppedSamples = j.at("dropped_samples");
    r.hasVisuals = j.at("has_visuals");
    return r;
}

// Rows as text that reads back bit-identical (%.17g); fields never contain tabs or newlines.
nlohmann::json VdpScoresJson(const std::vector<VdpScore>& scores) {
    nlohmann::json out = nlohmann::json::array();
    for (const VdpScore& s : scores)
        out.push_back({{"scene", s.scene}, {"seed", s.seed}, {"eye", s.eye}, {"variant", s.variant},
                       {"jod", s.jod}, {"jod_sustained", s.jodSustained}, {"jod_transient", s.jodTransient}});
    return out;
}

void WriteRows(const fs::path& path, const Results& results) {
    std::ofstream out(path);
    for (const ResultRow& r : results.rows())
        out << r.scene << '\t' << r.seed << '\t' << r.frame << '\t' << r.eye << '\t' << r.variant << '\t' << r.region
            << '\t' << r.metric << '\t' << fmt::format("{:.17g}", r.value) << '\n';
    if (!out) Fail("cannot write {}", path.string());
}

void ReadRows(const fs::path& path, Results& results) {
    std::ifstream in(path);
    if (!in) Fail("{}: cannot read", path.string());
    std::string line;
    size_t number = 0;
    while (std::getline(in, line)) {
        ++number;
        std::vector<std::string> f;
        std::stringstream fields(line);
        for (std::string field; std::getline(fields, field, '\t');) f.push_back(field);
        if (f.size() != 8) Fail("{}: line {}: {} fields, expected 8", path.string(), number, f.size());
        ResultRow r;
        r.scene = f[0];
        r.seed = uint32_t(std::stoul(f[1]));
        r.frame = std::stoi(f[2]);
        r.eye = std::stoi(f[3]);
        r.variant = f[4];
        r.region = f[5];
        r.metric = f[6];
        r.value = std::strtod(f[7].c_str(), nullptr);
        results.Add(std::move(r));
    }
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

std::vector<RunUnit> ShardUnits(const std::vector<RunUnit>& all, const ShardSelection& selection) {
    const size_t n = all.size(), count = size_t(selection.count), i = size_t(selection.index);
    const size_t begin = i * n / count, end = (i + 1) * n / count;
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
    return Hash(j.dump());
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
        WriteRows(temp / "rows.tsv", part.results);
        nlohmann::json scenes = nlohmann::json::array();
        for (const SceneRecord& r : part.scenes) {
            scenes.push_back(RecordJson(r));
            if (r.hasVisuals) WriteVisuals(temp / fmt::format("visuals-{}", r.index), r.visuals);
        }
        const nlohmann::json meta = {{"format", "fovrt-experiment-part"},
                                     {"version", kPartVersion},
                                     {"index", selection.index},
                                     {"count", selection.count},
                                     {"experiment", fingerprint},
                                     {"scenes", scenes},
                                     {"timings", part.timings.ToJson()},
                                     {"device", part.deviceDescription},
                                     {"replay", part.replayRecord},
                                     {"rows", part.results.rows().size()},
                                     {"vdp_display", part.vdpDisplay},
                                     {"vdp", VdpScoresJson(part.vdp)}};
        std::ofstream(temp / "part.json") << meta.dump(1) << "\n";
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
    std::vector<std::string> missing;
    for (int i = 0; i < count; ++i)
        if (!parts.count(i)) missing.push_back(fmt::format("{}/{}", i, count));
    if (!missing.empty())
        Fail("--merge: incomplete shard set in {}: missing {} (run: {})", shardsDir.string(),
             fmt::format("{}", fmt::join(missing, ", ")), rerunCommand);

    ExperimentPart merged;
    std::map<size_t, SceneRecord> scenes;
    for (const auto& [i, dir] : parts) {
        nlohmann::json meta;
        try {
            std::ifstream in(dir / "part.json");
            meta = nlohmann::json::parse(in);
        } catch (const std::exception& e) {
            Fail("--merge: {}: unreadable part.json ({})", dir.string(), e.what());
        }
        if (meta.value("format", "") != "fovrt-experiment-part" || meta.value("version", 0) != kPartVersion)
            Fail("--merge: {}: not a fovrt experiment part of version {}", dir.string(), kPartVersion);
        if (meta.at("experiment") != fingerprint)
            Fail("--merge: {} was computed for another experiment (config, scenes, variants or seeds differ): "
                 "rerun it ({})",
                 dir.string(), rerunCommand);
        const size_t before = merged.results.rows().size();
        ReadRows(dir / "rows.tsv", merged.results);
        if (merged.results.rows().size() - before != meta.at("rows").get<size_t>())
            Fail("--merge: {}: rows.tsv holds {} rows, part.json says {}", dir.string(),
                 merged.results.rows().size() - before, meta.at("rows").get<size_t>());
        merged.timings.Merge(PassTimings::FromJson(meta.at("timings")));
        if (merged.deviceDescription.empty()) merged.deviceDescription = meta.at("device");
        if (merged.replayRecord.is_null()) merged.replayRecord = meta.at("replay");
        if (merged.vdpDisplay.empty()) merged.vdpDisplay = meta.at("vdp_display").get<std::string>();
        for (const auto& j : meta.at("vdp"))
            merged.vdp.push_back({j.at("scene"), j.at("seed"), j.at("eye"), j.at("variant"), j.at("jod"),
                                  j.at("jod_sustained"), j.at("jod_transient")});
        for (const auto& j : meta.at("scenes")) {
            SceneRecord r = RecordFrom(j);
            if (r.hasVisuals) r.visuals = ReadVisuals(dir / fmt::format("visuals-{}", r.index));
            auto it = scenes.find(r.index);
            if (it == scenes.end()) {
                scenes.emplace(r.index, std::move(r));
                continue;
            }
            SceneRecord& m = it->second;
            m.renderMs += r.renderMs;
            m.referenceMs += r.referenceMs;
            m.referenceHits += r.referenceHits;
            m.referenceLookups += r.referenceLookups;
            m.eyeFrames += r.eyeFrames;
            m.blinkFrames = std::max(m.blinkFrames, r.blinkFrames);  // counted by the first seed's shards alike
            m.rays += r.rays;
            m.droppedSamples += r.droppedSamples;
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
