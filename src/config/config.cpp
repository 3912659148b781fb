#include "config/config.h"
#include "config/config_cli.h"
#include "config/config_io.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <type_traits>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <toml++/toml.h>

#include "core/check.h"
#include "core/error.h"
#include "core/nearest_name.h"
#include "denoise/params.h"
#include "denoise/variants.h"
#include "metrics/vdp_display.h"
#include "vk/device_choice.h"

namespace fovrt {
namespace {

// Where each leaf key came from ("a.toml:12", "--set", "--memory-budget", "JSON").
using Origins = std::map<std::string, std::string>;

// Tables the schema knows; every other table is an unknown key. The denoiser parameters' tables
// ([denoise.svgf], ...) come from their keys in denoise/params.cpp.
const std::set<std::string>& KnownSections() {
    static const std::set<std::string> sections = [] {
        std::set<std::string> names = {"scene", "camera",  "run",    "render",   "foveation",
                                       "gaze",  "denoise", "output", "reference", "metric"};
        names.insert("denoise.rae");  // RaeParams: string keys, outside the numeric tables
        const DenoiserParams defaults;
        ForEachDenoiserParam(defaults, [&](const ParamInfo& info, const auto&) {
            const std::string key = info.key;
            names.insert(key.substr(0, key.rfind('.')));
        });
        return names;
    }();
    return sections;
}

std::string TypeName(const toml::node& node) {
    switch (node.type()) {
        case toml::node_type::table: return "table";
        case toml::node_type::array: return "array";
        case toml::node_type::string: return "string";
        case toml::node_type::integer: return "integer";
        case toml::node_type::floating_point: return "float";
        case toml::node_type::boolean: return "boolean";
        default: return "date/time";
    }
}

void RecordOrigins(const toml::table& table, const std::string& prefix, const std::string& file,
                   Origins& origins) {
    for (const auto& [key, node] : table) {
        std::string path = prefix.empty() ? std::string(key.str()) : prefix + "." + std::string(key.str());
        if (const toml::table* sub = node.as_table()) {
            RecordOrigins(*sub, path, file, origins);
            // A table's own line (its [header]); implicit tables have none.
            if (sub->empty() || node.source().begin.line > 0)
                origins[path] = fmt::format("{}:{}", file, node.source().begin.line);
        } else {
            origins[path] = fmt::format("{}:{}", file, node.source().begin.line);
        }
    }
}

// Deep-merges `src` into `dst` (src wins), recording `origin` for every leaf it sets.
void Merge(toml::table& dst, const toml::table& src, const std::string& prefix, const std::string& origin,
           Origins& origins) {
    for (const auto& [key, node] : src) {
        std::string k(key.str());
        std::string path = prefix.empty() ? k : prefix + "." + k;
        if (const toml::table* sub = node.as_table()) {
            toml::node* existing = dst.get(k);
            if (existing && !existing->is_table()) Fail("{}: '{}' is a value, not a table", origin, path);
            if (!existing) dst.insert(k, toml::table{});
            Merge(*dst.get(k)->as_table(), *sub, path, origin, origins);
        } else {
            node.visit([&](const auto& value) { dst.insert_or_assign(k, value); });
            origins[path] = origin;
        }
    }
}

// Sets one dotted key (from --set) to `value`.
void SetPath(toml::table& root, const std::string& path, const toml::node& value, const std::string& origin,
             Origins& origins) {
    toml::table* table = &root;
    size_t start = 0;
    while (true) {
        size_t dot = path.find('.', start);
        std::string segment = path.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
        if (segment.empty()) Fail("{}: bad key '{}' (empty segment)", origin, path);
        if (dot == std::string::npos) {
            value.visit([&](const auto& v) { table->insert_or_assign(segment, v); });
            origins[path] = origin;
            return;
        }
        toml::node* next = table->get(segment);
        if (!next) {
            table->insert(segment, toml::table{});
            next = table->get(segment);
        }
        if (!next->is_table())
            Fail("{}: '{}' is a value, not a table", origin, path.substr(0, dot));
        table = next->as_table();
        start = dot + 1;
    }
}

// Reads typed values from the merged table, remembering which keys the schema consumed.
class Reader {
public:
    Reader(const toml::table& root, const Origins& origins) : root_(root), origins_(origins) {}

    [[noreturn]] void Bad(const std::string& key, const std::string& message) const {
        auto it = origins_.find(key);
        if (it != origins_.end()) Fail("config key '{}' ({}): {}", key, it->second, message);
        Fail("config key '{}': {}", key, message);
    }

    const toml::node* Find(const std::string& key) {
        used_.insert(key);
        toml::node_view<const toml::node> view = root_.at_path(key);
        return view.node();
    }

