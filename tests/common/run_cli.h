// Runs one of the project's command-line programs from a test and keeps its exit code and both streams, so
// CLI tests can check exit codes and messages rather than only that "something ran".
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace lc2wf::testing {

struct CliResult {
  int code = -1;  // -1 when the program did not exit normally (signal, crash)
  std::string out, err;
};

inline std::string slurp_and_remove(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  std::filesystem::remove(path);
  return ss.str();
}

// `command` is passed to the shell as is; stdout and stderr go to files next to the system temp folder.
inline CliResult run_cli(const std::string& command) {
  const auto tmp = std::filesystem::temp_directory_path();
  const std::string tag = "lc2wf_cli_" + std::to_string(::getpid()) + "_" + std::to_string(std::rand());
  const auto out = tmp / (tag + ".out"), err = tmp / (tag + ".err");
  const int status = std::system((command + " >" + out.string() + " 2>" + err.string()).c_str());
  CliResult r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp_and_remove(out);
  r.err = slurp_and_remove(err);
  return r;
}

}  // namespace lc2wf::testing
