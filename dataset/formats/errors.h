// Errors raised on bad input files. The message always names the source (file or stream name) and,
// when known, the 1-based line, so a user can find the problem without a debugger.
#pragma once

#include <stdexcept>
#include <string>

namespace lc2wf {

class DataError : public std::runtime_error {
 public:
  DataError(const std::string& source, int line, const std::string& problem)
      : std::runtime_error(format(source, line, problem)), source_(source), line_(line) {}
  DataError(const std::string& source, const std::string& problem) : DataError(source, 0, problem) {}

  const std::string& source() const { return source_; }
  int line() const { return line_; }

 private:
  static std::string format(const std::string& source, int line, const std::string& problem) {
    return line > 0 ? source + ":" + std::to_string(line) + ": " + problem : source + ": " + problem;
  }
  std::string source_;
  int line_;
};

// A building that loads but is rejected by a repair policy (e.g. non-planar faces with policy Skip).
class BuildingSkipped : public DataError {
 public:
  using DataError::DataError;
};

}  // namespace lc2wf
