// Starting external programs (COLMAP) from an argument vector: no shell, so paths with spaces or quotes
// in them are passed through unchanged and nothing is interpreted.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace lc2wf {

struct ProcessResult {
  int exit_code = -1;  // the program's exit status; -1 when it could not start or was killed
  int signal = 0;      // the signal that ended it, 0 when it exited
  double seconds = 0;  // wall time
};

// Runs argv[0] (searched on PATH) with the given arguments, waits, and appends its stdout and stderr to
// `log` (created when missing). Throws std::runtime_error when the log cannot be opened.
ProcessResult run_process(const std::vector<std::string>& argv, const std::filesystem::path& log);

// True when `program` is an executable on PATH (or an executable path).
bool program_on_path(const std::string& program);

}  // namespace lc2wf