    void Int(const std::string& key, int& out, int64_t lo, int64_t hi) {
        int64_t v = out;
        Int64(key, v, lo, hi);
        out = int(v);
    }
    void Int(const std::string& key, int& out, const ParamRange& range) {
        const toml::node* n = Find(key);
        if (!n) return;
        if (!n->is_integer()) Bad(key, fmt::format("expected an integer, got {}", TypeName(*n)));
        int64_t v = n->as_integer()->get();
        if (!range.Contains(double(v))) Bad(key, fmt::format("{} is out of range {}", v, range.Describe()));
        out = int(v);
    }
    void Int64(const std::string& key, int64_t& out, int64_t lo, int64_t hi) {
        const toml::node* n = Find(key);
        if (!n) return;
        if (!n->is_integer()) Bad(key, fmt::format("expected an integer, got {}", TypeName(*n)));
        int64_t v = n->as_integer()->get();
        if (v < lo || v > hi) Bad(key, fmt::format("{} is out of range [{}, {}]", v, lo, hi));
        out = v;
    }
    void Float(const std::string& key, float& out, double lo, double hi, bool loOpen = false) {
        Float(key, out, ParamRange{lo, hi, loOpen, false});
    }
    void Float(const std::string& key, float& out, const ParamRange& range) {
        const toml::node* n = Find(key);
        if (!n) return;
        double v;
        if (n->is_integer()) v = double(n->as_integer()->get());
        else if (n->is_floating_point()) v = n->as_floating_point()->get();
        else Bad(key, fmt::format("expected a number, got {}", TypeName(*n)));
        if (!range.Contains(v)) Bad(key, fmt::format("{} is out of range {}", v, range.Describe()));
        out = float(v);
    }
    void Double(const std::string& key, double& out) {
        const toml::node* n = Find(key);
        if (!n) return;
        if (n->is_integer()) out = double(n->as_integer()->get());
        else if (n->is_floating_point()) out = n->as_floating_point()->get();
        else Bad(key, fmt::format("expected a number, got {}", TypeName(*n)));
        if (!std::isfinite(out)) Bad(key, "must be finite");
    }
    void Bool(const std::string& key, bool& out) {
        const toml::node* n = Find(key);
        if (!n) return;
        if (!n->is_boolean()) Bad(key, fmt::format("expected true or false, got {}", TypeName(*n)));
        out = n->as_boolean()->get();
    }
    void String(const std::string& key, std::string& out, const std::vector<std::string>& allowed = {}) {
        const toml::node* n = Find(key);
        if (!n) return;
        if (!n->is_string()) Bad(key, fmt::format("expected a string, got {}", TypeName(*n)));
        std::string v = n->as_string()->get();
        if (allowed.size() != 0) {
            bool ok = false;
            std::string list;
            for (const std::string& a : allowed) {
                ok = ok || v == a;
                list += (list.empty() ? "" : ", ") + a;
            }
            if (!ok) Bad(key, fmt::format("'{}' is not one of {} (did you mean '{}'?)", v, list, NearestName(v, allowed)));
        }
        out = v;
    }
    void Strings(const std::string& key, std::vector<std::string>& out) {
        const toml::node* n = Find(key);
        if (!n) return;
        if (n->is_string()) {
            out = {n->as_string()->get()};
            return;
        }
        if (!n->is_array()) Bad(key, fmt::format("expected an array of strings, got {}", TypeName(*n)));
        std::vector<std::string> v;
        for (const toml::node& e : *n->as_array()) {
            if (!e.is_string()) Bad(key, fmt::format("expected an array of strings, found a {}", TypeName(e)));
            v.push_back(e.as_string()->get());
        }
        out = v;
    }
    // A fixed-size array of numbers.
    template <size_t N>
    bool Numbers(const std::string& key, std::array<float, N>& out) {
        const toml::node* n = Find(key);
        if (!n) return false;
        const toml::array* a = n->as_array();
        if (!a || a->size() != N) Bad(key, fmt::format("expected an array of {} numbers", N));
        for (size_t i = 0; i < N; ++i) {
            const toml::node& e = *a->get(i);
            double v;
            if (e.is_integer()) v = double(e.as_integer()->get());
            else if (e.is_floating_point()) v = e.as_floating_point()->get();
            else Bad(key, fmt::format("expected an array of {} numbers, found a {}", N, TypeName(e)));
            if (!std::isfinite(v)) Bad(key, "values must be finite");
            out[i] = float(v);
        }
        return true;
    }
    void Vec2(const std::string& key, vec2& out) {
        std::array<float, 2> a{out.x, out.y};
        if (Numbers(key, a)) out = vec2(a[0], a[1]);
    }
    // A denoiser parameter: its type is the member's, its range the table row's.
    void Param(const ParamInfo& info, float& out) { Float(info.key, out, info.range); }
    void Param(const ParamInfo& info, int& out) { Int(info.key, out, info.range); }
    void Param(const ParamInfo& info, bool& out) { Bool(info.key, out); }

    // Every key present but not consumed by the schema is an error.
    void CheckUnknown(const toml::table& table, const std::string& prefix) const {
        for (const auto& [key, node] : table) {
            std::string path = prefix.empty() ? std::string(key.str()) : prefix + "." + std::string(key.str());
            if (used_.count(path)) continue;
            if (node.is_table() && KnownSections().count(path)) {
                CheckUnknown(*node.as_table(), path);
                continue;
            }
            auto it = origins_.find(path);
            if (it == origins_.end() && node.is_table() && !node.as_table()->empty()) {
                // An unknown table: report its first key (which has an origin).
                CheckUnknownLeaf(*node.as_table(), path);
            }
            Fail("unknown config key '{}'{}{}", path, it != origins_.end() ? " (" + it->second + ")" : "", Suggest(path));
        }
    }

private:
    // " (did you mean 'camera.width'?)": the nearest key the schema knows.
    std::string Suggest(const std::string& key) const {
        const std::string nearest = NearestName(key, used_);
        return nearest.empty() ? std::string() : fmt::format(" (did you mean '{}'?)", nearest);
    }

