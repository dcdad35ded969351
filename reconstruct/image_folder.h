// The photos of one reconstruction: every *.png / *.jpg / *.jpeg of a folder in name order, read as
// 8-bit gray. Unreadable files are listed and skipped; all readable images must share one size (one
// camera, as COLMAP is run with a single shared intrinsics).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace lc2wf {

struct ImageFolder {
  std::vector<std::string> all_names;        // every image file found, name order (readable or not)
  std::vector<std::filesystem::path> paths;  // readable images, name order
  std::vector<cv::Mat> images;               // 8-bit gray, one per path
  std::vector<std::string> unreadable;       // file names that failed to decode, or "NAME (not a regular file)"
  int width = 0, height = 0;
};

// Throws StageError("images", ...) when the folder cannot be listed, holds fewer than `min_images`
// readable images (naming the unreadable ones), or images of different sizes (naming them).
ImageFolder read_image_folder(const std::filesystem::path& dir, int min_images);

}  // namespace lc2wf
