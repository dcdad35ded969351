// Atomic file writes: write to a temporary file in the same folder, flush, then rename over the target,
// so a killed process never leaves a truncated checkpoint or dataset file behind.
#pragma once

#include <atomic>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <unistd.h>

namespace lc2wf {

// Calls write(stream) on a temporary sibling of `path`, then renames it to `path`. A `path` that is a folder,
// FIFO, socket or device is refused: it is never replaced.
inline void write_file_atomically(const std::filesystem::path& path,
                                  const std::function<void(std::ostream&)>& write,
                                  std::ios::openmode mode = std::ios::binary) {
  namespace fs = std::filesystem;
  if (path.has_parent_path()) fs::create_directories(path.parent_path());
  // The rename below replaces whatever has the name: as root, `-o /dev/null` turned the device into a file.
  std::error_code type_ec;
  const fs::file_type existing = fs::symlink_status(path, type_ec).type();
  if (existing == fs::file_type::directory)
    throw std::runtime_error(path.string() + ": is a directory, not replaced by a file");
  if (existing != fs::file_type::not_found && existing != fs::file_type::none && existing != fs::file_type::regular &&
      existing != fs::file_type::symlink)
    throw std::runtime_error(path.string() + ": is not a regular file (a FIFO, socket or device), not replaced");
  // Unique per process and call, so threads writing different files never share a temporary name.
  static std::atomic<unsigned> counter{0};
  // The target's name is cut so the temporary name stays within the 255-byte NAME_MAX of a long target name.
  const std::string suffix = ".tmp." + std::to_string(::getpid()) + "." + std::to_string(counter++);
  const fs::path tmp = path.parent_path() / (path.filename().string().substr(0, 255 - 1 - suffix.size()) + suffix);
  {
    std::ofstream out(tmp, mode | std::ios::out | std::ios::trunc);
    if (!out) throw std::runtime_error("cannot open " + tmp.string() + " for writing");
    write(out);
    out.flush();
    if (!out) {
      out.close();
      std::error_code ignored;
      fs::remove(tmp, ignored);
      throw std::runtime_error("failed writing " + tmp.string() + " (disk full?)");
    }
  }
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) {
    std::error_code ignored;
    fs::remove(tmp, ignored);
    throw std::runtime_error("cannot rename " + tmp.string() + " to " + path.string() + ": " + ec.message());
  }
}

inline void write_file_atomic(const std::filesystem::path& path, std::string_view bytes) {
  write_file_atomically(path, [&](std::ostream& out) { out.write(bytes.data(), static_cast<std::streamsize>(bytes.size())); });
}

inline void write_text_atomically(const std::filesystem::path& path, const std::string& text) {
  write_file_atomic(path, text);
}

}  // namespace lc2wf
