#include "config/config.h"
#include "config/config_cli.h"
#include "config/config_io.h"
#include "config/settings_tables.h"

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

#include "core/error.h"
#include "core/nearest_name.h"
#include "denoise/params.h"
#include "denoise/variants.h"
#include "vk/device_choice.h"

namespace fovrt {
namespace {

// Where each leaf key came from ("a.toml:12", "--set", "--memory-budget", "JSON").
using Origins = std::map<std::string, std::string>;

// Tables the schema knows (the sections of every key of the settings tables); every other table is
// an unknown key.
const std::set<std::string>& KnownSections() {
    static const std::set<std::string> sections = [] {
        std::set<std::string> names;
        auto addSection = [&](const std::string& key) {
            if (key.find('.') != std::string::npos) names.insert(key.substr(0, key.rfind('.')));
        };
        const RunConfig defaults;
        ForEachSetting(defaults, [&](const ParamInfo& info, const auto&) { addSection(info.key); });
        addSection(kPrecisionKey);
        return names;
    }();
    return sections;
}

// The rows whose value is a path (ParamInfo::path), by key.
const std::map<std::string, const ParamInfo*>& PathRows() {
    static const std::map<std::string, const ParamInfo*> rows = [] {
        std::map<std::string, const ParamInfo*> byKey;
        const RunConfig defaults;
        ForEachSetting(defaults, [&](const ParamInfo& info, const auto&) {
            if (info.path) byKey.emplace(info.key, &info);
        });
        return byKey;
    }();
    return rows;
}

// The value `key` (a setting's key, or one inside an overlay table: experiment.quick.gaze.trace_path)
// should hold when `value` was written relative to `base`: the absolute path, for a path row's
// relative string that is not a name (ParamInfo::orName); nullopt otherwise (kept as written).
std::optional<std::string> PathFrom(const std::filesystem::path& base, const std::string& key,
                                    const toml::node& value) {
    const std::string* text = value.is_string() ? &value.as_string()->get() : nullptr;
    if (text == nullptr || text->empty() || std::filesystem::path(*text).is_absolute()) return std::nullopt;
    for (const auto& [rowKey, info] : PathRows()) {
        const bool matches = key == rowKey || (key.size() > rowKey.size() && key.ends_with("." + rowKey));
        if (!matches) continue;
        if (info->orName && text->find_first_of("/.") == std::string::npos) return std::nullopt;
        return std::filesystem::absolute(base / *text).lexically_normal().string();
    }
    return std::nullopt;
}

// Every path written relative in the config file `file` made absolute from the file's folder,
// so a preset names its recordings and weights wherever it is run from.
void ResolvePathsFromFile(toml::table& table, const std::string& prefix, const std::filesystem::path& file) {
    for (auto&& [key, node] : table) {
        const std::string path = prefix.empty() ? std::string(key.str()) : prefix + "." + std::string(key.str());
        if (toml::table* sub = node.as_table()) {
            ResolvePathsFromFile(*sub, path, file);
        } else if (std::optional<std::string> absolute = PathFrom(file.parent_path(), path, node)) {
            node.as_string()->get() = *absolute;
        }
    }
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

    // One key of a settings table: read as the member's type, checked against its row
    // (SettingValueProblem); an absent key keeps the member's value.
    void Setting(const ParamInfo& info, bool& out) {
        const toml::node* n = Find(info.key);
        if (!n) return;
        if (!n->is_boolean()) Bad(info.key, fmt::format("expected true or false, got {}", TypeName(*n)));
        out = n->as_boolean()->get();
    }
    template <class Integer>
        requires std::is_integral_v<Integer>
    void Setting(const ParamInfo& info, Integer& out) {
        const toml::node* n = Find(info.key);
        if (!n) return;
        if (!n->is_integer()) Bad(info.key, fmt::format("expected an integer, got {}", TypeName(*n)));
        Check(info, n->as_integer()->get());
        out = Integer(n->as_integer()->get());
    }
    // uint64_t members are byte sizes: an integer, or a size string ("2GiB").
    void Setting(const ParamInfo& info, uint64_t& out) {
        const toml::node* n = Find(info.key);
        if (!n) return;
        if (n->is_integer()) {
            Check(info, n->as_integer()->get());
            out = uint64_t(n->as_integer()->get());
        } else if (n->is_string()) {
            try {
                out = ParseByteSize(n->as_string()->get(), info.key);
            } catch (const Error& e) {
                Bad(info.key, e.what());
            }
        } else {
            Bad(info.key, fmt::format("expected bytes (integer or \"512MiB\"), got {}", TypeName(*n)));
        }
    }
    void Setting(const ParamInfo& info, float& out) {
        double v = out;
        Setting(info, v);
        out = float(v);
    }
    void Setting(const ParamInfo& info, double& out) {
        const toml::node* n = Find(info.key);
        if (!n) return;
        const double v = Number(info.key, *n, "a number");
        Check(info, v);
        out = v;
    }
    void Setting(const ParamInfo& info, vec2& out) {
        std::array<float, 2> a{};
        if (!Numbers(info, a)) return;
        out = vec2(a[0], a[1]);
    }
    void Setting(const ParamInfo& info, FovDegrees& out) {
        std::array<float, 4> a{};
        if (!Numbers(info, a)) return;
        out = a;
    }
    void Setting(const ParamInfo& info, std::string& out) {
        const toml::node* n = Find(info.key);
        if (!n) return;
        if (!n->is_string()) Bad(info.key, fmt::format("expected a string, got {}", TypeName(*n)));
        Check(info, std::string(n->as_string()->get()));
        out = n->as_string()->get();
    }
    void Setting(const ParamInfo& info, std::vector<std::string>& out) {
        const toml::node* n = Find(info.key);
        if (!n) return;
        if (n->is_string()) {
            out = {n->as_string()->get()};
            return;
        }
        if (!n->is_array()) Bad(info.key, fmt::format("expected an array of strings, got {}", TypeName(*n)));
        std::vector<std::string> v;
        for (const toml::node& e : *n->as_array()) {
            if (!e.is_string()) Bad(info.key, fmt::format("expected an array of strings, found a {}", TypeName(e)));
            v.push_back(e.as_string()->get());
        }
        out = v;
    }
    // The value against its row; fails naming the key and the range or names.
    template <class Value>
    void Check(const ParamInfo& info, const Value& value) const {
        if (std::optional<std::string> problem = SettingValueProblem(info, value)) Bad(info.key, *problem);
    }

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
    // An integer or a float; fails naming `key` and what it expected otherwise.
    double Number(const std::string& key, const toml::node& n, const std::string& expected) const {
        if (n.is_integer()) return double(n.as_integer()->get());
        if (n.is_floating_point()) return n.as_floating_point()->get();
        Bad(key, fmt::format("expected {}, got {}", expected, TypeName(n)));
    }
    // A fixed-size array of numbers, each in the row's range.
    template <size_t N>
    bool Numbers(const ParamInfo& info, std::array<float, N>& out) {
        const toml::node* n = Find(info.key);
        if (!n) return false;
        const toml::array* a = n->as_array();
        if (!a || a->size() != N) Bad(info.key, fmt::format("expected an array of {} numbers", N));
        for (size_t i = 0; i < N; ++i) {
            const double v = Number(info.key, *a->get(i), fmt::format("an array of {} numbers", N));
            Check(info, v);
            out[i] = float(v);
        }
        return true;
    }

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

// A device index may be given as a number (device = 1) or a string ("1"): the table's row is a
// string, so a number is turned into its text first.
toml::table WithDeviceAsText(const toml::table& root, const Origins& origins) {
    toml::table copy = root;
    toml::node_view<toml::node> device = copy.at_path("denoise.device");
    if (device.is_integer()) {
        const int64_t index = device.as_integer()->get();
        if (index < 0) Reader(root, origins).Bad("denoise.device", "a device index must be >= 0");
        copy["denoise"].as_table()->insert_or_assign("device", std::to_string(index));
    }
    return copy;
}

// The rules between keys and the checks a row cannot state (names of denoisers, devices present),
// each failing with the key's origin.
void CheckRules(const RunConfig& c, const Reader& r) {
    if (c.camera.fovDeg) {
        const auto& fov = *c.camera.fovDeg;
        if (!(fov[0] < fov[1])) r.Bad("camera.fov_deg", "left must be < right ([left, right, up, down])");
        if (!(fov[3] < fov[2])) r.Bad("camera.fov_deg", "down must be < up ([left, right, up, down])");
    }
    if (c.run.warmupFrames > c.run.firstFrame)
        r.Bad("run.warmup_frames", fmt::format("{} frames precede run.first_frame = {}: set run.first_frame to at "
                                               "least {} (the scored frames start there)",
                                               c.run.warmupFrames, c.run.firstFrame, c.run.warmupFrames));
    const FoveationConfig& f = c.foveation;
    const int64_t pixels = int64_t(c.camera.width) * c.camera.height;
    const int64_t leastBudget = int64_t(std::ceil(double(f.sppFloor) * double(pixels)));
    const int cap = BudgetSppCap(f, pixels);
    if (f.rayBudget != 0 && (f.rayBudget < leastBudget || f.rayBudget > pixels * cap))
        r.Bad("foveation.ray_budget",
              fmt::format("{} is outside [spp_floor*width*height, cap*width*height] = [{}, {}] (0 = no budget; "
                          "foveation.spp_floor = {} and {} bound the spp it may scale a pixel to)",
                          f.rayBudget, leastBudget, pixels * cap, f.sppFloor,
                          FlatSppMap(f) && cap > f.sppCap
                              ? fmt::format("the {} model's most, {} spp (every pixel at the mean)", f.model, cap)
                          : f.sppCapRatio > 0 ? fmt::format("the cap of {} (foveation.spp_cap_ratio = {} times the mean)",
                                                            cap, f.sppCapRatio)
                                              : fmt::format("foveation.spp_cap = {}", cap)));
    const DenoiseConfig& d = c.denoise;
    std::map<std::string, std::string> spelled;  // canonical name → the first spelling of it
    for (const std::string& name : d.denoisers) {
        if (name.empty()) r.Bad("denoise.denoisers", "names must not be empty");
        if (auto problem = DenoiserNameProblem(name)) {
            r.Bad("denoise.denoisers", *problem);
            continue;
        }
        // Two spellings of one composition would run the same denoiser twice under two names.
        const auto [first, fresh] = spelled.emplace(CanonicalDenoiserName(name), name);
        if (!fresh)
            r.Bad("denoise.denoisers", fmt::format("'{}' and '{}' are the same denoiser ({}); list it once",
                                                   first->second, name, first->first));
    }
    if (!ParseDeviceSetting(d.device))
        r.Bad("denoise.device", fmt::format("'{}' is not {} (Vulkan devices present: {})", d.device,
                                            kDeviceSettingForms, DescribeVulkanDevices(VulkanContext::ListDevices())));
    for (const std::optional<ParamProblem>& problem :
         {FoveationParamConflict(f), GazeParamConflict(c.gaze), DenoiserParamConflict(d.params)})
        if (problem) r.Bad(problem->key, problem->message);
}

RunConfig Build(const toml::table& given, const Origins& origins, const std::string& sources,
                const std::vector<std::string>& ignoredTables = {}) {
    const toml::table root = WithDeviceAsText(given, origins);
    RunConfig c;
    Reader r(root, origins);
    ForEachSetting(c, [&](const ParamInfo& info, auto& value) { r.Setting(info, value); });
    std::string precision = PrecisionName(c.denoise.params.precision);
    r.Setting(kPrecisionInfo, precision);
    PrecisionFromName(precision, c.denoise.params.precision);
    CheckRules(c, r);

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
    table->insert_or_assign(key.substr(start), std::move(value));
}

// One setting as TOML: floats as their shortest decimal, integers as TOML's 64-bit integers.
template <class Value>
auto TomlValue(const Value& value) {
    if constexpr (std::is_same_v<Value, float>) {
        return CleanFloat(value);
    } else if constexpr (std::is_same_v<Value, bool> || std::is_same_v<Value, double> ||
                         std::is_same_v<Value, std::string>) {
        return value;
    } else if constexpr (std::is_integral_v<Value>) {
        return int64_t(value);
    } else if constexpr (std::is_same_v<Value, vec2>) {
        toml::array a;
        for (int i = 0; i < 2; ++i) a.push_back(CleanFloat(value[i]));
        return a;
    } else if constexpr (std::is_same_v<Value, std::array<float, 4>>) {
        toml::array a;
        for (float v : value) a.push_back(CleanFloat(v));
        return a;
    } else {
        static_assert(std::is_same_v<Value, std::vector<std::string>>);
        toml::array a;
        for (const std::string& v : value) a.push_back(v);
        return a;
    }
}

toml::table ToTable(const RunConfig& c) {
    toml::table root;
    ForEachSetting(c, [&](const ParamInfo& info, const auto& value) {
        if constexpr (std::is_same_v<std::decay_t<decltype(value)>, FovDegrees>) {
            if (value) InsertAt(root, info.key, TomlValue(*value));  // absent: from the scene
        } else {
            InsertAt(root, info.key, TomlValue(value));
        }
    });
    InsertAt(root, kPrecisionKey, std::string(PrecisionName(c.denoise.params.precision)));
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
        ResolvePathsFromFile(table, "", path);
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
    AddConfigOverrideOptions(command, options);
}

void AddConfigOverrideOptions(CLI::App* command, ConfigOptions& options) {
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
    toml::table parsed;
    try {
        parsed = toml::parse("v = " + value);
    } catch (const toml::parse_error&) {
        // Not a TOML value: take it as a bare string (paths, scene names).
        parsed.insert("v", value);
    }
    // A relative path on the command line is from the working directory; stored absolute, so a
    // manifest re-read from elsewhere names the same file.
    if (std::optional<std::string> absolute = PathFrom(std::filesystem::current_path(), key, *parsed.get("v")))
        parsed.insert_or_assign("v", *absolute);
    SetPath(root, key, *parsed.get("v"), origin, origins);
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
    // --quick first: a command's own overlays (a sampling design) go over it.
    if (quick) resolved.overlayTables.insert(resolved.overlayTables.begin(), "experiment.quick");
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
