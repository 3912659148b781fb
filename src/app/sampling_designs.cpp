#include "app/sampling_designs.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <sstream>

#include <fmt/format.h>

#include "config/config_cli.h"
#include "core/error.h"
#include "core/nearest_name.h"
#include "foveation/spp_model.h"
#include "gaze/gaze_source.h"

namespace fovrt {
namespace {

constexpr const char* kRayBudgetKey = "foveation.ray_budget";

// The keys a design may set: every [foveation] row and the eye tracker's rows of [gaze].
std::vector<std::string> DesignKeys() {
    std::vector<std::string> keys;
    for (const auto& row : FoveationParamTable()) keys.emplace_back(row.info.key);
    for (const auto& row : TrackerParamTable()) keys.emplace_back(row.info.key);
    return keys;
}

// A design's leaves as dotted keys (an inline table and a [sub.table] give the same keys).
void Flatten(const toml::table& table, const std::string& prefix, std::vector<std::pair<std::string, std::string>>& out) {
    for (const auto& [key, node] : table) {
        const std::string path = prefix.empty() ? std::string(key.str()) : prefix + "." + std::string(key.str());
        if (const toml::table* sub = node.as_table()) {
            Flatten(*sub, path, out);
            continue;
        }
        std::ostringstream text;
        node.visit([&](const auto& value) { text << value; });
        out.emplace_back(path, text.str());
    }
}

// The line a key was given on ("exp.toml:12" -> 12); keys from --set sort after the file's.
int LineOf(const std::string& origin) {
    const size_t colon = origin.rfind(':');
    if (colon == std::string::npos || colon + 1 == origin.size()) return std::numeric_limits<int>::max();
    const std::string digits = origin.substr(colon + 1);
    if (digits.find_first_not_of("0123456789") != std::string::npos || digits.size() > 9)
        return std::numeric_limits<int>::max();
    return std::stoi(digits);
}

bool IsPathComponent(const std::string& name) {
    if (name.empty() || name.find_first_not_of('.') == std::string::npos) return false;
    return std::ranges::all_of(name, [](char c) {
        return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' || c == '_' ||
               c == '-';
    });
}

// A budgets array (`what` names it in errors): numbers in (0, kMaxSpp], distinct, sorted.
std::vector<double> ParseBudgets(const toml::node& node, const std::string& origin, const std::string& what) {
    std::vector<double> budgets;
    const toml::array* array = node.as_array();
    if (!array || array->empty())
        Fail("{}: {} must be a non-empty array of mean samples per pixel, e.g. [1, 2, 4]", origin, what);
    for (const toml::node& element : *array) {
        std::optional<double> value = element.value<double>();
        if (!value || !(element.is_integer() || element.is_floating_point()) || !std::isfinite(*value) ||
            *value <= 0 || *value > kMaxSpp)
            Fail("{}: {} must hold numbers in (0, {}] (mean path samples per pixel)", origin, what, kMaxSpp);
        if (std::ranges::find(budgets, *value) != budgets.end()) Fail("{}: {} lists {:g} twice", origin, what, *value);
        budgets.push_back(*value);
    }
    std::ranges::sort(budgets);
    return budgets;
}

}  // namespace

std::string SweepPointLabel(const std::string& design, std::optional<double> budgetSpp) {
    return budgetSpp ? fmt::format("{}-b{:g}", design, *budgetSpp) : design;
}

SamplingSweep LoadSamplingSweep(const ExperimentTable& experiment, const ConfigOptions& options, bool quick,
                                const std::vector<std::string>& variants) {
    SamplingSweep sweep;
    const toml::node* node = experiment.table.get("designs");
    if (!node) {
        for (const char* key : {"budgets", "anchor_design", "run_designs"})
            if (experiment.table.contains(key))
                Fail("{}: experiment.{} needs experiment.designs (the sampling designs it applies to)",
                     experiment.Origin(key), key);
        return sweep;
    }
    const toml::table* designs = node->as_table();
    if (!designs || designs->empty())
        Fail("{}: experiment.designs must be a table of named designs, e.g. [experiment.designs.uniform]",
             experiment.Origin("designs"));
    if (const toml::node* budgets = experiment.table.get("budgets"))
        sweep.budgets = ParseBudgets(*budgets, experiment.Origin("budgets"), "experiment.budgets");
    const std::vector<std::string> allowed = DesignKeys();

    // The designs in the order the file gives them (toml++ keeps a table's keys sorted).
    std::vector<std::pair<int, std::string>> order;
    for (const auto& [key, value] : *designs) {
        const std::string name(key.str());
        int line = std::numeric_limits<int>::max();
        for (const auto& [k, origin] : experiment.origins)
            if (k.rfind("designs." + name + ".", 0) == 0 || k == "designs." + name) line = std::min(line, LineOf(origin));
        order.emplace_back(line, name);
    }
    std::ranges::stable_sort(order, {}, &std::pair<int, std::string>::first);

    // experiment.run_designs: the designs to run, each named in experiment.designs.
    std::optional<std::vector<std::string>> run;
    if (const toml::node* list = experiment.table.get("run_designs")) {
        const std::string origin = experiment.Origin("run_designs");
        const toml::array* array = list->as_array();
        if (!array || array->empty()) Fail("{}: experiment.run_designs must be a non-empty array of design names", origin);
        std::vector<std::string> names;
        for (const auto& [line, name] : order) names.push_back(name);
        run.emplace();
        for (const toml::node& element : *array) {
            std::optional<std::string> name = element.value<std::string>();
            if (!name || std::ranges::find(names, *name) == names.end())
                Fail("{}: experiment.run_designs: '{}' is not one of experiment.designs (did you mean '{}'?)", origin,
                     name.value_or("?"), NearestName(name.value_or(""), names));
            run->push_back(*name);
        }
    }
    // Every design is checked, the ones run_designs leaves out too (a mistake in the file is one
    // whether or not this run reaches it); a --set only conflicts with a design that runs.
    for (const auto& [line, name] : order) {
        const bool runs = !run || std::ranges::find(*run, name) != run->end();
        const std::string where = "experiment.designs." + name;
        const std::string origin = experiment.Origin("designs." + name);
        if (!IsPathComponent(name))
            Fail("{}: {}: a design's name is a folder name: letters, digits, '.', '_', '-'", origin, where);
        const toml::table* table = designs->get(name)->as_table();
        if (!table) Fail("{}: {} must be a table of [foveation] and gaze.tracker_* keys", origin, where);
        SamplingDesign design{name, {}, sweep.budgets};
        toml::table sampling = *table;
        if (const toml::node* own = table->get("budgets")) {  // the design's own budgets
            design.budgets = ParseBudgets(*own, experiment.Origin("designs." + name + ".budgets"), where + ".budgets");
            sampling.erase("budgets");
        }
        Flatten(sampling, "", design.keys);
        for (const auto& [key, value] : design.keys) {
            const std::string keyOrigin = experiment.Origin("designs." + name + "." + key);
            if (std::ranges::find(allowed, key) == allowed.end())
                Fail("{}: {}.{}: a design sets only [foveation] keys and the eye tracker's gaze.* keys "
                     "(did you mean {}?)",
                     keyOrigin, where, key, NearestName(key, allowed));
            if (key == kRayBudgetKey && !design.budgets.empty())
                Fail("{}: {}.{}: the budgets (experiment.budgets, or the design's own) set the ray budget of every point",
                     keyOrigin, where, key);
            for (const std::string& set : runs ? options.sets : std::vector<std::string>{})
                if (set.rfind(key + "=", 0) == 0 || set.rfind(key + " ", 0) == 0)
                    Fail("--set {}: {} sets {} (a design's keys are the experiment's axis; edit the design "
                         "or use --set {}.{}=VALUE)",
                         set, where, key, where, key);
        }
        if (runs) sweep.designs.push_back(std::move(design));
    }

    if (const toml::node* anchor = experiment.table.get("anchor_design")) {
        std::optional<std::string> name = anchor->value<std::string>();
        std::vector<std::string> names;
        for (const SamplingDesign& d : sweep.designs) names.push_back(d.name);
        if (!name || std::ranges::find(names, *name) == names.end())
            Fail("{}: experiment.anchor_design must name one of experiment.designs (did you mean '{}'?)",
                 experiment.Origin("anchor_design"), NearestName(name.value_or(""), names));
        sweep.anchor = size_t(std::ranges::find(names, *name) - names.begin());
    }

    for (size_t d = 0; d < sweep.designs.size(); ++d) {
        const std::vector<double>& own = sweep.designs[d].budgets;
        std::vector<std::optional<double>> budgets(own.begin(), own.end());
        if (budgets.empty()) budgets.push_back(std::nullopt);
        for (std::optional<double> budget : budgets) {
            SweepPoint point{d, budget, SweepPointLabel(sweep.designs[d].name, budget), {}};
            ConfigOptions resolved = options;
            resolved.overlayTables.push_back("experiment.designs." + sweep.designs[d].name);
            resolved.ignoredTables.push_back("budgets");  // a design's own budgets are the sweep's, not config
            ExperimentTable unused;
            try {
                if (budget) {
                    // The budget in samples per eye per frame, from the experiment's resolution.
                    const RunConfig plain = ResolveExperimentConfig(resolved, quick, unused);
                    const double pixels = double(plain.camera.width) * double(plain.camera.height);
                    resolved.sets.push_back(fmt::format("{}={}", kRayBudgetKey, std::llround(*budget * pixels)));
                }
                point.config = ResolveExperimentConfig(resolved, quick, unused);
            } catch (const Error& e) {
                Fail("experiment.designs.{}{}: {}", sweep.designs[d].name,
                     budget ? fmt::format(" at budget {:g} spp", *budget) : std::string(), e.what());
            }
            point.config.denoise.denoisers = variants;
            sweep.points.push_back(std::move(point));
        }
    }
    // Without anchor_design: the one design that samples uniformly (none when two do).
    if (!sweep.anchor) {
        std::vector<size_t> uniform;
        for (const SweepPoint& p : sweep.points)
            if (p.config.foveation.model == "uniform" && std::ranges::find(uniform, p.design) == uniform.end())
                uniform.push_back(p.design);
        if (uniform.size() == 1) sweep.anchor = uniform.front();
    }
    return sweep;
}

}  // namespace fovrt
