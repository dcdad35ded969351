// A reconstruction stage that cannot go on: the message names the stage and the files involved, and the
// command exits with code 3 (data or I/O error) without writing anything into the output folder.
#pragma once

#include <stdexcept>
#include <string>

namespace lc2wf {

class StageError : public std::runtime_error {
 public:
  StageError(const std::string& stage, const std::string& problem) : std::runtime_error(stage + ": " + problem), stage_(stage) {}
  const std::string& stage() const { return stage_; }

 private:
  std::string stage_;
};

}  // namespace lc2wf
