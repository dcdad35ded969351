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

namespace {

// Where a stage stands: its position in the schedule, its best validation so far and the "last" slot the
// next save goes to.
struct StageState {
  TrainingPosition pos;
  Best best;
  int slot = 0;
};

// The newest "last" slot that loads completely (weights + matching optimiser state); a slot trained on
// other inputs is passed over, so the stage starts again.
void resume_from_last_checkpoint(const StageLoopOptions& o, Module& model, Rng& dropout_rng, Optimizer* optimizer, StageState& st) {
  const std::string& stage = o.stage;
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
  for (const auto& [step, k] : slots) {
    const fs::path p = last_checkpoint_path(o.out, stage, k);
    if (read_checkpoint_info(p).config.value("net", nlohmann::json()) != o.model_config.at("net"))
      throw std::runtime_error(p.string() + ": the network config differs from the one being resumed");
    try {
      const CheckpointInfo info = load_checkpoint(p, model, &dropout_rng, optimizer);
      st.pos = info.position;
      st.best = Best::from_json(info.config.value("best", nlohmann::json::object()));
      st.slot = 1 - k;
      if (!o.quiet)
        std::fprintf(stderr, "%s: resuming from %s (epoch %lld, step %lld)\n", stage.c_str(), p.string().c_str(),
                     static_cast<long long>(st.pos.epoch), static_cast<long long>(st.pos.step));
      return;
    } catch (const std::exception& e) {  // a pair torn by a kill: fall back to the other slot
      if (!o.quiet) std::fprintf(stderr, "%s: cannot resume from %s: %s\n", stage.c_str(), p.string().c_str(), e.what());
    }
  }
  if (!slots.empty()) throw std::runtime_error(stage + ": no usable checkpoint to resume from in " + (o.out / "checkpoints").string());
  if (!o.quiet) std::fprintf(stderr, "%s: no checkpoint in %s, starting from scratch\n", stage.c_str(), (o.out / "checkpoints").string().c_str());
}

// A net config without what a fine-tune may change: the patch distance picks the lines the weights see, not
// the weights' shapes (a model stored before the key existed used the release's).
nlohmann::json weight_shapes(nlohmann::json net) {
  if (net.is_object()) net.erase("patch_distance");
  return net;
}

void load_init_weights(const StageLoopOptions& o, Module& model) {
  if (weight_shapes(read_checkpoint_info(o.init_weights).config.value("net", nlohmann::json())) != weight_shapes(o.model_config.at("net")))
    throw std::runtime_error("init_weights: " + o.init_weights.string() + " has another network config than " + o.stage + ".net");
  load_checkpoint(o.init_weights, model, nullptr, nullptr);
  if (!o.quiet) std::fprintf(stderr, "%s: starting from the weights of %s\n", o.stage.c_str(), o.init_weights.string().c_str());
}

// Rank 0's position, weights, optimiser and dropout stream, so every replica starts equal.
void share_start_state(Communicator& comm, Module& model, Optimizer* optimizer, Rng& dropout_rng, StageState& st) {
  std::string state = nlohmann::json{{"epoch", st.pos.epoch}, {"step", st.pos.step}, {"epoch_loss_sum", st.pos.epoch_loss_sum},
                                     {"best", st.best.to_json()}}.dump();
  comm.broadcast(state, "start-up state");
  const nlohmann::json j = nlohmann::json::parse(state);
  st.pos.epoch = j["epoch"].get<int64_t>();
  st.pos.step = j["step"].get<int64_t>();
  st.pos.epoch_loss_sum = j["epoch_loss_sum"].get<double>();
  st.best = Best::from_json(j["best"]);
  broadcast_training_state(comm, model, optimizer, dropout_rng);
}

// One stage's training run: its checkpoints, its log and its steps, shared by the epochs.
class StageRun {
 public:
  StageRun(const StageLoopOptions& o, Module& model, Rng& dropout_rng, RunLog& log, const StageCallbacks& cb)
      : o_(o), model_(model), dropout_rng_(dropout_rng), log_(log), cb_(cb), optimizer_(make_optimizer(model, o.optim)),
        comm_(o.comm ? *o.comm : local_communicator()), writer_(comm_.rank() == 0) {}

