// The three steps of `lc2wf-train`: the junction model, the hand-off (predicted junctions of the train and
// validation buildings from the frozen best junction model, train/junction_handoff.h), and the edge model
// on GT + predicted pairs. Each validates on the validation split only.
#pragma once

#include <filesystem>
#include <string>

#include "nn/model_checkpoint.h"
#include "train/building_set.h"
#include "train/run_log.h"
#include "train/stage_loop.h"
#include "train/train_config.h"

namespace lc2wf {

struct StageRun {
  std::filesystem::path out;
  bool resume = false;
  bool quiet = false;
  std::filesystem::path init_weights;  // folder of <stage>.safetensors to fine-tune from (config "init_weights")
  Communicator* comm = nullptr;  // the data-parallel job; null: one process

  Communicator& communicator() const { return comm ? *comm : local_communicator(); }
};

// What both stages hand to run_stage: their schedule and optimiser, the config stored in every
// checkpoint, and the run paths.
template <class StageConfig>
StageLoopOptions stage_loop_options(const std::string& stage, const StageConfig& c, uint64_t seed, const StageRun& run) {
  StageLoopOptions lo;
  lo.stage = stage;
  lo.schedule = c.schedule;
  lo.optim = c.optim;
  lo.model_config = model_metadata(stage, c.net.to_json(), c.loss.to_json(), c.optim.to_json(), seed);
  lo.out = run.out;
  lo.resume = run.resume;
  lo.quiet = run.quiet;
  if (!run.init_weights.empty()) lo.init_weights = run.init_weights / (stage + ".safetensors");
  lo.comm = run.comm;
  return lo;
}

// Best weights `<out>/junction.safetensors`; selection by mean vAP (eta 0.15/0.25/0.35 m) of the
// point-NMS'd candidates of the validation buildings.
void train_junction_stage(const TrainConfig& config, const BuildingSet& train, const BuildingSet& val, RunLog& log,
                          const StageRun& run);

// `<out>/predicted_junctions/<name>.json` for every train and validation building, plus manifest.json:
// the junction model's raw candidates, which the edge stage selects and refines with inference's rule
// (dataset/selection/junction_selection.h), run as `selection` says (predict_junction_candidates). With run.resume a
// complete hand-off of the same junction checkpoint is kept, unless the selection screens offsets
// (edge.max_offset_m) and its files predate them, or it was sampled in another number of passes
// (edge.sampling_passes), views (edge.test_time_views) or with other seeds (edge.density_seeds).
std::filesystem::path write_junction_handoff(const BuildingSet& train, const BuildingSet& val, RunLog& log,
                                             const StageRun& run, const JunctionSelectionOptions& selection);

// Whether a hand-off of this manifest version serves: the current one always, version 3 (no offsets) only
// when no max_offset_m screen needs them, so older runs resume without predicting everything again.
bool handoff_version_usable(int version, bool need_offsets);

// What the edge stage trains on, from the hand-off's manifest: {"junction_step", "clouds_fingerprint"}.
// Stored in its checkpoints, so a stage trained on another hand-off is never resumed.
nlohmann::json handoff_identity(const std::filesystem::path& handoff_dir);

// Best weights `<out>/edge.safetensors`; selection by mean sAP (eta 0.25/0.35/0.50 m) of the post-processed
// wireframes of the validation buildings.
void train_edge_stage(const TrainConfig& config, const BuildingSet& train, const BuildingSet& val,
                      const std::filesystem::path& handoff_dir, RunLog& log, const StageRun& run);

}  // namespace lc2wf
