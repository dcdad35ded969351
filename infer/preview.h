// A quick look at one result: the line cloud (grey), the ground truth (green, when known) and the
// predicted wireframe (red) drawn from an oblique view with OpenCV's drawing, written as a PNG (png_file.h).
#pragma once

#include <filesystem>

#include "dataset/geometry/geometry.h"
#include "dataset/geometry/line_cloud.h"

namespace lc2wf {

struct PreviewOptions {
  int width = 960;
  int height = 720;
  double azimuth_deg = 35.0;    // viewing direction around the vertical axis
  double elevation_deg = 30.0;  // viewing angle above the horizon
  // The frame fits the wireframes and the cloud's segment ends between this quantile and its complement
  // on each screen axis, so a few outliers far off do not shrink the building (0 = every end).
  double cloud_frame_quantile = 0.01;
  void Check() const;           // throws std::invalid_argument naming the bad field
};

// Orthographic oblique projection fitted to the wireframes and the bulk of the cloud (cloud_frame_quantile).
// `gt` may be null. Written atomically; throws std::runtime_error naming the file when it cannot be written.
void write_preview(const std::filesystem::path& png, const LineCloud& cloud, const Wireframe& prediction,
                   const Wireframe* gt, const PreviewOptions& options = {});

}  // namespace lc2wf
