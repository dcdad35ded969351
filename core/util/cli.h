// The shared shape of lc2wf's command-line programs: --help anywhere prints the usage and exits 0, a
// UsageError exits 2 with a pointer to --help, any other exception (while parsing or running) exits 1
// naming the program.
#pragma once

#include <cmath>
#include <cstdio>
#include <optional>
#include <stdexcept>
#include <string>

#include "core/util/version.h"

namespace lc2wf {

struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

constexpr int kExitFailure = 1;
constexpr int kExitUsage = 2;

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

// The value after the flag at argv[i] (advancing i), or a usage error naming the flag.
inline std::string flag_value(int argc, char** argv, int& i) {
  if (i + 1 >= argc) throw UsageError(std::string(argv[i]) + " needs a value");
  return argv[++i];
}

// parse(argc, argv) -> Args (throws UsageError on a bad command line); run(const Args&) -> exit code.
template <class Parse, class Run>
int cli_main(const char* program, const char* usage, int argc, char** argv, Parse parse, Run run) {
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    if (flag == "-h" || flag == "--help") {
      std::fputs(usage, stdout);
      return 0;
    }
    if (flag == "--version") {
      std::printf("%s %s\n", program, version_line().c_str());
      return 0;
    }
  }
  decltype(parse(argc, argv)) args;
  try {
    args = parse(argc, argv);
  } catch (const UsageError& e) {
    std::fprintf(stderr, "%s: %s\nRun '%s --help' for usage.\n", program, e.what(), program);
    return kExitUsage;
  } catch (const std::exception& e) {  // e.g. an output folder that cannot be created: not a usage error
    std::fprintf(stderr, "%s: error: %s\n", program, e.what());
    return kExitFailure;
  }
  try {
    return run(args);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "\n%s: error: %s\n", program, e.what());
    return kExitFailure;
  }
}

}  // namespace lc2wf
