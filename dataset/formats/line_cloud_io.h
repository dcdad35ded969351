// On-disk line-cloud format (documented in dataset/README.md): a JSON header followed by a binary block of
// little-endian arrays ("LC2WF-LINECLOUD 1 <header bytes>\n" + header + blob), or the same header with the
// arrays inline as plain JSON (human-readable; for small files and hand-written fixtures).
#pragma once

#include <filesystem>
#include <string>

#include "dataset/geometry/line_cloud.h"

namespace lc2wf {

struct LineCloudWriteOptions {
  bool binary = true;  // false: pure JSON with inline arrays
};

// Atomic write; validates first (throws DataError naming the path on an inconsistent cloud).
void write_line_cloud(const std::filesystem::path& path, const LineCloud& cloud, const LineCloudWriteOptions& options = {});
std::string line_cloud_to_bytes(const LineCloud& cloud, const LineCloudWriteOptions& options = {});

// Reads either variant (detected from the first byte) and validates. Throws DataError naming the file.
LineCloud read_line_cloud(const std::filesystem::path& path);
LineCloud line_cloud_from_bytes(const std::string& bytes, const std::string& source_name);

}  // namespace lc2wf
