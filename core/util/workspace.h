// The scratch folder of a command that runs other programs (COLMAP) or stages its outputs: a private
// temporary folder, removed at the end unless kept, or a folder the user named. A named folder is used
// only when it is new or empty, or when an earlier lc2wf run made it (it holds the marker file
// `.lc2wf-workspace`); any other folder is refused, so a photo folder passed by mistake is never touched,
// and a named workspace is never deleted.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace lc2wf {

class Workspace {
 public:
  static constexpr const char* kMarker = ".lc2wf-workspace";

  // `named` empty: a fresh folder under the system temporary folder (removed unless `keep`).
  // Throws std::runtime_error when `named` is refused (see above) or a folder cannot be created.
  Workspace(const std::filesystem::path& named, bool keep);
  ~Workspace();
  Workspace(const Workspace&) = delete;
  Workspace& operator=(const Workspace&) = delete;

  const std::filesystem::path& root() const { return root_; }
  std::filesystem::path staging() const { return root_ / "out"; }
  bool removed_at_exit() const { return owned_ && !keep_; }
  // Keeps a private folder after all (e.g. to show a failed run's logs).
  void keep() { keep_ = true; }

  // Copies every staged file into `out` (created when missing), each written atomically; returns the
  // names copied. Other files already in `out` are left alone.
  std::vector<std::string> publish(const std::filesystem::path& out) const;

 private:
  std::filesystem::path root_;
  bool owned_ = false;  // created by us under the temporary folder
  bool keep_ = false;
};

}  // namespace lc2wf
