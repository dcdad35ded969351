// The training log `<out>/log.jsonl`: one JSON object per line, appended and flushed as training goes
// (format in train/README.md). Every line has "stage" and "type" ("step", "val", "epoch", "handoff") and,
// for "step"/"val"/"epoch", the global optimiser "step" it belongs to.
#pragma once

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

namespace lc2wf {

class RunLog {
 public:
  explicit RunLog(std::filesystem::path path);

  void append(const nlohmann::json& line);

  // Before a (re)start of `stage` at optimiser step `step`: keeps the lines of earlier stages and this
  // stage's lines up to `step` (those of a killed run past its last checkpoint are dropped, so a resumed
  // run logs exactly what an uninterrupted one would). Lines of later stages and torn lines are dropped.
  // `stage_order` lists the stages in run order.
  void rewind(const std::string& stage, int64_t step, const std::vector<std::string>& stage_order);

  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  std::ofstream out_;
};

}  // namespace lc2wf
