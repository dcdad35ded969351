// Shared helpers for the dataset tests.
#pragma once

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>

namespace lc2wf::test {

// The shared data folder: $LC2WF_DATA_DIR, else the compile-time default next to the repository.
inline std::filesystem::path shared_data_dir() {
  if (const char* env = std::getenv("LC2WF_DATA_DIR"); env && *env) return env;
  return LC2WF_SHARED_DATA_DIR;
}

// A fresh, empty scratch folder per test.
inline std::filesystem::path scratch_dir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("lc2wf_dataset_test_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace lc2wf::test
