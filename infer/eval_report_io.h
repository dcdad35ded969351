// Output formats of an evaluation: a Markdown table shaped like the paper's Table 2, a JSON with every
// number, and a per-building CSV (formats documented in infer/README.md).
#pragma once

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "infer/building3d_io.h"
#include "infer/evaluator.h"

namespace lc2wf {

std::string eval_markdown(const EvalReport& report, const std::string& method);
nlohmann::json eval_json(const EvalReport& report, const std::string& method);
std::string eval_per_building_csv(const EvalReport& report);

// Writes `<dir>/metrics.md`, `<dir>/metrics.json` and `<dir>/per_building.csv`, each atomically; with
// `building3d`, its section is appended to metrics.md and stored under "building3d" in metrics.json.
void write_eval_outputs(const std::filesystem::path& dir, const EvalReport& report, const std::string& method,
                        const Building3dReport* building3d = nullptr);

}  // namespace lc2wf
