#include "train/stage_loop.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <limits>
#include <memory>
#include <stdexcept>

#include "core/blas_backend.h"
#include "core/matmul_precision.h"
#include "core/util/progress.h"
#include "nn/checkpoint.h"
#include "nn/optimizer.h"
#include "train/data_parallel.h"

namespace lc2wf {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

const std::vector<std::string>& stage_order() {
  static const std::vector<std::string> order{"junction", "handoff", "edge"};
  return order;
}

fs::path best_checkpoint_path(const fs::path& out, const std::string& stage) { return out / (stage + ".safetensors"); }
fs::path last_checkpoint_path(const fs::path& out, const std::string& stage, int slot) {
  return out / "checkpoints" / (stage + "_last_" + std::to_string(slot) + ".safetensors");
}

namespace {

struct Best {
  double score = -std::numeric_limits<double>::infinity();
  double loss = std::numeric_limits<double>::infinity();
  int64_t epoch = 0;
  nlohmann::json to_json() const {
    return {{"score", std::isfinite(score) ? nlohmann::json(score) : nlohmann::json(nullptr)},
            {"loss", std::isfinite(loss) ? nlohmann::json(loss) : nlohmann::json(nullptr)},
            {"epoch", epoch}};
  }
  static Best from_json(const nlohmann::json& j) {
    Best b;
    if (j.contains("score") && j["score"].is_number()) b.score = j["score"].get<double>();
    if (j.contains("loss") && j["loss"].is_number()) b.loss = j["loss"].get<double>();
    b.epoch = j.value("epoch", int64_t{0});
    return b;
  }
};

// CPU time of the whole process (every thread): unlike wall time it hardly depends on the machine's load.
double process_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

std::string hex(uint64_t v) {
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(v));
  return text;
}

// Every rank's fingerprint of its replica after a step; they must all be equal.
nlohmann::json check_replicas(Communicator& comm, const Module& model, const std::string& stage, int64_t step) {
  const uint64_t mine = state_fingerprint(model);
  nlohmann::json all = nlohmann::json::array();
  bool equal = true;
  for (const std::string& bytes : comm.all_gather(std::string(reinterpret_cast<const char*>(&mine), sizeof mine), "replica check")) {
    uint64_t v = 0;
    std::memcpy(&v, bytes.data(), sizeof v);
    equal = equal && v == mine;
    all.push_back(hex(v));
  }
  if (!equal)
    throw std::runtime_error(stage + " stage: the ranks' model replicas differ after step " + std::to_string(step) +
                             " (fingerprints " + all.dump() + "); the MPI sums did not give every rank the same bits");
  return all;
}

}  // namespace

Communicator& local_communicator() {
  static LocalCommunicator local;
  return local;
}

std::vector<std::pair<int, int>> micro_batch_ranges(int batch, int64_t micro) {
  const int step = micro <= 0 || micro >= batch ? batch : static_cast<int>(micro);
  std::vector<std::pair<int, int>> out;
  for (int first = 0; first < batch; first += step) out.emplace_back(first, std::min(step, batch - first));
  return out;
}

