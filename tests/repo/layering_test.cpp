// The modules follow the data flow (top-level CMakeLists.txt): no module includes a header of a module
// above it. core/util is the bottom (it includes no other lc2wf module), dataset does not use the tensor
// engine, tools and infer do not know each other, and train and infer share the model layer, never each other.
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
    {"model", {"core/util", "core", "nn", "dataset"}},
    {"tools", {"core/util", "dataset"}},
    {"infer", {"core/util", "core", "nn", "dataset", "model"}},
    {"reconstruct", {"core/util", "core", "nn", "dataset", "model", "tools", "infer"}},
    {"train", {"core/util", "core", "nn", "dataset", "model"}},
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

// dataset/ is the widest module: its sources live in one sub-folder per job (formats, geometry, labels,
// sampling, selection, synthetic, photo, splits, cli), so none grows into a catch-all at the top.
TEST(Layering, DatasetSourcesLiveInSubfoldersByJob) {
  int files = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(LC2WF_SOURCE_DIR) / "dataset")) {
    const std::string ext = entry.path().extension().string();
    EXPECT_FALSE(entry.is_regular_file() && (ext == ".h" || ext == ".cpp"))
        << "dataset/" << entry.path().filename().string() << " belongs in a sub-folder of dataset/";
    if (entry.is_directory()) ++files;
  }
  EXPECT_GE(files, 5);
}

}  // namespace
