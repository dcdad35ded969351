// Sizes and options of the networks, losses and optimiser. Defaults are the values of the LC2WF paper
// and its released code (width 256, G = 256 / 512, N = 32 / 64, AdamW 1e-3); every struct round-trips through JSON and Check() names a bad field.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace lc2wf {

// Every from_json starts from `base` (the defaults unless given), so absent keys keep its values
// and unknown keys are rejected.
struct LptConfig {
  int64_t input_dim = 7;          // F: per-line features (7 junction, 6 edge)
  int64_t lines_per_patch = 32;   // N: line slots per patch (32 junction, 64 edge)
  int64_t patches = 256;          // G: patches per building in training (256 junction, 512 edge pairs)
  std::vector<int64_t> mlp_dims{64, 64, 128, 128, 256};  // per-line MLP; the last equals hidden_dim
  int64_t hidden_dim = 256;
  int64_t num_heads = 8;
  int64_t ffn_dim = 256;
  double dropout = 0.5;           // residual and FFN dropout inside the encoders
  double attn_dropout = 0.5;      // attention-weight dropout
  int64_t line_layers = 1;        // encoder over the N lines of a patch
  int64_t patch_layers = 1;       // encoder over the G patches of a building
  std::string pool = "mean_all";  // "mean_all" (release: padded slots included) or "mean_valid"

  // Every JSON key, listed once (to_json and from_json both walk it).
  template <class S, class V>
  static void fields(S& s, V& v) {
    v("input_dim", s.input_dim);
    v("lines_per_patch", s.lines_per_patch);
    v("patches", s.patches);
    v("mlp_dims", s.mlp_dims);
    v("hidden_dim", s.hidden_dim);
    v("num_heads", s.num_heads);
    v("ffn_dim", s.ffn_dim);
    v("dropout", s.dropout);
    v("attn_dropout", s.attn_dropout);
    v("line_layers", s.line_layers);
    v("patch_layers", s.patch_layers);
    v("pool", s.pool);
  }
  void Check() const;
  nlohmann::json to_json() const;
  static LptConfig from_json(const nlohmann::json& j, const std::string& where = "lpt");
  static LptConfig from_json(const nlohmann::json& j, const std::string& where, LptConfig base);
};

struct HeadConfig {
  std::vector<int64_t> dims{128, 64, 32};  // hidden widths, each Linear + BatchNorm + ReLU + Dropout
  double dropout = 0.1;

  // Every JSON key, listed once (to_json and from_json both walk it).
  template <class S, class V>
  static void fields(S& s, V& v) {
    v("dims", s.dims);
    v("dropout", s.dropout);
  }
  void Check() const;
  nlohmann::json to_json() const;
  static HeadConfig from_json(const nlohmann::json& j, const std::string& where = "head");
  static HeadConfig from_json(const nlohmann::json& j, const std::string& where, HeadConfig base);
};

struct JunctionNetConfig {
  LptConfig lpt;  // F 7, N 32, G 256
  HeadConfig head;
  // Which lines fill a patch: "infinite_line" (the release's: nearest by distance to the line's extension) or
  // "segment" (nearest by distance to the segment). Part of what the weights learnt, so it travels with them.
  std::string patch_distance = "infinite_line";

  // Every JSON key, listed once (to_json and from_json both walk it).
  template <class S, class V>
  static void fields(S& s, V& v) {
    v("lpt", s.lpt);
    v("head", s.head);
    v("patch_distance", s.patch_distance);
  }
  void Check() const;
  nlohmann::json to_json() const;
  static JunctionNetConfig from_json(const nlohmann::json& j, const std::string& where = "junction_net");
  static JunctionNetConfig from_json(const nlohmann::json& j, const std::string& where, JunctionNetConfig base);
};

struct EdgeNetConfig {
  LptConfig lpt = edge_lpt_defaults();  // F 6, N 64, G 512
  HeadConfig head;
  int64_t num_classes = 5;

  // Every JSON key, listed once (to_json and from_json both walk it).
  template <class S, class V>
  static void fields(S& s, V& v) {
    v("lpt", s.lpt);
    v("head", s.head);
    v("num_classes", s.num_classes);
  }
  void Check() const;
  nlohmann::json to_json() const;
  static EdgeNetConfig from_json(const nlohmann::json& j, const std::string& where = "edge_net");
  static EdgeNetConfig from_json(const nlohmann::json& j, const std::string& where, EdgeNetConfig base);
  static LptConfig edge_lpt_defaults();
};

// "paper": BCE on the positive-class logit + reg_weight * L2 (what the paper states);
// "release": 2-class softmax CE + reg_weight * L1 (what the released code trains with).
struct JunctionLossConfig {
  std::string kind = "paper";
  double reg_weight = 10.0;  // lambda_v

  // Every JSON key, listed once (to_json and from_json both walk it).
  template <class S, class V>
  static void fields(S& s, V& v) {
    v("kind", s.kind);
    v("reg_weight", s.reg_weight);
  }
  void Check() const;
  nlohmann::json to_json() const;
  static JunctionLossConfig from_json(const nlohmann::json& j, const std::string& where = "junction_loss");
  static JunctionLossConfig from_json(const nlohmann::json& j, const std::string& where, JunctionLossConfig base);
};

struct EdgeLossConfig {
  std::vector<double> class_weights{1, 3, 1, 1, 1};  // identical, connected, dist 2, dist > 2, false positive

  // Every JSON key, listed once (to_json and from_json both walk it).
  template <class S, class V>
  static void fields(S& s, V& v) {
    v("class_weights", s.class_weights);
  }
  void Check() const;
  nlohmann::json to_json() const;
  static EdgeLossConfig from_json(const nlohmann::json& j, const std::string& where = "edge_loss");
  static EdgeLossConfig from_json(const nlohmann::json& j, const std::string& where, EdgeLossConfig base);
};

struct OptimConfig {
  std::string optimizer = "adamw";  // "adamw" or "sgd"
  double lr = 1e-3;
  double beta1 = 0.9, beta2 = 0.999, eps = 1e-8;  // AdamW
  double momentum = 0.9;                          // SGD
  double weight_decay = 1e-5;                     // on every parameter whose name has no "bias"
  std::vector<int64_t> milestones{15, 30, 41};     // MultiStepLR epochs (edge stage: 15, 25, 31)
  double gamma = 0.1;
  double clip_grad_norm = 0.0;  // 0 = no clipping

  // Every JSON key, listed once (to_json and from_json both walk it).
  template <class S, class V>
  static void fields(S& s, V& v) {
    v("optimizer", s.optimizer);
    v("lr", s.lr);
    v("beta1", s.beta1);
    v("beta2", s.beta2);
    v("eps", s.eps);
    v("momentum", s.momentum);
    v("weight_decay", s.weight_decay);
    v("milestones", s.milestones);
    v("gamma", s.gamma);
    v("clip_grad_norm", s.clip_grad_norm);
  }
  void Check() const;
  nlohmann::json to_json() const;
  static OptimConfig from_json(const nlohmann::json& j, const std::string& where = "optim");
  static OptimConfig from_json(const nlohmann::json& j, const std::string& where, OptimConfig base);
};

}  // namespace lc2wf
