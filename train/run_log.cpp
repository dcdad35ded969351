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
    nlohmann::json j;
    try {
      j = nlohmann::json::parse(line);
    } catch (const nlohmann::json::parse_error&) {
      continue;  // a line torn by a kill
    }
    const long r = rank(j.value("stage", std::string()));
    if (r > current) continue;
    if (r == current && j.value("step", int64_t{0}) > step) continue;
    if (r == current && step == 0) continue;
    text += line + "\n";
  }
  in.close();
  write_text_atomically(path_, text);
}

}  // namespace lc2wf
