// 2D line segments with OpenCV 4.6's LSD (restored in 4.5.4; Debian's 4.6.0 has it and it does not
// throw), as Line3D++ uses it: refinement, minimum length relative to the image diagonal, the longest
// segments kept, sorted longest first (the index is the segment id).
// Refinement defaults to STD: on our clean synthetic renders ADV drops many true segments (on three
// 640x480 renders 233/77/66 segments with ADV vs 395/98/189 with STD; it even drops two sides of a
// noise-free rectangle), so ADV (Line3D++'s choice) stays an option.
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "dataset/geometry/geometry.h"

namespace lc2wf {

struct LsdOptions {
  bool refine_advanced = false;     // LSD_REFINE_ADV, else LSD_REFINE_STD
  double min_length_frac = 0.005;   // of the full-resolution image diagonal (Line3D++)
  int max_segments = 1000;          // keep the longest
  int max_side = 0;                 // downscale so the larger side is at most this before LSD (0 = never)
  double scale = 0.8;               // LSD's own Gaussian pre-scaling (OpenCV's default 0.8)
  void Check() const;
};

// The options for images `scale` times larger than those `options` were set for (tools/render/camera_ring.h,
// view_scale_for): the same shortest segment in pixels of the set size, and as many segments per set-size
// pixel area.
LsdOptions scaled_lsd(const LsdOptions& options, double scale);

// Accepts 8-bit gray or BGR images; throws std::invalid_argument for an empty or other-typed image.
std::vector<Segment2> detect_segments(const cv::Mat& image, const LsdOptions& options);

}  // namespace lc2wf
