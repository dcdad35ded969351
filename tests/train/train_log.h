// Reading lc2wf-train's log.jsonl in tests: the lines of one type, and the (stage, step, loss) of every
// optimiser step.
#pragma once

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <tuple>
#include <vector>

#include <nlohmann/json.hpp>

namespace lc2wf::testing {

inline std::vector<nlohmann::json> log_lines(const std::filesystem::path& p, const std::string& type) {
  std::vector<nlohmann::json> out;
  std::ifstream in(p);
  std::string line;
  // A last line without its newline is still being written by a running lc2wf-train (tests poll the log).
  while (std::getline(in, line) && !in.eof()) {
    const nlohmann::json j = nlohmann::json::parse(line);
    if (j["type"] == type) out.push_back(j);
  }
  return out;
}

inline std::vector<std::tuple<std::string, int64_t, double>> step_losses(const std::filesystem::path& log) {
  std::vector<std::tuple<std::string, int64_t, double>> out;
  for (const auto& j : log_lines(log, "step")) out.emplace_back(j["stage"], j["step"], j["loss"]);
  return out;
}

}  // namespace lc2wf::testing
