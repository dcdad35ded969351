// The training configuration read by lc2wf-train (documented in train/README.md). Defaults are the
// settings of the LC2WF paper and its released training scripts; configs/*.json differ only in values (every one
// but base.json "extends" another: train/config_extends.h). Unknown keys and bad values are rejected with the key's
// dotted name ("junction.optim.lr must be > 0").
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "dataset/sampling/cloud_augmentation.h"
#include "dataset/geometry/geometry.h"
#include "dataset/selection/junction_selection.h"
#include "nn/config.h"

namespace lc2wf {

struct DataConfig {
  std::string format = "lc2wf";  // "lc2wf" (lc2wf-dataset line clouds) or "release" (LineCloud JSON)
  std::string dir;               // one file per building, file stem = building name
  std::string train_split;       // building names, one per line
  std::string val_split;         // validation names (never the test split)
  double raw_per_metre = kRawUnitsPerMetre;  // release JSON only: raw units per metre

  // Every JSON key, listed once (to_json and from_json both walk it).
  template <class S, class V>
  static void fields(S& s, V& v) {
    v("format", s.format);
    v("dir", s.dir);
    v("train_split", s.train_split);
    v("val_split", s.val_split);
    v("raw_per_metre", s.raw_per_metre);
  }
  void Check() const;
  nlohmann::json to_json() const;
  static DataConfig from_json(const nlohmann::json& j, const std::string& where, DataConfig base);
};

// Training-time augmentation of the clouds' statistics (dataset/sampling/cloud_augmentation.h). Off by default:
// the paper's configs do not use it; experiments/configs/robust.json does.
struct CloudAugmentConfig {
  bool enabled = false;
  CloudAugmentOptions options;
  // Every JSON key, listed once (to_json and from_json both walk it).
  template <class S, class V>
  static void fields(S& s, V& v) {
    v("enabled", s.enabled);
    v("merge_prob_max", s.options.merge_prob_max);
    v("split_prob_max", s.options.split_prob_max);
    v("densify_prob_max", s.options.densify_prob_max);
    v("drop_max", s.options.drop_max);
    v("endpoint_noise_max_m", s.options.endpoint_noise_max_m);
    v("min_length_m", s.options.min_length_m);
    v("face_clutter_max", s.options.face_clutter_max);
    v("ground_clutter_max", s.options.ground_clutter_max);
    v("clutter_length_max_m", s.options.clutter_length_max_m);
    v("merged_map_prob", s.options.merged_map_prob);
  }
  nlohmann::json to_json() const;
  static CloudAugmentConfig from_json(const nlohmann::json& j, const std::string& where, CloudAugmentConfig base);
};

// Options shared by both stages' loops.
struct StageSchedule {
  int64_t epochs = 41;
  int64_t batch_size = 16;
  int64_t max_steps_per_epoch = 0;  // 0 = every full batch of the split
  int64_t val_every = 1;            // validate after every k-th epoch (and after the last)
  int64_t checkpoint_every_steps = 0;  // also save "last" mid-epoch every k steps (0 = per epoch only)
  bool augment = true;              // the release's per-building scale + shift
  // Not in the release: with augment, also a uniform turn about the vertical (the networks' answers depend
  // on the building's orientation; experiments/README.md, "Test-time views").
  bool augment_rotate_z = false;
  bool drop_last = true;
  // Buildings per forward/backward pass; the gradients of a batch's micro-batches are summed before the
  // optimiser step, so only BatchNorm's statistics see fewer buildings. Bounds activation memory.
  int64_t micro_batch = 0;          // 0 = the whole batch at once
  // Rebuild the line MLP's activations in the backward pass instead of keeping them: ≈ 0.23 GB less per 4
  // edge or 16 junction buildings, ≈ 9 % slower steps in both stages (bench/README.md).
  bool recompute_mlp = false;
  CloudAugmentConfig cloud_augment;  // training batches only, never validation
  // Data-parallel jobs (mpirun): BatchNorm statistics of each rank's own passes ("per_rank") or summed
  // over the ranks' passes ("sync"). One process: no difference.
  std::string batch_norm = "per_rank";

