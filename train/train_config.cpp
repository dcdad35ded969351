#include "train/train_config.h"

#include <fstream>
#include <sstream>
#include <stdexcept>

#include "nn/json_fields.h"

namespace lc2wf {
namespace {

void require(bool ok, const std::string& field, const std::string& rule) {
  if (!ok) throw std::invalid_argument(field + " " + rule);
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

nlohmann::json DataConfig::to_json() const {
  return {{"format", format}, {"dir", dir}, {"train_split", train_split}, {"val_split", val_split},
          {"raw_per_metre", raw_per_metre}};
}

DataConfig DataConfig::from_json(const nlohmann::json& j, const std::string& where, DataConfig c) {
  JsonFields f(j, where);
  f.read("format", c.format);
  f.read("dir", c.dir);
  f.read("train_split", c.train_split);
  f.read("val_split", c.val_split);
  f.read("raw_per_metre", c.raw_per_metre);
  f.finish();
  return c;
}

// -------------------------------------------------------------------------------------- StageSchedule
void StageSchedule::Check(const std::string& w) const {
  require(epochs >= 1, w + ".epochs", "must be >= 1");
  require(batch_size >= 1, w + ".batch_size", "must be >= 1");
  require(max_steps_per_epoch >= 0, w + ".max_steps_per_epoch", "must be >= 0 (0 = whole split)");
  require(val_every >= 1, w + ".val_every", "must be >= 1");
  require(checkpoint_every_steps >= 0, w + ".checkpoint_every_steps", "must be >= 0 (0 = per epoch)");
}

void StageSchedule::read(JsonFields& f) {
  f.read("epochs", epochs);
  f.read("batch_size", batch_size);
  f.read("max_steps_per_epoch", max_steps_per_epoch);
  f.read("val_every", val_every);
  f.read("checkpoint_every_steps", checkpoint_every_steps);
  f.read("augment", augment);
  f.read("drop_last", drop_last);
}

nlohmann::json StageSchedule::to_json() const {
  return {{"epochs", epochs},     {"batch_size", batch_size}, {"max_steps_per_epoch", max_steps_per_epoch},
          {"val_every", val_every}, {"checkpoint_every_steps", checkpoint_every_steps},
          {"augment", augment},   {"drop_last", drop_last}};
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
}

nlohmann::json JunctionStageConfig::to_json() const {
  nlohmann::json j = schedule.to_json();
  j["net"] = net.to_json();
  j["loss"] = loss.to_json();
  j["optim"] = optim.to_json();
  j["near_gt_samples"] = near_gt_samples;
  j["endpoint_label_max_distance_m"] = endpoint_label_max_distance_m;
  return j;
}

JunctionStageConfig JunctionStageConfig::from_json(const nlohmann::json& j, const std::string& where,
                                                   JunctionStageConfig c) {
  JsonFields f(j, where);
  f.read_struct("net", c.net);
  f.read_struct("loss", c.loss);
  f.read_struct("optim", c.optim);
  c.schedule.read(f);
  f.read("near_gt_samples", c.near_gt_samples);
  f.read("endpoint_label_max_distance_m", c.endpoint_label_max_distance_m);
  f.finish();
  return c;
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
}

nlohmann::json EdgeStageConfig::to_json() const {
  nlohmann::json j = schedule.to_json();
  j["net"] = net.to_json();
  j["loss"] = loss.to_json();
  j["optim"] = optim.to_json();
  j["max_static_pairs"] = max_static_pairs;
  j["top_k"] = top_k;
  return j;
}

EdgeStageConfig EdgeStageConfig::from_json(const nlohmann::json& j, const std::string& where, EdgeStageConfig c) {
  JsonFields f(j, where);
  f.read_struct("net", c.net);
  f.read_struct("loss", c.loss);
  f.read_struct("optim", c.optim);
  c.schedule.read(f);
  f.read("max_static_pairs", c.max_static_pairs);
  f.read("top_k", c.top_k);
  f.finish();
  return c;
}

// ---------------------------------------------------------------------------------------- TrainConfig
void TrainConfig::Check() const {
  require(threads >= 1, "threads", "must be >= 1");
  require(loader_workers >= 1, "loader_workers", "must be >= 1");
  require(!out.empty(), "out", "must name the output folder");
  data.Check();
  junction.Check();
  edge.Check();
}

nlohmann::json TrainConfig::to_json() const {
  return {{"seed", seed},       {"threads", threads},           {"loader_workers", loader_workers},
          {"out", out},         {"data", data.to_json()},       {"junction", junction.to_json()},
          {"edge", edge.to_json()}};
}

TrainConfig TrainConfig::from_json(const nlohmann::json& j) {
  TrainConfig c;
  JsonFields f(j, "config");
  f.read("seed", c.seed);
  f.read("threads", c.threads);
  f.read("loader_workers", c.loader_workers);
  f.read("out", c.out);
  f.read_struct("data", c.data);
  f.read_struct("junction", c.junction);
  f.read_struct("edge", c.edge);
  f.finish();
  c.Check();
  return c;
}

TrainConfig TrainConfig::from_file(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path.string() + ": cannot open config");
  std::stringstream ss;
  ss << in.rdbuf();
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(ss.str());
  } catch (const nlohmann::json::parse_error& e) {
    throw std::runtime_error(path.string() + ": not valid JSON: " + e.what());
  }
  try {
    return from_json(j);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(path.string() + ": " + e.what());
  }
}

}  // namespace lc2wf
