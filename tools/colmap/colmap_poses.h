// Camera poses from images with COLMAP 3.8 (CPU SIFT, our exact matching of the SIFT descriptors, COLMAP's
// geometric verification and mapper with fixed known intrinsics), for users with real photos. Its models are read by tools/colmap/colmap_model.h.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "dataset/geometry/geometry.h"
#include "tools/colmap/colmap_model.h"  // ColmapImage, read_colmap_model, quaternions

namespace lc2wf {

struct PoseComparison {
  int reference = 0;       // views in the reference
  int registered = 0;      // views COLMAP placed
  int inliers = 0;         // registered views the final similarity was fitted to
  double scale = 1.0;      // similarity X_ref = scale * rotation * X_est + translation that maps the estimated
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // centres onto the reference ones
  Vec3 translation = Vec3::Zero();
  double median_centre_error = 0, max_centre_error = 0;  // reference units, after alignment
  double median_rotation_deg = 0, max_rotation_deg = 0;
  double camera_distance = 0;  // median distance from a reference camera to the point its axes aim at
  std::vector<double> centre_error, rotation_deg;  // per view; NaN when not registered
};

struct AlignOptions {
  // Views whose centre error exceeds this multiple of the median (and 1% of the camera distance) are
  // left out of the next fit: one view SfM placed on the wrong side of a symmetric house must not
  // drag the similarity for all others. 0 fits every registered view once.
  double outlier_factor = 0;
  int rounds = 3;
  void Check() const;
};

// Aligns the estimated cameras to the reference ones (Umeyama similarity over views present in both, of
// their centres and of points along their optical and image-down axes, so that cameras on one line still
// fix the turn about it), rewrites the estimated cameras into the reference frame and measures the errors. Needs at least
// 3 registered views; throws std::invalid_argument otherwise.
PoseComparison align_to_reference(const std::vector<Camera>& reference, std::vector<std::optional<Camera>>& estimated,
                                  const AlignOptions& options = {});

// Least-squares point closest to every camera's optical axis (the point a ring of cameras looks at).
Vec3 common_aim_point(const std::vector<Camera>& cameras);

struct ColmapOptions {
  std::string executable = "colmap";
  int max_features = 4000;
  // SIFT's first octave: -1 (COLMAP's default) doubles the image first, 0 starts at its own size: 4x less
  // extraction time and fewer small features, enough for 20 views around a building, not for a 10-view ring.
  // Unset: -1 for photos within max_image_size, 0 for larger ones (SIFT scales them down first, and doubling
  // would only undo that at about 3x the time: 52 s instead of 18 s for 20 photos of 12 MP).
  std::optional<int> first_octave;
  // SIFT runs on the image scaled down to at most this many pixels on its longer side (COLMAP's
  // SiftExtraction.max_image_size; its keypoints come back in full-size pixels). COLMAP's own default, 3200,
  // spends 167 s on 20 photos of 12 MP on 2 cores; a building needs far fewer pixels to be registered.
  int max_image_size = 1600;
  std::string matcher = "exhaustive";  // image pairs matched: all, or "sequential": only views close in name order
  int sequential_overlap = 10;         // sequential: each view is matched with this many next ones
  int init_min_inliers = 100;          // mapper: verified matches of the initial pair (COLMAP's default)
  int abs_pose_min_inliers = 30;       // mapper: 2D-3D inliers to register a view (COLMAP's default)
  // Bundle adjustment also refines each camera's focal length (the principal point stays): for photos whose
  // focal length is a guess. Known intrinsics stay fixed, which registers more reliably; when the mapper
  // finds no model with free focal lengths it runs once more with them fixed (ColmapRun::focal_refined).
  bool refine_focal_length = false;
  int threads = 0;                     // every COLMAP stage; 0 = all cores
  void Check() const;
};

// The first octave SIFT runs with on photos whose longer side is `longer_side` pixels (ColmapOptions::first_octave).
int sift_first_octave(const ColmapOptions& options, int longer_side);

struct ColmapRun {
  std::vector<std::optional<Camera>> cameras;  // one per image (empty when not registered), COLMAP's frame
  std::vector<std::pair<std::string, double>> step_seconds;  // wall time of each COLMAP command
  bool focal_refined = false;  // refine_focal_length asked and the mapper succeeded with it (else fixed focal lengths)
};

// Runs feature_extractor, our matcher (tools/colmap/sift_matching.h), matches_importer, mapper and model_converter in `workspace` on `images`
// with their intrinsics, fixed during mapping: `K[i]` is image i's. Images of equal intrinsics share one COLMAP
// camera, so photos taken upright and sideways (or cropped) are registered together. `workspace` belongs to
// the caller (core/util/workspace.h): only what a previous call wrote there (images/, database.db, matches.txt,
// image_list_*.txt, sparse/, model_txt_*, colmap.log) is replaced. The mapper may build several models; the one
// with the most registered images is used. Throws std::invalid_argument when K and images differ in number,
// std::runtime_error naming the failing step and its log.
ColmapRun estimate_poses_with_colmap(const std::vector<std::filesystem::path>& images, const std::vector<Eigen::Matrix3d>& K,
                                     const std::filesystem::path& workspace, const ColmapOptions& options);

// Every image with the same intrinsics K (one camera).
inline ColmapRun estimate_poses_with_colmap(const std::vector<std::filesystem::path>& images, const Eigen::Matrix3d& K,
                                            const std::filesystem::path& workspace, const ColmapOptions& options) {
  return estimate_poses_with_colmap(images, std::vector<Eigen::Matrix3d>(images.size(), K), workspace, options);
}

}  // namespace lc2wf