  int64_t run() {
    const std::string& stage = o_.stage;
    if (cb_.batches_per_epoch < 1)
      throw std::runtime_error(stage + " stage: the training split's " + std::to_string(cb_.training_buildings) +
                               " usable building(s) give no full batch of " + stage + ".batch_size = " +
                               std::to_string(o_.schedule.batch_size) + " (set " + stage + ".drop_last to false, or a smaller batch)");
    if (o_.resume && writer_) resume_from_last_checkpoint(o_, model_, dropout_rng_, optimizer_.get(), st_);
    if (st_.pos.step == 0 && !o_.init_weights.empty()) load_init_weights(o_, model_);
    if (comm_.size() > 1) share_start_state(comm_, model_, optimizer_.get(), dropout_rng_, st_);
    if (st_.pos.epoch >= o_.schedule.epochs) {  // complete: its log and the later stages' stay as they are
      if (!o_.quiet) std::fprintf(stderr, "%s: already trained for %lld epochs\n", stage.c_str(), static_cast<long long>(st_.pos.epoch));
      return 0;
    }
    if (writer_) log_.rewind(stage, st_.pos.step, stage_order());
    model_.train();
    const MultiStepLR schedule(o_.optim.lr, o_.optim.milestones, o_.optim.gamma);
    for (int64_t epoch = st_.pos.epoch; epoch < o_.schedule.epochs; ++epoch) {
      const double lr = schedule.lr_at(epoch);
      optimizer_->set_lr(lr);
      const EpochTotals totals = train_epoch(epoch, lr);
      st_.pos.epoch = epoch + 1;
      st_.pos.epoch_loss_sum = 0.0;
      if ((epoch + 1) % o_.schedule.val_every == 0 || epoch + 1 == o_.schedule.epochs) validate(epoch);
      log_epoch(epoch, lr, totals);
      save_last();
    }
    return steps_run_;
  }

 private:
  struct EpochTotals {
    double loss = 0, seconds = 0;
    int64_t steps = 0, buildings = 0;
  };

  nlohmann::json config_with_best() const {
    nlohmann::json c = o_.model_config;
    c["best"] = st_.best.to_json();
    return c;
  }

  void save_last() {
    if (!writer_) return;
    save_checkpoint(last_checkpoint_path(o_.out, o_.stage, st_.slot), model_, config_with_best(), dropout_rng_, optimizer_.get(), st_.pos);
    st_.slot = 1 - st_.slot;
  }

  EpochTotals train_epoch(int64_t epoch, double lr) {
    const std::string& stage = o_.stage;
    const int64_t spe = cb_.batches_per_epoch;
    const int64_t first = st_.pos.step - epoch * spe;  // > 0 only when resuming mid-epoch
    if (first < 0 || first > spe) throw std::runtime_error(stage + ": checkpoint step " + std::to_string(st_.pos.step) + " does not match the schedule");
    cb_.start_epoch(epoch, first);
    std::unique_ptr<Progress> bar;
    if (!o_.quiet)
      bar = std::make_unique<Progress>(stage + " epoch " + std::to_string(epoch + 1) + "/" + std::to_string(o_.schedule.epochs),
                                       spe - first);
    const auto epoch_start = Clock::now();
    // A mid-epoch resume carries on the checkpoint's sum (same additions, same order): the logged mean is exact.
    EpochTotals t;
    t.loss = first > 0 ? st_.pos.epoch_loss_sum : 0.0;
    t.steps = first;
    for (;;) {
      step_start_ = Clock::now();
      step_cpu0_ = process_cpu_seconds();
      const std::optional<StageStep> s = cb_.train_step();
      if (!s) break;
      train_step(*s, epoch, lr);
      t.loss += s->loss;
      ++t.steps;
      t.buildings += s->buildings;
      if (bar) {
        char note[64];
        std::snprintf(note, sizeof note, "loss %.4f", s->loss);
        bar->step(1, note);
      }
      const bool epoch_end = st_.pos.step == (epoch + 1) * spe;
      if (o_.schedule.checkpoint_every_steps > 0 && st_.pos.step % o_.schedule.checkpoint_every_steps == 0 && !epoch_end) {
        st_.pos.epoch = epoch;
        st_.pos.epoch_loss_sum = t.loss;
        save_last();
      }
    }
    if (bar) bar->finish();
    t.seconds = std::chrono::duration<double>(Clock::now() - epoch_start).count();
    return t;
  }