int64_t run_stage(const StageLoopOptions& o, Module& model, Rng& dropout_rng, RunLog& log, const StageCallbacks& cb) {
  const std::string& stage = o.stage;
  const fs::path best_path = best_checkpoint_path(o.out, stage);
  std::unique_ptr<Optimizer> optimizer = make_optimizer(model, o.optim);
  const MultiStepLR schedule(o.optim.lr, o.optim.milestones, o.optim.gamma);
  const int64_t spe = cb.batches_per_epoch;
  if (spe < 1)
    throw std::runtime_error(stage + " stage: the training split's " + std::to_string(cb.training_buildings) +
                             " usable building(s) give no full batch of " + stage + ".batch_size = " +
                             std::to_string(o.schedule.batch_size) + " (set " + stage + ".drop_last to false, or a smaller batch)");

  Communicator& comm = o.comm ? *o.comm : local_communicator();
  const bool writer = comm.rank() == 0;  // logs and checkpoints
  TrainingPosition pos;
  Best best;
  int slot = 0;  // the "last" slot the next save goes to
  if (o.resume && writer) {
    // Newest slot that loads completely (weights + matching optimiser state) wins.
    std::vector<std::pair<int64_t, int>> slots;
    for (int k : {0, 1}) {
      const fs::path p = last_checkpoint_path(o.out, stage, k);
      if (!fs::exists(p)) continue;
      try {
        const CheckpointInfo info = read_checkpoint_info(p);
        const nlohmann::json inputs = info.config.value("inputs", nlohmann::json());
        if (inputs != o.model_config.value("inputs", nlohmann::json())) {
          // E.g. the clouds were regenerated and the hand-off predicted again: this state learnt from other data.
          std::fprintf(stderr, "%s: not resuming %s: it was trained on other inputs (%s, now %s); the stage starts again\n",
                       stage.c_str(), p.string().c_str(), inputs.dump().c_str(),
                       o.model_config.value("inputs", nlohmann::json()).dump().c_str());
          continue;
        }
        slots.push_back({info.position.step, k});
      } catch (const std::exception& e) {
        if (!o.quiet) std::fprintf(stderr, "%s: ignoring %s: %s\n", stage.c_str(), p.string().c_str(), e.what());
      }
    }
    std::sort(slots.rbegin(), slots.rend());
    bool loaded = false;
    for (const auto& [step, k] : slots) {
      const fs::path p = last_checkpoint_path(o.out, stage, k);
      if (read_checkpoint_info(p).config.value("net", nlohmann::json()) != o.model_config.at("net"))
        throw std::runtime_error(p.string() + ": the network config differs from the one being resumed");
      try {
        const CheckpointInfo info = load_checkpoint(p, model, &dropout_rng, optimizer.get());
        pos = info.position;
        best = Best::from_json(info.config.value("best", nlohmann::json::object()));
        slot = 1 - k;
        loaded = true;
        if (!o.quiet)
          std::fprintf(stderr, "%s: resuming from %s (epoch %lld, step %lld)\n", stage.c_str(), p.string().c_str(),
                       static_cast<long long>(pos.epoch), static_cast<long long>(pos.step));
        break;
      } catch (const std::exception& e) {  // a pair torn by a kill: fall back to the other slot
        if (!o.quiet) std::fprintf(stderr, "%s: cannot resume from %s: %s\n", stage.c_str(), p.string().c_str(), e.what());
      }
    }
    if (!loaded) {
      if (!slots.empty()) throw std::runtime_error(stage + ": no usable checkpoint to resume from in " + (o.out / "checkpoints").string());
      if (!o.quiet) std::fprintf(stderr, "%s: no checkpoint in %s, starting from scratch\n", stage.c_str(), (o.out / "checkpoints").string().c_str());
    }
  }
  if (pos.step == 0 && !o.init_weights.empty()) {
    if (read_checkpoint_info(o.init_weights).config.value("net", nlohmann::json()) != o.model_config.at("net"))
      throw std::runtime_error("init_weights: " + o.init_weights.string() + " has another network config than " + stage + ".net");
    load_checkpoint(o.init_weights, model, nullptr, nullptr);
    if (!o.quiet) std::fprintf(stderr, "%s: starting from the weights of %s\n", stage.c_str(), o.init_weights.string().c_str());
  }
  if (comm.size() > 1) {
    // Rank 0's position, weights, optimiser and dropout stream, so every replica starts equal.
    std::string state = nlohmann::json{{"epoch", pos.epoch}, {"step", pos.step}, {"epoch_loss_sum", pos.epoch_loss_sum},
                                       {"best", best.to_json()}}.dump();
    comm.broadcast(state, "start-up state");
    const nlohmann::json j = nlohmann::json::parse(state);
    pos.epoch = j["epoch"].get<int64_t>();
    pos.step = j["step"].get<int64_t>();
    pos.epoch_loss_sum = j["epoch_loss_sum"].get<double>();
    best = Best::from_json(j["best"]);
    broadcast_training_state(comm, model, optimizer.get(), dropout_rng);
  }
  if (pos.epoch >= o.schedule.epochs) {  // complete: its log and the later stages' stay as they are
    if (!o.quiet) std::fprintf(stderr, "%s: already trained for %lld epochs\n", stage.c_str(), static_cast<long long>(pos.epoch));
    return 0;
  }
  if (writer) log.rewind(stage, pos.step, stage_order());

  auto config_with_best = [&] {
    nlohmann::json c = o.model_config;
    c["best"] = best.to_json();
    return c;
  };
  auto save_last = [&] {
    if (!writer) return;
    save_checkpoint(last_checkpoint_path(o.out, stage, slot), model, config_with_best(), dropout_rng, optimizer.get(), pos);
    slot = 1 - slot;
  };

  int64_t steps_run = 0;
  model.train();
  for (int64_t epoch = pos.epoch; epoch < o.schedule.epochs; ++epoch) {
    const double lr = schedule.lr_at(epoch);
    optimizer->set_lr(lr);
    const int64_t first = pos.step - epoch * spe;  // > 0 only when resuming mid-epoch
    if (first < 0 || first > spe) throw std::runtime_error(stage + ": checkpoint step " + std::to_string(pos.step) + " does not match the schedule");
    cb.start_epoch(epoch, first);
    std::unique_ptr<Progress> bar;
    if (!o.quiet)
      bar = std::make_unique<Progress>(stage + " epoch " + std::to_string(epoch + 1) + "/" + std::to_string(o.schedule.epochs),
                                       spe - first);
    const auto epoch_start = Clock::now();
    // A mid-epoch resume carries on the checkpoint's sum (same additions, same order): the logged mean is exact.
    double epoch_loss = first > 0 ? pos.epoch_loss_sum : 0.0;
    int64_t epoch_steps = first, epoch_buildings = 0;
    for (;;) {
      const auto t0 = Clock::now();
      const double cpu0 = process_cpu_seconds();
      std::optional<StageStep> s = cb.train_step();
      if (!s) break;
      if (!std::isfinite(s->loss))
        throw std::runtime_error(stage + " stage: loss is " + std::to_string(s->loss) + " at step " + std::to_string(pos.step + 1));
      double grad_norm = -1.0;
      if (o.optim.clip_grad_norm > 0) grad_norm = clip_grad_norm(model.parameters(), o.optim.clip_grad_norm);
      optimizer->step();
      optimizer->zero_grad();
      ++pos.step;
      ++steps_run;
      const double seconds = std::chrono::duration<double>(Clock::now() - t0).count();
      nlohmann::json line = {{"stage", stage}, {"type", "step"}, {"epoch", epoch + 1}, {"step", pos.step},
                             {"loss", s->loss}, {"lr", lr}, {"seconds", seconds},
                             {"cpu_seconds", process_cpu_seconds() - cpu0},
                             {"buildings_per_s", seconds > 0 ? s->buildings / seconds : 0.0}};
      for (auto it = s->terms.begin(); it != s->terms.end(); ++it) line[it.key()] = it.value();
      if (grad_norm >= 0) line["grad_norm"] = grad_norm;
      if (comm.size() > 1) {
        line["ranks"] = comm.size();
        line["comm_seconds"] = s->comm_seconds;
        line["replicas"] = check_replicas(comm, model, stage, pos.step);
      }
      if (writer) log.append(line);
      epoch_loss += s->loss;
      ++epoch_steps;
      epoch_buildings += s->buildings;
      if (bar) {
        char note[64];
        std::snprintf(note, sizeof note, "loss %.4f", s->loss);
        bar->step(1, note);
      }
      const bool epoch_end = pos.step == (epoch + 1) * spe;
      if (o.schedule.checkpoint_every_steps > 0 && pos.step % o.schedule.checkpoint_every_steps == 0 && !epoch_end) {
        pos.epoch = epoch;
        pos.epoch_loss_sum = epoch_loss;
        save_last();
      }
    }
    if (bar) bar->finish();
    const double epoch_seconds = std::chrono::duration<double>(Clock::now() - epoch_start).count();
    pos.epoch = epoch + 1;
    pos.epoch_loss_sum = 0.0;

    if ((epoch + 1) % o.schedule.val_every == 0 || epoch + 1 == o.schedule.epochs) {
      const auto v0 = Clock::now();
      const StageValidation v = cb.validate();
      model.train();
      const bool improved = v.score > best.score || (v.score == best.score && v.loss < best.loss);
      if (improved) best = {v.score, v.loss, epoch + 1};
      nlohmann::json line = {{"stage", stage}, {"type", "val"}, {"epoch", epoch + 1}, {"step", pos.step},
                             {"score", v.score}, {"loss", v.loss}, {"best", improved},
                             {"seconds", std::chrono::duration<double>(Clock::now() - v0).count()}};
      for (auto it = v.metrics.begin(); it != v.metrics.end(); ++it) line[it.key()] = it.value();
      if (writer) log.append(line);
      if (improved && writer) save_checkpoint(best_path, model, config_with_best(), dropout_rng, nullptr, pos);
      if (!o.quiet)
        std::fprintf(stderr, "%s epoch %lld: validation score %.4f loss %.4f%s\n", stage.c_str(),
                     static_cast<long long>(epoch + 1), v.score, v.loss, improved ? " (best)" : "");
    }
    if (writer)
      log.append({{"stage", stage}, {"type", "epoch"}, {"epoch", epoch + 1}, {"step", pos.step},
                {"train_loss", epoch_steps ? epoch_loss / epoch_steps : 0.0}, {"lr", lr}, {"seconds", epoch_seconds},
                {"buildings_per_s", epoch_seconds > 0 ? epoch_buildings / epoch_seconds : 0.0},
                // A run resumed on another machine mixes them: the model card lists what each stage ran on.
                {"precision", to_string(matmul_precision())}, {"gemm", gemm_backend_name()}});
    save_last();
  }
  return steps_run;
}

}  // namespace lc2wf
