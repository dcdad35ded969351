// Predicted wireframes on disk: `<name>.obj` (`v` + `l`, metres or raw units) plus an optional sidecar
// `<name>.json` with the scores (format documented in infer/README.md):
//   {"format": "lc2wf-wireframe-scores", "version": 1,
//    "junction_scores": [one per `v`, file order], "edge_scores": [one per `l` segment, file order],
//    "notes": [optional strings, e.g. post-processing notes]}
// Without a sidecar every score is 1.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "model/scored_wireframe.h"

namespace lc2wf {

struct PredictionScores {
  std::optional<std::vector<double>> junction_scores;  // absent key: nullopt
  std::optional<std::vector<double>> edge_scores;
  std::vector<std::string> notes;
};

std::string scores_json_string(const ScoredWireframe& prediction, const std::vector<std::string>& notes = {});
// Throws DataError naming `source` on malformed JSON, a wrong format tag or non-finite scores.
PredictionScores parse_scores_json(const std::string& text, const std::string& source);

// The sidecar path of a prediction OBJ: same folder and stem, extension .json.
std::filesystem::path scores_path_for(const std::filesystem::path& obj);

// Reads a prediction OBJ (+ sidecar when present). `raw_units`, when given, converts raw coordinates to
// metres. Faces are rejected (predictions are `l` wireframes); edges keep the file's `l` order so they
// line up with edge_scores. Throws DataError naming the file.
ScoredWireframe read_prediction(const std::filesystem::path& obj, const UnitTransform* raw_units = nullptr);

// True for a name that stays inside the output folder as `<name>.obj`: not empty, `.` or `..`, no `/` or NUL.
bool is_plain_file_name(const std::string& name);

// Writes `<dir>/<name>.obj` and `<dir>/<name>.json` atomically (creating `dir`); `raw_units` writes raw
// coordinates. Throws std::invalid_argument when `name` is not a plain file name.
void write_prediction(const std::filesystem::path& dir, const std::string& name, const ScoredWireframe& prediction,
                      const std::vector<std::string>& notes = {}, const UnitTransform* raw_units = nullptr);

}  // namespace lc2wf
