// The epoch/step loop shared by both training stages: learning-rate schedule, optimiser steps, gradient
// clipping, validation every k epochs, best and last checkpoints, the JSONL log, the progress bar and
// exact resume. A stage supplies its batches, its loss and its validation through callbacks.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/rng.h"
#include "nn/config.h"
#include "nn/module.h"
#include "train/communicator.h"
#include "train/run_log.h"
#include "train/train_config.h"

namespace lc2wf {

// Stage order in a run (for log rewinding).
const std::vector<std::string>& stage_order();

// `<out>/<stage>.safetensors` (best, weights only) and the two alternating "last" slots
// `<out>/checkpoints/<stage>_last_<slot>.safetensors` (+ `.optim.safetensors`): a checkpoint is a pair of
// files, so a kill between the two writes leaves the other slot as a consistent fallback.
std::filesystem::path best_checkpoint_path(const std::filesystem::path& out, const std::string& stage);
std::filesystem::path last_checkpoint_path(const std::filesystem::path& out, const std::string& stage, int slot);

struct StageStep {
  double loss = 0.0;          // total loss of the batch (summed over the ranks)
  nlohmann::json terms;       // extra loss terms for the log
  int64_t buildings = 0;      // buildings in the batch
  double comm_seconds = 0.0;  // waiting for the gradient sum after the backward pass (data-parallel jobs)
};

struct StageValidation {
  double score = 0.0;     // higher is better (selects the best checkpoint)
  double loss = 0.0;      // tie-breaker: lower is better
  nlohmann::json metrics; // everything logged
};

struct StageCallbacks {
  int64_t batches_per_epoch = 0;
  size_t training_buildings = 0;  // named when they give no full batch
  // Prepares the batches of `epoch`, starting at batch `first_batch`.
  std::function<void(int64_t epoch, int64_t first_batch)> start_epoch;
  // Runs forward and backward on the next batch (the loop steps the optimiser); nullopt ends the epoch.
  std::function<std::optional<StageStep>()> train_step;
  std::function<StageValidation()> validate;
};

struct StageLoopOptions {
  std::string stage;          // "junction" or "edge"
  StageSchedule schedule;
  OptimConfig optim;
  // {"stage", "net", ...}: stored in every checkpoint. Its "inputs" (if any) name the data the stage trains
  // on beyond the config (the edge stage: its hand-off); a checkpoint of other inputs is not resumed.
  nlohmann::json model_config;
  std::filesystem::path out;
  bool resume = false;
  bool quiet = false;
  // Fine-tuning: weights to start from (a best-weights file of an earlier run, same network config);
  // the optimiser, schedule and dropout stream start fresh. A resumed checkpoint takes precedence.
  std::filesystem::path init_weights;
  // The data-parallel job (null: one process). Rank 0 resumes, logs and writes checkpoints; the other
  // ranks receive its state at the start, and every step checks that all replicas are still equal.
  Communicator* comm = nullptr;
};

// The job of one process, for callers without a communicator.
Communicator& local_communicator();

// (first, count) ranges cutting a batch of `batch` buildings into micro-batches of at most `micro`
// buildings (micro <= 0 or >= batch: the whole batch in one range).
std::vector<std::pair<int, int>> micro_batch_ranges(int batch, int64_t micro);

// Trains `model` to the end of the schedule (or returns at once when a resumed stage is complete).
// Returns the number of optimiser steps run by this call.
int64_t run_stage(const StageLoopOptions& options, Module& model, Rng& dropout_rng, RunLog& log,
                  const StageCallbacks& callbacks);

}  // namespace lc2wf
