// Input files are read only when they are regular files of bounded size: a FIFO blocks open() forever and
// /dev/zero or a device is read until memory runs out. Header-only, like atomic_file.h.
#pragma once

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

namespace lc2wf {

// Far above any real cloud, mesh, config or checkpoint; a bound on what one read may allocate.
inline constexpr std::uintmax_t kMaxInputFileBytes = std::uintmax_t{4} << 30;

// Empty when `path` is a regular file of at most max_bytes (or does not exist: opening it then reports
// that), otherwise why it must not be opened. Checked before opening, since opening a FIFO blocks.
inline std::string input_file_problem(const std::filesystem::path& path, std::uintmax_t max_bytes = kMaxInputFileBytes) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (ec || status.type() == fs::file_type::not_found) return {};
  if (status.type() == fs::file_type::directory) return "is a directory, not a file";
  if (status.type() != fs::file_type::regular) return "is not a regular file (a FIFO, socket or device)";
  const std::uintmax_t size = fs::file_size(path, ec);
  if (!ec && size > max_bytes)
    return "is " + std::to_string(size) + " bytes, more than the " + std::to_string(max_bytes) + "-byte limit";
  return {};
}

// The whole file; throws std::runtime_error "PATH: problem" for anything but a readable regular file.
inline std::string read_input_file(const std::filesystem::path& path, std::uintmax_t max_bytes = kMaxInputFileBytes) {
  if (const std::string problem = input_file_problem(path, max_bytes); !problem.empty())
    throw std::runtime_error(path.string() + ": " + problem);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path.string() + ": cannot open file: " + std::strerror(errno));
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace lc2wf
