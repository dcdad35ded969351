#include "dataset/formats/cloud_input.h"

#include <algorithm>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "dataset/formats/read_file.h"
#include "dataset/formats/errors.h"
#include "dataset/formats/limap_io.h"
#include "dataset/formats/line3dpp_io.h"
#include "dataset/formats/line_cloud_io.h"
#include "dataset/formats/line_obj_io.h"
#include "dataset/formats/release_json.h"

namespace lc2wf {

namespace fs = std::filesystem;

CloudFormat parse_cloud_format(const std::string& text, const std::string& what) {
  if (text == "auto") return CloudFormat::kAuto;
  if (text == "lc2wf") return CloudFormat::kLc2wf;
  if (text == "release") return CloudFormat::kRelease;
  if (text == "line3dpp") return CloudFormat::kLine3dpp;
  if (text == "limap") return CloudFormat::kLimap;
  if (text == "obj") return CloudFormat::kLineObj;
  throw std::invalid_argument(what + " must be auto, lc2wf, release, line3dpp, limap or obj, got \"" + text + "\"");
}

namespace {

// Clouds made by other programs: frame and units as in the file, no supports, no ground truth.
LineCloud load_external_cloud(const fs::path& path, CloudFormat format) {
  if (format == CloudFormat::kAuto)
    format = fs::is_directory(path) ? CloudFormat::kLimap : path.extension() == ".obj" ? CloudFormat::kLineObj : CloudFormat::kLine3dpp;
  const ExternalLineMap map = format == CloudFormat::kLimap      ? read_limap_tracks(path)
                              : format == CloudFormat::kLineObj ? read_line_obj(path)
                                                                : read_line3dpp_txt(path);
  return to_line_cloud(map, path.stem().string(), path.string());
}

}  // namespace

LineCloud load_line_cloud(const fs::path& path, CloudFormat format, double raw_per_metre) {
  const bool external = format == CloudFormat::kLine3dpp || format == CloudFormat::kLimap || format == CloudFormat::kLineObj;
  if (external || (format == CloudFormat::kAuto && (fs::is_directory(path) || path.extension() == ".obj")))
    return load_external_cloud(path, format);
  const std::string bytes = read_file(path);  // regular files only: a FIFO or /dev/zero never ends
  if (format == CloudFormat::kAuto && looks_like_line3dpp_txt(bytes))
    return to_line_cloud(parse_line3dpp_txt(bytes, path.string()), path.stem().string(), path.string());
  if (format == CloudFormat::kAuto) {
    // Both formats may start with '{'; only the release's JSON has `junc3DList` without our format tag.
    const bool release = bytes.find("\"junc3DList\"") != std::string::npos &&
                         bytes.find("\"lc2wf-linecloud\"") == std::string::npos;
    format = release ? CloudFormat::kRelease : CloudFormat::kLc2wf;
  }
  LineCloud cloud;
  if (format == CloudFormat::kRelease) {
    ReleaseJsonOptions options;
    options.raw_per_metre = raw_per_metre;
    cloud = parse_release_line_cloud(bytes, path.string(), options);
  } else {
    cloud = line_cloud_from_bytes(bytes, path.string());
  }
  if (cloud.name.empty()) cloud.name = path.stem().string();
  return cloud;
}

std::optional<fs::path> find_cloud_file_if_any(const fs::path& dir, const std::string& name) {
  std::vector<fs::path> hits;
  std::error_code ec, type_ec;
  // Not only regular files: a FIFO or device under the name is then refused by the reader, naming it.
  std::vector<fs::path> folders;  // e.g. a folder named b.lcloud: named when no file stands for the building
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    if (entry.path().stem() != name) continue;
    if (!entry.is_directory(type_ec) || is_limap_tracks_dir(entry.path())) hits.push_back(entry.path());
    else if (entry.path().has_extension()) folders.push_back(entry.path());
  }
  if (ec) throw DataError(dir.string(), "cannot list folder: " + ec.message());
  if (hits.empty() && !folders.empty())
    throw DataError(std::min_element(folders.begin(), folders.end())->string(), "is a folder, not a line-cloud file (nor LIMAP tracks)");
  std::sort(hits.begin(), hits.end());
  if (hits.size() > 1)
    throw DataError(dir.string(), "building '" + name + "' has several files (" + hits[0].filename().string() + ", " +
                                      hits[1].filename().string() + "); keep one line cloud per building");
  if (hits.empty()) return std::nullopt;
  return hits[0];
}

fs::path find_cloud_file(const fs::path& dir, const std::string& name) {
  if (auto path = find_cloud_file_if_any(dir, name)) return *path;
  throw DataError(dir.string(), "no line-cloud file for building '" + name + "'");
}

}  // namespace lc2wf
