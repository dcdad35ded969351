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
  void Check() const;           // throws std::invalid_argument naming the bad field
};

// Orthographic oblique projection fitted to everything drawn. `gt` may be null. Written atomically;
// throws std::runtime_error naming the file when it cannot be written.
void write_preview(const std::filesystem::path& png, const LineCloud& cloud, const Wireframe& prediction,
                   const Wireframe* gt, const PreviewOptions& options = {});

}  // namespace lc2wf
