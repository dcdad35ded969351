#include "train/model_card.h"

#include <string>

#include "core/util/atomic_file.h"
#include "core/util/version.h"
#include "nn/checkpoint.h"
#include "train/stage_loop.h"

namespace lc2wf {

namespace {

// One table row: the kept weights of `stage` and the validation score they were selected by.
std::string stage_row(const std::filesystem::path& out, const std::string& stage, const std::string& metric, int64_t epochs) {
  const std::filesystem::path best = best_checkpoint_path(out, stage);
  if (!std::filesystem::exists(best)) return "| " + stage + " | not trained | | |\n";
  const nlohmann::json kept = read_checkpoint_info(best).config.value("best", nlohmann::json::object());
  const nlohmann::json score = kept.value("score", nlohmann::json());
  return "| " + stage + " | `" + best.filename().string() + "` | " + std::to_string(kept.value("epoch", int64_t{0})) + " of " +
         std::to_string(epochs) + " | " + metric + " " + (score.is_number() ? std::to_string(score.get<double>()) : "-") + " |\n";
}

}  // namespace

void write_model_card(const std::filesystem::path& out, const std::filesystem::path& config_file, const TrainConfig& config,
                      const BuildingSet& train, const BuildingSet& val) {
  std::string card = "# lc2wf model\n\n";
  card += "Trained by `lc2wf-train " + config_file.string() + "` with lc2wf " + lc2wf_version() + " (commit " + lc2wf_git_commit() +
          "); the resolved config is `config.json`, the learning curves `log.jsonl`.\n\n";
  card += "Data: " + std::to_string(train.clouds.size()) + " training buildings (`" + train.split + "`), " +
          std::to_string(val.clouds.size()) + " validation buildings (`" + val.split + "`), line clouds from `" + config.data.dir +
          "` (format " + config.data.format + ").\n\n";
  card += "| stage | weights | kept epoch | validation score |\n|---|---|---|---|\n";
  card += stage_row(out, "junction", "vAP mean", config.junction.schedule.epochs);
  card += stage_row(out, "edge", "sAP mean", config.edge.schedule.epochs);
  card += "\nUse: `lc2wf-infer --weights DIR CLOUD... -o OUT`, `lc2wf-eval --weights DIR --data CLOUDS -o OUT`.\n";
  write_text_atomically(out / "README.md", card);
}

}  // namespace lc2wf