  void Check(const std::string& where) const;
  // The schedule keys live directly in the stage object, so the stages list them through this.
  template <class S, class V>
  static void fields(S& s, V& v) {
    v("epochs", s.epochs);
    v("batch_size", s.batch_size);
    v("max_steps_per_epoch", s.max_steps_per_epoch);
    v("val_every", s.val_every);
    v("checkpoint_every_steps", s.checkpoint_every_steps);
    v("augment", s.augment);
    v("augment_rotate_z", s.augment_rotate_z);
    v("drop_last", s.drop_last);
    v("micro_batch", s.micro_batch);
    v("recompute_mlp", s.recompute_mlp);
    v("cloud_augment", s.cloud_augment);
    v("batch_norm", s.batch_norm);
  }
};

struct JunctionStageConfig {
  JunctionNetConfig net;  // G = net.lpt.patches samples of N = net.lpt.lines_per_patch lines
  JunctionLossConfig loss;
  OptimConfig optim;      // milestones [15, 30, 41]
  StageSchedule schedule;
  int64_t near_gt_samples = 0;                // the paper's near-GT training samples (the release has none)
  double endpoint_label_max_distance_m = -1;  // <= 0: the plain (f, i1, i2) endpoint labels
  double positive_radius_m = -1;  // > 0: patches whose junction is farther than this are negative (PatchOptions)
  // Which endpoints seed the sample points of the training and validation patches (DensitySeedRule::parse):
  // the release's by default; "loose" trains on the patches inference samples by default.
  std::string density_seeds = "release";

  // Every JSON key, listed once (to_json and from_json both walk it).
  template <class S, class V>
  static void fields(S& s, V& v) {
    v("net", s.net);
    v("loss", s.loss);
    v("optim", s.optim);
    StageSchedule::fields(s.schedule, v);
    v("near_gt_samples", s.near_gt_samples);
    v("endpoint_label_max_distance_m", s.endpoint_label_max_distance_m);
    v("positive_radius_m", s.positive_radius_m);
    v("density_seeds", s.density_seeds);
  }
  void Check() const;
  nlohmann::json to_json() const;
  static JunctionStageConfig from_json(const nlohmann::json& j, const std::string& where, JunctionStageConfig base);
};

struct EdgeStageConfig {
  EdgeNetConfig net;  // pairs per building = net.lpt.patches, lines per pair = net.lpt.lines_per_patch (2 x 32)
  EdgeLossConfig loss;
  OptimConfig optim = edge_optim_defaults();  // milestones [15, 25, 31]
  StageSchedule schedule = edge_schedule_defaults();
  int64_t max_static_pairs = 256;
  int64_t top_k = 100;
  // Junction selection and post-processing of the training pairs and the validation wireframes, as
  // lc2wf-infer: "sound" (its defaults) or "release" (--release-quirks).
  std::string post_process = "sound";
  // Validation pairs the junctions above this confidence, as lc2wf-infer --min-confidence (training
  // pairs take the top_k instead). The selection keys default to lc2wf-infer's (JunctionSelectionOptions).
  double min_confidence = JunctionSelectionOptions{}.min_confidence;
  // Validation classifies only pairs with at least this line support, as lc2wf-infer --pair-support
  // (dataset/selection/pair_support.h); 0 = every pair, as the release.
  double pair_support = 0.0;
  // Candidate junctions within this of a more confident one are dropped before the cut, in the training
  // pairs, validation and lc2wf-infer --nms-radius alike (the release: 0.25, its 5 raw units).
  double nms_radius_m = JunctionSelectionOptions{}.nms_radius_m;
  // > 0: candidates regressed farther than this from their sample point take no part, as lc2wf-infer
  // --max-offset; <= 0: every candidate (the release).
  double max_offset_m = JunctionSelectionOptions{}.max_offset_m;
  // Selected junctions stay only where segments of two directions end within this many metres, in the
  // training pairs, validation and lc2wf-infer --corner-radius alike; 0 = every junction (the release).
  double corner_radius_m = JunctionSelectionOptions{}.corner.radius_m;
  // Selected junctions on the ground stay only where segment ends stand over them within this many metres
  // (horizontally), in the training pairs, validation and lc2wf-infer --footing-radius alike; 0 = every one.
  double footing_radius_m = JunctionSelectionOptions{}.footing.radius_m;
  // The junction model's sample points in passes of G, in the hand-off and so in the training pairs and
  // validation, as lc2wf-infer --sampling-passes (the release: 1).
  int64_t sampling_passes = JunctionSelectionOptions{}.sampling_passes;
  // The junction model's mean over this many views of each patch (1, 2, 4 or 8), in the hand-off and so in
  // the training pairs and validation, as lc2wf-infer --test-time-views (the release: 1).
  int64_t test_time_views = JunctionSelectionOptions{}.test_time_views;
  // Which endpoints seed the junction model's sample points, in the hand-off and so in the training pairs
  // and validation, as lc2wf-infer --density-seeds: "release", "loose" or "MIN_COUNT,MIN_RATIO,NMS_M".
  std::string density_seeds = JunctionSelectionOptions{}.density_seeds.str();

