// Reading the line clouds the networks run on: our line-cloud files (dataset/line_cloud_io.h) or the
// paper release's LineCloud JSON (dataset/release_json.h), chosen by name or detected from the content.
#pragma once

#include <filesystem>
#include <string>

#include "dataset/line_cloud.h"

namespace lc2wf {

enum class CloudFormat { kAuto, kLc2wf, kRelease };

// "auto", "lc2wf" or "release"; throws std::invalid_argument naming `what` otherwise.
CloudFormat parse_cloud_format(const std::string& text, const std::string& what);

// Reads one building; the name defaults to the file stem. `raw_per_metre` applies to release JSON only.
// Throws DataError naming the file.
LineCloud load_line_cloud(const std::filesystem::path& path, CloudFormat format, double raw_per_metre = 20.0);

// The file holding building `name` in `dir`: the single regular file whose stem is `name`. Throws DataError
// when there is none or more than one.
std::filesystem::path find_cloud_file(const std::filesystem::path& dir, const std::string& name);

}  // namespace lc2wf
