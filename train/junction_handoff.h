// The hand-off between the two stages (as the release: the edge model trains on the junction model's
// predictions, not only on GT junctions): the frozen junction model's candidates
// for one building, written as `<dir>/<name>.json`:
//   {"format": "lc2wf-predicted-junctions", "version": 1, "name": "<building>", "units": "metres",
//    "positions": [[x, y, z], ...],   one per sample point (G), in the building frame
//    "confidences": [c, ...]}         junction confidence softmax(logits)[1], same order
// No NMS or threshold is applied: the edge stage's pair sampling does that (top-k after point NMS).
#pragma once

#include <filesystem>
#include <string>

#include "dataset/sampling/pair_sampling.h"

namespace lc2wf {

void write_predicted_junctions(const std::filesystem::path& dir, const std::string& name, const PredictedJunctions& p);
// Throws DataError naming the file on a wrong format tag, mismatched counts or non-finite values.
PredictedJunctions read_predicted_junctions(const std::filesystem::path& path);
std::filesystem::path predicted_junctions_path(const std::filesystem::path& dir, const std::string& name);

}  // namespace lc2wf
