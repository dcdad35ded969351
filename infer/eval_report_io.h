// Output formats of an evaluation: a Markdown table shaped like the paper's Table 2, a JSON with every
// number, and a per-building CSV (formats documented in infer/README.md).
#pragma once

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "infer/building3d_io.h"
#include "model/evaluator.h"
#include "infer/inference_timing.h"
#include "infer/surfaces/face_metrics_io.h"

namespace lc2wf {

std::string eval_markdown(const EvalReport& report, const std::string& method);
nlohmann::json eval_json(const EvalReport& report, const std::string& method);
std::string eval_per_building_csv(const EvalReport& report);

// Seconds per building of each inference stage and pairs per building (lc2wf-eval --weights).
std::string inference_markdown(const InferenceTiming& s);
nlohmann::json inference_json(const InferenceTiming& s);
// The inverse of inference_json (per-building means back to totals); a field that metrics written before
// it existed lack keeps its default. Throws nlohmann::json::exception on a malformed block.
InferenceTiming inference_from_json(const nlohmann::json& j);

// Writes `<dir>/metrics.md`, `<dir>/metrics.json` and `<dir>/per_building.csv`, each atomically; with
// `building3d`, its section is appended to metrics.md and stored under "building3d" in metrics.json, and
// likewise `inference` (the timing of the predictions just made) under "inference".
// `faces` (the LoD2 surfaces of the predictions, infer/surfaces/face_metrics_io.h) likewise under "faces".
void write_eval_outputs(const std::filesystem::path& dir, const EvalReport& report, const std::string& method,
                        const Building3dReport* building3d = nullptr, const InferenceTiming* inference = nullptr,
                        const FaceReport* faces = nullptr);

}  // namespace lc2wf
