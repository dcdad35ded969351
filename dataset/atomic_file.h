// Atomic whole-file writes: readers never see a half-written file.
#pragma once

#include <filesystem>
#include <string_view>

namespace lc2wf {

// Writes `bytes` to a temporary sibling of `path` and renames it over `path`. Throws std::runtime_error
// naming the path on failure.
void write_file_atomic(const std::filesystem::path& path, std::string_view bytes);

// Reads a whole file; throws DataError naming the path when it cannot be opened.
std::string read_file(const std::filesystem::path& path);

}  // namespace lc2wf
