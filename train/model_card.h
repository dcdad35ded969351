// The model card of a training run, `<out>/README.md`: which lc2wf version and commit trained it, on which
// data and config, and the validation score of the kept weights of each stage. Copy it along with the
// weights (a models/<name>/ folder needs one).
#pragma once

#include <filesystem>

#include "train/building_set.h"
#include "train/train_config.h"

namespace lc2wf {

// Written atomically after each `lc2wf-train` run; stages without kept weights are listed as not trained.
void write_model_card(const std::filesystem::path& out, const std::filesystem::path& config_file, const TrainConfig& config,
                      const BuildingSet& train, const BuildingSet& val);

}  // namespace lc2wf
