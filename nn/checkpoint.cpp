#include "nn/checkpoint.h"

#include <cstdio>
#include <map>
#include <stdexcept>

#include "core/util/version.h"
#include "nn/safetensors.h"

namespace lc2wf {

namespace {
constexpr const char* kFormat = "lc2wf-checkpoint-1";

std::string exact(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

const std::string& meta(const std::map<std::string, std::string>& m, const std::string& key, const std::string& file) {
  auto it = m.find(key);
  if (it == m.end()) throw std::runtime_error(file + ": checkpoint metadata lacks '" + key + "'");
  return it->second;
}

template <class T>
T meta_number(const std::map<std::string, std::string>& m, const std::string& key, const std::string& file) {
  const std::string& s = meta(m, key, file);
  try {
    size_t used = 0;
    T v;
    if constexpr (std::is_same_v<T, double>) v = std::stod(s, &used);
    else if constexpr (std::is_same_v<T, uint64_t>) v = std::stoull(s, &used);
    else v = std::stoll(s, &used);
    if (used != s.size()) throw std::invalid_argument("trailing characters");
    return v;
  } catch (const std::exception&) {
    throw std::runtime_error(file + ": checkpoint metadata '" + key + "' is not a number: '" + s + "'");
  }
}

CheckpointInfo parse_info(const std::map<std::string, std::string>& m, const std::string& file) {
  if (meta(m, "format", file) != kFormat)
    throw std::runtime_error(file + ": not an lc2wf checkpoint (format '" + meta(m, "format", file) + "')");
  CheckpointInfo info;
  try {
    info.config = nlohmann::json::parse(meta(m, "config", file));
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(file + ": checkpoint config is not valid JSON: " + e.what());
  }
  info.position.epoch = meta_number<int64_t>(m, "epoch", file);
  info.position.step = meta_number<int64_t>(m, "step", file);
  if (m.count("epoch_loss_sum")) info.position.epoch_loss_sum = meta_number<double>(m, "epoch_loss_sum", file);
  info.rng_seed = meta_number<uint64_t>(m, "dropout_rng_seed", file);
  info.rng_counter = meta_number<uint64_t>(m, "dropout_rng_counter", file);
  info.has_optimizer = meta(m, "optimizer", file) == "1";
  return info;
}
}  // namespace

std::filesystem::path optimizer_state_path(const std::filesystem::path& model_path) {
  std::filesystem::path p = model_path;
  p.replace_filename(model_path.stem().string() + ".optim.safetensors");
  return p;
}

void save_checkpoint(const std::filesystem::path& path, const Module& model, const nlohmann::json& config,
                     const Rng& dropout_rng, const Optimizer* optimizer, const TrainingPosition& position) {
  const std::string step = std::to_string(position.step);
  if (optimizer) {
    write_safetensors(optimizer_state_path(path), optimizer->state(),
                      {{"format", kFormat},
                       {"step", step},
                       {"optimizer_steps", std::to_string(optimizer->step_count())},
                       {"lr", exact(optimizer->lr())},
                       {"lc2wf_version", lc2wf_version()},
                       {"commit", lc2wf_git_commit()}});
  }
  write_safetensors(path, model.state_dict(),
                    {{"format", kFormat},
                     {"config", config.dump()},
                     {"epoch", std::to_string(position.epoch)},
                     {"step", step},
                     {"epoch_loss_sum", exact(position.epoch_loss_sum)},
                     {"dropout_rng_seed", std::to_string(dropout_rng.seed())},
                     {"dropout_rng_counter", std::to_string(dropout_rng.counter())},
                     {"optimizer", optimizer ? "1" : "0"},
                     {"lc2wf_version", lc2wf_version()},
                     {"commit", lc2wf_git_commit()}});
}

CheckpointInfo read_checkpoint_info(const std::filesystem::path& path) {
  return parse_info(read_safetensors(path).metadata, path.string());
}

CheckpointInfo load_checkpoint(const std::filesystem::path& path, Module& model, Rng* dropout_rng,
                               Optimizer* optimizer) {
  const SafetensorsFile file = read_safetensors(path);
  const CheckpointInfo info = parse_info(file.metadata, path.string());
  SafetensorsFile optim;
  const std::filesystem::path optim_path = optimizer_state_path(path);
  // Read and verify everything before touching the model, so a failed load changes nothing.
  if (optimizer) {
    if (!info.has_optimizer) throw std::runtime_error(path.string() + ": checkpoint holds no optimizer state");
    optim = read_safetensors(optim_path);
    if (meta(optim.metadata, "format", optim_path.string()) != kFormat ||
        meta_number<int64_t>(optim.metadata, "step", optim_path.string()) != info.position.step)
      throw std::runtime_error(optim_path.string() + ": optimizer state does not belong to " + path.string() +
                               " (different step)");
  }
  model.load_state_dict(file.tensors, path.string());
  if (dropout_rng) dropout_rng->set_state(info.rng_seed, info.rng_counter);
  if (optimizer) {
    optimizer->load_state(optim.tensors, meta_number<int64_t>(optim.metadata, "optimizer_steps", optim_path.string()),
                          optim_path.string());
    optimizer->set_lr(meta_number<double>(optim.metadata, "lr", optim_path.string()));
  }
  return info;
}

}  // namespace lc2wf
