// Every key of RunConfig, walked in one order: the rows of this library's sections ([scene],
// [camera], [run], [render], [denoise], [output], [reference], [metric], memory_budget) and the
// modules' own tables ([foveation]: foveation/, [gaze]: gaze/, [denoise.*]: denoise/params.cpp).
// The TOML reader and writer (config.cpp), `fovrt config --keys` and the tests walk them; only
// denoise.precision (an enum: PrecisionTable) is read and written beside the walk.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "config/config.h"

namespace fovrt {

std::span<const SettingRow<RunConfig>> RunConfigTable();          // memory_budget
std::span<const SettingRow<SceneConfig>> SceneTable();            // [scene]
std::span<const SettingRow<CameraConfig>> CameraTable();          // [camera]
std::span<const SettingRow<RunSettings>> RunTable();              // [run]
std::span<const SettingRow<RenderConfig>> RenderTable();          // [render]
std::span<const SettingRow<DenoiseConfig>> DenoiseTable();        // [denoise] denoisers, device
std::span<const SettingRow<OutputConfig>> OutputTable();          // [output]
std::span<const SettingRow<ReferenceConfig>> ReferenceTable();    // [reference]
std::span<const SettingRow<MetricConfig>> MetricTable();          // [metric]

// Calls visit(info, value) for every key of `config` (RunConfig or const RunConfig) in table
// order; `value` is the member (bool&, int&, float&, std::string&, ...).
template <class Config, class Visit>
void ForEachSetting(Config& c, Visit&& visit) {
    VisitRows(c, RunConfigTable(), visit);
    VisitRows(c.scene, SceneTable(), visit);
    VisitRows(c.camera, CameraTable(), visit);
    VisitRows(c.run, RunTable(), visit);
    VisitRows(c.render, RenderTable(), visit);
    VisitRows(c.foveation, FoveationParamTable(), visit);
    VisitRows(c.gaze, GazeParamTable(), visit);
    VisitRows(c.gaze.tracker, TrackerParamTable(), visit);
    VisitRows(c.denoise, DenoiseTable(), visit);
    VisitRows(c.denoise.params.rae, RaeParamTable(), visit);
    ForEachDenoiserParam(c.denoise.params, visit);
    VisitRows(c.output, OutputTable(), visit);
    VisitRows(c.reference, ReferenceTable(), visit);
    VisitRows(c.metric, MetricTable(), visit);
}

// One line of `fovrt config --keys`: the key, its default as written to TOML ("" when absent by
// default), what it allows (a range, names, "true|false") and its meaning.
struct SettingLine {
    std::string key;
    std::string defaultValue;
    std::string allowed;
    std::string doc;
};
std::vector<SettingLine> DescribeSettings();  // every key, denoise.precision included

}  // namespace fovrt
