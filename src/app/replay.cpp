#include "app/replay.h"

#include <cstdio>
#include <map>

#include <fmt/format.h>

#include "config/config_cli.h"
#include "config/config_io.h"
#include "core/error.h"
#include "denoise/variants.h"
#include "pipeline/build_info.h"
#include "pipeline/reference_cache.h"

namespace fovrt {
namespace {

enum class KeyRule { kFree, kSupplied, kChanges, kRefused };

struct ReplayKeyRule {
    const char* key;  // a leaf key, or a table with its dot ("foveation.")
    KeyRule rule;
    const char* why;  // what the key does to a replay
};

// Every config key's effect on a replay (replay.h); the longest matching row wins, and a key no
// row matches changes the frames (a new key is assumed to matter until it is listed here).
constexpr ReplayKeyRule kReplayKeyRules[] = {
    {"scene.", KeyRule::kRefused, "the recorded poses belong to the recorded scene"},
    {"camera.width", KeyRule::kChanges, "the recorded eyes rendered at another size"},
    {"camera.height", KeyRule::kChanges, "the recorded eyes rendered at another size"},
    {"camera.fov_deg", KeyRule::kSupplied, "each recorded eye has its FOV"},
    {"camera.ipd", KeyRule::kSupplied, "each recorded eye has its position"},
    {"run.frames", KeyRule::kSupplied, "every recorded frame is rendered"},
    {"run.first_frame", KeyRule::kSupplied, "every recorded frame is rendered"},
    {"run.warmup_frames", KeyRule::kRefused, "a replay renders the recorded frames only"},
    {"run.fps", KeyRule::kSupplied, "each recorded frame has its scene time"},
    {"run.seed", KeyRule::kChanges, "seeds every sample"},
    {"run.max_depth", KeyRule::kChanges, "the path length"},
    {"run.threads", KeyRule::kFree, "images are identical for any thread count"},
    {"run.score", KeyRule::kFree, "scores the frames after they are rendered"},
    {"render.demodulation", KeyRule::kChanges, "what direct / indirect are divided by"},
    {"gaze.", KeyRule::kSupplied, "each recorded frame has its gaze sample"},
    {"gaze.blink", KeyRule::kChanges, "builds the spp maps of the recorded blinks"},
    {"foveation.", KeyRule::kChanges, "builds the spp maps"},
    {"denoise.", KeyRule::kFree, "denoising follows rendering"},
    {"output.", KeyRule::kFree, "outputs only"},
    {"reference.", KeyRule::kFree, "references only"},
    {"memory_budget", KeyRule::kFree, "a check only"},
};

const ReplayKeyRule* RuleOf(const std::string& key) {
    const ReplayKeyRule* best = nullptr;
    size_t bestLength = 0;
    for (const ReplayKeyRule& row : kReplayKeyRules) {
        const std::string prefix = row.key;
        const bool table = prefix.back() == '.';
        const bool match = table ? key.compare(0, prefix.size(), prefix) == 0 : key == prefix;
        if (match && prefix.size() > bestLength) {
            best = &row;
            bestLength = prefix.size();
        }
    }
    return best;
}

// Leaf key -> value of a config's JSON (arrays are leaves).
void Flatten(const nlohmann::json& json, const std::string& prefix, std::map<std::string, nlohmann::json>& out) {
    for (const auto& [key, value] : json.items()) {
        const std::string path = prefix.empty() ? key : prefix + "." + key;
        if (value.is_object()) Flatten(value, path, out);
        else out[path] = value;
    }
}

std::string Show(const std::map<std::string, nlohmann::json>& leaves, const std::string& key) {
    auto it = leaves.find(key);
    return it == leaves.end() ? "(absent)" : it->second.dump();
}

bool NeedsGradientSamples(const DenoiseConfig& denoise) {
    return RendererNeedsOf(denoise.denoisers, "denoise.denoisers").gradientSamples;
}

// Sets a dotted key of a JSON object (making the objects on the way); `value` null = erase it.
void SetLeaf(nlohmann::json& root, const std::string& key, const nlohmann::json* value) {
    nlohmann::json* node = &root;
    size_t start = 0;
    for (size_t dot = key.find('.'); dot != std::string::npos; dot = key.find('.', start)) {
        node = &(*node)[key.substr(start, dot - start)];
        start = dot + 1;
    }
    if (value) (*node)[key.substr(start)] = *value;
    else node->erase(key.substr(start));
}

std::string Join(const std::vector<std::string>& items, const std::string& separator = ", ") {
    std::string out;
    for (const std::string& item : items) out += (out.empty() ? "" : separator) + item;
    return out;
}

}  // namespace

nlohmann::json Replay::ToJson() const {
    return {{"file", file.string()},
            {"frames", summary.frames},
            {"first_frame", summary.firstFrame},
            {"last_frame", summary.lastFrame},
            {"allow_changes", allowChanges},
            {"ignored_keys", ignored},
            {"changed_keys", changed}};
}

Replay OpenReplay(const std::filesystem::path& file, bool allowChanges) {
    Replay replay;
    replay.file = file;
    replay.allowChanges = allowChanges;
    {
        SessionReader reader(file);
        replay.header = reader.Header();
    }
    try {
        replay.recorded = ConfigFromJson(replay.header.at("config"));
    } catch (const Error& e) {
        Fail("{}: the recorded config: {}", file.string(), e.what());
    }
    replay.summary = ScanSession(file);
    if (replay.summary.frames == 0) Fail("{}: the recording has no frames", file.string());
    return replay;
}

RunConfig ResolveReplayConfig(Replay& replay, ConfigOptions options,
                              const std::function<RunConfig(const ConfigOptions&)>& resolve,
                              const std::string& command) {
    const std::string file = replay.file.string();
    const nlohmann::json recordedJson = ConfigToJson(replay.recorded);
    options.base = recordedJson;
    options.baseOrigin = file;
    RunConfig resolved = resolve(options);

    std::map<std::string, nlohmann::json> before, after;
    Flatten(recordedJson, "", before);
    nlohmann::json json = ConfigToJson(resolved);
    Flatten(json, "", after);
    std::vector<std::string> keys;
    for (const auto& [key, value] : before) keys.push_back(key);
    for (const auto& [key, value] : after)
        if (!before.count(key)) keys.push_back(key);

    replay.ignored.clear();
    replay.changed = nlohmann::json::array();
    std::vector<std::string> refused;  // changes without --allow-changes: all named in one line
    auto change = [&](const std::string& key, const std::string& why, bool refuseAlways) {
        if (refuseAlways)
            Fail("{}: replay: {} = {} differs from the recording's {}: {}", file, key, Show(after, key),
                 Show(before, key), why);
        if (!replay.allowChanges) {
            refused.push_back(fmt::format("{} = {} differs from the recording's {} ({})", key, Show(after, key),
                                          Show(before, key), why));
            return;
        }
        replay.changed.push_back({{"key", key}, {"value", after.count(key) ? after[key] : nullptr},
                                  {"recorded", before.count(key) ? before[key] : nullptr}});
    };
    for (const std::string& key : keys) {
        auto b = before.find(key);
        auto a = after.find(key);
        if (b != before.end() && a != after.end() && b->second == a->second) continue;
        const ReplayKeyRule* rule = RuleOf(key);
        switch (rule ? rule->rule : KeyRule::kChanges) {
            case KeyRule::kFree: break;
            case KeyRule::kSupplied:
                replay.ignored.push_back(key);
                SetLeaf(json, key, b != before.end() ? &b->second : nullptr);
                break;
            case KeyRule::kChanges: change(key, rule ? rule->why : "a key a replay does not know", false); break;
            case KeyRule::kRefused: change(key, rule->why, true); break;
        }
    }
    RunConfig config = replay.ignored.empty() ? resolved : ConfigFromJson(json);
    if (NeedsGradientSamples(replay.recorded.denoise) != NeedsGradientSamples(config.denoise))
        change("denoise.denoisers",
               "adds or drops A-SVGF gradient samples, which replace some noisy samples", false);
    if (!refused.empty())
        Fail("{}: replay: {}; the frames would differ from the recording (--allow-changes renders them anyway)", file,
             Join(refused, "; "));
    config.run.frames = int(replay.summary.frames);
    config.run.firstFrame = int(replay.summary.firstFrame);

    if (!replay.ignored.empty())
        std::fprintf(stderr, "%s: replay: the recording supplies %s (the config's values are ignored)\n",
                     command.c_str(), Join(replay.ignored).c_str());
    if (!replay.changed.empty()) {
        std::vector<std::string> keysChanged;
        for (const nlohmann::json& c : replay.changed) keysChanged.push_back(c["key"].get<std::string>());
        std::fprintf(stderr, "%s: replay with changes (--allow-changes): %s; the frames differ from the recording\n",
                     command.c_str(), Join(keysChanged).c_str());
    }
    return config;
}

RunConfig ReplayPipelineConfig(RunConfig config) {
    config.gaze = GazeParams{};
    config.gaze.source = "static";
    return config;
}

nlohmann::json SessionHeaderExtra(const FramePipeline& pipeline) {
    const Scene& scene = pipeline.GetScene();
    return {{"build", BuildInfoJson()},
            {"scene", {{"name", scene.name},
                       {"source", scene.sourcePath.string()},
                       {"fingerprint", fmt::format("{:016x}", SceneFingerprint(scene))}}}};
}

void CheckReplayScene(Replay& replay, const FramePipeline& pipeline) {
    const nlohmann::json& header = replay.header;
    if (!header.contains("scene") || !header["scene"].is_object() || !header["scene"].contains("fingerprint"))
        return;  // a recording without the scene's fingerprint (not written by fovrt's recorder)
    const nlohmann::json& fingerprint = header["scene"]["fingerprint"];
    const std::string recorded = fingerprint.is_string() ? fingerprint.get<std::string>() : fingerprint.dump();
    const std::string now = fmt::format("{:016x}", SceneFingerprint(pipeline.GetScene()));
    if (recorded == now) return;
    const std::string name = pipeline.Config().scene.name;
    if (!replay.allowChanges)
        Fail("{}: replay: scene '{}' is not the recorded one (content fingerprint {}, recorded {}): its files "
             "changed since the recording (--allow-changes renders it anyway)",
             replay.file.string(), name, now, recorded);
    std::fprintf(stderr, "replay: scene '%s' changed since the recording (fingerprint %s, recorded %s)\n",
                 name.c_str(), now.c_str(), recorded.c_str());
    replay.changed.push_back({{"key", "scene fingerprint"}, {"value", now}, {"recorded", recorded}});
}

uint32_t LastFrameOf(const RunConfig& config, const Replay* replay) {
    return replay ? replay->summary.lastFrame : uint32_t(config.run.firstFrame + config.run.frames - 1);
}

FrameSequence::FrameSequence(const FramePipeline& pipeline)
    : pipeline_(pipeline),
      first_(pipeline.Config().run.firstFrame - pipeline.Config().run.warmupFrames),
      warmup_(pipeline.Config().run.warmupFrames),
      count_(pipeline.Config().run.frames + pipeline.Config().run.warmupFrames),
      lastFrame_(LastFrameOf(pipeline.Config(), nullptr)) {
    pipeline.CheckGazeCovers(uint32_t(first_), count_);
}

FrameSequence::FrameSequence(const FramePipeline& pipeline, const Replay& replay)
    : pipeline_(pipeline), reader_(std::make_unique<SessionReader>(replay.file)),
      count_(int(replay.summary.frames)), lastFrame_(LastFrameOf(pipeline.Config(), &replay)) {
    const RunConfig& config = pipeline.Config();
    if (config.camera.width != replay.recorded.camera.width || config.camera.height != replay.recorded.camera.height) {
        width_ = config.camera.width;
        height_ = config.camera.height;
    }
}

bool FrameSequence::Next(RecordedFrame& out) {
    if (next_ >= count_) return false;
    if (reader_) {
        if (!reader_->Next(out))
            Fail("{}: the recording ended after {} of {} frames (changed while replaying?)",
                 reader_->Path().string(), next_, count_);
        if (width_ > 0)
            for (EyeCamera& eye : out.request.eyes) eye = EyeCamera(eye.pose(), eye.fov(), width_, height_);
    } else {
        const uint32_t frame = uint32_t(first_ + next_);
        out.request = pipeline_.RequestAt(frame);
        out.head = pipeline_.RigAt(frame).head;
        out.gazeSamples.assign(1, out.request.gaze);
    }
    ++next_;
    return true;
}

}  // namespace fovrt
