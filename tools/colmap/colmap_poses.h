// Camera poses from images with COLMAP 3.8 (CPU SIFT, exhaustive matching, mapper with fixed known
// intrinsics), for users with real photos. COLMAP's text model is converted to our cameras: its pixel
// origin is the corner of the top-left pixel (cx_colmap = cx_opencv + 0.5) and its quaternions are
// Hamilton (qw qx qy qz) world-to-camera rotations.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "dataset/geometry.h"

namespace lc2wf {

Eigen::Matrix3d quaternion_to_rotation(double qw, double qx, double qy, double qz);
Eigen::Vector4d rotation_to_quaternion(const Eigen::Matrix3d& R);  // (qw, qx, qy, qz), qw >= 0

struct ColmapImage {
  std::string name;
  Camera camera;
};

// Reads cameras.txt and images.txt of a COLMAP text model (PINHOLE, SIMPLE_PINHOLE, SIMPLE_RADIAL and
// RADIAL are accepted; distortion must be zero). Throws DataError naming the file and line.
std::vector<ColmapImage> read_colmap_text_model(const std::filesystem::path& dir);

struct PoseComparison {
  int reference = 0;       // views in the reference
  int registered = 0;      // views COLMAP placed
  double scale = 1.0;      // similarity that maps the estimated centres onto the reference ones
  double median_centre_error = 0, max_centre_error = 0;  // reference units, after alignment
  double median_rotation_deg = 0, max_rotation_deg = 0;
};

// Aligns the estimated camera centres to the reference ones (Umeyama similarity over views present in
// both), rewrites the estimated cameras into the reference frame and measures the errors. Needs at least
// 3 registered views; throws std::invalid_argument otherwise.
PoseComparison align_to_reference(const std::vector<Camera>& reference, std::vector<std::optional<Camera>>& estimated);

struct ColmapOptions {
  std::string executable = "colmap";
  int max_features = 4000;
  void Check() const;
};

// Runs feature_extractor, exhaustive_matcher, mapper and model_converter in `workspace` on `images`
// (one camera: intrinsics K, fixed during mapping). Returns one optional camera per image (empty when not
// registered), in COLMAP's own frame. Throws std::runtime_error naming the failing step and its log.
std::vector<std::optional<Camera>> estimate_poses_with_colmap(const std::vector<std::filesystem::path>& images,
                                                              const Eigen::Matrix3d& K, int width, int height,
                                                              const std::filesystem::path& workspace, const ColmapOptions& options);

}  // namespace lc2wf
