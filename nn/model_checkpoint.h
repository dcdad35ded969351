// What a trained model's checkpoint says about itself, written by lc2wf-train and read by every command that
// loads a model: the metadata `config` object {"stage": "junction"|"edge", "net", "loss", "optim", "seed"}
// (plus "best" in the trainer's checkpoints), and the networks rebuilt from it. The one definition of
// that layout; checkpoints of earlier runs hold the same keys and stay loadable.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "nn/edge_net.h"
#include "nn/junction_net.h"

namespace lc2wf {

// The `config` metadata of a stage's checkpoints.
nlohmann::json model_metadata(const std::string& stage, const nlohmann::json& net, const nlohmann::json& loss,
                              const nlohmann::json& optim, uint64_t seed);

// The network config stored in a checkpoint of `stage`; throws std::runtime_error naming the file when the
// checkpoint has none or belongs to the other stage.
nlohmann::json stored_net_config(const std::filesystem::path& path, const std::string& stage);

// Rebuilds a network from the config stored in a checkpoint and loads its weights (eval mode).
std::unique_ptr<JunctionNet> load_junction_net(const std::filesystem::path& path);
std::unique_ptr<EdgeNet> load_edge_net(const std::filesystem::path& path);

}  // namespace lc2wf
