#include "train/train_config.h"

#include <cmath>
#include <stdexcept>
#include <utility>

#include "core/matmul_precision.h"
#include "nn/json_fields.h"
#include "train/config_extends.h"

namespace lc2wf {
namespace {

void require(bool ok, const std::string& field, const std::string& rule) {
  if (!ok) throw std::invalid_argument(field + " " + rule);
}

void require_seed_rule(const std::string& text, const std::string& field) {
  try {
    DensitySeedRule::parse(text);
  } catch (const std::invalid_argument& e) {
    require(false, field, std::string("is invalid: ") + e.what());
  }
}

// nn's Check() messages name the field relative to its struct ("optim.lr"); prefix the stage.
template <class T>
void check_nested(const T& c, const std::string& prefix) {
  try {
    c.Check();
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(prefix + "." + e.what());
  }
}

}  // namespace

// ----------------------------------------------------------------------------------------- DataConfig
void DataConfig::Check() const {
  require(format == "lc2wf" || format == "release", "data.format", "must be \"lc2wf\" or \"release\"");
  require(!dir.empty(), "data.dir", "must name the line-cloud folder");
  require(!train_split.empty(), "data.train_split", "must name a split file");
  require(!val_split.empty(), "data.val_split", "must name a split file");
  require(raw_per_metre > 0, "data.raw_per_metre", "must be > 0");
}

nlohmann::json DataConfig::to_json() const { return fields_to_json(*this); }

DataConfig DataConfig::from_json(const nlohmann::json& j, const std::string& where, DataConfig c) {
  return fields_from_json(j, where, std::move(c));
}

// -------------------------------------------------------------------------------------- StageSchedule
void StageSchedule::Check(const std::string& w) const {
  require(epochs >= 1, w + ".epochs", "must be >= 1");
  require(batch_size >= 1, w + ".batch_size", "must be >= 1");
  require(max_steps_per_epoch >= 0, w + ".max_steps_per_epoch", "must be >= 0 (0 = whole split)");
  require(val_every >= 1, w + ".val_every", "must be >= 1");
  require(checkpoint_every_steps >= 0, w + ".checkpoint_every_steps", "must be >= 0 (0 = per epoch)");
  require(micro_batch >= 0, w + ".micro_batch", "must be >= 0 (0 = the whole batch)");
  require(batch_norm == "per_rank" || batch_norm == "sync", w + ".batch_norm", "must be \"per_rank\" or \"sync\"");
  check_nested(cloud_augment.options, w);
}

nlohmann::json CloudAugmentConfig::to_json() const { return fields_to_json(*this); }

CloudAugmentConfig CloudAugmentConfig::from_json(const nlohmann::json& j, const std::string& where, CloudAugmentConfig c) {
  return fields_from_json(j, where, std::move(c));
}

// -------------------------------------------------------------------------------- JunctionStageConfig
void JunctionStageConfig::Check() const {
  check_nested(net, "junction.net");
  require(net.lpt.input_dim == 7, "junction.net.lpt.input_dim", "must be 7 (junction patch features)");
  check_nested(loss, "junction");
  check_nested(optim, "junction");
  schedule.Check("junction");
  require(near_gt_samples >= 0 && near_gt_samples <= net.lpt.patches, "junction.near_gt_samples",
          "must be in [0, net.lpt.patches]");
  require(std::isfinite(positive_radius_m), "junction.positive_radius_m", "must be a number of metres (<= 0: the release's labels)");
  require_seed_rule(density_seeds, "junction.density_seeds");
}

nlohmann::json JunctionStageConfig::to_json() const { return fields_to_json(*this); }

JunctionStageConfig JunctionStageConfig::from_json(const nlohmann::json& j, const std::string& where, JunctionStageConfig c) {
  return fields_from_json(j, where, std::move(c));
}

// ------------------------------------------------------------------------------------ EdgeStageConfig
OptimConfig EdgeStageConfig::edge_optim_defaults() {
  OptimConfig o;
  o.milestones = {15, 25, 31};
  return o;
}

StageSchedule EdgeStageConfig::edge_schedule_defaults() {
  StageSchedule s;
  s.epochs = 31;
  s.batch_size = 32;
  s.drop_last = false;  // the release's edge loader keeps the last partial batch
  return s;
}

void EdgeStageConfig::Check() const {
  check_nested(net, "edge.net");
  require(net.lpt.input_dim == 6, "edge.net.lpt.input_dim", "must be 6 (pair patch features)");
  require(net.lpt.lines_per_patch % 2 == 0, "edge.net.lpt.lines_per_patch", "must be even (two halves of a pair)");
  require(net.num_classes == 5, "edge.net.num_classes", "must be 5 (the pair classes)");
  check_nested(loss, "edge");
  check_nested(optim, "edge");
  schedule.Check("edge");
  require(max_static_pairs >= 0 && max_static_pairs <= net.lpt.patches, "edge.max_static_pairs",
          "must be in [0, net.lpt.patches]");
  require(top_k >= 2, "edge.top_k", "must be >= 2");
  require(post_process == "sound" || post_process == "release", "edge.post_process",
          "must be \"sound\" or \"release\"");
  require(min_confidence >= 0 && min_confidence <= 1, "edge.min_confidence", "must be in [0, 1]");
  require(pair_support >= 0 && pair_support <= 1, "edge.pair_support", "must be in [0, 1]");
  require(nms_radius_m > 0 && std::isfinite(nms_radius_m), "edge.nms_radius_m", "must be a positive distance in metres");
  require(std::isfinite(max_offset_m), "edge.max_offset_m", "must be a number of metres (<= 0: every candidate)");
  require(corner_radius_m >= 0 && std::isfinite(corner_radius_m), "edge.corner_radius_m", "must be a distance >= 0 in metres (0: off)");
  require(footing_radius_m >= 0 && std::isfinite(footing_radius_m), "edge.footing_radius_m", "must be a distance >= 0 in metres (0: off)");
  require(sampling_passes >= 1 && sampling_passes <= 8, "edge.sampling_passes", "must be in [1, 8]");
  require(JunctionSelectionOptions::valid_view_count(test_time_views), "edge.test_time_views", "must be 1, 2, 4 or 8");
  require_seed_rule(density_seeds, "edge.density_seeds");
}

nlohmann::json EdgeStageConfig::to_json() const { return fields_to_json(*this); }

EdgeStageConfig EdgeStageConfig::from_json(const nlohmann::json& j, const std::string& where, EdgeStageConfig c) {
  return fields_from_json(j, where, std::move(c));
}

// ---------------------------------------------------------------------------------------- TrainConfig
void TrainConfig::Check() const {
  require(threads >= 1, "threads", "must be >= 1");
  require(loader_workers >= 1, "loader_workers", "must be >= 1");
  parse_matmul_precision(precision, "precision");
  require(!out.empty(), "out", "must name the output folder");
  data.Check();
  junction.Check();
  edge.Check();
}

nlohmann::json TrainConfig::to_json() const { return fields_to_json(*this); }

TrainConfig TrainConfig::from_json(const nlohmann::json& j) {
  TrainConfig c = fields_from_json(j, "config", TrainConfig());
  c.Check();
  return c;
}

TrainConfig TrainConfig::from_file(const std::filesystem::path& path) {
  const nlohmann::json j = resolve_config_json(path);  // its "extends" chain merged; errors name the file
  try {
    return from_json(j);
  } catch (const std::exception& e) {  // any field error, named with the file
    throw std::runtime_error(path.string() + ": " + e.what());
  }
}

}  // namespace lc2wf
