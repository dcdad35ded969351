// The shared shape of lc2wf's command-line programs (README.md, "Command-line conventions"): --help anywhere
// prints the usage with the common options, the environment variables and the exit codes, and exits 0;
// --version prints the version and git commit; a UsageError exits 2 with a pointer to --help; any other
// exception (while checking the inputs or running) is a data or I/O error, exit 3. A command returns 1
// itself when it did part of its work.
#pragma once

#include <cmath>
#include <cstdio>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/util/version.h"

namespace lc2wf {

struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

constexpr int kExitDone = 0;
constexpr int kExitPartly = 1;     // done, but some inputs failed (the command says which)
constexpr int kExitUsage = 2;      // bad command line
constexpr int kExitDataError = 3;  // bad or missing input data, I/O error; nothing or little was done

// An environment variable that changes what a command does, listed in its --help.
struct EnvVar {
  const char* name;
  const char* meaning;
};
inline constexpr EnvVar kEnvOmpThreads{"OMP_NUM_THREADS", "thread count when -j is not given (default: all cores)"};
inline constexpr EnvVar kEnvStorageCache{"LC2WF_STORAGE_CACHE_MB",
                                         "memory kept to reuse large tensor buffers, MB (default: a quarter of RAM, at most 4096)"};
inline constexpr EnvVar kEnvGemm{"LC2WF_GEMM",
                                 "eigen: matrix products by Eigen instead of OpenBLAS (default auto: OpenBLAS where installed)"};

struct Command {
  const char* program;              // "lc2wf-infer"
  const char* usage;                // "Usage: ..." and the command's options, -o/-j/-q among them
  std::vector<EnvVar> environment;  // what the command reads from the environment
};

// `parse(text, &used)` (std::stoi, std::stod, ...) when it consumes the whole non-empty string, else nothing.
template <class Parse>
auto parse_whole(const std::string& text, Parse parse) -> std::optional<decltype(parse(text, nullptr))> {
  try {
    size_t used = 0;
    const auto x = parse(text, &used);
    if (!text.empty() && used == text.size()) return x;
  } catch (const std::exception&) {
  }
  return std::nullopt;
}

// Whole-string non-negative integer for FLAG ("12x", "-1" and "" are usage errors, not silently 12/0).
inline long long parse_count_flag(const std::string& flag, const std::string& value) {
  const auto x = parse_whole(value, [](const std::string& t, size_t* used) { return std::stoll(t, used); });
  if (!x || *x < 0) throw UsageError(flag + " needs a non-negative integer, got '" + value + "'");
  return *x;
}

// Whole-string integer / number for FLAG; anything else is a usage error naming the flag and the value.
inline int int_flag(const std::string& flag, const std::string& value) {
  const auto x = parse_whole(value, [](const std::string& t, size_t* used) { return std::stoi(t, used); });
  if (!x) throw UsageError(flag + " expects an integer, got '" + value + "'");
  return *x;
}

inline double number_flag(const std::string& flag, const std::string& value) {
  const auto x = parse_whole(value, [](const std::string& t, size_t* used) { return std::stod(t, used); });
  if (!x) throw UsageError(flag + " expects a number, got '" + value + "'");
  // NaN and inf would slip through every range check downstream (NaN compares false).
  if (!std::isfinite(*x)) throw UsageError(flag + " expects a finite number, got '" + value + "'");
  return *x;
}

// -j/--threads N, at most 4096; 0 = the default (OMP_NUM_THREADS, else every core).
inline int threads_flag(const std::string& flag, const std::string& value) {
  const long long n = parse_count_flag(flag, value);
  if (n > 4096) throw UsageError(flag + " is too large, got '" + value + "'");
  return static_cast<int>(n);
}

// Runs an options struct's Check() and re-throws its message as a usage error with the flags the user
// wrote in place of the struct fields it names ({"TriangulatorOptions.min_best_score", "--min-score"}).
template <class Check>
void check_options(Check check, const std::vector<std::pair<std::string, std::string>>& field_flags) {
  try {
    check();
  } catch (const std::invalid_argument& e) {
    std::string message = e.what();
    for (const auto& [field, flag] : field_flags)
      if (const size_t at = message.find(field); at != std::string::npos) message.replace(at, field.size(), flag);
    throw UsageError(message);
  }
}

// The value after the flag at argv[i] (advancing i), or a usage error naming the flag.
inline std::string flag_value(int argc, char** argv, int& i) {
  if (i + 1 >= argc) throw UsageError(std::string(argv[i]) + " needs a value");
  return argv[++i];
}

// The text of --help: the command's usage, then what every command shares.
inline std::string help_text(const Command& c) {
  std::string text = c.usage;
  text += "\nEvery lc2wf command:\n"
          "  --version           print the lc2wf version and the git commit of this build\n"
          "  -h, --help          this text\n";
  if (!c.environment.empty()) {
    text += "\nEnvironment:\n";
    for (const EnvVar& e : c.environment) text += "  " + std::string(e.name) + "  " + e.meaning + "\n";
  }
  text += "\nResults go to stdout, progress and messages to stderr.\n"
          "Exit codes: 0 done, 1 partly failed (some inputs were skipped; each is named on stderr),\n"
          "            2 bad command line, 3 data or I/O error.\n";
  return text;
}

// parse(argc, argv) -> Args (throws UsageError on a bad command line, anything else for missing or bad
// inputs; nothing may be written before it returns); run(const Args&) -> exit code.
template <class Parse, class Run>
int cli_main(const Command& command, int argc, char** argv, Parse parse, Run run) {
  const char* program = command.program;
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    if (flag == "-h" || flag == "--help") {
      std::fputs(help_text(command).c_str(), stdout);
      return kExitDone;
    }
    if (flag == "--version") {
      std::printf("%s %s\n", program, version_line().c_str());
      return kExitDone;
    }
  }
  decltype(parse(argc, argv)) args;
  try {
    args = parse(argc, argv);
  } catch (const UsageError& e) {
    std::fprintf(stderr, "%s: %s\nRun '%s --help' for usage.\n", program, e.what(), program);
    return kExitUsage;
  } catch (const std::exception& e) {  // e.g. an input that does not exist: not a usage error
    std::fprintf(stderr, "%s: error: %s\n", program, e.what());
    return kExitDataError;
  }
  try {
    return run(args);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "\n%s: error: %s\n", program, e.what());
    return kExitDataError;
  }
}

}  // namespace lc2wf
