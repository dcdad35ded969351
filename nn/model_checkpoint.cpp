#include "nn/model_checkpoint.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "nn/checkpoint.h"

namespace lc2wf {

namespace {

// Check() names the field; the checkpoint's path makes the error findable.
template <class Config>
void check_stored(const Config& config, const std::filesystem::path& path) {
  try {
    config.Check();
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(path.string() + ": net: " + e.what());
  }
}

// A weight that is NaN or inf makes every prediction non-finite: refused here, naming the file and the
// tensor, instead of failing later on each cloud with a message about junction candidates.
void check_finite(const Module& net, const std::filesystem::path& path) {
  for (const auto& [name, tensor] : net.named_parameters()) {
    if (tensor.dtype() != DType::F32) continue;
    const float* v = tensor.data<float>();
    for (int64_t i = 0; i < tensor.numel(); ++i)
      if (!std::isfinite(v[i]))
        throw std::runtime_error(path.string() + ": tensor '" + name + "' holds a non-finite value (element " + std::to_string(i) +
                                 "): not a usable model");
  }
}

template <class Net, class Config>
std::unique_ptr<Net> load_net(const std::filesystem::path& path, const std::string& stage) {
  const Config config = Config::from_json(stored_net_config(path, stage), path.string() + ": net");
  check_stored(config, path);
  auto net = std::make_unique<Net>(config);
  load_checkpoint(path, *net, nullptr, nullptr);
  check_finite(*net, path);
  net->eval();
  return net;
}

}  // namespace

nlohmann::json model_metadata(const std::string& stage, const nlohmann::json& net, const nlohmann::json& loss,
                              const nlohmann::json& optim, uint64_t seed) {
  return {{"stage", stage}, {"net", net}, {"loss", loss}, {"optim", optim}, {"seed", seed}};
}

nlohmann::json stored_net_config(const std::filesystem::path& path, const std::string& stage) {
  const CheckpointInfo info = read_checkpoint_info(path);
  if (!info.config.is_object() || !info.config.contains("net"))
    throw std::runtime_error(path.string() + ": checkpoint has no network config (not written by lc2wf-train?)");
  const std::string found = info.config.value("stage", std::string());
  if (found != stage) throw std::runtime_error(path.string() + ": expected a " + stage + " model, found stage '" + found + "'");
  return info.config.at("net");
}

std::unique_ptr<JunctionNet> load_junction_net(const std::filesystem::path& path) {
  return load_net<JunctionNet, JunctionNetConfig>(path, "junction");
}

std::unique_ptr<EdgeNet> load_edge_net(const std::filesystem::path& path) { return load_net<EdgeNet, EdgeNetConfig>(path, "edge"); }

}  // namespace lc2wf
