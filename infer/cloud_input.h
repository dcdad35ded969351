// Reading the line clouds the networks run on: our line-cloud files (dataset/line_cloud_io.h), the
// paper release's LineCloud JSON (dataset/release_json.h), Line3D++ `.txt`, LIMAP `finaltracks/` and
// line OBJ files (dataset/line3dpp_io.h, limap_io.h, line_obj_io.h), chosen by name or detected.
#pragma once

#include <filesystem>
#include <string>

#include "dataset/line_cloud.h"

namespace lc2wf {

enum class CloudFormat { kAuto, kLc2wf, kRelease, kLine3dpp, kLimap, kLineObj };

// "auto", "lc2wf", "release", "line3dpp", "limap" or "obj"; throws std::invalid_argument naming `what` otherwise.
CloudFormat parse_cloud_format(const std::string& text, const std::string& what);

// Reads one building; the name defaults to the file stem. `raw_per_metre` applies to release JSON only.
// Auto-detection: a folder is LIMAP, `.obj` a line OBJ, a `.txt` whose first line parses as a Line3D++
// line is Line3D++, anything else ours or the release's JSON. Throws DataError naming the file.
LineCloud load_line_cloud(const std::filesystem::path& path, CloudFormat format, double raw_per_metre = 20.0);

// The file holding building `name` in `dir`: the single regular file (or LIMAP tracks folder) whose stem is `name`. Throws DataError
// when there is none or more than one.
std::filesystem::path find_cloud_file(const std::filesystem::path& dir, const std::string& name);

}  // namespace lc2wf
