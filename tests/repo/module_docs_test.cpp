// Every module README lists the module's libraries and source files, so the docs cannot silently fall
// behind the code. A file counts as listed when the README names it (`file.h`), its stem (`raster_renderer`)
// or a pattern covering it (`ops_*.cpp`).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

std::string read(const fs::path& p) {
  std::ifstream in(p);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// `prefix*suffix` patterns written in backticks.
bool covered_by_pattern(const std::string& readme, const std::string& name) {
  static const std::regex pattern("`([A-Za-z0-9_./-]*)\\*([A-Za-z0-9_.]*)`");
  for (std::sregex_iterator m(readme.begin(), readme.end(), pattern), end; m != end; ++m) {
    const std::string prefix = (*m)[1], suffix = (*m)[2];
    if (name.size() >= prefix.size() + suffix.size() && name.compare(0, prefix.size(), prefix) == 0 &&
        name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0)
      return true;
  }
  return false;
}

void expect_listed(const fs::path& module_dir, bool recursive, const std::vector<std::string>& skip_dirs) {
  const std::string readme = read(module_dir / "README.md");
  ASSERT_FALSE(readme.empty()) << module_dir << " has no README.md";
  std::vector<fs::path> files;
  auto consider = [&](const fs::directory_entry& e) {
    const std::string ext = e.path().extension().string();
    if (e.is_regular_file() && (ext == ".h" || ext == ".cpp")) files.push_back(e.path());
  };
  if (recursive) {
    for (auto it = fs::recursive_directory_iterator(module_dir); it != fs::recursive_directory_iterator(); ++it) {
      if (it->is_directory() && std::find(skip_dirs.begin(), skip_dirs.end(), it->path().filename()) != skip_dirs.end()) {
        it.disable_recursion_pending();
        continue;
      }
      consider(*it);
    }
  } else {
    for (const auto& e : fs::directory_iterator(module_dir)) consider(e);
  }
  for (const fs::path& f : files) {
    const std::string name = f.filename().string(), stem = f.stem().string();
    const bool listed = readme.find(name) != std::string::npos || readme.find("`" + stem) != std::string::npos ||
                        covered_by_pattern(readme, name);
    EXPECT_TRUE(listed) << (module_dir / "README.md") << " does not list " << fs::relative(f, module_dir);
  }
  const std::regex add_library("add_library\\((\\w+)");
  const std::string cmake = read(module_dir / "CMakeLists.txt");
  for (std::sregex_iterator m(cmake.begin(), cmake.end(), add_library), end; m != end; ++m)
    EXPECT_THAT(readme, ::testing::HasSubstr((*m)[1].str())) << (module_dir / "README.md") << " does not name its library";
}

TEST(ModuleDocs, EveryReadmeListsItsFilesAndLibraries) {
  const fs::path root = LC2WF_SOURCE_DIR;
  expect_listed(root / "core", false, {});
  expect_listed(root / "core" / "util", false, {});
  for (const char* module : {"nn", "dataset", "model", "tools", "infer", "reconstruct", "train"}) expect_listed(root / module, true, {});
}

}  // namespace
