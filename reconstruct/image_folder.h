// The photos of one reconstruction: every *.png / *.jpg / *.jpeg / *.tif / *.tiff / *.bmp of a folder in name
// order, read as 8-bit gray with their pixels as stored (an EXIF orientation is not applied: COLMAP 3.8 ignores
// it, and the lines must be found in the pixels its cameras were estimated for). Unreadable files are listed
// and skipped, HEIC/HEIF and camera raw files named as not read; sizes may differ (upright and sideways photos,
// crops: one camera per size).
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
  std::vector<std::string> unsupported;      // HEIC/HEIF and camera raw files: photos, but not read (name order)
  std::vector<cv::Size> sizes;               // one per path
};

// The sentence that names unsupported photos and what to do with them.
std::string unsupported_text(const std::vector<std::string>& names);

// "3072x2048", or "19 of 3072x2048, 6 of 2048x3072" (most frequent first; three named, then "and N more sizes").
std::string describe_sizes(const std::vector<cv::Size>& sizes);

// Throws StageError("images", ...) when the folder cannot be listed, holds fewer than `min_images`
// readable images (naming the unreadable ones).
ImageFolder read_image_folder(const std::filesystem::path& dir, int min_images);

}  // namespace lc2wf
