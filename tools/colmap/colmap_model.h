// COLMAP model folders (cameras + images), text (`cameras.txt`, `images.txt`) or binary (`cameras.bin`,
// `images.bin`), read without running COLMAP. Its pixel origin is the corner of the top-left pixel
// (cx_colmap = cx_opencv + 0.5) and its quaternions are Hamilton (qw qx qy qz) world-to-camera rotations.
// Only pinhole-like models are accepted (PINHOLE, SIMPLE_PINHOLE, and SIMPLE_RADIAL / RADIAL with zero
// distortion). Every error is a DataError naming the file and the line (text) or byte offset (binary).
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "dataset/geometry/geometry.h"

namespace lc2wf {

Eigen::Matrix3d quaternion_to_rotation(double qw, double qx, double qy, double qz);
Eigen::Vector4d rotation_to_quaternion(const Eigen::Matrix3d& R);  // (qw, qx, qy, qz), qw >= 0

struct ColmapImage {
  std::string name;
  Camera camera;
};

// Intrinsics by COLMAP camera id, in our pixel convention.
struct ColmapIntrinsics {
  Eigen::Matrix3d K = Eigen::Matrix3d::Identity();
  int width = 0, height = 0;
};
using ColmapCameras = std::map<long long, ColmapIntrinsics>;

// One file each; `source` names it in errors. Images refer to cameras by id (an unknown id is an error).
ColmapCameras parse_colmap_cameras_txt(const std::string& text, const std::string& source);
std::vector<ColmapImage> parse_colmap_images_txt(const std::string& text, const std::string& source, const ColmapCameras& cameras);
ColmapCameras parse_colmap_cameras_bin(std::string_view bytes, const std::string& source);
std::vector<ColmapImage> parse_colmap_images_bin(std::string_view bytes, const std::string& source, const ColmapCameras& cameras);

// Reads `dir`: the text model when cameras.txt is there, otherwise the binary one.
std::vector<ColmapImage> read_colmap_model(const std::filesystem::path& dir);
std::vector<ColmapImage> read_colmap_text_model(const std::filesystem::path& dir);

}  // namespace lc2wf
