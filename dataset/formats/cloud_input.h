// Reading a building's line cloud in any format the project knows: our line-cloud files (line_cloud_io.h),
// the paper release's LineCloud JSON (release_json.h), Line3D++ `.txt`, LIMAP `finaltracks/` and line OBJ
// files (line3dpp_io.h, limap_io.h, line_obj_io.h), chosen by name or detected; and finding a building's
// file in a folder. lc2wf-train, lc2wf-infer and lc2wf-eval all read clouds through here.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "dataset/geometry/geometry.h"
#include "dataset/geometry/line_cloud.h"

namespace lc2wf {

enum class CloudFormat { kAuto, kLc2wf, kRelease, kLine3dpp, kLimap, kLineObj };

// "auto", "lc2wf", "release", "line3dpp", "limap" or "obj"; throws std::invalid_argument naming `what` otherwise.
CloudFormat parse_cloud_format(const std::string& text, const std::string& what);

// Reads one building; the name defaults to the file stem. `raw_per_metre` applies to release JSON only.
// Auto-detection: a folder is LIMAP, `.obj` a line OBJ, a `.txt` whose first line parses as a Line3D++
// line is Line3D++, anything else ours or the release's JSON. Throws DataError naming the file.
LineCloud load_line_cloud(const std::filesystem::path& path, CloudFormat format, double raw_per_metre = kRawUnitsPerMetre);

// The file holding building `name` in `dir`: the single regular file (or LIMAP tracks folder) whose stem is
// `name`; nullopt when there is none. Throws DataError when there are several or `dir` cannot be listed.
std::optional<std::filesystem::path> find_cloud_file_if_any(const std::filesystem::path& dir, const std::string& name);
// The same, but a missing file is a DataError too.
std::filesystem::path find_cloud_file(const std::filesystem::path& dir, const std::string& name);

}  // namespace lc2wf
