#include "core/util/workspace.h"

#include <algorithm>
#include <cstdlib>
#include <stdexcept>

#include "core/util/atomic_file.h"
#include "core/util/input_file.h"

namespace lc2wf {

namespace fs = std::filesystem;

Workspace::Workspace(const fs::path& named, bool keep) : keep_(keep) {
  if (named.empty()) {
    std::string pattern = (fs::temp_directory_path() / "lc2wf-XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("cannot create a temporary folder under " + fs::temp_directory_path().string());
    root_ = pattern;
    owned_ = true;
  } else {
    std::error_code ec;
    const bool exists = fs::exists(named, ec);
    if (exists && !fs::is_directory(named, ec)) throw std::runtime_error("workspace " + named.string() + " is not a folder");
    if (exists && !fs::is_empty(named, ec) && !fs::exists(named / kMarker, ec))
      throw std::runtime_error("workspace " + named.string() + " is not empty and was not made by lc2wf (no " + kMarker +
                               "); name a new or empty folder: a workspace is never cleared");
    fs::create_directories(named);
    write_text_atomically(named / kMarker, "A workspace of lc2wf: the next lc2wf run given this folder may replace what it wrote here.\n");
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
  for (const std::string& n : names) write_file_atomic(out / n, read_input_file(staging() / n));
  return names;
}

}  // namespace lc2wf
