// The modules follow the data flow (top-level CMakeLists.txt): no module includes a header of a module
// above it. core/util is the bottom (it includes no other lc2wf module), dataset does not use the tensor
// engine, tools and infer do not know each other, and train reads its data through dataset, never infer.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <string>

namespace {

namespace fs = std::filesystem;

// The lc2wf modules each module may include (besides itself).
const std::map<std::string, std::set<std::string>> kMayInclude = {
    {"core/util", {}},
    {"core", {"core/util"}},
    {"nn", {"core/util", "core"}},
    {"dataset", {"core/util"}},
    {"tools", {"core/util", "dataset"}},
    {"infer", {"core/util", "core", "nn", "dataset"}},
    {"reconstruct", {"core/util", "core", "nn", "dataset", "tools", "infer"}},
    {"train", {"core/util", "core", "nn", "dataset", "infer"}},
};

// The module an include path belongs to ("core/util/cli.h" -> "core/util", "infer/x.h" -> "infer").
std::string module_of(const std::string& include) {
  if (include.rfind("core/util/", 0) == 0) return "core/util";
  const size_t slash = include.find('/');
  return slash == std::string::npos ? "" : include.substr(0, slash);
}

std::string module_of_file(const fs::path& relative) {
  const std::string s = relative.generic_string();
  return module_of(s);
}

TEST(Layering, NoModuleIncludesAModuleAboveIt) {
  const fs::path root = LC2WF_SOURCE_DIR;
  const std::regex include_line("^\\s*#\\s*include\\s+\"([^\"]+)\"");
  int files = 0;
  for (const auto& [module, allowed] : kMayInclude) {
    for (const auto& entry : fs::recursive_directory_iterator(root / module)) {
      const fs::path rel = fs::relative(entry.path(), root);
      if (module_of_file(rel) != module) continue;  // core/util files are checked as core/util, not core
      if (rel.extension() != ".h" && rel.extension() != ".cpp") continue;
      ++files;
      std::ifstream in(entry.path());
      int line_no = 0;
      for (std::string line; std::getline(in, line);) {
        ++line_no;
        std::smatch m;
        if (!std::regex_search(line, m, include_line)) continue;
        const std::string target = module_of(m[1]);
        if (!kMayInclude.count(target) || target == module) continue;  // generated or same-module headers
        EXPECT_TRUE(allowed.count(target)) << rel.string() << ":" << line_no << " includes " << m[1] << ", but " << module
                                           << " sits below " << target << " in the data flow";
      }
    }
  }
  EXPECT_GT(files, 100);
}

// train/ uses infer/ for the networks' inputs, validation metrics and inference, never to read its data:
// line clouds and split lists come from dataset/ (cloud_input.h, splits.h).
TEST(Layering, TrainReadsItsDataThroughDataset) {
  const std::set<std::string> data_readers = {"infer/eval_inputs.h", "infer/batch_inference.h", "infer/prediction_io.h"};
  const std::regex include_line("^\\s*#\\s*include\\s+\"([^\"]+)\"");
  for (const auto& entry : fs::directory_iterator(fs::path(LC2WF_SOURCE_DIR) / "train")) {
    std::ifstream in(entry.path());
    for (std::string line; std::getline(in, line);) {
      std::smatch m;
      if (std::regex_search(line, m, include_line))
        EXPECT_FALSE(data_readers.count(m[1])) << entry.path().filename() << " reads data through " << m[1];
    }
  }
}

}  // namespace
