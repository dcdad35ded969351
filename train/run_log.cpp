#include "train/run_log.h"

#include <algorithm>
#include <stdexcept>
#include <vector>

#include "core/util/atomic_file.h"

namespace lc2wf {

namespace fs = std::filesystem;

RunLog::RunLog(fs::path path) : path_(std::move(path)) {}

void RunLog::append(const nlohmann::json& line) {
  if (!out_.is_open()) {
    if (path_.has_parent_path()) fs::create_directories(path_.parent_path());
    out_.open(path_, std::ios::app);
    if (!out_) throw std::runtime_error("cannot open " + path_.string() + " for appending");
  }
  out_ << line.dump() << '\n';
  out_.flush();
  if (!out_) throw std::runtime_error("failed writing " + path_.string());
}

void RunLog::rewind(const std::string& stage, int64_t step, const std::vector<std::string>& stage_order) {
  if (out_.is_open()) out_.close();
  if (!fs::exists(path_)) return;
  const auto rank = [&](const std::string& s) {
    const auto it = std::find(stage_order.begin(), stage_order.end(), s);
    return it == stage_order.end() ? static_cast<long>(stage_order.size()) : static_cast<long>(it - stage_order.begin());
  };
  const long current = rank(stage);
  std::ifstream in(path_);
  std::string text, line;
  while (std::getline(in, line)) {
    const nlohmann::json j = nlohmann::json::parse(line, nullptr, /*allow_exceptions=*/false);
    // A line torn by a kill, or not one of ours ('5', a string "stage"), is dropped: value() would throw.
    if (!j.is_object()) continue;
    const auto stage_it = j.find("stage"), step_it = j.find("step");
    const std::string stage_name = stage_it != j.end() && stage_it->is_string() ? stage_it->get<std::string>() : "";
    const int64_t line_step = step_it != j.end() && step_it->is_number_integer() ? step_it->get<int64_t>() : 0;
    const long r = rank(stage_name);
    if (r > current) continue;
    if (r == current && line_step > step) continue;
    if (r == current && step == 0) continue;
    text += line + "\n";
  }
  in.close();
  write_text_atomically(path_, text);
}

}  // namespace lc2wf
