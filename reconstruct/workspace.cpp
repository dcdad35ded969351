#include "reconstruct/workspace.h"

#include <algorithm>
#include <cstdlib>
#include <stdexcept>

#include "dataset/atomic_file.h"

namespace lc2wf {

namespace fs = std::filesystem;

Workspace::Workspace(const fs::path& named, bool keep) : keep_(keep) {
  if (named.empty()) {
    std::string pattern = (fs::temp_directory_path() / "lc2wf-reconstruct-XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("cannot create a temporary folder under " + fs::temp_directory_path().string());
    root_ = pattern;
    owned_ = true;
  } else {
    std::error_code ec;
    if (fs::exists(named, ec) && (!fs::is_directory(named, ec) || !fs::is_empty(named, ec)))
      throw std::runtime_error("workspace " + named.string() + " exists and is not an empty folder (it is never cleared)");
    fs::create_directories(named);
    root_ = named;
  }
  fs::create_directories(staging());
}

Workspace::~Workspace() {
  if (!removed_at_exit()) return;
  std::error_code ignored;
  fs::remove_all(root_, ignored);
}

std::vector<std::string> Workspace::publish(const fs::path& out) const {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(staging()))
    if (e.is_regular_file()) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  for (const std::string& n : names) write_file_atomic(out / n, read_file(staging() / n));
  return names;
}

}  // namespace lc2wf
