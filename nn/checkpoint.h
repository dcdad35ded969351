// Training checkpoints as two safetensors files: `<name>.safetensors` holds the model state dict (loadable
// on its own, also from Python) with the config, training position and dropout-RNG state in its metadata;
// `<name>.optim.safetensors` holds the optimiser state. Both are written atomically, the model file
// last, and each records the step so a mismatched pair is refused on load, and the lc2wf version and git
// commit that wrote it (`lc2wf_version`, `commit`; not needed to load, so older files load the same).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "core/rng.h"
#include "nn/module.h"
#include "nn/optimizer.h"

namespace lc2wf {

struct TrainingPosition {
  int64_t epoch = 0;  // completed epochs
  int64_t step = 0;   // completed optimiser steps
  // Sum of the step losses of the current epoch so far, so a mid-epoch resume logs the epoch's exact mean.
  double epoch_loss_sum = 0.0;
};

struct CheckpointInfo {
  nlohmann::json config;  // whatever the trainer stored (model/loss/optim configs)
  TrainingPosition position;
  uint64_t rng_seed = 0, rng_counter = 0;  // dropout stream
  bool has_optimizer = false;
};

// "<dir>/<stem>.optim.safetensors" next to the model file.
std::filesystem::path optimizer_state_path(const std::filesystem::path& model_path);

// optimizer may be null (weights-only checkpoint, e.g. for inference).
void save_checkpoint(const std::filesystem::path& path, const Module& model, const nlohmann::json& config,
                     const Rng& dropout_rng, const Optimizer* optimizer, const TrainingPosition& position);

// Reads only the metadata, so a caller can build the model from the stored config before loading.
CheckpointInfo read_checkpoint_info(const std::filesystem::path& path);

// Loads weights (strict: missing/extra/misshaped tensors throw naming the tensor), and, when given, the
// dropout RNG state and the optimiser state.
CheckpointInfo load_checkpoint(const std::filesystem::path& path, Module& model, Rng* dropout_rng,
                               Optimizer* optimizer);

}  // namespace lc2wf