  // Every JSON key, listed once (to_json and from_json both walk it).
  template <class S, class V>
  static void fields(S& s, V& v) {
    v("net", s.net);
    v("loss", s.loss);
    v("optim", s.optim);
    StageSchedule::fields(s.schedule, v);
    v("max_static_pairs", s.max_static_pairs);
    v("top_k", s.top_k);
    v("post_process", s.post_process);
    v("min_confidence", s.min_confidence);
    v("pair_support", s.pair_support);
    v("nms_radius_m", s.nms_radius_m);
    v("max_offset_m", s.max_offset_m);
    v("corner_radius_m", s.corner_radius_m);
    v("footing_radius_m", s.footing_radius_m);
    v("sampling_passes", s.sampling_passes);
    v("test_time_views", s.test_time_views);
    v("density_seeds", s.density_seeds);
  }
  void Check() const;
  nlohmann::json to_json() const;
  static EdgeStageConfig from_json(const nlohmann::json& j, const std::string& where, EdgeStageConfig base);
  static OptimConfig edge_optim_defaults();
  static StageSchedule edge_schedule_defaults();
};

struct TrainConfig {
  uint64_t seed = 1555;
  int64_t threads = 2;         // compute threads (set_num_threads)
  int64_t loader_workers = 1;  // threads building batches ahead of the compute
  // GEMM operands: "fp32" (the paper's numbers), "bf16" (fp32 accumulation, master weights and optimiser
  // state; emulated without AVX512-BF16) or "auto" (bf16 where the CPU has AVX512-BF16). core/matmul_precision.h.
  std::string precision = "fp32";
  std::string out = "runs/base";
  std::string init_weights;    // fine-tune: a trained model's folder (junction/edge.safetensors); "" = random init
  DataConfig data;
  JunctionStageConfig junction;
  EdgeStageConfig edge;

  // Every JSON key, listed once (to_json and from_json both walk it).
  template <class S, class V>
  static void fields(S& s, V& v) {
    v("seed", s.seed);
    v("threads", s.threads);
    v("loader_workers", s.loader_workers);
    v("precision", s.precision);
    v("out", s.out);
    v("init_weights", s.init_weights);
    v("data", s.data);
    v("junction", s.junction);
    v("edge", s.edge);
  }
  void Check() const;
  nlohmann::json to_json() const;
  static TrainConfig from_json(const nlohmann::json& j);
  // Parses (resolving "extends") and checks; errors name the file and the key.
  static TrainConfig from_file(const std::filesystem::path& path);
};

}  // namespace lc2wf
