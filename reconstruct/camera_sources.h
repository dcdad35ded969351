// Where the cameras of a reconstruction come from: a given file (a COLMAP model folder, text or binary,
// matched to the images by file name; or the project's cameras JSON, one entry or null per image in name
// order, unreadable images included) or a COLMAP run on the images (tools/colmap).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "dataset/geometry/geometry.h"
#include "tools/colmap/colmap_poses.h"

namespace lc2wf {

struct CameraSet {
  std::vector<std::optional<Camera>> cameras;  // one per image; empty = not registered
  std::string source;                          // "colmap", "colmap model", "cameras json"
  bool metric_z_up = false;                    // the project's cameras JSON: metres, z up already
  std::vector<std::pair<std::string, double>> step_seconds;  // COLMAP steps when it ran
  bool focal_refined = false;                                 // COLMAP refined the focal lengths
};

// Reads `path` (a folder = COLMAP model, a file = cameras JSON). Throws StageError("cameras", ...) naming
// the file when it cannot be read or its count does not match the images.
// `all_names`: every image file of the folder (the JSON's entries), `images`: the readable ones.
CameraSet cameras_from_file(const std::filesystem::path& path, const std::vector<std::string>& all_names,
                            const std::vector<std::filesystem::path>& images);

// Runs COLMAP with fixed pinhole intrinsics, K[i] for image i, in `workspace` (created; must be ours to delete).
// Throws StageError("cameras", ...) with COLMAP's failing step and log.
CameraSet cameras_from_colmap(const std::vector<std::filesystem::path>& images, const std::vector<Eigen::Matrix3d>& K,
                              const std::filesystem::path& workspace, const ColmapOptions& options);

}  // namespace lc2wf