    void CheckUnknownLeaf(const toml::table& table, const std::string& prefix) const {
        for (const auto& [key, node] : table) {
            std::string path = prefix + "." + std::string(key.str());
            auto it = origins_.find(path);
            if (it != origins_.end())
                Fail("unknown config key '{}' ({}){}", path, it->second, Suggest(path));
            if (node.is_table()) CheckUnknownLeaf(*node.as_table(), path);
        }
    }

    const toml::table& root_;
    const Origins& origins_;
    std::set<std::string> used_;
};

RunConfig Build(const toml::table& root, const Origins& origins, const std::string& sources,
                const std::vector<std::string>& ignoredTables = {}) {
    RunConfig c;
    Reader r(root, origins);
    constexpr int64_t kMaxInt = std::numeric_limits<int>::max();

    // memory_budget: bytes as an integer, or a size string ("2GiB").
    if (const toml::node* n = r.Find("memory_budget")) {
        if (n->is_integer()) {
            int64_t v = n->as_integer()->get();
            if (v < 0) r.Bad("memory_budget", fmt::format("{} must be >= 0 (0 = no budget)", v));
            c.memoryBudget = uint64_t(v);
        } else if (n->is_string()) {
            try {
                c.memoryBudget = ParseByteSize(n->as_string()->get(), "memory_budget");
            } catch (const Error& e) {
                r.Bad("memory_budget", e.what());
            }
        } else {
            r.Bad("memory_budget", fmt::format("expected bytes (integer or \"512MiB\"), got {}", TypeName(*n)));
        }
    }

    r.String("scene.name", c.scene.name);
    if (c.scene.name.empty()) r.Bad("scene.name", "must not be empty");

    r.Int("camera.width", c.camera.width, 1, 16384);
    r.Int("camera.height", c.camera.height, 1, 16384);
    std::array<float, 4> fov{};
    if (r.Numbers("camera.fov_deg", fov)) {
        for (float a : fov)
            if (!(std::abs(a) < 90.0f)) r.Bad("camera.fov_deg", "angles must lie in (-90, 90) degrees");
        if (!(fov[0] < fov[1])) r.Bad("camera.fov_deg", "left must be < right ([left, right, up, down])");
        if (!(fov[3] < fov[2])) r.Bad("camera.fov_deg", "down must be < up ([left, right, up, down])");
        c.camera.fovDeg = fov;
    }
    r.Float("camera.ipd", c.camera.ipd, 0.0, 1.0);

    r.Int("run.frames", c.run.frames, 1, kMaxInt);
    r.Int("run.first_frame", c.run.firstFrame, 0, kMaxInt);
    r.Float("run.fps", c.run.fps, 0.0, 10000.0);
    int64_t seed = c.run.seed;
    r.Int64("run.seed", seed, 0, std::numeric_limits<uint32_t>::max());
    c.run.seed = uint32_t(seed);
    r.Int("run.threads", c.run.threads, 0, 4096);
    r.Int("run.max_depth", c.run.maxDepth, 0, 1024);
    r.Bool("run.score", c.run.score);
    r.String("render.demodulation", c.render.demodulation, {"albedo", "brdf"});

    FoveationConfig& f = c.foveation;
    r.String("foveation.model", f.model, {"disc", "linear", "acuity", "uniform"});
    r.Int("foveation.spp_inside", f.sppInside, 1, kMaxSpp);
    r.Int("foveation.spp_outside", f.sppOutside, 1, kMaxSpp);
    r.Float("foveation.radius_px", f.radiusPx, 0.0, 1e6, true);
    r.Int("foveation.radius_reference_width", f.radiusReferenceWidth, 1, 16384);
    r.Float("foveation.radius_deg", f.radiusDeg, 0.0, 179.0);
    r.Int("foveation.spp_max", f.sppMax, 1, kMaxSpp);
    r.Int("foveation.spp_min", f.sppMin, 1, kMaxSpp);
    r.Float("foveation.foveal_deg", f.fovealDeg, 0.0, 180.0);
    r.Float("foveation.peripheral_deg", f.peripheralDeg, 0.0, 180.0);
    r.Float("foveation.omega0_deg", f.omega0Deg, 0.0, 10.0, true);
    r.Float("foveation.mar_slope", f.marSlope, 0.0, 10.0);
    r.Int("foveation.uniform_spp", f.uniformSpp, 1, kMaxSpp);
    r.Int64("foveation.ray_budget", f.rayBudget, 0, std::numeric_limits<int64_t>::max());
    const int64_t pixels = int64_t(c.camera.width) * c.camera.height;
    if (f.rayBudget != 0 && (f.rayBudget < pixels || f.rayBudget > pixels * kMaxSpp))
        r.Bad("foveation.ray_budget",
              fmt::format("{} is outside [width*height, {}*width*height] = [{}, {}] (0 = no budget)",
                          f.rayBudget, kMaxSpp, pixels, pixels * kMaxSpp));
    if (f.peripheralDeg <= f.fovealDeg)
        r.Bad("foveation.peripheral_deg",
              fmt::format("{} must be > foveation.foveal_deg = {}", f.peripheralDeg, f.fovealDeg));

    GazeConfig& g = c.gaze;
    r.String("gaze.source", g.source, {"lissajous", "trace", "recording", "static", "mouse"});
    r.String("gaze.units", g.units, {"px", "deg"});
    r.Vec2("gaze.amplitude", g.amplitude);
    r.Vec2("gaze.frequency_hz", g.frequencyHz);
    r.Vec2("gaze.phase_deg", g.phaseDeg);
    r.Vec2("gaze.offset", g.offset);
    r.Int("gaze.reference_width", g.referenceWidth, 1, 16384);
    r.Int("gaze.reference_height", g.referenceHeight, 1, 16384);
    r.String("gaze.trace_path", g.tracePath);
    r.Double("gaze.trace_start_ms", g.traceStartMs);
    r.String("gaze.blink", g.blink, {"hold", "uniform"});
    r.Float("gaze.yaw_deg", g.yawDeg, -89.999, 89.999);
    r.Float("gaze.pitch_deg", g.pitchDeg, -89.999, 89.999);
    r.String("gaze.recording_path", g.recordingPath);
    TrackerParams& t = g.tracker;  // ranges: ValidateTrackerParams (gaze/tracker.cpp)
    r.Double("gaze.tracker_rate_hz", t.rateHz);
    r.Double("gaze.tracker_phase_ms", t.phaseMs);
    r.Double("gaze.tracker_latency_ms", t.latencyMs);
    r.Float("gaze.tracker_noise_deg", t.noiseDeg, 0.0, 45.0);
    r.Vec2("gaze.tracker_bias_deg", t.biasDeg);
    r.Double("gaze.tracker_dropout", t.dropout);
    r.Double("gaze.tracker_blink_ms", t.blinkMs);
    int64_t trackerSeed = t.seed;
    r.Int64("gaze.tracker_seed", trackerSeed, 0, std::numeric_limits<uint32_t>::max());
    t.seed = uint32_t(trackerSeed);
    r.String("gaze.prediction", t.prediction, {"none", "cv", "landing"});
    r.Float("gaze.saccade_deg_s", t.saccadeDegPerS, 0.0, 2000.0, true);
    if (g.source == "trace" && g.tracePath.empty())
        r.Bad("gaze.trace_path", "must be set when gaze.source = \"trace\"");
    if (g.frequencyHz.x < 0 || g.frequencyHz.y < 0) r.Bad("gaze.frequency_hz", "must be >= 0");

    DenoiseConfig& d = c.denoise;
    r.Strings("denoise.denoisers", d.denoisers);
    for (const std::string& name : d.denoisers) {
        if (name.empty()) r.Bad("denoise.denoisers", "names must not be empty");
        if (auto problem = DenoiserNameProblem(name)) r.Bad("denoise.denoisers", *problem);
    }
    // A device index may be given as a number (device = 1) or a string ("1").
    if (const toml::node* n = r.Find("denoise.device"); n && n->is_integer()) {
        if (n->as_integer()->get() < 0) r.Bad("denoise.device", "a device index must be >= 0");
        d.device = std::to_string(n->as_integer()->get());
    } else {
        r.String("denoise.device", d.device);
    }
    if (!ParseDeviceSetting(d.device))
        r.Bad("denoise.device", fmt::format("'{}' is not {} (Vulkan devices present: {})", d.device,
                                            kDeviceSettingForms, DescribeVulkanDevices(VulkanContext::ListDevices())));
    std::string precision = PrecisionName(d.params.precision);
    std::vector<std::string> precisionNames;
    for (const PrecisionRow& row : PrecisionTable()) precisionNames.push_back(row.name);
    r.String(kPrecisionKey, precision, precisionNames);
    PrecisionFromName(precision, d.params.precision);
    r.String(kRaeWeightsKey, d.params.rae.weights);
    if (d.params.rae.weights.empty()) r.Bad(kRaeWeightsKey, "must not be empty");
    r.String(kRaeWeightsSppKey, d.params.rae.weightsSpp);
    if (d.params.rae.weightsSpp.empty()) r.Bad(kRaeWeightsSppKey, "must not be empty");
    ForEachDenoiserParam(d.params, [&](const ParamInfo& info, auto& value) { r.Param(info, value); });
    if (std::optional<ParamProblem> problem = DenoiserParamConflict(d.params))
        r.Bad(problem->key, problem->message);

    r.String("output.dir", c.output.dir);
    if (c.output.dir.empty()) r.Bad("output.dir", "must not be empty");
    r.Bool("output.write_exr", c.output.writeExr);
    r.Bool("output.write_png", c.output.writePng);
    r.Bool("output.write_inputs", c.output.writeInputs);
    r.Float("output.exposure", c.output.exposure, -64.0, 64.0);
    r.Bool("output.report", c.output.report);

    r.Int("reference.spp", c.reference.spp, 1, 1 << 24);
    int64_t referenceSeed = c.reference.seed;
    r.Int64("reference.seed", referenceSeed, 0, std::numeric_limits<uint32_t>::max());
    c.reference.seed = uint32_t(referenceSeed);
    r.String("reference.cache_dir", c.reference.cacheDir);

    r.Bool("metric.vdp", c.metric.vdp);
    std::vector<std::string> displays = {"camera"};
    for (const VdpDisplay& d : VdpDisplayProfiles()) displays.push_back(d.name);
    r.String("metric.display", c.metric.display, displays);
    r.Float("metric.ppd", c.metric.ppd, 0.0, 1000.0);
    r.Float("metric.peak", c.metric.peak, 0.0, 100000.0);

    toml::table checked = root;
    for (const std::string& name : ignoredTables) checked.erase(name);
    r.CheckUnknown(checked, "");

    // The modules' own validation (same key names) as a last line of defence.
    try {
        ValidateFoveationParams(c.foveation);
        ValidateGazeParams(c.gaze);
        ValidateDenoiserParams(c.denoise.params);
    } catch (const Error& e) {
        Fail("{} (config: {})", e.what(), sources);
    }
    return c;
}

// Shortest decimal that round-trips the float, as a double: manifests show 0.063, not 0.0630000010.
double CleanFloat(float v) { return std::stod(fmt::format("{}", v)); }

toml::array TomlArray(std::initializer_list<float> values) {
    toml::array a;
    for (float v : values) a.push_back(CleanFloat(v));
    return a;
}

// Sets a dotted key ("denoise.svgf.alpha_color") of `root`, making the tables on the way.
template <class Value>
void InsertAt(toml::table& root, const std::string& key, Value value) {
    toml::table* table = &root;
    size_t start = 0;
    for (size_t dot = key.find('.'); dot != std::string::npos; dot = key.find('.', start)) {
        const std::string segment = key.substr(start, dot - start);
        if (!table->contains(segment)) table->insert(segment, toml::table{});
        table = table->get(segment)->as_table();
        start = dot + 1;
    }
    table->insert_or_assign(key.substr(start), value);
}

// The denoiser parameters from their tables: floats as their shortest decimal, like every float.
void InsertDenoiserParams(toml::table& root, const DenoiserParams& p) {
    InsertAt(root, kPrecisionKey, std::string(PrecisionName(p.precision)));
    InsertAt(root, kRaeWeightsKey, p.rae.weights);
    InsertAt(root, kRaeWeightsSppKey, p.rae.weightsSpp);
    ForEachDenoiserParam(p, [&](const ParamInfo& info, const auto& value) {
        if constexpr (std::is_same_v<std::decay_t<decltype(value)>, float>) InsertAt(root, info.key, CleanFloat(value));
        else InsertAt(root, info.key, value);
    });
}

toml::table ToTable(const RunConfig& c) {
    const FoveationConfig& f = c.foveation;
    const GazeConfig& g = c.gaze;
    toml::table camera{{"width", c.camera.width}, {"height", c.camera.height}, {"ipd", CleanFloat(c.camera.ipd)}};
    if (c.camera.fovDeg) {
        const auto& v = *c.camera.fovDeg;
        camera.insert("fov_deg", TomlArray({v[0], v[1], v[2], v[3]}));
    }
    toml::array denoisers;
    for (const std::string& name : c.denoise.denoisers) denoisers.push_back(name);
    toml::table root{
        {"memory_budget", int64_t(c.memoryBudget)},
        {"scene", toml::table{{"name", c.scene.name}}},
        {"camera", camera},
        {"run", toml::table{{"frames", c.run.frames},
                            {"first_frame", c.run.firstFrame},
                            {"fps", CleanFloat(c.run.fps)},
                            {"seed", int64_t(c.run.seed)},
                            {"threads", c.run.threads},
                            {"max_depth", c.run.maxDepth},
                            {"score", c.run.score}}},
        {"render", toml::table{{"demodulation", c.render.demodulation}}},
        {"foveation", toml::table{{"model", f.model},
                                  {"spp_inside", f.sppInside},
                                  {"spp_outside", f.sppOutside},
                                  {"radius_px", CleanFloat(f.radiusPx)},
                                  {"radius_reference_width", f.radiusReferenceWidth},
                                  {"radius_deg", CleanFloat(f.radiusDeg)},
                                  {"spp_max", f.sppMax},
                                  {"spp_min", f.sppMin},
                                  {"foveal_deg", CleanFloat(f.fovealDeg)},
                                  {"peripheral_deg", CleanFloat(f.peripheralDeg)},
                                  {"omega0_deg", CleanFloat(f.omega0Deg)},
                                  {"mar_slope", CleanFloat(f.marSlope)},
                                  {"uniform_spp", f.uniformSpp},
                                  {"ray_budget", f.rayBudget}}},
        {"gaze", toml::table{{"source", g.source},
                             {"units", g.units},
                             {"amplitude", TomlArray({g.amplitude.x, g.amplitude.y})},
                             {"frequency_hz", TomlArray({g.frequencyHz.x, g.frequencyHz.y})},
                             {"phase_deg", TomlArray({g.phaseDeg.x, g.phaseDeg.y})},
                             {"offset", TomlArray({g.offset.x, g.offset.y})},
                             {"reference_width", g.referenceWidth},
                             {"reference_height", g.referenceHeight},
                             {"trace_path", g.tracePath},
                             {"trace_start_ms", g.traceStartMs},
                             {"blink", g.blink},
                             {"yaw_deg", CleanFloat(g.yawDeg)},
                             {"pitch_deg", CleanFloat(g.pitchDeg)},
                             {"recording_path", g.recordingPath},
                             {"tracker_rate_hz", g.tracker.rateHz},
                             {"tracker_phase_ms", g.tracker.phaseMs},
                             {"tracker_latency_ms", g.tracker.latencyMs},
                             {"tracker_noise_deg", CleanFloat(g.tracker.noiseDeg)},
                             {"tracker_bias_deg", TomlArray({g.tracker.biasDeg.x, g.tracker.biasDeg.y})},
                             {"tracker_dropout", g.tracker.dropout},
                             {"tracker_blink_ms", g.tracker.blinkMs},
                             {"tracker_seed", int64_t(g.tracker.seed)},
                             {"prediction", g.tracker.prediction},
                             {"saccade_deg_s", CleanFloat(g.tracker.saccadeDegPerS)}}},
        {"denoise", toml::table{{"denoisers", denoisers}, {"device", c.denoise.device}}},
        {"output", toml::table{{"dir", c.output.dir},
                               {"write_exr", c.output.writeExr},
                               {"write_png", c.output.writePng},
                               {"write_inputs", c.output.writeInputs},
                               {"exposure", CleanFloat(c.output.exposure)},
                               {"report", c.output.report}}},
        {"reference", toml::table{{"spp", c.reference.spp},
                                  {"seed", int64_t(c.reference.seed)},
                                  {"cache_dir", c.reference.cacheDir}}},
        {"metric", toml::table{{"vdp", c.metric.vdp},
                               {"display", c.metric.display},
                               {"ppd", CleanFloat(c.metric.ppd)},
                               {"peak", CleanFloat(c.metric.peak)}}},
    };
    InsertDenoiserParams(root, c.denoise.params);
    return root;
}

nlohmann::json NodeToJson(const toml::node& node) {
    if (const toml::table* t = node.as_table()) {
        nlohmann::json j = nlohmann::json::object();
        for (const auto& [key, value] : *t) j[std::string(key.str())] = NodeToJson(value);
        return j;
    }
    if (const toml::array* a = node.as_array()) {
        nlohmann::json j = nlohmann::json::array();
        for (const toml::node& e : *a) j.push_back(NodeToJson(e));
        return j;
    }
    if (node.is_string()) return node.as_string()->get();
    if (node.is_integer()) return node.as_integer()->get();
    if (node.is_floating_point()) return node.as_floating_point()->get();
    if (node.is_boolean()) return node.as_boolean()->get();
    return nullptr;
}

// JSON -> TOML node; `path` names the key in errors. null members are skipped (= default).
void JsonIntoTable(const nlohmann::json& j, toml::table& out, const std::string& prefix);

toml::array JsonToArray(const nlohmann::json& j, const std::string& path) {
    toml::array a;
    for (const nlohmann::json& e : j) {
        if (e.is_string()) a.push_back(e.get<std::string>());
        else if (e.is_boolean()) a.push_back(e.get<bool>());
        else if (e.is_number_integer()) a.push_back(e.get<int64_t>());
        else if (e.is_number()) a.push_back(e.get<double>());
        else Fail("JSON config key '{}': arrays may hold only strings, numbers and booleans", path);
    }
    return a;
}

void JsonIntoTable(const nlohmann::json& j, toml::table& out, const std::string& prefix) {
    for (const auto& [key, value] : j.items()) {
        std::string path = prefix.empty() ? key : prefix + "." + key;
        if (value.is_null()) continue;
        if (value.is_object()) {
            toml::table sub;
            JsonIntoTable(value, sub, path);
            out.insert(key, std::move(sub));
        } else if (value.is_array()) {
            out.insert(key, JsonToArray(value, path));
        } else if (value.is_string()) {
            out.insert(key, value.get<std::string>());
        } else if (value.is_boolean()) {
            out.insert(key, value.get<bool>());
        } else if (value.is_number_unsigned() && value.get<uint64_t>() > uint64_t(std::numeric_limits<int64_t>::max())) {
            Fail("JSON config key '{}': {} is too large", path, value.get<uint64_t>());
        } else if (value.is_number_integer()) {
            out.insert(key, value.get<int64_t>());
        } else {
            out.insert(key, value.get<double>());
        }
    }
}

void RecordAll(const toml::table& table, const std::string& prefix, const std::string& origin, Origins& origins) {
    for (const auto& [key, node] : table) {
        std::string path = prefix.empty() ? std::string(key.str()) : prefix + "." + std::string(key.str());
        if (const toml::table* sub = node.as_table()) RecordAll(*sub, path, origin, origins);
        else origins[path] = origin;
    }
}

toml::table ParseTomlFile(const std::string& path, Origins& origins) {
    if (!std::filesystem::exists(path)) Fail("config file '{}' does not exist", path);
    try {
        toml::table table = toml::parse_file(path);
        RecordOrigins(table, "", path, origins);
        return table;
    } catch (const toml::parse_error& e) {
        Fail("{}:{}:{}: {}", path, e.source().begin.line, e.source().begin.column, e.description());
    }
}

}  // namespace

uint64_t ParseByteSize(const std::string& text, const std::string& what) {
    std::string s;
    for (char ch : text)
        if (!std::isspace(static_cast<unsigned char>(ch))) s += ch;
    size_t split = 0;
    while (split < s.size() && (std::isdigit(static_cast<unsigned char>(s[split])) || s[split] == '.')) ++split;
    double number = 0.0;
    auto [ptr, ec] = std::from_chars(s.data(), s.data() + split, number);
    if (split == 0 || ec != std::errc() || ptr != s.data() + split)
        Fail("{}: '{}' is not a byte size (e.g. 1073741824, 512MiB, 2GB)", what, text);
    std::string unit;
    for (char ch : s.substr(split)) unit += char(std::tolower(static_cast<unsigned char>(ch)));
    static const std::map<std::string, double> kUnits = {
        {"", 1.0},        {"b", 1.0},
        {"k", 0x1p10},    {"kib", 0x1p10}, {"kb", 1e3},
        {"m", 0x1p20},    {"mib", 0x1p20}, {"mb", 1e6},
        {"g", 0x1p30},    {"gib", 0x1p30}, {"gb", 1e9},
        {"t", 0x1p40},    {"tib", 0x1p40}, {"tb", 1e12}};
    auto it = kUnits.find(unit);
    if (it == kUnits.end())
        Fail("{}: unknown unit in '{}' (use B, KiB, MiB, GiB, TiB, KB, MB, GB, TB)", what, text);
    double bytes = number * it->second;
    if (!(bytes < 0x1p63)) Fail("{}: '{}' is too large", what, text);
    return uint64_t(std::llround(bytes));
}

Fov EyeFov(const CameraConfig& camera, float sceneHorizontalFovDegrees) {
    if (camera.fovDeg) {
        const auto& a = *camera.fovDeg;
        return Fov{Radians(a[0]), Radians(a[1]), Radians(a[2]), Radians(a[3])};
    }
    return Fov::FromHorizontal(Radians(sceneHorizontalFovDegrees), float(camera.width) / float(camera.height));
}

double FrameTimeSeconds(const RunSettings& run, float sceneFrameRate, int frame) {
    double fps = run.fps > 0.0f ? double(run.fps) : double(sceneFrameRate);
    FOVRT_CHECK_OP(fps, >, 0.0);
    return double(frame) / fps;
}

RunConfig DefaultConfig() { return Build(toml::table{}, {}, "defaults"); }

RunConfig LoadConfigFile(const std::string& path) {
    Origins origins;
    toml::table table = ParseTomlFile(path, origins);
    return Build(table, origins, path);
}

RunConfig ConfigFromTomlString(const std::string& text, const std::string& origin) {
    Origins origins;
    try {
        toml::table table = toml::parse(text, origin);
        RecordOrigins(table, "", origin, origins);
        return Build(table, origins, origin);
    } catch (const toml::parse_error& e) {
        Fail("{}:{}:{}: {}", origin, e.source().begin.line, e.source().begin.column, e.description());
    }
}

RunConfig ConfigFromJson(const nlohmann::json& json) {
    if (!json.is_object()) Fail("JSON config must be an object");
    toml::table table;
    JsonIntoTable(json, table, "");
    Origins origins;
    RecordAll(table, "", "JSON", origins);
    return Build(table, origins, "JSON");
}

std::string ConfigToToml(const RunConfig& config) {
    std::ostringstream out;
    // toml++ prints doubles with 17 significant digits (0.20000000000000001): exact, if not pretty.
    // Its relaxed-precision mode keeps only 6 digits, which would break the round trip.
    out << ToTable(config) << "\n";
    return out.str();
}

nlohmann::json ConfigToJson(const RunConfig& config) { return NodeToJson(ToTable(config)); }

void AddConfigOptions(CLI::App* command, ConfigOptions& options) {
    command->add_option("-c,--config", options.configPath, "TOML config file (defaults apply to absent keys)");
    command->add_option("--set", options.sets,
                        "Override one config key: section.key=value (TOML value; repeatable)")
        ->allow_extra_args(false);
    command->add_option("--memory-budget", options.memoryBudget,
                        "Memory budget in bytes (e.g. 2GiB); 0 = none. Overrides memory_budget");
}

namespace {

// One --set: parses `section.key=value` (a TOML value, else a bare string) into `root`.
void ApplySet(const std::string& set, toml::table& root, Origins& origins) {
    std::string origin = "--set " + set;
    size_t eq = set.find('=');
    if (eq == std::string::npos || eq == 0) Fail("--set '{}': expected section.key=value", set);
    std::string key = set.substr(0, eq);
    std::string value = set.substr(eq + 1);
    while (!key.empty() && std::isspace(static_cast<unsigned char>(key.back()))) key.pop_back();
    // Every value ends up in a JSON manifest, which must be UTF-8: refuse it now, naming the key,
    // rather than after the whole render when the manifest is written (nlohmann's own check).
    for (const std::string* text : {&key, &value}) {
        try {
            (void)nlohmann::json(*text).dump();
        } catch (const nlohmann::json::type_error&) {
            std::string shown = nlohmann::json(key).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
            Fail("--set {}: the {} is not valid UTF-8 (config values are written to JSON manifests)",
                 shown.substr(1, shown.size() - 2), text == &key ? "key" : "value");
        }
    }
    try {
        toml::table parsed = toml::parse("v = " + value);
        SetPath(root, key, *parsed.get("v"), origin, origins);
    } catch (const toml::parse_error&) {
        // Not a TOML value: take it as a bare string (paths, scene names).
        SetPath(root, key, toml::value<std::string>(value), origin, origins);
    }
}

// True when `set` names a key inside one of `tables` (e.g. --set experiment.quick.run.frames=2).
bool SetsInside(const std::string& set, const std::vector<std::string>& tables) {
    for (const std::string& table : tables)
        if (set.rfind(table + ".", 0) == 0) return true;
    return false;
}

// Every source merged into one table (defaults are Build's): base, file, overlays, --set,
// --memory-budget. A --set inside an overlay table edits that table before it is merged, so it
// acts exactly like the same key in the file.
toml::table ResolveTable(const ConfigOptions& options, Origins& origins, std::string& sources) {
    toml::table root;
    sources = "defaults";
    if (!options.base.is_null()) {
        if (!options.base.is_object()) Fail("{}: the config is not a JSON object", options.baseOrigin);
        JsonIntoTable(options.base, root, "");
        RecordAll(root, "", options.baseOrigin, origins);
        sources = options.baseOrigin;
    }
    if (!options.configPath.empty() && options.base.is_null()) {
        root = ParseTomlFile(options.configPath, origins);
        sources = options.configPath;
    } else if (!options.configPath.empty()) {
        Origins fileOrigins;
        toml::table file = ParseTomlFile(options.configPath, fileOrigins);
        Merge(root, file, "", options.configPath, origins);
        for (const auto& [key, origin] : fileOrigins) origins[key] = origin;  // file:line
        sources += " + " + options.configPath;
    }
    for (const std::string& set : options.sets)
        if (SetsInside(set, options.overlayTables)) ApplySet(set, root, origins);
    for (const std::string& overlay : options.overlayTables) {
        toml::node_view<toml::node> view = root.at_path(overlay);
        if (!view) continue;  // the file has no such table: nothing to merge
        if (!view.is_table()) Fail("config table '{}' is not a table ({})", overlay, sources);
        // Origins of the overlay's keys: where the table's own keys came from (file:line or
        // --set), keyed by the merged path.
        Origins overlayOrigins;
        for (const auto& [key, origin] : origins)
            if (key.rfind(overlay + ".", 0) == 0) overlayOrigins[key.substr(overlay.size() + 1)] = origin;
        toml::table copy = *view.as_table();
        Merge(root, copy, "", "[" + overlay + "]", origins);
        for (const auto& [key, origin] : overlayOrigins) origins[key] = origin + " [" + overlay + "]";
        sources += " + [" + overlay + "]";
    }
    for (const std::string& set : options.sets) {
        if (SetsInside(set, options.overlayTables)) continue;
        ApplySet(set, root, origins);
        sources += " + --set";
    }
    if (!options.memoryBudget.empty()) {
        uint64_t bytes = ParseByteSize(options.memoryBudget, "--memory-budget");
        if (bytes > uint64_t(std::numeric_limits<int64_t>::max())) Fail("--memory-budget: too large");
        root.insert_or_assign("memory_budget", int64_t(bytes));
        origins["memory_budget"] = "--memory-budget";
    }
    return root;
}

}  // namespace

RunConfig ResolveConfig(const ConfigOptions& options) {
    Origins origins;
    std::string sources;
    toml::table root = ResolveTable(options, origins, sources);
    return Build(root, origins, sources, options.ignoredTables);
}

std::string ExperimentTable::Origin(const std::string& key) const {
    auto it = origins.find(key);
    return it != origins.end() ? it->second : file;
}

RunConfig ResolveExperimentConfig(const ConfigOptions& options, bool quick, ExperimentTable& experiment) {
    ConfigOptions resolved = options;
    resolved.ignoredTables.push_back("experiment");
    if (quick) resolved.overlayTables.push_back("experiment.quick");
    Origins origins;
    std::string sources;
    toml::table root = ResolveTable(resolved, origins, sources);
    RunConfig config = Build(root, origins, sources, resolved.ignoredTables);
    // [experiment] as merged from the file and every --set experiment.KEY, with each key's origin.
    experiment = ExperimentTable{};
    experiment.file = options.configPath;
    if (toml::node* node = root.get("experiment")) {
        if (!node->is_table()) {
            auto it = origins.find("experiment");
            Fail("{}: 'experiment' must be a table", it != origins.end() ? it->second : sources);
        }
        experiment.table = *node->as_table();
    }
    for (const auto& [key, origin] : origins)
        if (key.rfind("experiment.", 0) == 0) experiment.origins[key.substr(11)] = origin;
    return config;
}

}  // namespace fovrt
