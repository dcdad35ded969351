#include "nn/config.h"

#include <stdexcept>
#include <string>
#include <utility>

#include "nn/json_fields.h"

namespace lc2wf {

namespace {
void require(bool ok, const std::string& field, const std::string& rule) {
  if (!ok) throw std::invalid_argument(field + " " + rule);
}
// Upper bounds far above the paper's networks (N 32/64, G 256/512, width 256, 1 layer): a config, or the
// one inside a checkpoint's metadata, must not make the program allocate gigabytes before it can fail.
constexpr int64_t kMaxWidth = 4096, kMaxLinesPerPatch = 1024, kMaxPatches = 8192, kMaxLayers = 32, kMaxDepth = 32;
void require_dims(const std::vector<int64_t>& dims, const std::string& field) {
  require(!dims.empty() && static_cast<int64_t>(dims.size()) <= kMaxDepth, field, "must have 1 to " + std::to_string(kMaxDepth) + " entries");
  for (int64_t d : dims) require(d > 0 && d <= kMaxWidth, field, "entries must be in [1, " + std::to_string(kMaxWidth) + "]");
}
std::string range(int64_t hi) { return "must be in [1, " + std::to_string(hi) + "]"; }
bool is_probability(double p) { return p >= 0.0 && p < 1.0; }
}  // namespace

// ------------------------------------------------------------------------------------------ LptConfig
void LptConfig::Check() const {
  require(input_dim > 0 && input_dim <= kMaxWidth, "lpt.input_dim", range(kMaxWidth));
  require(lines_per_patch > 0 && lines_per_patch <= kMaxLinesPerPatch, "lpt.lines_per_patch", range(kMaxLinesPerPatch));
  require(patches > 0 && patches <= kMaxPatches, "lpt.patches", range(kMaxPatches));
  require_dims(mlp_dims, "lpt.mlp_dims");
  require(hidden_dim > 0 && hidden_dim <= kMaxWidth, "lpt.hidden_dim", range(kMaxWidth));
  require(mlp_dims.back() == hidden_dim, "lpt.mlp_dims",
          "must end with hidden_dim (" + std::to_string(hidden_dim) + ")");
  require(num_heads > 0 && hidden_dim % num_heads == 0, "lpt.num_heads", "must divide hidden_dim");
  require(ffn_dim > 0 && ffn_dim <= 4 * kMaxWidth, "lpt.ffn_dim", range(4 * kMaxWidth));
  require(is_probability(dropout), "lpt.dropout", "must be in [0, 1)");
  require(is_probability(attn_dropout), "lpt.attn_dropout", "must be in [0, 1)");
  require(line_layers >= 1 && line_layers <= kMaxLayers, "lpt.line_layers", range(kMaxLayers));
  require(patch_layers >= 1 && patch_layers <= kMaxLayers, "lpt.patch_layers", range(kMaxLayers));
  require(pool == "mean_all" || pool == "mean_valid", "lpt.pool", "must be \"mean_all\" or \"mean_valid\"");
}

nlohmann::json LptConfig::to_json() const { return fields_to_json(*this); }

LptConfig LptConfig::from_json(const nlohmann::json& j, const std::string& where) { return from_json(j, where, LptConfig()); }

LptConfig LptConfig::from_json(const nlohmann::json& j, const std::string& where, LptConfig c) {
  return fields_from_json(j, where, std::move(c));
}

// ----------------------------------------------------------------------------------------- HeadConfig
void HeadConfig::Check() const {
  require_dims(dims, "head.dims");
  require(is_probability(dropout), "head.dropout", "must be in [0, 1)");
}

nlohmann::json HeadConfig::to_json() const { return fields_to_json(*this); }

HeadConfig HeadConfig::from_json(const nlohmann::json& j, const std::string& where) { return from_json(j, where, HeadConfig()); }

HeadConfig HeadConfig::from_json(const nlohmann::json& j, const std::string& where, HeadConfig c) {
  return fields_from_json(j, where, std::move(c));
}

// ---------------------------------------------------------------------------------- JunctionNetConfig
void JunctionNetConfig::Check() const {
  lpt.Check();
  head.Check();
  require(patch_distance == "infinite_line" || patch_distance == "segment", "junction_net.patch_distance",
          "must be \"infinite_line\" or \"segment\"");
}

nlohmann::json JunctionNetConfig::to_json() const { return fields_to_json(*this); }

JunctionNetConfig JunctionNetConfig::from_json(const nlohmann::json& j, const std::string& where) { return from_json(j, where, JunctionNetConfig()); }

JunctionNetConfig JunctionNetConfig::from_json(const nlohmann::json& j, const std::string& where, JunctionNetConfig c) {
  return fields_from_json(j, where, std::move(c));
}

// -------------------------------------------------------------------------------------- EdgeNetConfig
LptConfig EdgeNetConfig::edge_lpt_defaults() {
  LptConfig c;
  c.input_dim = 6;
  c.lines_per_patch = 64;
  c.patches = 512;
  return c;
}

void EdgeNetConfig::Check() const {
  lpt.Check();
  head.Check();
  require(num_classes >= 2 && num_classes <= kMaxWidth, "edge_net.num_classes", "must be in [2, " + std::to_string(kMaxWidth) + "]");
}

nlohmann::json EdgeNetConfig::to_json() const { return fields_to_json(*this); }

EdgeNetConfig EdgeNetConfig::from_json(const nlohmann::json& j, const std::string& where) { return from_json(j, where, EdgeNetConfig()); }

EdgeNetConfig EdgeNetConfig::from_json(const nlohmann::json& j, const std::string& where, EdgeNetConfig c) {
  return fields_from_json(j, where, std::move(c));
}

// --------------------------------------------------------------------------------- JunctionLossConfig
void JunctionLossConfig::Check() const {
  require(kind == "paper" || kind == "release", "junction_loss.kind", "must be \"paper\" or \"release\"");
  require(reg_weight >= 0.0, "junction_loss.reg_weight", "must be >= 0");
}

nlohmann::json JunctionLossConfig::to_json() const { return fields_to_json(*this); }

JunctionLossConfig JunctionLossConfig::from_json(const nlohmann::json& j, const std::string& where) { return from_json(j, where, JunctionLossConfig()); }

JunctionLossConfig JunctionLossConfig::from_json(const nlohmann::json& j, const std::string& where, JunctionLossConfig c) {
  return fields_from_json(j, where, std::move(c));
}

// ------------------------------------------------------------------------------------- EdgeLossConfig
void EdgeLossConfig::Check() const {
  require(!class_weights.empty(), "edge_loss.class_weights", "must not be empty");
  for (double w : class_weights) require(w >= 0.0, "edge_loss.class_weights", "entries must be >= 0");
}

nlohmann::json EdgeLossConfig::to_json() const { return fields_to_json(*this); }

EdgeLossConfig EdgeLossConfig::from_json(const nlohmann::json& j, const std::string& where) { return from_json(j, where, EdgeLossConfig()); }

EdgeLossConfig EdgeLossConfig::from_json(const nlohmann::json& j, const std::string& where, EdgeLossConfig c) {
  return fields_from_json(j, where, std::move(c));
}

// ---------------------------------------------------------------------------------------- OptimConfig
void OptimConfig::Check() const {
  require(optimizer == "adamw" || optimizer == "sgd", "optim.optimizer", "must be \"adamw\" or \"sgd\"");
  require(lr > 0.0, "optim.lr", "must be > 0");
  require(beta1 >= 0.0 && beta1 < 1.0, "optim.beta1", "must be in [0, 1)");
  require(beta2 >= 0.0 && beta2 < 1.0, "optim.beta2", "must be in [0, 1)");
  require(eps > 0.0, "optim.eps", "must be > 0");
  require(momentum >= 0.0 && momentum < 1.0, "optim.momentum", "must be in [0, 1)");
  require(weight_decay >= 0.0, "optim.weight_decay", "must be >= 0");
  for (size_t i = 0; i < milestones.size(); ++i) {
    require(milestones[i] > 0, "optim.milestones", "entries must be > 0");
    require(i == 0 || milestones[i] > milestones[i - 1], "optim.milestones", "must be strictly increasing");
  }
  require(gamma > 0.0, "optim.gamma", "must be > 0");
  require(clip_grad_norm >= 0.0, "optim.clip_grad_norm", "must be >= 0 (0 disables clipping)");
}

nlohmann::json OptimConfig::to_json() const { return fields_to_json(*this); }

OptimConfig OptimConfig::from_json(const nlohmann::json& j, const std::string& where) { return from_json(j, where, OptimConfig()); }

OptimConfig OptimConfig::from_json(const nlohmann::json& j, const std::string& where, OptimConfig c) {
  return fields_from_json(j, where, std::move(c));
}

}  // namespace lc2wf
