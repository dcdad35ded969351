// Runs one of the project's command-line programs from a test and keeps its exit code and both streams, so
// CLI tests can check exit codes and messages rather than only that "something ran".
#pragma once

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

extern char** environ;

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

// `argv` run without a shell (argv[0] is the program's path), so arguments with spaces or quotes arrive as written.
inline CliResult run_argv(const std::vector<std::string>& argv) {
  const auto tmp = std::filesystem::temp_directory_path();
  const std::string tag = "lc2wf_cli_" + std::to_string(::getpid()) + "_" + std::to_string(std::rand());
  const auto out = tmp / (tag + ".out"), err = tmp / (tag + ".err");
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_t pid = 0;
  CliResult r;
  if (posix_spawn(&pid, args[0], &actions, nullptr, args.data(), environ) == 0) {
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0) {
    }
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  posix_spawn_file_actions_destroy(&actions);
  r.out = slurp_and_remove(out);
  r.err = slurp_and_remove(err);
  return r;
}

}  // namespace lc2wf::testing