  // The optimiser step after the callback's forward and backward pass, and its log line.
  void train_step(const StageStep& s, int64_t epoch, double lr) {
    const std::string& stage = o_.stage;
    const Clock::time_point t0 = step_start_;  // taken before the callback's forward and backward pass
    const double cpu0 = step_cpu0_;
    if (!std::isfinite(s.loss))
      throw std::runtime_error(stage + " stage: loss is " + std::to_string(s.loss) + " at step " + std::to_string(st_.pos.step + 1));
    double grad_norm = -1.0;
    if (o_.optim.clip_grad_norm > 0) grad_norm = clip_grad_norm(model_.parameters(), o_.optim.clip_grad_norm);
    optimizer_->step();
    optimizer_->zero_grad();
    ++st_.pos.step;
    ++steps_run_;
    const double seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    nlohmann::json line = {{"stage", stage}, {"type", "step"}, {"epoch", epoch + 1}, {"step", st_.pos.step},
                           {"loss", s.loss}, {"lr", lr}, {"seconds", seconds},
                           {"cpu_seconds", process_cpu_seconds() - cpu0},
                           {"buildings_per_s", seconds > 0 ? s.buildings / seconds : 0.0}};
    for (auto it = s.terms.begin(); it != s.terms.end(); ++it) line[it.key()] = it.value();
    if (grad_norm >= 0) line["grad_norm"] = grad_norm;
    if (comm_.size() > 1) {
      line["ranks"] = comm_.size();
      line["comm_seconds"] = s.comm_seconds;
      line["replicas"] = check_replicas(comm_, model_, stage, st_.pos.step);
    }
    if (writer_) log_.append(line);
  }

  void validate(int64_t epoch) {
    const std::string& stage = o_.stage;
    const auto v0 = Clock::now();
    const StageValidation v = cb_.validate();
    model_.train();
    const bool improved = v.score > st_.best.score || (v.score == st_.best.score && v.loss < st_.best.loss);
    if (improved) st_.best = {v.score, v.loss, epoch + 1};
    nlohmann::json line = {{"stage", stage}, {"type", "val"}, {"epoch", epoch + 1}, {"step", st_.pos.step},
                           {"score", v.score}, {"loss", v.loss}, {"best", improved},
                           {"seconds", std::chrono::duration<double>(Clock::now() - v0).count()}};
    for (auto it = v.metrics.begin(); it != v.metrics.end(); ++it) line[it.key()] = it.value();
    if (writer_) log_.append(line);
    if (improved && writer_) save_checkpoint(best_checkpoint_path(o_.out, stage), model_, config_with_best(), dropout_rng_, nullptr, st_.pos);
    if (!o_.quiet)
      std::fprintf(stderr, "%s epoch %lld: validation score %.4f loss %.4f%s\n", stage.c_str(), static_cast<long long>(epoch + 1),
                   v.score, v.loss, improved ? " (best)" : "");
  }

  void log_epoch(int64_t epoch, double lr, const EpochTotals& t) {
    if (!writer_) return;
    log_.append({{"stage", o_.stage}, {"type", "epoch"}, {"epoch", epoch + 1}, {"step", st_.pos.step},
                 {"train_loss", t.steps ? t.loss / t.steps : 0.0}, {"lr", lr}, {"seconds", t.seconds},
                 {"buildings_per_s", t.seconds > 0 ? t.buildings / t.seconds : 0.0},
                 // A run resumed on another machine mixes them: the model card lists what each stage ran on.
                 {"precision", to_string(matmul_precision())}, {"gemm", gemm_backend_name()}});
  }

  const StageLoopOptions& o_;
  Module& model_;
  Rng& dropout_rng_;
  RunLog& log_;
  const StageCallbacks& cb_;
  std::unique_ptr<Optimizer> optimizer_;
  Communicator& comm_;
  const bool writer_;
  StageState st_;
  int64_t steps_run_ = 0;
  Clock::time_point step_start_;
  double step_cpu0_ = 0;
};

}  // namespace

int64_t run_stage(const StageLoopOptions& o, Module& model, Rng& dropout_rng, RunLog& log, const StageCallbacks& cb) {
  return StageRun(o, model, dropout_rng, log, cb).run();
}

}  // namespace lc2wf
