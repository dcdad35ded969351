// The intermediate folder of one reconstruction (COLMAP database, staged outputs): a private temporary
// folder removed at the end unless kept, or a folder the user named, which must be new or empty and is
// never removed. Outputs are staged in `staging()` and copied into OUT only when every stage succeeded.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace lc2wf {

class Workspace {
 public:
  // `named` empty: a fresh folder under the system temporary folder (removed unless `keep`).
  // Throws std::runtime_error when `named` exists and is not an empty folder, or creation fails.
  Workspace(const std::filesystem::path& named, bool keep);
  ~Workspace();
  Workspace(const Workspace&) = delete;
  Workspace& operator=(const Workspace&) = delete;

  const std::filesystem::path& root() const { return root_; }
  std::filesystem::path staging() const { return root_ / "out"; }
  bool removed_at_exit() const { return owned_ && !keep_; }

  // Copies every staged file into `out` (created when missing), each written atomically; returns the
  // names copied. Other files already in `out` are left alone.
  std::vector<std::string> publish(const std::filesystem::path& out) const;

 private:
  std::filesystem::path root_;
  bool owned_ = false;  // created by us under the temporary folder
  bool keep_ = false;
};

}  // namespace lc2wf
